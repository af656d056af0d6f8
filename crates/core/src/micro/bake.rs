//! The micro-relief baker (SPEC §3): pores + furrows, log-smoothed (eq. 18), plus fBm
//! (eq. 17), with pores and furrows evaluated in a domain-warped frame.
//!
//! Design, for speed with exact determinism:
//! - features are generated once, in millimetres ([`MicroRelief::new`]), independent of the
//!   map size;
//! - each feature becomes a *stamp* with a bounding row range (its reach includes the
//!   largest warp displacement); on tiled maps stamps near an edge get shifted copies, so
//!   everything wraps;
//! - the map is cut into bands of [`BAND_ROWS`] rows, each with the list of stamps that
//!   touch it (in global feature order), and bands are baked in parallel with rayon. A
//!   pixel's value depends only on its own row, so any thread count gives the same bytes;
//! - per row, every stamp adds exp(β·m) − 1 over its exact x-interval (a circle or an
//!   oriented rectangle cut by the row), then the row is resolved with one `ln` per pixel
//!   and the fBm row is added;
//! - the warp (two fBm fields) is smooth, so it is evaluated on a coarse grid (≤ 16 px,
//!   at most a quarter of its finest lattice cell) and interpolated bilinearly;
//! - the hot loops are plain `f32` code over slices; the band function is compiled twice,
//!   for the SSE2 baseline and with AVX2 enabled, and chosen at run time. Both do the same
//!   IEEE operations (no fused multiply-add), so their output is byte-identical.

use rayon::prelude::*;

use super::furrows::{Furrow, build_network};
use super::noise::{FbmField, LANES, RowSampler, RowScratch};
use super::overlap::{resolve, term};
use super::pores::{Pore, PoreProfile, Rim, place_pores, rim_window};
use crate::error::Error;
use crate::heightmap::HeightMap;
use crate::project::Project;

/// Rows per parallel band.
pub const BAND_ROWS: usize = 16;

/// Wall-clock time of the stages of a bake, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BakeTimings {
    /// Pore placement and the furrow network (size independent, done in `new`).
    pub features_ms: f64,
    /// Stamps, band lists, column tables.
    pub setup_ms: f64,
    /// The band pass: stamping, overlap resolve, noise.
    pub relief_ms: f64,
}

/// Which parts a bake evaluates (all by default; the benchmark times them apart).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parts {
    pub features: bool,
    pub noise: bool,
}

impl Default for Parts {
    fn default() -> Self {
        Self {
            features: true,
            noise: true,
        }
    }
}

/// A project's micro-relief, ready to bake at any size.
#[derive(Clone, Debug)]
pub struct MicroRelief {
    project: Project,
    pores: Vec<Pore>,
    pore_spacing_mm: f32,
    furrows: Vec<Furrow>,
    noise: FbmField,
    warp: [FbmField; 2],
    features_ms: f64,
}

impl MicroRelief {
    /// Validates the project and generates its pores and furrows.
    pub fn new(project: &Project) -> Result<Self, Error> {
        project.validate().map_err(|message| Error::Project {
            source_name: "project".into(),
            message,
        })?;
        let t0 = std::time::Instant::now();
        let p = project;
        let size = p.map_size_mm;
        let placement = place_pores(
            p.pore_count(),
            &p.pore_stats(),
            p.pores.placement,
            size,
            p.tile,
            p.seed,
        );
        let furrows = if p.furrows.enabled {
            build_network(&placement.pores, &p.furrow_params(), size, p.tile, p.seed)
        } else {
            Vec::new()
        };
        let noise = FbmField::new(&p.noise_params(), size, p.tile, p.noise.strength, p.seed, 0);
        let warp_gain = p.warp.strength_mm;
        let warp = [
            FbmField::new(&p.warp_params(), size, p.tile, warp_gain, p.seed, 1),
            FbmField::new(&p.warp_params(), size, p.tile, warp_gain, p.seed, 2),
        ];
        Ok(Self {
            project: p.clone(),
            pores: placement.pores,
            pore_spacing_mm: placement.min_spacing_mm,
            furrows,
            noise,
            warp,
            features_ms: t0.elapsed().as_secs_f64() * 1e3,
        })
    }

    pub fn pores(&self) -> &[Pore] {
        &self.pores
    }

