//! A dense head's shape settled on a coarser stand-in (docs/models.md §13 "A dense
//! head"). Keeping the skin clear of the skin, unfolding it and evening the cuts out,
//! made on the triangles of a million-triangle scan (a third of a millimetre wide), took
//! most of what the regions move: on the scan split three times 4 % of the vertices moved
//! more than 1 mm at 85, 17 % on the scan split once, the temples and the mid-face all
//! but still, and the cheek beside one nasolabial fold cut into a plate; and they took 7
//! of the 9.5 s its shape cost. So on a head whose triangles are fine
//! ([`settles_on_stand_in`]) the cuts are made on a stand-in whose vertices lie about
//! [`COARSE_CUBE_MM`] apart (the fit's proxy, its vertex clustering, the skin and what is
//! not skin never in one cluster, so a lid does not carry the eyeball it touches): each
//! cluster takes the mean of its vertices' moves, the stand-in is settled, and what that
//! changed is carried back to the head's vertices smoothly over the clusters round each
//! and added to their own moves; what still folds on the head's own finer triangles is
//! then unfolded there, which costs little once the wide folds are gone. (Carrying the
//! stand-in's moves whole, not the change, left a crumpled jowl; a stand-in of 1–2 mm,
//! lumps and dark lines on the cheeks.)

use glam::Vec3;
use rayon::prelude::*;

use super::settle;
use crate::head::fit::proxy::{Proxy, clustered, mean_edge};
use crate::head::mesh::normals::smooth_normals;

/// The stand-in's cube, mm: about the triangles of the scan split once (70k triangles,
/// its mean edge 3 mm), whose shape ages whole and smoothly.
pub const COARSE_CUBE_MM: f32 = 4.0;

/// Whether a head whose triangles' mean edge is `mean_edge_mm` is settled on a stand-in:
/// where the stand-in's cube is at least twice as long (the scan split twice, 1.5 mm, and
/// the dense panel head, 1.5 mm, are; the scan split once, 3 mm, and every coarser head
/// are settled whole).
pub fn settles_on_stand_in(mean_edge_mm: f32) -> bool {
    mean_edge_mm > 0.0 && COARSE_CUBE_MM >= 2.0 * mean_edge_mm
}

/// The stand-in of the mesh of `positions` and `indices` (`skin` per vertex, `mm` a
/// millimetre in its units): its vertices clustered in [`COARSE_CUBE_MM`] cubes, skin and
/// not skin apart; `None` where its triangles are not fine enough ([`settles_on_stand_in`]).
fn stand_in(positions: &[Vec3], indices: &[u32], skin: &[bool], mm: f32) -> Option<Proxy> {
    let edge_mm = mean_edge(positions, indices) / mm;
    if !(mm > 0.0 && settles_on_stand_in(edge_mm)) {
        return None;
    }
    Some(clustered(
        positions,
        indices,
        COARSE_CUBE_MM * mm,
        Some(skin),
    ))
}

/// The mean of the points there are over each cluster of `proxy` (`None` where none is).
fn gather_points(proxy: &Proxy, points: &[Option<Vec3>]) -> Vec<Option<Vec3>> {
    let mut sums = vec![(Vec3::ZERO, 0u32); proxy.positions.len()];
    for (&c, p) in proxy.cluster_of_vertex.iter().zip(points) {
        if let (Some(s), Some(p)) = (sums.get_mut(c as usize), p) {
            s.0 += *p;
            s.1 += 1;
        }
    }
    sums.iter()
        .map(|&(s, n)| (n > 0).then(|| s / n as f32))
        .collect()
}

/// Adds to `full` (per region, per vertex of the head at `positions` with its normals
/// `vertex_normals`, the vertices at one position `welded` together) the clusters'
/// `moves` (per region, per cluster of `proxy`; their normals `normals`) carried to each
/// vertex by [`Proxy::weights`], its own cluster's where none reaches.
fn add_spread(
    proxy: &Proxy,
    moves: &[Vec<Vec3>],
    normals: &[Vec3],
    positions: &[Vec3],
    vertex_normals: &[Vec3],
    welded: &[u32],
    full: &mut [Vec<Vec3>],
) {
    let regions = moves.len();
    let moved: Vec<bool> = (0..regions)
        .map(|r| moves[r].iter().any(|d| *d != Vec3::ZERO))
        .collect();
    let mut out = vec![Vec3::ZERO; positions.len() * regions];
    out.par_chunks_mut(regions)
        .enumerate()
        .for_each(|(v, row)| {
            let own = proxy.cluster_of_vertex[v];
            if welded[v] as usize != v || own == u32::MAX {
                return;
            }
            let (mut weights, mut count, mut total) =
                proxy.weights(positions[v], vertex_normals[v], own, normals);
            if total <= 0.0 {
                weights[0] = (own, 1.0);
                (count, total) = (1, 1.0);
            }
            for (r, out) in row.iter_mut().enumerate() {
                if moved[r] {
                    *out = weights[..count]
                        .iter()
                        .map(|&(c, w)| moves[r][c as usize] * w)
                        .sum::<Vec3>()
                        / total;
                }
            }
        });
    for (r, f) in full.iter_mut().enumerate() {
        if moved[r] {
            for v in 0..f.len() {
                f[v] += out[welded[v] as usize * regions + r];
            }
        }
    }
}

/// Settles `full` (per region, per vertex of the mesh of `positions` and `indices`, the
/// vertices at one position `welded` together, `skin` per vertex, `smooth` its smooth
/// normals, `points` each vertex's place in the face frame, `mm` a millimetre in its
/// units) on a stand-in when the head's triangles are fine (see the module docs), then
/// unfolds what still folds on the head itself. `false` (nothing done) on a coarser head
/// ([`settles_on_stand_in`]): settle it whole ([`settle::settle`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn settle(
    positions: &[Vec3],
    indices: &[u32],
    welded: &[u32],
    skin: &[bool],
    smooth: &[Vec3],
    full: &mut [Vec<Vec3>],
    points: &[Option<Vec3>],
    mm: f32,
) -> bool {
    let Some(coarse) = stand_in(positions, indices, skin, mm) else {
        return false;
    };
    let mut moves: Vec<Vec<Vec3>> = full.iter().map(|f| coarse.gather(f)).collect();
    let before = moves.clone();
    let identity: Vec<u32> = (0..coarse.positions.len() as u32).collect();
    let normals = smooth_normals(&coarse.positions, &coarse.indices);
    settle::settle(
        &coarse.positions,
        &coarse.indices,
        &identity,
        &normals,
        &mut moves,
        &gather_points(&coarse, points),
        mm,
        None,
    );
    // What the cuts changed, carried to the head's vertices: its own moves keep what its
    // finer triangles carry (carrying the stand-in's moves whole left a crumpled jowl).
    let change: Vec<Vec<Vec3>> = moves
        .iter()
        .zip(&before)
        .map(|(a, b)| a.iter().zip(b).map(|(a, b)| *a - *b).collect())
        .collect();
    add_spread(&coarse, &change, &normals, positions, smooth, welded, full);
    // Each round of unfolding can leave a fold next to one it spread (a few hundred
    // vertices of the scan split three times after the first).
    settle::unfold_only(positions, indices, welded, full, mm, UNFOLD_ROUNDS);
    true
}

/// See [`settle`].
const UNFOLD_ROUNDS: usize = 4;
