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
    /// kept; nothing recedes.
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
mod tests {
    use super::*;
    use crate::layers::hair::transition::{DistanceMetric, HairRegions, hair_present};
    use crate::maps::mask::Mask;
    use crate::test_util::close;
    use placement::{RAGGED_MM, STRAY_LENGTH, STRAY_REACH_MM, STRAY_SHARE, ragged_noise};

    /// A flat grid of `n × n` quads over [0, side]² (mesh units) in the z = 0 plane, UV =
    /// position / side, normals +z.
    struct Grid {
        positions: Vec<Vec3>,
        normals: Vec<Vec3>,
        uvs: Vec<Vec2>,
        indices: Vec<u32>,
    }

    fn grid(n: u32, side: f32) -> Grid {
        let mut g = Grid {
            positions: vec![],
            normals: vec![],
            uvs: vec![],
            indices: vec![],
        };
        for y in 0..=n {
            for x in 0..=n {
                let (u, v) = (x as f32 / n as f32, y as f32 / n as f32);
                g.positions.push(Vec3::new(u * side, v * side, 0.0));
                g.normals.push(Vec3::Z);
                g.uvs.push(Vec2::new(u, v));
            }
        }
        for y in 0..n {
            for x in 0..n {
                let i = y * (n + 1) + x;
                g.indices
                    .extend([i, i + 1, i + n + 2, i, i + n + 2, i + n + 1]);
            }
        }
        g
    }

