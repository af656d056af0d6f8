//! Skin that never folds (docs/models.md §13 "No folded skin"). The regions' displacements
//! are smooth fields over the face, but a head's triangles are not: where a field changes
//! faster than a small triangle is wide (the lid's crease, beside the nose on a coarse
//! head) the moved triangle turns over and shows its back. Wherever a triangle would turn
//! by more than [`MAX_TURN_DEG`] — at full age (the exported morph target) or at any age the
//! editor shows — the displacement of its corners is relaxed toward its neighbours' (the
//! move spread over the neighbours, its mean kept), in every region's field alike, until
//! none does; what still turns after [`SPREAD_PASSES`] is shrunk in place. (Ending the spread
//! early once it stopped paying, which saved a 1.13M-triangle head 8 s, was tried and
//! taken back: it left a hole beside the dense panel head's nostril.) Only the triangles
//! round what changed are checked again, so a dense head costs what its folds do.

use glam::Vec3;
use rayon::prelude::*;

/// The most a triangle's normal may turn under the shape's move, degrees.
pub const MAX_TURN_DEG: f32 = 60.0;
/// Passes that spread a fold's move over the neighbours before one shrinks it.
const SPREAD_PASSES: usize = 128;
/// The most relaxation sweeps in one pass.
const MAX_SWEEPS: usize = 16;
/// Passes without fewer folds after which the spread widens by one ring.
const STALL_PASSES: usize = 4;
/// Vertices in a ring from which a relaxation sweep runs on the thread pool.
const PARALLEL_RING: usize = 4096;
/// Passes that shrink what still folds (each takes a third of the move at the fold).
const SHRINK_PASSES: usize = 48;

/// How far from a fold's corners its move is spread at most, mm. Unbounded, the spread
/// grew ring by ring over a coarse head (triangles 5 mm wide) from a lower lid that would
/// not unfold down over the whole cheek, and the relaxation, which smooths every region's
/// field toward its values round the spread, flattened the cheek's roll and the mid-cheek
/// hollow on that side: the asian panel head aged on one side only, the other side's fold
/// read blind as "a deep one-sided diagonal crease far out on the cheek" (rounds 11–16,
/// on six heads of seven; over the cheek below each eye, one side moved 0.14, 0.39 and
/// 0.53 of the other on three panel heads, 0.67–1.0 within 8 mm, 0.59–0.76 within 12;
/// 0.63–0.90 with the cheek's later, broader roll). A dense head's fold (1 mm triangles)
/// still spreads over 8 rings.
pub const SPREAD_REACH_MM: f32 = 8.0;

