//! Non-rigid refinement of the landmark warp (docs/models.md §7a, step 4): the warped head's
//! skin is drawn onto the template's surface by a smooth displacement field, in rounds of
//! decreasing stiffness, before each vertex takes its closest template point.
//!
//! Each round pairs every warped skin point with its closest template point, keeps the pairs
//! whose normals agree (a cheek point is not matched to the back of an ear) and whose
//! distance is within the round's reach, and smooths their offsets into a field: a Gaussian
//! of width σ over 3D space, computed on a voxel grid (splat, separable blur, trilinear read,
//! so a round costs O(points + cells), not O(points²)). The landmarks are anchors with zero
//! offset, so the warp's landmark placement is kept. A wide σ first moves whole regions (a
//! jaw, a brow ridge), narrow ones later fit the forms (the nose wing, the lips).

use glam::{IVec3, Vec3};

use super::bvh::Bvh;

/// One round of the schedule: Gaussian width and farthest pair kept, metres.
#[derive(Clone, Copy, Debug)]
pub struct Round {
    pub sigma_m: f32,
    pub reach_m: f32,
}

/// The default schedule: stiff to supple.
pub const SCHEDULE: [Round; 4] = [
    Round {
        sigma_m: 0.030,
        reach_m: 0.020,
    },
    Round {
        sigma_m: 0.020,
        reach_m: 0.015,
    },
    Round {
        sigma_m: 0.012,
        reach_m: 0.010,
    },
    Round {
        sigma_m: 0.008,
        reach_m: 0.008,
    },
];

/// Most points paired in a round (and measured for the report).
const MAX_PAIRED: usize = 50_000;

/// Pairs whose normals are farther apart than this (cosine) are left out.
const MIN_NORMAL_COS: f32 = 0.5;

/// A landmark anchor weighs this many times the pairs around it (their Gaussian weights
/// at the anchor summed), so it holds on a dense mesh as on a coarse one.
const ANCHOR_WEIGHT: f32 = 1.0;

/// Grid cells per σ.
const CELLS_PER_SIGMA: f32 = 2.0;

/// What a refinement did, for reports.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RefineReport {
    /// Median distance of the warped skin to the template before and after, mm.
    pub median_before_mm: f32,
    pub median_after_mm: f32,
}

/// Moves `points` (the warped head skin, template metres, with their `normals`) onto the
/// template surface `bvh` (face normals `template_normals` per BVH triangle), keeping
/// `anchors` (the warped landmarks) in place.
pub fn refine(
    points: &mut [Vec3],
    normals: &[Vec3],
    bvh: &Bvh,
    template_normals: &[Vec3],
    anchors: &[Vec3],
    schedule: &[Round],
) -> RefineReport {
    use rayon::prelude::*;
    // A dense head pairs every `step`-th point: the field is smooth over σ ≥ 8 mm, far
    // wider than a 50k-point head's spacing, and its pull on the rest is the same.
    let step = points.len().div_ceil(MAX_PAIRED).max(1);
    let median = |points: &[Vec3]| {
        let mut d: Vec<f32> = points
            .par_iter()
            .step_by(step)
            .filter_map(|&p| bvh.closest(p, 0.05).map(|h| h.distance))
            .collect();
        if d.is_empty() {
            return f32::NAN;
        }
        let mid = d.len() / 2;
        *d.select_nth_unstable_by(mid, f32::total_cmp).1 * 1e3
    };
    let median_before_mm = median(points);
    let mut moved_anchors = anchors.to_vec();
    for round in schedule {
        // Pairs: offset to the closest template point, where the surfaces face alike.
        let mut pairs: Vec<(Vec3, Vec3, f32)> = points
            .par_iter()
            .zip(normals.par_iter())
            .step_by(step)
            .filter_map(|(&p, &n)| {
                let hit = bvh.closest(p, round.reach_m)?;
                let tn = template_normals.get(hit.triangle as usize)?;
                (tn.dot(n) >= MIN_NORMAL_COS).then_some((p, hit.point - p, 1.0))
            })
            .collect();
        let k = -0.5 / (round.sigma_m * round.sigma_m);
        // An anchor moves with the field like any point and pulls back to where the warp
        // put it.
        let anchored: Vec<(Vec3, Vec3, f32)> = anchors
            .par_iter()
            .zip(moved_anchors.par_iter())
            .map(|(&home, &a)| {
                let around: f32 = pairs
                    .iter()
                    .map(|(p, ..)| (p.distance_squared(a) * k).exp())
                    .sum();
                (a, home - a, ANCHOR_WEIGHT * around.max(1.0))
            })
            .collect();
        pairs.extend(anchored);
        let Some(field) = Field::smooth(&pairs, round.sigma_m) else {
            continue;
        };
        points.par_iter_mut().for_each(|p| *p += field.at(*p));
        for a in &mut moved_anchors {
            *a += field.at(*a);
        }
    }
    RefineReport {
        median_before_mm,
        median_after_mm: median(points),
    }
}

