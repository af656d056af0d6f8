//! Hair instances, the count table and graying (docs/models.md §9 "Hair instances", "Graying";
//! [T §6.1, §6.2, §7.3]).
//!
//! Hairs are scattered over a triangle mesh in proportion to triangle area, where the
//! transition texture says there is hair at t = 0. Each gets a disappearance age `a_k` from
//! the texture, a graying onset `t_k < a_k`, and a direction. They are sorted by `a_k`
//! descending, so the hairs present at age t are exactly the first [`HairInstances::count`]
//! of them: the renderer uploads [`HairInstances::as_bytes`] once as an instance buffer and
//! draws `count(t)` instances in one instanced draw call.
//!
//! Determinism (docs/models.md §1): triangle `i` draws its hairs from `Rng::for_stream(seed, i)`, the
//! triangles are generated in parallel and concatenated in triangle order, then sorted by a
//! stable sort on `a_k`: the bytes are the same on any number of threads.

pub mod brows;
pub mod lashes;
mod packing;
mod placement;
pub mod scalp;
pub mod strand;
pub mod transition;

use packing::unorm16;
pub use packing::{oct_decode, oct_encode};
use placement::{torn_triangles, triangle_hairs};

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::base::error::Error;
use crate::base::rng::Rng;
use crate::layers::hair::transition::{TransitionTexture, clamp_age};

/// Default hair density, hairs per cm² of surface. The human scalp has about 150–300
/// follicular hairs per cm²; [T] draws fewer for speed. This is the middle of that range.
pub const DEFAULT_DENSITY_PER_CM2: f32 = 200.0;
/// How wide a scalp hair is drawn, mm: what of the scalp it covers in the 3D view
/// (docs/models.md §9 "Cover"). A hair is 0.05–0.12 mm across (Franbourg et al. 2003);
/// **choice**: 0.2 mm, about two and a half diameters, for the shadow it casts and the
/// light it scatters (at 0.08 the young hair was a flat painted cap; drawn a whole
/// ribbon wide, 0.45 px, about 0.5 mm on the panel's renders, a crown that had lost two
/// thirds of its hairs looked untouched).
pub const SCALP_HAIR_COVER_MM: f32 = 0.2;
/// The share of its cover a white scalp hair keeps against a pigmented one (docs/models.md
/// §9 "Cover"; `shaders/common.wgsl`'s `WHITE_HAIR_COVER`): without melanin a hair lets
/// more of the light through. **Choice**: 0.6 (0.9, nearly as opaque, drew old heads that
/// keep their hair as "a uniform white cap, only recoloured", "no salt-and-pepper stage",
/// blind, rounds 21–25).
pub const WHITE_SCALP_HAIR_COVER: f32 = 0.6;
/// How much of the skin behind it a white brow hair hides, as the width of a pigmented
/// hair that would hide as much, mm (docs/models.md §9 "Cover"): without melanin a hair
/// lets the light through. **Choice**: 0.25 mm (drawn as opaque as a pigmented one, the
/// old brows on dark skin read, blind, as "stark white bristles that look stuck on").
pub const WHITE_BROW_HAIR_COVER_MM: f32 = 0.25;
/// Default largest angle between a hair's direction and the surface normal, radians (≈ 10°).
pub const DEFAULT_MAX_DEVIATION_RAD: f32 = 0.175;
/// Default range of the graying onset: `t_k = U[min, max)` (**Choice**: docs/models.md §9;
/// [T]'s t_k below a_k grayed the receding crown first). Every hair starts graying between
/// t = 0.2 and t = 0.9; one that goes before its onset never grays.
pub const DEFAULT_GRAYING_ONSET_MIN: f32 = 0.2;
/// See [`DEFAULT_GRAYING_ONSET_MIN`].
pub const DEFAULT_GRAYING_ONSET_MAX: f32 = 0.9;
/// The project's default thinning (`hair.thinning`): the fraction of every region's hair
/// (the fringe that stays too) lost by t = 1, hair by hair, evenly over t ∈
/// [[`THINNING_FROM`], 1] (docs/models.md §9 "Thinning": scalp hair density falls by about
/// a third to a half into old age). [`HairParams`] start with none ([T]'s model).
pub const DEFAULT_THINNING: f32 = 0.45;
/// The age t from which hair thins.
pub const THINNING_FROM: f32 = 0.3;
/// How far (in t) the project spreads each receding hair's disappearance age about the
/// texture's: the hairline recedes as a thinning fringe, not a cut edge.
pub const RECESSION_SPREAD: f32 = 0.12;
/// The largest number of hairs one generation may produce (32 bytes each: 2 GiB). [T]
/// notes about 20 million instances fit in instance data on current hardware.
pub const MAX_INSTANCES: u64 = 64 << 20;

