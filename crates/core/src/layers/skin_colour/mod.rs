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

mod eyes;
mod own;
mod spots;
mod texels;
mod tone;

pub use eyes::*;
pub use own::*;
pub use spots::*;
pub use texels::*;
use tone::*;

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
use crate::maps::raster::raster_banded;

/// Smallest and largest age-spot diameter, mm (solar lentigines: docs/models.md
/// "Skin colour").
pub const SPOT_DIAMETER_MM: (f32, f32) = (2.0, 10.0);

/// A spot's size when it first shows, as a fraction of its final size.
const SPOT_FIRST_SIZE: f32 = 0.4;

/// How far (in the spot curve's factor) after it appears a spot reaches its full size.
const SPOT_GROWTH: f32 = 0.35;

/// How much melanin mottling darkens each channel at full strength.
const MOTTLE_TINT: [f32; 3] = [0.30, 0.40, 0.50];

/// Pigment specks: hyperpigmented flecks of about this size, mm, over the mottling, each
/// darkening by up to [`SPECK_TINT`] (uneven tone at the finest scale: mottled
/// hyperpigmentation of photo-aged skin).
const SPECK_MM: f32 = 1.3;
const SPECK_TINT: [f32; 3] = [0.6, 0.75, 0.9];
const SPECK_TINT_DARK: [f32; 3] = [0.7, 0.72, 0.74];

/// How much more dark skin mottles: uneven pigmentation is the first sign of age on it,
/// before wrinkles (Vashi et al. 2016).
const MOTTLE_ON_DARK: f32 = 1.0;

/// Feature sizes of the mottling, mm: blotches and a finer grain.
const MOTTLE_MM: (f32, f32) = (9.0, 2.6);

/// How far a gray stubble hair's texel goes toward a light gray (the bare skin's, lighter),
/// and how far every beard texel goes toward the bare skin when all the hair is gray.
const BEARD_GRAY: f32 = 0.8;
/// See [`BEARD_GRAY`].
const BEARD_LIFT: f32 = 0.65;
/// A stubble hair's draw of the salt and pepper is one value-noise cell this size, mm (a
/// hair and the skin round it).
const STUBBLE_MM: f32 = 0.5;
/// A gray stubble texel: this much lighter than the bare skin round the beard.
const STUBBLE_GRAY_LIGHT: f32 = 1.18;
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

/// Linear luminance of the skin round a texel below which it counts as dark (fully dark
/// at the first: the panel's dark heads are about 0.07; light skin 0.35–0.5).
const DARK_SKIN_LUM: (f32, f32) = (0.08, 0.2);
/// How much saturation dark skin loses at full paling (ashier, not yellower), and how much
/// less its redness shows.
const ASHY: f32 = 0.2;
const DARK_SKIN_REDNESS: f32 = 0.6;

/// The yellowing's tint per unit (green and blue lowered, red kept).
const YELLOW_TINT: [f32; 3] = [0.0, 0.06, 0.22];

/// How much of the contrast loss reaches the brows (on light skin, on dark skin by
/// [`DARK_SKIN_LUM`]) and the lips (brows keep more: they thin and gray more than they
/// fade). On dark skin the brows' texels go no lighter than a little over the skin
/// ([`BROW_GRAY_OVER_SKIN`]), so the painted brow fades more toward the skin instead.
const CONTRAST_BROWS: (f32, f32) = (0.2, 0.65);
const CONTRAST_LIPS: f32 = 0.6;
/// The lips' colour on a head without a colour map, times the skin's (linear): darker and
/// redder, as the vermilion is (about 10 darker in L* and 10 redder in a* than the cheek:
/// Porcheron et al. 2013). Without it the untextured heads' lips were the skin's colour,
/// read blind as "a lipless slit", "lips that have vanished" (rounds 21–23), and their
/// fading with age (below) had nothing to fade.
const LIP_TONE: [f32; 3] = [0.8, 0.58, 0.6];

/// How much more than the rest of the lips their outer part (`Regions::lip_rim`) fades.
const LIP_THINNING: f32 = 0.9;

/// Brightness of gray brow hair relative to the hair's gray colour: coarse white brow
/// hair over the skin reads lighter than the silver of the scalp's (at the scalp's
/// brightness the brows read, blind, as "gray putty").
const BROW_GRAY_BRIGHTNESS: f32 = 1.0;

