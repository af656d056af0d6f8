//! Fractal gradient noise (fBm) of SPEC §3 "Noise" [P §3.4, eq. 17], periodic when tiling.
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
//! **Speed.** [`RowSampler`] evaluates whole rows: along a row the lattice row j and the
//! fade in v are fixed, and the fade in u depends on the column only, so per octave it keeps
//! four per-column basis functions and, per row, hashes each lattice point once. A pixel
//! octave then costs four multiply-adds over contiguous arrays, which the compiler
//! vectorises (see `micro::bake` for the AVX2 dispatch). The result is bit-identical to the
//! scalar [`FbmField::sample`].

/// Parameters of one fBm (SPEC §3 "Noise"); validated by `project::NoiseSection`.
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

/// An fBm over a map of `size_mm` × `size_mm`, in UV (SPEC §0), fixed by its seed.
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
        let mut rng = crate::rng::Rng::for_stream(seed, 0x6e6f_6973_6500 ^ salt);
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
            let y = v * o.cells_v + o.offset[1];
            let j = y.floor();
            let fy = y - j;
            let sy = fade(fy);
            let x = u * o.cells_u + o.offset[0];
            let i = x.floor();
            let fx = x - i;
            let t = fade(fx);
            let (i, j) = (i as i32, j as i32);
            let g00 = o.gradient(i, j);
            let g10 = o.gradient(i + 1, j);
            let g01 = o.gradient(i, j + 1);
            let g11 = o.gradient(i + 1, j + 1);
            let [c0, d0, c1, d1] = cell_coefficients(g00, g10, g01, g11, fy, sy, o.amplitude);
            let b = basis(fx, t);
            acc += c0 * b[0] + c1 * b[1] + d0 * b[2] + d1 * b[3];
        }
        acc
    }
}

impl Octave {
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

/// Per lattice cell and row: the two edge functions e0(fx) = c0 + d0·fx (left corners
/// blended in v) and e1(fx) = c1 + d1·(fx − 1) (right corners), times the amplitude.
#[inline(always)]
fn cell_coefficients(
    g00: [f32; 2],
    g10: [f32; 2],
    g01: [f32; 2],
    g11: [f32; 2],
    fy: f32,
    sy: f32,
    amp: f32,
) -> [f32; 4] {
    let fy1 = fy - 1.0;
    let c0 = g00[1] * fy + sy * (g01[1] * fy1 - g00[1] * fy);
    let d0 = g00[0] + sy * (g01[0] - g00[0]);
    let c1 = g10[1] * fy + sy * (g11[1] * fy1 - g10[1] * fy);
    let d1 = g10[0] + sy * (g11[0] - g10[0]);
    [c0 * amp, d0 * amp, c1 * amp, d1 * amp]
}

/// Per-octave column tables of a [`RowSampler`].
#[derive(Clone, Debug)]
struct OctaveColumns {
    /// Runs of columns in the same lattice cell: (cell index i, first column, end column).
    runs: Vec<(i32, u32, u32)>,
    /// The four basis functions, one array each, one value per column.
    basis: [Vec<f32>; 4],
}

/// Evaluates an [`FbmField`] along rows at a fixed, increasing list of u positions.
#[derive(Clone, Debug)]
pub struct RowSampler<'a> {
    field: &'a FbmField,
    columns: Vec<OctaveColumns>,
    len: usize,
}

/// Per-thread scratch space of [`RowSampler::add_row`].
#[derive(Clone, Debug, Default)]
pub struct RowScratch {
    grads: Vec<[f32; 2]>,
}

/// Padding (in columns) kept after every per-column table and row buffer.
pub(crate) const LANES: usize = 8;

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
                    let fx = x - i;
                    let b = basis_of(fx);
                    for (dst, val) in basis.iter_mut().zip(b) {
                        dst.push(val);
                    }
                    let i = i as i32;
                    match runs.last_mut() {
                        Some(last) if last.0 == i => last.2 = c as u32 + 1,
                        _ => runs.push((i, c as u32, c as u32 + 1)),
                    }
                }
                for b in &mut basis {
                    b.resize(us.len() + LANES, 0.0);
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

    /// Adds gain · fBm(u_c, v) to `out[c]` for every column c. `out.len()` must equal the
    /// number of positions given to [`RowSampler::new`] (longer outputs are only partly
    /// written, shorter ones are filled as far as they go).
    #[inline(always)]
    pub fn add_row(&self, v: f32, out: &mut [f32], scratch: &mut RowScratch) {
        let n = self.len.min(out.len());
        let out = &mut out[..n];
        for (o, cols) in self.field.octaves.iter().zip(&self.columns) {
            let (Some(first), Some(last)) = (cols.runs.first(), cols.runs.last()) else {
                continue;
            };
            let y = v * o.cells_v + o.offset[1];
            let j = y.floor();
            let fy = y - j;
            let sy = fade(fy);
            let j = j as i32;
            // Hash each lattice point of the two lattice rows once.
            let (i0, i1) = (first.0, last.0 + 1);
            scratch.grads.clear();
            for i in i0..=i1 {
                scratch.grads.push(o.gradient(i, j));
                scratch.grads.push(o.gradient(i, j + 1));
            }
            for &(i, x0, x1) in &cols.runs {
                let k = 2 * (i - i0) as usize;
                let g = &scratch.grads[k..k + 4];
                let [c0, d0, c1, d1] =
                    cell_coefficients(g[0], g[2], g[1], g[3], fy, sy, o.amplitude);
                let (x0, x1) = (x0 as usize, (x1 as usize).min(out.len()));
                if x0 >= x1 {
                    break;
                }
                let dst = &mut out[x0..x1];
                let (b0, b1) = (&cols.basis[0][x0..x1], &cols.basis[1][x0..x1]);
                let (b2, b3) = (&cols.basis[2][x0..x1], &cols.basis[3][x0..x1]);
                for ((((d, &p), &q), &r), &s) in dst.iter_mut().zip(b0).zip(b1).zip(b2).zip(b3) {
                    *d += c0 * p + c1 * q + d0 * r + d1 * s;
                }
            }
        }
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
        let f = FbmField::new(&params(4.5), 50.0, true, 0.8, 3, 1);
        let us = grid(301);
        let s = RowSampler::new(&f, &us);
        let mut scratch = RowScratch::default();
        for y in 0..40 {
            let v = 1.0 - (y as f32 + 0.5) / 40.0;
            let mut row = vec![0.0; us.len()];
            s.add_row(v, &mut row, &mut scratch);
            for (x, &u) in us.iter().enumerate() {
                assert_eq!(row[x].to_bits(), f.sample(u, v).to_bits(), "x={x} y={y}");
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
