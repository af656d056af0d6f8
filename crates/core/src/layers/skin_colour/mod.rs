//! The aged base colour (docs/models.md "Skin colour"): the head's own colour map (or the
//! skin colour when it has none) baked at an age, in its own UV layout, with
//!
//! - **age spots** (solar lentigines), 2–10 mm across, placed on the head's surface in
//!   metres, on sun-exposed skin (forehead, temples, cheeks, nose, ears, a bald scalp),
//!   appearing one after another from the onset of their curve and growing;
//! - **uneven tone**: mottled melanin on sun-exposed skin, and redness with thread veins
//!   (telangiectasia) on the cheeks and the nose;
//! - **paling and yellowing**, as a tint (the scan's brows and lips stay darker than the
//!   skin around them);
//! - **lower facial contrast**: lips and brows fade toward the skin around them, and the
//!   brows **gray** with the hair.
//!
//! The regions (sun exposure, brows, lips, cheeks and nose, eyes) are functions of the
//! template point each texel stands for (the default head's own point, or the fitted
//! template's through [`crate::head::fit::Fit::template_point`]): authored once on the template,
//! they reach every head. The spots and the noise live in the head's own metres, so their
//! sizes are physical whatever the head's units and UV layout, and a spot crossing a UV
//! seam continues on the other side. Seeded and hashed: the same bytes on any thread count.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::age::ColourFactors;
use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::base::math::smoothstep;
use crate::base::rng::{Rng, mix64, value3};
use crate::head::frame::Regions;
use crate::head::mesh::Mesh;
use crate::maps::mask::{HeadImage, linear_to_srgb, srgb_to_linear};
use crate::maps::raster::raster_uv;

/// Smallest and largest age-spot diameter, mm (solar lentigines: docs/models.md
/// "Skin colour").
pub const SPOT_DIAMETER_MM: (f32, f32) = (2.0, 10.0);

/// A spot's size when it first shows, as a fraction of its final size.
const SPOT_FIRST_SIZE: f32 = 0.4;

/// How far (in the spot curve's factor) after it appears a spot reaches its full size.
const SPOT_GROWTH: f32 = 0.35;

/// How much each linear channel of a full-strength spot darkens (brown: blue most).
const SPOT_TINT: [f32; 3] = [0.55, 0.68, 0.78];

/// How much melanin mottling darkens each channel at full strength.
const MOTTLE_TINT: [f32; 3] = [0.30, 0.40, 0.50];

/// Feature sizes of the mottling, mm: blotches and a finer grain.
const MOTTLE_MM: (f32, f32) = (9.0, 2.6);

/// How far the beard's darkest texels go toward the bare skin round the beard when all the
/// hair is gray, and how far every beard texel does.
const BEARD_GRAY: f32 = 0.8;
/// See [`BEARD_GRAY`].
const BEARD_LIFT: f32 = 0.5;
/// How much a full under-eye shadow takes from each linear channel (red least, blue most:
/// a brown-grey shadow; a violet one, and one taking a third from green, read blind as
/// "bruise paint").
const UNDER_EYE_TINT: [f32; 3] = [0.16, 0.2, 0.22];
/// How much the shadow under the bags darkens the skin at the crease, at full age and
/// strength, and its tint per channel: blue taken most (0.36 taking green most, a magenta,
/// read blind as "a purple bruise"). A quarter of what it was (0.3): the shape's relief
/// draws the crease's shape (`shape::relief`), and at 0.15, with the contact shadows, the
/// crease read as "brownish streaks across the upper cheeks, painted on".
const CREASE_SHADE: f32 = 0.07;
const CREASE_TINT: [f32; 3] = [0.7, 0.85, 1.0];
/// Feature size of the redness and of the thread veins, mm.
const REDNESS_MM: (f32, f32) = (6.0, 3.0);

/// The yellowing's tint per unit (green and blue lowered, red kept).
const YELLOW_TINT: [f32; 3] = [0.0, 0.06, 0.22];

/// How much of the contrast loss reaches the brows and the lips (brows keep more: they
/// thin and gray more than they fade).
const CONTRAST_BROWS: f32 = 0.2;
const CONTRAST_LIPS: f32 = 0.6;
/// How much more than the rest of the lips their outer part (`Regions::lip_rim`) fades.
const LIP_THINNING: f32 = 0.9;

/// Brightness of gray brow hair relative to the hair's gray colour: coarse white brow
/// hair over the skin reads lighter than the silver of the scalp's (at the scalp's
/// brightness the brows read, blind, as "gray putty").
const BROW_GRAY_BRIGHTNESS: f32 = 1.2;

/// Age spots gather over patches of about this size, mm, tried up to this many times each
/// ([`place_spots`]).
const SPOT_CLUSTER_MM: f32 = 35.0;
const SPOT_CLUSTER_TRIES: usize = 8;

/// One brow hair's draw in the salt-and-pepper graying and the bushier old brow: a streak
/// this long along the brow's arch and this wide, mm.
const BROW_STRAND_MM: (f32, f32) = (5.0, 0.9);

/// How dark a brow hair grown with age is against the skin around it (the scan's brow
/// hair, where the young brow was, is about this dark).
const BROW_GROWN_DARKNESS: f32 = 0.45;

/// How much of the brow region the old brow's longer, unruly hairs cover at full age
/// (beyond the young brow's own hair).
const BROW_BUSHY: f32 = 0.55;

/// Gray brow hair is warmer than the hair's gray: yellowed, as old white hair (the plain
/// gray read, blind, as blue-gray on the aged skin).
const BROW_GRAY_TINT: [f32; 3] = [1.0, 0.96, 0.9];

