//! Pores of docs/models.md §4 "Pores" [P §3.2]: placement (blue noise or uniform) and profiles.
//!
//! Positions are in millimetres on the map, (0,0) at its bottom-left corner (u right, v up,
//! docs/models.md §1). A pore of radius R, depth dmax and falloff α has the height h(r) = −m(r) with
//!
//! - [`PoreProfile::Gaussian`] (default, eq. 15): m = dmax·exp(−α r²/R²) for r ≤ R, 0
//!   outside. With [`Rim::Smooth`] (default) it is multiplied by a window that is 1 up to
//!   r = (1 − [`RIM_BAND`])·R and falls to 0 with zero slope at R (a smoothstep in r²/R²);
//!   [`Rim::Exact`] keeps eq. 15's step of dmax·e^(−α) at the rim. Negative α makes the
//!   depth grow toward the rim, so the centre becomes a raised dome ("goose skin", [P fig. 13]).
//! - [`PoreProfile::Quadratic`] (eq. 3): m = dmax·(1 − r/R)².
//! - [`PoreProfile::Quartic`] (eq. 11): m = dmax·(1 − r²/R²)².
//!
//! The last two already reach 0 with zero slope at R, so `rim` does not change them.

use serde::{Deserialize, Serialize};

use crate::base::rng::Rng;

/// Width of the smooth rim window, as a fraction of the radius (**Choice**: wide enough to
/// hide the step, narrow enough to keep eq. 15's shape, goose-skin domes included).
pub const RIM_BAND: f32 = 0.3;

/// Blue-noise minimum spacing as a fraction of the hexagonal-packing spacing of the
/// requested count. Random dart throwing fills up to about 0.74 of it; 0.65 is reached
/// quickly for any count. If it is not, the spacing shrinks by 10 % steps (never silently:
/// [`PorePlacement::min_spacing_mm`] reports the spacing that was guaranteed).
pub const BLUE_NOISE_SPACING_FRACTION: f32 = 0.65;

/// The radial profile of a pore.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PoreProfile {
    /// eq. 15, dmax·exp(−α r²/R²).
    #[default]
    Gaussian,
    /// eq. 3, dmax·(1 − r/R)².
    Quadratic,
    /// eq. 11, dmax·(1 − r²/R²)².
    Quartic,
}

/// How eq. 15 ends at r = R.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Rim {
    /// Smooth window to 0 with zero slope at R.
    #[default]
    Smooth,
    /// Eq. 15 exactly: a step at R.
    Exact,
}

/// How pore centres are scattered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Placement {
    /// Poisson disc: a guaranteed minimum spacing, no clumps.
    #[default]
    BlueNoise,
    /// Independent uniform positions (clumps, as [P] notes).
    Uniform,
}

/// One pore, drawn from the project's means and spreads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pore {
    /// Centre in millimetres, (0,0) at the map's bottom-left corner.
    pub centre_mm: [f32; 2],
    /// R in millimetres, > 0.
    pub radius_mm: f32,
    /// dmax in height units, ≥ 0.
    pub depth: f32,
    /// α, dimensionless; negative gives goose skin.
    pub falloff: f32,
}

/// A pore's shape settings shared by all pores.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PoreShape {
    pub profile: PoreProfile,
    pub rim: Rim,
}

impl PoreShape {
    /// The height h(r) of `pore` at distance² `r2_mm2` from its centre (docs/models.md §4 eqs. 15, 3,
    /// 11): ≤ 0, 0 for r ≥ R.
    #[inline(always)]
    pub fn height(&self, pore: &Pore, r2_mm2: f32) -> f32 {
        let t = r2_mm2 / (pore.radius_mm * pore.radius_mm);
        if t >= 1.0 {
            return 0.0;
        }
        -pore.depth * self.shape(t, pore.falloff)
    }

    /// The profile m/dmax as a function of t = r²/R² in [0, 1).
    #[inline(always)]
    pub fn shape(&self, t: f32, falloff: f32) -> f32 {
        match self.profile {
            PoreProfile::Gaussian => {
                let g = super::fastmath::exp(-falloff * t);
                match self.rim {
                    Rim::Exact => g,
                    Rim::Smooth => g * rim_window(t),
                }
            }
            PoreProfile::Quadratic => {
                let s = 1.0 - t.sqrt();
                s * s
            }
            PoreProfile::Quartic => {
                let s = 1.0 - t;
                s * s
            }
        }
    }
}