    /// The minimum pore spacing blue-noise placement guaranteed, mm (0 for uniform).
    pub fn pore_spacing_mm(&self) -> f32 {
        self.pore_spacing_mm
    }

    pub fn furrows(&self) -> &[Furrow] {
        &self.furrows
    }

    /// Bakes a `size_px`² height map of everything.
    pub fn bake(&self, size_px: u32) -> Result<(HeightMap, BakeTimings), Error> {
        self.bake_parts(size_px, Parts::default())
    }

    /// Bakes only the chosen parts.
    pub fn bake_parts(
        &self,
        size_px: u32,
        parts: Parts,
    ) -> Result<(HeightMap, BakeTimings), Error> {
        let mut map = HeightMap::zeros(size_px, size_px)?;
        let t0 = std::time::Instant::now();
        let ctx = Context::new(self, size_px as usize, parts);
        let t1 = std::time::Instant::now();
        let w = size_px as usize;
        map.data_mut()
            .par_chunks_mut(BAND_ROWS * w)
            .enumerate()
            .for_each_init(
                || Scratch::new(&ctx),
                |scratch, (band, out)| bake_band_dispatch(&ctx, band, out, scratch),
            );
        let t2 = std::time::Instant::now();
        Ok((
            map,
            BakeTimings {
                features_ms: self.features_ms,
                setup_ms: (t1 - t0).as_secs_f64() * 1e3,
                relief_ms: (t2 - t1).as_secs_f64() * 1e3,
            },
        ))
    }
}

/// One feature placed on the map (possibly a shifted copy on tiled maps).
#[derive(Clone, Copy, Debug)]
enum Stamp {
    Pore {
        centre: [f32; 2],
        inv_r2: f32,
        depth: f32,
        falloff: f32,
        radius: f32,
        reach: f32,
    },
    Furrow {
        start: [f32; 2],
        dir: [f32; 2],
        inv_len: f32,
        len: f32,
        depth: f32,
        width: f32,
        inv_w2: f32,
        inv_taper: f32,
        reach: f32,
    },
}

/// Everything shared by the bands of one bake.
struct Context<'a> {
    w: usize,
    h: usize,
    size_mm: f32,
    beta: f32,
    inv_n: f32,
    profile: PoreProfile,
    rim: Rim,
    stamps: Vec<Stamp>,
    /// Stamp indices touching each band, in stamp order.
    bands: Vec<Vec<u32>>,
    /// Pixel-centre x in mm.
    x_mm: Vec<f32>,
    noise: Option<RowSampler<'a>>,
    warp: Option<Warp<'a>>,
}

struct Warp<'a> {
    /// Coarse grid step, pixels.
    step: usize,
    cols: usize,
    fields: [RowSampler<'a>; 2],
}

