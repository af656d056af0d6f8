//! Skin micro-relief, docs/models.md §4 [P]: pores, furrows between pores, fractal noise, and their
//! log-smoothed overlaps, baked into a [`HeightMap`](crate::HeightMap).
//!
//! - [`pores`]: placement (blue noise / uniform) and the profiles of eqs. 15, 3, 11;
//! - [`furrows`]: the furrow network and eq. 16;
//! - [`noise`]: periodic fBm of gradient noise (eq. 17) with a row-coherent fast path;
//! - [`overlap`]: the log-mean-exp combination of eq. 18;
//! - [`bake`]: the band-parallel baker that puts them together;
//! - `fastmath`: portable, vectorisable `exp`/`ln` used by the hot loops.

pub mod bake;
mod fastmath;
pub mod furrows;
pub mod noise;
pub mod overlap;
pub mod pores;
pub mod weight;

pub use bake::{BakeTimings, MicroRelief};

use crate::maps::normal_map::NormalSettings;

/// Everything the micro-relief depends on, in the micro-relief's own terms (so this module
/// does not depend on the project file). Made, validated, by
/// [`crate::project::Project::micro_settings`].
#[derive(Clone, Debug, PartialEq)]
pub struct MicroSettings {
    /// Side of the square skin patch, mm.
    pub map_size_mm: f32,
    pub seed: u64,
    /// Periodic noise, features wrapping around the edges.
    pub tile: bool,
    pub pore_count: usize,
    pub pore_stats: pores::PoreStats,
    pub placement: pores::Placement,
    pub pore_shape: pores::PoreShape,
    /// The furrow network, or `None` when furrows are off.
    pub furrows: Option<furrows::FurrowParams>,
    /// The skin's tension lines on the patch, degrees counter-clockwise from +u (the
    /// furrows' preferred direction θ): what pores stretch along with age.
    pub tension_deg: f32,
    pub noise: noise::FbmParams,
    /// λ of eq. 17, height units.
    pub noise_strength: f32,
    pub warp: noise::FbmParams,
    /// Largest warp displacement per axis, mm.
    pub warp_strength_mm: f32,
    /// β and N of eq. 18.
    pub overlap_beta: f32,
    pub overlap_n: f32,
    pub normal: NormalSettings,
}

impl MicroSettings {
    /// The tension lines' direction at `c` (mm on the patch; radians, counter-clockwise
    /// from +u): `tension_deg` turned by up to ±0.6 rad (34°) by two smooth waves that
    /// wrap with the patch, so they curve over the skin as Langer's lines do (one
    /// direction over the whole patch, repeated over the head, drew the old pores, blind,
    /// as "dashes all pointing the same way, like hatching"; docs/models.md §4 "Age").
    pub fn tension_at(&self, c: [f32; 2]) -> f32 {
        let k = std::f32::consts::TAU / self.map_size_mm.max(1e-6);
        let (x, y) = (c[0] * k, c[1] * k);
        self.tension_deg.to_radians()
            + 0.35 * (2.0 * x + y + 0.7).sin()
            + 0.25 * (x - 2.0 * y + 2.1).sin()
    }

    /// Whether the pores and furrows of `self` and `other` are the same (the same seed,
    /// patch, tiling, pore and furrow settings): then only the bake has to be redone.
    pub fn same_features(&self, other: &Self) -> bool {
        self.map_size_mm == other.map_size_mm
            && self.seed == other.seed
            && self.tile == other.tile
            && self.pore_count == other.pore_count
            && self.pore_stats == other.pore_stats
            && self.placement == other.placement
            && self.furrows == other.furrows
    }
}