/// Relaxes `fields` (per region, per vertex: the move at full strength) on the mesh of
/// `positions` and `indices` so that no triangle turns by more than [`MAX_TURN_DEG`] under
/// any of `checks` (each a factor per region: the full age, and the ages between), the
/// move of vertex v at full age never longer than `caps[v]` (what keeps it clear of the
/// skin in front, `clearance`; infinite where nothing is in front), and spread no farther
/// than `reach` (mesh units) from the fold it unfolds ([`SPREAD_REACH_MM`]). `welded[v]`
/// is the first vertex at v's position: split vertices move together. Returns the number
/// of vertices changed.
pub fn unfold(
    positions: &[Vec3],
    indices: &[u32],
    welded: &[u32],
    fields: &mut [Vec<Vec3>],
    checks: &[Vec<f32>],
    caps: &[f32],
    reach: f32,
) -> usize {
    let n = positions.len();
    if fields.iter().all(|f| f.iter().all(|d| *d == Vec3::ZERO)) || n == 0 {
        return 0;
    }
    // Triangles over welded vertices, each welded vertex's neighbours and triangles.
    let triangles: Vec<[usize; 3]> = indices
        .chunks_exact(3)
        .map(|t| [0, 1, 2].map(|k| welded[t[k] as usize] as usize))
        .filter(|t| t.iter().all(|&v| v < n))
        .collect();
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, t) in triangles.iter().enumerate() {
        for k in 0..3 {
            incident[t[k]].push(i);
            for j in 1..3 {
                let (a, b) = (t[k], t[(k + j) % 3]);
                if !neighbours[a].contains(&b) {
                    neighbours[a].push(b);
                }
            }
        }
    }
    let cos_max = MAX_TURN_DEG.to_radians().cos();
    // Only what moves is relaxed (a vertex that stays — off every region, not skin — stays:
    // it holds the spread like a wall). First every triangle that moves is checked; then
    // only those round what changed.
    let moving: Vec<bool> = (0..n)
        .map(|v| fields.iter().any(|f| f[v] != Vec3::ZERO))
        .collect();
    let mut suspects: Vec<usize> = (0..triangles.len())
        .filter(|&i| triangles[i].iter().any(|&v| moving[v]))
        .collect();
    // The vertices relaxed each pass: every fold's corners and their ring so far, grown by
    // one more ring whenever the folds stop shrinking (a fold whose surroundings jump too
    // needs a wider spread).
    let mut active = vec![false; n];
    // The fold each active vertex spreads: the corner that made it active, or whose ring
    // it joined (a ring grows only within `reach` of it).
    let mut seed = vec![usize::MAX; n];
    let mut best = usize::MAX;
    let mut stalled = 0;
    for pass in 0..SPREAD_PASSES + SHRINK_PASSES {
        let bad = folded_vertices(positions, &triangles, &suspects, fields, checks, cos_max);
        if bad.is_empty() {
            break;
        }
        let mut touched: Vec<usize> = Vec::new();
        if pass >= SPREAD_PASSES {
            // What still folds is shrunk in place with its ring, the ring less, so that
            // the shrink makes no new step.
            let mut ring: Vec<usize> = bad
                .iter()
                .flat_map(|&v| neighbours[v].iter().copied())
                .filter(|&v| moving[v])
                .collect();
            ring.sort_unstable();
            ring.dedup();
            for field in fields.iter_mut() {
                for &v in &ring {
                    field[v] *= 0.75;
                }
                for &v in &bad {
                    field[v] *= 2.0 / 3.0;
                }
            }
            touched.extend(ring);
            touched.extend_from_slice(&bad);
        } else {
            for &v in &bad {
                if seed[v] == usize::MAX {
                    seed[v] = v;
                }
                active[v] = moving[v];
                for &u in &neighbours[v] {
                    active[u] = moving[u];
                    if seed[u] == usize::MAX {
                        seed[u] = seed[v];
                    }
                }
            }
            if bad.len() < best {
                (best, stalled) = (bad.len(), 0);
            } else {
                stalled += 1;
            }
            if stalled >= STALL_PASSES {
                stalled = 0;
                let grown: Vec<(usize, usize)> = (0..n)
                    .filter(|&v| active[v])
                    .flat_map(|v| neighbours[v].iter().map(move |&u| (u, v)))
                    .filter(|&(u, v)| !active[u] && seed[v] != usize::MAX)
                    .collect();
                for (u, v) in grown {
                    let from = seed[v];
                    if moving[u] && positions[u].distance(positions[from]) <= reach {
                        active[u] = true;
                        if seed[u] == usize::MAX {
                            seed[u] = from;
                        }
                    }
                }
            }
            // Each active vertex takes the mean of its neighbours' move, half way, more
            // sweeps as the passes go on (a wide fold on a dense head needs many).
            let ring: Vec<usize> = (0..n).filter(|&v| active[v]).collect();
            let sweeps = (1 + pass / 4).min(MAX_SWEEPS);
            // A region's field that is zero over the ring and its neighbours stays zero
            // under the sweeps: it is left alone (most regions, at most folds).
            let live: Vec<bool> = fields
                .iter()
                .map(|field| {
                    ring.iter().any(|&v| {
                        field[v] != Vec3::ZERO
                            || neighbours[v].iter().any(|&u| field[u] != Vec3::ZERO)
                    })
                })
                .collect();
            for _ in 0..sweeps {
                for (field, _) in fields.iter_mut().zip(&live).filter(|(_, live)| **live) {
                    relax(field, &ring, &neighbours);
                }
                cap(fields, &ring, caps);
            }
            touched = ring;
        }
        suspects = touched
            .iter()
            .flat_map(|&v| incident[v].iter().copied())
            .collect();
        suspects.sort_unstable();
        suspects.dedup();
    }
    let changed = active.iter().filter(|&&a| a).count();
    // Split vertices take their position's move.
    for field in fields.iter_mut() {
        for v in 0..n {
            let w = welded[v] as usize;
            if w != v && w < n {
                field[v] = field[w];
            }
        }
    }
    changed
}