impl<'a> Context<'a> {
    fn new(relief: &'a MicroRelief, size_px: usize, parts: Parts) -> Self {
        let p = &relief.project;
        let (w, h) = (size_px, size_px);
        let size_mm = p.map_size_mm;
        let us: Vec<f32> = (0..w)
            .map(|x| crate::heightmap::pixel_to_u(x as u32, w as u32))
            .collect();
        // Pixel-centre x in mm, padded by LANES columns so stamps can work in whole chunks.
        let x_mm: Vec<f32> = (0..w + LANES)
            .map(|x| (x as f32 + 0.5) / w as f32 * size_mm)
            .collect();
        let warp_on =
            parts.features && p.warp.strength_mm > 0.0 && relief.warp[0].octave_count() > 0;
        let warp = warp_on.then(|| {
            // A quarter of the finest warp lattice cell, a power of two in 1..=16 pixels.
            let cell_px = w as f32 / relief.warp[0].finest_cells().max(1e-3);
            let step = (1usize << ((cell_px / 4.0).max(1.0).log2().floor() as u32).min(4)).max(1);
            let cols = w / step + 2;
            let cus: Vec<f32> = (0..cols)
                .map(|i| ((i * step) as f32 + 0.5) / w as f32)
                .collect();
            Warp {
                step,
                cols,
                fields: [
                    RowSampler::new(&relief.warp[0], &cus),
                    RowSampler::new(&relief.warp[1], &cus),
                ],
            }
        });
        // |fBm| ≤ 1 per axis, so the warp moves a point by at most √2·strength.
        let reach = if warp_on {
            std::f32::consts::SQRT_2 * p.warp.strength_mm
        } else {
            0.0
        };
        let mut stamps = Vec::new();
        if parts.features {
            for pore in &relief.pores {
                stamps.push(Stamp::Pore {
                    centre: pore.centre_mm,
                    inv_r2: 1.0 / (pore.radius_mm * pore.radius_mm),
                    depth: pore.depth,
                    falloff: pore.falloff,
                    radius: pore.radius_mm,
                    reach: pore.radius_mm + reach,
                });
            }
            for f in &relief.furrows {
                let d = [f.end_mm[0] - f.start_mm[0], f.end_mm[1] - f.start_mm[1]];
                let len = (d[0] * d[0] + d[1] * d[1]).sqrt().max(1e-6);
                stamps.push(Stamp::Furrow {
                    start: f.start_mm,
                    dir: [d[0] / len, d[1] / len],
                    inv_len: 1.0 / len,
                    len,
                    depth: f.depth,
                    width: f.width_mm,
                    inv_w2: 1.0 / (f.width_mm * f.width_mm),
                    inv_taper: 1.0 / f.taper,
                    reach,
                });
            }
        }
        if p.tile {
            stamps = tile_copies(&stamps, size_mm);
        }
        let n_bands = h.div_ceil(BAND_ROWS);
        let mut bands = vec![Vec::new(); n_bands];
        for (k, s) in stamps.iter().enumerate() {
            if let Some((y0, y1)) = row_range(s, size_mm, h) {
                for band in bands
                    .iter_mut()
                    .take((y1 - 1) / BAND_ROWS + 1)
                    .skip(y0 / BAND_ROWS)
                {
                    band.push(k as u32);
                }
            }
        }
        let noise = (parts.noise && relief.noise.octave_count() > 0 && p.noise.strength > 0.0)
            .then(|| RowSampler::new(&relief.noise, &us));
        Self {
            w,
            h,
            size_mm,
            beta: p.overlap.beta,
            inv_n: 1.0 / p.overlap.n,
            profile: p.pores.profile,
            rim: p.pores.rim,
            stamps,
            bands,
            x_mm,
            noise,
            warp,
        }
    }

    /// Pixel column range [x0, x1) covering x_mm in [lo, hi].
    fn cols(&self, lo: f32, hi: f32) -> (usize, usize) {
        let f = self.w as f32 / self.size_mm;
        let x0 = (lo * f - 0.5).floor().max(0.0) as usize;
        let x1 = ((hi * f - 0.5).ceil() + 1.0).clamp(0.0, self.w as f32) as usize;
        (x0.min(x1), x1)
    }
}

/// Bounding rows [y0, y1) of a stamp, `None` when it misses the map.
fn row_range(s: &Stamp, size_mm: f32, h: usize) -> Option<(usize, usize)> {
    let (lo, hi) = y_extent(s);
    let row = |y_mm: f32| (1.0 - y_mm / size_mm) * h as f32 - 0.5;
    let y0 = row(hi).floor().max(0.0);
    let y1 = (row(lo).ceil() + 1.0).min(h as f32);
    (y1 > y0).then_some((y0 as usize, y1 as usize))
}

fn y_extent(s: &Stamp) -> (f32, f32) {
    match *s {
        Stamp::Pore { centre, reach, .. } => (centre[1] - reach, centre[1] + reach),
        Stamp::Furrow {
            start,
            dir,
            len,
            width,
            reach,
            ..
        } => {
            let end = start[1] + dir[1] * len;
            let r = width + reach;
            (start[1].min(end) - r, start[1].max(end) + r)
        }
    }
}

fn x_extent(s: &Stamp) -> (f32, f32) {
    match *s {
        Stamp::Pore { centre, reach, .. } => (centre[0] - reach, centre[0] + reach),
        Stamp::Furrow {
            start,
            dir,
            len,
            width,
            reach,
            ..
        } => {
            let end = start[0] + dir[0] * len;
            let r = width + reach;
            (start[0].min(end) - r, start[0].max(end) + r)
        }
    }
}

