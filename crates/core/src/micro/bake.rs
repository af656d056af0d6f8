//! The micro-relief baker (SPEC §3): pores + furrows, log-smoothed (eq. 18), plus fBm
//! (eq. 17), with pores and furrows evaluated in a domain-warped frame; optionally fused
//! with the 8-bit normal map (SPEC §4).
//!
//! Design, for speed with exact determinism:
//! - features are generated once, in millimetres ([`MicroRelief::new`]), independent of the
//!   map size;
//! - each feature becomes a *stamp* with a bounding row range (its reach includes the
//!   largest warp displacement); on tiled maps stamps near an edge get shifted copies, so
//!   everything wraps;
//! - the map is cut into bands of [`BAND_ROWS`] rows, each with the list of stamps that
//!   touch it (in global feature order), and bands are baked in parallel with rayon. A
//!   pixel's value depends only on its own row (a row always uses the stamp list of the
//!   band that owns it), so any thread count gives the same bytes;
//! - per row, every stamp adds exp(β·m) − 1 over its x-interval in chunks of [`LANES`]
//!   pixels (a circle or an oriented rectangle cut by the row; chunks the feature does not
//!   reach skip the `exp`), then the row is resolved with one `ln` per pixel of the chunks
//!   some feature covers; the band's fBm is then added in one pass over its rows, in
//!   column tiles ([`RowSampler::add_rows`]);
//! - the warp (two fBm fields) is smooth, so it is evaluated on a coarse grid (≤ 16 px,
//!   at most a quarter of its finest lattice cell), cached per coarse row, and interpolated;
//! - with normals ([`MicroRelief::bake_with_normals`]) each band also bakes the row above
//!   and below it (a one-row halo, recomputed unless the task's previous band just baked
//!   it: same bytes as its owner band's) and encodes its normal rows while its heights
//!   are still in cache, with the same row kernel as [`normal_map::encode_rgb8`], so the
//!   bytes equal `encode_rgb8(bake())`;
//! - a band is baked into the task's scratch and streamed to the output with
//!   non-temporal stores ([`crate::simd::stream_copy`]): the output is written once and
//!   never read in first;
//! - the hot loops are plain `f32` code over fixed-size chunks; the band function runs
//!   under [`crate::simd::dispatch`] (AVX-512, AVX2 or the SSE2 baseline, chosen at run
//!   time). All paths do the same IEEE operations (no fused multiply-add), so their output
//!   is byte-identical.

// Lane loops (`for l in 0..LANES`) over several fixed-size arrays at once are the shape the
// vectoriser turns into whole-register operations; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

use rayon::prelude::*;

use super::furrows::{Furrow, build_network};
use super::noise::{Chunk, FbmField, LANES, RowSampler, RowScratch};
use super::overlap::resolve;
use super::pores::{Pore, PoreProfile, Rim, place_pores, rim_window};
use crate::cancel::CancelToken;
use crate::error::Error;
use crate::heightmap::HeightMap;
use crate::normal_map::{self, NormalSettings, RowRule};
use crate::project::Project;
use crate::simd::Level;

/// Rows per parallel band.
pub const BAND_ROWS: usize = 32;

