//! A coarse stand-in for a dense mesh, for what only needs its shape (the search for a
//! head's axes and landmarks, the sky the aged shape hides): vertex clustering (Rossignac
//! & Borrel 1993). The vertices are gathered in a grid of cubes sized so that about a
//! target number of triangles is left, each cube's vertices merged at their mean, the
//! triangles whose corners fall in three cubes kept. Linear in the triangles, no more
//! than a cube's width from the surface; a mesh of fewer triangles is used as it is.
//! What is computed on the proxy comes back to the mesh's vertices by [`Proxy::spread`].

use glam::Vec3;

use crate::base::cells::{CubeMap, cube_of};

/// Triangles of skin above which the landmark and axes searches run on a proxy, and
/// about how many the proxy keeps.
pub const PROXY_TRIANGLES: usize = 100_000;

/// A mesh, coarser.
#[derive(Clone, Debug)]
pub struct Proxy {
    /// Each cluster's mean position.
    pub positions: Vec<Vec3>,
    /// Three per triangle, into `positions`.
    pub indices: Vec<u32>,
    /// The cluster of each vertex of the mesh (`u32::MAX`: in no triangle).
    pub cluster_of_vertex: Vec<u32>,
    /// The cubes' side, mesh units.
    pub cube: f32,
    /// Each cluster's kind ([`clustered`]'s `kinds`: two kinds never share a cluster).
    pub kind: Vec<bool>,
    /// The clusters by cube, one map per kind.
    cluster_of_cube: [CubeMap<u32>; 2],
}

/// The proxy of the skin triangles `skin` (three indices each) of `positions`; `None`
/// when there are at most [`PROXY_TRIANGLES`] of them (use the skin itself).
pub fn of_skin(positions: &[Vec3], skin: &[u32]) -> Option<Proxy> {
    of_triangles(positions, skin, PROXY_TRIANGLES)
}

/// The proxy of the triangles `triangles` (three indices each) of `positions` with about
/// `target` triangles; `None` when there are at most `target` (use the mesh itself).
pub fn of_triangles(positions: &[Vec3], skin: &[u32], target: usize) -> Option<Proxy> {
    let triangles = skin.len() / 3;
    if triangles <= target.max(1) {
        return None;
    }
    // A cube of `edge · √(triangles / target)` holds about triangles / target of them.
    let edge = mean_edge(positions, skin);
    let cube = edge * (triangles as f32 / target as f32).sqrt();
    if !(cube.is_finite() && cube > 0.0) {
        return None;
    }
    Some(clustered(positions, skin, cube, None))
}

/// The triangles `triangles` (three indices each) of `positions` clustered in cubes of
/// side `cube`: each cube's vertices merged at their mean, the triangles whose corners fall
/// in three clusters kept. With `kinds` (one per vertex), vertices of the two kinds never
/// share a cluster (a dense head's skin and its eyeballs: [`crate::layers::shape`]).
pub fn clustered(
    positions: &[Vec3],
    triangles: &[u32],
    cube: f32,
    kinds: Option<&[bool]>,
) -> Proxy {
    // Clusters numbered in the order their first vertex is met: the same proxy on any
    // machine.
    let mut cluster_of_cube: [CubeMap<u32>; 2] = Default::default();
    let mut cluster_of_vertex = vec![u32::MAX; positions.len()];
    let mut sums: Vec<(Vec3, u32)> = Vec::new();
    let mut kind = Vec::new();
    let mut indices = Vec::with_capacity(triangles.len() / 2);
    for t in triangles.chunks_exact(3) {
        let mut corner = [0u32; 3];
        let mut ok = true;
        for (k, &v) in t.iter().enumerate() {
            let Some(&p) = positions.get(v as usize) else {
                ok = false;
                break;
            };
            let known = &mut cluster_of_vertex[v as usize];
            if *known == u32::MAX {
                let of_kind = kinds
                    .and_then(|k| k.get(v as usize).copied())
                    .unwrap_or(false);
                let next = sums.len() as u32;
                let c = *cluster_of_cube[usize::from(of_kind)]
                    .entry(cube_of(p, cube))
                    .or_insert(next);
                if c == next {
                    sums.push((Vec3::ZERO, 0));
                    kind.push(of_kind);
                }
                sums[c as usize].0 += p;
                sums[c as usize].1 += 1;
                *known = c;
            }
            corner[k] = *known;
        }
        if ok && corner[0] != corner[1] && corner[1] != corner[2] && corner[0] != corner[2] {
            indices.extend_from_slice(&corner);
        }
    }
    Proxy {
        positions: sums.iter().map(|&(s, n)| s / n as f32).collect(),
        indices,
        cluster_of_vertex,
        cube,
        kind,
        cluster_of_cube,
    }
}

/// The mean edge of the triangles `triangles` (three indices each) of `positions`, over
/// every 16th triangle (0 without any).
pub fn mean_edge(positions: &[Vec3], triangles: &[u32]) -> f32 {
    let (mut sum, mut count) = (0.0f64, 0usize);
    for t in triangles.chunks_exact(3).step_by(16) {
        let p = |k: usize| positions.get(t[k] as usize).copied();
        if let (Some(a), Some(b), Some(c)) = (p(0), p(1), p(2)) {
            sum += f64::from(a.distance(b) + b.distance(c) + c.distance(a));
            count += 3;
        }
    }
    (sum / count.max(1) as f64) as f32
}