/// On tiled maps: every stamp plus its copies shifted by ±size that reach into the map.
fn tile_copies(stamps: &[Stamp], size_mm: f32) -> Vec<Stamp> {
    let mut out = Vec::with_capacity(stamps.len() * 5 / 4);
    for s in stamps {
        let (x0, x1) = x_extent(s);
        let (y0, y1) = y_extent(s);
        for oy in [0.0, -size_mm, size_mm] {
            for ox in [0.0, -size_mm, size_mm] {
                if x1 + ox < 0.0 || x0 + ox > size_mm || y1 + oy < 0.0 || y0 + oy > size_mm {
                    continue;
                }
                let mut c = *s;
                match &mut c {
                    Stamp::Pore { centre, .. } => *centre = [centre[0] + ox, centre[1] + oy],
                    Stamp::Furrow { start, .. } => *start = [start[0] + ox, start[1] + oy],
                }
                out.push(c);
            }
        }
    }
    out
}

/// Per-task buffers.
struct Scratch {
    acc: Vec<f32>,
    wx: Vec<f32>,
    wy: Vec<f32>,
    coarse: [Vec<f32>; 2],
    noise: RowScratch,
}

impl Scratch {
    fn new(ctx: &Context) -> Self {
        let cols = ctx.warp.as_ref().map_or(0, |w| w.cols);
        let coarse_rows = BAND_ROWS / ctx.warp.as_ref().map_or(BAND_ROWS, |w| w.step) + 2;
        Self {
            acc: vec![0.0; ctx.w + LANES],
            wx: vec![0.0; ctx.w + LANES],
            wy: vec![0.0; ctx.w + LANES],
            coarse: [vec![0.0; cols * coarse_rows], vec![0.0; cols * coarse_rows]],
            noise: RowScratch::default(),
        }
    }
}

fn bake_band_dispatch(ctx: &Context, band: usize, out: &mut [f32], scratch: &mut Scratch) {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 (checked just above), the only requirement of
            // calling a `#[target_feature(enable = "avx2")]` function.
            unsafe { bake_band_avx2(ctx, band, out, scratch) };
            return;
        }
    }
    bake_band(ctx, band, out, scratch);
}

/// [`bake_band`] compiled with AVX2 (same operations, wider vectors; no FMA).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn bake_band_avx2(ctx: &Context, band: usize, out: &mut [f32], scratch: &mut Scratch) {
    bake_band(ctx, band, out, scratch);
}

#[inline(always)]
fn bake_band(ctx: &Context, band: usize, out: &mut [f32], scratch: &mut Scratch) {
    let w = ctx.w;
    let y_first = band * BAND_ROWS;
    let rows = out.len() / w;
    let Scratch {
        acc,
        wx,
        wy,
        coarse,
        noise,
    } = scratch;
    // Coarse warp rows covering this band (one past its last row, for interpolation).
    let warp_first = ctx.warp.as_ref().map(|warp| {
        let (j0, j1) = (y_first / warp.step, (y_first + rows - 1) / warp.step + 1);
        for (field, grid) in warp.fields.iter().zip(coarse.iter_mut()) {
            for j in j0..=j1 {
                let v = 1.0 - ((j * warp.step) as f32 + 0.5) / ctx.h as f32;
                let row = &mut grid[(j - j0) * warp.cols..(j - j0 + 1) * warp.cols];
                row.fill(0.0);
                field.add_row(v, row, noise);
            }
        }
        j0
    });
    // The warp of this band is a convex blend of its coarse values, so their largest
    // magnitude bounds it: stamps only visit pixels within that reach (pixels outside a
    // stamp's support add exactly 0, so the bound changes speed, never the bytes).
    let band_reach = match (ctx.warp.as_ref(), warp_first) {
        (Some(warp), Some(j0)) => {
            let rows_used = (y_first + rows - 1) / warp.step + 2 - j0;
            let max_abs = |g: &[f32]| {
                g[..rows_used * warp.cols]
                    .iter()
                    .fold(0.0f32, |m, v| m.max(v.abs()))
            };
            let (mx, my) = (max_abs(&coarse[0]), max_abs(&coarse[1]));
            (mx * mx + my * my).sqrt() * 1.0001
        }
        _ => 0.0,
    };
    let stamps = &ctx.bands[band];
    for r in 0..rows {
        let y = y_first + r;
        let out_row = &mut out[r * w..(r + 1) * w];
        let v = crate::heightmap::pixel_to_v(y as u32, ctx.h as u32);
        let y_mm = v * ctx.size_mm;
        if let (Some(warp), Some(j0)) = (ctx.warp.as_ref(), warp_first) {
            let j = y / warp.step - j0;
            let fy = (y % warp.step) as f32 / warp.step as f32;
            for (grid, dst) in coarse.iter().zip([&mut *wx, &mut *wy]) {
                let (a, b) = (
                    &grid[j * warp.cols..(j + 1) * warp.cols],
                    &grid[(j + 1) * warp.cols..(j + 2) * warp.cols],
                );
                interpolate_row(a, b, fy, warp.step, &mut dst[..w]);
            }
        }
        if !stamps.is_empty() {
            acc.fill(0.0);
            for &k in stamps {
                stamp_row(ctx, &ctx.stamps[k as usize], y_mm, band_reach, acc, wx, wy);
            }
            let (beta, inv_n) = (ctx.beta, ctx.inv_n);
            for (o, &a) in out_row.iter_mut().zip(acc.iter()) {
                *o = -resolve(a, beta, inv_n);
            }
        }
        if let Some(n) = &ctx.noise {
            n.add_row(v, out_row, noise);
        }
    }
}

