//! The project's sections of the relief: large wrinkles, the micro-relief's pores, furrows,
//! noise, domain warp and overlaps, and the height → normal map.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use super::DEFAULT_GAMMA;
use crate::layers::micro::pores::{Placement, PoreProfile, Rim};
use crate::maps::normal_map::Convention;

/// A value drawn uniformly in `mean ± spread` per feature.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeanSpread {
    pub mean: f32,
    #[serde(default)]
    pub spread: f32,
}

impl MeanSpread {
    pub const fn new(mean: f32, spread: f32) -> Self {
        Self { mean, spread }
    }
    pub(super) fn pair(&self) -> (f32, f32) {
        (self.mean, self.spread)
    }
}

/// Large wrinkles (docs/models.md §2–3), combined as `depth × (normalised height)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LargeSection {
    /// Bake the large-wrinkle layer at all (the skin-patch presets turn it off).
    pub enabled: bool,
    /// Wrinkle description files (docs/models.md §3); relative paths are relative to the project file.
    pub wrinkles: Vec<PathBuf>,
    /// Optional grey mask image multiplying the large wrinkles.
    pub mask: Option<PathBuf>,
    /// Crest flattening γ, 0.01–10 (`muscle::GAMMA_RANGE`).
    pub gamma: f32,
    /// Height units of a normalised wrinkle height of 1; 0–10.
    pub depth: f32,
}

/// Pores (docs/models.md §4 "Pores").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PoreSection {
    pub enabled: bool,
    /// Exact number of pores, 0–200000 (ignored when `density_per_cm2` is set).
    pub count: u32,
    /// Pores per cm² of skin; when set, count = round(density × area).
    pub density_per_cm2: Option<f32>,
    pub placement: Placement,
    /// R, mm: mean 0–1, spread 0–1.
    pub radius_mm: MeanSpread,
    /// dmax, height units: mean 0–4 (Table 1 slider 0–2; [P] fig. 15 uses 3), spread 0–4.
    pub depth: MeanSpread,
    /// α: mean −1.5–1.5 (negative = goose skin), spread 0–1.5.
    pub falloff: MeanSpread,
    pub profile: PoreProfile,
    pub rim: Rim,
    /// Aspect ratio (long over short axis) of every pore at full age, along the furrows'
    /// direction θ (the tension lines), 1–4; 1 = round at every age.
    pub elongation: f32,
}

/// Furrows between pores (docs/models.md §4 "Wrinkles between pores").
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FurrowSection {
    pub enabled: bool,
    /// Links from each pore to its nearest neighbours, 1–8.
    pub links_per_pore: u32,
    /// Keep at most this many links (a seeded random subset); `null` = all.
    pub max_count: Option<u32>,
    /// A, height units: mean 0–2.5, spread 0–2.5.
    pub depth: MeanSpread,
    /// ω (half-width), mm: mean 0–1.5, spread 0–1.5.
    pub width_mm: MeanSpread,
    /// Preferred direction θ, degrees counter-clockwise from +u, −360–360.
    pub direction_deg: f32,
    /// 0–1: how much shallower links across θ are than links along it.
    pub direction_strength: f32,
    /// 0–1: how much more the furrows follow θ at full age (across ones fading, along
    /// ones deepening), on top of `direction_strength`.
    pub anisotropy: f32,
    /// Fraction of the length over which each end narrows to half width (the depth stays
    /// full, so furrows join at pores), 0.01–0.5.
    pub taper: f32,
}

/// fBm added to the heights (docs/models.md §4 "Noise", eq. 17).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NoiseSection {
    /// Octaves 0–12, fractional allowed; 0 = no noise.
    pub details: f32,
    /// Amplitude gain per octave, 0–1.
    pub roughness: f32,
    /// Frequency factor per octave, 0.1–4.
    pub lacunarity: f32,
    /// First-octave lattice cell, mm, 0.01–1000.
    pub scale_mm: f32,
    /// λ, height units, 0–10.
    pub strength: f32,
}

/// Domain warp of pores and furrows (docs/models.md §4 Choice): the same fBm, own settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WarpSection {
    /// Largest displacement per axis, mm, 0–10; 0 = no warp.
    pub strength_mm: f32,
    /// Octaves 0–6.
    pub details: f32,
    pub roughness: f32,
    pub lacunarity: f32,
    /// First-octave lattice cell, mm, 0.01–1000.
    pub scale_mm: f32,
}

/// Log-smoothed overlaps (docs/models.md §4 "Overlaps", eq. 18).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OverlapSection {
    /// β, per height unit, 0.01–40; larger = sharper (the deepest wins).
    pub beta: f32,
    /// N ≥ 1, 1–100: smoothing.
    pub n: f32,
}

/// Height → normal map settings (docs/models.md §5).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NormalSection {
    /// s of docs/models.md §5: UV units per height unit, 0–1000 (resolution independent; see
    /// `normal_map`). The micro-relief default 0.002 reads as moderate relief on a 50 mm map.
    pub strength: f32,
    /// `opengl` (green up, default) or `directx`.
    pub convention: Convention,
}

impl Default for LargeSection {
    fn default() -> Self {
        Self {
            enabled: true,
            wrinkles: Vec::new(),
            mask: None,
            gamma: DEFAULT_GAMMA,
            depth: 1.0,
        }
    }
}

impl Default for PoreSection {
    fn default() -> Self {
        Self {
            enabled: true,
            count: 1500,
            density_per_cm2: None,
            placement: Placement::BlueNoise,
            radius_mm: MeanSpread::new(0.3, 0.08),
            // 1.0 ± 0.3 with furrows of 0.2 read, blind, at 75 as "fish scales".
            depth: MeanSpread::new(0.7, 0.25),
            falloff: MeanSpread::new(1.0, 0.2),
            profile: PoreProfile::Gaussian,
            rim: Rim::Smooth,
            // docs/models.md "Micro-relief with age": ≈ 1 young, ≥ 1.5 by the 60s.
            elongation: 1.6,
        }
    }
}

impl Default for FurrowSection {
    fn default() -> Self {
        Self {
            enabled: true,
            // Two links a pore: a broken network of lines between the pores. Four closed
            // every pore in a polygon, read blind at 75 as "crocodile leather".
            links_per_pore: 2,
            max_count: None,
            // Narrow, shallow lines (a blind rating read [P]'s 0.6 deep, 0.3 mm half-wide
            // network as cracked vinyl at a face's distance): skin furrows are 20–200 µm
            // deep and about a tenth of a millimetre wide.
            depth: MeanSpread::new(0.14, 0.06),
            width_mm: MeanSpread::new(0.12, 0.03),
            direction_deg: 30.0,
            direction_strength: 0.5,
            anisotropy: 0.8,
            taper: 0.3,
        }
    }
}

impl Default for NoiseSection {
    fn default() -> Self {
        Self {
            details: 5.0,
            roughness: 0.5,
            lacunarity: 2.0,
            scale_mm: 4.0,
            strength: 0.3,
        }
    }
}

impl Default for WarpSection {
    fn default() -> Self {
        Self {
            strength_mm: 0.25,
            details: 2.0,
            roughness: 0.5,
            lacunarity: 2.0,
            scale_mm: 3.0,
        }
    }
}

impl Default for OverlapSection {
    fn default() -> Self {
        Self { beta: 4.0, n: 1.0 }
    }
}

impl Default for NormalSection {
    fn default() -> Self {
        Self {
            strength: crate::maps::normal_map::DEFAULT_STRENGTH,
            convention: Convention::OpenGl,
        }
    }
}
