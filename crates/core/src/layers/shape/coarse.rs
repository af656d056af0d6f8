//! A dense head's shape settled on a coarser stand-in (docs/models.md §13 "A dense
//! head"). Keeping the skin clear of the skin, unfolding it and evening the cuts out,
//! made on the triangles of a million-triangle scan (a third of a millimetre wide), took
//! most of what the regions move: on the scan split three times 4 % of the vertices moved
//! more than 1 mm at 85, 17 % on the scan split once, the temples and the mid-face all
//! but still, and the cheek beside one nasolabial fold cut into a plate; and they took 7
//! of the 9.5 s its shape cost. So on a head whose triangles are fine
//! ([`settles_on_stand_in`]) the cuts are made on a stand-in whose vertices lie about [`COARSE_CUBE_MM`]
//! apart (vertex clustering, as the fit's proxy; the skin and what is not skin never in
//! one cluster, so a lid does not carry the eyeball it touches): each cluster takes the
//! mean of its vertices' moves, the stand-in is settled, and what that changed is carried
//! back to the head's vertices smoothly over the clusters round each and added to their
//! own moves; what still folds on the head's own finer triangles is then unfolded there,
//! which costs little once the wide folds are gone. (Carrying the stand-in's moves whole,
//! not the change, left a crumpled jowl; a stand-in of 1–2 mm, lumps and dark lines on
//! the cheeks.)

use glam::Vec3;
use rayon::prelude::*;

use super::settle;
use crate::base::cells::{CubeMap, cube_of};
use crate::head::fit::proxy::mean_edge;
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

/// The stand-in: each cluster's mean position, its triangles, the cluster of each vertex
/// of the head, and the clusters by cube (skin and not skin apart).
struct Coarse {
    positions: Vec<Vec3>,
    indices: Vec<u32>,
    cluster_of_vertex: Vec<u32>,
    /// Whether each cluster is of skin (its map in `cluster_of_cube`).
    skin: Vec<bool>,
    cube: f32,
    cluster_of_cube: [CubeMap<u32>; 2],
}

impl Coarse {
    /// The stand-in of the mesh of `positions` and `indices` (`skin` per vertex, `mm` a
    /// millimetre in its units); `None` where its triangles are not fine enough
    /// ([`settles_on_stand_in`]).
    fn of(positions: &[Vec3], indices: &[u32], skin: &[bool], mm: f32) -> Option<Self> {
        let edge_mm = mean_edge(positions, indices) / mm;
        if !(mm > 0.0 && settles_on_stand_in(edge_mm)) {
            return None;
        }
        let cube = COARSE_CUBE_MM * mm;
        // Clusters numbered in the order their first vertex is met: the same stand-in on
        // any machine.
        let mut cluster_of_cube: [CubeMap<u32>; 2] = Default::default();
        let mut cluster_of_vertex = vec![u32::MAX; positions.len()];
        let mut sums: Vec<(Vec3, u32)> = Vec::new();
        let mut of_skin: Vec<bool> = Vec::new();
        let mut kept = Vec::with_capacity(indices.len() / 2);
        for t in indices.chunks_exact(3) {
            let mut corner = [0u32; 3];
            for (k, &v) in t.iter().enumerate() {
                let v = v as usize;
                if cluster_of_vertex[v] == u32::MAX {
                    let p = positions[v];
                    let next = sums.len() as u32;
                    let map = &mut cluster_of_cube[usize::from(skin[v])];
                    let c = *map.entry(cube_of(p, cube)).or_insert(next);
                    if c == next {
                        sums.push((Vec3::ZERO, 0));
                        of_skin.push(skin[v]);
                    }
                    sums[c as usize].0 += p;
                    sums[c as usize].1 += 1;
                    cluster_of_vertex[v] = c;
                }
                corner[k] = cluster_of_vertex[v];
            }
            if corner[0] != corner[1] && corner[1] != corner[2] && corner[0] != corner[2] {
                kept.extend_from_slice(&corner);
            }
        }
        Some(Self {
            positions: sums.iter().map(|&(s, n)| s / n as f32).collect(),
            indices: kept,
            cluster_of_vertex,
            skin: of_skin,
            cube,
            cluster_of_cube,
        })
    }