/// Shortens the move at full age of each vertex of `ring` to its cap (every field alike).
fn cap(fields: &mut [Vec<Vec3>], ring: &[usize], caps: &[f32]) {
    for &v in ring {
        let limit = caps.get(v).copied().unwrap_or(f32::INFINITY);
        if !limit.is_finite() {
            continue;
        }
        let len = fields.iter().map(|f| f[v]).sum::<Vec3>().length();
        if len > limit && len > 0.0 {
            let s = limit / len;
            for f in fields.iter_mut() {
                f[v] *= s;
            }
        }
    }
}

/// One Jacobi sweep over `ring`: each vertex half way to its neighbours' mean move (every
/// new value from the old ones).
fn relax(field: &mut [Vec3], ring: &[usize], neighbours: &[Vec<usize>]) {
    let relax_one = |&v: &usize| {
        let around = &neighbours[v];
        if around.is_empty() {
            return field[v];
        }
        let mean = around.iter().map(|&u| field[u]).sum::<Vec3>() / around.len() as f32;
        0.5 * (field[v] + mean)
    };
    // In parallel only where it pays (a dense head's ring): a small ring costs less than
    // the pool's start.
    let relaxed: Vec<Vec3> = if ring.len() >= PARALLEL_RING {
        ring.par_iter().map(relax_one).collect()
    } else {
        ring.iter().map(relax_one).collect()
    };
    for (&v, d) in ring.iter().zip(relaxed) {
        field[v] = d;
    }
}

/// The corners of the triangles that turn by more than the limit under any check.
fn folded_vertices(
    positions: &[Vec3],
    triangles: &[[usize; 3]],
    suspects: &[usize],
    fields: &[Vec<Vec3>],
    checks: &[Vec<f32>],
    cos_max: f32,
) -> Vec<usize> {
    // Each check's move of every corner of a suspect, once (a corner is shared by about
    // six triangles): `moves[slot · checks + k]`.
    let mut corners: Vec<usize> = suspects.iter().flat_map(|&i| triangles[i]).collect();
    corners.sort_unstable();
    corners.dedup();
    let k = checks.len();
    let mut moves = vec![Vec3::ZERO; corners.len() * k];
    let corner_moves = |(out, &v): (&mut [Vec3], &usize)| {
        // Only the regions that move this corner (one to three of them, mostly).
        for (r, field) in fields.iter().enumerate() {
            let d = field[v];
            if d != Vec3::ZERO {
                for (o, factors) in out.iter_mut().zip(checks) {
                    *o += d * factors[r];
                }
            }
        }
    };
    let parallel = suspects.len() >= PARALLEL_RING;
    if parallel {
        (moves.par_chunks_mut(k.max(1)).zip(corners.par_iter())).for_each(corner_moves);
    } else {
        (moves.chunks_mut(k.max(1)).zip(corners.iter())).for_each(corner_moves);
    }
    let slot = |v: usize| corners.binary_search(&v).unwrap_or(0) * k;
    let folded = |&i: &usize| {
        let t = &triangles[i];
        let [a, b, c] = t.map(|v| positions[v]);
        let rest = (b - a).cross(c - a);
        if rest.length_squared() <= 0.0 || !rest.is_finite() {
            return None;
        }
        let [sa, sb, sc] = t.map(slot);
        let folds = (0..k).any(|j| {
            let (da, db, dc) = (moves[sa + j], moves[sb + j], moves[sc + j]);
            if da == Vec3::ZERO && db == Vec3::ZERO && dc == Vec3::ZERO {
                return false;
            }
            turned(rest, (b + db) - (a + da), (c + dc) - (a + da), cos_max)
        });
        folds.then_some(*t)
    };
    let mut out: Vec<usize> = if parallel {
        suspects.par_iter().filter_map(folded).flatten().collect()
    } else {
        suspects.iter().filter_map(folded).flatten().collect()
    };
    out.sort_unstable();
    out.dedup();
    out
}