    impl Grid {
        fn surface(&self) -> SurfaceRef<'_> {
            SurfaceRef::new(&self.positions, &self.normals, &self.uvs, &self.indices).unwrap()
        }
    }

    /// Outer: a disc of radius 0.4 around the centre; inner: a band at the bottom (v < 0.25)
    /// that also extends outside the disc; 64² working size.
    fn transition() -> TransitionTexture {
        let n = 64u32;
        let mut outer = vec![0.0; (n * n) as usize];
        let mut inner = vec![0.0; (n * n) as usize];
        for y in 0..n {
            for x in 0..n {
                let (u, v) = (
                    crate::maps::heightmap::pixel_to_u(x, n),
                    crate::maps::heightmap::pixel_to_v(y, n),
                );
                let i = (y * n + x) as usize;
                if (u - 0.5).powi(2) + (v - 0.5).powi(2) < 0.16 {
                    outer[i] = 1.0;
                }
                if v < 0.25 {
                    inner[i] = 1.0;
                }
            }
        }
        TransitionTexture::from_masks(
            &Mask::from_values(n, n, outer).unwrap(),
            &Mask::from_values(n, n, inner).unwrap(),
            n,
            n,
            DistanceMetric::Chebyshev,
        )
        .unwrap()
    }

    /// Hairs on a 10 cm square in metres (the disc that recedes and the band that stays of
    /// [`transition`]), graying over t 0.2–0.9: for the tests of what is made of hairs.
    pub(super) fn some_hairs() -> HairInstances {
        let params = HairParams::new(20.0, 1.0)
            .unwrap()
            .with_graying_onset_range(0.2, 0.9)
            .unwrap();
        HairInstances::generate(&grid(8, 0.1).surface(), &transition(), &params).unwrap()
    }

    #[test]
    fn instance_is_32_bytes_with_the_documented_offsets() {
        assert_eq!(std::mem::size_of::<HairInstance>(), 32);
        assert_eq!(std::mem::align_of::<HairInstance>(), 4);
        assert_eq!(std::mem::offset_of!(HairInstance, disappear_age), 12);
        assert_eq!(std::mem::offset_of!(HairInstance, direction_oct), 16);
        assert_eq!(std::mem::offset_of!(HairInstance, graying_onset), 20);
        assert_eq!(std::mem::offset_of!(HairInstance, uv_unorm), 24);
        assert_eq!(std::mem::offset_of!(HairInstance, random_unorm), 28);
        assert_eq!(std::mem::offset_of!(HairInstance, length_unorm), 30);
    }

    #[test]
    fn octahedral_directions_round_trip() {
        let mut rng = Rng::new(3);
        let mut worst = 0.0f32;
        for _ in 0..20_000 {
            let v = Vec3::new(
                rng.range_f32(-1.0, 1.0),
                rng.range_f32(-1.0, 1.0),
                rng.range_f32(-1.0, 1.0),
            )
            .normalize();
            // |a × b| = sin(angle): accurate for tiny angles, unlike acos.
            worst = worst.max(oct_decode(oct_encode(v)).cross(v).length());
        }
        for v in [
            Vec3::X,
            Vec3::NEG_X,
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::NEG_Z,
        ] {
            worst = worst.max(oct_decode(oct_encode(v)).cross(v).length());
        }
        assert!(worst < 1e-4, "worst angle {worst} rad");
    }

    #[test]
    fn density_follows_area_and_units() {
        // A 10 cm × 10 cm square in metres, no masks limiting: 100 cm² × 50 /cm² = 5000.
        let g = grid(8, 0.1);
        let full = Mask::from_values(1, 1, vec![1.0]).unwrap();
        let tex =
            TransitionTexture::from_masks(&full, &full, 4, 4, DistanceMetric::Chebyshev).unwrap();
        let params = HairParams::new(50.0, 1.0).unwrap();
        let hairs = HairInstances::generate(&g.surface(), &tex, &params).unwrap();
        let n = hairs.len() as f64;
        // 128 triangles of 39.0625 hairs each: per triangle 39 or 40 → 4992..=5120 hairs.
        assert!((4992.0..=5120.0).contains(&n), "{n}");
        // The same square in centimetres (side 10, 0.01 m per unit) gives the same hairs.
        let g_cm = grid(8, 10.0);
        let params_cm = HairParams::new(50.0, 0.01).unwrap();
        let hairs_cm = HairInstances::generate(&g_cm.surface(), &tex, &params_cm).unwrap();
        assert_eq!(hairs_cm.len(), hairs.len());
        for (a, b) in hairs.instances().iter().zip(hairs_cm.instances()) {
            assert!((a.position() * 100.0 - b.position()).length() < 1e-3);
        }
    }

    #[test]
    fn hairs_are_only_where_there_is_hair_at_t0_with_the_textures_age() {
        let g = grid(16, 0.3);
        let tex = transition();
        let params = HairParams::new(30.0, 1.0).unwrap().with_seed(9);
        let hairs = HairInstances::generate(&g.surface(), &tex, &params).unwrap();
        assert!(hairs.len() > 1000, "{}", hairs.len());
        assert!(
            (hairs.len() as u64) < hairs.candidates(),
            "some candidates fall outside"
        );
        for h in hairs.instances() {
            let uv = h.uv();
            assert!(hair_present(h.disappear_age(), 0.0));
            // UV is 16-bit: read the age back at the exact root UV from the position.
            let p = h.position() / 0.3;
            close(uv.x, p.x, 2e-5);
            close(uv.y, p.y, 2e-5);
            // Position and UV are interpolated separately: allow a rounding's worth of slack
            // at texel borders.
            let near: Vec<f32> = [-1e-4f32, 0.0, 1e-4]
                .iter()
                .flat_map(|&dx| [-1e-4f32, 0.0, 1e-4].map(|dy| tex.age_at_uv(p.x + dx, p.y + dy)))
                .collect();
            assert!(
                near.contains(&h.disappear_age()),
                "{} not in {near:?}",
                h.disappear_age()
            );
            // The onset is the hair's own, whenever it goes, within its patch's reach and
            // never far before the range.
            let range = DEFAULT_GRAYING_ONSET_MAX - DEFAULT_GRAYING_ONSET_MIN;
            let earliest = DEFAULT_GRAYING_ONSET_MIN - placement::GRAYING_EARLIEST * range;
            let latest = DEFAULT_GRAYING_ONSET_MAX + placement::GRAYING_PATCHES * range;
            assert!((earliest - 1e-6..=latest).contains(&h.graying_onset()));
            assert!((0.0..1.0).contains(&h.random()));
            let cos = h.direction().dot(Vec3::Z);
            assert!(cos >= DEFAULT_MAX_DEVIATION_RAD.cos() - 1e-4, "{cos}");
        }
        // Directions are deviated, not all equal to the normal.
        assert!(
            hairs
                .instances()
                .iter()
                .any(|h| h.direction().dot(Vec3::Z) < 0.995)
        );
    }

    #[test]
    fn drawn_prefix_is_exactly_the_hairs_present() {
        let g = grid(16, 0.3);
        let hairs = HairInstances::generate(
            &g.surface(),
            &transition(),
            &HairParams::new(30.0, 1.0).unwrap(),
        )
        .unwrap();
        let mut previous = usize::MAX;
        for i in 0..=400 {
            let t = i as f32 / 400.0;
            let n = hairs.count(t);
            assert!(n <= previous, "count increased at t = {t}");
            previous = n;
            let (drawn, rest) = hairs.instances().split_at(n);
            assert!(drawn.iter().all(|h| h.disappear_age() >= t), "t = {t}");
            assert!(rest.iter().all(|h| h.disappear_age() < t), "t = {t}");
        }
        // Also at every level exactly, where the ≥ matters.
        for l in hairs.levels() {
            assert_eq!(hairs.count(l.age), l.count as usize);
            let want = hairs
                .instances()
                .iter()
                .filter(|h| h.disappear_age() >= l.age)
                .count();
            assert_eq!(l.count as usize, want);
        }
        assert_eq!(hairs.count(0.0), hairs.len());
        assert_eq!(hairs.count(-5.0), hairs.len());
    }

    #[test]
    fn inner_hair_never_disappears() {
        let g = grid(16, 0.3);
        let tex = transition();
        let hairs =
            HairInstances::generate(&g.surface(), &tex, &HairParams::new(30.0, 1.0).unwrap())
                .unwrap();
        // The inner band is v ≤ 0.25 (texel rows 48..64 of 64), over the whole width, so
        // also outside the outer disc.
        let v = |h: &HairInstance| h.position().y / 0.3;
        let remaining = &hairs.instances()[..hairs.count(1.0)];
        assert!(remaining.len() > 300, "{}", remaining.len());
        assert!(
            remaining
                .iter()
                .all(|h| h.disappear_age() == 1.0 && v(h) < 0.2501)
        );
        let band = hairs.instances().iter().filter(|h| v(h) < 0.2499);
        assert!(
            band.clone().all(|h| h.disappear_age() == 1.0),
            "the inner band remains at t = 1"
        );
        assert!(remaining.len() >= band.count());
        assert!(
            remaining.iter().any(|h| h.uv().x < 0.05),
            "inner hair outside the outer disc"
        );
        assert!(hairs.count(0.5) > remaining.len());
    }

    #[test]
    fn identical_bytes_on_one_and_many_threads() {
        let g = grid(24, 0.3);
        let tex = transition();
        let params = HairParams::new(40.0, 1.0).unwrap().with_seed(77);
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| HairInstances::generate(&g.surface(), &tex, &params).unwrap())
        };
        let one = run(1);
        let many = run(4);
        assert!(one.len() > 1000);
        assert_eq!(one.as_bytes(), many.as_bytes());
        assert_eq!(one.levels(), many.levels());
        let other_seed =
            HairInstances::generate(&g.surface(), &tex, &params.clone().with_seed(78)).unwrap();
        assert_ne!(one.as_bytes(), other_seed.as_bytes());
    }

    #[test]
    fn empty_masks_and_zero_density_give_no_hairs() {
        let g = grid(4, 0.3);
        let none = Mask::from_values(2, 2, vec![0.0; 4]).unwrap();
        let tex =
            TransitionTexture::from_masks(&none, &none, 16, 16, DistanceMetric::Euclidean).unwrap();
        let hairs = HairInstances::generate(&g.surface(), &tex, &HairParams::default()).unwrap();
        assert!(hairs.is_empty());
        assert_eq!(hairs.count(0.0), 0);
        assert!(hairs.candidates() > 0);
        let tex = transition();
        let hairs =
            HairInstances::generate(&g.surface(), &tex, &HairParams::new(0.0, 1.0).unwrap())
                .unwrap();
        assert!(hairs.is_empty());
    }

    #[test]
    fn bad_inputs_are_errors() {
        let g = grid(2, 1.0);
        assert!(SurfaceRef::new(&g.positions, &g.normals[1..], &g.uvs, &g.indices).is_err());
        assert!(SurfaceRef::new(&g.positions, &g.normals, &g.uvs, &g.indices[1..]).is_err());
        let bad = [0, 1, 99];
        let err = SurfaceRef::new(&g.positions, &g.normals, &g.uvs, &bad)
            .unwrap_err()
            .to_string();
        assert!(err.contains("99"), "{err}");
        assert!(HairParams::new(-1.0, 1.0).is_err());
        assert!(HairParams::new(f32::NAN, 1.0).is_err());
        assert!(HairParams::new(1.0, 0.0).is_err());
        assert!(
            HairParams::default()
                .with_graying_onset_range(0.5, 0.4)
                .is_err()
        );
        assert!(HairParams::default().with_max_deviation_rad(2.0).is_err());
        // A 1 m² grid at 10 000 hairs/cm² is 10⁸ hairs: refused before allocating.
        let tex = transition();
        let huge = HairParams::new(10_000.0, 1.0).unwrap();
        assert!(HairInstances::generate(&g.surface(), &tex, &huge).is_err());
        let mut nan = grid(1, 1.0);
        nan.positions[0].x = f32::NAN;
        assert!(HairInstances::generate(&nan.surface(), &tex, &HairParams::default()).is_err());
    }

    #[test]
    fn key_sort_equals_a_stable_sort() {
        let mut rng = Rng::new(5);
        let unsorted: Vec<HairInstance> = (0..5000)
            .map(|i| HairInstance {
                position: [i as f32, 0.0, 0.0],
                disappear_age: [0.0, 0.25, 0.5, 1.0, 1e-30][rng.below(5) as usize],
                direction_oct: [0, 0],
                graying_onset: 0.0,
                uv_unorm: [0, 0],
                random_unorm: 0,
                length_unorm: 65535,
            })
            .collect();
        let mut want = unsorted.clone();
        want.sort_by(|a, b| b.disappear_age.total_cmp(&a.disappear_age));
        assert_eq!(sort_by_age_descending(&unsorted), want);
    }

    /// A hair is whole until shortly before it goes, and a hair that never goes stays whole.
    #[test]
    fn a_hair_is_miniaturised_just_before_it_goes() {
        assert_eq!(hair_whole(0.6, 0.3), 1.0);
        assert_eq!(hair_whole(0.6, 0.6 - MINIATURE_T), 1.0);
        let half = hair_whole(0.6, 0.6 - 0.5 * MINIATURE_T);
        assert!((half - 0.5).abs() < 1e-5, "{half}");
        assert_eq!(hair_whole(0.6, 0.6), 0.0);
        assert_eq!(hair_whole(1.0, 0.99), 1.0);
        assert_eq!(hair_whole(1.0, 1.0), 1.0);
    }

    /// Black hair grays 8 years later, a dark brown and lighter on time (the default
    /// head's fallback dark brown, L* 20.6, 1.6 years).
    #[test]
    fn black_hair_grays_later_and_brown_hair_on_time() {
        assert_eq!(graying_delay_years(4.0), DARK_HAIR_DELAY_YEARS);
        assert_eq!(graying_delay_years(BLACK_HAIR_L), DARK_HAIR_DELAY_YEARS);
        assert_eq!(graying_delay_years(DARK_BROWN_HAIR_L), 0.0);
        assert_eq!(graying_delay_years(45.0), 0.0);
        let brown = graying_delay_years(20.6);
        assert!((1.4..1.8).contains(&brown), "{brown}");
    }

    #[test]
    fn graying_at_hand_computed_points() {
        // t_k = 0.2, the ramp 0.08: y(0.24) = 0.5; smoothstep(0.5) = 0.5; y(0.22) = 0.25,
        // smoothstep(0.25) = 3/16 − 2/64 = 0.15625; done from 0.28 on.
        close(gray_fraction(0.24, 0.2, GrayingRamp::Linear), 0.5, 1e-5);
        close(gray_fraction(0.24, 0.2, GrayingRamp::Smoothstep), 0.5, 1e-5);
        close(gray_fraction(0.22, 0.2, GrayingRamp::Linear), 0.25, 1e-5);
        close(
            gray_fraction(0.22, 0.2, GrayingRamp::Smoothstep),
            0.15625,
            1e-5,
        );
        close(gray_fraction(0.1, 0.2, GrayingRamp::Linear), 0.0, 0.0);
        close(gray_fraction(0.28, 0.2, GrayingRamp::Smoothstep), 1.0, 1e-6);
        close(gray_fraction(0.6, 0.2, GrayingRamp::Linear), 1.0, 1e-6);
        close(gray_fraction(3.0, 0.2, GrayingRamp::Linear), 1.0, 1e-6);
        close(gray_fraction(1.0, 1.0, GrayingRamp::Linear), 0.0, 0.0);
        // An onset past the oldest age never grays.
        close(gray_fraction(1.0, 1.3, GrayingRamp::Linear), 0.0, 0.0);
        // C = (1 − y)·base + y·gray: y = 0.25 between brown (0.4, 0.2, 0.1) and gray 0.8.
        let c = hair_colour(Vec3::new(0.4, 0.2, 0.1), Vec3::splat(0.8), 0.25);
        close(c.x, 0.5, 1e-6);
        close(c.y, 0.35, 1e-6);
        close(c.z, 0.275, 1e-6);
    }

    #[test]
    fn the_default_head_in_metres_gets_a_plausible_scalp() {
        let head = crate::head::default::default_head();
        let surface = SurfaceRef::from(&head);
        // The upper part of the default head's chart (the forehead, the scalp and the
        // top of the ears; head module docs): an outer mask v > 0.6 and an inner band
        // 0.6 < v < 0.7.
        let n = 64u32;
        let outer: Vec<f32> = (0..n * n)
            .map(|i| f32::from(crate::maps::heightmap::pixel_to_v(i / n, n) > 0.6))
            .collect();
        let inner: Vec<f32> = (0..n * n)
            .map(|i| {
                let v = crate::maps::heightmap::pixel_to_v(i / n, n);
                f32::from(v > 0.6 && v < 0.7)
            })
            .collect();
        let tex = TransitionTexture::from_masks(
            &Mask::from_values(n, n, outer).unwrap(),
            &Mask::from_values(n, n, inner).unwrap(),
            n,
            n,
            DistanceMetric::Chebyshev,
        )
        .unwrap();
        let hairs =
            HairInstances::generate(&surface, &tex, &HairParams::new(10.0, 1.0).unwrap()).unwrap();
        // A head's crown above v = 0.6 is a few hundred cm²: thousands of hairs at 10 /cm².
        assert!((1_000..20_000).contains(&hairs.len()), "{}", hairs.len());
        // Hairs point away from the head: upward on the crown (within 1 cm of the top,
        // metres, where the scan's normals are within 35° of +Y).
        let crown = head.bounds().max.y - 0.01;
        let top = hairs.instances().iter().filter(|h| h.position().y > crown);
        assert!(top.clone().count() > 10);
        assert!(
            top.clone().all(|h| h.direction().y > 0.7),
            "crown hairs point up"
        );
    }

    #[test]
    fn thinning_loses_its_fraction_of_the_hair_that_stays_and_the_fringe_recedes_ragged() {
        let g = grid(16, 0.3);
        let tex = transition();
        let plain = HairInstances::generate(
            &g.surface(),
            &tex,
            &HairParams::new(30.0, 1.0).unwrap().with_seed(3),
        )
        .unwrap();
        let params = HairParams::new(30.0, 1.0)
            .unwrap()
            .with_seed(3)
            .with_thinning(0.4, RECESSION_SPREAD)
            .unwrap();
        let thinned = HairInstances::generate(&g.surface(), &tex, &params).unwrap();
        // The same places are drawn; near bare skin some hairs are left out (a soft
        // edge), the others only change their disappearance ages.
        assert!(
            thinned.len() < plain.len() && thinned.len() * 10 > plain.len() * 8,
            "{} of {}",
            thinned.len(),
            plain.len()
        );
        // Of the hair that stays, 40 % is gone at t = 1 (and some more at the edges).
        let stays = plain.count(1.0) as f32;
        let kept = thinned.count(1.0) as f32 / stays;
        eprintln!("{kept} of the hair that stays kept");
        assert!(
            (0.45..0.62).contains(&kept),
            "{kept} of the hair that stays kept"
        );
        assert!(thinned.instances().iter().all(|h| h.disappear_age() > 0.0));
        // The receding hair goes over a band of ages, not at its texel's age: at the
        // middle of the recession, some hairs of a texel are gone and some not.
        let mid = 0.5;
        let fringe = thinned
            .instances()
            .iter()
            .filter(|h| {
                let uv = h.uv();
                (tex.age_at_uv(uv.x, uv.y) - mid).abs() < 0.03
            })
            .map(|h| h.disappear_age() >= mid)
            .collect::<Vec<_>>();
        let present = fringe.iter().filter(|&&p| p).count();
        assert!(
            present > fringe.len() / 5 && present < fringe.len() * 4 / 5,
            "{present} of {} fringe hairs present at t = {mid}",
            fringe.len()
        );
    }

    #[test]
    fn the_taper_shortens_and_thins_the_hair_toward_its_regions_edges() {
        // The disc of hair (radius 0.4 of the 300 mm square: 120 mm), the part that stays
        // below v = 0.25; texels of 4.7 mm.
        let g = grid(16, 0.3);
        let tex = transition();
        let base = HairParams::new(30.0, 1.0).unwrap().with_seed(3);
        let plain = HairInstances::generate(&g.surface(), &tex, &base).unwrap();
        assert!(plain.instances().iter().all(|h| h.length_factor() == 1.0));
        let tapered = HairInstances::generate(
            &g.surface(),
            &tex,
            &base.clone().with_taper_mm(DEFAULT_TAPER_MM).unwrap(),
        )
        .unwrap();
        // mm inside the disc's edge.
        let inside = |h: &HairInstance| (0.4 - (h.uv() - Vec2::splat(0.5)).length()) * 300.0;
        let mean_length = |lo: f32, hi: f32| {
            let l: Vec<f32> = tapered
                .instances()
                .iter()
                .filter(|h| (lo..hi).contains(&inside(h)) && h.uv().y > 0.35)
                .map(HairInstance::length_factor)
                .collect();
            (l.iter().sum::<f32>() / l.len() as f32, l.len())
        };
        let (edge, n_edge) = mean_length(0.0, 5.0);
        let (deep, _) = mean_length(30.0, 200.0);
        eprintln!("length factor {edge} within 5 mm of the edge ({n_edge} hairs), {deep} deep");
        assert!(edge < 0.45, "{edge}");
        assert!(deep > 0.99, "{deep}");
        // Sparser at the edge: fewer of the same places kept within 5 mm than deep in.
        let kept = |lo: f32, hi: f32, hairs: &HairInstances| {
            hairs
                .instances()
                .iter()
                .filter(|h| (lo..hi).contains(&inside(h)) && h.uv().y > 0.35)
                .count() as f32
        };
        let edge_kept = kept(0.0, 5.0, &tapered) / kept(0.0, 5.0, &plain);
        let deep_kept = kept(30.0, 200.0, &tapered) / kept(30.0, 200.0, &plain);
        assert!(
            edge_kept < 0.75 && deep_kept == 1.0,
            "{edge_kept} {deep_kept}"
        );
        // The hair that stays (v < 0.25) fades out toward the hair that goes: at t = 1
        // fewer and shorter hairs within 5 mm of v = 0.25 than 20–25 mm below it (and as
        // far inside the disc: the taper's reach is 18 mm, the fringe's thinning 45 mm).
        let band = |lo: f32, hi: f32| {
            let hs: Vec<&HairInstance> = tapered
                .instances()
                .iter()
                .filter(|h| {
                    let below = (0.25 - h.uv().y) * 300.0;
                    (lo..hi).contains(&below) && inside(h) > 20.0
                })
                .collect();
            let stay = hs.iter().filter(|h| h.disappear_age() >= 1.0).count() as f32;
            let length = hs.iter().map(|h| h.length_factor()).sum::<f32>() / hs.len() as f32;
            (stay / hs.len() as f32, length)
        };
        let (near_stay, near_length) = band(0.0, 5.0);
        let (far_stay, far_length) = band(20.0, 25.0);
        eprintln!("stays at t = 1: {near_stay} near the fringe's edge, {far_stay} below it");
        assert!(
            near_stay < 0.5 && far_stay > near_stay + 0.3 && far_stay < 1.0,
            "{near_stay} {far_stay}"
        );
        assert!(
            near_length < 0.45 && far_length > 0.99,
            "{near_length} {far_length}"
        );
        // Same bytes again.
        let again = HairInstances::generate(
            &g.surface(),
            &tex,
            &base.with_taper_mm(DEFAULT_TAPER_MM).unwrap(),
        )
        .unwrap();
        assert_eq!(again.as_bytes(), tapered.as_bytes());
        assert!(HairParams::default().with_taper_mm(f32::NAN).is_err());
    }

    /// The 300 mm grid and the disc of hair of [`transition`], 60 hairs/cm², tapered (the
    /// project's taper, with its ragged fringe and strays).
    fn dense_tapered_hairs() -> (Grid, HairInstances) {
        let g = grid(16, 0.3);
        let params = HairParams::new(60.0, 1.0)
            .unwrap()
            .with_seed(5)
            .with_taper_mm(DEFAULT_TAPER_MM)
            .unwrap();
        let hairs = HairInstances::generate(&g.surface(), &transition(), &params).unwrap();
        (g, hairs)
    }

    #[test]
    fn the_fringes_top_edge_moves_along_its_length() {
        // The transition texture's edge between the hair that stays (v < 0.25) and the
        // hair that goes is a straight line; at t = 1 the fringe's top wanders about it:
        // tufts of hair that stays above it, bays below it, within [`RAGGED_MM`].
        let (_, hairs) = dense_tapered_hairs();
        // 10 mm columns across the edge, 20 mm or more inside the disc of hair; in each,
        // the fringe's top: the highest 4 mm band where two in five of the hairs (of any
        // age) stay at t = 1 (the fade makes the hair that stays sparse over 45 mm, so a
        // lone hair is no edge).
        let mut tops = Vec::new();
        for c in 0..14 {
            let (lo, hi) = (0.26 + c as f32 / 30.0, 0.26 + (c + 1) as f32 / 30.0);
            let mut bands = [(0u32, 0u32); 20];
            for h in hairs.instances() {
                let above = (h.uv().y - 0.25) * 300.0;
                if (lo..hi).contains(&h.uv().x) && (-60.0..20.0).contains(&above) {
                    let band = &mut bands[((above + 60.0) / 4.0) as usize];
                    band.0 += u32::from(h.disappear_age() >= 1.0);
                    band.1 += 1;
                }
            }
            let top = (0..20)
                .rev()
                .find(|&k| bands[k].1 > 0 && bands[k].0 as f32 >= 0.4 * bands[k].1 as f32)
                .map_or(-60.0, |k| k as f32 * 4.0 - 58.0);
            tops.push(top);
        }
        eprintln!("the fringe's top in 10 mm columns, mm above the texture's edge: {tops:?}");
        let (low, high) = tops
            .iter()
            .fold((f32::MAX, f32::MIN), |(l, h), &t| (l.min(t), h.max(t)));
        assert!(high - low >= 12.0, "a straight top: {tops:?}");
        assert!(
            low > -60.0 && high <= RAGGED_MM,
            "moved further than the edge moves: {tops:?}"
        );
        // The noise: bounded, smooth (1 mm apart differ little), seeded.
        let mut most = 0.0f32;
        for k in 0..2000 {
            let p = Vec3::new(k as f32 * 0.37, (k % 17) as f32 * 3.1, (k % 5) as f32 * 7.3);
            let n = ragged_noise(p, 5);
            assert!((-1.0..=1.0).contains(&n), "{n}");
            most = most.max((ragged_noise(p + Vec3::X, 5) - n).abs());
            assert_eq!(n, ragged_noise(p, 5));
        }
        assert!(most < 0.25, "{most}");
        assert_ne!(
            ragged_noise(Vec3::ONE * 10.0, 5),
            ragged_noise(Vec3::ONE * 10.0, 6)
        );
    }

    #[test]
    fn strays_thin_out_over_the_bald_scalp_above_the_fringe() {
        // Above the fringe's top (the texture's edge at v = 0.25, tufts reaching
        // [`RAGGED_MM`] above it), a few of the hairs that go stay at t = 1, fewer farther
        // up, none beyond the strays' reach.
        let (g, hairs) = dense_tapered_hairs();
        // The share that stays at t = 1 among the hairs `lo`–`hi` mm above the edge, 20 mm
        // or more inside the disc of hair.
        let share = |lo: f32, hi: f32| {
            let hs: Vec<&HairInstance> = hairs
                .instances()
                .iter()
                .filter(|h| {
                    let above = (h.uv().y - 0.25) * 300.0;
                    let inside = (0.4 - (h.uv() - Vec2::splat(0.5)).length()) * 300.0;
                    (lo..hi).contains(&above) && inside > 20.0
                })
                .collect();
            let stay = hs.iter().filter(|h| h.disappear_age() >= 1.0).count();
            (stay as f32 / hs.len() as f32, hs.len())
        };
        // (The distance to the hair that stays is read on rings, the outer two at 65 and
        // 100 % of the reach: 23 and 35 mm.)
        let (near, n_near) = share(RAGGED_MM + 2.0, RAGGED_MM + 6.0);
        let (far, _) = share(RAGGED_MM + 10.0, RAGGED_MM + STRAY_REACH_MM);
        let (beyond, n_beyond) = share(RAGGED_MM + STRAY_REACH_MM + 2.0, 150.0);
        eprintln!("strays: {near} of {n_near} near, {far} farther, {beyond} of {n_beyond} beyond");
        assert!(near > 0.02 && near < STRAY_SHARE, "{near}");
        assert!(far < near, "{far} {near}");
        assert!(beyond == 0.0 && n_beyond > 100, "{beyond} {n_beyond}");
        // Miniaturised: no stray has the full length (stored as 16 bits).
        assert!(
            hairs
                .instances()
                .iter()
                .filter(|h| (h.uv().y - 0.25) * 300.0 > RAGGED_MM + 2.0 && h.disappear_age() >= 1.0)
                .all(|h| h.length_factor() <= STRAY_LENGTH + 1e-4)
        );
        // [T]'s model (no taper) keeps none.
        let plain = HairInstances::generate(
            &g.surface(),
            &transition(),
            &HairParams::new(60.0, 1.0).unwrap().with_seed(5),
        )
        .unwrap();
        assert!(
            plain
                .instances()
                .iter()
                .all(|h| h.uv().y <= 0.26 || h.disappear_age() < 1.0)
        );
    }

    #[test]
    fn regions_from_bools_feed_instances_too() {
        // Keeps HairRegions usable as an input: a 2×1 texture, left half inner.
        let r = HairRegions::from_bools(2, 1, &[true, false], &[true, false]).unwrap();
        let tex = TransitionTexture::from_regions(&r, DistanceMetric::Chebyshev).unwrap();
        let g = grid(4, 0.1);
        let hairs =
            HairInstances::generate(&g.surface(), &tex, &HairParams::new(20.0, 1.0).unwrap())
                .unwrap();
        assert!(!hairs.is_empty());
        assert!(
            hairs
                .instances()
                .iter()
                .all(|h| h.uv().x <= 0.5 && h.disappear_age() == 1.0)
        );
    }
}