/// dst[x] = bilinear warp at pixel x of a row between coarse rows `a` and `b`.
#[inline(always)]
fn interpolate_row(a: &[f32], b: &[f32], fy: f32, step: usize, dst: &mut [f32]) {
    let inv = 1.0 / step as f32;
    for (i, chunk) in dst.chunks_mut(step).enumerate() {
        let l = a[i] + (b[i] - a[i]) * fy;
        let r = a[i + 1] + (b[i + 1] - a[i + 1]) * fy;
        for (k, d) in chunk.iter_mut().enumerate() {
            *d = l + (r - l) * (k as f32 * inv);
        }
    }
}

/// Adds one stamp's exp(β·m) − 1 to the row accumulator over its x-interval.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn stamp_row(
    ctx: &Context,
    s: &Stamp,
    y_mm: f32,
    band_reach: f32,
    acc: &mut [f32],
    wx: &[f32],
    wy: &[f32],
) {
    let beta = ctx.beta;
    match *s {
        Stamp::Pore {
            centre,
            inv_r2,
            depth,
            falloff,
            radius,
            ..
        } => {
            let reach = radius + band_reach;
            let dy = y_mm - centre[1];
            let hw2 = reach * reach - dy * dy;
            if hw2 <= 0.0 {
                return;
            }
            let hw = hw2.sqrt();
            let (x0, x1) = ctx.cols(centre[0] - hw, centre[0] + hw);
            if x0 >= x1 {
                return;
            }
            let span = Span::new(acc, &ctx.x_mm, wx, wy, x0, x1);
            let (cx, cy) = (centre[0], centre[1] - y_mm);
            match (ctx.profile, ctx.rim) {
                (PoreProfile::Gaussian, Rim::Smooth) => {
                    span.pore(cx, cy, inv_r2, depth, beta, |t| {
                        super::fastmath::exp(-falloff * t) * rim_window(t)
                    })
                }
                (PoreProfile::Gaussian, Rim::Exact) => {
                    span.pore(cx, cy, inv_r2, depth, beta, |t| {
                        super::fastmath::exp(-falloff * t)
                    })
                }
                (PoreProfile::Quadratic, _) => span.pore(cx, cy, inv_r2, depth, beta, |t| {
                    let s = 1.0 - t.sqrt();
                    s * s
                }),
                (PoreProfile::Quartic, _) => {
                    span.pore(cx, cy, inv_r2, depth, beta, |t| (1.0 - t) * (1.0 - t))
                }
            }
        }
        Stamp::Furrow {
            start,
            dir,
            inv_len,
            len,
            depth,
            width,
            inv_w2,
            inv_taper,
            ..
        } => {
            let reach = band_reach;
            // Along a row, cross(x) and along(x) are linear in x: intersect their bands.
            let py = y_mm - start[1];
            let r = width + reach;
            let (mut lo, mut hi) = (f32::NEG_INFINITY, f32::INFINITY);
            for (slope, offset, a, b) in [
                (dir[1], -py * dir[0], -r, r),
                (dir[0], py * dir[1], -reach, len + reach),
            ] {
                if slope.abs() < 1e-9 {
                    if offset < a || offset > b {
                        return;
                    }
                } else {
                    let (p, q) = ((a - offset) / slope, (b - offset) / slope);
                    lo = lo.max(p.min(q));
                    hi = hi.min(p.max(q));
                }
            }
            if lo > hi {
                return;
            }
            let (x0, x1) = ctx.cols(start[0] + lo, start[0] + hi);
            if x0 >= x1 {
                return;
            }
            let span = Span::new(acc, &ctx.x_mm, wx, wy, x0, x1);
            span.furrow(start[0], py, dir, inv_len, depth, inv_w2, inv_taper, beta);
        }
    }
}

