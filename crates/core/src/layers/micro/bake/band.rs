//! One band of rows baked in cache: the warp, the stamps' exp(β·m) − 1 sums per row span,
//! the overlap resolve, the noise, and (fused) the normal rows.

// Lane loops over fixed-size arrays are the shape the vectoriser turns into whole-register
// operations (see the parent module).
#![allow(clippy::needless_range_loop)]

use super::*;

/// One coarse warp row: both fields at the coarse columns, and their largest magnitudes.
#[derive(Clone, Debug, Default)]
pub(super) struct CoarseRow {
    pub(super) j: Option<usize>,
    pub(super) values: [Vec<f32>; 2],
    pub(super) max_abs: [f32; 2],
}

/// Per-task buffers.
pub(super) struct Scratch {
    /// Σ (exp(β·m) − 1) of the current row.
    pub(super) acc: Vec<Chunk>,
    /// Warped pixel-centre x (x_mm + warp x), mm.
    pub(super) px: Vec<Chunk>,
    /// Warp y, mm.
    pub(super) wy: Vec<Chunk>,
    /// Coarse warp rows j and j + 1 of the current row.
    pub(super) coarse: [CoarseRow; 2],
    /// The coarse warp row blended to the current row, per field.
    pub(super) blend: [Vec<f32>; 2],
    pub(super) noise: RowScratch,
    /// The warp fields' own caches (each keeps its lattice rows between pixel rows).
    pub(super) warp_noise: [RowScratch; 2],
    /// The band's height rows, baked here and streamed to the output at the end (rows
    /// are 64-byte aligned when the width is a whole number of chunks).
    pub(super) rows: Vec<Chunk>,
    /// One row of the normal map, encoded here and streamed to the output.
    pub(super) rgb_row: Vec<u8>,
    /// Height rows just outside the band (the normal map's neighbours).
    pub(super) halo: [Vec<f32>; 2],
    /// Rows kept from the previous band of this task for its successor (with normals):
    /// that band's last row (the next band's halo above) and its halo below (the next
    /// band's first row), by row index.
    pub(super) kept: [(Option<usize>, Vec<f32>); 2],
}

impl Scratch {
    pub(super) fn new(ctx: &Context) -> Self {
        let cols = ctx.warp.as_ref().map_or(0, |w| w.cols);
        let blend_len = ctx
            .warp
            .as_ref()
            .map_or(0, |w| cols.max(ctx.chunks * LANES / w.step + 1));
        Self {
            acc: vec![Chunk([0.0; LANES]); ctx.chunks],
            // Without a warp, px stays x_mm and wy stays 0.
            px: ctx.x_mm.clone(),
            wy: vec![Chunk([0.0; LANES]); ctx.chunks],
            coarse: Default::default(),
            // Padded to whole chunks of pixels (see `interpolate`).
            blend: [vec![0.0; blend_len], vec![0.0; blend_len]],
            noise: RowScratch::default(),
            warp_noise: Default::default(),
            rows: vec![Chunk::ZERO; (BAND_ROWS * ctx.w).div_ceil(LANES)],
            rgb_row: vec![0; 3 * ctx.w],
            halo: [vec![0.0; ctx.w], vec![0.0; ctx.w]],
            kept: [(None, vec![0.0; ctx.w]), (None, vec![0.0; ctx.w])],
        }
    }
}

/// One band's work, a [`crate::base::simd::Kernel`].
pub(super) struct Band<'a, 'c> {
    pub(super) ctx: &'a Context<'c>,
    pub(super) band: usize,
    pub(super) out: &'a mut [f32],
    pub(super) rgb: Option<&'a mut [u8]>,
    pub(super) scratch: &'a mut Scratch,
}

impl crate::base::simd::Kernel for Band<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        bake_band(self.ctx, self.band, self.out, self.rgb, self.scratch);
    }
}

