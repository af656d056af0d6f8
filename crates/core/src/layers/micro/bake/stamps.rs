//! Features as stamps: each pore or furrow with its reach, the rows it touches, and its
//! shifted copies on tiled maps; the [`Context`] shared by the bands of one bake.

// Lane loops over fixed-size arrays are the shape the vectoriser turns into whole-register
// operations (see the parent module).
#![allow(clippy::needless_range_loop)]

use super::*;

/// One feature placed on the map (possibly a shifted copy on tiled maps).
#[derive(Clone, Copy, Debug)]
pub(super) enum Stamp {
    Pore {
        centre: [f32; 2],
        inv_r2: f32,
        /// The pore's ellipse: cos and sin of its long axis and its aspect ratio (1 =
        /// round, the exact circular formula).
        ellipse: [f32; 3],
        /// β·dmax: the profile times this is β·m.
        beta_depth: f32,
        falloff: f32,
        radius: f32,
    },
    Furrow {
        start: [f32; 2],
        dir: [f32; 2],
        len: f32,
        /// β·A.
        beta_depth: f32,
        width: f32,
        inv_w2: f32,
        /// 1 / the length over which each end narrows, 1/mm.
        inv_taper: f32,
    },
}

/// Everything shared by the bands of one bake.
pub(super) struct Context<'a> {
    pub(super) w: usize,
    pub(super) h: usize,
    /// Chunks of [`LANES`] covering a row.
    pub(super) chunks: usize,
    pub(super) size_mm: f32,
    pub(super) beta: f32,
    pub(super) inv_n: f32,
    pub(super) profile: PoreProfile,
    pub(super) rim: Rim,
    pub(super) stamps: Vec<Stamp>,
    /// Stamp indices touching each band, in stamp order.
    pub(super) bands: Vec<Vec<u32>>,
    /// Pixel-centre x in mm, padded to whole chunks.
    pub(super) x_mm: Vec<Chunk>,
    pub(super) noise: Option<RowSampler<'a>>,
    pub(super) warp: Option<Warp<'a>>,
    pub(super) normals: Option<NormalSettings>,
}

pub(super) struct Warp<'a> {
    /// Coarse grid step, pixels.
    pub(super) step: usize,
    pub(super) cols: usize,
    pub(super) fields: [RowSampler<'a>; 2],
}