/// Side of the coarse grid of the local skin tone (the reference brows and lips fade to).
const TONE_GRID: usize = 32;

/// Blur passes (3×3 cells of [`TONE_GRID`]) of the bare skin's tone: about a quarter of
/// the UV layout's side, enough to reach across a beard.
const BARE_TONE_PASSES: usize = 8;

/// The artist's settings of the aged colour: the project's `skin` fields of the same
/// names (their meaning, units and ranges: `project::fields`), colours in linear RGB, and
/// the hair's gray colour (`hair.gray_colour`).
#[derive(Clone, Debug, PartialEq)]
pub struct ColourSettings {
    /// `skin.albedo`: also the colour of a head without a colour map.
    pub albedo: [f32; 3],
    /// `skin.pale_albedo`: paling multiplies the colour by `pale_albedo / albedo`.
    pub pale_albedo: [f32; 3],
    pub pale_amount: f32,
    pub spots_per_cm2: f32,
    pub spot_strength: f32,
    pub mottle: f32,
    pub redness: f32,
    pub yellowing: f32,
    pub contrast_loss: f32,
    /// `skin.under_eye`: the shadow of the tear trough and the lower lid.
    pub under_eye: f32,
    pub gray_hair: [f32; 3],
    /// `skin.colour_seed`.
    pub seed: u64,
}

impl Default for ColourSettings {
    fn default() -> Self {
        Self {
            albedo: [0.69, 0.35, 0.24],
            pale_albedo: [0.69, 0.48, 0.37],
            pale_amount: 0.25,
            spots_per_cm2: 0.6,
            spot_strength: 0.7,
            mottle: 0.3,
            redness: 0.5,
            yellowing: 0.6,
            contrast_loss: 0.7,
            under_eye: 0.65,
            gray_hair: [0.51, 0.49, 0.46],
            seed: 1,
        }
    }
}

/// One age spot on the head's surface (head metres).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spot {
    pub centre: Vec3,
    /// The surface normal there (the spot's plane).
    pub normal: Vec3,
    /// Final diameter, mm, in [`SPOT_DIAMETER_MM`].
    pub diameter_mm: f32,
    /// The spot curve's factor at which it appears, [0, 1).
    pub appears: f32,
    /// Darkness, 0.3–1.3 (times the project's strength, then at most 1).
    pub strength: f32,
    /// Phases of its outline's wobble.
    phases: [f32; 3],
}

impl Spot {
    /// Its size (fraction of the final diameter) and darkness at spot factor `f`; 0 before
    /// it appears.
    pub fn grown(&self, f: f32) -> f32 {
        if f <= self.appears {
            return 0.0;
        }
        let g = ((f - self.appears) / SPOT_GROWTH).min(1.0);
        SPOT_FIRST_SIZE + (1.0 - SPOT_FIRST_SIZE) * g
    }

    /// Its diameter at spot factor `f`, mm (0 before it appears).
    pub fn diameter_at(&self, f: f32) -> f32 {
        self.diameter_mm * self.grown(f)
    }
}

/// The age spots of a head: drawn by area over its skin, weighted by sun exposure squared,
/// gathered in patches, each with its own appearance, size and darkness (docs/models.md
/// "Skin colour").
pub fn place_spots(
    mesh: &Mesh,
    template_point: &dyn Fn(usize) -> Option<Vec3>,
    metres_per_unit: f32,
    regions: &Regions,
    spots_per_cm2: f32,
    seed: u64,
) -> Vec<Spot> {
    place_spots_gathered(
        mesh,
        template_point,
        metres_per_unit,
        regions,
        spots_per_cm2,
        seed,
        SPOT_CLUSTER_TRIES,
    )
}

/// [`place_spots`] with `tries` draws per spot for the gathering (1: spread evenly).
fn place_spots_gathered(
    mesh: &Mesh,
    template_point: &dyn Fn(usize) -> Option<Vec3>,
    metres_per_unit: f32,
    regions: &Regions,
    spots_per_cm2: f32,
    seed: u64,
    tries: usize,
) -> Vec<Spot> {
    let positions = mesh.positions();
    let idx = mesh.skin_indices();
    // Each skin triangle's exposed area, m², as a running sum.
    let mut cumulative = Vec::with_capacity(idx.len() / 3);
    let mut total = 0.0f64;
    for tri in idx.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|i| positions[tri[i] as usize] * metres_per_unit);
        let area = 0.5 * (b - a).cross(c - a).length();
        let points: Option<Vec<Vec3>> = tri.iter().map(|&v| template_point(v as usize)).collect();
        // No spots on the lids nor in the brows (shaded; a dark fleck there read, blind,
        // as a speck of dirt once the lid hooded over it). Lentigines follow the lifetime's
        // dose, so the exposure counts squared: few where it is partial (by the mouth, a
        // patch of them read, blind, as "a dirty smudge in the fold").
        let sun = points.map_or(0.0, |p| {
            let c = (p[0] + p[1] + p[2]) / 3.0;
            regions.sun(c).powi(2) * (1.0 - regions.eyes(c)) * (1.0 - regions.brows(c))
        });
        if area.is_finite() {
            total += f64::from(area * sun);
        }
        cumulative.push(total);
    }
    let expected = total * 1e4 * f64::from(spots_per_cm2.max(0.0));
    if expected.is_nan() || expected <= 0.0 || !expected.is_finite() {
        return Vec::new();
    }
    let mut rng = Rng::for_stream(seed, 0x5907);
    // The count: the expectation's whole part, and one more with its fraction.
    let count = expected.floor() as usize + usize::from(rng.next_f64() < expected.fract());
    let count = count.min(100_000);
    let (lo, hi) = SPOT_DIAMETER_MM;
    (0..count)
        .map(|_| {
            // Spots gather: a place is kept with a chance that follows a noise of
            // SPOT_CLUSTER_MM (up to SPOT_CLUSTER_TRIES draws), so there are clusters and
            // bare patches (an even spread read, blind, as "stamped on").
            let mut place = || {
                let x = rng.next_f64() * total;
                let k = cumulative
                    .partition_point(|&c| c <= x)
                    .min(cumulative.len() - 1);
                let tri = &idx[3 * k..3 * k + 3];
                let [a, b, c] = [0, 1, 2].map(|i| positions[tri[i] as usize] * metres_per_unit);
                let (mut u, mut v) = (rng.next_f32(), rng.next_f32());
                if u + v > 1.0 {
                    (u, v) = (1.0 - u, 1.0 - v);
                }
                let keep = rng.next_f32();
                (a, b, c, u, v, keep)
            };
            let mut drawn = place();
            for _ in 1..tries {
                let (a, b, c, u, v, keep) = drawn;
                if keep < spot_gathering(a + (b - a) * u + (c - a) * v, seed) {
                    break;
                }
                drawn = place();
            }
            let (a, b, c, u, v, _) = drawn;
            // Small spots are common, large ones rare: d = lo·(hi/lo)^(x³) (a blind
            // rating read x² as "a few large soft smudges").
            let size = rng.next_f32();
            // Most faint, a few dark: 0.3 + x² (0.5–1 read, blind, as "same-coloured flat
            // decals").
            let dark = rng.next_f32();
            Spot {
                centre: a + (b - a) * u + (c - a) * v,
                normal: (b - a).cross(c - a).normalize_or(Vec3::Z),
                diameter_mm: lo * (hi / lo).powf(size * size * size),
                appears: rng.next_f32(),
                strength: 0.3 + dark * dark,
                phases: [0; 3].map(|_| rng.range_f32(0.0, std::f32::consts::TAU)),
            }
        })
        .collect()
}