/// Parameters of hair placement (docs/models.md §9 "Hair instances").
#[derive(Clone, Debug, PartialEq)]
pub struct HairParams {
    density_per_cm2: f32,
    metres_per_unit: f32,
    max_deviation_rad: f32,
    graying_onset_min: f32,
    graying_onset_max: f32,
    thinning: f32,
    recession_spread: f32,
    taper_mm: f32,
    loss: HairLoss,
    seed: u64,
}

impl Default for HairParams {
    /// Default density and deviation, a mesh in metres, seed 0.
    fn default() -> Self {
        Self {
            density_per_cm2: DEFAULT_DENSITY_PER_CM2,
            metres_per_unit: 1.0,
            max_deviation_rad: DEFAULT_MAX_DEVIATION_RAD,
            graying_onset_min: DEFAULT_GRAYING_ONSET_MIN,
            graying_onset_max: DEFAULT_GRAYING_ONSET_MAX,
            thinning: 0.0,
            recession_spread: 0.0,
            taper_mm: 0.0,
            loss: HairLoss::Male,
            seed: 0,
        }
    }
}

impl HairParams {
    /// `density_per_cm2`: hairs per cm² of surface, finite and ≥ 0 (0 gives no hairs).
    /// `metres_per_unit`: the length of one mesh unit in metres (1 for a mesh in metres,
    /// 0.01 for centimetres), finite and > 0. Other values are an error.
    pub fn new(density_per_cm2: f32, metres_per_unit: f32) -> Result<Self, Error> {
        if !(density_per_cm2.is_finite() && density_per_cm2 >= 0.0) {
            return Err(invalid(
                "hair density (hairs/cm²)",
                density_per_cm2,
                "a finite value ≥ 0",
            ));
        }
        if !(metres_per_unit.is_finite() && metres_per_unit > 0.0) {
            return Err(invalid(
                "metres per mesh unit",
                metres_per_unit,
                "a finite value > 0",
            ));
        }
        Ok(Self {
            density_per_cm2,
            metres_per_unit,
            ..Self::default()
        })
    }

    /// The seed of all random choices (positions, directions, onsets).
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Largest angle between direction and normal, radians, in [0, π/2].
    pub fn with_max_deviation_rad(mut self, max_deviation_rad: f32) -> Result<Self, Error> {
        if !(0.0..=std::f32::consts::FRAC_PI_2).contains(&max_deviation_rad) {
            return Err(invalid(
                "hair direction deviation (rad)",
                max_deviation_rad,
                "0 ≤ value ≤ π/2",
            ));
        }
        self.max_deviation_rad = max_deviation_rad;
        Ok(self)
    }

    /// Graying onset range as a fraction of a_k: 0 ≤ `min` ≤ `max` ≤ 10 (an onset past
    /// t = 1 never grays: the part of the population's range beyond the oldest age).
    pub fn with_graying_onset_range(mut self, min: f32, max: f32) -> Result<Self, Error> {
        if !(0.0 <= min && min <= max && max <= 10.0) {
            return Err(Error::InvalidValue {
                what: "graying onset range".into(),
                value: format!("{min}..{max}"),
                expected: "0 ≤ min ≤ max ≤ 10".into(),
            });
        }
        self.graying_onset_min = min;
        self.graying_onset_max = max;
        Ok(self)
    }

    /// Thinning and a receding fringe (docs/models.md §9 "Thinning"): the fraction of the
    /// hair lost by t = 1, in [0, 1], and how far (t, in [0, 1)) each receding hair's
    /// disappearance age is spread about its texel's. Both 0 by default ([T]).
    pub fn with_thinning(mut self, thinning: f32, recession_spread: f32) -> Result<Self, Error> {
        if !(0.0..=1.0).contains(&thinning) {
            return Err(invalid("hair thinning", thinning, "0 ≤ value ≤ 1"));
        }
        if !(0.0..1.0).contains(&recession_spread) {
            return Err(invalid(
                "hair recession spread",
                recession_spread,
                "0 ≤ value < 1",
            ));
        }
        self.thinning = thinning;
        self.recession_spread = recession_spread;
        Ok(self)
    }