/// 1 for t ≤ t₀ = (1 − RIM_BAND)², then 1 − smoothstep(t₀, 1, t): 0 with zero slope at t = 1.
#[inline(always)]
pub fn rim_window(t: f32) -> f32 {
    const T0: f32 = (1.0 - RIM_BAND) * (1.0 - RIM_BAND);
    let s = ((t - T0) * (1.0 / (1.0 - T0))).clamp(0.0, 1.0);
    1.0 - s * s * (3.0 - 2.0 * s)
}

/// A value drawn uniformly in mean ± spread.
#[inline]
fn draw(rng: &mut Rng, mean: f32, spread: f32) -> f32 {
    mean + spread * (2.0 * rng.next_f32() - 1.0)
}

/// Pore statistics: each drawn uniformly in mean ± spread (radius and depth clamped ≥ 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoreStats {
    pub radius_mm: (f32, f32),
    pub depth: (f32, f32),
    pub falloff: (f32, f32),
}

/// The result of [`place_pores`].
#[derive(Clone, Debug, PartialEq)]
pub struct PorePlacement {
    pub pores: Vec<Pore>,
    /// The minimum centre distance guaranteed (0 for uniform placement), mm.
    pub min_spacing_mm: f32,
}

/// Scatters exactly `count` pores over a `size_mm`² map (docs/models.md §4 "Pores"). Distances wrap
/// around the map when `tile` is set. Deterministic in `seed`.
pub fn place_pores(
    count: usize,
    stats: &PoreStats,
    placement: Placement,
    size_mm: f32,
    tile: bool,
    seed: u64,
) -> PorePlacement {
    let (centres, min_spacing_mm) = match placement {
        Placement::Uniform => {
            let mut rng = Rng::for_stream(seed, 0x706f_7265_0001);
            let c = (0..count)
                .map(|_| [rng.next_f32() * size_mm, rng.next_f32() * size_mm])
                .collect();
            (c, 0.0)
        }
        Placement::BlueNoise => blue_noise(count, size_mm, tile, seed),
    };
    let pores = centres
        .into_iter()
        .enumerate()
        .map(|(k, centre_mm)| {
            let mut rng = Rng::for_stream(seed ^ 0x706f_7265_0002, k as u64);
            Pore {
                centre_mm,
                radius_mm: draw(&mut rng, stats.radius_mm.0, stats.radius_mm.1).max(1e-4),
                depth: draw(&mut rng, stats.depth.0, stats.depth.1).max(0.0),
                falloff: draw(&mut rng, stats.falloff.0, stats.falloff.1),
            }
        })
        .collect();
    PorePlacement {
        pores,
        min_spacing_mm,
    }
}

/// Dart throwing with a background grid (one point per cell at most).
fn blue_noise(count: usize, size_mm: f32, tile: bool, seed: u64) -> (Vec<[f32; 2]>, f32) {
    if count == 0 {
        return (Vec::new(), 0.0);
    }
    let hex = (2.0 * size_mm * size_mm / (3f32.sqrt() * count as f32)).sqrt();
    let mut d = BLUE_NOISE_SPACING_FRACTION * hex;
    let mut rng = Rng::for_stream(seed, 0x706f_7265_0003);
    let mut pts: Vec<[f32; 2]> = Vec::with_capacity(count);
    loop {
        let grid = Grid::new(size_mm, d, &pts);
        let mut grid = grid;
        let mut misses = 0usize;
        // 64 consecutive misses per missing point means the disc is nearly saturated.
        while pts.len() < count && misses < 64 * count.max(16) {
            let p = [rng.next_f32() * size_mm, rng.next_f32() * size_mm];
            if grid.is_free(p, d, &pts, tile) {
                grid.insert(p, pts.len());
                pts.push(p);
                misses = 0;
            } else {
                misses += 1;
            }
        }
        if pts.len() == count {
            return (pts, d);
        }
        d *= 0.9;
    }
}

struct Grid {
    n: usize,
    cell_mm: f32,
    size_mm: f32,
    slots: Vec<u32>,
}

impl Grid {
    const EMPTY: u32 = u32::MAX;

