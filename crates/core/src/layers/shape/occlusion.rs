//! The sky the aged shape hides (docs/models.md §13 "Occlusion"): per vertex, how much of
//! the sky it sees on the displaced mesh over how much it saw on the undisplaced one.
//!
//! A scan's colour map already holds the occlusion of its own shape (the skin in the crease
//! under the jaw was photographed darker), so the renderer multiplies the skin by the
//! ratio, not by the aged occlusion itself: the young head is drawn exactly as before, and
//! at old age only what the shape changed darkens (the cheek rolling over the nasolabial
//! fold, the jowl over the jaw, the bag over the lid–cheek junction, the wattle under the
//! chin) or lightens (a crease the shape fills).
//!
//! Visibility: [`RAYS`] rays over the cosine-weighted hemisphere about each position's
//! smooth normal (one fixed set, a Fibonacci spiral: the same directions at every vertex,
//! so neighbours differ only by their geometry, never by sampling noise), each occluded by
//! the first triangle it meets within [`REACH_MM`], weighted 1 at the skin and falling
//! linearly to 0 at the reach (a fold next to the skin darkens, the shoulder far below does
//! not). Per position, not per vertex: vertices split for a UV seam get one value.

use glam::Vec3;
use rayon::prelude::*;

use crate::head::fit::bvh::Bvh;
use crate::head::mesh::normals::{smooth_normals, weld_by_position};

/// Rays per position.
pub const RAYS: usize = 48;
/// How far an occluder counts, mm.
pub const REACH_MM: f32 = 25.0;
/// How far off the skin a ray starts, mm (past the skin's own triangles around it).
const START_MM: f32 = 0.2;
/// The least and most the ratio may be.
pub const RATIO_RANGE: (f32, f32) = (0.35, 1.25);
/// The sky added to both sides of the ratio: a vertex that saw almost none at rest (inside
/// the lids' seam, the mouth's slit) does not swing from the little it sees.
const RATIO_FLOOR: f32 = 0.15;

/// The ray directions about +Z: cosine-weighted (a Fibonacci spiral on the unit disk,
/// lifted onto the hemisphere).
fn directions() -> [Vec3; RAYS] {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    std::array::from_fn(|i| {
        let r = ((i as f32 + 0.5) / RAYS as f32).sqrt();
        let a = i as f32 * golden;
        Vec3::new(r * a.cos(), r * a.sin(), (1.0 - r * r).max(0.0).sqrt())
    })
}

/// How much of the sky (0–1, cosine-weighted) each vertex of the mesh `positions` ×
/// `indices` sees, for the vertices `wanted` says (the others: 1). `metres_per_unit`: the
/// mesh's unit.
pub fn sky_visibility(
    positions: &[Vec3],
    indices: &[u32],
    metres_per_unit: f32,
    wanted: &(dyn Fn(usize) -> bool + Sync),
) -> Vec<f32> {
    let n = positions.len();
    let mm = 1e-3 / metres_per_unit.max(1e-12);
    let (reach, start) = (REACH_MM * mm, START_MM * mm);
    let welded = weld_by_position(positions);
    let normals = smooth_normals(positions, indices);
    let bvh = Bvh::new(positions, indices);
    let dirs = directions();
    let mut out: Vec<f32> = (0..n)
        .into_par_iter()
        .map(|v| {
            if welded[v] as usize != v || !wanted(v) {
                return 1.0;
            }
            let (p, normal) = (positions[v], normals[v]);
            let (t, b) = normal.any_orthonormal_pair();
            let origin = p + normal * start;
            let hidden: f32 = dirs
                .iter()
                .map(|d| {
                    let dir = t * d.x + b * d.y + normal * d.z;
                    bvh.ray(origin, dir, 0.0, reach)
                        .map_or(0.0, |hit| 1.0 - hit / reach)
                })
                .sum();
            1.0 - hidden / RAYS as f32
        })
        .collect();
    // Split vertices take their position's first vertex's value.
    for v in 0..n {
        let w = welded[v] as usize;
        if w != v {
            out[v] = out[w];
        }
    }
    out
}

/// Triangles above which the sky is measured on a proxy of the mesh (about this many
/// triangles; [`crate::head::fit::proxy`]) and carried back to its vertices: the sky
/// changes over millimetres, a million-triangle scan's edges are a fraction of one.
pub const SKY_PROXY_TRIANGLES: usize = 40_000;