/// Bakes the rows of `band` into `out` (and their normals into `rgb`).
///
/// The rows are baked into the task's scratch band (which stays in cache for the normal
/// map) and streamed to `out` and `rgb` at the end ([`crate::base::simd::stream_copy`]): the
/// output is written once, without reading it in first.
#[inline(always)]
pub(super) fn bake_band(
    ctx: &Context,
    band: usize,
    out: &mut [f32],
    rgb: Option<&mut [u8]>,
    s: &mut Scratch,
) {
    let w = ctx.w;
    let y0 = band * BAND_ROWS;
    let y1 = y0 + out.len() / w;
    let mut rows = std::mem::take(&mut s.rows);
    let heights = &mut bytemuck::cast_slice_mut::<Chunk, f32>(&mut rows)[..out.len()];
    // With normals, the neighbour rows outside the band are baked again into the halo
    // buffers; rows go strictly downward (halo above, band, halo below) so the noise and
    // warp caches move forward only.
    let settings = ctx.normals.filter(|_| rgb.is_some());
    let outside = |y: usize| !(y0..y1).contains(&y);
    let halo_rows = settings.map_or([None, None], |settings| {
        let first = RowRule::new(y0, w, ctx.h, &settings).above;
        let last = RowRule::new(y1 - 1, w, ctx.h, &settings).below;
        [
            outside(first).then_some(first),
            outside(last).then_some(last),
        ]
    });
    let mut halo = std::mem::take(&mut s.halo);
    // A row the previous band of this task already baked is copied (a row's bytes depend
    // only on its index), otherwise baked.
    let row =
        |y: usize, dst: &mut [f32], s: &mut Scratch| match s.kept.iter().find(|k| k.0 == Some(y)) {
            Some((_, kept)) => dst.copy_from_slice(kept),
            None => height_row(ctx, y, dst, s),
        };
    if let Some(y) = halo_rows[0] {
        row(y, &mut halo[0], s);
    }
    // The band's features row by row, then its noise in one pass over the block (which
    // keeps the noise's lattice rows in cache); a first row kept from the previous band
    // is whole already.
    let mut first = 0;
    if let (Some(_), Some((_, kept))) = (settings, s.kept.iter().find(|k| k.0 == Some(y0))) {
        heights[..w].copy_from_slice(kept);
        first = 1;
    }
    for (r, dst) in heights.chunks_exact_mut(w).enumerate().skip(first) {
        feature_row(ctx, y0 + r, dst, s);
    }
    add_noise(ctx, y0 + first, &mut heights[first * w..], s);
    if let Some(y) = halo_rows[1] {
        height_row(ctx, y, &mut halo[1], s);
    }
    if let (Some(rgb), Some(settings)) = (rgb, settings) {
        // Keep the last row and the halo below for the next band (see `row` above).
        s.kept[0].0 = Some(y1 - 1);
        s.kept[0].1.copy_from_slice(&heights[(y1 - 1 - y0) * w..]);
        s.kept[1].0 = halo_rows[1];
        if halo_rows[1].is_some() {
            s.kept[1].1.copy_from_slice(&halo[1]);
        }
        let row_of = |y: usize| -> &[f32] {
            if !outside(y) {
                &heights[(y - y0) * w..(y - y0 + 1) * w]
            } else if halo_rows[0] == Some(y) {
                &halo[0]
            } else {
                &halo[1]
            }
        };
        for (r, dst) in rgb.chunks_exact_mut(3 * w).enumerate() {
            let y = y0 + r;
            let rule = RowRule::new(y, w, ctx.h, &settings);
            normal_map::encode_row_rgb8(
                row_of(rule.above),
                row_of(y),
                row_of(rule.below),
                &rule,
                &mut s.rgb_row,
            );
            crate::base::simd::stream_copy(dst, &s.rgb_row);
        }
    }
    crate::base::simd::stream_copy(out, heights);
    crate::base::simd::stream_fence();
    s.halo = halo;
    s.rows = rows;
}

/// Bakes the features (pores and furrows, log-smoothed) of row `y` into `dst` (w values).
#[inline(always)]
pub(super) fn feature_row(ctx: &Context, y: usize, dst: &mut [f32], s: &mut Scratch) {
    let v = crate::maps::heightmap::pixel_to_v(y as u32, ctx.h as u32);
    let y_mm = v * ctx.size_mm;
    let stamps = &ctx.bands[y / BAND_ROWS];
    let features = !stamps.is_empty();
    if features {
        let reach = match &ctx.warp {
            Some(warp) => warp_row(ctx, warp, y, s),
            None => 0.0,
        };
        for a in s.acc.iter_mut() {
            *a = Chunk([0.0; LANES]);
        }
        for &k in stamps {
            stamp_row(ctx, &ctx.stamps[k as usize], y_mm, reach, s);
        }
    }
    // Feature depth (0 where no feature reaches a chunk: skips the `ln`) plus noise.
    let (beta, inv_n) = (ctx.beta, ctx.inv_n);
    let full = dst.len() / LANES;
    let (head, tail) = dst.split_at_mut(full * LANES);
    for (d, a) in head.chunks_exact_mut(LANES).zip(&s.acc) {
        let mut out = [0.0; LANES];
        if features && any(a.0.map(|v| v != 0.0)) {
            for l in 0..LANES {
                out[l] = -resolve(a.0[l], beta, inv_n);
            }
        }
        d.copy_from_slice(&out);
    }
    if !tail.is_empty() {
        let mut out = [0.0; LANES];
        if features {
            for l in 0..LANES {
                out[l] = -resolve(s.acc[full].0[l], beta, inv_n);
            }
        }
        tail.copy_from_slice(&out[..tail.len()]);
    }
}

