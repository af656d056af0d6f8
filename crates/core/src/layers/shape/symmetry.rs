//! The shape's cuts alike on both sides of the face (docs/models.md §13 "Alike on both
//! sides"). Keeping the skin clear of the skin and unfolding it shorten a move where the
//! head's own triangles would fold or cross; a head is never quite symmetric, so one side
//! was cut more than the other: on the African woman one upper lid came down half as far
//! as the other, read blind as "one half-closed eye, like ptosis or an injury". Each
//! vertex's move is shortened to the share its mirror image keeps, when that is less.

use glam::Vec3;

use crate::base::cells::{CubeMap, EVERY_CUBE, cube_of, for_each_in_shell};

/// Each point's mirror partner: the point nearest its mirror image about x = 0 (face
/// units, [`crate::head::frame::Regions::relative`]) within `tolerance`; `None` for no
/// point, or none near enough; of two as near, the lower index.
///
/// The points are gathered in cubes of a quarter of the tolerance and each mirror image
/// searched shell by shell outward from its own cube, until no point farther out can be
/// nearer: on a dense head (570k points, a few hundred in a tolerance's cube) cubes of the
/// whole tolerance made every search weigh thousands of points (3.7 s there, 0.2 s now).
pub fn mirror_partners(points: &[Option<Vec3>], tolerance: f32) -> Vec<Option<u32>> {
    let all: Vec<usize> = (0..points.len()).collect();
    partners_of(points, tolerance, &all)
}

/// [`mirror_partners`] of the points `which` only (in that order), searched among all.
fn partners_of(points: &[Option<Vec3>], tolerance: f32, which: &[usize]) -> Vec<Option<u32>> {
    use rayon::prelude::*;
    const SHELLS: i32 = 4;
    let cell = (tolerance / SHELLS as f32).max(1e-7);
    let mut grid: CubeMap<Vec<u32>> = CubeMap::default();
    for (i, p) in points.iter().enumerate() {
        if let Some(p) = p {
            grid.entry(cube_of(*p, cell)).or_default().push(i as u32);
        }
    }
    let limit = tolerance * tolerance;
    which
        .par_iter()
        .map(|&i| {
            let mirrored = points.get(i).copied().flatten()? * Vec3::new(-1.0, 1.0, 1.0);
            let home = cube_of(mirrored, cell);
            let mut best: Option<(f32, u32)> = None;
            for r in 0..=SHELLS {
                for_each_in_shell(home, r, EVERY_CUBE, |at| {
                    for &j in grid.get(&at).into_iter().flatten() {
                        let d = points[j as usize]
                            .map_or(f32::INFINITY, |q| q.distance_squared(mirrored));
                        if d <= limit && best.is_none_or(|b| (d, j) < b) {
                            best = Some((d, j));
                        }
                    }
                });
                // A point in a cube past shell r lies at least r cubes away.
                let reach = r as f32 * cell;
                if best.is_some_and(|(d, _)| d <= reach * reach) {
                    break;
                }
            }
            best.map(|(_, j)| j)
        })
        .collect()
}

/// How many points set a head's mirror plane ([`head_mirror`]), at most.
const MIRROR_SAMPLE: usize = 4096;

