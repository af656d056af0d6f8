//! Fractal gradient noise (fBm) of docs/models.md §4 "Noise" [P §3.4, eq. 17], periodic when tiling.
//!
//! fBm(p) = Σ_k w_k · noise(c_k · p + o_k) / Σ_k w_k with w_k = g^k (g = `roughness`), the
//! last octave weighted by the fractional part of `details`, c_k = c_0 · lacunarity^k lattice
//! cells across the map and o_k a per-octave random lattice offset. `noise` is 2-D gradient
//! (Perlin) noise with the quintic fade 6t⁵ − 15t⁴ + 10t³ and 8 unit gradients, scaled by √2
//! so that |noise| ≤ 1; hence |fBm| ≤ 1, and the mean is 0 for every octave count (each
//! octave is zero at its lattice points and symmetric in sign), which keeps the mean level
//! independent of `details` (a complaint about other tools).
//!
//! **Tiling.** When the map tiles, c_k is rounded to a whole number of cells and lattice
//! indices wrap modulo c_k, so every octave is periodic over the map (u → u + 1).
//!
//! **Speed.** [`RowSampler`] evaluates whole rows. Gradient noise in a cell regroups as
//! W0·Q_y(j) + W1·Q_y(j+1) + W2·Q_x(j) + W3·Q_x(j+1), where the weights W depend on the
//! pixel row only and Q(j) on the column and the gradients of lattice row j only
//! ([`Octave::row_weights`]). Per octave it keeps Q of the lattice rows a block of pixel
//! rows needs, computed once per lattice row (each lattice point hashed once per lattice
//! row, not per pixel). A pixel octave then costs four loads, four products and four sums
//! over contiguous arrays in chunks of [`LANES`] with no per-cell runs, which the compiler
//! vectorises (see `micro::bake` for the AVX2 / AVX-512 dispatch); a block of rows goes
//! through in column tiles, so those arrays are read from L1, not L2. The result is
//! bit-identical to the scalar [`FbmField::sample`].

use crate::base::simd::{Chunk, LANES, resize_chunks};

/// Parameters of one fBm (docs/models.md §4 "Noise"); validated by `project::NoiseSection`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FbmParams {
    /// Octaves; fractional values blend in the last octave; 0 = no noise. Range 0–12.
    pub details: f32,
    /// Amplitude gain g from one octave to the next. Range 0–1.
    pub roughness: f32,
    /// Frequency factor from one octave to the next. Range 0.1–4.
    pub lacunarity: f32,
    /// Size of one lattice cell of the first octave, in millimetres. Range > 0.
    pub scale_mm: f32,
}

/// The 8 unit gradients (exact literals so every platform agrees).
const GRADIENTS: [[f32; 2]; 8] = [
    [1.0, 0.0],
    [-1.0, 0.0],
    [0.0, 1.0],
    [0.0, -1.0],
    [
        std::f32::consts::FRAC_1_SQRT_2,
        std::f32::consts::FRAC_1_SQRT_2,
    ],
    [
        -std::f32::consts::FRAC_1_SQRT_2,
        std::f32::consts::FRAC_1_SQRT_2,
    ],
    [
        std::f32::consts::FRAC_1_SQRT_2,
        -std::f32::consts::FRAC_1_SQRT_2,
    ],
    [
        -std::f32::consts::FRAC_1_SQRT_2,
        -std::f32::consts::FRAC_1_SQRT_2,
    ],
];

/// One octave of an [`FbmField`].
#[derive(Clone, Debug)]
struct Octave {
    /// Lattice cells across the map in u and in v.
    cells_u: f32,
    cells_v: f32,
    /// Lattice period in cells (tiling), or `None`.
    period: Option<(i32, i32)>,
    offset: [f32; 2],
    /// Final amplitude: gain · √2 · w_k / Σw.
    amplitude: f32,
    hash_seed: u32,
}

/// An fBm over a map of `size_mm` × `size_mm`, in UV (docs/models.md §1), fixed by its seed.
#[derive(Clone, Debug)]
pub struct FbmField {
    octaves: Vec<Octave>,
}

