//! The UV rasteriser: the texels of a map a UV triangle covers, with barycentric weights
//! and a guard band (docs/models.md §1 pixel centres). Every per-texel bake goes through it.

use std::ops::Range;

use glam::Vec2;
use rayon::prelude::*;

use crate::base::error::Error;

/// How far below 0 a guard texel's barycentric weight may go (1: one triangle's width
/// beyond the edge).
const MAX_GUARD_WEIGHT: f32 = 1.0;

/// Visits the texels of a `size`² map (docs/models.md §1: rows from the top, v up) whose
/// centres lie in the UV triangle `uv` or within `guard` pixels of it (and no farther than
/// its own width beyond an edge: a sliver's guard band is thinner): `visit(x, y,
/// barycentric weights (extrapolated outside), distance outside in pixels)`. A triangle
/// with no UV area visits nothing.
pub fn raster_uv(
    uv: [Vec2; 3],
    size: u32,
    guard: f32,
    visit: impl FnMut(usize, usize, [f32; 3], f32),
) {
    raster_uv_rows(uv, size, guard, 0..size as usize, visit);
}

/// [`raster_uv`] over the texel rows `rows` alone.
pub fn raster_uv_rows(
    uv: [Vec2; 3],
    size: u32,
    guard: f32,
    rows: Range<usize>,
    mut visit: impl FnMut(usize, usize, [f32; 3], f32),
) {
    let s = size as f32;
    // Continuous pixel coordinates: texel (x, y) has its centre at (x + ½, y + ½).
    let px = |uv: Vec2| Vec2::new(uv.x * s, (1.0 - uv.y) * s);
    let (pa, pb, pc) = (px(uv[0]), px(uv[1]), px(uv[2]));
    let area = (pb - pa).perp_dot(pc - pa);
    if area.abs() < 1e-12 || !area.is_finite() {
        return;
    }
    let lo = (pa.min(pb).min(pc) - guard).floor().max(Vec2::ZERO);
    let hi = (pa.max(pb).max(pc) + guard).ceil().min(Vec2::splat(s));
    let edge_len = [(pc - pb).length(), (pa - pc).length(), (pb - pa).length()];
    for y in (lo.y as usize).max(rows.start)..(hi.y as usize).min(rows.end) {
        for x in lo.x as usize..hi.x as usize {
            let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let w0 = (pc - pb).perp_dot(p - pb) / area;
            let w1 = (pa - pc).perp_dot(p - pc) / area;
            let w2 = 1.0 - w0 - w1;
            // Distance outside the triangle, pixels (0 inside).
            let outside = [w0, w1, w2]
                .iter()
                .zip(edge_len)
                .map(|(w, len)| (-w).max(0.0) * area.abs() / len.max(1e-12))
                .fold(0.0f32, f32::max);
            // Beyond a sliver's edge the weights blow up (a point far off the surface):
            // only a guard texel whose weights stay near the triangle is visited.
            let sane = outside == 0.0 || w0.min(w1).min(w2) >= -MAX_GUARD_WEIGHT;
            if outside <= guard && sane {
                visit(x, y, [w0, w1, w2], outside);
            }
        }
    }
}

/// Rows of a map in one band of [`raster_banded`]: at most this many, and the map cut into
/// at least [`BANDS`] bands. Fixed counts (not the thread count): the same bands, so the
/// same result, on any machine.
const BAND_ROWS: usize = 32;
const BANDS: usize = 16;

/// One band of rows of a map in [`raster_banded`]: its per-texel state, and the
/// rasteriser restricted to its rows.
pub struct Band<'a, T> {
    size: u32,
    rows: Range<usize>,
    /// The window's columns.
    columns: Range<usize>,
    texels: &'a mut [T],
}