    /// The taper (docs/models.md §9 "Taper"): hairs shorten over this many mm toward the
    /// edge of their region, to [`TAPER_SHORTEST`] of their length at it; finite, ≥ 0 (0,
    /// the default, keeps every hair at full length, [T]'s model).
    pub fn with_taper_mm(mut self, taper_mm: f32) -> Result<Self, Error> {
        if !(taper_mm.is_finite() && taper_mm >= 0.0) {
            return Err(invalid("hair taper (mm)", taper_mm, "a finite value ≥ 0"));
        }
        self.taper_mm = taper_mm;
        Ok(self)
    }

    /// The pattern the hair is lost in ([`HairLoss`]; male by default, [T]'s masks).
    pub fn with_loss(mut self, loss: HairLoss) -> Self {
        self.loss = loss;
        self
    }

    pub fn density_per_cm2(&self) -> f32 {
        self.density_per_cm2
    }

    pub fn metres_per_unit(&self) -> f32 {
        self.metres_per_unit
    }

    pub fn max_deviation_rad(&self) -> f32 {
        self.max_deviation_rad
    }

    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Expected hairs per square mesh unit.
    fn density_per_unit2(&self) -> f64 {
        let cm_per_unit = self.metres_per_unit as f64 * 100.0;
        self.density_per_cm2 as f64 * cm_per_unit * cm_per_unit
    }
}

/// A triangle mesh as plain slices: what hair placement needs, whatever type holds it.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceRef<'a> {
    positions: &'a [Vec3],
    normals: &'a [Vec3],
    uvs: &'a [Vec2],
    indices: &'a [u32],
}

impl<'a> SurfaceRef<'a> {
    /// Positions (mesh units), per-vertex normals (any length; re-normalised), UVs
    /// (docs/models.md §1, v up) and a triangle list. `normals` and `uvs` must have one entry per
    /// position; `indices.len()` must be a multiple of 3, every index < `positions.len()`.
    pub fn new(
        positions: &'a [Vec3],
        normals: &'a [Vec3],
        uvs: &'a [Vec2],
        indices: &'a [u32],
    ) -> Result<Self, Error> {
        let n = positions.len();
        for (what, len) in [("normals", normals.len()), ("UVs", uvs.len())] {
            if len != n {
                return Err(Error::InvalidValue {
                    what: format!("number of {what}"),
                    value: len.to_string(),
                    expected: format!("one per vertex ({n})"),
                });
            }
        }
        if !indices.len().is_multiple_of(3) {
            return Err(invalid(
                "index count",
                indices.len(),
                "a multiple of 3 (a triangle list)",
            ));
        }
        if let Some(i) = indices.iter().position(|&i| i as usize >= n) {
            return Err(Error::InvalidValue {
                what: format!("index {i} (triangle {})", i / 3),
                value: indices[i].to_string(),
                expected: format!("a vertex index < {n}"),
            });
        }
        Ok(Self {
            positions,
            normals,
            uvs,
            indices,
        })
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }
}

impl<'a> From<&'a crate::head::mesh::Mesh> for SurfaceRef<'a> {
    /// A [`crate::head::mesh::Mesh`] is already validated (one normal and UV per vertex, indices
    /// in range). Its units are whatever it was loaded in: the default head is in metres.
    fn from(mesh: &'a crate::head::mesh::Mesh) -> Self {
        Self {
            positions: mesh.positions(),
            normals: mesh.normals(),
            uvs: mesh.uvs(),
            indices: mesh.indices(),
        }
    }
}

