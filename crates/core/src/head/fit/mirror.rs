//! The face's own mirror plane: the plane its skin is most nearly symmetric about, found on
//! the head itself (docs/models.md §7a, the automatic landmarks). The template's
//! midline, as aligned, is not quite the head's: the template (a scan) is itself a little
//! asymmetric, and on a symmetric head its x = 0 plane, carried over, lay 1–2 mm to one
//! side of the head's own: every pair of landmarks was shifted that way, the fit with it,
//! and the African woman's glabellar lines came out one deep and one faint.

use glam::{Mat3, Vec3};

use super::bvh::Bvh;

/// Refinement steps (each finds the mirrored points' closest skin again).
const ITERATIONS: usize = 12;
/// The share of point pairs kept each step (the farthest left out: an ear, a nostril
/// that has no mirror image).
const KEPT: f32 = 0.8;
/// The most the refined plane may turn from the start (degrees) or move along its normal
/// (as a share of the search's reach) before the start is kept instead: a face that has
/// no mirror plane near the template's keeps the template's.
const MAX_TURN_DEG: f32 = 12.0;
const MAX_SHIFT: f32 = 1.0;

/// A mirror plane: a point on it and its unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub origin: Vec3,
    pub normal: Vec3,
}

impl Plane {
    /// `p` mirrored in the plane.
    pub fn mirror(&self, p: Vec3) -> Vec3 {
        p - self.normal * (2.0 * (p - self.origin).dot(self.normal))
    }

    /// `p` put on the plane.
    pub fn project(&self, p: Vec3) -> Vec3 {
        p - self.normal * (p - self.origin).dot(self.normal)
    }
}

/// The plane the skin `points` are most nearly symmetric about, from `start`: each step
/// mirrors the points, takes the closest skin (`bvh`, its triangles' `normals`) within
/// `reach`, and moves and turns the plane so that the mirrored points come onto the skin's
/// tangent planes there (Gauss–Newton on the point-to-plane distances; the farthest fifth
/// left out). Returns the plane and the median distance of the mirrored points to the
/// skin; `start` (with its median) when too few points have a mirror image or the plane
/// would go further than [`MAX_TURN_DEG`] or [`MAX_SHIFT`] × `reach`.
pub fn refine(
    points: &[Vec3],
    bvh: &Bvh,
    normals: &[Vec3],
    start: Plane,
    reach: f32,
) -> (Plane, f32) {
    use rayon::prelude::*;
    let mut plane = start;
    let mut median = f32::INFINITY;
    let mut start_median = None;
    for _ in 0..ITERATIONS {
        let (u, v) = plane.normal.any_orthonormal_pair();
        // In parallel, in the points' order: the same rows on any thread count.
        let mut rows: Vec<([f32; 3], f32, f32)> = points
            .par_iter()
            .with_min_len(64)
            .filter_map(|&p| {
                let m = plane.mirror(p);
                let hit = bvh.closest(m, reach)?;
                let nq = *normals.get(hit.triangle as usize)?;
                let off = p - plane.origin;
                // How the mirrored point moves with the plane's shift along its normal and
                // its turn toward u and v, along the skin's normal there.
                let along = |d: Vec3| d.dot(nq);
                let j = [
                    along(plane.normal * 2.0),
                    along(-2.0 * (plane.normal * off.dot(u) + u * off.dot(plane.normal))),
                    along(-2.0 * (plane.normal * off.dot(v) + v * off.dot(plane.normal))),
                ];
                Some((j, (m - hit.point).dot(nq), hit.distance))
            })
            .collect();
        if rows.len() < 30 {
            return (start, median);
        }
        rows.sort_by(|a, b| a.2.total_cmp(&b.2));
        median = rows[rows.len() / 2].2;
        start_median.get_or_insert(median);
        rows.truncate(((rows.len() as f32) * KEPT) as usize);
        let (mut jtj, mut jtr) = (Mat3::ZERO, Vec3::ZERO);
        for (j, r, _) in &rows {
            let j = Vec3::from(*j);
            jtj += Mat3::from_cols(j * j.x, j * j.y, j * j.z);
            jtr += j * *r;
        }
        let det = jtj.determinant();
        if det == 0.0 || !det.is_finite() {
            break;
        }
        let x = -(jtj.inverse() * jtr);
        if !x.is_finite() {
            break;
        }
        plane = Plane {
            origin: plane.origin + plane.normal * x.x,
            normal: (plane.normal + u * x.y + v * x.z).normalize(),
        };
        if x.x.abs() < 1e-4 * reach && x.y.abs() + x.z.abs() < 1e-5 {
            break;
        }
    }
    let turned = plane
        .normal
        .dot(start.normal)
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees();
    let shifted = (plane.origin - start.origin).dot(start.normal).abs();
    if !(turned <= MAX_TURN_DEG && shifted <= MAX_SHIFT * reach) {
        return (start, start_median.unwrap_or(median));
    }
    (plane, median)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bumpy surface symmetric about x = 0.3 (a face-like height field), its plane found
    /// from a start 4 mm off and 5° turned.
    #[test]
    fn the_plane_of_a_symmetric_surface_is_found_from_a_start_beside_it() {
        let (n, size) = (60, 0.16f32);
        let height = |x: f32, y: f32| {
            let d = x - 0.3;
            0.03 * (-(d * d) / 0.002).exp() + 0.01 * (y * 40.0).sin() * (d * 30.0).cos()
                - 2.0 * d * d
        };
        let mut positions = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let x = 0.3 - size / 2.0 + size * i as f32 / (n - 1) as f32;
                let y = -size / 2.0 + size * j as f32 / (n - 1) as f32;
                positions.push(Vec3::new(x, y, height(x, y)));
            }
        }
        let mut indices = Vec::new();
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let k = (j * n + i) as u32;
                let n = n as u32;
                indices.extend_from_slice(&[k, k + 1, k + n, k + 1, k + n + 1, k + n]);
            }
        }
        let normals: Vec<Vec3> = indices
            .chunks_exact(3)
            .map(|t| {
                let p = |k: usize| positions[t[k] as usize];
                (p(1) - p(0)).cross(p(2) - p(0)).normalize()
            })
            .collect();
        let bvh = Bvh::new(&positions, &indices);
        let start = Plane {
            origin: Vec3::new(0.304, 0.0, 0.0),
            normal: glam::Quat::from_rotation_y(5f32.to_radians()) * Vec3::X,
        };
        // The middle of the patch (its mirror images inside it).
        let points: Vec<Vec3> = positions
            .iter()
            .copied()
            .filter(|p| (p.x - 0.3).abs() < 0.06 && p.y.abs() < 0.07)
            .collect();
        let (plane, median) = refine(&points, &bvh, &normals, start, 0.01);
        assert!(plane.normal.dot(Vec3::X) > 0.99999, "{plane:?}");
        let off = (Vec3::new(0.3, 0.0, 0.0) - plane.origin).dot(plane.normal);
        assert!(off.abs() < 2e-4, "{off} {plane:?}");
        assert!(median < 2e-4, "{median}");
    }
}