impl FbmField {
    /// Builds the octaves. `gain` multiplies the whole field (λ of eq. 17 or the warp
    /// strength); `salt` separates independent fields drawn from the same seed.
    pub fn new(
        params: &FbmParams,
        size_mm: f32,
        tile: bool,
        gain: f32,
        seed: u64,
        salt: u64,
    ) -> Self {
        let n = params.details.max(0.0).ceil() as usize;
        let mut weights = Vec::with_capacity(n);
        let mut w = 1.0f32;
        for k in 0..n {
            let frac = (params.details - k as f32).min(1.0);
            weights.push(w * frac);
            w *= params.roughness;
        }
        let total: f32 = weights.iter().sum();
        let mut rng = crate::base::rng::Rng::for_stream(seed, 0x6e6f_6973_6500 ^ salt);
        let mut octaves = Vec::with_capacity(n);
        let mut cells = size_mm / params.scale_mm;
        for (k, &wk) in weights.iter().enumerate() {
            let (cells_k, period) = if tile {
                let c = cells.round().max(1.0);
                (c, Some((c as i32, c as i32)))
            } else {
                (cells, None)
            };
            let offset = [rng.next_f32() * 64.0, rng.next_f32() * 64.0];
            let hash_seed = (rng.next_u64() >> 32) as u32 ^ k as u32;
            octaves.push(Octave {
                cells_u: cells_k,
                cells_v: cells_k,
                period,
                offset,
                amplitude: if total > 0.0 {
                    gain * std::f32::consts::SQRT_2 * wk / total
                } else {
                    0.0
                },
                hash_seed,
            });
            cells *= params.lacunarity;
        }
        Self { octaves }
    }

    /// Number of octaves actually evaluated.
    pub fn octave_count(&self) -> usize {
        self.octaves.len()
    }

    /// Lattice cells across the map of the finest octave (0 without octaves).
    pub fn finest_cells(&self) -> f32 {
        self.octaves.iter().map(|o| o.cells_u).fold(0.0, f32::max)
    }

    /// gain · fBm at (u, v), scalar reference of [`RowSampler::add_row`] (bit-identical).
    pub fn sample(&self, u: f32, v: f32) -> f32 {
        let mut acc = 0.0f32;
        for o in &self.octaves {
            let (j, w) = o.row_weights(v);
            let x = u * o.cells_u + o.offset[0];
            let i = x.floor();
            let b = basis_of(x - i);
            let i = i as i32;
            let q = |j: i32| lattice_row_terms(o.gradient(i, j), o.gradient(i + 1, j), b);
            let ([qy0, qx0], [qy1, qx1]) = (q(j), q(j + 1));
            acc += combine(w, qy0, qy1, qx0, qx1);
        }
        acc
    }
}

/// One octave's value from the row weights and the four lattice-row terms (the exact
/// operation order shared by [`FbmField::sample`] and [`RowSampler::add_row`]).
#[inline(always)]
fn combine(w: [f32; 4], qy0: f32, qy1: f32, qx0: f32, qx1: f32) -> f32 {
    w[0] * qy0 + w[1] * qy1 + w[2] * qx0 + w[3] * qx1
}

/// For the lattice row j and a column in cell i: (Q_y, Q_x) = (g_y(i,j)·b0 + g_y(i+1,j)·b1,
/// g_x(i,j)·b2 + g_x(i+1,j)·b3), the parts of the noise that depend on j only through
/// the gradients (see [`Octave::row_weights`]).
#[inline(always)]
fn lattice_row_terms(ga: [f32; 2], gb: [f32; 2], b: [f32; 4]) -> [f32; 2] {
    [ga[1] * b[0] + gb[1] * b[1], ga[0] * b[2] + gb[0] * b[3]]
}

impl Octave {
    /// The lattice row j below v and the row weights of the decomposition
    /// noise = W0·Q_y(j) + W1·Q_y(j+1) + W2·Q_x(j) + W3·Q_x(j+1) with (fy, sy) the offset in
    /// the cell and its fade: W = amp·(fy(1 − sy), (fy − 1)·sy, 1 − sy, sy). This is the
    /// gradient-noise sum g00·(fx, fy)·(1−t)(1−sy) + … regrouped so that, along a row, the
    /// per-column factors Q depend on the lattice row only and are reused by every pixel row
    /// in the same lattice row.
    #[inline(always)]
    fn row_weights(&self, v: f32) -> (i32, [f32; 4]) {
        let y = v * self.cells_v + self.offset[1];
        let j = y.floor();
        let fy = y - j;
        let sy = fade(fy);
        let a = self.amplitude;
        (
            j as i32,
            [
                fy * (1.0 - sy) * a,
                (fy - 1.0) * sy * a,
                (1.0 - sy) * a,
                sy * a,
            ],
        )
    }