/// One hair, ready for the GPU: 32 bytes, `#[repr(C)]`, no padding.
///
/// WGSL (as vertex attributes with `step_mode: Instance`, or as a storage-buffer struct):
///
/// ```wgsl
/// struct HairInstance {
///     position: vec3<f32>,      // offset  0, Float32x3, mesh units
///     disappear_age: f32,       // offset 12, Float32,   a_k ∈ (0, 1]; drawn while a_k ≥ t
///     direction_oct: u32,       // offset 16, Snorm16x2, octahedral unit vector
///                               //            (storage buffer: unpack2x16snorm)
///     graying_onset: f32,       // offset 20, Float32,   t_k ∈ [0, a_k)
///     uv: u32,                  // offset 24, Unorm16x2, docs/models.md §1 UV (unpack2x16unorm)
///     random: u16,              // offset 28, Unorm16,   uniform [0, 1) per hair
///     length: u16,              // offset 30, Unorm16,   the taper: length factor (0, 1]
///                               //            (the pair: Unorm16x2, unpack2x16unorm)
/// }
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct HairInstance {
    position: [f32; 3],
    disappear_age: f32,
    direction_oct: [i16; 2],
    graying_onset: f32,
    uv_unorm: [u16; 2],
    random_unorm: u16,
    length_unorm: u16,
}

impl HairInstance {
    /// Root position in mesh units.
    pub fn position(&self) -> Vec3 {
        Vec3::from(self.position)
    }

    /// a_k: the hair is present while a_k ≥ t. 1 for inner hair (never disappears).
    pub fn disappear_age(&self) -> f32 {
        self.disappear_age
    }

    /// Unit growth direction, decoded from the octahedral encoding (error < 1e-4 rad·2π).
    pub fn direction(&self) -> Vec3 {
        oct_decode(self.direction_oct)
    }

    /// t_k: the age at which the hair starts graying (never, when it goes first).
    pub fn graying_onset(&self) -> f32 {
        self.graying_onset
    }

    /// UV of the root (16-bit per axis, clamped to [0,1]).
    pub fn uv(&self) -> Vec2 {
        Vec2::new(self.uv_unorm[0] as f32, self.uv_unorm[1] as f32) / 65535.0
    }

    /// A uniform random number in [0, 1) for per-hair variation (length, shade).
    pub fn random(&self) -> f32 {
        self.random_unorm as f32 / 65536.0
    }

    /// The random number as the hair pass reads it (its 16 bits as a unorm: / 65535).
    pub fn random_as_drawn(&self) -> f32 {
        self.random_unorm as f32 / 65535.0
    }

    /// The hair's length as a fraction of the project's (docs/models.md §9 "Taper"): 1
    /// inside its region, shorter toward the region's edge (the nape, round the ears, the
    /// hairline), as a barber tapers a cut.
    pub fn length_factor(&self) -> f32 {
        self.length_unorm as f32 / 65535.0
    }

    /// y_k(t), the gray fraction of this hair at age `t` (see [`gray_fraction`]).
    pub fn gray_fraction(&self, t: f32, ramp: GrayingRamp) -> f32 {
        gray_fraction(t, self.graying_onset, ramp)
    }
}

/// One step of the count table: `count` hairs have `disappear_age ≥ age`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct AgeLevel {
    pub age: f32,
    pub count: u32,
}

/// The hairs of one head, sorted by a_k descending, with their cumulative count table.
#[derive(Clone, Debug, PartialEq)]
pub struct HairInstances {
    instances: Vec<HairInstance>,
    /// Distinct a_k values, descending, with the cumulative counts.
    levels: Vec<AgeLevel>,
    /// Candidates drawn before the t = 0 mask test.
    candidates: u64,
}

