//! The age model (`docs/models.md` "Age"; docs/models.md §1 "Age", §1, §5, §6): one age value
//! drives every layer.
//!
//! The models see t ∈ [0, 1] (0 = the young state, 1 = the old state, [T]); people see
//! years, `years = young + t·(old − young)` ([`AgeMapping`], default 20 and 80). An
//! [`AgeCurve`] turns an age into a factor in [0, 1]: 0 before its onset, 1 from its full
//! age on, a smoothstep (default) or linear ramp between. Onsets are in years, so a
//! curve keeps meaning "crow's feet from 35" when the mapping changes.
//!
//! [`AgeFactors`] is everything the layers need at one age, computed by
//! [`crate::project::AgeSection::factors`]: the per-group large-wrinkle factors come from
//! each fibre's own curve (wrinkle-file keys `ageOnset`/`ageFull`) or the layer default.

use serde::{Deserialize, Serialize};

/// Youngest and oldest ages a curve or mapping may name, years.
pub const YEARS_RANGE: (f32, f32) = (0.0, 150.0);
/// Default age that t = 0 stands for, years.
pub const DEFAULT_YOUNG_YEARS: f32 = 20.0;
/// Default age that t = 1 stands for, years.
pub const DEFAULT_OLD_YEARS: f32 = 80.0;

/// The old age's span, years: from [`LATE_START_YEARS`] (no gain) a smoothstep to
/// [`LATE_END_YEARS`] (the whole gain), for the shape's volume and sag, which keep going
/// after their full age (docs/models.md §13 "Old age"). From each region's own full age
/// instead (linear over 15 years), the tear trough (whole at 65) stood at 1.5 by 80,
/// deepening the mid-cheek's edge and the upper-lid sulcus the rubric's 80 sees (rounds
/// 37–39).
pub const LATE_START_YEARS: f32 = 75.0;
pub const LATE_END_YEARS: f32 = 90.0;

/// How far the old age has come at `years`, 0–1: 0 up to [`LATE_START_YEARS`], 1 from
/// [`LATE_END_YEARS`] on, a smoothstep between.
pub fn old_age_share(years: f32) -> f32 {
    if years <= LATE_START_YEARS {
        return 0.0;
    }
    CurveShape::Smoothstep.eval((years - LATE_START_YEARS) / (LATE_END_YEARS - LATE_START_YEARS))
}

/// How much deeper than at their full age the large wrinkles are from the second of
/// [`WRINKLE_LATE_YEARS`] on, linearly from the first (docs/models.md "Age"): wrinkle
/// scores rise with age as a line (Trojahn et al. 2015: r = 0.90 with the chronological
/// age), with no plateau the literature reports, where every file's curve is whole by
/// 75–80. Whole at 80 and still after, the default head at 85 read blind as 75–78 in every
/// round from 34 to 44 (an 80-year-old's wrinkles, the same picture). From 80, the
/// default mapping's old end: every factor up to it is its curve's, so a fully aged
/// project's maps keep their bytes.
pub const WRINKLE_LATE_GAIN: f32 = 1.4;
pub const WRINKLE_LATE_YEARS: (f32, f32) = (80.0, 90.0);

/// How much deeper every large wrinkle is drawn from the second of [`WRINKLE_LATE_YEARS`]
/// on: the layer's depth (`large.depth`, the deepest line's) times this, 1 up to the first,
/// linearly between ([`wrinkle_depth_gain`]; docs/models.md "Age"). [`WRINKLE_LATE_GAIN`]
/// brings the shallower lines up toward the deepest (the normalised map is clamped to 1
/// there), this deepens them all, the deepest too. With the gain alone, the default head
/// and the African man at 85 read blind as 72–78 (rounds 50–66, every round); drawn 1.7 ×
/// as deep at 85, as 79 and 77, the other heads' 85 as 81–86 (`docs/ratings.md` round
/// 67). From 80, so the rubric's 80 keeps its bytes.
pub const WRINKLE_LATE_DEPTH: f32 = 2.4;