    #[inline]
    fn gradient(&self, i: i32, j: i32) -> [f32; 2] {
        let (i, j) = match self.period {
            Some((pu, pv)) => (i.rem_euclid(pu), j.rem_euclid(pv)),
            None => (i, j),
        };
        GRADIENTS[(hash3(i as u32, j as u32, self.hash_seed) >> 29) as usize]
    }
}

/// A 32-bit integer hash of a lattice point (lowbias32 finaliser by C. Wellons).
#[inline]
fn hash3(i: u32, j: u32, seed: u32) -> u32 {
    let mut h =
        i.wrapping_mul(0x8DA6_B343) ^ j.wrapping_mul(0xD816_3841) ^ seed.wrapping_mul(0xCB1A_B31F);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7FEB_352D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846C_A68B);
    h ^ (h >> 16)
}

/// The quintic fade 6t⁵ − 15t⁴ + 10t³.
#[inline(always)]
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// The per-column basis: noise = c0·(1−t) + c1·t + d0·fx(1−t) + d1·(fx−1)·t.
#[inline(always)]
fn basis(fx: f32, t: f32) -> [f32; 4] {
    [1.0 - t, t, fx * (1.0 - t), (fx - 1.0) * t]
}

/// Per-octave column tables of a [`RowSampler`].
#[derive(Clone, Debug)]
struct OctaveColumns {
    /// Runs of columns in the same lattice cell: (cell index i, first column, end column).
    runs: Vec<(i32, u32, u32)>,
    /// The four per-column basis functions (1 − t, t, fx(1 − t), (fx − 1)·t), one array
    /// each.
    basis: [Vec<f32>; 4],
}

/// Evaluates an [`FbmField`] along rows at a fixed, increasing list of u positions.
#[derive(Clone, Debug)]
pub struct RowSampler<'a> {
    field: &'a FbmField,
    columns: Vec<OctaveColumns>,
    len: usize,
}

/// The Q_y and Q_x rows of one lattice row of one octave (see [`Octave::row_weights`]).
#[derive(Clone, Debug, Default)]
struct LatticeRow {
    j: Option<i32>,
    qy: Vec<Chunk>,
    qx: Vec<Chunk>,
}

/// Recently used lattice rows of one octave: at least the ones a block of pixel rows
/// needs at once (all lattice rows from the top block row's j to the bottom one's j + 1),
/// plus a few kept for the next block (whose halo row above is this block's last row).
#[derive(Clone, Debug, Default)]
struct Slots {
    rows: Vec<LatticeRow>,
    used: Vec<u64>,
    clock: u64,
}

/// Per-thread scratch space of [`RowSampler::add_rows`]: per octave, the lattice rows of the
/// last rows evaluated (neighbouring pixel rows mostly share them).
#[derive(Clone, Debug, Default)]
pub struct RowScratch {
    rows: Vec<Slots>,
    /// Per octave and block row: the slots of lattice rows j and j + 1, and the row weights.
    plan: Vec<Vec<([usize; 2], [f32; 4])>>,
    /// Reused per octave: each block row's lattice row j and weights, and the slots of
    /// the block's lattice rows (kept here so a call allocates nothing once warm).
    weights: Vec<(i32, [f32; 4])>,
    found: Vec<usize>,
}

/// Columns per tile of [`RowSampler::add_rows`]: the lattice-row slices of a tile (four
/// arrays per octave, times the rows a block spans) stay in the L1 cache while every
/// pixel row of the block reads them.
const TILE: usize = 256;