/// How far a brow texel's hair goes toward the gray at its full gray (0.75 read, blind, as
/// "white paint blobs" on dark skin).
const BROW_TEXEL_GRAY: f32 = 0.6;

/// How much of the skin's colour round a gray brow texel is in its gray (the skin shows
/// between the gray hairs): on light skin, and on dark skin (by [`DARK_SKIN_LUM`]).
const BROW_GRAY_SKIN_HUE: (f32, f32) = (0.3, 0.8);

/// The lightest a gray brow texel gets, in luminance over the skin around it: on light
/// skin, and on dark skin (by [`DARK_SKIN_LUM`]). At 2.2 on the dark heads, the painted
/// brows' texels and the darker skin in the brows' region above them went a pale gray
/// under the gray brow strands, read blind as "gray patches above the brows", "white paint
/// splotches" (rounds 40–44, the African man's cue 11 at 1).
const BROW_GRAY_OVER_SKIN: (f32, f32) = (2.2, 1.35);

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
/// Its defaults are the project's (`Project::default().colour_settings()`): one copy.
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

/// The hair painted on a head's colour map (a game head's scalp): it goes where the hair
/// goes and grays with it, so an old head's bald crown is skin, not the young hair's paint
/// (docs/models.md "Skin colour", "Painted hair").
#[derive(Clone, Copy, Debug)]
pub struct PaintedHair<'a> {
    /// Per texel: the hair's disappearance age in the male pattern as
    /// [`crate::layers::hair::scalp::hair_age_alpha`] writes it (0: no hair there, else
    /// 1 + 254·a), whatever the pattern: where the male pattern's hair goes is the crown that
    /// the female pattern thins most.
    pub ages: &'a [u8],
    /// The age t.
    pub t: f32,
    /// The bare scalp's colour (linear): the head's skin tone.
    pub bald: Vec3,
    /// The painted hair's colour (linear), measured: a texel's share of hair is how far it
    /// is from the bald colour toward it.
    pub hair: Vec3,
    /// The share of the hairs thinning has taken at this age (docs/models.md §9
    /// "Thinning") over the crown (where the male pattern recedes) and elsewhere.
    pub thinned: [f32; 2],
    /// Whether the pattern keeps the hairline (female, none): then the paint over the
    /// crown thins by its share instead of going where the male pattern's hair goes (it
    /// went, and the women's crowns showed a hard-edged bald oval under a full head of
    /// hair).
    pub keeps_hairline: bool,
}

impl PaintedHair<'_> {
    /// [`PaintedHair::thinned`] at age `t` for `thinning` (`hair.thinning`) and its shares
    /// over the crown and elsewhere (`hair::FEMALE_THINNING` in the female pattern, else 1).
    pub fn thinned_at(t: f32, thinning: f32, shares: (f32, f32)) -> [f32; 2] {
        use crate::layers::hair::THINNING_FROM;
        let ramp = ((t - THINNING_FROM) / (1.0 - THINNING_FROM)).clamp(0.0, 1.0);
        [shares.0, shares.1].map(|share| (thinning * share).clamp(0.0, 1.0) * ramp)
    }
}

/// How much of the painted hair's gray a fully gray head shows (the skin between the
/// hairs keeps some of the rest, and the strands drawn over it carry the white: at 0.7 the
/// African man's fringe read, blind, as "a flat pure-white block over a painted white
/// base with a hard top edge").
const PAINTED_GRAY: f32 = 0.35;

/// Over how much of the hair's age (t) painted hair fades to skin where the hair goes:
/// its edge follows the ragged fringe softly.
const PAINTED_EDGE: f32 = 0.08;

/// Over how much of the male pattern's age (t) below 1 the crown's paint thins from the
/// sides' share to the crown's, in the patterns that keep the hairline.
const PAINTED_CROWN_EDGE: f32 = 0.2;

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
                // Without a map the lips take the lip tone over the skin's.
                None => Vec3::from(albedo).lerp(
                    Vec3::from(albedo) * Vec3::from(LIP_TONE),
                    from_unit(texels.fields[y * n + x].lips),
                ),
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
        let tone = local_tone(n, texels, &base_at);
        let bare = bare_tone(n, texels, &base_at);
        Self {
            size: texels.size,
            colour,
            alpha,
            tone,
            bare,
        }
    }
}