    fn new(size_mm: f32, d: f32, pts: &[[f32; 2]]) -> Self {
        let n = ((size_mm / (d * std::f32::consts::FRAC_1_SQRT_2)).ceil() as usize).clamp(1, 8192);
        let mut g = Self {
            n,
            cell_mm: size_mm / n as f32,
            size_mm,
            slots: vec![Self::EMPTY; n * n],
        };
        for (k, &p) in pts.iter().enumerate() {
            g.insert(p, k);
        }
        g
    }

    fn cell(&self, p: [f32; 2]) -> (usize, usize) {
        let c = |x: f32| ((x / self.cell_mm) as usize).min(self.n - 1);
        (c(p[0]), c(p[1]))
    }

    fn insert(&mut self, p: [f32; 2], k: usize) {
        let (i, j) = self.cell(p);
        self.slots[j * self.n + i] = k as u32;
    }

    fn is_free(&self, p: [f32; 2], d: f32, pts: &[[f32; 2]], tile: bool) -> bool {
        let r = (d / self.cell_mm).ceil() as isize;
        let (ci, cj) = self.cell(p);
        let n = self.n as isize;
        for dj in -r..=r {
            for di in -r..=r {
                let (mut i, mut j) = (ci as isize + di, cj as isize + dj);
                if tile {
                    i = i.rem_euclid(n);
                    j = j.rem_euclid(n);
                } else if i < 0 || j < 0 || i >= n || j >= n {
                    continue;
                }
                let s = self.slots[j as usize * self.n + i as usize];
                if s != Self::EMPTY && distance2(p, pts[s as usize], self.size_mm, tile) < d * d {
                    return false;
                }
            }
        }
        true
    }
}

/// Squared distance, the shortest way around the map when `tile` is set.
pub fn distance2(a: [f32; 2], b: [f32; 2], size_mm: f32, tile: bool) -> f32 {
    let [dx, dy] = delta(a, b, size_mm, tile);
    dx * dx + dy * dy
}