/// The pixels of one row a stamp covers.
struct Span<'s> {
    acc: &'s mut [f32],
    x_mm: &'s [f32],
    wx: &'s [f32],
    wy: &'s [f32],
}

impl<'s> Span<'s> {
    /// Columns [x0, x1) rounded up to whole LANES chunks (the buffers are padded).
    #[inline(always)]
    fn new(
        acc: &'s mut [f32],
        x_mm: &'s [f32],
        wx: &'s [f32],
        wy: &'s [f32],
        x0: usize,
        x1: usize,
    ) -> Self {
        let x1 = x0 + (x1 - x0).div_ceil(LANES) * LANES;
        Self {
            acc: &mut acc[x0..x1],
            x_mm: &x_mm[x0..x1],
            wx: &wx[x0..x1],
            wy: &wy[x0..x1],
        }
    }

    /// Pore centred `cy` mm above this row at x = `cx`: m = depth·shape(r²/R²).
    #[inline(always)]
    fn pore(
        self,
        cx: f32,
        cy: f32,
        inv_r2: f32,
        depth: f32,
        beta: f32,
        shape: impl Fn(f32) -> f32,
    ) {
        for (((a, &x), &wx), &wy) in self.acc.iter_mut().zip(self.x_mm).zip(self.wx).zip(self.wy) {
            {
                let dx = x + wx - cx;
                let dy = wy - cy;
                let t = (dx * dx + dy * dy) * inv_r2;
                let m = if t < 1.0 { depth * shape(t) } else { 0.0 };
                *a += term(m, beta);
            }
        }
    }

