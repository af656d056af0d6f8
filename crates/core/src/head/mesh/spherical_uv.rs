//! UVs for meshes that have none: the inverse spherical mapping of docs/models.md §6.
//!
//! Around a centre c, a point p maps to its longitude and latitude:
//! u = 0.5 + atan2(x, z)/(2π) (so the +Z side — the face, in glTF's convention of a model
//! looking along +Z — is at u = 0.5 and the seam is at the back), and
//! v = 0.5 + asin(y/‖p − c‖)/π (v up, poles at v = 0 and 1).
//!
//! Seam fix (docs/models.md §6): a triangle whose corners' u differ by more than 0.5 straddles the
//! seam; its corners with u < 0.5 get u + 1, on a duplicated vertex, so no triangle spans
//! the whole texture. Pole fix: a vertex on the axis (x = z = 0) has no longitude; in each
//! triangle it takes the mean u of the other corners, again on a duplicate. Generated u
//! thus lies in [0, 1.5): textures must wrap in u (they do, around a head).

use std::collections::HashMap;
use std::f32::consts::PI;

use glam::{Vec2, Vec3};

/// UVs for every vertex (inputs first, then duplicates) and the rewritten triangles.
#[derive(Clone, Debug)]
pub struct SphericalUvs {
    pub uvs: Vec<Vec2>,
    /// For each duplicate vertex (appended after the inputs), the vertex it copies.
    pub duplicated_from: Vec<u32>,
    pub indices: Vec<u32>,
}

/// Longitude/latitude UV of `p` around `centre` (docs/models.md §6), without the seam fix. `None`
/// on the axis (no longitude) — the latitude alone is then returned as `Err(v)`.
pub fn spherical_uv(p: Vec3, centre: Vec3) -> Result<Vec2, f32> {
    let d = p - centre;
    let r = d.length();
    let v = if r > 0.0 {
        0.5 + (d.y / r).clamp(-1.0, 1.0).asin() / PI
    } else {
        0.5
    };
    let horizontal = d.x.hypot(d.z);
    if horizontal <= r * 1e-6 || horizontal == 0.0 {
        return Err(v);
    }
    let u = 0.5 + d.x.atan2(d.z) / (2.0 * PI);
    Ok(Vec2::new(u, v))
}