/// The large wrinkles' depth at `years` over the layer's depth: 1 up to
/// [`WRINKLE_LATE_YEARS`]'s first, [`WRINKLE_LATE_DEPTH`] from its second, linear between.
pub fn wrinkle_depth_gain(years: f32) -> f32 {
    let (from, to) = WRINKLE_LATE_YEARS;
    if years.is_nan() || years <= from {
        return 1.0;
    }
    1.0 + (WRINKLE_LATE_DEPTH - 1.0) * ((years - from) / (to - from)).min(1.0)
}

/// A large wrinkle's depth factor at `years`: its curve's, times its old-age gain (1 up
/// to [`WRINKLE_LATE_YEARS`]'s first, [`WRINKLE_LATE_GAIN`] from its second on).
pub fn wrinkle_factor(curve: &AgeCurve, years: f32) -> f32 {
    let f = curve.factor(years);
    let (from, to) = WRINKLE_LATE_YEARS;
    if years <= from {
        return f;
    }
    f * (1.0 + (WRINKLE_LATE_GAIN - 1.0) * ((years - from) / (to - from)).min(1.0))
}

/// How a curve ramps from its onset to its full age.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CurveShape {
    /// 3x² − 2x³ (docs/models.md §2 S(x)): starts and ends gently, as visible wrinkles do.
    #[default]
    Smoothstep,
    /// x: [T] §5.2's blend of the fine wrinkles is linear in t.
    Linear,
}

impl CurveShape {
    pub const ALL: [CurveShape; 2] = [CurveShape::Smoothstep, CurveShape::Linear];

    pub fn name(self) -> &'static str {
        match self {
            CurveShape::Smoothstep => "smoothstep",
            CurveShape::Linear => "linear",
        }
    }

    /// The ramp at x ∈ [0, 1] (clamped).
    pub fn eval(self, x: f32) -> f32 {
        let x = x.clamp(0.0, 1.0);
        match self {
            CurveShape::Smoothstep => x * x * (3.0 - 2.0 * x),
            CurveShape::Linear => x,
        }
    }
}

/// A factor in [0, 1] as a function of age: 0 up to `onset_years`, 1 from `full_years`
/// on, `shape` between. `onset_years ≤ full_years`; when they are equal the curve is a
/// step at that age.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AgeCurve {
    /// Age at which the effect starts, years, 0–150.
    pub onset_years: f32,
    /// Age at which it is complete, years, 0–150, ≥ onset.
    pub full_years: f32,
    pub shape: CurveShape,
}

impl Default for AgeCurve {
    fn default() -> Self {
        Self::new(
            DEFAULT_YOUNG_YEARS,
            DEFAULT_OLD_YEARS,
            CurveShape::Smoothstep,
        )
    }
}

impl AgeCurve {
    pub const fn new(onset_years: f32, full_years: f32, shape: CurveShape) -> Self {
        Self {
            onset_years,
            full_years,
            shape,
        }
    }

    /// The factor at `years`. Exactly 0 at or before the onset and exactly 1 at or after
    /// the full age, so a layer at full age keeps its bytes (multiplying by 1 is exact).
    pub fn factor(&self, years: f32) -> f32 {
        if years >= self.full_years {
            return 1.0;
        }
        if years <= self.onset_years {
            return 0.0;
        }
        self.shape
            .eval((years - self.onset_years) / (self.full_years - self.onset_years))
    }

    /// Every problem with the curve, each as (field suffix, message).
    pub fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        for (name, v) in [
            ("onset_years", self.onset_years),
            ("full_years", self.full_years),
        ] {
            if !(YEARS_RANGE.0..=YEARS_RANGE.1).contains(&v) {
                out.push((
                    name,
                    format!(
                        "{v} is out of range: expected {}..={}",
                        YEARS_RANGE.0, YEARS_RANGE.1
                    ),
                ));
            }
        }
        if self.full_years < self.onset_years {
            out.push((
                "full_years",
                format!(
                    "{} is before the onset ({}): expected full_years ≥ onset_years",
                    self.full_years, self.onset_years
                ),
            ));
        }
        out
    }
}