    /// Furrow from (sx, row − py) along `dir`: m = A·(1 − x²/ω²)·taper(s) (eq. 16).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn furrow(
        self,
        sx: f32,
        py: f32,
        dir: [f32; 2],
        inv_len: f32,
        depth: f32,
        inv_w2: f32,
        inv_taper: f32,
        beta: f32,
    ) {
        for (((a, &x), &wx), &wy) in self.acc.iter_mut().zip(self.x_mm).zip(self.wx).zip(self.wy) {
            {
                let px = x + wx - sx;
                let py = py + wy;
                let along = (px * dir[0] + py * dir[1]) * inv_len;
                let cross = px * dir[1] - py * dir[0];
                let q = cross * cross * inv_w2;
                let e = (along.min(1.0 - along) * inv_taper).clamp(0.0, 1.0);
                let taper = e * e * (3.0 - 2.0 * e);
                let m = if q < 1.0 {
                    depth * (1.0 - q) * taper
                } else {
                    0.0
                };
                *a += term(m, beta);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn project(tile: bool) -> Project {
        let mut p = Project {
            tile,
            ..Project::default()
        };
        p.pores.count = 300;
        p
    }

    #[test]
    fn byte_identical_on_1_and_2_threads_and_across_runs() {
        let relief = MicroRelief::new(&project(true)).unwrap();
        let pool1 = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let pool2 = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let a = pool1.install(|| relief.bake(256).unwrap().0);
        let b = pool2.install(|| relief.bake(256).unwrap().0);
        let c = MicroRelief::new(&project(true))
            .unwrap()
            .bake(256)
            .unwrap()
            .0;
        let bits = |m: &HeightMap| m.data().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
        assert_eq!(bits(&a), bits(&c));
        let (lo, hi) = a.min_max();
        assert!(lo < -0.5 && hi > 0.0, "range {lo}..{hi}");
    }

    #[test]
    fn simd_and_scalar_paths_give_the_same_bytes() {
        let relief = MicroRelief::new(&project(false)).unwrap();
        let ctx = Context::new(&relief, 128, Parts::default());
        let mut scratch = Scratch::new(&ctx);
        let mut a = vec![0.0; 128 * BAND_ROWS];
        let mut b = vec![0.0; 128 * BAND_ROWS];
        for band in 0..128 / BAND_ROWS {
            bake_band(&ctx, band, &mut a, &mut scratch);
            bake_band_dispatch(&ctx, band, &mut b, &mut scratch);
            assert!(
                a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
                "band {band}"
            );
        }
    }

    #[test]
    fn a_lone_pore_bakes_to_its_profile() {
        // One pore in the middle, no furrows, noise or warp: the map is eq. 15 (smooth rim).
        let mut p = Project::default();
        p.pores.count = 1;
        p.pores.radius_mm = crate::project::MeanSpread::new(5.0 / 10.0, 0.0);
        p.pores.depth = crate::project::MeanSpread::new(1.0, 0.0);
        p.pores.falloff = crate::project::MeanSpread::new(1.0, 0.0);
        p.furrows.enabled = false;
        p.noise.details = 0.0;
        p.warp.strength_mm = 0.0;
        let relief = MicroRelief::new(&p).unwrap();
        let pore = relief.pores()[0];
        let (map, _) = relief.bake(512).unwrap();
        let shape = crate::micro::pores::PoreShape::default();
        let mut worst = 0.0f32;
        for y in 0..512 {
            for x in 0..512 {
                let q = [
                    crate::heightmap::pixel_to_u(x, 512) * 50.0,
                    crate::heightmap::pixel_to_v(y, 512) * 50.0,
                ];
                let r2 = (q[0] - pore.centre_mm[0]).powi(2) + (q[1] - pore.centre_mm[1]).powi(2);
                worst = worst.max((map.get(x, y) - shape.height(&pore, r2)).abs());
            }
        }
        assert!(worst < 1e-5, "largest difference from eq. 15: {worst}");
        assert!(map.min_max().0 < -0.9);
    }

    #[test]
    fn tiled_maps_match_across_opposite_edges() {
        let relief = MicroRelief::new(&project(true)).unwrap();
        let (m, _) = relief.bake(256).unwrap();
        let n = 256;
        let mean_abs = |f: &dyn Fn(u32) -> f32| (0..n).map(f).map(f32::abs).sum::<f32>() / n as f32;
        // Across the seam vs. between the two columns (rows) next to it.
        let seam_x = mean_abs(&|y| m.get(0, y) - m.get(n - 1, y));
        let inner_x = mean_abs(&|y| m.get(1, y) - m.get(0, y));
        let seam_y = mean_abs(&|x| m.get(x, 0) - m.get(x, n - 1));
        let inner_y = mean_abs(&|x| m.get(x, 1) - m.get(x, 0));
        assert!(
            seam_x < 2.0 * inner_x + 1e-3,
            "x seam {seam_x} vs neighbours {inner_x}"
        );
        assert!(
            seam_y < 2.0 * inner_y + 1e-3,
            "y seam {seam_y} vs neighbours {inner_y}"
        );
        // An untiled map has a real seam.
        let (u, _) = MicroRelief::new(&project(false))
            .unwrap()
            .bake(256)
            .unwrap();
        let seam_u = (0..n)
            .map(|y| (u.get(0, y) - u.get(n - 1, y)).abs())
            .sum::<f32>()
            / n as f32;
        assert!(
            seam_u > 2.0 * seam_x,
            "untiled seam {seam_u} vs tiled {seam_x}"
        );
    }

    #[test]
    fn resolution_independent_within_tolerance() {
        // 1024² vs 4096² box-downsampled by 4: same picture (tolerance: 3 % of the height
        // range in the mean, from sub-pixel detail that only the large bake resolves).
        let mut p = project(false);
        p.noise.details = 3.0;
        let relief = MicroRelief::new(&p).unwrap();
        let (small, _) = relief.bake(1024).unwrap();
        let (big, _) = relief.bake(4096).unwrap();
        let down = big.downsample_box(4).unwrap();
        let (lo, hi) = down.min_max();
        let mean_diff = small
            .data()
            .iter()
            .zip(down.data())
            .map(|(a, b)| (a - b).abs())
            .sum::<f32>()
            / small.data().len() as f32;
        assert!(
            mean_diff < 0.03 * (hi - lo),
            "mean |1024 − 4096↓| = {mean_diff}, range {}",
            hi - lo
        );
    }
}