/// The chance that a spot drawn at `p` (head metres) is kept ([`place_spots`]): (0.5 +
/// 0.5 n)³, n a value noise of [`SPOT_CLUSTER_MM`] seeded by `seed`.
fn spot_gathering(p: Vec3, seed: u64) -> f32 {
    let key = (mix64(seed ^ 0x0059_07c1) & 0xffff_ffff) as u32;
    let g = 0.5 + 0.5 * value3(p * 1000.0 / SPOT_CLUSTER_MM, key);
    g * g * g
}

/// The head's surface per texel of its UV layout: the point (head metres) each texel
/// stands for (NaN where no skin triangle covers it), and what does not change with age
/// there ([`Fields`]: the regions of its template point, the noise): made once per head, size and
/// seed, so an age change only re-weights.
#[derive(Clone, Debug)]
pub struct SurfaceTexels {
    size: u32,
    position: Vec<Vec3>,
    fields: Vec<Fields>,
}

/// The regions' weights and the uneven tone's noise at one texel, as bytes (weights
/// 0–1, noise −1–1 in 255 steps: far below what a colour shows).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Fields {
    sun: u8,
    brows: u8,
    lips: u8,
    lip_rim: u8,
    red: u8,
    blotch: u8,
    grain: u8,
    flush: u8,
    vein: u8,
    brow_draw: u8,
    brow_strand: u8,
    under_eye: u8,
    crease: u8,
    beard: u8,
    bare: u8,
}

fn unit_byte(x: f32) -> u8 {
    (x.clamp(0.0, 1.0) * 255.0).round() as u8
}

fn signed_byte(x: f32) -> u8 {
    unit_byte(0.5 + 0.5 * x)
}

fn from_unit(b: u8) -> f32 {
    f32::from(b) / 255.0
}

fn from_signed(b: u8) -> f32 {
    f32::from(b) / 127.5 - 1.0
}

/// The noise streams of one seed: blotch, grain, flush, vein, brow hair, spot grain.
fn noise_keys(seed: u64) -> [u32; 6] {
    [1, 2, 3, 4, 5, 6].map(|k| (mix64(seed ^ k) & 0xffff_ffff) as u32)
}

/// The face frame the aged colour is drawn in: the template's regions, and the crease the
/// colour draws under the bags (a template point's weight, 0–1). The crease's line belongs
/// to the shape layer (its bags' roll); the scene hands it in, so that no layer imports
/// another.
#[derive(Clone, Copy)]
pub struct Face<'a> {
    pub regions: &'a Regions,
    /// The lid–cheek crease at a point of the face frame ([`Regions::relative`]).
    pub drawn_crease: &'a (dyn Fn(Vec3) -> f32 + Sync),
}