/// Whether the triangle of edges `e1`, `e2` has turned from the rest normal `rest` by more
/// than the angle of `cos_max` (or collapsed).
fn turned(rest: Vec3, e1: Vec3, e2: Vec3, cos_max: f32) -> bool {
    let moved = e1.cross(e2);
    let len = (rest.length() * moved.length()).max(f32::MIN_POSITIVE);
    moved.length_squared() <= 0.0 || rest.dot(moved) / len < cos_max
}

/// The largest turn of any triangle, degrees, and how many turn by more than 90°, when
/// `moves` moves the vertices of `positions` (for tests and reports).
pub fn worst_turn(positions: &[Vec3], indices: &[u32], moves: &[Vec3]) -> (f32, usize) {
    let (mut worst, mut flipped) = (0.0f32, 0);
    for t in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| t[k] as usize);
        let rest = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
        let p = |v: usize| positions[v] + moves[v];
        let moved = (p(b) - p(a)).cross(p(c) - p(a));
        let len = rest.length() * moved.length();
        if len <= 0.0 || !len.is_finite() {
            continue;
        }
        let deg = (rest.dot(moved) / len).clamp(-1.0, 1.0).acos().to_degrees();
        worst = worst.max(deg);
        flipped += usize::from(deg > 90.0);
    }
    (worst, flipped)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of thin triangles across a step in the move: the field jumps by more than
    /// the triangles are wide, so they fold; unfolded, none turns by more than the limit,
    /// and the mean move is kept.
    #[test]
    fn a_step_sharper_than_the_triangles_is_spread_until_nothing_folds() {
        let cols = 12;
        let mut positions = Vec::new();
        for y in 0..2 {
            for x in 0..=cols {
                positions.push(Vec3::new(x as f32 * 0.001, y as f32 * 0.02, 0.0));
            }
        }
        let mut indices = Vec::new();
        let row = cols as u32 + 1;
        for x in 0..cols as u32 {
            indices.extend([x, x + 1, x + row, x + 1, x + row + 1, x + row]);
        }
        // A move along x that jumps by 3 mm between columns 5 and 7 (1 mm apart).
        let field: Vec<Vec3> = positions
            .iter()
            .map(|p| Vec3::new(if p.x > 0.0055 { -0.003 } else { 0.0 }, 0.0, 0.0))
            .collect();
        let (before, flipped) = worst_turn(&positions, &indices, &field);
        assert!(before > 90.0 && flipped > 0, "{before}");
        let welded: Vec<u32> = (0..positions.len() as u32).collect();
        let mut fields = vec![field.clone()];
        let caps = vec![f32::INFINITY; positions.len()];
        let changed = unfold(
            &positions,
            &indices,
            &welded,
            &mut fields,
            &[vec![1.0]],
            &caps,
            f32::INFINITY,
        );
        assert!(changed > 0);
        let (after, flipped) = worst_turn(&positions, &indices, &fields[0]);
        assert!(after <= MAX_TURN_DEG + 1e-3 && flipped == 0, "{after}");
        // Spread, not removed: most of the move is still there.
        let sum = |f: &[Vec3]| f.iter().map(|d| d.x).sum::<f32>().abs();
        assert!(
            sum(&fields[0]) > 0.5 * sum(&field),
            "{} {}",
            sum(&fields[0]),
            sum(&field)
        );
    }

    #[test]
    fn a_move_that_folds_nothing_is_left_as_it_is() {
        let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
        let indices = vec![0, 1, 2];
        let mut fields = vec![vec![Vec3::Z * 0.1; 3]];
        let kept = fields.clone();
        assert_eq!(
            unfold(
                &positions,
                &indices,
                &[0, 1, 2],
                &mut fields,
                &[vec![1.0]],
                &[f32::INFINITY; 3],
                f32::INFINITY,
            ),
            0
        );
        assert_eq!(fields, kept);
    }
}
