//! The similarity (scale, rotation, translation) that best takes one point set onto
//! another in the least-squares sense: Umeyama's estimate, with the rotation found by
//! Horn's unit-quaternion method (the largest eigenvector of a symmetric 4 × 4 matrix,
//! by Jacobi rotations) — no SVD needed, never a reflection.

use glam::{DMat3, DQuat, DVec3, Mat3, Quat, Vec3};

/// x ↦ scale · R x + translation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Similarity {
    pub scale: f32,
    pub rotation: Quat,
    pub translation: Vec3,
}

impl Similarity {
    pub const IDENTITY: Self = Self {
        scale: 1.0,
        rotation: Quat::IDENTITY,
        translation: Vec3::ZERO,
    };

    pub fn apply(&self, p: Vec3) -> Vec3 {
        self.rotation * p * self.scale + self.translation
    }

    /// A direction turned (not scaled, not moved).
    pub fn turn(&self, d: Vec3) -> Vec3 {
        self.rotation * d
    }

    pub fn inverse(&self) -> Self {
        let r = self.rotation.inverse();
        let s = 1.0 / self.scale;
        Self {
            scale: s,
            rotation: r,
            translation: -(r * self.translation) * s,
        }
    }

    /// `self` after `first`.
    pub fn after(&self, first: &Self) -> Self {
        Self {
            scale: self.scale * first.scale,
            rotation: self.rotation * first.rotation,
            translation: self.apply(first.translation),
        }
    }

    /// The least-squares similarity taking `from[i]` to `to[i]` with weights `weight[i]`
    /// (all 1 when empty). `None` with fewer than three points, when the `from` points
    /// coincide or the weights sum to nothing.
    pub fn fit(from: &[Vec3], to: &[Vec3], weight: &[f32]) -> Option<Self> {
        let n = from.len().min(to.len());
        let w = |i: usize| weight.get(i).map_or(1.0, |&w| f64::from(w));
        let total: f64 = (0..n).map(w).sum();
        if n < 3 || total <= 0.0 || !total.is_finite() {
            return None;
        }
        let d = |v: Vec3| v.as_dvec3();
        let ca = (0..n).map(|i| d(from[i]) * w(i)).sum::<DVec3>() / total;
        let cb = (0..n).map(|i| d(to[i]) * w(i)).sum::<DVec3>() / total;
        let mut m = DMat3::ZERO;
        let mut var_a = 0.0;
        for i in 0..n {
            let (a, b) = (d(from[i]) - ca, d(to[i]) - cb);
            // m = Σ w a bᵀ
            m += DMat3::from_cols(a * b.x, a * b.y, a * b.z) * w(i);
            var_a += w(i) * a.length_squared();
        }
        if var_a <= 1e-30 {
            return None;
        }
        let rotation = horn_rotation(&m)?;
        let mut dot = 0.0;
        for i in 0..n {
            let (a, b) = (d(from[i]) - ca, d(to[i]) - cb);
            dot += w(i) * b.dot(rotation * a);
        }
        let scale = dot / var_a;
        if !(scale > 0.0 && scale.is_finite()) {
            return None;
        }
        let translation = cb - rotation * ca * scale;
        Some(Self {
            scale: scale as f32,
            rotation: rotation.as_quat().normalize(),
            translation: translation.as_vec3(),
        })
    }

    /// As a 3 × 3 linear part (scale · R).
    pub fn linear(&self) -> Mat3 {
        Mat3::from_quat(self.rotation) * self.scale
    }
}

/// Horn's method: with S = m (Σ a bᵀ), the quaternion maximising Σ b · R a is the
/// eigenvector of N's largest eigenvalue.
fn horn_rotation(m: &DMat3) -> Option<DQuat> {
    // s[i][j] = Σ a_i b_j
    let s = |i: usize, j: usize| m.col(j)[i];
    let (sxx, sxy, sxz) = (s(0, 0), s(0, 1), s(0, 2));
    let (syx, syy, syz) = (s(1, 0), s(1, 1), s(1, 2));
    let (szx, szy, szz) = (s(2, 0), s(2, 1), s(2, 2));
    let n = [
        [sxx + syy + szz, syz - szy, szx - sxz, sxy - syx],
        [syz - szy, sxx - syy - szz, sxy + syx, szx + sxz],
        [szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy],
        [sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz],
    ];
    let (values, vectors) = jacobi4(n);
    let best = (0..4).max_by(|&a, &b| values[a].total_cmp(&values[b]))?;
    let q = [0, 1, 2, 3].map(|r| vectors[r][best]);
    // (w, x, y, z)
    let quat = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
    let len = quat.length();
    (len > 0.0 && len.is_finite()).then(|| quat / len)
}

/// Eigenvalues and eigenvectors (columns) of a symmetric 4 × 4 matrix, by cyclic Jacobi.
fn jacobi4(mut a: [[f64; 4]; 4]) -> ([f64; 4], [[f64; 4]; 4]) {
    let mut v = [[0.0; 4]; 4];
    for (i, row) in v.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for _sweep in 0..50 {
        let off: f64 = (0..4)
            .flat_map(|i| (0..4).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        if off < 1e-30 {
            break;
        }
        for p in 0..3 {
            for q in p + 1..4 {
                if a[p][q].abs() < 1e-300 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for row in &mut a {
                    let (akp, akq) = (row[p], row[q]);
                    row[p] = c * akp - s * akq;
                    row[q] = s * akp + c * akq;
                }
                let (row_p, row_q) = (a[p], a[q]);
                for k in 0..4 {
                    a[p][k] = c * row_p[k] - s * row_q[k];
                    a[q][k] = s * row_p[k] + c * row_q[k];
                }
                for row in &mut v {
                    let (vp, vq) = (row[p], row[q]);
                    row[p] = c * vp - s * vq;
                    row[q] = s * vp + c * vq;
                }
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2], a[3][3]], v)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_known_similarity_is_recovered() {
        let truth = Similarity {
            scale: 0.0528,
            rotation: Quat::from_euler(glam::EulerRot::YXZ, 2.1, -0.4, 0.9),
            translation: Vec3::new(0.3, -1.2, 4.0),
        };
        let from: Vec<Vec3> = (0..16)
            .map(|i| {
                let f = i as f32;
                Vec3::new((f * 1.7).sin(), (f * 0.9).cos() * 2.0, f * 0.1 - 0.5)
            })
            .collect();
        let to: Vec<Vec3> = from.iter().map(|&p| truth.apply(p)).collect();
        let got = Similarity::fit(&from, &to, &[]).unwrap();
        for (a, b) in from.iter().zip(&to) {
            assert!(got.apply(*a).distance(*b) < 1e-5, "{got:?}");
        }
        assert!((got.scale - truth.scale).abs() < 1e-5);
        let back = got.inverse();
        assert!(back.apply(to[3]).distance(from[3]) < 1e-4);
        assert!(got.after(&back).apply(to[5]).distance(to[5]) < 1e-4);
    }

    #[test]
    fn too_few_or_collinear_points_give_none() {
        let line: Vec<Vec3> = (0..5).map(|i| Vec3::X * i as f32).collect();
        assert!(Similarity::fit(&line[..2], &line[..2], &[]).is_none());
        // Collinear: the rotation about the line is free, but a fit still exists.
        assert!(Similarity::fit(&line, &line, &[]).is_some());
        let same = vec![Vec3::ONE; 4];
        assert!(Similarity::fit(&same, &line[..4], &[]).is_none());
    }
}