impl Fields {
    fn at(p: Vec3, t: Vec3, face_frame: Face<'_>, keys: &[u32; 6]) -> Self {
        let regions = face_frame.regions;
        let on_template = !t.x.is_nan();
        // Behind the face (the scalp, the back of the head) only the sun exposure, the
        // beard and the bare skin (the neck) can be non-zero: the face's other regions
        // are skipped there.
        let face = on_template && regions.in_front(t) > 0.0;
        let w = |g: fn(&Regions, Vec3) -> f32| if face { g(regions, t) } else { 0.0 };
        let anywhere = |g: fn(&Regions, Vec3) -> f32| {
            if on_template { g(regions, t) } else { 0.0 }
        };
        let sun = anywhere(Regions::sun);
        let (brows, red) = (w(Regions::brows), w(Regions::redness));
        let mm = p * 1000.0;
        Self {
            sun: unit_byte(sun),
            brows: unit_byte(brows),
            lips: unit_byte(w(Regions::lips)),
            lip_rim: unit_byte(w(Regions::lip_rim)),
            red: unit_byte(red),
            blotch: signed_byte(fbm(mm / MOTTLE_MM.0, keys[0])),
            grain: signed_byte(value3(mm / MOTTLE_MM.1, keys[1])),
            flush: if red > 0.0 {
                signed_byte(fbm(mm / REDNESS_MM.0, keys[2]))
            } else {
                128
            },
            vein: if red > 0.0 {
                signed_byte(fbm(mm / REDNESS_MM.1, keys[3]))
            } else {
                128
            },
            brow_draw: if brows > 0.0 {
                signed_byte(value3(brow_streak(regions, t), keys[4]))
            } else {
                128
            },
            // The old brow's longer hair grows from the brow, not on the lid below it
            // (where a dark one read as a speck once the lid hooded).
            brow_strand: if brows > 0.0 {
                signed_byte(
                    value3(brow_streak(regions, t), keys[4] ^ 0x5bd1_e995)
                        * (1.0 - w(Regions::eyes)),
                )
            } else {
                128
            },
            under_eye: unit_byte(w(Regions::under_eye)),
            crease: if face {
                unit_byte((face_frame.drawn_crease)(regions.relative(t)))
            } else {
                0
            },
            // The beard wraps round the jaw's angle, behind the face's plane.
            beard: unit_byte(anywhere(Regions::beard)),
            bare: unit_byte(anywhere(Regions::bare_skin)),
        }
    }
}

/// How far (pixels) beyond its triangle a texel still takes the triangle's surface: the
/// bilinear and mip filtering of an island's edge read aged texels.
const GUARD_PX: f32 = 1.5;

impl SurfaceTexels {
    /// Rasterises the skin triangles of `mesh` in its UV layout at `size`², and each
    /// covered texel's regions and noise (of `seed`).
    pub fn new(
        mesh: &Mesh,
        template_point: &dyn Fn(usize) -> Option<Vec3>,
        metres_per_unit: f32,
        size: u32,
        face: Face<'_>,
        seed: u64,
        cancel: &CancelToken,
    ) -> Result<Self, Error> {
        crate::maps::heightmap::check_size(size, size)?;
        let n = size as usize;
        let nan = Vec3::splat(f32::NAN);
        let mut position = vec![nan; n * n];
        let mut template = vec![nan; n * n];
        let mut distance = vec![f32::INFINITY; n * n];
        let (uvs, positions) = (mesh.uvs(), mesh.positions());
        for (k, tri) in mesh.skin_indices().chunks_exact(3).enumerate() {
            if k % 4096 == 0 {
                cancel.check()?;
            }
            let v = [0, 1, 2].map(|i| tri[i] as usize);
            let uv = v.map(|i| uvs.get(i).copied().unwrap_or(Vec2::NAN));
            let p = v.map(|i| positions[i] * metres_per_unit);
            let t = v.map(|i| template_point(i).unwrap_or(nan));
            raster_uv(uv, size, GUARD_PX, |x, y, w, outside| {
                let i = y * n + x;
                if outside < distance[i] {
                    distance[i] = outside;
                    position[i] = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
                    template[i] = t[0] * w[0] + t[1] * w[1] + t[2] * w[2];
                }
            });
        }
        let keys = noise_keys(seed);
        let mut fields = vec![Fields::default(); n * n];
        fields
            .par_chunks_mut(n)
            .enumerate()
            .try_for_each(|(y, row)| -> Result<(), Error> {
                if y % 64 == 0 {
                    cancel.check()?;
                }
                for (x, f) in row.iter_mut().enumerate() {
                    let p = position[y * n + x];
                    if !p.x.is_nan() {
                        *f = Fields::at(p, template[y * n + x], face, &keys);
                    }
                }
                Ok(())
            })?;
        Ok(Self {
            size,
            position,
            fields,
        })
    }

    pub fn size(&self) -> u32 {
        self.size
    }
}

/// What the aged colour starts from at each texel, kept between ages: the base colour
/// (the head's colour map resampled, or the skin colour), in linear light, its alpha, the
/// local skin tone around it, and the bare skin's tone round the beard.
#[derive(Clone, Debug)]
pub struct BaseColour {
    size: u32,
    colour: Vec<Vec3>,
    alpha: Vec<u8>,
    tone: Vec<Vec3>,
    bare: ToneCells,
}

impl BaseColour {
    /// `base` (the head's colour map, any size, sRGB) or `albedo` (linear) where there is
    /// none, at the texels' size.
    pub fn new(base: Option<&HeadImage>, albedo: [f32; 3], texels: &SurfaceTexels) -> Self {
        let n = texels.size as usize;
        let to_linear: Vec<f32> = (0..256).map(|c| srgb_to_linear(c as f32 / 255.0)).collect();
        let base_at = |x: usize, y: usize| -> Vec3 {
            match base {
                Some(img) => sample_linear(
                    img,
                    &to_linear,
                    (x as f32 + 0.5) / n as f32,
                    (y as f32 + 0.5) / n as f32,
                ),
                None => Vec3::from(albedo),
            }
        };
        let mut colour = vec![Vec3::ZERO; n * n];
        let mut alpha = vec![255u8; n * n];
        colour
            .par_chunks_mut(n)
            .zip(alpha.par_chunks_mut(n))
            .enumerate()
            .for_each(|(y, (row, a))| {
                for x in 0..n {
                    row[x] = base_at(x, y);
                    a[x] = base.map_or(255, |img| alpha_at(img, x, y, n));
                }
            });
        let tone = local_tone(n, &texels.position, &texels.fields, &base_at);
        let bare = bare_tone(n, &texels.position, &texels.fields, &base_at);
        Self {
            size: texels.size,
            colour,
            alpha,
            tone,
            bare,
        }
    }
}

