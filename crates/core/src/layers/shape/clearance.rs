//! Skin that never passes through skin (docs/models.md §13 "No skin through skin"). A roll
//! or a bulge moves the skin out along its normal; where the skin faces another surface a
//! few millimetres away — the cheek beside the nose's wing, the lid under the brow — the
//! move could carry it through that surface, which then shows a hole (blind reviewers:
//! "a dark red hole torn in the face beside the nostril"). Each vertex that moves outward
//! or inward looks along its move for the head's surface as it rests; its move (in every region's
//! field alike) is shortened to half the way there.

use glam::Vec3;
use rayon::prelude::*;

use crate::head::fit::bvh::Bvh;

/// The share of the way to the surface in front that an outward move may take.
pub const CLEARANCE_SHARE: f32 = 0.5;
/// The least a move must lean outward or inward (its cosine with the normal) to be
/// checked: a move along the skin (a descent) slides over it, not through what faces it.
const OUTWARD: f32 = 0.3;

/// Rings of neighbours over which a shortened move eases back to the whole move (each
/// ring keeps half of what the ring inside it lost), so the skin round a blocked vertex
/// comes down with it instead of folding round it.
const EASE_RINGS: usize = 3;

/// Shortens each vertex's move in `fields` (per region, per vertex: the move at full
/// strength) so that its oldest move (all regions, each times its gain in `gains`)
/// goes at most [`CLEARANCE_SHARE`] of the way to the surface of `positions`/`indices`
/// in front of it, and eases the shortening out over [`EASE_RINGS`] rings of neighbours.
/// `normals` are the vertices' normals; `bvh` the tree of `positions`/`indices`;
/// `welded[v]` the first vertex at v's position; `near` how far from a vertex its own
/// surface is ignored (mesh units). Each blocked vertex's cap (the longest its move at
/// full strength may be, for `unfold`) is lowered to its shortened move. Returns the
/// number of vertices blocked.
#[allow(clippy::too_many_arguments)]
pub fn keep_clear(
    positions: &[Vec3],
    normals: &[Vec3],
    indices: &[u32],
    bvh: &Bvh,
    welded: &[u32],
    fields: &mut [Vec<Vec3>],
    gains: &[f32],
    near: f32,
    caps: &mut [f32],
) -> usize {
    let n = positions.len();
    let sum = |v: usize, gained: bool| -> Vec3 {
        fields
            .iter()
            .zip(gains.iter().chain(std::iter::repeat(&1.0)))
            .map(|(f, g)| if gained { f[v] * *g } else { f[v] })
            .sum()
    };
    let total: Vec<Vec3> = (0..n).map(|v| sum(v, true)).collect();
    let outward: Vec<usize> = (0..n)
        .filter(|&v| {
            let (d, normal) = (total[v], normals.get(v).copied().unwrap_or(Vec3::ZERO));
            let len = d.length();
            // Inward too: a deflation beside the nose's wing carried the cheek through the
            // nostril's inner wall behind it (its inside then showed as "a black hole
            // beside the nostril", blind).
            len > near && d.dot(normal).abs() > OUTWARD * len * normal.length()
        })
        .collect();
    if outward.is_empty() {
        return 0;
    }
    let scales: Vec<(usize, f32)> = outward
        .par_iter()
        .filter_map(|&v| {
            let d = total[v];
            let len = d.length();
            let hit = bvh.ray(positions[v], d / len, near, len / CLEARANCE_SHARE)?;
            let scale = CLEARANCE_SHARE * hit / len;
            (scale < 0.999).then_some((v, scale))
        })
        .collect();
    if scales.is_empty() {
        return 0;
    }
    let mut scale = vec![1.0f32; n];
    for &(v, s) in &scales {
        let w = welded.get(v).map_or(v, |&w| w as usize);
        scale[w] = scale[w].min(s);
        // The blocked vertex's move may not grow back (`unfold` keeps to its cap).
        if let Some(c) = caps.get_mut(w) {
            *c = c.min(s * sum(v, false).length());
        }
    }
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
    for t in indices.chunks_exact(3) {
        let t = [0, 1, 2].map(|k| welded.get(t[k] as usize).map_or(n, |&w| w as usize));
        if t.iter().any(|&v| v >= n) {
            continue;
        }
        for k in 0..3 {
            for j in 1..3 {
                let (a, b) = (t[k], t[(k + j) % 3]);
                if !neighbours[a].contains(&b) {
                    neighbours[a].push(b);
                }
            }
        }
    }
    for _ in 0..EASE_RINGS {
        let eased: Vec<f32> = (0..n)
            .map(|u| {
                let least = neighbours[u].iter().map(|&w| scale[w]).fold(1.0, f32::min);
                scale[u].min(0.5 * (1.0 + least))
            })
            .collect();
        scale = eased;
    }
    for field in fields.iter_mut() {
        for (v, d) in field.iter_mut().enumerate() {
            let w = welded.get(v).map_or(v, |&w| w as usize);
            if scale[w] < 1.0 {
                *d *= scale[w];
            }
        }
    }
    scales.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A floor that bulges up 3 mm under a small roof 2 mm above one of its corners (as the
    /// cheek beside the nose's wing faces the wing): that corner stops half way to the
    /// roof; the others keep their whole move.
    #[test]
    fn a_bulge_into_a_surface_in_front_stops_half_way() {
        let mm = 0.001;
        let positions = vec![
            // The floor, 4 vertices.
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(10.0 * mm, 0.0, 0.0),
            Vec3::new(10.0 * mm, 10.0 * mm, 0.0),
            Vec3::new(0.0, 10.0 * mm, 0.0),
            // A roof 2 mm above the floor's first corner.
            Vec3::new(-mm, -mm, 2.0 * mm),
            Vec3::new(mm, -mm, 2.0 * mm),
            Vec3::new(mm, mm, 2.0 * mm),
            Vec3::new(-mm, mm, 2.0 * mm),
        ];
        let indices = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
        let normals = vec![Vec3::Z; 8];
        let up = |v: usize| {
            if v < 4 {
                Vec3::Z * 3.0 * mm
            } else {
                Vec3::ZERO
            }
        };
        let mut fields = vec![(0..8).map(up).collect::<Vec<_>>()];
        let welded: Vec<u32> = (0..8).collect();
        let mut caps = vec![f32::INFINITY; 8];
        let bvh = Bvh::new(&positions, &indices);
        let shortened = keep_clear(
            &positions,
            &normals,
            &indices,
            &bvh,
            &welded,
            &mut fields,
            &[1.0],
            0.01 * mm,
            &mut caps,
        );
        assert!((caps[0] - mm).abs() < 1e-7 && caps[1].is_infinite());
        assert_eq!(shortened, 1);
        // Under the roof: half of the 2 mm.
        assert!((fields[0][0].z - mm).abs() < 1e-7, "{}", fields[0][0].z);
        // Its neighbours come down part way (eased over the rings), the roof stays.
        assert!(fields[0][2].z > fields[0][0].z && fields[0][2].z <= 3.0 * mm);
        assert_eq!(fields[0][4], Vec3::ZERO);
    }

    #[test]
    fn a_move_along_the_skin_is_not_checked() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
        let normals = vec![Vec3::Z; 3];
        let mut fields = vec![vec![Vec3::NEG_Y * 0.1; 3]];
        assert_eq!(
            keep_clear(
                &positions,
                &normals,
                &[0, 1, 2],
                &Bvh::new(&positions, &[0, 1, 2]),
                &[0, 1, 2],
                &mut fields,
                &[1.0],
                1e-5,
                &mut [f32::INFINITY; 3]
            ),
            0
        );
    }
}
