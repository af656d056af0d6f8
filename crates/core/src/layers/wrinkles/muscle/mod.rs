//! Large wrinkles: the muscle-fibre model (docs/models.md §2, [T] §5.1).
//!
//! A wrinkle group ("fibre") is a segment mA → mB in UV space. Wrinkles run across it,
//! `n` of them along its length, fading out over a capsule of half-width `W·L` around it.
//! [`Fibre::height_at`] evaluates one fibre at a UV point; [`rasterize`] sums all fibres
//! into a [`HeightMap`], normalises by the maximum, applies γ and an optional mask.

use std::f32::consts::{FRAC_PI_2, PI};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::base::error::Error;
use crate::maps::heightmap::{HeightMap, pixel_to_u, pixel_to_v};
use crate::maps::mask::Mask;

pub use super::fibre_params::{
    DEFAULT_DEPTH, DEFAULT_MAX_ANGLE, DEFAULT_OMEGA_LOW, DEFAULT_REL_WIDTH, RangeError,
    check_count, check_point,
};
use super::fibre_params::{DEPTH, IRREGULARITY, MAX_ANGLE, OMEGA_LOW, REL_WIDTH, WAVINESS};

/// Default crest-flattening exponent γ (docs/models.md §2 "Blending").
pub const DEFAULT_GAMMA: f32 = 0.4;

/// Valid range of γ. γ < 1 flattens crests, γ > 1 sharpens them.
pub const GAMMA_RANGE: (f32, f32) = (0.01, 10.0);

/// The cross-section of the wrinkles along a fibre (docs/models.md §2 "Alternative cross-section
/// profiles"). Every profile is a function of the phase x = n·ω(d)·t with period 1, equal
/// to 0 at integer x (between wrinkles) and 1 at half-integer x (the bottom of the
/// wrinkle: the layer is a depth, cut into the skin). `fold` alone goes below 0: its raised
/// side.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Profile {
    /// |sin(πx)| — [T] 5.3, the default: rounded crests, sharp creases between them.
    #[default]
    AbsSin,
    /// 0.5 + 0.5·sin(π(2x − 0.5)) — [T] 5.2: smooth crests and creases.
    Sin,
    /// exp(−x'²/2σ²) with x' = frac(x) − 0.5 and σ = 1/6 — [P] eq. 2 applied per wrinkle
    /// (**Choice**: σ so that the crest reaches ≈ 0.011 at the wrinkle's edge).
    Gauss,
    /// 1 − x'²/ω² with x' = frac(x) − 0.5 and ω = 0.5 — [P] eq. 16 applied per wrinkle.
    Parabola,
    /// (1 − |x'|/w)² for |x'| < w, w = [`CREASE_HALF_WIDTH`], else 0: a narrow crease with a
    /// sharp bottom and soft shoulders in flat skin (how skin folds at a line; the shipped
    /// forehead, glabella, crow's feet, lip and neck lines).
    Crease,
    /// A crease with one side raised over it: [`Profile::Crease`] minus a hump of height
    /// [`FOLD_RAISE`] on the side toward mA (x' < 0), so the crease's wall there is steep
    /// and high and the other side falls gently (the nasolabial and marionette folds: the
    /// cheek over the crease, docs/models.md §2 "Folds").
    Fold,
}

/// Half-width of a [`Profile::Crease`], in periods: the crease takes 2 × 0.15 of the spacing
/// between wrinkles and flat skin the rest.
pub const CREASE_HALF_WIDTH: f32 = 0.15;

/// Height of a [`Profile::Fold`]'s raised side, relative to its crease's depth (0.3 read,
/// blind, as "a faint shading line, no cheek over it").
pub const FOLD_RAISE: f32 = 0.45;

/// Half-width of a [`Profile::Fold`]'s crease, in periods (wider than a line's: a fold is
/// a valley under the cheek, not a line).
pub const FOLD_HALF_WIDTH: f32 = 0.22;

impl Profile {
    /// All profiles, in the order the wrinkle file documents them.
    pub const ALL: [Profile; 6] = [
        Profile::AbsSin,
        Profile::Sin,
        Profile::Gauss,
        Profile::Parabola,
        Profile::Crease,
        Profile::Fold,
    ];