/// Adds the noise to `rows` (consecutive rows from `y`, `w` values each).
#[inline(always)]
pub(super) fn add_noise(ctx: &Context, y: usize, rows: &mut [f32], s: &mut Scratch) {
    if let Some(n) = &ctx.noise {
        // At most a band's rows.
        let mut vs = [0.0f32; BAND_ROWS];
        let vs = &mut vs[..rows.len() / ctx.w];
        for (k, v) in vs.iter_mut().enumerate() {
            *v = crate::maps::heightmap::pixel_to_v((y + k) as u32, ctx.h as u32);
        }
        n.add_rows(vs, rows, ctx.w, &mut s.noise);
    }
}

/// Bakes row `y` whole (features, then noise) into `dst`.
#[inline(always)]
pub(super) fn height_row(ctx: &Context, y: usize, dst: &mut [f32], s: &mut Scratch) {
    feature_row(ctx, y, dst, s);
    add_noise(ctx, y, dst, s);
}

/// True when any lane is set (compiles to one vector test).
#[inline(always)]
pub(super) fn any(mask: [bool; LANES]) -> bool {
    mask.iter().fold(false, |a, &b| a | b)
}

/// Fills `s.px` (x_mm + warp x) and `s.wy` for row `y`; returns a bound on the warp
/// displacement in this row (the row's warp is a convex blend of the two coarse rows
/// around it, so their largest magnitudes bound it). Stamps only visit pixels within that
/// reach; pixels outside a stamp's support add exactly 0, so the bound changes speed,
/// never the bytes.
#[inline(always)]
pub(super) fn warp_row(ctx: &Context, warp: &Warp, y: usize, s: &mut Scratch) -> f32 {
    let j = y / warp.step;
    for (k, cj) in [j, j + 1].into_iter().enumerate() {
        if s.coarse[k].j == Some(cj) {
            continue;
        }
        if s.coarse[1 - k].j == Some(cj) {
            s.coarse.swap(0, 1);
            continue;
        }
        let row = &mut s.coarse[k];
        let v = 1.0 - ((cj * warp.step) as f32 + 0.5) / ctx.h as f32;
        for f in 0..2 {
            row.values[f].clear();
            row.values[f].resize(warp.cols, 0.0);
            warp.fields[f].add_row(v, &mut row.values[f], &mut s.warp_noise[f]);
            row.max_abs[f] = row.values[f].iter().fold(0.0f32, |m, v| m.max(v.abs()));
        }
        row.j = Some(cj);
    }
    let fy = (y % warp.step) as f32 / warp.step as f32;
    let [c0, c1] = &s.coarse;
    for f in 0..2 {
        let (a, b) = (&c0.values[f], &c1.values[f]);
        for ((d, &a), &b) in s.blend[f].iter_mut().zip(a).zip(b) {
            *d = a + (b - a) * fy;
        }
    }
    let (px, wy, x_mm) = (&mut s.px, &mut s.wy, &ctx.x_mm);
    match warp.step {
        1 => interpolate::<1>(&s.blend, x_mm, px, wy),
        2 => interpolate::<2>(&s.blend, x_mm, px, wy),
        4 => interpolate::<4>(&s.blend, x_mm, px, wy),
        8 => interpolate::<8>(&s.blend, x_mm, px, wy),
        _ => interpolate::<16>(&s.blend, x_mm, px, wy),
    }
    let mx = c0.max_abs[0].max(c1.max_abs[0]);
    let my = c0.max_abs[1].max(c1.max_abs[1]);
    (mx * mx + my * my).sqrt() * 1.0001
}