/// A smoothed offset field on a voxel grid: Σ w r and Σ w, each blurred by a Gaussian.
struct Field {
    origin: Vec3,
    cell: f32,
    dims: IVec3,
    /// (Σ w r, Σ w) per cell.
    cells: Vec<[f32; 4]>,
}

impl Field {
    /// The Nadaraya–Watson average of the pairs' offsets with a Gaussian of width `sigma`;
    /// where there are no pairs near, the offset falls to zero (a prior of weight one pair).
    fn smooth(pairs: &[(Vec3, Vec3, f32)], sigma: f32) -> Option<Self> {
        let (lo, hi) = pairs.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), (p, ..)| (lo.min(*p), hi.max(*p)),
        );
        if !lo.is_finite() || !hi.is_finite() || sigma <= 0.0 {
            return None;
        }
        let cell = sigma / CELLS_PER_SIGMA;
        let margin = Vec3::splat(3.0 * sigma + cell);
        let origin = lo - margin;
        let dims = (((hi + margin - origin) / cell).ceil().as_ivec3() + 1).max(IVec3::ONE);
        // A head is ~0.3 m across; refuse a degenerate cloud rather than allocate.
        if dims.x as i64 * dims.y as i64 * dims.z as i64 > 8_000_000 {
            return None;
        }
        let mut field = Self {
            origin,
            cell,
            dims,
            cells: vec![[0.0; 4]; (dims.x * dims.y * dims.z) as usize],
        };
        for &(p, r, w) in pairs {
            field.splat(p, [r.x * w, r.y * w, r.z * w, w]);
        }
        field.blur(CELLS_PER_SIGMA);
        Some(field)
    }

    fn index(&self, c: IVec3) -> usize {
        ((c.z * self.dims.y + c.y) * self.dims.x + c.x) as usize
    }

    /// Trilinear corners and weights of `p`.
    fn corners(&self, p: Vec3) -> Option<([IVec3; 8], [f32; 8])> {
        let g = (p - self.origin) / self.cell;
        let base = g.floor();
        let f = g - base;
        let b = base.as_ivec3();
        if b.cmplt(IVec3::ZERO).any() || (b + 1).cmpge(self.dims).any() {
            return None;
        }
        let mut cs = [IVec3::ZERO; 8];
        let mut ws = [0.0; 8];
        for k in 0..8 {
            let o = IVec3::new(k & 1, (k >> 1) & 1, (k >> 2) & 1);
            cs[k as usize] = b + o;
            let w = |i: i32, f: f32| if i == 1 { f } else { 1.0 - f };
            ws[k as usize] = w(o.x, f.x) * w(o.y, f.y) * w(o.z, f.z);
        }
        Some((cs, ws))
    }

    fn splat(&mut self, p: Vec3, v: [f32; 4]) {
        let Some((cs, ws)) = self.corners(p) else {
            return;
        };
        for (c, w) in cs.iter().zip(ws) {
            let i = self.index(*c);
            for (cell, v) in self.cells[i].iter_mut().zip(v) {
                *cell += v * w;
            }
        }
    }

    /// Separable Gaussian blur of standard deviation `s` cells, three passes.
    fn blur(&mut self, s: f32) {
        let radius = (3.0 * s).ceil() as i32;
        let kernel: Vec<f32> = (-radius..=radius)
            .map(|i| (-0.5 * (i as f32 / s).powi(2)).exp())
            .collect();
        for axis in 0..3 {
            let step = match axis {
                0 => 1,
                1 => self.dims.x as isize,
                _ => (self.dims.x * self.dims.y) as isize,
            };
            let len = self.dims[axis];
            let src = self.cells.clone();
            use rayon::prelude::*;
            self.cells.par_iter_mut().enumerate().for_each(|(i, out)| {
                let pos = (i as isize / step) as i32 % len;
                let mut acc = [0.0f32; 4];
                for (j, &k) in kernel.iter().enumerate() {
                    let q = pos + j as i32 - radius;
                    if q < 0 || q >= len {
                        continue;
                    }
                    let v = &src[(i as isize + (q - pos) as isize * step) as usize];
                    for (a, v) in acc.iter_mut().zip(v) {
                        *a += v * k;
                    }
                }
                *out = acc;
            });
        }
    }

    /// The smoothed offset at `p` (zero off the grid).
    fn at(&self, p: Vec3) -> Vec3 {
        let Some((cs, ws)) = self.corners(p) else {
            return Vec3::ZERO;
        };
        let mut acc = [0.0f32; 4];
        for (c, w) in cs.iter().zip(ws) {
            let v = self.cells[self.index(*c)];
            for (a, v) in acc.iter_mut().zip(v) {
                *a += v * w;
            }
        }
        // The Gaussian's peak weight of one pair, as the prior toward zero.
        let prior = 1.0;
        Vec3::new(acc[0], acc[1], acc[2]) / (acc[3] + prior)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere of radius `r`: positions and triangles (latitude-longitude).
    fn sphere(r: f32, n: usize) -> (Vec<Vec3>, Vec<u32>) {
        let mut p = Vec::new();
        for i in 0..=n {
            let theta = std::f32::consts::PI * i as f32 / n as f32;
            for j in 0..2 * n {
                let phi = std::f32::consts::PI * j as f32 / n as f32;
                p.push(
                    r * Vec3::new(
                        theta.sin() * phi.cos(),
                        theta.cos(),
                        theta.sin() * phi.sin(),
                    ),
                );
            }
        }
        let w = 2 * n as u32;
        let mut ix = Vec::new();
        for i in 0..n as u32 {
            for j in 0..w {
                let (a, b) = (i * w + j, i * w + (j + 1) % w);
                let (c, d) = (a + w, b + w);
                ix.extend([a, c, b, b, c, d]);
            }
        }
        (p, ix)
    }

    #[test]
    fn a_surface_off_by_5_mm_is_drawn_on_and_the_anchors_hold() {
        let (tp, ti) = sphere(0.1, 48);
        let bvh = Bvh::new(&tp, &ti);
        let normals: Vec<Vec3> = ti
            .chunks_exact(3)
            .map(|t| {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| tp[i as usize]);
                let n = (b - a).cross(c - a).normalize_or_zero();
                // Outward whichever way the triangle winds.
                if n.dot(a + b + c) < 0.0 { -n } else { n }
            })
            .collect();
        let (hp, _) = sphere(0.105, 24);
        let head_normals: Vec<Vec3> = hp.iter().map(|p| p.normalize()).collect();
        let anchor = Vec3::new(0.0, 0.0, 0.105);
        let mut points = hp.clone();
        let report = refine(
            &mut points,
            &head_normals,
            &bvh,
            &normals,
            &[anchor],
            &SCHEDULE,
        );
        assert!((report.median_before_mm - 5.0).abs() < 0.3, "{report:?}");
        assert!(report.median_after_mm < 1.0, "{report:?}");
        // Beside the anchor the pull is shared with it; far from it the points go all the
        // way.
        for (before, after) in hp.iter().zip(&points) {
            let moved = before.distance(*after);
            let from_anchor = before.distance(anchor);
            if from_anchor < 0.004 {
                assert!(moved < 3.0e-3, "{moved} m beside the anchor");
            } else if from_anchor > 0.1 {
                assert!(moved > 4.0e-3, "{moved} m far from the anchor");
            }
            assert!(moved < 6.0e-3, "{moved} m");
        }
        // Deterministic.
        let mut again = hp.clone();
        refine(
            &mut again,
            &head_normals,
            &bvh,
            &normals,
            &[anchor],
            &SCHEDULE,
        );
        assert_eq!(again, points);
    }
}