/// The years that t = 0 and t = 1 stand for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AgeMapping {
    pub young_years: f32,
    pub old_years: f32,
}

impl Default for AgeMapping {
    fn default() -> Self {
        Self {
            young_years: DEFAULT_YOUNG_YEARS,
            old_years: DEFAULT_OLD_YEARS,
        }
    }
}

impl AgeMapping {
    /// years = young + t·(old − young), t clamped to [0, 1].
    pub fn years(&self, t: f32) -> f32 {
        let t = t.clamp(0.0, 1.0);
        self.young_years + t * (self.old_years - self.young_years)
    }

    /// The t of `years`, clamped to [0, 1].
    pub fn t(&self, years: f32) -> f32 {
        let span = self.old_years - self.young_years;
        if span <= 0.0 {
            return 0.0;
        }
        ((years - self.young_years) / span).clamp(0.0, 1.0)
    }
}

/// A scale that grows with age: `young_scale` before the curve's onset, 1 at its full age
/// (the project's nominal value is the old value), `young + (1 − young)·curve` between.
pub fn scale(young_scale: f32, curve_factor: f32) -> f32 {
    if curve_factor >= 1.0 {
        1.0
    } else {
        young_scale + (1.0 - young_scale) * curve_factor
    }
}

/// Everything the layers need at one age. See [`crate::project::AgeSection::factors`].
#[derive(Clone, Debug, PartialEq)]
pub struct AgeFactors {
    /// t ∈ [0, 1].
    pub t: f32,
    /// The age in years.
    pub years: f32,
    /// Depth factor of each large-wrinkle fibre, in the scene's fibre order.
    pub large: Vec<f32>,
    /// Blend of the fine-wrinkle normal, 0 = surface normal, 1 = fine tile ([T] §5.2).
    pub fine_blend: f32,
    /// Multiplier of every pore's radius R (1 = the project's value).
    pub pore_radius_scale: f32,
    /// Multiplier of every furrow's depth A (1 = the project's value).
    pub furrow_depth_scale: f32,
    /// How far the albedo has moved toward the pale tone, [0, 1] ([T] §3.1.1).
    pub paleness: f32,
}

/// The brows' gray fraction relative to the scalp hair's: brows gray later. At 0.65, the
/// black-haired heads' brows stayed dark beside a white fringe at 80, read blind as "the
/// eyebrows stay jet black while the scalp is gray" (round 45, both East Asian and
/// MakeHuman heads).
const BROW_GRAY_LAG: f32 = 0.8;

/// Each effect of the aged colour and the brows and lashes, its age factor 0–1 (the age
/// model's curves at one age; the scene makes them from the project).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ColourFactors {
    /// Paling and yellowing.
    pub pale: f32,
    /// Which spots show and how grown they are (a spot appears when this passes its own
    /// draw in [0, 1)).
    pub spots: f32,
    pub mottle: f32,
    pub redness: f32,
    /// Lips and brows fading.
    pub contrast: f32,
    /// The brows' gray fraction.
    pub brow_gray: f32,
    /// The bags' shape at this age (their region's strength times its curve): the
    /// shadow of the lid–cheek junction under them (the shape layer's `drawn_crease`,
    /// which the aged colour draws).
    pub bags: f32,
}

impl ColourFactors {
    /// The share of brow hairs that are gray: the brows gray later than the scalp
    /// ([`BROW_GRAY_LAG`]).
    pub fn brow_gray_fraction(&self) -> f32 {
        BROW_GRAY_LAG * self.brow_gray
    }