impl HairInstances {
    /// Scatters hairs over `surface` (docs/models.md §9 "Hair instances"): per triangle,
    /// `density · area` hairs on average (area in cm² through `params.metres_per_unit`;
    /// the fractional part is rounded up with that probability, so the total is unbiased),
    /// at uniform random barycentric coordinates; a candidate is kept only where the
    /// transition texture has hair at t = 0 (outer ∪ inner region). Position, normal and
    /// UV are interpolated; a_k is the texture's age at the UV (nearest texel); t_k =
    /// U[onset min, onset max); the direction is the normal turned by a uniform
    /// random direction in a cone of half-angle `max_deviation_rad`. Degenerate triangles
    /// get no hairs; a vertex normal sum of zero falls back to the face normal.
    ///
    /// Fails when the expected count exceeds [`MAX_INSTANCES`] or a triangle's area is not
    /// finite.
    pub fn generate(
        surface: &SurfaceRef<'_>,
        transition: &TransitionTexture,
        params: &HairParams,
    ) -> Result<Self, Error> {
        let per_unit2 = params.density_per_unit2();
        let areas: Vec<f64> = surface
            .indices
            .par_chunks_exact(3)
            .map(|tri| {
                let [a, b, c] = [0, 1, 2].map(|k| surface.positions[tri[k] as usize]);
                0.5 * (b - a).cross(c - a).length() as f64
            })
            .collect();
        if let Some(t) = areas.iter().position(|a| !a.is_finite()) {
            return Err(invalid(
                &format!("area of triangle {t}"),
                areas[t],
                "a finite area (finite positions)",
            ));
        }
        let expected: f64 = areas.iter().sum::<f64>() * per_unit2;
        if expected > MAX_INSTANCES as f64 {
            return Err(Error::InvalidValue {
                what: "expected number of hairs".into(),
                value: format!("{expected:.0}"),
                expected: format!("at most {MAX_INSTANCES}: lower the density"),
            });
        }
        let cos_max = params.max_deviation_rad.cos();
        let torn = torn_triangles(surface);

        // Chunks of consecutive triangles, concatenated in order: few allocations, and the
        // same sequence whatever the thread count.
        let per_chunk: Vec<(u64, Vec<HairInstance>)> = areas
            .par_chunks(TRIANGLES_PER_TASK)
            .enumerate()
            .map(|(c, chunk)| {
                let expected: f64 = chunk.iter().sum::<f64>() * per_unit2;
                let mut out = Vec::with_capacity(expected.ceil() as usize + chunk.len());
                let mut candidates = 0u64;
                for (j, &area) in chunk.iter().enumerate() {
                    let t = c * TRIANGLES_PER_TASK + j;
                    let tri = &surface.indices[3 * t..3 * t + 3];
                    if torn[t] {
                        continue;
                    }
                    candidates += triangle_hairs(
                        &mut out,
                        surface,
                        tri,
                        t,
                        area * per_unit2,
                        transition,
                        params,
                        cos_max,
                    ) as u64;
                }
                (candidates, out)
            })
            .collect();
        let candidates = per_chunk.iter().map(|(c, _)| c).sum();
        let total: usize = per_chunk.iter().map(|(_, v)| v.len()).sum();
        let mut unsorted: Vec<HairInstance> = Vec::new();
        unsorted
            .try_reserve_exact(total)
            .map_err(|_| Error::OutOfMemory {
                bytes: total as u64 * 32,
                what: "hair instances",
            })?;
        for (_, v) in per_chunk {
            unsorted.extend_from_slice(&v);
        }
        let instances = sort_by_age_descending(&unsorted);
        let levels = count_levels(&instances);
        Ok(Self {
            instances,
            levels,
            candidates,
        })
    }

    /// All hairs, a_k descending.
    pub fn instances(&self) -> &[HairInstance] {
        &self.instances
    }

    /// The instance buffer: `len() × 32` bytes, to upload once.
    pub fn as_bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.instances)
    }

    pub fn len(&self) -> usize {
        self.instances.len()
    }

    pub fn is_empty(&self) -> bool {
        self.instances.is_empty()
    }

    /// Candidates drawn before the mask test (≥ `len()`).
    pub fn candidates(&self) -> u64 {
        self.candidates
    }

    /// The count table: one entry per distinct a_k, descending; entry `count` is the
    /// number of hairs with a_k ≥ `age`.
    pub fn levels(&self) -> &[AgeLevel] {
        &self.levels
    }

    /// count(t): the number of hairs present at age `t`, i.e. with a_k ≥ t (docs/models.md §9). The
    /// first `count(t)` instances are exactly those. Non-increasing in t; `t` outside
    /// [0,1] is clamped, NaN counts as 0. O(log levels).
    pub fn count(&self, t: f32) -> usize {
        let t = clamp_age(t);
        let k = self.levels.partition_point(|l| l.age >= t);
        if k == 0 {
            0
        } else {
            self.levels[k - 1].count as usize
        }
    }
}

/// Triangles per parallel task of [`HairInstances::generate`].
const TRIANGLES_PER_TASK: usize = 1024;