    /// The name used in wrinkle files (`profile=abs_sin`).
    pub fn name(self) -> &'static str {
        match self {
            Profile::AbsSin => "abs_sin",
            Profile::Sin => "sin",
            Profile::Gauss => "gauss",
            Profile::Parabola => "parabola",
            Profile::Crease => "crease",
            Profile::Fold => "fold",
        }
    }

    /// Parses a wrinkle-file name, case-insensitively.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(name))
    }

    /// The profile at phase `x` (any real; period 1), in [0, 1] (`fold`: [−FOLD_RAISE, 1]).
    #[inline]
    pub fn eval(self, x: f32) -> f32 {
        match self {
            Profile::AbsSin => (PI * x).sin().abs(),
            Profile::Sin => 0.5 + 0.5 * (PI * (2.0 * x - 0.5)).sin(),
            Profile::Gauss => {
                let xc = x - x.floor() - 0.5;
                const SIGMA: f32 = 1.0 / 6.0;
                (-(xc * xc) / (2.0 * SIGMA * SIGMA)).exp()
            }
            Profile::Parabola => {
                let xc = x - x.floor() - 0.5;
                (1.0 - xc * xc / 0.25).max(0.0)
            }
            Profile::Crease => crease(x - x.floor() - 0.5),
            Profile::Fold => {
                let xc = x - x.floor() - 0.5;
                // The raised side: rising from nothing at the crease's centre to its top at
                // the crease's edge, then falling slowly to the period's end (a shelf
                // that overhangs the crease, not a ridge beside it).
                let s = -xc;
                let wall = if xc < 0.0 {
                    smoothstep((s / FOLD_HALF_WIDTH).min(1.0))
                        * (1.0
                            - smoothstep(
                                ((s - FOLD_HALF_WIDTH) / (0.5 - FOLD_HALF_WIDTH)).clamp(0.0, 1.0),
                            ))
                } else {
                    0.0
                };
                crease_of_width(xc, FOLD_HALF_WIDTH) - FOLD_RAISE * wall
            }
        }
    }
}

/// The crease (1 − |x'|/w)² of [`Profile::Crease`] at the offset `xc` from its centre.
#[inline]
fn crease(xc: f32) -> f32 {
    crease_of_width(xc, CREASE_HALF_WIDTH)
}

/// (1 − |x'|/w)² for |x'| < w, else 0.
#[inline]
fn crease_of_width(xc: f32, w: f32) -> f32 {
    let s = xc.abs() / w;
    if s < 1.0 { (1.0 - s) * (1.0 - s) } else { 0.0 }
}

/// A hash of `key` to [0, 1).
#[inline]
fn hash01(key: u32) -> f32 {
    (crate::base::rng::mix64(u64::from(key)) >> 40) as f32 / (1u64 << 24) as f32
}

/// Smooth 1D value noise in [0, 1]: hashed values at the integers of `x`, joined by
/// smoothstep; one stream per `key`.
#[inline]
fn value_noise(x: f32, key: u32) -> f32 {
    let i = x.floor();
    let f = x - i;
    let at = |j: f32| {
        hash01(key.wrapping_mul(0x85EB_CA6B) ^ (j as i32 as u32).wrapping_mul(0xC2B2_AE35))
    };
    at(i) + (at(i + 1.0) - at(i)) * smoothstep(f)
}

/// The smoothstep S(x) = 3x² − 2x³ ([T] 5.7), for x in [0,1]: `base::math::smooth01`.
use crate::base::math::smooth01 as smoothstep;

/// The radial attenuation At(d) = 1 − min(d/(W·L), 1) ([T] 5.5). `half_width` is W·L.
#[inline]
pub fn attenuation(d: f32, half_width: f32) -> f32 {
    1.0 - (d / half_width).min(1.0)
}

/// The relative frequency ω(d) = fmin + (1 − fmin)·S(At(d)) ([T] 5.6).
#[inline]
pub fn relative_frequency(at: f32, omega_low: f32) -> f32 {
    omega_low + (1.0 - omega_low) * smoothstep(at)
}

/// The end-angle attenuation Aα (docs/models.md §2). `alpha` is the angle, in radians, between the
/// direction pointing back into the fibre and the vector from the end to the point
/// (π/2 ≤ α ≤ π beyond an end); `max_angle` is αmax in units of π/2, in [1, 2].
/// With αmax = 1 nothing passes the ends (Aα = 0 for every α > π/2).
#[inline]
pub fn angle_attenuation(alpha: f32, max_angle: f32) -> f32 {
    let over = (alpha - FRAC_PI_2).max(0.0);
    let span = max_angle * FRAC_PI_2 - FRAC_PI_2;
    if span <= 0.0 {
        return if over > 0.0 { 0.0 } else { 1.0 };
    }
    1.0 - (over / span).min(1.0)
}