/// The aged base colour at `size`² (the texels' size): `base` (the head's colour map, any
/// size, sRGB) or `settings.albedo` where there is none, aged by `factors`, as sRGB RGBA8.
/// Texels no skin triangle covers keep the base colour. ([`bake_from`] with the base made
/// here.)
pub fn bake(
    base: Option<&HeadImage>,
    texels: &SurfaceTexels,
    spots: &[Spot],
    settings: &ColourSettings,
    factors: &ColourFactors,
    cancel: &CancelToken,
) -> Result<HeadImage, Error> {
    let base = BaseColour::new(base, settings.albedo, texels);
    bake_from(&base, texels, spots, settings, factors, cancel)
}

/// The aged colour from a kept [`BaseColour`] of the same texels: what an age change
/// re-does (the regions and noise of the texels, the base and its tone stay).
pub fn bake_from(
    base: &BaseColour,
    texels: &SurfaceTexels,
    spots: &[Spot],
    settings: &ColourSettings,
    factors: &ColourFactors,
    cancel: &CancelToken,
) -> Result<HeadImage, Error> {
    let n = texels.size as usize;
    if base.size != texels.size {
        return Err(Error::InvalidValue {
            what: "aged colour base".into(),
            value: format!("{}² for texels of {}²", base.size, texels.size),
            expected: "the texels' size".into(),
        });
    }
    let grid = SpotGrid::new(spots, factors.spots);
    let spot_key = noise_keys(settings.seed)[5];
    let pale_tint = {
        let (a, p) = (
            Vec3::from(settings.albedo),
            Vec3::from(settings.pale_albedo),
        );
        let ratio = (p / a.max(Vec3::splat(1e-3))).clamp(Vec3::splat(0.25), Vec3::splat(4.0));
        Vec3::ONE + (ratio - Vec3::ONE) * (settings.pale_amount * factors.pale).clamp(0.0, 1.0)
    };
    let yellow = Vec3::ONE - Vec3::from(YELLOW_TINT) * settings.yellowing * factors.pale;
    let gray = Vec3::from(settings.gray_hair) * Vec3::from(BROW_GRAY_TINT) * BROW_GRAY_BRIGHTNESS;
    let to_srgb: Vec<u8> = (0..4096)
        .map(|i| (linear_to_srgb(i as f32 / 4095.0) * 255.0).round() as u8)
        .collect();
    let encode = |c: f32| to_srgb[(c.clamp(0.0, 1.0) * 4095.0).round() as usize];
    let mut rgba = vec![0u8; n * n * 4];
    let young = factors.is_young();
    let look = Look {
        settings,
        factors,
        grid: &grid,
        spot_key,
        pale_tint,
        yellow,
        gray,
    };
    rgba.par_chunks_mut(n * 4)
        .enumerate()
        .try_for_each(|(y, row)| -> Result<(), Error> {
            if y % 64 == 0 {
                cancel.check()?;
            }
            for (x, px) in row.chunks_exact_mut(4).enumerate() {
                let i = y * n + x;
                let mut c = base.colour[i];
                let p = texels.position[i];
                if !young && !p.x.is_nan() {
                    let f = &texels.fields[i];
                    let bare = if f.beard > 0 {
                        base.bare.at(x, y)
                    } else {
                        Vec3::ZERO
                    };
                    c = look.age(c, p, f, base.tone[i], bare);
                }
                px[0] = encode(c.x);
                px[1] = encode(c.y);
                px[2] = encode(c.z);
                px[3] = base.alpha[i];
            }
            Ok(())
        })?;
    Ok(HeadImage {
        width_px: n as u32,
        height_px: n as u32,
        rgba,
    })
}

/// `image` with its alpha replaced by `alpha` (`hair::scalp::hair_age_alpha` of its size), or by 0
/// (no hair anywhere) without one: the 3D view's colour map; the skin pass tints the scalp
/// under the hair present at its age.
pub fn with_alpha(image: &HeadImage, alpha: Option<&[u8]>) -> HeadImage {
    let mut shown = image.clone();
    match alpha.filter(|a| a.len() * 4 == shown.rgba.len()) {
        Some(alpha) => shown
            .rgba
            .par_chunks_mut(4 * 4096)
            .zip(alpha.par_chunks(4096))
            .for_each(|(px, a)| {
                for (p, &a) in px.chunks_exact_mut(4).zip(a) {
                    p[3] = a;
                }
            }),
        None => shown.rgba.par_chunks_mut(4 * 4096).for_each(|px| {
            for p in px.chunks_exact_mut(4) {
                p[3] = 0;
            }
        }),
    }
    shown
}

/// What ages every texel alike at one age: the settings, the factors and the tints made
/// from them, the spots that show.
struct Look<'a> {
    settings: &'a ColourSettings,
    factors: &'a ColourFactors,
    grid: &'a SpotGrid,
    spot_key: u32,
    pale_tint: Vec3,
    yellow: Vec3,
    gray: Vec3,
}