/// Sorts by a_k descending, ties in generation order — the order a stable sort gives, so
/// the result is unique. Sorting (key, index) pairs packed in a u64 and gathering once is
/// several times faster than moving 32-byte instances through a merge sort.
fn sort_by_age_descending(unsorted: &[HairInstance]) -> Vec<HairInstance> {
    // Ages are ≥ 0, so their bit patterns order like the numbers; `!` makes it descending.
    // Indices fit in 32 bits: the count is bounded by MAX_INSTANCES (about 2^26).
    let mut keys: Vec<u64> = unsorted
        .par_iter()
        .enumerate()
        .map(|(i, h)| (u64::from(!h.disappear_age.to_bits()) << 32) | i as u64)
        .collect();
    keys.par_sort_unstable();
    keys.par_iter()
        .map(|&k| unsorted[(k & 0xFFFF_FFFF) as usize])
        .collect()
}

/// The project's default taper (`hair.taper_mm`): the distance over which hair shortens
/// toward the edge of its region, mm.
pub const DEFAULT_TAPER_MM: f32 = 18.0;
/// The length factor of a hair at the very edge of its region.
pub const TAPER_SHORTEST: f32 = 0.2;

fn count_levels(sorted: &[HairInstance]) -> Vec<AgeLevel> {
    let mut levels: Vec<AgeLevel> = Vec::new();
    for (i, h) in sorted.iter().enumerate() {
        match levels.last_mut() {
            Some(l) if l.age == h.disappear_age => l.count = i as u32 + 1,
            _ => levels.push(AgeLevel {
                age: h.disappear_age,
                count: i as u32 + 1,
            }),
        }
    }
    levels
}

/// How the gray fraction rises after the onset (docs/models.md §9 "Graying").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GrayingRamp {
    /// y = (t − t_k)/(1 − t_k).
    #[default]
    Linear,
    /// The linear y through the smoothstep 3y² − 2y³.
    Smoothstep,
}

/// Which pattern the hair is lost in with age (`hair.loss`; docs/models.md §9 "Hair
/// loss").
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "lowercase")]
pub enum HairLoss {
    /// Male pattern (Hamilton–Norwood): the temples recede and the crown thins to a bald
    /// top over a horseshoe fringe, as the transition texture's masks draw it ([T]).
    #[default]
    Male,
    /// Female pattern (Ludwig): diffuse thinning over the crown, the frontal hairline
    /// kept; only the temples recede a little, after the menopause
    /// ([`FEMALE_RECESSION_T`]).
    Female,
    /// No pattern: nothing recedes, only `hair.thinning` everywhere.
    None,
}

impl HairLoss {
    pub const NAMES: [&'static str; 3] = ["male", "female", "none"];

    pub fn name(self) -> &'static str {
        match self {
            Self::Male => "male",
            Self::Female => "female",
            Self::None => "none",
        }
    }

    /// A guess from the face's proportions when the artist has not said: the face's
    /// height (nasion to chin) over the outer eye corners' distance, which is larger in
    /// men (a longer lower face and chin: Farkas's norms give about 1.2 for men and 1.1
    /// for women). At or over [`MALE_FACE_RATIO`]: male; under it: female (the pattern
    /// that keeps the hairline, the milder wrong guess). Shown to the user as a guess.
    pub fn guess(face_ratio: f32) -> Self {
        if face_ratio >= MALE_FACE_RATIO {
            Self::Male
        } else {
            Self::Female
        }
    }
}

/// A guess of the hair's curl (0 straight, 1 coiled) from the skin's individual typology
/// angle when the artist has not said (`hair.curl`): coiled on dark skin (ITA° under
/// [`COILED_UNDER_ITA`], where afro-textured hair is by far the commonest), else straight.
/// A prior, not a measurement: shown to the user as a guess. (Drawn straight, the panel's
/// dark-skinned heads' white hair read, blind, as "straight and bristly, the wrong
/// texture", "a white wig".)
pub fn guess_curl(ita_degrees: f32) -> f32 {
    if ita_degrees < COILED_UNDER_ITA {
        1.0
    } else {
        0.0
    }
}

/// See [`guess_curl`]: the "dark" group of the ITA° scale (Chardon et al. 1991).
pub const COILED_UNDER_ITA: f32 = -30.0;