impl<'a> RowSampler<'a> {
    /// Precomputes the column tables for the positions `us` (must be non-decreasing).
    pub fn new(field: &'a FbmField, us: &[f32]) -> Self {
        let columns = field
            .octaves
            .iter()
            .map(|o| {
                let mut runs: Vec<(i32, u32, u32)> = Vec::new();
                let mut basis: [Vec<f32>; 4] =
                    std::array::from_fn(|_| Vec::with_capacity(us.len()));
                for (c, &u) in us.iter().enumerate() {
                    let x = u * o.cells_u + o.offset[0];
                    let i = x.floor();
                    let b = basis_of(x - i);
                    for (dst, val) in basis.iter_mut().zip(b) {
                        dst.push(val);
                    }
                    let i = i as i32;
                    match runs.last_mut() {
                        Some(last) if last.0 == i => last.2 = c as u32 + 1,
                        _ => runs.push((i, c as u32, c as u32 + 1)),
                    }
                }
                OctaveColumns { runs, basis }
            })
            .collect();
        Self {
            field,
            columns,
            len: us.len(),
        }
    }

    /// Fills `row` with Q_y, Q_x of lattice row `j` of octave `k`. Inlined into the
    /// dispatched kernels (see `crate::base::simd`), so its column loop is vectorised for them.
    #[inline(always)]
    fn lattice_row(&self, k: usize, j: i32, row: &mut LatticeRow) {
        let (o, cols) = (&self.field.octaves[k], &self.columns[k]);
        let padded = self.len.next_multiple_of(LANES);
        resize_chunks(&mut row.qy, padded);
        resize_chunks(&mut row.qx, padded);
        let qy: &mut [f32] = bytemuck::cast_slice_mut(&mut row.qy);
        let qx: &mut [f32] = bytemuck::cast_slice_mut(&mut row.qx);
        let [b0, b1, b2, b3] = &cols.basis;
        if cols.runs.is_empty() {
            return;
        }
        // The right gradient of one run is the left gradient of the next only when the runs
        // are in neighbouring cells; a row with fewer pixels than the octave has cells skips
        // cells, and then the left gradient must be hashed again.
        let mut previous: Option<(i32, [f32; 2])> = None;
        for &(i, x0, x1) in &cols.runs {
            let ga = match previous {
                Some((next_i, g)) if next_i == i => g,
                _ => o.gradient(i, j),
            };
            let gb = o.gradient(i + 1, j);
            let r = x0 as usize..x1 as usize;
            let basis = b0[r.clone()]
                .iter()
                .zip(&b1[r.clone()])
                .zip(b2[r.clone()].iter().zip(&b3[r.clone()]));
            for ((qy, qx), ((&p, &q), (&r, &s))) in
                qy[r.clone()].iter_mut().zip(&mut qx[r]).zip(basis)
            {
                [*qy, *qx] = lattice_row_terms(ga, gb, [p, q, r, s]);
            }
            previous = Some((i + 1, gb));
        }
        row.j = Some(j);
    }

    /// Makes the `slots` hold lattice rows `j0..=j1` of octave `k`, computing what is
    /// missing into slots not used by this call (the ones unused the longest), growing the
    /// slot list when all are taken; `found` becomes the slot index of each row, in order.
    #[inline(always)]
    fn ensure_rows(&self, k: usize, j0: i32, j1: i32, slots: &mut Slots, found: &mut Vec<usize>) {
        slots.clock += 1;
        let now = slots.clock;
        // Mark what is already there first, so the misses below do not evict it.
        found.clear();
        found.extend(
            (j0..=j1).map(|j| match slots.rows.iter().position(|r| r.j == Some(j)) {
                Some(i) => {
                    slots.used[i] = now;
                    i
                }
                None => usize::MAX,
            }),
        );
        for (n, j) in (j0..=j1).enumerate() {
            if found[n] != usize::MAX {
                continue;
            }
            let free = (0..slots.rows.len())
                .filter(|&i| slots.used[i] < now)
                .min_by_key(|&i| slots.used[i]);
            let i = match free {
                // Keep up to four rows beyond what one block needs before reusing slots.
                Some(i) if slots.rows.len() >= (j1 - j0 + 1) as usize + 4 => i,
                _ => {
                    slots.rows.push(LatticeRow::default());
                    slots.used.push(0);
                    slots.rows.len() - 1
                }
            };
            self.lattice_row(k, j, &mut slots.rows[i]);
            slots.used[i] = now;
            found[n] = i;
        }
    }

    /// Adds gain · fBm(u_c, v) to `out[c]` for every column c. `out.len()` must equal the
    /// number of positions given to [`RowSampler::new`] (longer outputs are only partly
    /// written, shorter ones are filled as far as they go).
    #[inline(always)]
    pub fn add_row(&self, v: f32, out: &mut [f32], scratch: &mut RowScratch) {
        let n = self.len.min(out.len());
        self.add_rows(&[v], &mut out[..n], n, scratch);
    }