/// A validated muscle fibre (one wrinkle group of a wrinkle file).
#[derive(Clone, Debug, PartialEq)]
pub struct Fibre {
    ma: [f32; 2],
    mb: [f32; 2],
    n: u32,
    rel_width: f32,
    max_angle: f32,
    omega_low: f32,
    profile: Profile,
    depth: f32,
    /// Irregularity in [0, 1] (docs/models.md §2 "Irregularity"): 0 = [T]'s regular wrinkles.
    irregularity: f32,
    /// Waviness, in periods of the wrinkle spacing, [0, 0.5].
    waviness: f32,
    /// Seed of the irregularity and waviness.
    seed: u32,
    /// Whether the group is straight in UV or on the surface (docs/models.md §3 `space`).
    space: Space,
    /// The warp that lays a `Space::Surface` group on the head's surface, attached by the
    /// scene for the layout the layer is baked in; `None`: evaluated in UV.
    warp: Option<std::sync::Arc<crate::layers::wrinkles::surface_warp::SurfaceWarp>>,
}

/// Where a wrinkle group is straight (docs/models.md §3 `space`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Space {
    /// Straight in the UV layout ([T]'s model).
    #[default]
    Uv,
    /// Straight on the head's surface: its tangent plane, mapped to UV by the affine map
    /// that best fits the layout over the group ([`crate::layers::wrinkles::surface_warp`]).
    Surface,
}

impl Space {
    pub const ALL: [Space; 2] = [Space::Uv, Space::Surface];

    /// The wrinkle file's value.
    pub fn name(self) -> &'static str {
        match self {
            Space::Uv => "uv",
            Space::Surface => "surface",
        }
    }
}

/// Irregularity's share that varies the depth *between* the wrinkles of a group; the rest
/// varies it along each wrinkle.
const BETWEEN_SHARE: f32 = 0.5;

/// Correlation length of the variation along a wrinkle, relative to the fibre's influence
/// half-width W·L: a few swells along one wrinkle.
const ALONG_SCALE: f32 = 0.35;

impl Fibre {
    /// A fibre from `ma` to `mb` with `n` wrinkles and the docs/models.md §2 defaults.
    /// Fails when a point is not finite, `n` is outside 1..=1000 or `ma == mb`.
    pub fn new(ma: [f32; 2], mb: [f32; 2], n: u32) -> Result<Self, Error> {
        let invalid = |what: &str, value: String, e: RangeError| Error::InvalidValue {
            what: what.into(),
            value,
            expected: e.expected,
        };
        check_point(ma).map_err(|e| invalid("ma", format!("{ma:?}"), e))?;
        check_point(mb).map_err(|e| invalid("mb", format!("{mb:?}"), e))?;
        check_count(n as i64).map_err(|e| invalid("n", n.to_string(), e))?;
        if ma == mb {
            return Err(Error::InvalidValue {
                what: "mb".into(),
                value: format!("{};{}", mb[0], mb[1]),
                expected: "a point different from ma".into(),
            });
        }
        Ok(Self {
            ma,
            mb,
            n,
            rel_width: DEFAULT_REL_WIDTH,
            max_angle: DEFAULT_MAX_ANGLE,
            omega_low: DEFAULT_OMEGA_LOW,
            profile: Profile::AbsSin,
            depth: DEFAULT_DEPTH,
            irregularity: 0.0,
            waviness: 0.0,
            seed: 0,
            space: Space::Uv,
            warp: None,
        })
    }

    /// Sets where the group is straight: in UV or on the surface.
    pub fn with_space(mut self, space: Space) -> Self {
        self.space = space;
        self
    }

    /// Attaches (or removes) the warp that lays the group on a head's surface; only a
    /// `Space::Surface` group takes one.
    pub fn with_warp(
        mut self,
        warp: Option<std::sync::Arc<crate::layers::wrinkles::surface_warp::SurfaceWarp>>,
    ) -> Self {
        self.warp = warp.filter(|_| self.space == Space::Surface);
        self
    }