/// Wall-clock time of the stages of a bake, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BakeTimings {
    /// Pore placement and the furrow network (size independent, done in `new`).
    pub features_ms: f64,
    /// Stamps, band lists, column tables, output allocation.
    pub setup_ms: f64,
    /// The band pass: stamping, overlap resolve, noise, and the normal map when fused.
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
    /// Age scales (`docs/models.md` "Age"): R and A multipliers, 1 = the project's values.
    pore_radius_scale: f32,
    furrow_depth_scale: f32,
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
            pore_radius_scale: 1.0,
            furrow_depth_scale: 1.0,
        })
    }

    /// The relief of `project`, reusing this one's pores and furrows when the fields they
    /// depend on (seed, map size, tiling, the `pores` and `furrows` sections) are unchanged:
    /// a noise, warp, overlap or normal change never re-places a feature. Returns whether
    /// the features were regenerated.
    pub fn with_project(&self, project: &Project) -> Result<(Self, bool), Error> {
        let (a, b) = (&self.project, project);
        let same_features = a.seed == b.seed
            && a.map_size_mm == b.map_size_mm
            && a.tile == b.tile
            && a.pores == b.pores
            && a.furrows == b.furrows;
        if !same_features {
            let mut fresh = Self::new(project)?;
            fresh.set_age_scales(self.pore_radius_scale, self.furrow_depth_scale);
            return Ok((fresh, true));
        }
        project.validate().map_err(|message| Error::Project {
            source_name: "project".into(),
            message,
        })?;
        let p = project;
        let size = p.map_size_mm;
        let warp_gain = p.warp.strength_mm;
        Ok((
            Self {
                project: p.clone(),
                pores: self.pores.clone(),
                pore_spacing_mm: self.pore_spacing_mm,
                furrows: self.furrows.clone(),
                noise: FbmField::new(&p.noise_params(), size, p.tile, p.noise.strength, p.seed, 0),
                warp: [
                    FbmField::new(&p.warp_params(), size, p.tile, warp_gain, p.seed, 1),
                    FbmField::new(&p.warp_params(), size, p.tile, warp_gain, p.seed, 2),
                ],
                features_ms: 0.0,
                pore_radius_scale: self.pore_radius_scale,
                furrow_depth_scale: self.furrow_depth_scale,
            },
            false,
        ))
    }

    /// Sets the age scales of the pore radius R and the furrow depth A (`docs/models.md`
    /// "Age"): the features stay where they are, only their size changes. Scales are
    /// clamped to [0.01, 4]; 1 (the default) bakes the project's values bit for bit.
    pub fn set_age_scales(&mut self, pore_radius: f32, furrow_depth: f32) {
        let clamp = |x: f32| {
            if x.is_finite() {
                x.clamp(0.01, 4.0)
            } else {
                1.0
            }
        };
        self.pore_radius_scale = clamp(pore_radius);
        self.furrow_depth_scale = clamp(furrow_depth);
    }

    /// The current (pore radius, furrow depth) age scales.
    pub fn age_scales(&self) -> (f32, f32) {
        (self.pore_radius_scale, self.furrow_depth_scale)
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

    /// The project's normal-map settings (strength, convention, tiling) for
    /// [`MicroRelief::bake_with_normals`].
    pub fn normal_settings(&self) -> NormalSettings {
        NormalSettings {
            strength: self.project.normal.strength,
            convention: self.project.normal.convention,
            tiling: self.project.tile,
        }
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
        let (map, _, timings) = self.bake_at(size_px, parts, None, Level::detect())?;
        Ok((map, timings))
    }

    /// Bakes the `size_px`² height map and its 8-bit RGB normal map (row-major, 3 bytes per
    /// pixel, RGB = n·0.5 + 0.5, SPEC §4) in one pass. The normal bytes equal
    /// `normal_map::encode_rgb8(&height, normals)`; fusing saves reading the height map
    /// back from memory. `normals` is usually [`MicroRelief::normal_settings`].
    pub fn bake_with_normals(
        &self,
        size_px: u32,
        normals: &NormalSettings,
    ) -> Result<(HeightMap, Vec<u8>, BakeTimings), Error> {
        normals.validate()?;
        let (map, rgb, timings) =
            self.bake_at(size_px, Parts::default(), Some(normals), Level::detect())?;
        Ok((map, rgb, timings))
    }

    /// [`MicroRelief::bake_with_normals`] into buffers the caller keeps between bakes (the
    /// editor's live preview): `map` becomes the `size_px`² height map and `rgb` its normal
    /// map, reusing their allocations, so a bake at an unchanged size allocates nothing and
    /// touches no fresh pages. Every value is overwritten; the bytes equal those of
    /// `bake_with_normals(size_px, normals)`. On error `map` and `rgb` keep their content.
    pub fn bake_into(
        &self,
        size_px: u32,
        map: &mut HeightMap,
        rgb: &mut Vec<u8>,
        normals: &NormalSettings,
    ) -> Result<BakeTimings, Error> {
        self.bake_into_cancellable(size_px, map, rgb, normals, &CancelToken::never())
    }

    /// [`MicroRelief::bake_into`] that stops within one band per thread once `cancel` is
    /// set, returning [`Error::Cancelled`]; `map` and `rgb` then hold a partial bake.
    pub fn bake_into_cancellable(
        &self,
        size_px: u32,
        map: &mut HeightMap,
        rgb: &mut Vec<u8>,
        normals: &NormalSettings,
        cancel: &CancelToken,
    ) -> Result<BakeTimings, Error> {
        normals.validate()?;
        crate::heightmap::check_size(size_px, size_px)?;
        let t0 = std::time::Instant::now();
        let w = size_px as usize;
        if map.width_px() != size_px || map.height_px() != size_px {
            // Keep the allocation: only its length changes (the bake overwrites it all).
            let placeholder = HeightMap::zeros(1, 1)?;
            let mut data = std::mem::replace(map, placeholder).into_vec();
            data.resize(w * w, 0.0);
            *map = HeightMap::from_vec(size_px, size_px, data)?;
        }
        rgb.resize(w * w * 3, 0);
        let resize_ms = t0.elapsed().as_secs_f64() * 1e3;
        let mut timings = self.bake_band_pass(
            map,
            rgb,
            Parts::default(),
            Some(normals),
            Level::detect(),
            cancel,
        );
        cancel.check()?;
        timings.setup_ms += resize_ms;
        Ok(timings)
    }

    /// The bake, with the normal map when `normals` is given, for instruction-set `level`,
    /// into freshly allocated buffers.
    fn bake_at(
        &self,
        size_px: u32,
        parts: Parts,
        normals: Option<&NormalSettings>,
        level: Level,
    ) -> Result<(HeightMap, Vec<u8>, BakeTimings), Error> {
        let t0 = std::time::Instant::now();
        let mut map = HeightMap::zeros(size_px, size_px)?;
        let w = size_px as usize;
        let mut rgb = match normals {
            Some(_) => crate::heightmap::zeroed_vec::<u8>(w * w * 3, "normal map")?,
            None => Vec::new(),
        };
        let alloc_ms = t0.elapsed().as_secs_f64() * 1e3;
        let mut timings = self.bake_band_pass(
            &mut map,
            &mut rgb,
            parts,
            normals,
            level,
            &CancelToken::never(),
        );
        timings.setup_ms += alloc_ms;
        Ok((map, rgb, timings))
    }

    /// The band pass over `map` (any size; square) and, when `normals` is given, `rgb`
    /// (3 bytes per pixel of `map`), overwriting every value.
    fn bake_band_pass(
        &self,
        map: &mut HeightMap,
        rgb: &mut [u8],
        parts: Parts,
        normals: Option<&NormalSettings>,
        level: Level,
        cancel: &CancelToken,
    ) -> BakeTimings {
        let t0 = std::time::Instant::now();
        let w = map.width_px() as usize;
        let ctx = Context::new(self, w, parts, normals.copied());
        let t1 = std::time::Instant::now();
        let bake = |band: usize, out: &mut [f32], rgb: Option<&mut [u8]>, s: &mut Scratch| {
            if cancel.is_cancelled() {
                return;
            }
            crate::simd::dispatch_at(
                level,
                Band {
                    ctx: &ctx,
                    band,
                    out,
                    rgb,
                    scratch: s,
                },
            );
        };
        // Runs of neighbouring bands per task (about four per thread, for balance), so one
        // scratch, with its cached noise and warp lattice rows, serves many bands in a row
        // instead of starting cold at each band. Bytes do not depend on the grouping.
        let n_bands = map.height_px().div_ceil(BAND_ROWS as u32) as usize;
        let per_task = (n_bands / (4 * rayon::current_num_threads()).max(1)).max(1);
        let heights = map
            .data_mut()
            .par_chunks_mut(BAND_ROWS * w)
            .with_min_len(per_task);
        if normals.is_some() {
            heights
                .zip(rgb.par_chunks_mut(BAND_ROWS * w * 3))
                .with_min_len(per_task)
                .enumerate()
                .for_each_init(
                    || Scratch::new(&ctx),
                    |s, (band, (out, rgb))| bake(band, out, Some(rgb), s),
                );
        } else {
            heights.enumerate().for_each_init(
                || Scratch::new(&ctx),
                |s, (band, out)| bake(band, out, None, s),
            );
        }
        let t2 = std::time::Instant::now();
        BakeTimings {
            features_ms: self.features_ms,
            setup_ms: (t1 - t0).as_secs_f64() * 1e3,
            relief_ms: (t2 - t1).as_secs_f64() * 1e3,
        }
    }
}