/// A head's own mirror pairs: the plane halfway between its outer eye corners `eyes`
/// (right, left), set again from the pairs of a sample of `points` (`None`: left out;
/// [`MIRROR_SAMPLE`] of them) whose mirror images lie within `loose` of each other (its normal the pairs' mean direction, through
/// their mean midpoint), then each point's partner within `tight` of its mirror image
/// about it (mutual pairs only; a point on the plane its own). Returns the plane's normal
/// and the partners; `None` when under a tenth of the sample or of the points have one (a
/// scan: no head is built symmetric to the vertex) or the eyes coincide. The eye corners
/// must be mirror images about the head's plane within a fraction of its vertices' spacing
/// (the pairs then are the true ones): the automatic landmarks are, about the face's own
/// plane (`head::fit::mirror`); two corners placed by hand millimetres off a dense
/// symmetric head's plane leave it as a scan.
pub fn head_mirror(
    points: &[Option<Vec3>],
    eyes: (Vec3, Vec3),
    loose: f32,
    tight: f32,
) -> Option<(Vec3, Vec<Option<u32>>)> {
    let (right, left) = eyes;
    let normal = (left - right).try_normalize()?;
    let origin = 0.5 * (left + right);
    let frame = |normal: Vec3, origin: Vec3| -> Vec<Option<Vec3>> {
        let (u, v) = normal.any_orthonormal_pair();
        points
            .iter()
            .map(|p| {
                p.map(|p| {
                    let d = p - origin;
                    Vec3::new(d.dot(normal), d.dot(u), d.dot(v))
                })
            })
            .collect()
    };
    // The plane from a sample (a point without a partner searches every shell round its
    // mirror image: on a scan of 570k points, searched all, 5 s for nothing).
    let present: Vec<usize> = (0..points.len()).filter(|&i| points[i].is_some()).collect();
    let total = present.len();
    let sample: Vec<usize> = present
        .iter()
        .copied()
        .step_by((total / MIRROR_SAMPLE).max(1))
        .collect();
    let pairs = partners_of(&frame(normal, origin), loose, &sample);
    let (mut across, mut middle, mut count) = (Vec3::ZERO, Vec3::ZERO, 0usize);
    for (&i, j) in sample.iter().zip(&pairs) {
        let (Some(j), Some(p)) = (j, points[i]) else {
            continue;
        };
        let Some(q) = points[*j as usize] else {
            continue;
        };
        let d = p - q;
        across += if d.dot(normal) < 0.0 { -d } else { d };
        middle += 0.5 * (p + q);
        count += 1;
    }
    if count * 10 < sample.len() || count == 0 {
        return None;
    }
    let normal = across.try_normalize().unwrap_or(normal);
    let origin = middle / count as f32;
    let turned = frame(normal, origin);
    // The sample first: a dense scan pairs nearly all its points within the loose reach
    // (its vertices a fraction of a millimetre apart) and almost none within the tight one.
    let tight_sample = partners_of(&turned, tight, &sample);
    if tight_sample.iter().flatten().count() * 10 < sample.len() {
        return None;
    }
    let pairs = mirror_partners(&turned, tight);
    let mutual: Vec<Option<u32>> = pairs
        .iter()
        .enumerate()
        .map(|(i, j)| j.filter(|&j| pairs[j as usize] == Some(i as u32)))
        .collect();
    let paired = mutual.iter().filter(|p| p.is_some()).count();
    (paired * 10 >= total).then_some((normal, mutual))
}

/// Makes each pair's moves (every region's displacement `full` and hollow `hollow`) mirror
/// images about a plane of normal `normal`: each the mean of its own and its partner's
/// reflected (a point its own partner loses its move across the plane).
pub fn mirror_average(
    full: &mut [Vec<Vec3>],
    hollow: &mut [Vec<f32>],
    partners: &[Option<u32>],
    normal: Vec3,
) {
    let reflect = |d: Vec3| d - normal * (2.0 * d.dot(normal));
    for (i, p) in partners.iter().enumerate() {
        let Some(j) = p.map(|j| j as usize) else {
            continue;
        };
        if j < i {
            continue;
        }
        for f in full.iter_mut() {
            let mean = 0.5 * (f[i] + reflect(f[j]));
            f[i] = mean;
            f[j] = reflect(mean);
        }
        for h in hollow.iter_mut() {
            let mean = 0.5 * (h[i] + h[j]);
            h[i] = mean;
            h[j] = mean;
        }
    }
}

/// Shortens each vertex's move (all regions' displacements `full`, per region per vertex)
/// to the share of its uncut move (`uncut`, the sum over the regions before the cuts)
/// that its mirror partner keeps, when that is less than its own share. Vertices without
/// a partner keep theirs. The shortening is smoothed over the mesh's edges (`triangles`,
/// three indices each) `passes` times, so that neighbours whose partners kept different
/// shares are not cut apart (on a dense head, unsmoothed, it folded 68,000 vertices that
/// had to be unfolded again). Returns how many were shortened.
pub fn even_out(
    full: &mut [Vec<Vec3>],
    uncut: &[Vec3],
    partners: &[Option<u32>],
    triangles: &[u32],
    passes: usize,
) -> usize {
    let n = uncut.len();
    let kept = |v: usize, full: &[Vec<Vec3>]| {
        let before = uncut[v].length();
        if before <= 1e-12 {
            return 1.0;
        }
        let after: Vec3 = full.iter().map(|f| f[v]).sum();
        (after.length() / before).min(1.0)
    };
    let shares: Vec<f32> = (0..n).map(|v| kept(v, full)).collect();
    let mut scale = vec![1.0f32; n];
    for v in 0..n {
        let Some(p) = partners[v] else {
            continue;
        };
        let (own, other) = (shares[v], shares[p as usize]);
        if other < own - 1e-3 && own > 0.0 {
            scale[v] = other / own;
        }
    }
    for _ in 0..passes {
        scale = smoothed(&scale, triangles);
    }
    let mut shortened = 0;
    for (v, &s) in scale.iter().enumerate() {
        if s < 1.0 - 1e-6 {
            for f in full.iter_mut() {
                f[v] *= s;
            }
            shortened += 1;
        }
    }
    shortened
}