impl<T> Band<'_, T> {
    /// [`raster_uv`] within this band's rows: `visit(x, y, weights, distance outside,
    /// texel (x, y)'s state)`.
    pub fn raster(
        &mut self,
        uv: [Vec2; 3],
        guard: f32,
        mut visit: impl FnMut(usize, usize, [f32; 3], f32, &mut T),
    ) {
        let (first, columns) = (self.rows.start, self.columns.clone());
        let width = columns.len();
        let texels = &mut *self.texels;
        raster_uv_rows(
            uv,
            self.size,
            guard,
            self.rows.clone(),
            |x, y, w, outside| {
                if columns.contains(&x) {
                    let texel = &mut texels[(y - first) * width + x - columns.start];
                    visit(x, y, w, outside, texel);
                }
            },
        );
    }
}

/// Rasterises `triangles` triangles into `texels` (a `size`² map's per-texel state, rows
/// from the top) in bands of rows side by side: each band runs `job(k, band, own)` for
/// every triangle `k` whose UV triangle `uv_of(k)`, with a guard band of `max_guard`
/// pixels, reaches its rows, in triangle order, and `job` rasterises it with
/// [`Band::raster`] (a guard of at most `max_guard`). Every texel lies in one band and
/// sees the triangles in the order a single pass over them would: the result is that
/// pass's, on any number of threads. Returns each band's `own` state, bands from the top.
pub fn raster_banded<T: Send, B: Default + Send>(
    size: u32,
    texels: &mut [T],
    triangles: usize,
    max_guard: f32,
    uv_of: impl Fn(usize) -> Option<[Vec2; 3]> + Sync,
    job: impl Fn(usize, &mut Band<'_, T>, &mut B) -> Result<(), Error> + Sync,
) -> Result<Vec<B>, Error> {
    let n = size as usize;
    raster_banded_in(size, (0..n, 0..n), texels, triangles, max_guard, uv_of, job)
}

/// [`raster_banded`] over a window of the map, `(columns, rows)`: `texels` holds its
/// texels alone (row by row), and texels outside it are not visited.
pub fn raster_banded_in<T: Send, B: Default + Send>(
    size: u32,
    (columns, rows): (Range<usize>, Range<usize>),
    texels: &mut [T],
    triangles: usize,
    max_guard: f32,
    uv_of: impl Fn(usize) -> Option<[Vec2; 3]> + Sync,
    job: impl Fn(usize, &mut Band<'_, T>, &mut B) -> Result<(), Error> + Sync,
) -> Result<Vec<B>, Error> {
    let (width, height) = (columns.len(), rows.len());
    assert_eq!(
        texels.len(),
        width * height,
        "raster_banded: one state per texel"
    );
    assert!(columns.end <= size as usize && rows.end <= size as usize);
    if width == 0 || height == 0 {
        return Ok(Vec::new());
    }
    let band_rows = BAND_ROWS.min(height.div_ceil(BANDS)).max(1);
    let bands = height.div_ceil(band_rows);
    // Each band's triangles, in order: those whose rows (with the guard) reach it.
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); bands];
    let s = size as f32;
    for k in 0..triangles {
        let Some(uv) = uv_of(k) else { continue };
        let ys = uv.map(|p| (1.0 - p.y) * s);
        let (lo, hi) = (ys[0].min(ys[1]).min(ys[2]), ys[0].max(ys[1]).max(ys[2]));
        if !(lo.is_finite() && hi.is_finite()) {
            continue;
        }
        let first = ((lo - max_guard).floor().max(0.0) as usize).max(rows.start) - rows.start;
        let end = ((hi + max_guard).ceil().min(s)).max(0.0) as usize;
        let end = end.min(rows.end).saturating_sub(rows.start);
        if first >= end {
            continue;
        }
        for bin in &mut bins[first / band_rows..=((end - 1) / band_rows).min(bands - 1)] {
            bin.push(k as u32);
        }
    }
    texels
        .par_chunks_mut(band_rows * width)
        .zip(bins.par_iter())
        .enumerate()
        .map(|(b, (texels, bin))| {
            let start = rows.start + b * band_rows;
            let mut band = Band {
                size,
                rows: start..start + texels.len() / width,
                columns: columns.clone(),
                texels,
            };
            let mut own = B::default();
            for &k in bin {
                job(k as usize, &mut band, &mut own)?;
            }
            Ok(own)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Triangles of every size over a map, many overlapping, some off the map and some
    /// without area: the banded pass writes what one pass over them in order writes.
    #[test]
    fn bands_write_what_one_pass_writes() {
        let mut seed = 7u32;
        let mut next = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        };
        let mut triangles: Vec<[Vec2; 3]> = Vec::new();
        for k in 0..3000 {
            let c = Vec2::new(next() * 1.2 - 0.1, next() * 1.2 - 0.1);
            let r = if k % 10 == 0 { 0.3 } else { 0.01 };
            triangles.push(std::array::from_fn(|_| {
                c + Vec2::new(next() - 0.5, next() - 0.5) * r
            }));
        }
        triangles.push([Vec2::ZERO, Vec2::ZERO, Vec2::ONE]);
        triangles.push([Vec2::NAN, Vec2::ONE, Vec2::ZERO]);
        for size in [1u32, 7, 100, 257] {
            let n = size as usize;
            // Each texel: the nearest triangle's weights (the first of equal distance),
            // and how many triangles reached it.
            let mut one = vec![(f32::INFINITY, usize::MAX, [0.0f32; 3], 0u32); n * n];
            for (k, uv) in triangles.iter().enumerate() {
                raster_uv(*uv, size, 1.5, |x, y, w, outside| {
                    let t = &mut one[y * n + x];
                    t.3 += 1;
                    if outside < t.0 {
                        *t = (outside, k, w, t.3);
                    }
                });
            }
            let mut banded = vec![(f32::INFINITY, usize::MAX, [0.0f32; 3], 0u32); n * n];
            let visits = raster_banded(
                size,
                &mut banded,
                triangles.len(),
                1.5,
                |k| Some(triangles[k]),
                |k, band, visits: &mut usize| {
                    band.raster(triangles[k], 1.5, |_, _, w, outside, t| {
                        *visits += 1;
                        t.3 += 1;
                        if outside < t.0 {
                            *t = (outside, k, w, t.3);
                        }
                    });
                    Ok(())
                },
            )
            .unwrap();
            let bits = |v: &[(f32, usize, [f32; 3], u32)]| -> Vec<(u32, usize, [u32; 3], u32)> {
                v.iter()
                    .map(|t| (t.0.to_bits(), t.1, t.2.map(f32::to_bits), t.3))
                    .collect()
            };
            assert_eq!(bits(&banded), bits(&one), "{size}²");
            let total: u32 = one.iter().map(|t| t.3).sum();
            assert_eq!(visits.iter().sum::<usize>(), total as usize, "{size}²");
            assert!(size < 100 || total > 10_000, "{size}²: {total} visits");
            // A window of the map: its texels, as the whole map's pass wrote them.
            let (columns, rows) = (n / 10..n * 9 / 10, n / 20..n * 3 / 4);
            let mut window =
                vec![(f32::INFINITY, usize::MAX, [0.0f32; 3], 0u32); columns.len() * rows.len()];
            raster_banded_in(
                size,
                (columns.clone(), rows.clone()),
                &mut window,
                triangles.len(),
                1.5,
                |k| Some(triangles[k]),
                |k, band, _: &mut ()| {
                    band.raster(triangles[k], 1.5, |_, _, w, outside, t| {
                        t.3 += 1;
                        if outside < t.0 {
                            *t = (outside, k, w, t.3);
                        }
                    });
                    Ok(())
                },
            )
            .unwrap();
            let expected: Vec<_> = rows
                .clone()
                .flat_map(|y| columns.clone().map(move |x| y * n + x))
                .map(|i| one[i])
                .collect();
            assert_eq!(bits(&window), bits(&expected), "{size}²'s window");
        }
    }
}