    /// [`RowSampler::add_row`] for a block of rows at once: `out` holds `vs.len()` rows of
    /// `stride` values (row r from `r·stride`; only its first `self.len` columns are
    /// touched). Per pixel the octaves are summed in order from 0 and the sum is added
    /// to `out`, as [`FbmField::sample`] does, so the bytes equal `add_row` row by row;
    /// going through the block in column tiles keeps the lattice rows in the L1 cache
    /// (loading them from L2 once per pixel row was the noise's bottleneck).
    #[inline(always)]
    pub(crate) fn add_rows(
        &self,
        vs: &[f32],
        out: &mut [f32],
        stride: usize,
        scratch: &mut RowScratch,
    ) {
        let octaves = &self.field.octaves;
        let n = self.len.min(stride);
        if octaves.is_empty() || vs.is_empty() || n == 0 {
            return;
        }
        scratch.rows.resize_with(octaves.len(), Default::default);
        scratch.plan.resize_with(octaves.len(), Vec::new);
        for (k, o) in octaves.iter().enumerate() {
            let weights = &mut scratch.weights;
            weights.clear();
            weights.extend(vs.iter().map(|&v| o.row_weights(v)));
            let j0 = weights.iter().map(|r| r.0).min().unwrap_or(0);
            let j1 = weights.iter().map(|r| r.0).max().unwrap_or(0) + 1;
            let slots = &mut scratch.found;
            self.ensure_rows(k, j0, j1, &mut scratch.rows[k], slots);
            let plan = &mut scratch.plan[k];
            plan.clear();
            plan.extend(weights.iter().map(|&(j, w)| {
                let at = (j - j0) as usize;
                ([slots[at], slots[at + 1]], w)
            }));
        }
        let (rows, plan) = (&scratch.rows, &scratch.plan);
        // Tiles of whole chunks; the last tile may end in a partial chunk, which goes
        // through a padded copy (the lattice rows are padded to whole chunks).
        for t0 in (0..n).step_by(TILE) {
            let t1 = (t0 + TILE).min(n);
            let whole = t0 + (t1 - t0) / LANES * LANES;
            for (r, row) in out.chunks_mut(stride).take(vs.len()).enumerate() {
                if whole > t0 {
                    add_tile(&mut row[t0..whole], t0, rows, plan, r);
                }
                if t1 > whole {
                    let mut pad = [0.0f32; LANES];
                    pad[..t1 - whole].copy_from_slice(&row[whole..t1]);
                    add_tile(&mut pad, whole, rows, plan, r);
                    row[whole..t1].copy_from_slice(&pad[..t1 - whole]);
                }
            }
        }
    }
}

/// Adds the fBm of block row `r` (its lattice rows and weights in `plan`) to `out`, the
/// columns from `c0` on (a whole number of [`LANES`] chunks): per pixel, octave 0, 1, …
/// summed from 0, then added to `out`. The running sums of the tile live on the stack
/// (in L1), one sweep per octave over four contiguous lattice-row slices (the lattice
/// rows are padded to whole chunks).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn add_tile(
    out: &mut [f32],
    c0: usize,
    rows: &[Slots],
    plan: &[Vec<([usize; 2], [f32; 4])>],
    r: usize,
) {
    let n = out.len();
    let mut sums = [Chunk::ZERO; TILE / LANES];
    let sums = &mut sums[..n / LANES];
    let (k0, k1) = (c0 / LANES, (c0 + n) / LANES);
    for (slots, plan) in rows.iter().zip(plan) {
        let ([i0, i1], w) = plan[r];
        let (r0, r1) = (&slots.rows[i0], &slots.rows[i1]);
        let q = r0.qy[k0..k1].iter().zip(&r1.qy[k0..k1]);
        let x = r0.qx[k0..k1].iter().zip(&r1.qx[k0..k1]);
        for (sum, ((qy0, qy1), (qx0, qx1))) in sums.iter_mut().zip(q.zip(x)) {
            crate::base::simd::keep_chunk_loop();
            let mut a = sum.0;
            for l in 0..LANES {
                a[l] += combine(w, qy0.0[l], qy1.0[l], qx0.0[l], qx1.0[l]);
            }
            *sum = Chunk(a);
        }
    }
    for (o, s) in out.chunks_exact_mut(LANES).zip(sums.iter()) {
        crate::base::simd::keep_chunk_loop();
        let mut v = [0.0f32; LANES];
        for l in 0..LANES {
            v[l] = o[l] + s.0[l];
        }
        o.copy_from_slice(&v);
    }
}

