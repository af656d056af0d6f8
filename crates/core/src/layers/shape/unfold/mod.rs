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
//! round what changed are checked again, so a dense head costs what its folds do, and a
//! fold that no longer folds stops spreading (its vertices hold still, walls to the folds
//! round it): relaxed on for every pass while other folds went on, the spread rings had
//! flattened what lay in them (the default head's temple hollow at 80 to 5–6 mm of its
//! 13–14, one earlobe's 8.5 mm descent to 0.3, the other's to 5), and a dense scan spent
//! two thirds of its sweeps there.

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
/// Vertices in a block of [`Moves::take`]'s and [`Moves::give_back`]'s copies.
const COPY_BLOCK: usize = 4096;
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
///
/// The regions' moves are held together per vertex while it works ([`Moves`]): a sweep
/// reads each neighbour's moves of every region at once (on a dense head the sweeps over
/// the spread rings are most of the shape's cost).
pub fn unfold(
    positions: &[Vec3],
    indices: &[u32],
    welded: &[u32],
    fields: &mut [Vec<Vec3>],
    checks: &[Vec<f32>],
    caps: &[f32],
    reach: f32,
) -> usize {
    if fields.iter().all(|f| f.iter().all(|d| *d == Vec3::ZERO)) || positions.is_empty() {
        return 0;
    }
    let topology = Topology::new(positions.len(), indices, welded);
    unfold_on(
        &topology, positions, welded, fields, checks, caps, reach, None,
    )
    .changed
}

/// The welded mesh as [`unfold`] walks it: its triangles over welded vertices, each
/// welded vertex's neighbours and triangles. Made once for rounds of unfolding on one
/// mesh ([`unfold_on`]).
pub struct Topology {
    triangles: Vec<[usize; 3]>,
    neighbours: Adjacency,
    incident: Adjacency,
}

impl Topology {
    /// Of the `n` vertices `welded` (each the first at its position) and `indices`.
    pub fn new(n: usize, indices: &[u32], welded: &[u32]) -> Self {
        let triangles: Vec<[usize; 3]> = indices
            .chunks_exact(3)
            .map(|t| [0, 1, 2].map(|k| welded[t[k] as usize] as usize))
            .filter(|t| t.iter().all(|&v| v < n))
            .collect();
        let (neighbours, incident) = Adjacency::new(n, &triangles);
        Self {
            triangles,
            neighbours,
            incident,
        }
    }
}

/// What one [`unfold_on`] did.
#[derive(Clone, Debug, Default)]
pub struct Unfolded {
    /// How many vertices its spread moved.
    pub changed: usize,
    /// Every (welded) vertex whose moves it wrote: where a later round on the same fields
    /// looks for folds ([`unfold_on`]'s `from`).
    pub written: Vec<usize>,
}