    /// Whether nothing ages: the bake is then the base colour itself.
    pub fn is_young(&self) -> bool {
        [
            self.pale,
            self.spots,
            self.mottle,
            self.redness,
            self.contrast,
            self.brow_gray,
            self.bags,
        ]
        .iter()
        .all(|&f| f <= 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::close;

    #[test]
    fn large_wrinkles_keep_deepening_past_80() {
        let curve = AgeCurve::new(40.0, 75.0, CurveShape::Smoothstep);
        assert_eq!(wrinkle_factor(&curve, 50.0), curve.factor(50.0));
        assert_eq!(wrinkle_factor(&curve, 80.0), 1.0);
        let at = |y| wrinkle_factor(&curve, y);
        assert!(at(82.0) > 1.0 && at(82.0) < at(85.0) && at(85.0) < at(90.0));
        assert!((at(85.0) - 1.2).abs() < 1e-5, "{}", at(85.0));
        assert_eq!(at(90.0), WRINKLE_LATE_GAIN);
        assert_eq!(wrinkle_depth_gain(80.0), 1.0);
        assert_eq!(wrinkle_depth_gain(f32::NAN), 1.0);
        assert!((wrinkle_depth_gain(85.0) - 0.5 * (1.0 + WRINKLE_LATE_DEPTH)).abs() < 1e-6);
        assert_eq!(wrinkle_depth_gain(120.0), WRINKLE_LATE_DEPTH);
        assert_eq!(at(120.0), WRINKLE_LATE_GAIN);
        // A curve not whole yet keeps its share.
        let late = AgeCurve::new(60.0, 100.0, CurveShape::Linear);
        assert!((wrinkle_factor(&late, 90.0) - 0.75 * WRINKLE_LATE_GAIN).abs() < 1e-5);
    }

    #[test]
    fn curve_is_zero_before_onset_one_after_full_and_smooth_between() {
        let c = AgeCurve::new(30.0, 60.0, CurveShape::Smoothstep);
        assert_eq!(c.factor(20.0), 0.0);
        assert_eq!(c.factor(30.0), 0.0);
        assert_eq!(c.factor(60.0), 1.0);
        assert_eq!(c.factor(80.0), 1.0);
        close(c.factor(45.0), 0.5, 1e-6);
        // smoothstep(0.25) = 3/16 − 2/64 = 0.15625
        close(c.factor(37.5), 0.15625, 1e-6);
        let l = AgeCurve::new(30.0, 60.0, CurveShape::Linear);
        close(l.factor(37.5), 0.25, 1e-6);
        let step = AgeCurve::new(40.0, 40.0, CurveShape::Smoothstep);
        assert_eq!((step.factor(39.9), step.factor(40.0)), (0.0, 1.0));
    }

    #[test]
    fn curve_is_monotone() {
        let c = AgeCurve::new(25.0, 65.0, CurveShape::Smoothstep);
        let mut last = 0.0;
        for i in 0..=200 {
            let f = c.factor(20.0 + i as f32 * 0.3);
            assert!(f >= last, "{f} < {last} at step {i}");
            last = f;
        }
    }

    #[test]
    fn mapping_round_trips_years_and_t() {
        let m = AgeMapping::default();
        assert_eq!(m.years(0.0), 20.0);
        assert_eq!(m.years(1.0), 80.0);
        close(m.years(0.5), 50.0, 1e-6);
        close(m.t(65.0), 0.75, 1e-6);
        assert_eq!(m.t(10.0), 0.0);
        assert_eq!(m.t(99.0), 1.0);
    }

    #[test]
    fn bad_curves_name_their_field() {
        let p = AgeCurve::new(60.0, 30.0, CurveShape::Linear).problems();
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].0, "full_years");
        let p = AgeCurve::new(-1.0, 200.0, CurveShape::Linear).problems();
        assert_eq!(p.len(), 2, "{p:?}");
    }

    #[test]
    fn scale_reaches_one_exactly_at_full_age() {
        assert_eq!(scale(0.6, 1.0), 1.0);
        assert_eq!(scale(0.6, 0.0), 0.6);
        close(scale(0.6, 0.5), 0.8, 1e-6);
    }
}