/// px = x_mm + the x warp and wy = the y warp, linear between the coarse columns `blend`
/// every `S` pixels (`S` a power of two up to [`LANES`]), one whole chunk at a time: lane k
/// of chunk c lies in segment c·LANES/S + k/S at fraction (k mod S)/S. Padding lanes past
/// the row get finite values no output reads (`blend` is padded to whole chunks).
#[inline(always)]
pub(super) fn interpolate<const S: usize>(
    blend: &[Vec<f32>; 2],
    x_mm: &[Chunk],
    px: &mut [Chunk],
    wy: &mut [Chunk],
) {
    let per = LANES / S;
    let frac: [f32; LANES] = std::array::from_fn(|k| (k % S) as f32 * (1.0 / S as f32));
    let (bx, by) = (blend[0].as_slice(), blend[1].as_slice());
    for (c, ((p, x), y)) in px.iter_mut().zip(x_mm).zip(wy.iter_mut()).enumerate() {
        crate::base::simd::keep_chunk_loop();
        let b = c * per;
        let (Some(ex), Some(ey)) = (bx.get(b..b + per + 1), by.get(b..b + per + 1)) else {
            break;
        };
        // Built in locals, then stored whole: stored in place, LLVM cannot tell that
        // `p`, `y` and `x` do not overlap and keeps the loop scalar.
        let (mut pk, mut yk) = ([0.0f32; LANES], [0.0f32; LANES]);
        for k in 0..LANES {
            let (lx, rx, ly, ry) = (ex[k / S], ex[k / S + 1], ey[k / S], ey[k / S + 1]);
            pk[k] = x.0[k] + (lx + (rx - lx) * frac[k]);
            yk[k] = ly + (ry - ly) * frac[k];
        }
        p.0 = pk;
        y.0 = yk;
    }
}

/// Adds one stamp's exp(β·m) − 1 to the row accumulator over its x-interval.
#[inline(always)]
pub(super) fn stamp_row(ctx: &Context, st: &Stamp, y_mm: f32, reach: f32, s: &mut Scratch) {
    match *st {
        Stamp::Pore {
            centre,
            inv_r2,
            ellipse,
            beta_depth,
            falloff,
            radius,
        } => {
            let r = radius + reach;
            let dy = y_mm - centre[1];
            let hw2 = r * r - dy * dy;
            if hw2 <= 0.0 {
                return;
            }
            let hw = hw2.sqrt();
            let (c0, c1) = ctx.chunk_range(centre[0] - hw, centre[0] + hw);
            let (cx, cy) = (centre[0], centre[1] - y_mm);
            let span = Span::new(s, c0, c1);
            // One monomorphised loop per (profile, rim), each calling the one copy of the
            // formula in `pores` with constant settings (the match there folds away).
            // A round pore keeps the exact circular formula; a stretched one its ellipse
            // (u along its long axis: t = (u²/aspect + v²·aspect)/R², area kept).
            let [c, sn, aspect] = ellipse;
            let (ka, kb) = (inv_r2 / aspect, inv_r2 * aspect);
            macro_rules! stamp {
                ($profile:expr, $rim:expr) => {{
                    let shape = PoreShape {
                        profile: $profile,
                        rim: $rim,
                    };
                    if aspect == 1.0 {
                        span.pore(
                            cx,
                            cy,
                            |dx, dy| (dx * dx + dy * dy) * inv_r2,
                            beta_depth,
                            |t| shape.shape(t, falloff),
                        )
                    } else {
                        span.pore(
                            cx,
                            cy,
                            |dx, dy| {
                                let u = dx * c + dy * sn;
                                let v = dy * c - dx * sn;
                                u * u * ka + v * v * kb
                            },
                            beta_depth,
                            |t| shape.shape(t, falloff),
                        )
                    }
                }};
            }
            match (ctx.profile, ctx.rim) {
                (PoreProfile::Gaussian, Rim::Smooth) => stamp!(PoreProfile::Gaussian, Rim::Smooth),
                (PoreProfile::Gaussian, Rim::Exact) => stamp!(PoreProfile::Gaussian, Rim::Exact),
                (PoreProfile::Quadratic, rim) => stamp!(PoreProfile::Quadratic, rim),
                (PoreProfile::Quartic, rim) => stamp!(PoreProfile::Quartic, rim),
            }
        }
        Stamp::Furrow {
            start,
            dir,
            len,
            beta_depth,
            width,
            inv_w2,
            inv_taper,
        } => {
            // Along a row, cross(x) and along(x) are linear in x: intersect their bands.
            let py = y_mm - start[1];
            let r = width + reach;
            let (mut lo, mut hi) = (f32::NEG_INFINITY, f32::INFINITY);
            for (slope, offset, a, b) in [
                (dir[1], -py * dir[0], -r, r),
                (dir[0], py * dir[1], -r, len + r),
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
            let (c0, c1) = ctx.chunk_range(start[0] + lo, start[0] + hi);
            Span::new(s, c0, c1).furrow(start[0], py, dir, len, beta_depth, inv_w2, inv_taper);
        }
    }
}

/// The chunks of one row a stamp covers.
pub(super) struct Span<'s> {
    pub(super) acc: &'s mut [Chunk],
    pub(super) px: &'s [Chunk],
    pub(super) wy: &'s [Chunk],
}