impl<'a> Context<'a> {
    pub(super) fn new(
        relief: &'a MicroRelief,
        size_px: usize,
        parts: Parts,
        normals: Option<NormalSettings>,
    ) -> Self {
        let p = &relief.settings;
        let (w, h) = (size_px, size_px);
        let size_mm = p.map_size_mm;
        let chunks = w.div_ceil(LANES);
        let us: Vec<f32> = (0..w)
            .map(|x| crate::maps::heightmap::pixel_to_u(x as u32, w as u32))
            .collect();
        let mut x_mm = vec![Chunk([0.0; LANES]); chunks];
        for (x, v) in bytemuck::cast_slice_mut::<Chunk, f32>(&mut x_mm)
            .iter_mut()
            .enumerate()
        {
            *v = (x as f32 + 0.5) / w as f32 * size_mm;
        }
        let warp_on =
            parts.features && p.warp_strength_mm > 0.0 && relief.warp[0].octave_count() > 0;
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
            std::f32::consts::SQRT_2 * p.warp_strength_mm
        } else {
            0.0
        };
        let beta = p.overlap_beta;
        let mut stamps = Vec::new();
        if parts.features {
            // The tension lines: the furrows' preferred direction θ, curving over the
            // patch (`MicroSettings::tension_at`).
            let aspect = relief.pore_aspect;
            for (k, pore) in relief.pores.iter().enumerate() {
                // Exact for the default scale 1 (x·1 = x): the project's own bytes.
                let radius = pore.radius_mm * relief.pore_radius_scale;
                // Each pore's long axis θ ± 15°, hashed from its index.
                let jitter = (crate::base::rng::mix64(p.seed ^ 0x504f_5245 ^ k as u64) >> 40)
                    as f32
                    / (1u64 << 24) as f32
                    - 0.5;
                let angle = p.tension_at(pore.centre_mm) + jitter * 30f32.to_radians();
                stamps.push(Stamp::Pore {
                    centre: pore.centre_mm,
                    inv_r2: 1.0 / (radius * radius),
                    ellipse: [angle.cos(), angle.sin(), aspect],
                    beta_depth: beta * pore.depth,
                    falloff: pore.falloff,
                    // The long semi-axis, R·√aspect (area kept).
                    radius: if aspect == 1.0 {
                        radius
                    } else {
                        radius * aspect.sqrt()
                    },
                });
            }
            let a = relief.furrow_anisotropy;
            for f in &relief.furrows {
                let d = [f.end_mm[0] - f.start_mm[0], f.end_mm[1] - f.start_mm[1]];
                let theta = p.tension_at([f.start_mm[0] + 0.5 * d[0], f.start_mm[1] + 0.5 * d[1]]);
                let (ct, st) = (theta.cos(), theta.sin());
                let len = (d[0] * d[0] + d[1] * d[1]).sqrt().max(1e-6);
                // Along the tension lines deeper, across them fading (exactly 1 at a = 0).
                let along = if a == 0.0 {
                    1.0
                } else {
                    let sin = (d[0] * st - d[1] * ct) / len;
                    let sin2 = sin * sin;
                    (1.0 - a * sin2) * (1.0 + 0.5 * a * (1.0 - sin2))
                };
                stamps.push(Stamp::Furrow {
                    start: f.start_mm,
                    dir: [d[0] / len, d[1] / len],
                    len,
                    beta_depth: beta * (f.depth * relief.furrow_depth_scale) * along,
                    width: f.width_mm,
                    inv_w2: 1.0 / (f.width_mm * f.width_mm),
                    inv_taper: 1.0 / (f.taper * len).max(1e-6),
                });
            }
        }
        if p.tile {
            stamps = tile_copies(&stamps, size_mm, reach);
        }
        let n_bands = h.div_ceil(BAND_ROWS);
        let mut bands = vec![Vec::new(); n_bands];
        for (k, s) in stamps.iter().enumerate() {
            if let Some((y0, y1)) = row_range(s, size_mm, h, reach) {
                for band in bands
                    .iter_mut()
                    .take((y1 - 1) / BAND_ROWS + 1)
                    .skip(y0 / BAND_ROWS)
                {
                    band.push(k as u32);
                }
            }
        }
        let noise = (parts.noise && relief.noise.octave_count() > 0 && p.noise_strength > 0.0)
            .then(|| RowSampler::new(&relief.noise, &us));
        Self {
            w,
            h,
            chunks,
            size_mm,
            beta,
            inv_n: 1.0 / p.overlap_n,
            profile: p.pore_shape.profile,
            rim: p.pore_shape.rim,
            stamps,
            bands,
            x_mm,
            noise,
            warp,
            normals,
        }
    }

    /// Chunk range [c0, c1) covering x_mm in [lo, hi].
    pub(super) fn chunk_range(&self, lo: f32, hi: f32) -> (usize, usize) {
        let f = self.w as f32 / self.size_mm;
        let x0 = (lo * f - 0.5).floor().max(0.0) as usize;
        let x1 = ((hi * f - 0.5).ceil() + 1.0).clamp(0.0, self.w as f32) as usize;
        if x0 >= x1 {
            return (0, 0);
        }
        (x0 / LANES, x1.div_ceil(LANES))
    }
}

/// Bounding rows [y0, y1) of a stamp (with the warp reach), `None` when it misses the map.
pub(super) fn row_range(s: &Stamp, size_mm: f32, h: usize, reach: f32) -> Option<(usize, usize)> {
    let (lo, hi) = extent(s, reach, 1);
    let row = |y_mm: f32| (1.0 - y_mm / size_mm) * h as f32 - 0.5;
    let y0 = row(hi).floor().max(0.0);
    let y1 = (row(lo).ceil() + 1.0).min(h as f32);
    (y1 > y0).then_some((y0 as usize, y1 as usize))
}

/// The stamp's extent along `axis` (0 = x, 1 = y), grown by `reach` (the warp).
pub(super) fn extent(s: &Stamp, reach: f32, axis: usize) -> (f32, f32) {
    match *s {
        Stamp::Pore { centre, radius, .. } => {
            (centre[axis] - radius - reach, centre[axis] + radius + reach)
        }
        Stamp::Furrow {
            start,
            dir,
            len,
            width,
            ..
        } => {
            let end = start[axis] + dir[axis] * len;
            let r = width + reach;
            (start[axis].min(end) - r, start[axis].max(end) + r)
        }
    }
}

/// On tiled maps: every stamp plus its copies shifted by ±size that reach into the map.
pub(super) fn tile_copies(stamps: &[Stamp], size_mm: f32, reach: f32) -> Vec<Stamp> {
    let mut out = Vec::with_capacity(stamps.len() * 5 / 4);
    for s in stamps {
        let (x0, x1) = extent(s, reach, 0);
        let (y0, y1) = extent(s, reach, 1);
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
