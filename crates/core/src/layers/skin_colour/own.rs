//! The head's own colours, measured on its colour map (docs/models.md "Skin colour", "The
//! head's own colours"): its skin tone on the cheeks, its hair on the scalp and its brows,
//! each the median (per CIELAB channel) of the texels of its region, so that a stray
//! texel, a highlight or a seam does not move it. A region whose colour is no darker than
//! the skin has nothing painted on it (a scalp without hair, brows left for the hair
//! cards): no measure there.

use super::*;
use crate::base::lab::lab;

/// One measured colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measured {
    /// Linear sRGB.
    pub linear: Vec3,
    /// CIELAB (D65).
    pub lab: Vec3,
    /// How many texels it was measured on.
    pub texels: usize,
}

impl Measured {
    /// `"#rrggbb"`.
    pub fn hex(&self) -> String {
        let c = self
            .linear
            .to_array()
            .map(|c| (linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0).round() as u8);
        format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
    }
}

/// The head's own colours; `None` where the colour map has none to measure.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OwnColours {
    pub skin: Option<Measured>,
    pub hair: Option<Measured>,
    pub brows: Option<Measured>,
    /// The contrast of its brows and lips with its skin.
    pub contrast: FacialContrast,
}

/// The facial contrast of a colour map (Porcheron et al. 2013, 2017: it falls with age and
/// is a cue of it): the luminance contrast (L*skin − L*feature) / (L*skin + L*feature) of
/// the brows and the lips against the skin (the cheeks and nose), each the mean L* of its
/// region (CIELAB), as Porcheron et al. measured it. `None` where a region has too few texels.
/// (Not measured: the eyes, whose colours are not in the skin's map, and the lips'
/// redness, which the cheeks' own redness with age would confound.)
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FacialContrast {
    pub brows: Option<f32>,
    pub lips: Option<f32>,
}

/// The texels of the skin a colour is measured on: the cheeks and nose, away from the
/// brows, lips, under-eye and beard.
fn is_skin(f: &Fields) -> bool {
    f.red > 128 && f.brows == 0 && f.lips == 0 && f.under_eye < 64 && f.beard < 64
}

/// The facial contrast of `colour` (linear RGB of texel i, row by row) over `texels`'
/// regions: of the head's map, or of an aged colour of the same texels.
pub fn facial_contrast(texels: &SurfaceTexels, colour: &dyn Fn(usize) -> Vec3) -> FacialContrast {
    // The mean L* of a region's texels.
    let l_star = |pick: &dyn Fn(&Fields) -> bool| -> Option<f32> {
        let l: Vec<f32> = (0..texels.fields.len())
            .filter(|&i| texels.on_surface(i) && pick(&texels.fields[i]))
            .map(|i| lab(colour(i)).x)
            .collect();
        (l.len() >= MIN_TEXELS).then(|| l.iter().sum::<f32>() / l.len() as f32)
    };
    let Some(skin) = l_star(&is_skin) else {
        return FacialContrast::default();
    };
    let contrast = |f: f32| (skin + f > 1e-3).then(|| (skin - f) / (skin + f));
    FacialContrast {
        brows: l_star(&|f| f.brows > 150).and_then(contrast),
        lips: l_star(&|f| f.lips > 150).and_then(contrast),
    }
}

/// The fewest texels a region is measured on.
const MIN_TEXELS: usize = 40;
/// How much darker (L*) than the skin painted hair is, at least: a scalp or brow as light
/// as the skin has none painted.
const HAIR_DARKER_L: f32 = 10.0;
const BROWS_DARKER_L: f32 = 6.0;
/// Of the scalp's and the brows' texels, the darkest share is the hair (the rest is skin
/// between the hairs, a receding corner, the brow's edge).
const HAIR_SHARE: f32 = 0.5;
const BROWS_SHARE: f32 = 0.2;
/// The reddest (a*) and most saturated (C*ab) a measured hair colour may be: hair from
/// black to blond and auburn stays within these; a redder one is skin, a lid or a lip the
/// region caught, not hair.
const HAIR_MAX_A: f32 = 22.0;
const HAIR_MAX_CHROMA: f32 = 38.0;

/// Measures the head's own colours on `base` (the head's colour map as the aged colour
/// starts from it: [`BaseColour`], of a head with a map) over `texels`' regions;
/// `scalp(i)` says whether texel i grows hair at the young end (the hair's transition).
pub fn measure(
    base: &BaseColour,
    texels: &SurfaceTexels,
    scalp: &dyn Fn(usize) -> bool,
) -> OwnColours {
    let on = |i: usize| texels.on_surface(i);
    let labs = |pick: &dyn Fn(usize, &Fields) -> bool| -> Vec<(f32, usize)> {
        (0..texels.fields.len())
            .filter(|&i| on(i) && pick(i, &texels.fields[i]))
            .map(|i| (lab(base.colour[i]).x, i))
            .collect()
    };
    let skin = median(base, &labs(&|_, f| is_skin(f)), 1.0);
    let dark = |m: Option<Measured>, darker: f32| {
        m.filter(|m| skin.is_none_or(|s| s.lab.x - m.lab.x >= darker))
            .filter(|m| m.lab.y <= HAIR_MAX_A && m.lab.y.hypot(m.lab.z) <= HAIR_MAX_CHROMA)
    };
    let hair = dark(
        median(
            base,
            &labs(&|i, f| {
                scalp(i) && f.brows == 0 && f.red == 0 && f.lips == 0 && f.under_eye == 0
            }),
            HAIR_SHARE,
        ),
        HAIR_DARKER_L,
    );
    let brows = dark(
        median(base, &labs(&|_, f| f.brows > 150), BROWS_SHARE),
        BROWS_DARKER_L,
    );
    OwnColours {
        skin,
        hair,
        brows,
        contrast: facial_contrast(texels, &|i| base.colour[i]),
    }
}

/// The median colour (per CIELAB channel, back to linear through the texel nearest it) of
/// the darkest `share` of `texels` (L*, index); `None` under [`MIN_TEXELS`].
fn median(base: &BaseColour, texels: &[(f32, usize)], share: f32) -> Option<Measured> {
    let mut sorted = texels.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let n = ((sorted.len() as f32 * share).ceil() as usize).min(sorted.len());
    if n < MIN_TEXELS {
        return None;
    }
    let kept = &sorted[..n];
    let mid = |channel: fn(Vec3) -> f32| {
        let mut v: Vec<f32> = kept
            .iter()
            .map(|&(_, i)| channel(lab(base.colour[i])))
            .collect();
        v.sort_by(f32::total_cmp);
        v[v.len() / 2]
    };
    let target = Vec3::new(mid(|c| c.x), mid(|c| c.y), mid(|c| c.z));
    // The linear colour of the median: the mean of the texels within a few ΔE of it (a
    // Lab → linear inverse is not needed for a colour the map has).
    let near: Vec<Vec3> = kept
        .iter()
        .map(|&(_, i)| base.colour[i])
        .filter(|&c| lab(c).distance(target) < 6.0)
        .collect();
    let linear = if near.is_empty() {
        kept.iter().map(|&(_, i)| base.colour[i]).sum::<Vec3>() / n as f32
    } else {
        near.iter().sum::<Vec3>() / near.len() as f32
    };
    Some(Measured {
        linear,
        lab: lab(linear),
        texels: n,
    })
}