/// `values` averaged with their neighbours over the edges of `triangles` (each vertex
/// with the mean of its own value and its triangles' other corners).
fn smoothed(values: &[f32], triangles: &[u32]) -> Vec<f32> {
    let mut sum: Vec<f32> = values.to_vec();
    let mut count = vec![1.0f32; values.len()];
    for t in triangles.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|v| v as usize);
        if a.max(b).max(c) >= values.len() {
            continue;
        }
        sum[a] += 0.5 * (values[b] + values[c]);
        sum[b] += 0.5 * (values[a] + values[c]);
        sum[c] += 0.5 * (values[a] + values[b]);
        count[a] += 1.0;
        count[b] += 1.0;
        count[c] += 1.0;
    }
    sum.iter().zip(&count).map(|(s, c)| s / c).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partners_are_mirror_images_within_the_tolerance() {
        let points = vec![
            Some(Vec3::new(0.5, 0.1, 0.2)),
            Some(Vec3::new(-0.51, 0.1, 0.2)),
            Some(Vec3::new(0.9, 0.0, 0.0)),
            None,
            Some(Vec3::new(0.0, 1.0, 0.0)),
        ];
        let p = mirror_partners(&points, 0.05);
        assert_eq!(p, vec![Some(1), Some(0), None, None, Some(4)]);
    }

    /// Points scattered over a curved patch (about 1.3 mm apart), each with its mirror
    /// image about x = 0.002 (metres): every point is paired with its mirror image about
    /// the plane found from eye corners 0.02 mm off it and turned 0.1°; with the mirror
    /// images moved up to three tenths of a millimetre at random, none is (every point has
    /// a neighbour within the loose reach of its mirror image, none within the tight one).
    #[test]
    fn a_symmetric_cloud_pairs_and_a_jittered_one_does_not() {
        let mut rng = crate::base::rng::Rng::new(7);
        let (mut symmetric, mut jittered) = (Vec::new(), Vec::new());
        let surface = |u: f32, y: f32| Vec3::new(0.002 + u, y, 0.01 - 20.0 * u * u - 5.0 * y * y);
        for _ in 0..1500 {
            let (u, y) = (0.04 * rng.next_f32() + 0.0003, 0.06 * rng.next_f32() - 0.03);
            let (p, q) = (surface(u, y), surface(-u, y));
            symmetric.extend([Some(p), Some(q)]);
            let shift = Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, 0.0) * 0.0006;
            jittered.extend([Some(p), Some(q + shift)]);
        }
        let eyes = (
            Vec3::new(-0.04598, 0.00992, 0.0),
            Vec3::new(0.05002, 0.01008, 0.0),
        );
        let (normal, pairs) = head_mirror(&symmetric, eyes, 0.002, 0.00005).unwrap();
        assert!(normal.dot(Vec3::X) > 0.99999, "{normal}");
        for (i, p) in pairs.iter().enumerate() {
            assert_eq!(p.map(|p| p as usize), Some(i ^ 1), "{i}");
        }
        assert!(head_mirror(&jittered, eyes, 0.002, 0.00005).is_none());
    }

    #[test]
    fn the_side_cut_less_is_cut_as_much_as_its_mirror_image() {
        // Two vertices, one region; the first kept half its move, the second all of it.
        let uncut = vec![Vec3::new(0.0, -2.0, 0.0), Vec3::new(0.0, -2.0, 0.0)];
        let mut full = vec![vec![Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, -2.0, 0.0)]];
        let partners = vec![Some(1), Some(0)];
        assert_eq!(even_out(&mut full, &uncut, &partners, &[], 0), 1);
        assert_eq!(full[0], vec![Vec3::new(0.0, -1.0, 0.0); 2]);
        // Alike already: nothing to do.
        assert_eq!(even_out(&mut full, &uncut, &partners, &[], 0), 0);
    }
}
