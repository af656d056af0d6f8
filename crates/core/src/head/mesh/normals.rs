//! Smooth vertex normals for meshes that have none.
//!
//! Each triangle adds its unit face normal weighted by the corner angle at the vertex
//! (Thürmer & Wüthrich 1998: "angle-weighted" normals, independent of how a surface is
//! triangulated, unlike pure area weighting which lets long thin triangles dominate).
//! Vertices at the same position (split for UV seams) share their sum, so seams do not
//! show in the shading.

use std::collections::HashMap;

use glam::Vec3;

/// One unit normal per vertex of `positions` for the triangle list `indices` (all
/// indices must be in range; [`super::Mesh::build`] ensures it). A vertex used by no
/// triangle, or only by zero-area ones, gets +Z.
pub fn smooth_normals(positions: &[Vec3], indices: &[u32]) -> Vec<Vec3> {
    let welded = weld_by_position(positions);
    let mut sums = vec![Vec3::ZERO; positions.len()];
    for t in indices.chunks_exact(3) {
        let p = [t[0], t[1], t[2]].map(|i| positions[i as usize]);
        let Some(face) = (p[1] - p[0]).cross(p[2] - p[0]).try_normalize() else {
            continue;
        };
        for k in 0..3 {
            let e1 = p[(k + 1) % 3] - p[k];
            let e2 = p[(k + 2) % 3] - p[k];
            let angle = e1.angle_between(e2);
            if angle.is_finite() {
                sums[welded[t[k] as usize] as usize] += face * angle;
            }
        }
    }
    welded
        .iter()
        .map(|&w| sums[w as usize].try_normalize().unwrap_or(Vec3::Z))
        .collect()
}

/// For each vertex, the index of the first vertex with bit-identical position.
pub fn weld_by_position(positions: &[Vec3]) -> Vec<u32> {
    let mut first: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            // +0.0 and −0.0 are the same point.
            let key = (*p + Vec3::ZERO).to_array().map(f32::to_bits);
            *first.entry(key).or_insert(i as u32)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::head::mesh::test_util::assert_vec_close;

    #[test]
    fn a_flat_fan_gets_the_plane_normal() {
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        let n = smooth_normals(&p, &[0, 1, 2, 0, 2, 3]);
        for v in n {
            assert_vec_close(v, Vec3::Z, 1e-6, "normal");
        }
    }

    #[test]
    fn the_corner_of_a_cube_points_along_the_diagonal_whatever_the_triangulation() {
        // Three faces of a cube meeting at the origin, seen from outside (the cube is in
        // the negative octant), the +X face split into two triangles and the others one:
        // angle weighting still gives the symmetric diagonal; area weighting would not.
        let p = vec![
            Vec3::ZERO,
            Vec3::new(0.0, -1.0, 0.0),
            Vec3::new(0.0, -1.0, -1.0),
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(-1.0, 0.0, 0.0),
        ];
        let idx = [
            0, 1, 2, 0, 2, 3, // x = 0 face, two triangles of 45° at the corner (normal +X)
            0, 3, 4, // y = 0 face, one triangle of 90° (normal +Y)
            0, 4, 1, // z = 0 face, one triangle of 90° (normal +Z)
        ];
        let n = smooth_normals(&p, &idx);
        assert_vec_close(n[0], Vec3::ONE.normalize(), 1e-5, "corner normal");
    }

    #[test]
    fn split_vertices_at_one_position_share_the_normal() {
        // A ridge: two triangles at 90°, the shared edge's vertices duplicated.
        let p = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(0.0, 1.0, -1.0),
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(0.0, -1.0, -1.0),
        ];
        let n = smooth_normals(&p, &[0, 1, 2, 3, 5, 4]);
        assert_vec_close(n[0], n[3], 0.0, "welded");
        assert_vec_close(n[0], Vec3::Z, 1e-6, "ridge normal");
    }
}