impl Look<'_> {
    /// One texel aged (linear RGB in, linear RGB out): `p` its point (head metres), `f`
    /// its regions and noise, `reference` the skin tone around it, `bare` the tone of the
    /// bare skin round the beard (used only in the beard).
    fn age(&self, mut c: Vec3, p: Vec3, f: &Fields, reference: Vec3, bare: Vec3) -> Vec3 {
        let (s, a) = (self.settings, self.factors);
        let (sun, brows, lips, red) = (
            from_unit(f.sun),
            from_unit(f.brows),
            from_unit(f.lips),
            from_unit(f.red),
        );
        // Brow hair: darker than the skin around it.
        let lum = |c: Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        let mut hair = brows * smoothstep(0.12, 0.45, 1.0 - lum(c) / lum(reference).max(1e-4));
        // The old brow is bushier: longer, unruly hairs beyond the young brow's own, in
        // streaks along the hairs' direction.
        let grown = BROW_BUSHY
            * a.contrast
            * brows
            * brows
            * smoothstep(0.1, 0.45, from_signed(f.brow_strand));
        if grown > hair {
            c = c.lerp(reference * BROW_GROWN_DARKNESS, grown - hair);
            hair = grown;
        }
        // Lips and brows fade toward the skin around them.
        // The lips' outer part fades further (their red narrows toward the mouth's line:
        // thinner lips; faded evenly they read, blind, as "paler but barely thinner").
        let lips = CONTRAST_LIPS * lips + LIP_THINNING * from_unit(f.lip_rim);
        let fade = s.contrast_loss * a.contrast * (CONTRAST_BROWS * brows).max(lips);
        c = c.lerp(reference, fade.clamp(0.0, 1.0));
        // The stubble grays with the hair: gray stubble on pale skin casts no shadow, so
        // the beard's texels go toward the bare skin round the beard, its darker texels
        // most: no "moustache" shadow at 80, and no grey jaw over a pink neck (toward the
        // beard's own tone, which the dark stubble pulls down and grays, the jaw read,
        // blind, as "a colour seam" where it met the neck).
        let beard = from_unit(f.beard) * a.brow_gray;
        if beard > 0.0 {
            let dark = smoothstep(0.0, 0.25, 1.0 - lum(c) / lum(reference).max(1e-4));
            let lift = beard * (BEARD_GRAY * dark + BEARD_LIFT);
            c = c.lerp(bare, lift.clamp(0.0, 1.0));
        }
        // The under-eye shadow (thinner lid skin over the orbicularis, the tear trough's
        // hollow): a brown-grey darkening on the contrast curve.
        let shadow = s.under_eye * a.contrast * from_unit(f.under_eye);
        if shadow > 0.0 {
            c *= Vec3::ONE - Vec3::from(UNDER_EYE_TINT) * shadow.min(1.0);
        }
        // The shadow under the bags, along the lid–cheek junction: the aged shape's crease
        // there is narrower than the mesh's triangles, so the shape's normals do not shade
        // it (the relief finer than the triangles draws its shape; docs/models.md §13
        // "Hollows"); a warm shadow (the skin's red scatters back out).
        let crease = CREASE_SHADE * a.bags.min(1.5) * from_unit(f.crease);
        if crease > 0.0 {
            c *= Vec3::ONE - Vec3::from(CREASE_TINT) * crease;
        }
        // Paling and yellowing: a tint, so what is darker stays darker.
        c *= self.pale_tint * self.yellow;
        // The brows gray with the hair, hair by hair: a texel's hair is gray when its draw
        // (value noise in streaks along the hairs, [`BROW_STRAND_MM`]) is under the gray
        // fraction: salt and pepper. The skin shows a little between the hairs.
        if hair > 0.0 && a.brow_gray > 0.0 {
            // Value noise gathers near 0: spread to about even over [0, 1], so the gray
            // fraction is the share of gray hair.
            let draw = 0.5 + 0.5 * (2.2 * from_signed(f.brow_draw)).clamp(-1.0, 1.0);
            let gray_hair = smoothstep(-0.08, 0.08, a.brow_gray_fraction() - draw);
            c = c.lerp(
                self.gray * (0.75 + 0.25 * draw),
                (0.75 * hair * gray_hair).clamp(0.0, 1.0),
            );
        }
        // Every skin mottles some; sun-exposed skin most. Darker blotches and lighter skin
        // between, about even on average, so no region's mean tone shifts (no edge where
        // the exposure falls off).
        let m = s.mottle * a.mottle * (0.35 + 0.65 * sun);
        if m > 0.0 {
            let (blotch, grain) = (from_signed(f.blotch), from_signed(f.grain));
            let d = (smoothstep(-0.3, 0.6, blotch) - 0.45
                + 0.4 * (smoothstep(-0.2, 0.7, grain) - 0.4))
                * m;
            c *= Vec3::ONE - Vec3::from(MOTTLE_TINT) * d;
        }
        // Redness and thread veins on the cheeks and the nose.
        let r = s.redness * a.redness * red;
        if r > 0.0 {
            let flush = r * (0.55 + 0.45 * from_signed(f.flush));
            let veins = r * (1.0 - from_signed(f.vein).abs()).powi(14);
            c *= Vec3::new(
                1.0 + 0.06 * flush,
                1.0 - 0.3 * flush - 0.4 * veins,
                1.0 - 0.22 * flush - 0.34 * veins,
            );
        }
        // Age spots.
        let spot = self.grid.darkness(p, self.spot_key) * s.spot_strength;
        if spot > 0.0 {
            c *= Vec3::ONE - Vec3::from(SPOT_TINT) * spot.min(1.0);
        }
        c
    }
}

/// The spots that show at one spot factor, in a uniform grid over their bounds (each spot
/// listed in every cell its disc touches, so a texel reads one cell).
struct SpotGrid {
    spots: Vec<(Spot, f32)>,
    origin: Vec3,
    cell: f32,
    dims: [usize; 3],
    cells: Vec<Vec<u32>>,
}