/// Inverse spherical UVs around `centre` with the seam and pole fixes (module docs).
pub fn spherical_uvs(positions: &[Vec3], indices: &[u32], centre: Vec3) -> SphericalUvs {
    let base: Vec<Result<Vec2, f32>> = positions.iter().map(|&p| spherical_uv(p, centre)).collect();
    let mut uvs: Vec<Vec2> = base
        .iter()
        .map(|r| match *r {
            Ok(uv) => uv,
            Err(v) => Vec2::new(0.5, v),
        })
        .collect();
    let mut duplicated_from = Vec::new();
    let mut out = indices.to_vec();
    // (vertex, bits of the new u) → its duplicate.
    let mut dups: HashMap<(u32, u32), u32> = HashMap::new();

    for tri in out.chunks_exact_mut(3) {
        let mut u: [Option<f32>; 3] = [0, 1, 2].map(|k| base[tri[k] as usize].ok().map(|uv| uv.x));
        let known: Vec<f32> = u.iter().flatten().copied().collect();
        if let (Some(lo), Some(hi)) = (
            known.iter().copied().reduce(f32::min),
            known.iter().copied().reduce(f32::max),
        ) && hi - lo > 0.5
        {
            for x in u.iter_mut().flatten() {
                if *x < 0.5 {
                    *x += 1.0;
                }
            }
        }
        let fixed: Vec<f32> = u.iter().flatten().copied().collect();
        let pole_u = if fixed.is_empty() {
            0.5
        } else {
            fixed.iter().sum::<f32>() / fixed.len() as f32
        };
        for k in 0..3 {
            let v = tri[k];
            let want = u[k].unwrap_or(pole_u);
            if want == uvs[v as usize].x {
                continue;
            }
            let key = (v, want.to_bits());
            let dup = *dups.entry(key).or_insert_with(|| {
                duplicated_from.push(v);
                uvs.push(Vec2::new(want, uvs[v as usize].y));
                (uvs.len() - 1) as u32
            });
            tri[k] = dup;
        }
    }
    SphericalUvs {
        uvs,
        duplicated_from,
        indices: out,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::head::mesh::test_util::assert_close;

    #[test]
    fn cardinal_directions_map_to_documented_uvs() {
        let c = Vec3::ZERO;
        let front = spherical_uv(Vec3::Z, c).unwrap();
        assert_close(front.x, 0.5, 1e-6, "front u");
        assert_close(front.y, 0.5, 1e-6, "equator v");
        assert_close(spherical_uv(Vec3::X, c).unwrap().x, 0.75, 1e-6, "+x u");
        assert_close(spherical_uv(Vec3::NEG_X, c).unwrap().x, 0.25, 1e-6, "−x u");
        let up45 = spherical_uv(Vec3::new(0.0, 1.0, 1.0), c).unwrap();
        assert_close(up45.y, 0.75, 1e-6, "45° up");
        assert_eq!(spherical_uv(Vec3::Y * 2.0, c), Err(1.0), "pole");
    }

    /// A UV sphere: `rings` latitude bands, `segments` longitude segments, single poles.
    fn sphere(rings: u32, segments: u32) -> (Vec<Vec3>, Vec<u32>) {
        let mut p = vec![Vec3::Y, Vec3::NEG_Y];
        for r in 1..rings {
            let theta = PI * r as f32 / rings as f32;
            for s in 0..segments {
                // Offset by half a segment so no vertex sits exactly on the seam.
                let phi = 2.0 * PI * (s as f32 + 0.5) / segments as f32;
                p.push(Vec3::new(
                    theta.sin() * phi.sin(),
                    theta.cos(),
                    theta.sin() * phi.cos(),
                ));
            }
        }
        let ring = |r: u32, s: u32| 2 + (r - 1) * segments + s % segments;
        let mut idx = Vec::new();
        for s in 0..segments {
            idx.extend_from_slice(&[0, ring(1, s), ring(1, s + 1)]);
            idx.extend_from_slice(&[1, ring(rings - 1, s + 1), ring(rings - 1, s)]);
            for r in 1..rings - 1 {
                let (a, b, c, d) = (
                    ring(r, s),
                    ring(r, s + 1),
                    ring(r + 1, s),
                    ring(r + 1, s + 1),
                );
                idx.extend_from_slice(&[a, c, d, a, d, b]);
            }
        }
        (p, idx)
    }

    #[test]
    fn the_seam_fix_leaves_no_triangle_spanning_more_than_half_the_u_range() {
        let (p, idx) = sphere(12, 24);
        let raw_span = idx
            .chunks_exact(3)
            .map(|t| {
                let u: Vec<f32> = t
                    .iter()
                    .filter_map(|&v| spherical_uv(p[v as usize], Vec3::ZERO).ok())
                    .map(|uv| uv.x)
                    .collect();
                u.iter().copied().fold(f32::MIN, f32::max)
                    - u.iter().copied().fold(f32::MAX, f32::min)
            })
            .fold(0.0, f32::max);
        assert!(
            raw_span > 0.9,
            "the fixture must straddle the seam ({raw_span})"
        );

        let m = spherical_uvs(&p, &idx, Vec3::ZERO);
        assert!(!m.duplicated_from.is_empty());
        assert_eq!(m.uvs.len(), p.len() + m.duplicated_from.len());
        for t in m.indices.chunks_exact(3) {
            let u = [t[0], t[1], t[2]].map(|v| m.uvs[v as usize].x);
            let span = u.iter().copied().fold(f32::MIN, f32::max)
                - u.iter().copied().fold(f32::MAX, f32::min);
            assert!(span <= 0.5, "triangle {t:?} spans u {u:?}");
            // Every corner kept its own position (duplicates copy the right vertex).
            for &v in t {
                let src = if (v as usize) < p.len() {
                    v
                } else {
                    m.duplicated_from[v as usize - p.len()]
                };
                assert!((m.uvs[v as usize].y - m.uvs[src as usize].y).abs() < 1e-6);
            }
        }
        assert!(
            m.uvs
                .iter()
                .all(|uv| (0.0..1.5).contains(&uv.x) && (0.0..=1.0).contains(&uv.y))
        );
    }
}