/// The full shape's ratio of sky ([`ratio`]) at each vertex of `positions` × `indices`
/// (smooth `normals`) moved by `full`; on a proxy when the mesh has more than
/// [`SKY_PROXY_TRIANGLES`] triangles.
pub fn full_ratio(
    positions: &[Vec3],
    normals: &[Vec3],
    indices: &[u32],
    full: &[Vec3],
    metres_per_unit: f32,
) -> Vec<f32> {
    full_ratio_with(
        positions,
        normals,
        indices,
        full,
        metres_per_unit,
        SKY_PROXY_TRIANGLES,
    )
}

fn full_ratio_with(
    positions: &[Vec3],
    normals: &[Vec3],
    indices: &[u32],
    full: &[Vec3],
    metres_per_unit: f32,
    proxy_triangles: usize,
) -> Vec<f32> {
    let proxy = crate::head::fit::proxy::of_triangles(positions, indices, proxy_triangles);
    let Some(proxy) = proxy else {
        // Only the skin near a movement can lose or gain sky.
        let near = near_movement(positions, full, metres_per_unit);
        let rest = sky_visibility(positions, indices, metres_per_unit, &|v| near[v]);
        let moved: Vec<Vec3> = positions.iter().zip(full).map(|(p, d)| *p + *d).collect();
        let aged = sky_visibility(&moved, indices, metres_per_unit, &|v| near[v]);
        return ratio(&aged, &rest);
    };
    let delta = proxy.gather(full);
    let near = near_movement(&proxy.positions, &delta, metres_per_unit);
    let rest = sky_visibility(&proxy.positions, &proxy.indices, metres_per_unit, &|v| {
        near[v]
    });
    let moved: Vec<Vec3> = (proxy.positions.iter().zip(&delta))
        .map(|(p, d)| *p + *d)
        .collect();
    let aged = sky_visibility(&moved, &proxy.indices, metres_per_unit, &|v| near[v]);
    let cluster_normals = smooth_normals(&proxy.positions, &proxy.indices);
    proxy.spread(&ratio(&aged, &rest), &cluster_normals, positions, normals)
}

/// The aged skin's sky over the rest's, per vertex ((aged + f)/(rest + f), f =
/// [`RATIO_FLOOR`]), within [`RATIO_RANGE`].
pub fn ratio(aged: &[f32], rest: &[f32]) -> Vec<f32> {
    aged.iter()
        .zip(rest)
        .map(|(&a, &r)| ((a + RATIO_FLOOR) / (r + RATIO_FLOOR)).clamp(RATIO_RANGE.0, RATIO_RANGE.1))
        .collect()
}