/// One feature placed on the map (possibly a shifted copy on tiled maps).
#[derive(Clone, Copy, Debug)]
enum Stamp {
    Pore {
        centre: [f32; 2],
        inv_r2: f32,
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
struct Context<'a> {
    w: usize,
    h: usize,
    /// Chunks of [`LANES`] covering a row.
    chunks: usize,
    size_mm: f32,
    beta: f32,
    inv_n: f32,
    profile: PoreProfile,
    rim: Rim,
    stamps: Vec<Stamp>,
    /// Stamp indices touching each band, in stamp order.
    bands: Vec<Vec<u32>>,
    /// Pixel-centre x in mm, padded to whole chunks.
    x_mm: Vec<Chunk>,
    noise: Option<RowSampler<'a>>,
    warp: Option<Warp<'a>>,
    normals: Option<NormalSettings>,
}

struct Warp<'a> {
    /// Coarse grid step, pixels.
    step: usize,
    cols: usize,
    fields: [RowSampler<'a>; 2],
}

impl<'a> Context<'a> {
    fn new(
        relief: &'a MicroRelief,
        size_px: usize,
        parts: Parts,
        normals: Option<NormalSettings>,
    ) -> Self {
        let p = &relief.project;
        let (w, h) = (size_px, size_px);
        let size_mm = p.map_size_mm;
        let chunks = w.div_ceil(LANES);
        let us: Vec<f32> = (0..w)
            .map(|x| crate::heightmap::pixel_to_u(x as u32, w as u32))
            .collect();
        let mut x_mm = vec![Chunk([0.0; LANES]); chunks];
        for (x, v) in bytemuck::cast_slice_mut::<Chunk, f32>(&mut x_mm)
            .iter_mut()
            .enumerate()
        {
            *v = (x as f32 + 0.5) / w as f32 * size_mm;
        }
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
        let beta = p.overlap.beta;
        let mut stamps = Vec::new();
        if parts.features {
            for pore in &relief.pores {
                // Exact for the default scale 1 (x·1 = x): the project's own bytes.
                let radius = pore.radius_mm * relief.pore_radius_scale;
                stamps.push(Stamp::Pore {
                    centre: pore.centre_mm,
                    inv_r2: 1.0 / (radius * radius),
                    beta_depth: beta * pore.depth,
                    falloff: pore.falloff,
                    radius,
                });
            }
            for f in &relief.furrows {
                let d = [f.end_mm[0] - f.start_mm[0], f.end_mm[1] - f.start_mm[1]];
                let len = (d[0] * d[0] + d[1] * d[1]).sqrt().max(1e-6);
                stamps.push(Stamp::Furrow {
                    start: f.start_mm,
                    dir: [d[0] / len, d[1] / len],
                    len,
                    beta_depth: beta * (f.depth * relief.furrow_depth_scale),
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
        let noise = (parts.noise && relief.noise.octave_count() > 0 && p.noise.strength > 0.0)
            .then(|| RowSampler::new(&relief.noise, &us));
        Self {
            w,
            h,
            chunks,
            size_mm,
            beta,
            inv_n: 1.0 / p.overlap.n,
            profile: p.pores.profile,
            rim: p.pores.rim,
            stamps,
            bands,
            x_mm,
            noise,
            warp,
            normals,
        }
    }

    /// Chunk range [c0, c1) covering x_mm in [lo, hi].
    fn chunk_range(&self, lo: f32, hi: f32) -> (usize, usize) {
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
fn row_range(s: &Stamp, size_mm: f32, h: usize, reach: f32) -> Option<(usize, usize)> {
    let (lo, hi) = extent(s, reach, 1);
    let row = |y_mm: f32| (1.0 - y_mm / size_mm) * h as f32 - 0.5;
    let y0 = row(hi).floor().max(0.0);
    let y1 = (row(lo).ceil() + 1.0).min(h as f32);
    (y1 > y0).then_some((y0 as usize, y1 as usize))
}

/// The stamp's extent along `axis` (0 = x, 1 = y), grown by `reach` (the warp).
fn extent(s: &Stamp, reach: f32, axis: usize) -> (f32, f32) {
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
fn tile_copies(stamps: &[Stamp], size_mm: f32, reach: f32) -> Vec<Stamp> {
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

/// One coarse warp row: both fields at the coarse columns, and their largest magnitudes.
#[derive(Clone, Debug, Default)]
struct CoarseRow {
    j: Option<usize>,
    values: [Vec<f32>; 2],
    max_abs: [f32; 2],
}

/// Per-task buffers.
struct Scratch {
    /// Σ (exp(β·m) − 1) of the current row.
    acc: Vec<Chunk>,
    /// Warped pixel-centre x (x_mm + warp x), mm.
    px: Vec<Chunk>,
    /// Warp y, mm.
    wy: Vec<Chunk>,
    /// Coarse warp rows j and j + 1 of the current row.
    coarse: [CoarseRow; 2],
    /// The coarse warp row blended to the current row, per field.
    blend: [Vec<f32>; 2],
    noise: RowScratch,
    /// The warp fields' own caches (each keeps its lattice rows between pixel rows).
    warp_noise: [RowScratch; 2],
    /// The band's height rows, baked here and streamed to the output at the end (rows
    /// are 64-byte aligned when the width is a whole number of chunks).
    rows: Vec<Chunk>,
    /// One row of the normal map, encoded here and streamed to the output.
    rgb_row: Vec<u8>,
    /// Height rows just outside the band (the normal map's neighbours).
    halo: [Vec<f32>; 2],
    /// Rows kept from the previous band of this task for its successor (with normals):
    /// that band's last row (the next band's halo above) and its halo below (the next
    /// band's first row), by row index.
    kept: [(Option<usize>, Vec<f32>); 2],
}

impl Scratch {
    fn new(ctx: &Context) -> Self {
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

/// One band's work, a [`crate::simd::Kernel`].
struct Band<'a, 'c> {
    ctx: &'a Context<'c>,
    band: usize,
    out: &'a mut [f32],
    rgb: Option<&'a mut [u8]>,
    scratch: &'a mut Scratch,
}

impl crate::simd::Kernel for Band<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        bake_band(self.ctx, self.band, self.out, self.rgb, self.scratch);
    }
}

/// Bakes the rows of `band` into `out` (and their normals into `rgb`).
///
/// The rows are baked into the task's scratch band (which stays in cache for the normal
/// map) and streamed to `out` and `rgb` at the end ([`crate::simd::stream_copy`]): the
/// output is written once, without reading it in first.
#[inline(always)]
fn bake_band(ctx: &Context, band: usize, out: &mut [f32], rgb: Option<&mut [u8]>, s: &mut Scratch) {
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
            crate::simd::stream_copy(dst, &s.rgb_row);
        }
    }
    crate::simd::stream_copy(out, heights);
    crate::simd::stream_fence();
    s.halo = halo;
    s.rows = rows;
}

/// Bakes the features (pores and furrows, log-smoothed) of row `y` into `dst` (w values).
#[inline(always)]
fn feature_row(ctx: &Context, y: usize, dst: &mut [f32], s: &mut Scratch) {
    let v = crate::heightmap::pixel_to_v(y as u32, ctx.h as u32);
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
fn add_noise(ctx: &Context, y: usize, rows: &mut [f32], s: &mut Scratch) {
    if let Some(n) = &ctx.noise {
        // At most a band's rows.
        let mut vs = [0.0f32; BAND_ROWS];
        let vs = &mut vs[..rows.len() / ctx.w];
        for (k, v) in vs.iter_mut().enumerate() {
            *v = crate::heightmap::pixel_to_v((y + k) as u32, ctx.h as u32);
        }
        n.add_rows(vs, rows, ctx.w, &mut s.noise);
    }
}

/// Bakes row `y` whole (features, then noise) into `dst`.
#[inline(always)]
fn height_row(ctx: &Context, y: usize, dst: &mut [f32], s: &mut Scratch) {
    feature_row(ctx, y, dst, s);
    add_noise(ctx, y, dst, s);
}

/// True when any lane is set (compiles to one vector test).
#[inline(always)]
fn any(mask: [bool; LANES]) -> bool {
    mask.iter().fold(false, |a, &b| a | b)
}

/// Fills `s.px` (x_mm + warp x) and `s.wy` for row `y`; returns a bound on the warp
/// displacement in this row (the row's warp is a convex blend of the two coarse rows
/// around it, so their largest magnitudes bound it). Stamps only visit pixels within that
/// reach; pixels outside a stamp's support add exactly 0, so the bound changes speed,
/// never the bytes.
#[inline(always)]
fn warp_row(ctx: &Context, warp: &Warp, y: usize, s: &mut Scratch) -> f32 {
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
fn interpolate<const S: usize>(
    blend: &[Vec<f32>; 2],
    x_mm: &[Chunk],
    px: &mut [Chunk],
    wy: &mut [Chunk],
) {
    let per = LANES / S;
    let frac: [f32; LANES] = std::array::from_fn(|k| (k % S) as f32 * (1.0 / S as f32));
    let (bx, by) = (blend[0].as_slice(), blend[1].as_slice());
    for (c, ((p, x), y)) in px.iter_mut().zip(x_mm).zip(wy.iter_mut()).enumerate() {
        crate::simd::keep_chunk_loop();
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
fn stamp_row(ctx: &Context, st: &Stamp, y_mm: f32, reach: f32, s: &mut Scratch) {
    match *st {
        Stamp::Pore {
            centre,
            inv_r2,
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
            match (ctx.profile, ctx.rim) {
                (PoreProfile::Gaussian, Rim::Smooth) => {
                    span.pore(cx, cy, inv_r2, beta_depth, |t| {
                        super::fastmath::exp(-falloff * t) * rim_window(t)
                    })
                }
                (PoreProfile::Gaussian, Rim::Exact) => span.pore(cx, cy, inv_r2, beta_depth, |t| {
                    super::fastmath::exp(-falloff * t)
                }),
                (PoreProfile::Quadratic, _) => span.pore(cx, cy, inv_r2, beta_depth, |t| {
                    let q = 1.0 - t.sqrt();
                    q * q
                }),
                (PoreProfile::Quartic, _) => {
                    span.pore(cx, cy, inv_r2, beta_depth, |t| (1.0 - t) * (1.0 - t))
                }
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
struct Span<'s> {
    acc: &'s mut [Chunk],
    px: &'s [Chunk],
    wy: &'s [Chunk],
}

impl<'s> Span<'s> {
    #[inline(always)]
    fn new(s: &'s mut Scratch, c0: usize, c1: usize) -> Self {
        Self {
            acc: &mut s.acc[c0..c1],
            px: &s.px[c0..c1],
            wy: &s.wy[c0..c1],
        }
    }

    /// Pore centred `cy` mm above this row at x = `cx`: β·m = β·dmax·shape(r²/R²).
    #[inline(always)]
    fn pore(self, cx: f32, cy: f32, inv_r2: f32, beta_depth: f32, shape: impl Fn(f32) -> f32) {
        for ((a, x), wy) in self.acc.iter_mut().zip(self.px).zip(self.wy) {
            let mut t = [0.0; LANES];
            for l in 0..LANES {
                let dx = x.0[l] - cx;
                let dy = wy.0[l] - cy;
                t[l] = (dx * dx + dy * dy) * inv_r2;
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
                a.0[l] += super::fastmath::exp(bm) - 1.0;
            }
        }
    }

    /// Furrow from (sx, row − py) along `dir`, `len` mm long: β·m = β·A·(1 − d²/(ω·f)²)
    /// (eq. 16 around the segment, see `furrows::height`), d the distance to the segment
    /// and f the width factor (1/2 at the ends, 1 from `1/inv_taper` mm inward).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn furrow(
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
                let e = (on[l].min(len - on[l]) * inv_taper).clamp(0.0, 1.0);
                let f = 0.5 + 0.5 * (e * e * (3.0 - 2.0 * e));
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
                let bm = if q[l] < 1.0 {
                    beta_depth * (1.0 - q[l])
                } else {
                    0.0
                };
                a.0[l] += super::fastmath::exp(bm) - 1.0;
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
        // Every level this CPU has (AVX-512, AVX2) against the baseline, height and normals,
        // tiled and not, at a width that is not a whole number of chunks.
        for tile in [false, true] {
            let relief = MicroRelief::new(&project(tile)).unwrap();
            let settings = relief.normal_settings();
            let bake = |level| {
                relief
                    .bake_at(200, Parts::default(), Some(&settings), level)
                    .unwrap()
            };
            let (base_h, base_n, _) = bake(Level::Baseline);
            let bits = |m: &HeightMap| m.data().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
            for level in [Level::Avx2, Level::Avx512] {
                let (h, n, _) = bake(level);
                assert_eq!(bits(&h), bits(&base_h), "heights, {level:?}, tile {tile}");
                assert_eq!(n, base_n, "normals, {level:?}, tile {tile}");
            }
        }
    }

    #[test]
    fn fused_normals_equal_encoding_the_baked_heights() {
        for (tile, convention) in [
            (false, crate::normal_map::Convention::OpenGl),
            (true, crate::normal_map::Convention::DirectX),
        ] {
            let relief = MicroRelief::new(&project(tile)).unwrap();
            let settings = NormalSettings {
                strength: 0.01,
                convention,
                tiling: tile,
            };
            // 2 full bands and a short one, so halos cross band and map edges.
            let size = 2 * BAND_ROWS as u32 + 7;
            let (h, rgb, _) = relief.bake_with_normals(size, &settings).unwrap();
            let (plain, _) = relief.bake(size).unwrap();
            assert_eq!(h.data(), plain.data());
            let want = crate::normal_map::encode_rgb8(&h, &settings).unwrap();
            assert_eq!(rgb.len(), want.len());
            let first_diff = rgb.iter().zip(&want).position(|(a, b)| a != b);
            assert_eq!(first_diff, None, "first differing byte");
            // Not flat: the relief shows in the normals.
            assert!(
                rgb.iter().step_by(3).any(|&r| r < 100) && rgb.iter().step_by(3).any(|&r| r > 156)
            );
        }
    }

    #[test]
    fn bake_into_reuses_buffers_and_equals_a_fresh_bake() {
        let relief = MicroRelief::new(&project(true)).unwrap();
        let settings = relief.normal_settings();
        // Stale buffers of another size, full of values a bake never writes (NaN, 0xAB):
        // growing, shrinking and an unchanged size must all overwrite every value.
        let mut map = HeightMap::from_vec(3, 3, vec![f32::NAN; 9]).unwrap();
        let mut rgb = vec![0xAB; 5];
        let bits = |m: &HeightMap| m.data().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
        for size in [2 * BAND_ROWS as u32 + 7, 40, 40] {
            let (want_h, want_rgb, _) = relief.bake_with_normals(size, &settings).unwrap();
            map.data_mut().fill(f32::NAN);
            rgb.fill(0xAB);
            relief
                .bake_into(size, &mut map, &mut rgb, &settings)
                .unwrap();
            assert_eq!((map.width_px(), map.height_px()), (size, size));
            assert_eq!(bits(&map), bits(&want_h), "heights at {size}²");
            assert_eq!(rgb, want_rgb, "normals at {size}²");
        }
        // Bad sizes are errors and leave the buffers as they were.
        let before = (bits(&map), rgb.clone());
        assert!(relief.bake_into(0, &mut map, &mut rgb, &settings).is_err());
        assert_eq!((bits(&map), rgb.clone()), before);
    }

    #[test]
    fn fused_bands_reusing_their_neighbours_rows_equal_two_passes() {
        // One thread: runs of bands per task, each band taking its first row and halo above
        // from the previous band; the bytes must not change.
        let relief = MicroRelief::new(&project(true)).unwrap();
        let settings = relief.normal_settings();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let size = 9 * BAND_ROWS as u32 + 5;
        let (h, rgb, _) = pool.install(|| relief.bake_with_normals(size, &settings).unwrap());
        let (plain, _) = relief.bake(size).unwrap();
        let bits = |m: &HeightMap| m.data().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&h), bits(&plain));
        let want = crate::normal_map::encode_rgb8(&plain, &settings).unwrap();
        let first_diff = rgb.iter().zip(&want).position(|(a, b)| a != b);
        assert_eq!(first_diff, None, "first differing byte");
    }

    /// FNV-1a over the height bits and the normal bytes.
    fn fingerprint(map: &HeightMap, rgb: &[u8]) -> u64 {
        let bytes = map.data().iter().flat_map(|h| h.to_le_bytes());
        bytes
            .chain(rgb.iter().copied())
            .fold(0xcbf2_9ce4_8422_2325, |h, b| {
                (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
            })
    }

    #[test]
    fn output_bytes_are_pinned() {
        // Speed work must not move a single bit: the rough preset (warp, 6 octaves of
        // noise, dense furrows) at widths that are and are not whole chunks, tiled and not.
        // A deliberate change of the model updates these numbers, and says so.
        let mut seen = Vec::new();
        for (size, tile) in [(200, false), (333, true), (512, false)] {
            let text = include_str!("../../../../assets/presets/rough.agesim.json");
            let mut p = Project::from_json_str(text, "rough").unwrap();
            p.tile = tile;
            let relief = MicroRelief::new(&p).unwrap();
            let (map, rgb, _) = relief
                .bake_with_normals(size, &relief.normal_settings())
                .unwrap();
            seen.push(fingerprint(&map, &rgb));
        }
        assert_eq!(
            seen,
            [915776542343579408, 456448684703738143, 9722876278322697966],
            "fingerprints changed"
        );
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