/// How many years later than a brown head's hair of lightness `l_star` (CIELAB) starts
/// graying: [`DARK_HAIR_DELAY_YEARS`] for black hair (L* [`BLACK_HAIR_L`] and under), none
/// from a dark brown ([`DARK_BROWN_HAIR_L`]) up. Graying comes later in East Asian and
/// African hair, by roughly 5–10 years (Panhard et al. 2012; Tobin 2008), whose hair is
/// black: the delay follows black hair, not darkness (reaching up to a medium brown, it
/// gave the default head's dark brown five years of it: no gray at the temples at 45, and
/// the head read, blind, as 33 at 45 and 55 at 65 over three rounds).
pub fn graying_delay_years(l_star: f32) -> f32 {
    DARK_HAIR_DELAY_YEARS
        * ((DARK_BROWN_HAIR_L - l_star) / (DARK_BROWN_HAIR_L - BLACK_HAIR_L)).clamp(0.0, 1.0)
}

/// See [`graying_delay_years`]: the lightness of black hair and of a dark brown (CIELAB L*).
pub const BLACK_HAIR_L: f32 = 15.0;
pub const DARK_BROWN_HAIR_L: f32 = 22.0;

/// See [`graying_delay_years`].
pub const DARK_HAIR_DELAY_YEARS: f32 = 8.0;

/// See [`HairLoss::guess`]: between the panel's women (1.03, 1.06) and men (1.15–1.18).
pub const MALE_FACE_RATIO: f32 = 1.1;

/// In the female pattern, how much of `hair.thinning` the crown (the male pattern's
/// receding region) loses, and the sides and back: the crown thins most, the frontal
/// hairline (within [`HAIRLINE_KEPT_MM`] of the face) as the sides.
pub const FEMALE_THINNING: (f32, f32) = (1.45, 0.6);
/// See [`FEMALE_THINNING`].
pub const HAIRLINE_KEPT_MM: f32 = 25.0;
/// Where the hairline stays in the patterns that keep it: where the male pattern has it at
/// this t (about 26 years). The masks' hair at t = 0 reaches lower, a boy's hairline the
/// male pattern recedes from at once; kept, it drew a band of hair down the forehead.
pub const KEPT_HAIRLINE_T: f32 = 0.1;
/// Over how much of the male pattern's ages (t) past [`KEPT_HAIRLINE_T`] the kept
/// hairline's scalp tint comes to the crown's: the hair along the kept hairline (the
/// taper's shorter, sparser hair) tints the scalp less.
pub const KEPT_HAIRLINE_RAMP: f32 = 0.3;

/// In the female pattern the hairline recedes a little after the menopause, most at the
/// temples: along the hairline (within [`HAIRLINE_KEPT_MM`] of it), the hair the male
/// pattern has lost by this t — the first at the front, the second where the scalp faces
/// sideways ([`FEMALE_TEMPLE_SIDE`]) — goes between [`FEMALE_RECESSION_FROM`] and t = 1,
/// the outermost first, so at full age the temples stand about where a man's are at 50
/// and the front (whose male ages are mostly later) keeps its place. Frontal and
/// frontoparietal recession is found in 37 % of postmenopausal women (Venning & Dawber
/// 1988, 564 women) and bitemporal recession in 64 % of the women of a population survey
/// (Gan & Sinclair 2005); kept where it was at 25, the panel's women's hairline read,
/// blind, as "unchanged at 80" (rounds 50–52; at 0.35 at the temples alone, too, round
/// 52) (docs/models.md §9 "Hair loss").
pub const FEMALE_RECESSION_T: (f32, f32) = (0.3, 0.5);
/// See [`FEMALE_RECESSION_T`]: the t from which the hairline recedes (50 years in the
/// default 20–80 mapping).
pub const FEMALE_RECESSION_FROM: f32 = 0.5;
/// See [`FEMALE_RECESSION_T`]: the scalp's sideways facing (|x| of its normal) over which
/// the recession goes from the front's to the temples'.
pub const FEMALE_TEMPLE_SIDE: (f32, f32) = (0.35, 0.65);