/// b − a, the shortest way around the map when `tile` is set.
pub fn delta(a: [f32; 2], b: [f32; 2], size_mm: f32, tile: bool) -> [f32; 2] {
    let mut d = [b[0] - a[0], b[1] - a[1]];
    if tile {
        for c in &mut d {
            *c -= size_mm * (*c / size_mm).round();
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::close;

    fn pore(falloff: f32) -> Pore {
        Pore {
            centre_mm: [0.0, 0.0],
            radius_mm: 2.0,
            depth: 1.5,
            falloff,
        }
    }

    #[test]
    fn eq15_exact_at_hand_computed_radii() {
        let s = PoreShape {
            profile: PoreProfile::Gaussian,
            rim: Rim::Exact,
        };
        let p = pore(1.2);
        close(s.height(&p, 0.0), -1.5, 1e-6);
        // r = 1 mm: −1.5·e^(−1.2·0.25) = −1.5·0.7408182 = −1.1112273
        close(s.height(&p, 1.0), -1.111_227_3, 1e-6);
        // just inside R (t = 0.999975): −1.5·e^(−1.19997) = −0.4518049; outside: 0 (the step)
        close(s.height(&p, 3.9999), -0.451_804_9, 1e-6);
        assert_eq!(s.height(&p, 4.0), 0.0);
    }

    #[test]
    fn smooth_rim_is_continuous_and_keeps_the_core() {
        let s = PoreShape {
            profile: PoreProfile::Gaussian,
            rim: Rim::Smooth,
        };
        let p = pore(1.2);
        // Inside (1 − RIM_BAND)·R = 1.4 mm the window is 1: same as eq. 15.
        close(s.height(&p, 1.0), -1.111_227_3, 1e-6);
        // Approaching R the height goes to 0 continuously, with vanishing slope.
        let near = s.height(&p, 4.0 * 0.999f32.powi(2));
        assert!(near.abs() < 1e-4, "height just inside the rim {near}");
        // Zero slope at R: the height falls off quadratically, 10× closer ⇒ 100× shallower.
        let (a, b) = (
            s.height(&p, 4.0 * 0.999f32.powi(2)),
            s.height(&p, 4.0 * 0.99f32.powi(2)),
        );
        assert!(
            a.abs() < 0.02 * b.abs(),
            "not flat at the rim: h(0.999R) = {a}, h(0.99R) = {b}"
        );
        // Midway through the band, t = 0.745: window = 0.5 (smoothstep at its midpoint).
        close(rim_window((0.49 + 1.0) / 2.0), 0.5, 1e-6);
    }

    #[test]
    fn eq3_and_eq11_at_hand_computed_radii() {
        let q = PoreShape {
            profile: PoreProfile::Quadratic,
            rim: Rim::Smooth,
        };
        let c = PoreShape {
            profile: PoreProfile::Quartic,
            rim: Rim::Exact,
        };
        let p = pore(1.0);
        // r = 1, R = 2: (1 − 0.5)² = 0.25 → −0.375; (1 − 0.25)² = 0.5625 → −0.84375
        close(q.height(&p, 1.0), -0.375, 1e-6);
        close(c.height(&p, 1.0), -0.843_75, 1e-6);
        // r = 1.5: (0.25)² = 0.0625 → −0.09375; (1 − 0.5625)² = 0.19140625 → −0.287109375
        close(q.height(&p, 2.25), -0.093_75, 1e-6);
        close(c.height(&p, 2.25), -0.287_109_38, 1e-6);
        assert_eq!(q.height(&p, 4.0), 0.0);
    }

    #[test]
    fn negative_falloff_raises_the_centre_goose_skin() {
        for rim in [Rim::Exact, Rim::Smooth] {
            let s = PoreShape {
                profile: PoreProfile::Gaussian,
                rim,
            };
            let goose = pore(-1.0);
            let plain = pore(1.0);
            // r = 0.6 R: goose skin is deeper there than at its centre (the centre is a dome),
            // an ordinary pore is shallower there than at its centre.
            let r2 = (0.6f32 * 2.0).powi(2);
            assert!(
                s.height(&goose, 0.0) > s.height(&goose, r2),
                "{rim:?}: centre not raised"
            );
            assert!(
                s.height(&plain, 0.0) < s.height(&plain, r2),
                "{rim:?}: pore centre not deepest"
            );
        }
    }

    #[test]
    fn blue_noise_count_is_exact_and_spacing_guaranteed() {
        let stats = PoreStats {
            radius_mm: (0.3, 0.1),
            depth: (1.0, 0.2),
            falloff: (1.0, 0.0),
        };
        for (count, tile) in [(1000, false), (1000, true), (37, true), (5000, false)] {
            let pl = place_pores(count, &stats, Placement::BlueNoise, 50.0, tile, 9);
            assert_eq!(pl.pores.len(), count);
            let hex = (2.0 * 2500.0 / (3f32.sqrt() * count as f32)).sqrt();
            assert!(
                pl.min_spacing_mm >= 0.5 * hex,
                "spacing shrank to {} (hex {hex})",
                pl.min_spacing_mm
            );
            let mut min = f32::INFINITY;
            for (a, pa) in pl.pores.iter().enumerate() {
                for pb in &pl.pores[a + 1..] {
                    min = min.min(distance2(pa.centre_mm, pb.centre_mm, 50.0, tile));
                }
            }
            assert!(
                min.sqrt() >= pl.min_spacing_mm,
                "{count}: closest pair {} < {}",
                min.sqrt(),
                pl.min_spacing_mm
            );
            assert!(
                pl.pores
                    .iter()
                    .all(|p| (0.0..50.0).contains(&p.centre_mm[0])
                        && (0.0..50.0).contains(&p.centre_mm[1]))
            );
        }
        // Uniform placement does clump: its closest pair is far below the blue-noise spacing.
        let u = place_pores(1000, &stats, Placement::Uniform, 50.0, false, 9);
        assert_eq!(u.pores.len(), 1000);
        let mut min = f32::INFINITY;
        for (a, pa) in u.pores.iter().enumerate() {
            for pb in &u.pores[a + 1..] {
                min = min.min(distance2(pa.centre_mm, pb.centre_mm, 50.0, false));
            }
        }
        assert!(min.sqrt() < 0.3, "uniform closest pair {}", min.sqrt());
    }

    #[test]
    fn attributes_stay_in_mean_plus_minus_spread() {
        let stats = PoreStats {
            radius_mm: (0.3, 0.1),
            depth: (1.0, 0.5),
            falloff: (-0.5, 0.25),
        };
        let pl = place_pores(500, &stats, Placement::BlueNoise, 50.0, false, 1);
        for p in &pl.pores {
            assert!((0.2..=0.4).contains(&p.radius_mm), "{p:?}");
            assert!((0.5..=1.5).contains(&p.depth), "{p:?}");
            assert!((-0.75..=-0.25).contains(&p.falloff), "{p:?}");
        }
    }
}