#[inline(always)]
fn basis_of(fx: f32) -> [f32; 4] {
    basis(fx, fade(fx))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(details: f32) -> FbmParams {
        FbmParams {
            details,
            roughness: 0.6,
            lacunarity: 2.0,
            scale_mm: 5.0,
        }
    }

    fn grid(n: usize) -> Vec<f32> {
        (0..n).map(|x| (x as f32 + 0.5) / n as f32).collect()
    }

    /// Textbook 2D gradient noise (Perlin's improved noise in 2D): the four corner
    /// gradients dotted with the offsets to the point, blended by the quintic fade along
    /// x then y. The field's regrouped evaluation must agree with it.
    fn textbook(field: &FbmField, u: f32, v: f32) -> f64 {
        let mut sum = 0.0f64;
        for o in &field.octaves {
            let (x, y) = (
                (u * o.cells_u + o.offset[0]) as f64,
                (v * o.cells_v + o.offset[1]) as f64,
            );
            let (i, j) = (x.floor(), y.floor());
            let (fx, fy) = (x - i, y - j);
            let (i, j) = (i as i32, j as i32);
            let dot = |di: i32, dj: i32| {
                let g = o.gradient(i + di, j + dj);
                g[0] as f64 * (fx - di as f64) + g[1] as f64 * (fy - dj as f64)
            };
            let fade = |t: f64| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
            let (sx, sy) = (fade(fx), fade(fy));
            let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
            let n = lerp(
                lerp(dot(0, 0), dot(1, 0), sx),
                lerp(dot(0, 1), dot(1, 1), sx),
                sy,
            );
            sum += o.amplitude as f64 * n;
        }
        sum
    }

    #[test]
    fn equals_a_textbook_gradient_noise_evaluation() {
        for tile in [false, true] {
            let field = FbmField::new(&params(4.5), 50.0, tile, 1.0, 9, 0);
            let mut worst = 0.0f64;
            for k in 0..4000 {
                let (u, v) = (
                    (k as f32 * 0.618_034).fract(),
                    (k as f32 * 0.414_213_5).fract(),
                );
                let d = (field.sample(u, v) as f64 - textbook(&field, u, v)).abs();
                worst = worst.max(d);
            }
            assert!(worst < 2e-5, "tile {tile}: largest difference {worst}");
        }
    }

    #[test]
    fn zero_details_is_no_noise() {
        let f = FbmField::new(&params(0.0), 50.0, false, 1.0, 7, 0);
        assert_eq!(f.octave_count(), 0);
        let us = grid(64);
        let s = RowSampler::new(&f, &us);
        let mut row = vec![0.0; 64];
        s.add_row(0.3, &mut row, &mut RowScratch::default());
        assert!(row.iter().all(|&h| h == 0.0));
        assert_eq!(f.sample(0.2, 0.7), 0.0);
    }

    #[test]
    fn rows_are_bit_identical_to_the_scalar_reference() {
        // 1, 5, 6 and 7 octaves: a partial sweep, and a full one plus 1, 2 or 3 octaves.
        for details in [1.0, 4.5, 6.0, 7.0] {
            let f = FbmField::new(&params(details), 50.0, true, 0.8, 3, 1);
            // Both cases: more columns than the finest octave has cells (1201), and fewer,
            // where a row skips lattice cells (61 and 301).
            for us in [grid(1201), grid(301), grid(61)] {
                let s = RowSampler::new(&f, &us);
                let mut scratch = RowScratch::default();
                for y in 0..40 {
                    let v = 1.0 - (y as f32 + 0.5) / 40.0;
                    let mut row = vec![0.0; us.len()];
                    s.add_row(v, &mut row, &mut scratch);
                    for (x, &u) in us.iter().enumerate() {
                        let want = f.sample(u, v).to_bits();
                        assert_eq!(
                            row[x].to_bits(),
                            want,
                            "x={x} y={y} details {details} width {}",
                            us.len()
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn blocks_of_rows_equal_the_scalar_reference() {
        // Blocks of 1 to 40 rows (a block of 40 spans many lattice rows of the fine
        // octaves: the slots must grow), visited out of order, with a row stride longer
        // than the row (the extra columns must stay untouched).
        for details in [4.5, 7.0] {
            let f = FbmField::new(&params(details), 50.0, true, 0.8, 3, 1);
            for us in [grid(1201), grid(61)] {
                let s = RowSampler::new(&f, &us);
                let mut scratch = RowScratch::default();
                let stride = us.len() + 5;
                let v = |y: usize| 1.0 - (y as f32 + 0.5) / 120.0;
                for (y0, rows) in [(40, 40), (0, 1), (1, 7), (8, 32), (80, 40)] {
                    let vs: Vec<f32> = (y0..y0 + rows).map(v).collect();
                    let mut block = vec![7.0f32; rows * stride];
                    s.add_rows(&vs, &mut block, stride, &mut scratch);
                    for (r, row) in block.chunks(stride).enumerate() {
                        for (x, &u) in us.iter().enumerate() {
                            let want = (7.0 + f.sample(u, vs[r])).to_bits();
                            assert_eq!(
                                row[x].to_bits(),
                                want,
                                "x={x} row {} details {details} width {}",
                                y0 + r,
                                us.len()
                            );
                        }
                        assert!(row[us.len()..].iter().all(|&h| h == 7.0));
                    }
                }
            }
        }
    }

    #[test]
    fn tiled_noise_is_periodic_over_the_map() {
        // Non-integer cell counts (50/7 cells) must still tile: they are rounded.
        let p = FbmParams {
            details: 3.3,
            roughness: 0.7,
            lacunarity: 2.3,
            scale_mm: 7.0,
        };
        let f = FbmField::new(&p, 50.0, true, 1.0, 11, 0);
        for k in 0..50 {
            let (u, v) = (k as f32 * 0.0193 + 0.01, 1.0 - k as f32 * 0.0171 - 0.02);
            let a = f.sample(u, v);
            for (du, dv) in [(1.0, 0.0), (0.0, 1.0), (-1.0, 1.0)] {
                let b = f.sample(u + du, v + dv);
                assert!(
                    (a - b).abs() < 2e-5,
                    "({u},{v}) shifted by ({du},{dv}): {a} vs {b}"
                );
            }
        }
        // Without tiling it is not periodic.
        let g = FbmField::new(&p, 50.0, false, 1.0, 11, 0);
        let diff: f32 = (0..50)
            .map(|k| {
                (g.sample(0.1 + k as f32 * 0.01, 0.5) - g.sample(1.1 + k as f32 * 0.01, 0.5)).abs()
            })
            .sum();
        assert!(
            diff > 0.5,
            "untiled noise unexpectedly periodic (sum of diffs {diff})"
        );
    }

    #[test]
    fn bounded_and_zero_mean_for_any_octave_count() {
        let n = 256;
        let us = grid(n);
        for details in [1.0, 2.5, 5.0, 8.0] {
            let p = FbmParams {
                scale_mm: 1.0,
                ..params(details)
            };
            let f = FbmField::new(&p, 50.0, true, 1.0, 5, 0);
            let s = RowSampler::new(&f, &us);
            let mut scratch = RowScratch::default();
            let (mut sum, mut sum2, mut max) = (0.0f64, 0.0f64, 0.0f32);
            for y in 0..n {
                let mut row = vec![0.0; n];
                s.add_row(1.0 - (y as f32 + 0.5) / n as f32, &mut row, &mut scratch);
                for &h in &row {
                    sum += h as f64;
                    sum2 += (h as f64).powi(2);
                    max = max.max(h.abs());
                }
            }
            let mean = sum / (n * n) as f64;
            let sd = (sum2 / (n * n) as f64 - mean * mean).sqrt();
            assert!(max <= 1.0, "details {details}: |fBm| reached {max}");
            assert!(
                mean.abs() < 0.1 * sd,
                "details {details}: mean {mean} vs sd {sd}"
            );
            assert!(sd > 0.05, "details {details}: sd {sd} too small");
        }
    }
}
