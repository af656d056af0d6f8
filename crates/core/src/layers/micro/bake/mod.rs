//! The micro-relief baker (docs/models.md §4): pores + furrows, log-smoothed (eq. 18), plus fBm
//! (eq. 17), with pores and furrows evaluated in a domain-warped frame; optionally fused
//! with the 8-bit normal map (docs/models.md §5).
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
//!   non-temporal stores ([`crate::base::simd::stream_copy`]): the output is written once and
//!   never read in first;
//! - the hot loops are plain `f32` code over fixed-size chunks; the band function runs
//!   under `crate::base::simd::dispatch_at` (AVX-512, AVX2 or the SSE2 baseline, chosen at run
//!   time). All paths do the same IEEE operations (no fused multiply-add), so their output
//!   is byte-identical.

// Lane loops (`for l in 0..LANES`) over several fixed-size arrays at once are the shape the
// vectoriser turns into whole-register operations; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

use rayon::prelude::*;

use super::MicroSettings;
use super::furrows::{Furrow, build_network};
use super::noise::{FbmField, RowSampler, RowScratch};
use super::overlap::resolve;
use super::pores::{Pore, PoreProfile, PoreShape, Rim, place_pores};
use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::base::simd::Level;
use crate::base::simd::{Chunk, LANES};
use crate::maps::heightmap::HeightMap;
use crate::maps::normal_map::{self, NormalSettings, RowRule};

mod band;
mod stamps;
#[cfg(test)]
mod tests;

use band::*;
use stamps::*;

/// The noise field and the two warp fields of `s`.
fn fields(s: &MicroSettings) -> (FbmField, [FbmField; 2]) {
    let size = s.map_size_mm;
    let gain = s.warp_strength_mm;
    (
        FbmField::new(&s.noise, size, s.tile, s.noise_strength, s.seed, 0),
        [
            FbmField::new(&s.warp, size, s.tile, gain, s.seed, 1),
            FbmField::new(&s.warp, size, s.tile, gain, s.seed, 2),
        ],
    )
}

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

/// The micro-relief of some [`MicroSettings`], ready to bake at any size.
#[derive(Clone, Debug)]
pub struct MicroRelief {
    settings: MicroSettings,
    pores: Vec<Pore>,
    pore_spacing_mm: f32,
    furrows: Vec<Furrow>,
    noise: FbmField,
    warp: [FbmField; 2],
    features_ms: f64,
    /// Age scales (`docs/models.md` "Age"): R and A multipliers, 1 = the project's values.
    pore_radius_scale: f32,
    furrow_depth_scale: f32,
    /// Age directions (`docs/models.md` "Age", "Micro-relief with age"): each pore's
    /// aspect ratio (1 = round) and how much the furrows follow the tension lines.
    pore_aspect: f32,
    furrow_anisotropy: f32,
}

impl MicroRelief {
    /// Generates the pores and furrows of `settings` (validated by
    /// [`crate::project::Project::micro_settings`]).
    pub fn new(settings: &MicroSettings) -> Result<Self, Error> {
        let t0 = std::time::Instant::now();
        let s = settings;
        let size = s.map_size_mm;
        let placement = place_pores(
            s.pore_count,
            &s.pore_stats,
            s.placement,
            size,
            s.tile,
            s.seed,
        );
        let furrows = match &s.furrows {
            Some(params) => build_network(&placement.pores, params, size, s.tile, s.seed),
            None => Vec::new(),
        };
        let (noise, warp) = fields(s);
        Ok(Self {
            settings: s.clone(),
            pores: placement.pores,
            pore_spacing_mm: placement.min_spacing_mm,
            furrows,
            noise,
            warp,
            features_ms: t0.elapsed().as_secs_f64() * 1e3,
            pore_radius_scale: 1.0,
            furrow_depth_scale: 1.0,
            pore_aspect: 1.0,
            furrow_anisotropy: 0.0,
        })
    }