/// How much drier old skin is (docs/models.md "Skin colour", "Sheen"): at full paling
/// (`age.pale`) its specular reflectance is this much lower and its roughness this much
/// higher. Sebum falls with age (Pochi et al. 1979), and an old face has less sheen; at
/// full sheen the cheek's crest over the nasolabial fold read, blind, on the dark-skinned
/// heads as "a wet white streak", their skin as "glossy plastic".
pub const DRY_SPECULAR: f32 = 0.45;
pub const DRY_ROUGHNESS: f32 = 0.15;

/// The skin's (roughness, specular) at paling factor `pale` (0 young, 1 old): the
/// project's at 0, drier with age ([`DRY_SPECULAR`], [`DRY_ROUGHNESS`]).
pub fn aged_sheen(roughness: f32, specular: f32, pale: f32) -> (f32, f32) {
    let f = pale.clamp(0.0, 1.0);
    (
        (roughness + DRY_ROUGHNESS * f).min(1.0),
        specular * (1.0 - DRY_SPECULAR * f),
    )
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
    bake_from(&base, texels, spots, settings, factors, None, cancel)
}

/// The aged colour from a kept [`BaseColour`] of the same texels: what an age change
/// re-does (the regions and noise of the texels, the base and its tone stay). `painted`:
/// the hair painted on the map, which goes and grays with the hair.
pub fn bake_from(
    base: &BaseColour,
    texels: &SurfaceTexels,
    spots: &[Spot],
    settings: &ColourSettings,
    factors: &ColourFactors,
    painted: Option<&PaintedHair>,
    cancel: &CancelToken,
) -> Result<HeadImage, Error> {
    let painted = painted.filter(|p| p.ages.len() == (texels.size as usize).pow(2));
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
                    if let Some(h) = painted {
                        c = h.age(c, h.ages[i], factors.brow_gray, look.gray);
                    }
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
///
/// Only skin grows hair: with `skin` (the texels `image` was baked on), texels no skin
/// triangle covers (a head's eyes, mapped onto its skin's map) get 0.
pub fn with_alpha(
    image: &HeadImage,
    alpha: Option<&[u8]>,
    skin: Option<&SurfaceTexels>,
) -> HeadImage {
    let mut shown = image.clone();
    let skin = skin.filter(|t| t.position.len() * 4 == shown.rgba.len());
    match alpha.filter(|a| a.len() * 4 == shown.rgba.len()) {
        Some(alpha) => shown
            .rgba
            .par_chunks_mut(4 * 4096)
            .zip(alpha.par_chunks(4096))
            .enumerate()
            .for_each(|(chunk, (px, a))| {
                for (k, (p, &a)) in px.chunks_exact_mut(4).zip(a).enumerate() {
                    let covered = skin.is_none_or(|t| t.covers_skin(chunk * 4096 + k));
                    p[3] = if covered { a } else { 0 };
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

impl PaintedHair<'_> {
    /// A texel of colour `c` whose hair goes at `age` (the alpha's byte): where the hair has
    /// gone its paint becomes the bald scalp's colour, where it stays it grays by
    /// `gray` (the hair's mean gray fraction) toward `gray_colour`.
    fn age(&self, c: Vec3, age: u8, gray: f32, gray_colour: Vec3) -> Vec3 {
        if age == 0 {
            return c;
        }
        let lum = |c: Vec3| c.dot(Vec3::new(0.2126, 0.7152, 0.0722));
        let span = lum(self.bald) - lum(self.hair);
        if span <= 1e-4 {
            return c;
        }
        // Skin a little darker than the measured tone is skin, not paint: the first
        // [`PAINTED_SKIN_SHARE`] of the way to the hair's lightness counts for nothing
        // (counted, the forehead's darker skin under a woman's kept hairline, where the
        // masks' hair reaches at t = 0, paled toward the measured tone as her paint
        // thinned: "a pale band like the edge of a bald cap", blind, round 69).
        let share =
            ((lum(self.bald) - lum(c)) / span - PAINTED_SKIN_SHARE) / (1.0 - PAINTED_SKIN_SHARE);
        let share = share.clamp(0.0, 1.0);
        let a = f32::from(age - 1) / 254.0;
        let receded = if a >= 1.0 {
            0.0
        } else {
            smoothstep(a - PAINTED_EDGE, a + PAINTED_EDGE, self.t)
        };
        let [crown, rest] = self.thinned;
        let kept = crate::layers::hair::KEPT_HAIRLINE_T;
        let gone = if self.keeps_hairline {
            if a < kept {
                // Below the kept hairline no strand grows at any age: the paint stays.
                return c;
            }
            // The crown (the male pattern's receding hair, its age blurred over its edge)
            // thins most, the rest as the sides; the paint along the kept hairline as the
            // crown (kept as the sides, its remaining paint grayed into a pale band between
            // the strands and the forehead, read blind as "the edge of a bald cap").
            // (Read on the kept pattern's alpha, which is 255 over the whole crown, the
            // women's painted crowns thinned as their sides: a full painted cap under
            // their thinned strands at 80.)
            let w = ((1.0 - a) / PAINTED_CROWN_EDGE).clamp(0.0, 1.0);
            rest + (crown - rest) * w
        } else {
            receded.max(rest)
        };
        let c = c.lerp(self.bald, share * gone);
        c.lerp(gray_colour, share * (1.0 - gone) * gray * PAINTED_GRAY)
    }
}

/// See [`PaintedHair::age`]: how far toward the hair's lightness a texel may be and still
/// count as skin.
const PAINTED_SKIN_SHARE: f32 = 0.3;

/// What ages every texel alike at one age: the settings, the factors and the tints made
/// from them, the spots that show.
/// A figure given for light skin and for dark skin (`(light, dark)`), between them by the
/// skin's darkness round the texel (`dark`, 0–1, by [`DARK_SKIN_LUM`]).
fn on_skin((light, dark_skin): (f32, f32), dark: f32) -> f32 {
    light + (dark_skin - light) * dark
}

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
        let dark = 1.0 - smoothstep(DARK_SKIN_LUM.0, DARK_SKIN_LUM.1, lum(reference));
        let fade_brows = on_skin(CONTRAST_BROWS, dark);
        let fade = s.contrast_loss * a.contrast * (fade_brows * brows).max(lips);
        c = c.lerp(reference, fade.clamp(0.0, 1.0));
        // The stubble grays with the hair: gray stubble on pale skin casts no shadow, so
        // the beard's texels go toward the bare skin round the beard, its darker texels
        // most: no "moustache" shadow at 80, and no grey jaw over a pink neck (toward the
        // beard's own tone, which the dark stubble pulls down and grays, the jaw read,
        // blind, as "a colour seam" where it met the neck).
        // Hair by hair (salt and pepper, docs/models.md "Skin colour"): a stubble texel
        // whose draw is under the gray fraction turns a gray a little lighter than the
        // bare skin, the others keep their dark, so the beard shadow grays and keeps its
        // grain instead of vanishing (the old beard evened out to bare skin made the aged
        // map *less* uneven than the young one).
        let beard = from_unit(f.beard);
        if beard > 0.0 && a.brow_gray > 0.0 {
            let dark = smoothstep(0.0, 0.25, 1.0 - lum(c) / lum(reference).max(1e-4));
            let draw = 0.5
                + 0.5
                    * (2.2 * value3(p * (1000.0 / STUBBLE_MM), self.spot_key ^ 0x9e37_79b9))
                        .clamp(-1.0, 1.0);
            let gray_hair = smoothstep(-0.08, 0.08, a.brow_gray - draw);
            let lift = beard * a.brow_gray * BEARD_LIFT * (1.0 - dark);
            c = c.lerp(bare, lift.clamp(0.0, 1.0));
            let whiten = beard * dark * gray_hair * BEARD_GRAY;
            c = c.lerp(bare * STUBBLE_GRAY_LIGHT, whiten.clamp(0.0, 1.0));
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
        // Paling and yellowing: a tint, so what is darker stays darker. On dark skin
        // (by the skin tone round the texel) old skin goes duller and ashier rather than
        // yellow: the yellowing fades out and the colour loses some saturation (yellowed,
        // it read, blind, as "the same saturated, glossy orange").
        c *= self.pale_tint * Vec3::ONE.lerp(self.yellow, 1.0 - dark);
        if dark > 0.0 {
            c = c.lerp(Vec3::splat(lum(c)), ASHY * dark * a.pale.min(1.0));
        }
        // The brows gray with the hair, hair by hair: a texel's hair is gray when its draw
        // (value noise in streaks along the hairs, [`BROW_STRAND_MM`]) is under the gray
        // fraction: salt and pepper. The skin shows a little between the hairs.
        if hair > 0.0 && a.brow_gray > 0.0 {
            // Value noise gathers near 0: spread to about even over [0, 1], so the gray
            // fraction is the share of gray hair.
            let draw = 0.5 + 0.5 * (2.2 * from_signed(f.brow_draw)).clamp(-1.0, 1.0);
            let gray_hair = smoothstep(-0.08, 0.08, a.brow_gray_fraction() - draw);
            // Toward a gray between the hair's and the skin's (the skin shows between
            // the gray hairs; the strands drawn over the brows carry the white): fully
            // white texels read, blind, as "white paint" on dark skin.
            // And no lighter than BROW_GRAY_OVER_SKIN × the skin around: on dark skin
            // the texels go to a light gray-brown, and the strands drawn over them carry
            // the white.
            // On dark skin, of the skin's hue more than the gray's (the gray's blue-gray
            // over dark skin read blind as "a blue-grey smear above the brow", round 45).
            let skin_share = on_skin(BROW_GRAY_SKIN_HUE, dark);
            let target = self.gray.lerp(reference, skin_share) * (0.75 + 0.25 * draw);
            let most = on_skin(BROW_GRAY_OVER_SKIN, dark) * lum(reference);
            let target = target * (most / lum(target).max(1e-4)).min(1.0);
            c = c.lerp(target, (BROW_TEXEL_GRAY * hair * gray_hair).clamp(0.0, 1.0));
        }
        // Every skin mottles some; sun-exposed skin most. Darker blotches and lighter skin
        // between, about even on average, so no region's mean tone shifts (no edge where
        // the exposure falls off).
        // Dark skin mottles more at the fine scale (the grain and the specks; its broad
        // blotches, as strong, read as a skin disease).
        let m = s.mottle * a.mottle * (0.35 + 0.65 * sun);
        if m > 0.0 {
            let fine = m * (1.0 + MOTTLE_ON_DARK * dark);
            let (blotch, grain) = (from_signed(f.blotch), from_signed(f.grain));
            let d = (smoothstep(-0.3, 0.6, blotch) - 0.45) * m
                + 0.4 * (smoothstep(-0.2, 0.7, grain) - 0.4) * fine;
            c *= Vec3::ONE - Vec3::from(MOTTLE_TINT) * d;
            // Pigment specks, on the exposed skin, gathered in the darker blotches (value
            // noise's peaks; spread evenly they read as grit).
            let speck = fine
                * sun
                * smoothstep(0.0, 0.5, blotch)
                * smoothstep(0.2, 0.5, from_signed(f.speck));
            // On dark skin a neutral dark brown (melanin over melanin; the light skin's
            // tint drew rust-red flecks there).
            let tint = Vec3::from(SPECK_TINT).lerp(Vec3::from(SPECK_TINT_DARK), dark);
            c *= Vec3::ONE - tint * speck;
        }
        // Redness and thread veins on the cheeks and the nose.
        // Redness shows far less through melanin.
        let r = s.redness * a.redness * red * (1.0 - DARK_SKIN_REDNESS * dark);
        if r > 0.0 {
            let flush = r * (0.55 + 0.45 * from_signed(f.flush));
            let veins = r * (1.0 - from_signed(f.vein).abs()).powi(14);
            c *= Vec3::new(
                1.0 + 0.06 * flush,
                1.0 - 0.3 * flush - 0.4 * veins,
                1.0 - 0.22 * flush - 0.34 * veins,
            );
        }
        // Age spots, each kind with its tint: lentigines show less on dark skin, the
        // dark papules only there.
        let spots = self.grid.darkness(p, self.spot_key);
        for (k, kind) in SPOT_KINDS.iter().enumerate() {
            let shows = on_skin(kind.shows, dark);
            let spot = spots[k] * shows * s.spot_strength;
            if spot > 0.0 {
                c *= Vec3::ONE - Vec3::from(kind.tint) * spot.min(1.0);
            }
        }
        c
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