    /// Sets the irregularity in [0, 1]: each wrinkle's depth varies along it and between
    /// the wrinkles of the group by up to this fraction (docs/models.md §2).
    pub fn with_irregularity(mut self, a: f32) -> Result<Self, Error> {
        self.irregularity = IRREGULARITY
            .check(a)
            .map_err(|e| range_err("irregularity", a, e))?;
        Ok(self)
    }

    /// Sets the waviness: each wrinkle line wanders across by up to this many periods of
    /// the wrinkle spacing, in [0, 0.5].
    pub fn with_waviness(mut self, w: f32) -> Result<Self, Error> {
        self.waviness = WAVINESS.check(w).map_err(|e| range_err("waviness", w, e))?;
        Ok(self)
    }

    /// Sets the seed of the irregularity and waviness.
    pub fn with_seed(mut self, seed: u32) -> Self {
        self.seed = seed;
        self
    }

    /// Sets W, the half-width relative to the fibre length, in [1e-6, 10].
    pub fn with_rel_width(mut self, w: f32) -> Result<Self, Error> {
        self.rel_width = REL_WIDTH
            .check(w)
            .map_err(|e| range_err("relWidth", w, e))?;
        Ok(self)
    }

    /// Sets αmax in units of π/2, in [1, 2].
    pub fn with_max_angle(mut self, a: f32) -> Result<Self, Error> {
        self.max_angle = MAX_ANGLE
            .check(a)
            .map_err(|e| range_err("maxAngle", a, e))?;
        Ok(self)
    }

    /// Sets fmin, the relative frequency at the edge of the influence area, in [0, 1].
    pub fn with_omega_low(mut self, f: f32) -> Result<Self, Error> {
        self.omega_low = OMEGA_LOW
            .check(f)
            .map_err(|e| range_err("omegaLow", f, e))?;
        Ok(self)
    }

    /// Sets the per-fibre amplitude A, in [0, 100] (relative: the layer is normalised).
    pub fn with_depth(mut self, a: f32) -> Result<Self, Error> {
        self.depth = DEPTH.check(a).map_err(|e| range_err("depth", a, e))?;
        Ok(self)
    }

    /// Sets the cross-section profile.
    pub fn with_profile(mut self, profile: Profile) -> Self {
        self.profile = profile;
        self
    }

    /// The same fibre with new end points (every other parameter kept), e.g. dragged in
    /// the editor. Fails like [`Fibre::new`] (equal or non-finite points).
    pub fn with_ends(&self, ma: [f32; 2], mb: [f32; 2]) -> Result<Self, Error> {
        Fibre::new(ma, mb, self.n).map(|f| Self {
            ma: f.ma,
            mb: f.mb,
            warp: None,
            ..self.clone()
        })
    }

    /// The same fibre with a new wrinkle count n (1..=1000).
    pub fn with_n(&self, n: u32) -> Result<Self, Error> {
        Fibre::new(self.ma, self.mb, n).map(|f| Self {
            n: f.n,
            ..self.clone()
        })
    }

    pub fn ma(&self) -> [f32; 2] {
        self.ma
    }
    pub fn mb(&self) -> [f32; 2] {
        self.mb
    }
    /// Number of wrinkles along the fibre (ω0 of [T]).
    pub fn n(&self) -> u32 {
        self.n
    }
    pub fn rel_width(&self) -> f32 {
        self.rel_width
    }
    pub fn max_angle(&self) -> f32 {
        self.max_angle
    }
    pub fn omega_low(&self) -> f32 {
        self.omega_low
    }
    pub fn profile(&self) -> Profile {
        self.profile
    }
    pub fn depth(&self) -> f32 {
        self.depth
    }
    pub fn irregularity(&self) -> f32 {
        self.irregularity
    }
    pub fn waviness(&self) -> f32 {
        self.waviness
    }
    pub fn seed(&self) -> u32 {
        self.seed
    }
    pub fn space(&self) -> Space {
        self.space
    }
    pub fn warp(&self) -> Option<&crate::layers::wrinkles::surface_warp::SurfaceWarp> {
        self.warp.as_deref()
    }

    /// Length L = ‖mB − mA‖ in UV units.
    pub fn length_uv(&self) -> f32 {
        let (dx, dy) = (self.mb[0] - self.ma[0], self.mb[1] - self.ma[1]);
        (dx * dx + dy * dy).sqrt()
    }

    /// The UV rectangle `[u0, v0, u1, v1]` outside which the fibre is exactly 0: the
    /// bounding box of the capsule of radius W·L around the segment, or its warp's grid.
    pub fn bounds_uv(&self) -> [f32; 4] {
        match &self.warp {
            Some(w) => w.bounds_uv(),
            None => self.capsule_bounds_uv(),
        }
    }

