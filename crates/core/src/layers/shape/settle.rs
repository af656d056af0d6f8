//! The aged shape settled on the head (docs/models.md §13): no skin moves through the
//! skin in front of it ("No skin through skin"), no triangle folds over at any age ("No
//! folded skin"), and what those cuts take from one side of the face they take from the
//! other ("Alike on both sides").

use glam::Vec3;

use super::{REGIONS, ShapeRegion, clearance, symmetry, unfold};

/// Turns of keeping the skin clear of the skin and unfolding it (each can undo a little
/// of the other).
const CLEAR_AND_UNFOLD_ROUNDS: usize = 4;

/// How far (face units, about 5 mm) a vertex's mirror partner may lie from its mirror
/// image ([`symmetry::mirror_partners`]).
pub(super) const MIRROR_TOLERANCE: f32 = 0.1;

/// How far, mm, the evening's shortening is smoothed over the mesh
/// ([`symmetry::even_out`]): (this / the mean edge)² passes, none on a head whose edges
/// are longer.
const EVEN_SMOOTH_MM: f32 = 2.0;

/// Settles the regions' full displacements `full` (per region, per vertex of the mesh of
/// `positions` and `indices`, the vertices at one position `welded` together) on the head:
/// `smooth` its smooth normals, `points` each vertex's place in the face frame (for its
/// mirror image; `None` off the template or not the first at its position), `mm` a
/// millimetre in the head's units,
/// `partners` the vertices' mirror partners the cuts are evened over (the head's own pairs
/// where it is its own mirror image, [`symmetry::head_mirror`]; `None`: those of `points`
/// within [`MIRROR_TOLERANCE`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn settle(
    positions: &[Vec3],
    indices: &[u32],
    welded: &[u32],
    smooth: &[Vec3],
    full: &mut [Vec<Vec3>],
    points: &[Option<Vec3>],
    mm: f32,
    partners: Option<&[Option<u32>]>,
) {
    let n = positions.len();
    let uncut: Vec<Vec3> = (0..n).map(|v| full.iter().map(|f| f[v]).sum()).collect();
    // No skin moves through the skin in front of it (docs/models.md §13 "No skin
    // through skin"), its own surface ignored within 0.2 mm, and no triangle folds
    // over, at the oldest (the exported morph target, every region at its old-age share) or at
    // any age between (§13 "No folded skin"): each spreads or shortens what the other
    // did, so they take turns.
    let checks = fold_checks();
    let mut caps = vec![f32::INFINITY; n];
    let moves = full.iter().any(|f| f.iter().any(|d| *d != Vec3::ZERO));
    let bvh = if moves {
        crate::head::fit::bvh::Bvh::new(positions, indices)
    } else {
        crate::head::fit::bvh::Bvh::new(&[], &[])
    };
    let found;
    let partners = match partners {
        Some(pairs) => pairs,
        None => {
            found = symmetry::mirror_partners(points, MIRROR_TOLERANCE);
            &found
        }
    };
    let welded_triangles: Vec<u32> = indices.iter().map(|&i| welded[i as usize]).collect();
    let passes = smoothing_passes(positions, indices, EVEN_SMOOTH_MM * mm);
    let (mut rounds, mut evened) = (0, false);
    loop {
        let blocked = clearance::keep_clear(
            positions,
            smooth,
            indices,
            &bvh,
            welded,
            full,
            &ShapeRegion::oldest(),
            0.2 * mm,
            &mut caps,
        );
        let spread = unfold::unfold(
            positions,
            indices,
            welded,
            full,
            &checks,
            &caps,
            unfold::SPREAD_REACH_MM * mm,
        );
        rounds += 1;
        if (blocked > 0 || spread > 0) && rounds < CLEAR_AND_UNFOLD_ROUNDS {
            continue;
        }
        // What the cuts took from one side they take from the other, then one more
        // turn keeps what that leaves clear and unfolded.
        if evened || symmetry::even_out(full, &uncut, partners, &welded_triangles, passes) == 0 {
            break;
        }
        evened = true;
        for f in full.iter_mut() {
            for v in 0..n {
                f[v] = f[welded[v] as usize];
            }
        }
    }
}

/// The region factors under which no triangle may fold: the oldest (the exported morph
/// target, every region at its old-age share), and every 5 years from 30 to 100.
fn fold_checks() -> Vec<Vec<f32>> {
    std::iter::once(ShapeRegion::oldest().to_vec())
        .chain((6..=20).map(|k| {
            let years = 5.0 * k as f32;
            REGIONS.iter().map(|r| r.factor(years)).collect()
        }))
        .collect()
}

/// Unfolds `full` on the mesh of `positions` and `indices` (vertices `welded` as in
/// [`settle`]) under the same checks, nothing in front of the skin: what a dense head's
/// shape, settled on its stand-in ([`super::coarse`]), still folds on its own finer
/// triangles, in up to `rounds` rounds (each can leave a fold next to one it spread) on one
/// [`unfold::Topology`]. Returns the number of vertices changed.
pub(super) fn unfold_only(
    positions: &[Vec3],
    indices: &[u32],
    welded: &[u32],
    full: &mut [Vec<Vec3>],
    mm: f32,
    rounds: usize,
) -> usize {
    let caps = vec![f32::INFINITY; positions.len()];
    let checks = fold_checks();
    let topology = unfold::Topology::new(positions.len(), indices, welded);
    let mut changed = 0;
    // Each round after the first looks for folds only round what the one before wrote.
    let mut from: Option<Vec<usize>> = None;
    for _ in 0..rounds {
        let round = unfold::unfold_on(
            &topology,
            positions,
            welded,
            full,
            &checks,
            &caps,
            unfold::SPREAD_REACH_MM * mm,
            from.as_deref(),
        );
        if round.changed == 0 {
            break;
        }
        changed += round.changed;
        from = Some(round.written);
    }
    changed
}

/// Passes of neighbour smoothing that reach about `reach` (mesh units) over the mesh of
/// `positions` and `indices`: (reach / its mean edge)², at most 64.
fn smoothing_passes(positions: &[Vec3], indices: &[u32], reach: f32) -> usize {
    let edge = crate::head::fit::proxy::mean_edge(positions, indices);
    if !(edge > 0.0 && edge.is_finite()) {
        return 0;
    }
    ((reach / edge).powi(2).round() as usize).min(64)
}