impl Proxy {
    /// The mean of `per_vertex` (a value of each mesh vertex) over each cluster: e.g. the
    /// proxy's positions after the mesh moved.
    pub fn gather(&self, per_vertex: &[Vec3]) -> Vec<Vec3> {
        let mut sums = vec![(Vec3::ZERO, 0u32); self.positions.len()];
        for (&c, &v) in self.cluster_of_vertex.iter().zip(per_vertex) {
            if let Some(s) = sums.get_mut(c as usize) {
                s.0 += v;
                s.1 += 1;
            }
        }
        sums.iter().map(|&(s, n)| s / n.max(1) as f32).collect()
    }

    /// A value of each cluster (`values`, with its `normals`) carried to the mesh's
    /// vertices at `positions` with their `normals` ([`Proxy::weights`]). A vertex no
    /// cluster reaches takes its own cluster's.
    pub fn spread(
        &self,
        values: &[f32],
        normals: &[Vec3],
        positions: &[Vec3],
        vertex_normals: &[Vec3],
    ) -> Vec<f32> {
        use rayon::prelude::*;
        (0..positions.len())
            .into_par_iter()
            .map(|v| {
                let own = self.cluster_of_vertex.get(v).copied().unwrap_or(u32::MAX);
                let Some(&fallback) = values.get(own as usize) else {
                    return 1.0;
                };
                let (weights, count, total) =
                    self.weights(positions[v], vertex_normals[v], own, normals);
                if total > 0.0 {
                    let sum: f32 = weights[..count]
                        .iter()
                        .map(|&(c, w)| w * values[c as usize])
                        .sum();
                    sum / total
                } else {
                    fallback
                }
            })
            .collect()
    }

    /// How much each cluster round a point `p` with normal `n` (of the cluster `own`'s
    /// kind) counts in a value carried to it from the clusters (their `normals`): the
    /// clusters of that kind in the 27 cubes round it, each by a tent of 1.5 cubes over its
    /// distance and by how alike it faces (a lip takes nothing from the lip it touches), so
    /// the value changes smoothly over the cubes. The weights, how many, and their sum
    /// (0: none reaches).
    pub fn weights(
        &self,
        p: Vec3,
        n: Vec3,
        own: u32,
        normals: &[Vec3],
    ) -> ([(u32, f32); 27], usize, f32) {
        let radius = 1.5 * self.cube;
        let kind = usize::from(self.kind.get(own as usize).copied().unwrap_or(false));
        let home = (p / self.cube).floor().as_ivec3();
        let mut weights = [(0u32, 0.0f32); 27];
        let (mut count, mut total) = (0, 0.0f32);
        for z in -1..=1 {
            for y in -1..=1 {
                for x in -1..=1 {
                    let key = (home + glam::IVec3::new(x, y, z)).to_array();
                    let Some(&c) = self.cluster_of_cube[kind].get(&key) else {
                        continue;
                    };
                    let near = (1.0 - self.positions[c as usize].distance(p) / radius).max(0.0);
                    let w = near * near * normals[c as usize].dot(n).max(0.0);
                    if w > 0.0 {
                        weights[count] = (c, w);
                        count += 1;
                        total += w;
                    }
                }
            }
        }
        (weights, count, total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere of `n` × 2n quads, two triangles each.
    fn sphere(n: usize) -> (Vec<Vec3>, Vec<u32>) {
        let mut p = Vec::new();
        for i in 0..=n {
            for j in 0..2 * n {
                let (th, ph) = (
                    std::f32::consts::PI * i as f32 / n as f32,
                    std::f32::consts::PI * j as f32 / n as f32,
                );
                p.push(Vec3::new(
                    th.sin() * ph.cos(),
                    th.cos(),
                    th.sin() * ph.sin(),
                ));
            }
        }
        let mut ix = Vec::new();
        let at = |i: usize, j: usize| (i * 2 * n + j % (2 * n)) as u32;
        for i in 0..n {
            for j in 0..2 * n {
                ix.extend([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                ix.extend([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        (p, ix)
    }

    #[test]
    fn a_dense_surface_keeps_its_shape_with_about_the_target_triangles() {
        let (p, ix) = sphere(300); // 360k triangles
        assert!(of_skin(&p, &ix[..PROXY_TRIANGLES * 3]).is_none());
        let proxy = of_skin(&p, &ix).unwrap();
        let kept = proxy.indices.len() / 3;
        assert!(
            kept > PROXY_TRIANGLES / 3 && kept < PROXY_TRIANGLES * 2,
            "{kept} triangles"
        );
        // On the sphere within a cube's width (the mean edge ×√3.6 here: ~0.02).
        let worst = proxy
            .positions
            .iter()
            .map(|q| (q.length() - 1.0).abs())
            .fold(0.0f32, f32::max);
        assert!(worst < 0.02, "{worst}");
        // The same proxy again, bit for bit.
        let again = of_skin(&p, &ix).unwrap();
        assert_eq!(again.indices, proxy.indices);
        assert_eq!(again.positions, proxy.positions);
    }
}
