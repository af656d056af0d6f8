//! A thin-plate spline in 3D: the smoothest warp (least bending energy, kernel
//! φ(r) = r, the biharmonic one in three dimensions) that takes a few control points to
//! their targets, plus an affine part that carries everything far from them.
//!
//! f(x) = A x + b + Σᵢ wᵢ φ(|x − cᵢ|), solved from the (n + 4)² system
//! [K + λI, P; Pᵀ, 0] [w; a] = [y; 0] by Gaussian elimination (n ≤ a few dozen).
//! λ > 0 relaxes the interpolation for points placed with some error.

use glam::{DVec3, Vec3};

/// A solved warp.
#[derive(Clone, Debug)]
pub struct ThinPlate {
    centres: Vec<DVec3>,
    /// One weight vector per centre.
    weights: Vec<DVec3>,
    /// The affine part: rows x, y, z, 1 of a 4 × 3 matrix.
    affine: [DVec3; 4],
}

impl ThinPlate {
    /// The warp taking `from[i]` to `to[i]`, smoothed by `lambda` (in units of the
    /// kernel, i.e. of distance). `None` with fewer than four points or a singular
    /// system (all points on one plane leave the affine part undetermined).
    pub fn fit(from: &[Vec3], to: &[Vec3], lambda: f32) -> Option<Self> {
        let n = from.len().min(to.len());
        if n < 4 {
            return None;
        }
        let c: Vec<DVec3> = from[..n].iter().map(|p| p.as_dvec3()).collect();
        let size = n + 4;
        let mut m = vec![0.0f64; size * size];
        let mut rhs = vec![DVec3::ZERO; size];
        for i in 0..n {
            for j in 0..n {
                m[i * size + j] = c[i].distance(c[j]);
            }
            m[i * size + i] += f64::from(lambda);
            let p = [c[i].x, c[i].y, c[i].z, 1.0];
            for (k, v) in p.iter().enumerate() {
                m[i * size + n + k] = *v;
                m[(n + k) * size + i] = *v;
            }
            rhs[i] = to[i].as_dvec3();
        }
        let x = solve(&mut m, &mut rhs, size)?;
        Some(Self {
            centres: c,
            weights: x[..n].to_vec(),
            affine: [x[n], x[n + 1], x[n + 2], x[n + 3]],
        })
    }

    pub fn apply(&self, p: Vec3) -> Vec3 {
        let q = p.as_dvec3();
        let a = &self.affine;
        let mut out = a[0] * q.x + a[1] * q.y + a[2] * q.z + a[3];
        for (c, w) in self.centres.iter().zip(&self.weights) {
            out += *w * c.distance(q);
        }
        out.as_vec3()
    }
}

/// Solves m x = rhs (row-major `size × size`) by Gaussian elimination with partial
/// pivoting; `None` when singular.
fn solve(m: &mut [f64], rhs: &mut [DVec3], size: usize) -> Option<Vec<DVec3>> {
    let scale = m.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
    for col in 0..size {
        let pivot = (col..size)
            .max_by(|&a, &b| m[a * size + col].abs().total_cmp(&m[b * size + col].abs()))?;
        if m[pivot * size + col].abs() < 1e-12 * scale {
            return None;
        }
        if pivot != col {
            for k in 0..size {
                m.swap(pivot * size + k, col * size + k);
            }
            rhs.swap(pivot, col);
        }
        let d = m[col * size + col];
        for row in col + 1..size {
            let f = m[row * size + col] / d;
            if f == 0.0 {
                continue;
            }
            for k in col..size {
                m[row * size + k] -= f * m[col * size + k];
            }
            let r = rhs[col];
            rhs[row] -= r * f;
        }
    }
    let mut x = vec![DVec3::ZERO; size];
    for row in (0..size).rev() {
        let mut acc = rhs[row];
        for k in row + 1..size {
            acc -= x[k] * m[row * size + k];
        }
        x[row] = acc / m[row * size + row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn points() -> Vec<Vec3> {
        (0..12)
            .map(|i| {
                let f = i as f32;
                Vec3::new((f * 1.3).sin(), (f * 0.7).cos(), (f * 2.1).sin() * 0.5)
            })
            .collect()
    }

    #[test]
    fn the_control_points_land_on_their_targets_and_an_affine_map_is_kept() {
        let from = points();
        let to: Vec<Vec3> = from
            .iter()
            .enumerate()
            .map(|(i, p)| *p * 1.5 + Vec3::new(0.1, 0.0, (i as f32 * 0.37).sin() * 0.05))
            .collect();
        let tps = ThinPlate::fit(&from, &to, 0.0).unwrap();
        for (a, b) in from.iter().zip(&to) {
            assert!(tps.apply(*a).distance(*b) < 1e-4);
        }
        // An affine target is reproduced everywhere, not only at the points.
        let affine: Vec<Vec3> = from.iter().map(|p| *p * 2.0 - Vec3::Y).collect();
        let tps = ThinPlate::fit(&from, &affine, 0.0).unwrap();
        let q = Vec3::new(3.0, -2.0, 0.7);
        assert!(tps.apply(q).distance(q * 2.0 - Vec3::Y) < 1e-3);
    }

    #[test]
    fn points_on_one_plane_are_refused() {
        let flat: Vec<Vec3> = points().iter().map(|p| p.with_z(0.0)).collect();
        assert!(ThinPlate::fit(&flat, &flat, 0.0).is_none());
        assert!(ThinPlate::fit(&flat[..3], &flat[..3], 0.0).is_none());
    }
}