    /// The bounding box of the capsule of radius W·L around the segment, in UV.
    pub fn capsule_bounds_uv(&self) -> [f32; 4] {
        let r = self.rel_width * self.length_uv();
        [
            self.ma[0].min(self.mb[0]) - r,
            self.ma[1].min(self.mb[1]) - r,
            self.ma[0].max(self.mb[0]) + r,
            self.ma[1].max(self.mb[1]) + r,
        ]
    }

    /// The wrinkle height h(t,d)·Aα of docs/models.md §2 at UV point (u, v), in [0, A]; exactly 0
    /// outside the region where At(d)·Aα > 0.
    #[inline]
    pub fn height_at(&self, u: f32, v: f32) -> f32 {
        // Laid on the surface: evaluated at the point the layout would give it were it
        // affine over the group.
        let (u, v) = match &self.warp {
            None => (u, v),
            Some(w) => match w.at(u, v) {
                Some([u, v]) => (u, v),
                None => return 0.0,
            },
        };
        let (ex, ey) = (self.mb[0] - self.ma[0], self.mb[1] - self.ma[1]);
        let len2 = ex * ex + ey * ey;
        let len = len2.sqrt();
        let (px, py) = (u - self.ma[0], v - self.ma[1]);
        // Position along the fibre, 0 at mA and 1 at mB, before and after the clamp.
        let t_raw = (px * ex + py * ey) / len2;
        let t = t_raw.clamp(0.0, 1.0);
        let (dx, dy) = (px - t * ex, py - t * ey);
        let d = (dx * dx + dy * dy).sqrt();
        let at = attenuation(d, self.rel_width * len);
        if at <= 0.0 {
            return 0.0;
        }
        let a_alpha = if !(0.0..=1.0).contains(&t_raw) {
            // Beyond an end: α is the angle between the direction back into the fibre and
            // the vector end → point. (dx, dy) is exactly that vector here, and the back
            // direction is ∓e, so cos α = ∓(d·e)/(|d|·L).
            let sign = if t_raw > 1.0 { -1.0 } else { 1.0 };
            let cos_alpha = (sign * (dx * ex + dy * ey) / (d * len)).clamp(-1.0, 1.0);
            let a = angle_attenuation(cos_alpha.acos(), self.max_angle);
            if a <= 0.0 {
                return 0.0;
            }
            a
        } else {
            1.0
        };
        let s = smoothstep(at);
        let omega = relative_frequency(at, self.omega_low);
        let phase = self.n as f32 * omega * t;
        if self.irregularity <= 0.0 && self.waviness <= 0.0 {
            return self.depth * s * self.profile.eval(phase) * a_alpha;
        }
        // Irregularity: where along its wrinkle a point lies is its signed distance across
        // the fibre; which wrinkle, the whole part of its phase (the profiles are ~0
        // between wrinkles, where that changes).
        let across = (px * ey - py * ex) / len / (self.rel_width * len);
        let k = phase.floor();
        let key = self.seed.wrapping_mul(0x9E37_79B9) ^ (k as i32 as u32);
        let wave =
            self.waviness * (2.0 * value_noise(across / ALONG_SCALE, key ^ 0x5bd1_e995) - 1.0);
        let a = self.irregularity;
        let between = 1.0 - a * BETWEEN_SHARE * hash01(key);
        let along = 1.0 - a * (1.0 - BETWEEN_SHARE) * value_noise(across / ALONG_SCALE, key);
        self.depth * s * self.profile.eval(phase + wave) * a_alpha * between * along
    }
}

fn range_err(what: &str, value: f32, e: RangeError) -> Error {
    Error::InvalidValue {
        what: what.into(),
        value: value.to_string(),
        expected: e.expected,
    }
}

/// Settings of the large-wrinkle layer (docs/models.md §2 "Blending" and "Mask").
#[derive(Clone, Debug)]
pub struct LargeWrinkleSettings<'a> {
    /// Crest-flattening exponent γ, in [0.01, 10]; default 0.4.
    pub gamma: f32,
    /// Optional grey mask multiplied in after γ (sampled bilinearly in UV).
    pub mask: Option<&'a Mask>,
}