impl SpotGrid {
    fn new(spots: &[Spot], factor: f32) -> Self {
        let shown: Vec<(Spot, f32)> = spots
            .iter()
            .filter_map(|s| {
                let g = s.grown(factor);
                (g > 0.0).then_some((*s, g))
            })
            .collect();
        // A spot's reach: its radius and its wobble, metres.
        let reach = |s: &Spot, g: f32| 0.5e-3 * s.diameter_mm * g * 1.5;
        let cell = SPOT_DIAMETER_MM.1 * 1e-3;
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for (s, g) in &shown {
            lo = lo.min(s.centre - reach(s, *g));
            hi = hi.max(s.centre + reach(s, *g));
        }
        if shown.is_empty() {
            return Self {
                spots: shown,
                origin: Vec3::ZERO,
                cell,
                dims: [0; 3],
                cells: Vec::new(),
            };
        }
        let dims = ((hi - lo) / cell)
            .ceil()
            .max(Vec3::ONE)
            .to_array()
            .map(|d| (d as usize).min(512));
        let mut cells = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        let index = |c: [usize; 3]| (c[2] * dims[1] + c[1]) * dims[0] + c[0];
        let to_cell = |p: Vec3| {
            let c = ((p - lo) / cell).floor();
            [0, 1, 2].map(|k| (c[k].max(0.0) as usize).min(dims[k] - 1))
        };
        for (k, (s, g)) in shown.iter().enumerate() {
            let (a, b) = (
                to_cell(s.centre - reach(s, *g)),
                to_cell(s.centre + reach(s, *g)),
            );
            for z in a[2]..=b[2] {
                for y in a[1]..=b[1] {
                    for x in a[0]..=b[0] {
                        cells[index([x, y, z])].push(k as u32);
                    }
                }
            }
        }
        Self {
            spots: shown,
            origin: lo,
            cell,
            dims,
            cells,
        }
    }

    /// The darkest spot at `p` (head metres), 0–1.
    fn darkness(&self, p: Vec3, key: u32) -> f32 {
        if self.cells.is_empty() {
            return 0.0;
        }
        let c = ((p - self.origin) / self.cell).floor();
        let mut at = [0usize; 3];
        for k in 0..3 {
            if c[k] < 0.0 || c[k] >= self.dims[k] as f32 {
                return 0.0;
            }
            at[k] = c[k] as usize;
        }
        let list = &self.cells[(at[2] * self.dims[1] + at[1]) * self.dims[0] + at[0]];
        let mut dark: f32 = 0.0;
        for &k in list {
            let (s, g) = &self.spots[k as usize];
            let d = p - s.centre;
            // In the spot's plane.
            let d = d - s.normal * d.dot(s.normal);
            let r = 0.5e-3 * s.diameter_mm * g;
            let dist = d.length();
            if dist > 1.5 * r {
                continue;
            }
            // The outline wobbles: an irregular macule, not a disc.
            let (e1, e2) = s.normal.any_orthonormal_pair();
            let theta = d.dot(e2).atan2(d.dot(e1));
            let ph = s.phases;
            let edge = r
                * (1.0
                    + 0.22 * (2.0 * theta + ph[0]).sin()
                    + 0.14 * (3.0 * theta + ph[1]).sin()
                    + 0.08 * (5.0 * theta + ph[2]).sin());
            let inside = 1.0 - smoothstep(0.7 * edge, edge, dist);
            if inside <= 0.0 {
                continue;
            }
            // Uneven inside: darker in patches.
            // Patchy inside (a blind rating read an even tint as "stickers"): blotches at
            // 1.2 mm and specks at 0.4 mm, darker toward the middle.
            let grain = (0.7
                + 0.3 * value3(p * 1000.0 / 1.2, key ^ k)
                + 0.15 * value3(p * 1000.0 / 0.4, (key ^ k).rotate_left(7)))
                * (1.1 - 0.25 * (dist / edge).min(1.0));
            dark = dark.max(
                inside
                    * s.strength
                    * grain
                    * (0.5 + 0.5 * ((g - SPOT_FIRST_SIZE) / (1.0 - SPOT_FIRST_SIZE))),
            );
        }
        dark
    }
}

/// The local skin tone per texel: the base colour averaged over a coarse grid of the UV
/// layout ([`ToneCells`]), read back bilinearly. What lips and brows fade toward, and
/// what brow hair is darker than. The lips do not count: the skin round them is what they
/// fade toward (with their own red in the average they kept much of it, and read blind as
/// "barely thinner").
fn local_tone(
    n: usize,
    position: &[Vec3],
    fields: &[Fields],
    base_at: &(dyn Fn(usize, usize) -> Vec3 + Sync),
) -> Vec<Vec3> {
    let cells = ToneCells::new(n, position, base_at, 2, |i| 1.0 - from_unit(fields[i].lips));
    let mut out = vec![Vec3::ZERO; n * n];
    out.par_chunks_mut(n).enumerate().for_each(|(y, row)| {
        for (x, o) in row.iter_mut().enumerate() {
            *o = cells.at(x, y);
        }
    });
    out
}

/// The bare skin's tone round the beard: the base colour of [`Regions::bare_skin`] away
/// from the beard, the lips, the redness and the eyes, blurred far enough ([`BARE_TONE_PASSES`]) to
/// reach across the beard from the skin round it (the cheeks above, the neck below).
fn bare_tone(
    n: usize,
    position: &[Vec3],
    fields: &[Fields],
    base_at: &(dyn Fn(usize, usize) -> Vec3 + Sync),
) -> ToneCells {
    ToneCells::new(n, position, base_at, BARE_TONE_PASSES, |i| {
        let f = &fields[i];
        [f.beard, f.lips, f.red, f.under_eye]
            .iter()
            .map(|&b| 1.0 - from_unit(b))
            .product::<f32>()
            * from_unit(f.bare)
    })
}