/// Which vertices lie within [`REACH_MM`] of a vertex that `delta` moves: the only ones
/// whose sky the shape can change (a grid of cells a reach wide over the moved ones).
pub fn near_movement(positions: &[Vec3], delta: &[Vec3], metres_per_unit: f32) -> Vec<bool> {
    let reach = REACH_MM * 1e-3 / metres_per_unit.max(1e-12);
    let cell = |p: Vec3| (p / reach).floor().as_ivec3();
    let moved: std::collections::HashSet<glam::IVec3> = positions
        .iter()
        .zip(delta)
        .filter(|(_, d)| **d != Vec3::ZERO)
        .map(|(p, _)| cell(*p))
        .collect();
    positions
        .iter()
        .map(|p| {
            let c = cell(*p);
            (-1..=1).any(|x| {
                (-1..=1).any(|y| (-1..=1).any(|z| moved.contains(&(c + glam::IVec3::new(x, y, z)))))
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat square of `n`² quads, side 2 (units), in z = 0, facing +z.
    fn plane(n: u32) -> (Vec<Vec3>, Vec<u32>) {
        let mut p = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                p.push(Vec3::new(
                    2.0 * i as f32 / n as f32 - 1.0,
                    2.0 * j as f32 / n as f32 - 1.0,
                    0.0,
                ));
            }
        }
        let mut idx = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let a = j * (n + 1) + i;
                idx.extend([a, a + 1, a + n + 2, a, a + n + 2, a + n + 1]);
            }
        }
        (p, idx)
    }

    /// On a proxy of an eighth of the triangles, the sky a ridge raised beside a dense
    /// plane's skin takes is the one measured on every vertex: within 0.03 on average,
    /// 0.12 at most, the darkest place as dark.
    #[test]
    fn the_sky_measured_on_a_proxy_is_the_mesh_s() {
        // Millimetres: the plane 40 mm across, a ridge 6 mm high along x = 0, 4 mm wide.
        let (p, idx) = plane(110);
        let p: Vec<Vec3> = p.iter().map(|q| *q * 20.0).collect();
        let full: Vec<Vec3> = p
            .iter()
            .map(|q| Vec3::Z * 6.0 * (-(q.x / 2.0).powi(2)).exp())
            .collect();
        let normals = vec![Vec3::Z; p.len()];
        let whole = full_ratio_with(&p, &normals, &idx, &full, 1e-3, usize::MAX);
        let coarse = full_ratio_with(&p, &normals, &idx, &full, 1e-3, idx.len() / 24);
        let diff: Vec<f32> = whole
            .iter()
            .zip(&coarse)
            .map(|(a, b)| (a - b).abs())
            .collect();
        let mean = diff.iter().sum::<f32>() / diff.len() as f32;
        let worst = diff.iter().copied().fold(0.0, f32::max);
        let darkest = |r: &[f32]| r.iter().copied().fold(f32::INFINITY, f32::min);
        assert!(
            darkest(&whole) < 0.9,
            "the ridge hides no sky: {}",
            darkest(&whole)
        );
        assert!(mean < 0.03 && worst < 0.12, "mean {mean}, worst {worst}");
        assert!((darkest(&whole) - darkest(&coarse)).abs() < 0.05);
    }

    #[test]
    fn the_directions_cover_the_hemisphere_cosine_weighted() {
        let d = directions();
        assert!(
            d.iter()
                .all(|v| (v.length() - 1.0).abs() < 1e-5 && v.z > 0.0)
        );
        // E[cos θ] over a cosine-weighted hemisphere is 2/3; the mean direction is +z.
        let mean = d.iter().copied().sum::<Vec3>() / RAYS as f32;
        assert!((mean.z - 2.0 / 3.0).abs() < 0.01, "{mean}");
        assert!(mean.x.abs() < 0.02 && mean.y.abs() < 0.02, "{mean}");
    }

    #[test]
    fn a_flat_plane_sees_the_whole_sky_and_a_fold_over_it_hides_some() {
        // A metre per unit: the reach is 25 mm, the plane 2 m across.
        let (p, idx) = plane(20);
        let open = sky_visibility(&p, &idx, 1.0, &|_| true);
        assert!(open.iter().all(|&v| v == 1.0), "{open:?}");
        // A lid 5 mm over the middle of the plane: the skin under it sees little sky, and
        // in units of millimetres the same (the reach is in mm).
        for (scale, mpu) in [(1.0, 1.0), (1000.0, 1e-3)] {
            let (mut p, mut idx) = plane(20);
            let base = p.len() as u32;
            let lid = [(-0.3, -0.3), (0.3, -0.3), (0.3, 0.3), (-0.3, 0.3)];
            p.extend(lid.map(|(x, y)| Vec3::new(x, y, 0.003) * scale));
            for q in &mut p[..base as usize] {
                *q *= scale;
            }
            idx.extend([base, base + 2, base + 1, base, base + 3, base + 2]);
            let sky = sky_visibility(&p, &idx, mpu, &|v| v < base as usize);
            let centre = 10 * 21 + 10;
            assert!(sky[centre] < 0.3, "{scale}: {}", sky[centre]);
            assert_eq!(sky[0], 1.0, "a corner of the plane, far from the lid");
            assert_eq!(sky[base as usize], 1.0, "not wanted");
        }
    }

    #[test]
    fn the_ratio_is_one_where_nothing_changed_and_bounded() {
        assert_eq!(ratio(&[0.5, 0.0], &[0.5, 0.0]), vec![1.0, 1.0]);
        assert_eq!(ratio(&[0.9, 0.0], &[0.3, 0.9]), vec![1.25, RATIO_RANGE.0]);
        // Little sky at rest: the floor keeps the ratio from swinging.
        let r = ratio(&[0.02], &[0.1])[0];
        assert!((r - 0.68).abs() < 1e-6, "{r}");
    }

    #[test]
    fn only_the_skin_near_a_movement_can_change() {
        // Metres: the reach is 25 mm; a vertex 10 mm from the moved one is near, 1 m is not.
        let p = [
            Vec3::ZERO,
            Vec3::new(0.01, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
        ];
        let d = [Vec3::Y * 0.002, Vec3::ZERO, Vec3::ZERO];
        assert_eq!(near_movement(&p, &d, 1.0), vec![true, true, false]);
        assert_eq!(near_movement(&p, &[Vec3::ZERO; 3], 1.0), vec![false; 3]);
    }
}