impl<'s> Span<'s> {
    #[inline(always)]
    pub(super) fn new(s: &'s mut Scratch, c0: usize, c1: usize) -> Self {
        Self {
            acc: &mut s.acc[c0..c1],
            px: &s.px[c0..c1],
            wy: &s.wy[c0..c1],
        }
    }

    /// Pore centred `cy` mm above this row at x = `cx`: β·m = β·dmax·shape(t), t =
    /// `metric(dx, dy)` (r²/R² for a round pore).
    #[inline(always)]
    pub(super) fn pore(
        self,
        cx: f32,
        cy: f32,
        metric: impl Fn(f32, f32) -> f32,
        beta_depth: f32,
        shape: impl Fn(f32) -> f32,
    ) {
        for ((a, x), wy) in self.acc.iter_mut().zip(self.px).zip(self.wy) {
            let mut t = [0.0; LANES];
            for l in 0..LANES {
                let dx = x.0[l] - cx;
                let dy = wy.0[l] - cy;
                t[l] = metric(dx, dy);
            }
            if !any(t.map(|t| t < 1.0)) {
                continue;
            }
            for l in 0..LANES {
                let bm = if t[l] < 1.0 {
                    beta_depth * shape(t[l])
                } else {
                    0.0
                };
                a.0[l] += crate::layers::micro::fastmath::exp(bm) - 1.0;
            }
        }
    }

    /// Furrow from (sx, row − py) along `dir`, `len` mm long: β·m = β·A·(1 − d²/(ω·f)²)
    /// (eq. 16 around the segment, see `furrows::height`), d the distance to the segment
    /// and f the width factor (1/2 at the ends, 1 from `1/inv_taper` mm inward).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn furrow(
        self,
        sx: f32,
        py: f32,
        dir: [f32; 2],
        len: f32,
        beta_depth: f32,
        inv_w2: f32,
        inv_taper: f32,
    ) {
        for ((a, x), wy) in self.acc.iter_mut().zip(self.px).zip(self.wy) {
            // q = d²/f² (d² the squared distance over ω²): the divide only where the chunk
            // is reached. d² < f² exactly when the rounded quotient could be below 1, and a
            // lane whose quotient rounds to 1 adds exp(0) − 1 = 0 either way, so skipping
            // on d² ≥ f² skips the same chunks as skipping on q ≥ 1.
            // The taper factor f is at most 1, so d² ≥ 1 already rules a lane out: most
            // chunks a furrow visits are dismissed before f is computed.
            let (mut d2, mut on) = ([0.0; LANES], [0.0; LANES]);
            for l in 0..LANES {
                let px = x.0[l] - sx;
                let py = py + wy.0[l];
                let along = px * dir[0] + py * dir[1];
                let cross = px * dir[1] - py * dir[0];
                on[l] = along.clamp(0.0, len);
                let beyond = along - on[l];
                d2[l] = (cross * cross + beyond * beyond) * inv_w2;
            }
            if !any(d2.map(|d2| d2 < 1.0)) {
                continue;
            }
            let mut f2 = [0.0; LANES];
            for l in 0..LANES {
                let f = crate::layers::micro::furrows::taper(on[l].min(len - on[l]) * inv_taper);
                f2[l] = f * f;
            }
            if !any(std::array::from_fn(|l| d2[l] < f2[l])) {
                continue;
            }
            let mut q = [0.0; LANES];
            for l in 0..LANES {
                q[l] = d2[l] / f2[l];
            }
            for l in 0..LANES {
                let bm = beta_depth * crate::layers::micro::furrows::profile(q[l]);
                a.0[l] += crate::layers::micro::fastmath::exp(bm) - 1.0;
            }
        }
    }
}