impl Default for LargeWrinkleSettings<'_> {
    fn default() -> Self {
        Self {
            gamma: DEFAULT_GAMMA,
            mask: None,
        }
    }
}

/// Pixel rectangle `[x0, y0, x1, y1)` of the map that can hold non-zero values of `fibre`.
pub(crate) fn pixel_bounds(fibre: &Fibre, width_px: u32, height_px: u32) -> Option<[u32; 4]> {
    let [u0, v0, u1, v1] = fibre.bounds_uv();
    let (w, h) = (width_px as f32, height_px as f32);
    // Pixel x has its centre at (x + 0.5)/W, so it is inside [u0, u1] when
    // u0·W − 0.5 ≤ x ≤ u1·W − 0.5. One pixel of margin absorbs rounding.
    let x0 = ((u0 * w - 0.5).floor() - 1.0).max(0.0);
    let x1 = ((u1 * w - 0.5).ceil() + 2.0).min(w);
    // Row y has v = 1 − (y + 0.5)/H, so v in [v0, v1] ⇔ (1 − v1)·H − 0.5 ≤ y ≤ (1 − v0)·H − 0.5.
    let y0 = (((1.0 - v1) * h - 0.5).floor() - 1.0).max(0.0);
    let y1 = (((1.0 - v0) * h - 0.5).ceil() + 2.0).min(h);
    if x0 >= x1 || y0 >= y1 {
        return None;
    }
    Some([x0 as u32, y0 as u32, x1 as u32, y1 as u32])
}

/// Σ_i h_i(p) over `fibres` into a zeroed map (docs/models.md §2 "Rasterising"), before
/// normalisation. Each fibre is evaluated only over its bounding rectangle, where it covers
/// the whole region with At·Aα > 0 (and adds exact zeros elsewhere in the rectangle, so the
/// sums equal those of [T]'s seed fill). Rows are processed in parallel; within a pixel the
/// fibres are summed in file order, so the result is byte-identical on any thread count.
pub fn accumulate(fibres: &[Fibre], map: &mut HeightMap) {
    let (w, h) = (map.width_px(), map.height_px());
    let bounds: Vec<Option<[u32; 4]>> = fibres.iter().map(|f| pixel_bounds(f, w, h)).collect();
    let us: Vec<f32> = (0..w).map(|x| pixel_to_u(x, w)).collect();
    map.data_mut()
        .par_chunks_mut(w as usize)
        .enumerate()
        .for_each(|(y, row)| {
            let y = y as u32;
            let v = pixel_to_v(y, h);
            for (fibre, b) in fibres.iter().zip(&bounds) {
                let Some([x0, y0, x1, y1]) = *b else { continue };
                if y < y0 || y >= y1 {
                    continue;
                }
                for x in x0 as usize..x1 as usize {
                    row[x] += fibre.height_at(us[x], v);
                }
            }
        });
}

/// Applies H := (H/h_max)^γ and the optional mask in place (docs/models.md §2 "Blending", "Mask"),
/// with h_max the map's own maximum. A map whose maximum is ≤ 0 (no fibre covers it) stays
/// all zeros.
pub fn finish(map: &mut HeightMap, settings: &LargeWrinkleSettings<'_>) -> Result<(), Error> {
    let (_, h_max) = map.min_max();
    finish_with_max(map, settings, h_max)
}

/// [`finish`] normalising by a given `h_max` (the layer's maximum at full age, so that a
/// younger map is shallower instead of re-inflated). Values are clamped to [0, 1].
pub fn finish_with_max(
    map: &mut HeightMap,
    settings: &LargeWrinkleSettings<'_>,
    h_max: f32,
) -> Result<(), Error> {
    let mask = settings.mask.map_or(MaskValues::None, MaskValues::Sample);
    finish_impl(
        map,
        settings.gamma,
        h_max,
        mask,
        &crate::base::cancel::CancelToken::never(),
    )
}