    /// The mean of `per_vertex` over each cluster.
    fn gather(&self, per_vertex: &[Vec3]) -> Vec<Vec3> {
        let mut sums = vec![(Vec3::ZERO, 0u32); self.positions.len()];
        for (&c, &d) in self.cluster_of_vertex.iter().zip(per_vertex) {
            if let Some(s) = sums.get_mut(c as usize) {
                s.0 += d;
                s.1 += 1;
            }
        }
        sums.iter().map(|&(s, n)| s / n.max(1) as f32).collect()
    }

    /// The mean of the points there are over each cluster (`None` where none is).
    fn gather_points(&self, points: &[Option<Vec3>]) -> Vec<Option<Vec3>> {
        let mut sums = vec![(Vec3::ZERO, 0u32); self.positions.len()];
        for (&c, p) in self.cluster_of_vertex.iter().zip(points) {
            if let (Some(s), Some(p)) = (sums.get_mut(c as usize), p) {
                s.0 += *p;
                s.1 += 1;
            }
        }
        sums.iter()
            .map(|&(s, n)| (n > 0).then(|| s / n as f32))
            .collect()
    }

    /// Sets `full` (per region, per vertex of the head at `positions` with its normals
    /// `vertex_normals`, the vertices at one position `welded` together) from the
    /// clusters' `moves` (per region, per cluster; their normals `normals`): at each vertex
    /// the clusters of its kind (skin or not) in the 27 cubes round it, weighted by a tent of 1.5
    /// cubes over their distance and by how alike they face (a lip takes nothing from the
    /// lip it touches); its own cluster's where none reaches.
    fn spread(
        &self,
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
        let radius = 1.5 * self.cube;
        let mut add = vec![Vec3::ZERO; positions.len() * regions];
        add.par_chunks_mut(regions)
            .enumerate()
            .for_each(|(v, row)| {
                let own = self.cluster_of_vertex[v];
                if welded[v] as usize != v || own == u32::MAX {
                    return;
                }
                let (p, n) = (positions[v], vertex_normals[v]);
                let class = usize::from(self.skin[own as usize]);
                let home = (p / self.cube).floor().as_ivec3();
                let mut weights = [(0u32, 0.0f32); 27];
                let (mut count, mut total) = (0, 0.0f32);
                for z in -1..=1 {
                    for y in -1..=1 {
                        for x in -1..=1 {
                            let key = (home + glam::IVec3::new(x, y, z)).to_array();
                            let Some(&c) = self.cluster_of_cube[class].get(&key) else {
                                continue;
                            };
                            let near =
                                (1.0 - self.positions[c as usize].distance(p) / radius).max(0.0);
                            let w = near * near * normals[c as usize].dot(n).max(0.0);
                            if w > 0.0 {
                                weights[count] = (c, w);
                                count += 1;
                                total += w;
                            }
                        }
                    }
                }
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
            for v in 0..f.len() {
                f[v] = add[welded[v] as usize * regions + r];
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
    let Some(coarse) = Coarse::of(positions, indices, skin, mm) else {
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
        &coarse.gather_points(points),
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
    let mut carried: Vec<Vec<Vec3>> = full.iter().map(|f| vec![Vec3::ZERO; f.len()]).collect();
    coarse.spread(&change, &normals, positions, smooth, welded, &mut carried);
    for (f, c) in full.iter_mut().zip(&carried) {
        for (f, c) in f.iter_mut().zip(c) {
            *f += *c;
        }
    }
    // Each round of unfolding can leave a fold next to one it spread (a few hundred
    // vertices of the scan split three times after the first).
    for _ in 0..UNFOLD_ROUNDS {
        if settle::unfold_only(positions, indices, welded, full, mm) == 0 {
            break;
        }
    }
    true
}

/// See [`settle`].
const UNFOLD_ROUNDS: usize = 4;