/// The disappearance age, in the female pattern, of a hair along the hairline where the
/// male pattern's texture age is `texture_age` and the scalp is a `temple` share (0–1) of
/// a temple ([`FEMALE_RECESSION_T`]); `jitter` (0–1, the hair's own draw) moves it by up to
/// a quarter of the span either way, so the edge is ragged. 1 (stays) from the pattern's
/// reach on.
pub fn female_recession(texture_age: f32, jitter: f32, temple: f32) -> f32 {
    let to = FEMALE_RECESSION_T.0 + (FEMALE_RECESSION_T.1 - FEMALE_RECESSION_T.0) * temple;
    if texture_age >= to {
        return 1.0;
    }
    let x = (texture_age - KEPT_HAIRLINE_T) / (to - KEPT_HAIRLINE_T);
    let x = (x + 0.5 * (jitter - 0.5)).clamp(0.0, 1.0);
    FEMALE_RECESSION_FROM + (1.0 - FEMALE_RECESSION_FROM) * x
}

/// How long (in t) one hair takes to turn from pigmented to white once its onset is
/// reached (docs/models.md §9 "Graying"): about five years of the default 20–80 mapping.
/// Each hair is pigmented or white, seldom between: a graying head is salt and pepper, the
/// white fraction rising as more hairs reach their onsets (a slow ramp per hair, to t = 1,
/// grayed every hair alike and read, blind, as "one flat bluish tint").
pub const GRAY_RAMP_T: f32 = 0.08;

/// How much earlier, as a share of the graying onsets' range, the hairs at the temples and
/// the sides gray in the male pattern (a fifth of the default 41–91 years: 10 years;
/// docs/models.md §9 "Graying").
pub const TEMPLE_GRAYING_LEAD: f32 = 0.2;

/// How much earlier, as a share of the graying onsets' range, the hairs along the frontal
/// hairline and at the temples gray in the female pattern: the lead at the kept hairline,
/// fading to none [`HAIRLINE_KEPT_MM`] behind it, and none at the nape: women see their
/// first gray hairs at the front more often, men at the temples (docs/models.md §9
/// "Graying").
pub const FRONT_GRAYING_LEAD: f32 = 0.2;

/// y_k(t) = clamp((t − t_k)/[`GRAY_RAMP_T`], 0, 1), optionally smoothstepped
/// (docs/models.md §9 "Graying"). `t` is clamped to [0,1] (NaN → 0); an onset t_k ≥ 1
/// never grays (y = 0), an onset ≤ 0 is used as is.
pub fn gray_fraction(t: f32, onset: f32, ramp: GrayingRamp) -> f32 {
    let t = clamp_age(t);
    if onset.is_nan() || onset >= 1.0 {
        return 0.0;
    }
    let y = ((t - onset) / GRAY_RAMP_T).clamp(0.0, 1.0);
    match ramp {
        GrayingRamp::Linear => y,
        GrayingRamp::Smoothstep => y * y * (3.0 - 2.0 * y),
    }
}

/// How long before its disappearance age (in t) a hair is miniaturised (docs/models.md §9
/// "Miniaturisation"): about five years of the default 20–80 mapping.
pub const MINIATURE_T: f32 = 0.08;

/// How whole a hair of disappearance age `disappear_age` (a_k) is at age `t`, 0–1: 1 until
/// [`MINIATURE_T`] before a_k, falling to 0 at a_k as a smoothstep; a hair that never goes
/// (a_k ≥ 1) stays whole. A hair about to go is miniaturised first (the follicle shrinks
/// to a fine, short vellus hair before it is lost), so a receding edge fades over a few
/// millimetres instead of ending in a block of full hairs. The hair pass draws it thinner
/// (a fifth of its cover) and shorter (a third of its length) as it falls
/// (`shaders/common.wgsl`'s twin).
pub fn hair_whole(disappear_age: f32, t: f32) -> f32 {
    if disappear_age >= 1.0 {
        return 1.0;
    }
    let x = ((disappear_age - t) / MINIATURE_T).clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// C_k(t) = (1 − y)·C_base + y·C_gray (docs/models.md §9), linear RGB; `y` is clamped to [0,1].
pub fn hair_colour(base: Vec3, gray: Vec3, y: f32) -> Vec3 {
    let y = y.clamp(0.0, 1.0);
    base * (1.0 - y) + gray * y
}

fn invalid(what: &str, value: impl std::fmt::Display, expected: &str) -> Error {
    Error::InvalidValue {
        what: what.into(),
        value: value.to_string(),
        expected: expected.into(),
    }
}

#[cfg(test)]
mod tests;