/// Where [`finish_impl`] gets the mask from.
#[derive(Clone, Copy)]
pub(crate) enum MaskValues<'a> {
    None,
    /// Sampled bilinearly at each pixel centre.
    Sample(&'a Mask),
    /// Already sampled at this map's pixel centres (by [`sample_mask`]: the same values).
    Values(&'a [f32]),
    /// Sampled from the column taps (`Mask::tap_u` of every pixel column) and each row's
    /// tap: the same values again, without a map-sized buffer.
    Taps(&'a Mask, &'a [(usize, usize, f32)]),
}

/// The column taps of `mask` for a map `width_px` wide ([`MaskValues::Taps`]).
pub(crate) fn mask_columns(mask: &Mask, width_px: u32) -> Vec<(usize, usize, f32)> {
    (0..width_px)
        .map(|x| mask.tap_u(pixel_to_u(x, width_px)))
        .collect()
}

/// `mask` sampled at every pixel centre of a `width_px × height_px` map, in parallel; the
/// values [`finish`] would sample one by one.
pub(crate) fn sample_mask(mask: &Mask, width_px: u32, height_px: u32) -> Vec<f32> {
    let n = width_px as usize * height_px as usize;
    // Huge pages where the platform has them: a 4096² map faults in 32 pages, not 16k.
    let mut out =
        crate::maps::heightmap::zeroed_vec(n, "mask samples").unwrap_or_else(|_| vec![0.0; n]);
    // The column taps once for all rows: the same samples as `Mask::sample` per pixel.
    let columns = mask_columns(mask, width_px);
    out.par_chunks_mut(width_px as usize)
        .enumerate()
        .for_each(|(y, row)| {
            let row_tap = mask.tap_v(pixel_to_v(y as u32, height_px));
            for (m, &column) in row.iter_mut().zip(&columns) {
                *m = mask.sample_taps(column, row_tap);
            }
        });
    out
}

pub(crate) fn finish_impl(
    map: &mut HeightMap,
    gamma: f32,
    h_max: f32,
    mask: MaskValues<'_>,
    cancel: &crate::base::cancel::CancelToken,
) -> Result<(), Error> {
    if !(gamma.is_finite() && gamma >= GAMMA_RANGE.0 && gamma <= GAMMA_RANGE.1) {
        let expected = format!("a number in [{}, {}]", GAMMA_RANGE.0, GAMMA_RANGE.1);
        return Err(range_err("gamma", gamma, RangeError { expected }));
    }
    let (w, h) = (map.width_px(), map.height_px());
    if h_max.is_nan() || h_max <= 0.0 {
        map.data_mut().fill(0.0);
        return Ok(());
    }
    let inv = 1.0 / h_max;
    map.data_mut()
        .par_chunks_mut(w as usize)
        .enumerate()
        .for_each(|(y, row)| {
            if cancel.is_cancelled() {
                return;
            }
            let v = pixel_to_v(y as u32, h);
            let row_tap = match mask {
                MaskValues::Taps(m, _) => m.tap_v(v),
                _ => (0, 0, 0.0),
            };
            for (x, p) in row.iter_mut().enumerate() {
                // Most of a face map is untouched skin: 0^γ = 0, skip the powf.
                if *p == 0.0 || p.is_nan() {
                    *p = 0.0;
                    continue;
                }
                // A fold's raised side is below zero: γ shapes both sides alike.
                let mut value = (p.abs() * inv).clamp(0.0, 1.0).powf(gamma).copysign(*p);
                match mask {
                    MaskValues::None => {}
                    MaskValues::Sample(m) => value *= m.sample(pixel_to_u(x as u32, w), v),
                    MaskValues::Values(m) => value *= m[y * w as usize + x],
                    MaskValues::Taps(m, columns) => value *= m.sample_taps(columns[x], row_tap),
                }
                *p = value;
            }
        });
    cancel.check()
}

/// The whole large-wrinkle layer: a `width_px × height_px` map in [0,1].
pub fn rasterize(
    fibres: &[Fibre],
    width_px: u32,
    height_px: u32,
    settings: &LargeWrinkleSettings<'_>,
) -> Result<HeightMap, Error> {
    let mut map = HeightMap::zeros(width_px, height_px)?;
    accumulate(fibres, &mut map);
    finish(&mut map, settings)?;
    Ok(map)
}

/// The simple baseline: every pixel against every fibre, one thread, no bounds. Used as
/// the brute-force reference in tests and as the benchmark's baseline.
pub fn accumulate_brute_force(fibres: &[Fibre], map: &mut HeightMap) {
    let (w, h) = (map.width_px(), map.height_px());
    for y in 0..h {
        let v = pixel_to_v(y, h);
        for x in 0..w {
            let u = pixel_to_u(x, w);
            let mut sum = 0.0;
            for f in fibres {
                sum += f.height_at(u, v);
            }
            map.data_mut()[(y * w + x) as usize] = sum;
        }
    }
}

#[cfg(test)]
mod tests;