    /// The relief of `settings`, reusing this one's pores and furrows when the fields they
    /// depend on are unchanged ([`MicroSettings::same_features`]): a noise, warp, overlap or
    /// normal change never re-places a feature. Returns whether the features were
    /// regenerated.
    pub fn with_settings(&self, settings: &MicroSettings) -> Result<(Self, bool), Error> {
        if !self.settings.same_features(settings) {
            let mut fresh = Self::new(settings)?;
            fresh.set_age_scales(self.pore_radius_scale, self.furrow_depth_scale);
            fresh.set_age_directions(self.pore_aspect, self.furrow_anisotropy);
            return Ok((fresh, true));
        }
        let (noise, warp) = fields(settings);
        Ok((
            Self {
                settings: settings.clone(),
                pores: self.pores.clone(),
                pore_spacing_mm: self.pore_spacing_mm,
                furrows: self.furrows.clone(),
                noise,
                warp,
                features_ms: 0.0,
                pore_radius_scale: self.pore_radius_scale,
                furrow_depth_scale: self.furrow_depth_scale,
                pore_aspect: self.pore_aspect,
                furrow_anisotropy: self.furrow_anisotropy,
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

    /// Sets how the pores stretch and the furrows align with age along the tension lines
    /// (the furrows' preferred direction θ; `docs/models.md` "Micro-relief with age"):
    /// every pore an ellipse of `pore_aspect` (long over short axis, area kept) along θ ±
    /// 15° (its own, hashed), and every furrow's depth times (1 − a·sin²φ)(1 + a·cos²φ/2)
    /// for `furrow_anisotropy` a and φ its angle to θ (across ones fade, along ones deepen).
    /// Clamped to [1, 4] and [0, 1]; (1, 0), the default, bakes the project's values bit for
    /// bit.
    pub fn set_age_directions(&mut self, pore_aspect: f32, furrow_anisotropy: f32) {
        self.pore_aspect = if pore_aspect.is_finite() {
            pore_aspect.clamp(1.0, 4.0)
        } else {
            1.0
        };
        self.furrow_anisotropy = if furrow_anisotropy.is_finite() {
            furrow_anisotropy.clamp(0.0, 1.0)
        } else {
            0.0
        };
    }

    /// The current (pore aspect, furrow anisotropy) age directions.
    pub fn age_directions(&self) -> (f32, f32) {
        (self.pore_aspect, self.furrow_anisotropy)
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
            tiling: self.settings.tile,
            ..self.settings.normal
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
    /// pixel, RGB = n·0.5 + 0.5, docs/models.md §5) in one pass. The normal bytes equal
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
        crate::maps::heightmap::check_size(size_px, size_px)?;
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

    /// Bakes only `parts` (features or noise) into `map` (reusing its allocation), no
    /// normals: the editor keeps the two apart so an age change re-bakes the features
    /// and a noise change the noise. Features + noise, added per pixel, are the bytes of
    /// the whole bake (the band pass adds the noise's octave sum to the features the
    /// same way).
    pub fn bake_parts_into(
        &self,
        size_px: u32,
        parts: Parts,
        map: &mut HeightMap,
        cancel: &CancelToken,
    ) -> Result<(), Error> {
        crate::maps::heightmap::check_size(size_px, size_px)?;
        if map.width_px() != size_px || map.height_px() != size_px {
            let placeholder = HeightMap::zeros(1, 1)?;
            let mut data = std::mem::replace(map, placeholder).into_vec();
            data.resize(size_px as usize * size_px as usize, 0.0);
            *map = HeightMap::from_vec(size_px, size_px, data)?;
        }
        self.bake_band_pass(map, &mut [], parts, None, Level::detect(), cancel);
        cancel.check()
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
            Some(_) => crate::maps::heightmap::zeroed_vec::<u8>(w * w * 3, "normal map")?,
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
            crate::base::simd::dispatch_at(
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