/// A skin tone over the UV layout: the base colour averaged over a [`TONE_GRID`]² grid
/// (only covered texels count, each with its weight, so the background does not darken
/// island edges), blurred by a number of 3×3 box passes (normalised convolution).
#[derive(Clone, Debug)]
struct ToneCells {
    /// The bake's side, texels.
    n: usize,
    /// Mean colour per cell; NaN where nothing counted within the blur's reach.
    cells: Vec<Vec3>,
}

impl ToneCells {
    fn new(
        n: usize,
        position: &[Vec3],
        base_at: &(dyn Fn(usize, usize) -> Vec3 + Sync),
        passes: usize,
        weight_of: impl Fn(usize) -> f32,
    ) -> Self {
        let g = TONE_GRID;
        let mut sum = vec![Vec3::ZERO; g * g];
        let mut weight = vec![0.0f32; g * g];
        // A sparse sample is enough for a coarse average.
        let step = (n / 256).max(1);
        for y in (0..n).step_by(step) {
            for x in (0..n).step_by(step) {
                let i = y * n + x;
                if position[i].x.is_nan() {
                    continue;
                }
                let w = weight_of(i);
                if w <= 0.0 {
                    continue;
                }
                let k = (y * g / n) * g + x * g / n;
                sum[k] += base_at(x, y) * w;
                weight[k] += w;
            }
        }
        for _ in 0..passes {
            let (s0, w0) = (sum.clone(), weight.clone());
            for y in 0..g {
                for x in 0..g {
                    let (mut s, mut w) = (Vec3::ZERO, 0.0);
                    for dy in -1i32..=1 {
                        for dx in -1i32..=1 {
                            let (xx, yy) = (x as i32 + dx, y as i32 + dy);
                            if xx < 0 || yy < 0 || xx >= g as i32 || yy >= g as i32 {
                                continue;
                            }
                            let k = yy as usize * g + xx as usize;
                            s += s0[k];
                            w += w0[k];
                        }
                    }
                    sum[y * g + x] = s;
                    weight[y * g + x] = w;
                }
            }
        }
        let cells = sum
            .iter()
            .zip(&weight)
            .map(|(s, &w)| {
                if w > 0.0 {
                    *s / w
                } else {
                    Vec3::splat(f32::NAN)
                }
            })
            .collect();
        Self { n, cells }
    }

    /// The tone at texel (x, y), bilinear over the cells that have one (mid-gray where
    /// none near has).
    fn at(&self, x: usize, y: usize) -> Vec3 {
        let (g, n) = (TONE_GRID, self.n);
        let cell =
            |t: usize| ((t as f32 + 0.5) * g as f32 / n as f32 - 0.5).clamp(0.0, (g - 1) as f32);
        let (fx, fy) = (cell(x), cell(y));
        let (x0, y0) = (fx.floor() as usize, fy.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(g - 1), (y0 + 1).min(g - 1));
        let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
        let mut acc = Vec3::ZERO;
        let mut w = 0.0;
        for (cx, cy, cw) in [
            (x0, y0, (1.0 - tx) * (1.0 - ty)),
            (x1, y0, tx * (1.0 - ty)),
            (x0, y1, (1.0 - tx) * ty),
            (x1, y1, tx * ty),
        ] {
            let v = self.cells[cy * g + cx];
            if !v.x.is_nan() && cw > 0.0 {
                acc += v * cw;
                w += cw;
            }
        }
        if w > 0.0 { acc / w } else { Vec3::splat(0.5) }
    }
}

/// Bilinear linear-light colour of an sRGB picture at (u, v) (v up, u wrapping, v clamped).
fn sample_linear(img: &HeadImage, to_linear: &[f32], u: f32, v_down: f32) -> Vec3 {
    let (w, h) = (img.width_px as i64, img.height_px as i64);
    if w == 0 || h == 0 {
        return Vec3::splat(0.5);
    }
    let x = u * w as f32 - 0.5;
    let y = v_down * h as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |xi: i64, yi: i64| {
        let i = ((yi.clamp(0, h - 1) * w + xi.rem_euclid(w)) * 4) as usize;
        Vec3::new(
            to_linear[img.rgba[i] as usize],
            to_linear[img.rgba[i + 1] as usize],
            to_linear[img.rgba[i + 2] as usize],
        )
    };
    let (x0, y0) = (x0 as i64, y0 as i64);
    let top = at(x0, y0).lerp(at(x0 + 1, y0), fx);
    let bottom = at(x0, y0 + 1).lerp(at(x0 + 1, y0 + 1), fx);
    top.lerp(bottom, fy)
}

/// The base picture's alpha at texel (x, y) of an `n`² bake (nearest).
fn alpha_at(img: &HeadImage, x: usize, y: usize, n: usize) -> u8 {
    let (w, h) = (img.width_px as usize, img.height_px as usize);
    if w == 0 || h == 0 {
        return 255;
    }
    let (sx, sy) = ((x * w / n).min(w - 1), (y * h / n).min(h - 1));
    img.rgba[(sy * w + sx) * 4 + 3]
}

/// The point `t` (template metres) in brow-hair streak units: its place on the brow
/// ([`Regions::brow_coords`]) over [`BROW_STRAND_MM`].
fn brow_streak(regions: &Regions, t: Vec3) -> Vec3 {
    let b = regions.brow_coords(t);
    Vec3::new(b.x / BROW_STRAND_MM.0, b.y / BROW_STRAND_MM.1, 0.0)
}

/// Three octaves of [`value3`], in about [−1, 1].
fn fbm(p: Vec3, key: u32) -> f32 {
    (value3(p, key)
        + 0.5 * value3(p * 2.03 + Vec3::splat(17.1), key ^ 0x9e37)
        + 0.25 * value3(p * 4.1 + Vec3::splat(31.7), key ^ 0x7f4a))
        / 1.75
}

#[cfg(test)]
mod tests;