/// [`unfold`] on a [`Topology`] made of the same mesh. With `from`, the moves are those a
/// round before left, unfolded but for the triangles round the vertices it wrote (its
/// [`Unfolded::written`]): only those are looked at first (every other triangle was
/// found unfolded and has not changed since), not every triangle that moves.
#[allow(clippy::too_many_arguments)]
pub fn unfold_on(
    topology: &Topology,
    positions: &[Vec3],
    welded: &[u32],
    fields: &mut [Vec<Vec3>],
    checks: &[Vec<f32>],
    caps: &[f32],
    reach: f32,
    from: Option<&[usize]>,
) -> Unfolded {
    let n = positions.len();
    if fields.iter().all(|f| f.iter().all(|d| *d == Vec3::ZERO)) || n == 0 {
        return Unfolded::default();
    }
    let Topology {
        triangles,
        neighbours,
        incident,
    } = topology;
    let mut moves = Moves::take(fields, n);
    let cos_max = MAX_TURN_DEG.to_radians().cos();
    // Only what moves is relaxed (a vertex that stays — off every region, not skin — stays:
    // it holds the spread like a wall). First every triangle that moves is checked; then
    // only those round what changed.
    let moving: Vec<bool> = (0..n)
        .map(|v| moves.row(v).iter().any(|d| *d != Vec3::ZERO))
        .collect();
    let mut suspected = vec![false; triangles.len()];
    let mut suspects: Vec<usize> = match from {
        None => (0..triangles.len())
            .filter(|&i| triangles[i].iter().any(|&v| moving[v]))
            .collect(),
        Some(from) => {
            let mut round: Vec<usize> = Vec::new();
            for &v in from.iter().filter(|&&v| v < n) {
                for &i in incident.of(v) {
                    if !std::mem::replace(&mut suspected[i as usize], true) {
                        round.push(i as usize);
                    }
                }
            }
            round.iter().for_each(|&i| suspected[i] = false);
            round.retain(|&i| triangles[i].iter().any(|&v| moving[v]));
            round
        }
    };
    // Every vertex whose moves a pass wrote.
    let mut written = vec![false; n];
    // The vertices relaxed each pass: every fold's corners and their ring so far, grown by
    // one more ring whenever the folds stop shrinking (a fold whose surroundings jump too
    // needs a wider spread).
    let mut active = vec![false; n];
    // The fold each active vertex spreads: the corner that made it active, or whose ring
    // it joined (a ring grows only within `reach` of it).
    let mut seed = vec![usize::MAX; n];
    // The active vertices, in the order they became so (the relaxation does not depend on
    // the order; the growth goes in vertex order).
    let mut ring: Vec<usize> = Vec::new();
    // The folds (by their seed) that still fold this pass (set from the pass's folded
    // corners and cleared from them again, not over every vertex: a dense head's passes).
    let mut live_seed = vec![false; n];
    // Every vertex the spread has moved.
    let mut ever = vec![false; n];
    let mut slots = vec![u32::MAX; n];
    let mut best = usize::MAX;
    let mut stalled = 0;
    for pass in 0..SPREAD_PASSES + SHRINK_PASSES {
        let bad = folded_vertices(
            positions, triangles, &suspects, &moves, checks, cos_max, &mut slots,
        );
        if bad.is_empty() {
            break;
        }
        let mut touched: Vec<usize> = Vec::new();
        if pass >= SPREAD_PASSES {
            // What still folds is shrunk in place with its ring, the ring less, so that
            // the shrink makes no new step.
            let mut ring: Vec<usize> = bad
                .iter()
                .flat_map(|&v| neighbours.of(v).iter().map(|&u| u as usize))
                .filter(|&v| moving[v])
                .collect();
            ring.sort_unstable();
            ring.dedup();
            for &v in &ring {
                moves.row_mut(v).iter_mut().for_each(|d| *d *= 0.75);
            }
            for &v in &bad {
                moves.row_mut(v).iter_mut().for_each(|d| *d *= 2.0 / 3.0);
            }
            touched.extend(ring);
            touched.extend_from_slice(&bad);
        } else {
            let activate = |v: usize, active: &mut [bool], ring: &mut Vec<usize>| {
                if moving[v] && !active[v] {
                    active[v] = true;
                    ring.push(v);
                }
            };
            for &v in &bad {
                if seed[v] == usize::MAX {
                    seed[v] = v;
                }
                activate(v, &mut active, &mut ring);
                for &u in neighbours.of(v) {
                    let u = u as usize;
                    activate(u, &mut active, &mut ring);
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
                ring.sort_unstable();
                let grown: Vec<(usize, usize)> = (ring.iter().copied())
                    .flat_map(|v| neighbours.of(v).iter().map(move |&u| (u as usize, v)))
                    .filter(|&(u, v)| !active[u] && seed[v] != usize::MAX)
                    .collect();
                for (u, v) in grown {
                    let from = seed[v];
                    if moving[u] && positions[u].distance(positions[from]) <= reach {
                        activate(u, &mut active, &mut ring);
                        if seed[u] == usize::MAX {
                            seed[u] = from;
                        }
                    }
                }
            }
            // A fold that no longer folds is left as it stands: its spread stops (its
            // vertices hold still, walls to the folds round it, and join again if they
            // fold again). On the scan split three times two thirds of the ring had no
            // fold left by the 8th pass and were relaxed for 120 more.
            ring.iter().for_each(|&v| ever[v] = true);
            for &v in &bad {
                if let Some(l) = live_seed.get_mut(seed[v]) {
                    *l = true;
                }
            }
            ring.retain(|&v| {
                let keep = live_seed.get(seed[v]).copied().unwrap_or(true);
                active[v] = keep;
                keep
            });
            for &v in &bad {
                if let Some(l) = live_seed.get_mut(seed[v]) {
                    *l = false;
                }
            }
            // Each active vertex takes the mean of its neighbours' move, half way, more
            // sweeps as the passes go on (a wide fold on a dense head needs many).
            let sweeps = (1 + pass / 4).min(MAX_SWEEPS);
            // A region's field that is zero over the ring and its neighbours stays zero
            // under the sweeps: it is left alone (most regions, at most folds).
            let live = moves.live(&ring, neighbours);
            let mut relaxed = vec![Vec3::ZERO; ring.len() * moves.regions];
            let mut masks = Vec::new();
            for _ in 0..sweeps {
                moves.relax(&ring, neighbours, &live, &mut relaxed, &mut masks);
                moves.cap(&ring, caps);
            }
            touched = ring.clone();
        }
        touched.iter().for_each(|&v| written[v] = true);
        // Each triangle once (their order does not matter).
        suspects.clear();
        for &v in &touched {
            for &i in incident.of(v) {
                if !std::mem::replace(&mut suspected[i as usize], true) {
                    suspects.push(i as usize);
                }
            }
        }
        suspects.iter().for_each(|&i| suspected[i] = false);
    }
    ring.iter().for_each(|&v| ever[v] = true);
    let changed = ever.iter().filter(|&&e| e).count();
    // Split vertices take their position's move.
    let r = moves.regions;
    for (v, &w) in welded.iter().enumerate().take(n) {
        let w = w as usize;
        if w != v && w < n {
            moves.all.copy_within(w * r..(w + 1) * r, v * r);
        }
    }
    moves.give_back(fields);
    Unfolded {
        changed,
        written: (0..n).filter(|&v| written[v]).collect(),
    }
}

/// Each vertex's neighbours or triangles, in one array (`of(v)`), in the order they were
/// met.
struct Adjacency {
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Adjacency {
    /// The neighbours (each once) and the triangles of every vertex below `n`.
    fn new(n: usize, triangles: &[[usize; 3]]) -> (Self, Self) {
        let mut count = vec![0u32; n + 1];
        for t in triangles {
            for &v in t {
                count[v + 1] += 1;
            }
        }
        for v in 0..n {
            count[v + 1] += count[v];
        }
        // A vertex has at most two neighbours per triangle.
        let mut incident = vec![0u32; count[n] as usize];
        let mut around = vec![0u32; 2 * count[n] as usize];
        let (mut filled, mut met) = (vec![0u32; n], vec![0u32; n]);
        for (i, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                let a = t[k];
                let base = count[a] as usize;
                incident[base + filled[a] as usize] = i as u32;
                filled[a] += 1;
                for j in 1..3 {
                    let b = t[(k + j) % 3] as u32;
                    let slot = &mut around[2 * base..2 * base + met[a] as usize];
                    if !slot.contains(&b) {
                        around[2 * base + met[a] as usize] = b;
                        met[a] += 1;
                    }
                }
            }
        }
        let mut start = vec![0u32; n + 1];
        let mut items = Vec::with_capacity(met.iter().map(|&m| m as usize).sum());
        for v in 0..n {
            let base = 2 * count[v] as usize;
            items.extend_from_slice(&around[base..base + met[v] as usize]);
            start[v + 1] = items.len() as u32;
        }
        (
            Self { start, items },
            Self {
                start: count,
                items: incident,
            },
        )
    }

    fn of(&self, v: usize) -> &[u32] {
        &self.items[self.start[v] as usize..self.start[v + 1] as usize]
    }
}

/// Every region's move of every vertex, a vertex's moves side by side (`row(v)`): taken
/// from the per-region fields and given back to them.
struct Moves {
    regions: usize,
    all: Vec<Vec3>,
    /// Per vertex, a bit ([`region_bit`]) for each region that may move it (set wherever
    /// the move is not zero; a zero move round a vertex stays zero under the sweeps, which
    /// skip it: a vertex is moved by one to three regions).
    masks: Vec<u64>,
    /// What each field held past the mesh's vertices (nothing, on a well-made field).
    tails: Vec<Vec<Vec3>>,
}

impl Moves {
    fn take(fields: &mut [Vec<Vec3>], n: usize) -> Self {
        let regions = fields.len();
        let r = regions.max(1);
        let mut all = vec![Vec3::ZERO; n * regions];
        // Block by block of vertices (a block's rows stay in the cache while each field's
        // stretch is read into them: written field by field over the whole mesh, each
        // store a row's length from the last, the copy was a sixth of a dense head's
        // unfolding).
        let fields_ro: &[Vec<Vec3>] = fields;
        all.par_chunks_mut(r * COPY_BLOCK)
            .enumerate()
            .for_each(|(b, rows)| {
                let first = b * COPY_BLOCK;
                for (k, field) in fields_ro.iter().enumerate() {
                    let stretch = field.get(first..).unwrap_or(&[]);
                    for (row, d) in rows.chunks_exact_mut(r).zip(stretch) {
                        row[k] = *d;
                    }
                }
            });
        let tails = fields
            .iter_mut()
            .map(|field| {
                let mut field = std::mem::take(field);
                field.split_off(n.min(field.len()))
            })
            .collect();
        let masks = (all.chunks(r).take(n))
            .map(|row| {
                (row.iter().enumerate())
                    .filter(|(_, d)| **d != Vec3::ZERO)
                    .fold(0, |m, (k, _)| m | region_bit(k))
            })
            .collect();
        Self {
            regions,
            all,
            masks,
            tails,
        }
    }

    fn give_back(self, fields: &mut [Vec<Vec3>]) {
        let r = self.regions.max(1);
        let n = self.all.len() / r;
        let mut out: Vec<Vec<Vec3>> = (0..self.regions).map(|_| vec![Vec3::ZERO; n]).collect();
        // Each block of vertices: every field's stretch of it ([`Moves::take`]'s blocks).
        let mut blocks: Vec<Vec<&mut [Vec3]>> = (0..n.div_ceil(COPY_BLOCK))
            .map(|_| Vec::with_capacity(self.regions))
            .collect();
        for field in &mut out {
            for (b, stretch) in field.chunks_mut(COPY_BLOCK).enumerate() {
                blocks[b].push(stretch);
            }
        }
        let all = &self.all;
        blocks
            .into_par_iter()
            .enumerate()
            .for_each(|(b, mut stretches)| {
                let rows = &all[b * COPY_BLOCK * r..];
                for (k, stretch) in stretches.iter_mut().enumerate() {
                    for (d, row) in stretch.iter_mut().zip(rows.chunks_exact(r)) {
                        *d = row[k];
                    }
                }
            });
        for ((field, mut moved), tail) in fields.iter_mut().zip(out).zip(self.tails) {
            moved.extend(tail);
            *field = moved;
        }
    }

    fn row(&self, v: usize) -> &[Vec3] {
        &self.all[v * self.regions..(v + 1) * self.regions]
    }

    fn row_mut(&mut self, v: usize) -> &mut [Vec3] {
        &mut self.all[v * self.regions..(v + 1) * self.regions]
    }

    /// Whether each region may move anything over `ring` and its neighbours.
    fn live(&self, ring: &[usize], neighbours: &Adjacency) -> Vec<bool> {
        let mut mask = 0;
        for &v in ring {
            mask |= self.masks[v];
            neighbours
                .of(v)
                .iter()
                .for_each(|&u| mask |= self.masks[u as usize]);
        }
        (0..self.regions)
            .map(|k| mask & region_bit(k) != 0)
            .collect()
    }

    /// One Jacobi sweep over `ring`: each vertex's move of each `live` region half way to
    /// its neighbours' mean (every new value from the old ones; `relaxed` the scratch of
    /// ring × regions). A region that moves neither the vertex nor a neighbour is skipped
    /// (its move stays zero).
    fn relax(
        &mut self,
        ring: &[usize],
        neighbours: &Adjacency,
        live: &[bool],
        relaxed: &mut [Vec3],
        masks: &mut Vec<u64>,
    ) {
        let r = self.regions;
        if r == 0 {
            return;
        }
        let live = (0..r)
            .filter(|&k| live[k])
            .fold(0, |m, k| m | region_bit(k));
        let (all, old_masks) = (&self.all, &self.masks);
        let relax_one = |((out, mask), &v): ((&mut [Vec3], &mut u64), &usize)| {
            let own = &all[v * r..(v + 1) * r];
            let around = neighbours.of(v);
            let near = around
                .iter()
                .fold(old_masks[v], |m, &u| m | old_masks[u as usize])
                & live;
            // The regions relaxed here (only they are written back).
            *mask = if around.is_empty() { 0 } else { near };
            if *mask == 0 {
                return;
            }
            let count = around.len() as f32;
            for (k, (o, d)) in out.iter_mut().zip(own).enumerate() {
                if near & region_bit(k) == 0 {
                    continue;
                }
                let sum = (around.iter()).fold(Vec3::ZERO, |s, &u| s + all[u as usize * r + k]);
                *o = 0.5 * (*d + sum / count);
            }
        };
        // In parallel only where it pays (a dense head's ring): a small ring costs less
        // than the pool's start.
        let relaxed = &mut relaxed[..ring.len() * r];
        masks.resize(ring.len(), 0);
        if ring.len() >= PARALLEL_RING {
            (relaxed.par_chunks_mut(r).zip(masks.par_iter_mut()))
                .zip(ring.par_iter())
                .for_each(relax_one);
        } else {
            (relaxed.chunks_mut(r).zip(masks.iter_mut()))
                .zip(ring.iter())
                .for_each(relax_one);
        }
        for ((&v, row), &mask) in ring.iter().zip(relaxed.chunks(r)).zip(masks.iter()) {
            if mask == 0 {
                continue;
            }
            let own = &mut self.all[v * r..(v + 1) * r];
            for (k, (o, d)) in own.iter_mut().zip(row).enumerate() {
                if mask & region_bit(k) != 0 {
                    *o = *d;
                }
            }
            self.masks[v] |= mask;
        }
    }

    /// Shortens the move at full age of each vertex of `ring` to its cap (every region
    /// alike).
    fn cap(&mut self, ring: &[usize], caps: &[f32]) {
        for &v in ring {
            let limit = caps.get(v).copied().unwrap_or(f32::INFINITY);
            if !limit.is_finite() {
                continue;
            }
            let row = self.row_mut(v);
            let len = row.iter().copied().sum::<Vec3>().length();
            if len > limit && len > 0.0 {
                let s = limit / len;
                row.iter_mut().for_each(|d| *d *= s);
            }
        }
    }
}

/// Region k's bit in [`Moves`]' masks (regions past the 64th share the last).
fn region_bit(k: usize) -> u64 {
    1 << k.min(63)
}

/// The corners of the triangles that turn by more than the limit under any check
/// (`slots`: one entry per vertex, all `u32::MAX`, left so).
fn folded_vertices(
    positions: &[Vec3],
    triangles: &[[usize; 3]],
    suspects: &[usize],
    moves: &Moves,
    checks: &[Vec<f32>],
    cos_max: f32,
    slots: &mut [u32],
) -> Vec<usize> {
    // Each check's move of every corner of a suspect, once (a corner is shared by about
    // six triangles): `corner_moves[slot · checks + k]`.
    // Each corner once, numbered in `slots` (their order does not matter).
    let mut corners: Vec<usize> = Vec::new();
    for &v in suspects.iter().flat_map(|&i| &triangles[i]) {
        if slots[v] == u32::MAX {
            slots[v] = corners.len() as u32;
            corners.push(v);
        }
    }
    let k = checks.len();
    let mut corner_moves = vec![Vec3::ZERO; corners.len() * k];
    let one_corner = |(out, &v): (&mut [Vec3], &usize)| {
        // Only the regions that move this corner (one to three of them, mostly).
        for (r, d) in moves.row(v).iter().enumerate() {
            if *d != Vec3::ZERO {
                for (o, factors) in out.iter_mut().zip(checks) {
                    *o += *d * factors[r];
                }
            }
        }
    };
    let parallel = suspects.len() >= PARALLEL_RING;
    if parallel {
        (corner_moves
            .par_chunks_mut(k.max(1))
            .zip(corners.par_iter()))
        .for_each(one_corner);
    } else {
        (corner_moves.chunks_mut(k.max(1)).zip(corners.iter())).for_each(one_corner);
    }
    let slots_ro: &[u32] = slots;
    let slot = |v: usize| slots_ro[v] as usize * k;
    let folded = |&i: &usize| {
        let t = &triangles[i];
        let [a, b, c] = t.map(|v| positions[v]);
        let rest = (b - a).cross(c - a);
        if rest.length_squared() <= 0.0 || !rest.is_finite() {
            return None;
        }
        let [sa, sb, sc] = t.map(slot);
        let folds = (0..k).any(|j| {
            let (da, db, dc) = (
                corner_moves[sa + j],
                corner_moves[sb + j],
                corner_moves[sc + j],
            );
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
    for &v in &corners {
        slots[v] = u32::MAX;
    }
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
mod tests;
