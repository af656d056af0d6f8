//! The project file, `*.agesim.json`: every bake setting in one serde document (issue 3).
//!
//! `"version": 1`; every field has a default, so partial files load; unknown fields are an
//! error naming them by their JSON path; values outside their range are an error naming the
//! field and the range. `docs/project-file.md` documents every field (units, range, default).
//! [`Project::set`] edits one field by its JSON path (`pores.count=1000`) with the same
//! validation, for the command line's `--set`.
//!
//! **Units (SPEC §3 Choice).** The map is a square patch of skin `map_size_mm` on a side
//! (default 50 mm). Pore radius R and furrow half-width ω are in millimetres, so [P]'s
//! Table 1 ranges (R 0–1, ω 0–1.5) span fine pores to acne-scale ones; depths (dmax, A,
//! noise λ, large-wrinkle depth) are in height units (SPEC §0), the same units as the
//! baked height map. Nothing is in pixels, so a project bakes the same picture at any size.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::micro::furrows::FurrowParams;
use crate::micro::noise::FbmParams;
use crate::micro::pores::{Placement, PoreProfile, PoreStats, Rim};
use crate::normal_map::Convention;

/// The only project-file version this build reads and writes.
pub const PROJECT_VERSION: u32 = 1;
/// Default side of the skin patch, mm.
pub const DEFAULT_MAP_SIZE_MM: f32 = 50.0;
/// Default large-wrinkle crest flattening γ (SPEC §1).
pub const DEFAULT_GAMMA: f32 = crate::muscle::DEFAULT_GAMMA;

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
    fn pair(&self) -> (f32, f32) {
        (self.mean, self.spread)
    }
}

/// The whole project. See `docs/project-file.md` for every field.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Project {
    /// Must be 1.
    pub version: u32,
    /// Side of the square skin patch the map covers, mm. Range 1–1000.
    pub map_size_mm: f32,
    /// Seed of every random choice (pore positions, attributes, noise).
    pub seed: u64,
    /// Make the map tile: periodic noise, features wrapping around the edges.
    pub tile: bool,
    pub large: LargeSection,
    pub pores: PoreSection,
    pub furrows: FurrowSection,
    pub noise: NoiseSection,
    pub warp: WarpSection,
    pub overlap: OverlapSection,
    pub normal: NormalSection,
}

/// Large wrinkles (SPEC §1–2), combined as `depth × (normalised height)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LargeSection {
    /// Bake the large-wrinkle layer at all (the skin-patch presets turn it off).
    pub enabled: bool,
    /// Wrinkle description files (SPEC §2); relative paths are relative to the project file.
    pub wrinkles: Vec<PathBuf>,
    /// Optional grey mask image multiplying the large wrinkles.
    pub mask: Option<PathBuf>,
    /// Crest flattening γ, 0.01–10 (`muscle::GAMMA_RANGE`).
    pub gamma: f32,
    /// Height units of a normalised wrinkle height of 1; 0–10.
    pub depth: f32,
}

/// Pores (SPEC §3 "Pores").
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
}

/// Furrows between pores (SPEC §3 "Wrinkles between pores").
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
    /// Fraction of the length over which each end narrows to half width (the depth stays
    /// full, so furrows join at pores), 0.01–0.5.
    pub taper: f32,
}

/// fBm added to the heights (SPEC §3 "Noise", eq. 17).
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

/// Domain warp of pores and furrows (SPEC §3 Choice): the same fBm, own settings.
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

/// Log-smoothed overlaps (SPEC §3 "Overlaps", eq. 18).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OverlapSection {
    /// β, per height unit, 0.01–40; larger = sharper (the deepest wins).
    pub beta: f32,
    /// N ≥ 1, 1–100: smoothing.
    pub n: f32,
}

/// Height → normal map settings (SPEC §4).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NormalSection {
    /// s of SPEC §4: UV units per height unit, 0–1000 (resolution independent; see
    /// `normal_map`). The micro-relief default 0.002 reads as moderate relief on a 50 mm map.
    pub strength: f32,
    /// `opengl` (green up, default) or `directx`.
    pub convention: Convention,
}

impl Default for Project {
    fn default() -> Self {
        Self {
            version: PROJECT_VERSION,
            map_size_mm: DEFAULT_MAP_SIZE_MM,
            seed: 1,
            tile: false,
            large: LargeSection::default(),
            pores: PoreSection::default(),
            furrows: FurrowSection::default(),
            noise: NoiseSection::default(),
            warp: WarpSection::default(),
            overlap: OverlapSection::default(),
            normal: NormalSection::default(),
        }
    }
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
            depth: MeanSpread::new(1.0, 0.3),
            falloff: MeanSpread::new(1.0, 0.2),
            profile: PoreProfile::Gaussian,
            rim: Rim::Smooth,
        }
    }
}

impl Default for FurrowSection {
    fn default() -> Self {
        Self {
            enabled: true,
            links_per_pore: 4,
            max_count: None,
            depth: MeanSpread::new(0.6, 0.15),
            width_mm: MeanSpread::new(0.3, 0.05),
            direction_deg: 30.0,
            direction_strength: 0.5,
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
            strength: crate::normal_map::DEFAULT_STRENGTH,
            convention: Convention::OpenGl,
        }
    }
}

impl Project {
    /// Parses and validates a project document; `source` names it in errors.
    pub fn from_json_str(text: &str, source: &str) -> Result<Self, Error> {
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| Error::Project {
            source_name: source.to_owned(),
            message: e.to_string(),
        })?;
        Self::from_value(value, source)
    }

    /// Reads a `*.agesim.json` file. Relative wrinkle and mask paths are resolved against
    /// the file's directory.
    pub fn load(path: &Path) -> Result<Self, Error> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let mut p = Self::from_json_str(&text, &path.display().to_string())?;
        if let Some(dir) = path.parent() {
            p.large.resolve_paths(dir);
        }
        Ok(p)
    }

    /// Validates a JSON value and turns it into a project.
    pub fn from_value(value: serde_json::Value, source: &str) -> Result<Self, Error> {
        let err = |message: String| Error::Project {
            source_name: source.to_owned(),
            message,
        };
        let schema = serde_json::to_value(Self::default()).map_err(|e| err(e.to_string()))?;
        check_known_fields(&value, &schema, "")?.map_or(Ok(()), |m| Err(err(m)))?;
        let p: Self = serde_json::from_value(value).map_err(|e| err(e.to_string()))?;
        p.validate().map_err(err)?;
        Ok(p)
    }

    /// The project as a JSON value (every field, defaults included).
    pub fn to_value(&self) -> serde_json::Value {
        // Serialising plain structs of numbers, strings and paths cannot fail.
        serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
    }

    /// Pretty JSON of the whole project.
    pub fn to_json_pretty(&self) -> String {
        serde_json::to_string_pretty(&self.to_value()).unwrap_or_default()
    }

    /// Sets one field by its JSON path (`noise.details`) to `value_text` (JSON; bare words
    /// are taken as strings), then validates the whole project again.
    pub fn set(&self, path: &str, value_text: &str) -> Result<Self, Error> {
        let source = format!("--set {path}={value_text}");
        let value: serde_json::Value = serde_json::from_str(value_text)
            .unwrap_or_else(|_| serde_json::Value::String(value_text.to_owned()));
        let mut doc = self.to_value();
        let mut node = &mut doc;
        let keys: Vec<&str> = path.split('.').collect();
        if keys.iter().any(|k| k.is_empty()) {
            return Err(Error::Project {
                source_name: source,
                message: "empty field name in path".into(),
            });
        }
        for (depth, key) in keys.iter().enumerate() {
            let serde_json::Value::Object(map) = node else {
                return Err(Error::Project {
                    source_name: source,
                    message: format!("`{}` is not an object", keys[..depth].join(".")),
                });
            };
            let Some(next) = map.get_mut(*key) else {
                return Err(Error::Project {
                    source_name: source,
                    message: format!("unknown field `{}`", keys[..=depth].join(".")),
                });
            };
            node = next;
        }
        *node = value;
        // Paths set on the command line stay relative to the working directory.
        Self::from_value(doc, &source)
    }

    /// Checks every range; the message names the field and its range.
    pub fn validate(&self) -> Result<(), String> {
        let mut c = Checker::default();
        if self.version != PROJECT_VERSION {
            c.fail("version", self.version, &format!("{PROJECT_VERSION}"));
        }
        c.range("map_size_mm", self.map_size_mm, 1.0, 1000.0);
        let (gamma_lo, gamma_hi) = crate::muscle::GAMMA_RANGE;
        c.range("large.gamma", self.large.gamma, gamma_lo, gamma_hi);
        c.range("large.depth", self.large.depth, 0.0, 10.0);
        let p = &self.pores;
        c.range("pores.count", p.count as f32, 0.0, 200_000.0);
        if let Some(d) = p.density_per_cm2 {
            c.range("pores.density_per_cm2", d, 0.0, 10_000.0);
            let count = d * self.map_size_mm * self.map_size_mm / 100.0;
            if count > 200_000.0 {
                c.fail(
                    "pores.density_per_cm2",
                    d,
                    "a density giving at most 200000 pores on the map",
                );
            }
        }
        c.mean_spread("pores.radius_mm", p.radius_mm, 0.0, 1.0, 1.0);
        c.mean_spread("pores.depth", p.depth, 0.0, 4.0, 4.0);
        c.mean_spread("pores.falloff", p.falloff, -1.5, 1.5, 1.5);
        let f = &self.furrows;
        c.range("furrows.links_per_pore", f.links_per_pore as f32, 1.0, 8.0);
        c.mean_spread("furrows.depth", f.depth, 0.0, 2.5, 2.5);
        c.mean_spread("furrows.width_mm", f.width_mm, 0.0, 1.5, 1.5);
        c.range("furrows.direction_deg", f.direction_deg, -360.0, 360.0);
        c.range("furrows.direction_strength", f.direction_strength, 0.0, 1.0);
        c.range("furrows.taper", f.taper, 0.01, 0.5);
        let n = &self.noise;
        c.range("noise.details", n.details, 0.0, 12.0);
        c.range("noise.roughness", n.roughness, 0.0, 1.0);
        c.range("noise.lacunarity", n.lacunarity, 0.1, 4.0);
        c.range("noise.scale_mm", n.scale_mm, 0.01, 1000.0);
        c.range("noise.strength", n.strength, 0.0, 10.0);
        let w = &self.warp;
        c.range("warp.strength_mm", w.strength_mm, 0.0, 10.0);
        c.range("warp.details", w.details, 0.0, 6.0);
        c.range("warp.roughness", w.roughness, 0.0, 1.0);
        c.range("warp.lacunarity", w.lacunarity, 0.1, 4.0);
        c.range("warp.scale_mm", w.scale_mm, 0.01, 1000.0);
        c.range("overlap.beta", self.overlap.beta, 0.01, 40.0);
        c.range("overlap.n", self.overlap.n, 1.0, 100.0);
        c.range("normal.strength", self.normal.strength, 0.0, 1000.0);
        // Finest noise cell no smaller than 1 µm, so lattice coordinates stay exact in f32.
        for (name, s) in [
            ("noise", n.scale_mm / n.lacunarity.max(1.0).powf(n.details)),
            ("warp", w.scale_mm / w.lacunarity.max(1.0).powf(w.details)),
        ] {
            if s < 1e-3 && c.first.is_none() {
                c.fail(
                    &format!("{name}.details"),
                    "too many octaves",
                    "a finest lattice cell of at least 0.001 mm (scale_mm / lacunarity^details)",
                );
            }
        }
        // exp(β·m) must stay finite (SPEC §3 "Overlaps"): β × the deepest possible feature.
        let deepest = self.deepest_feature();
        if self.overlap.beta * deepest > crate::micro::overlap::MAX_BETA_TIMES_DEPTH
            && c.first.is_none()
        {
            c.fail(
                "overlap.beta",
                self.overlap.beta,
                &format!("at most {:.3} for these depths (β × the deepest feature, {deepest:.3}, must be ≤ 80)", 80.0 / deepest),
            );
        }
        c.first.map_or(Ok(()), Err)
    }

    /// The largest depth magnitude any pore or furrow can reach, height units.
    pub fn deepest_feature(&self) -> f32 {
        let p = &self.pores;
        let dmax = p.depth.mean + p.depth.spread;
        let alpha_min = (p.falloff.mean - p.falloff.spread).min(0.0);
        let pore = if p.enabled {
            match p.profile {
                PoreProfile::Gaussian => dmax * (-alpha_min).exp(),
                _ => dmax,
            }
        } else {
            0.0
        };
        let furrow = if self.furrows.enabled {
            self.furrows.depth.mean + self.furrows.depth.spread
        } else {
            0.0
        };
        pore.max(furrow)
    }

    /// The pore count after `density_per_cm2`.
    pub fn pore_count(&self) -> usize {
        if !self.pores.enabled {
            return 0;
        }
        match self.pores.density_per_cm2 {
            Some(d) => (d * self.map_size_mm * self.map_size_mm / 100.0).round() as usize,
            None => self.pores.count as usize,
        }
    }

    pub(crate) fn pore_stats(&self) -> PoreStats {
        PoreStats {
            radius_mm: self.pores.radius_mm.pair(),
            depth: self.pores.depth.pair(),
            falloff: self.pores.falloff.pair(),
        }
    }

    pub(crate) fn furrow_params(&self) -> FurrowParams {
        let f = &self.furrows;
        FurrowParams {
            links_per_pore: f.links_per_pore,
            max_count: f.max_count,
            depth: f.depth.pair(),
            width_mm: f.width_mm.pair(),
            direction_deg: f.direction_deg,
            direction_strength: f.direction_strength,
            taper: f.taper,
        }
    }

    pub(crate) fn noise_params(&self) -> FbmParams {
        let n = &self.noise;
        FbmParams {
            details: n.details,
            roughness: n.roughness,
            lacunarity: n.lacunarity,
            scale_mm: n.scale_mm,
        }
    }

    pub(crate) fn warp_params(&self) -> FbmParams {
        let w = &self.warp;
        FbmParams {
            details: w.details,
            roughness: w.roughness,
            lacunarity: w.lacunarity,
            scale_mm: w.scale_mm,
        }
    }
}

impl LargeSection {
    fn resolve_paths(&mut self, dir: &Path) {
        for p in self.wrinkles.iter_mut().chain(self.mask.as_mut()) {
            if p.is_relative() {
                *p = dir.join(&*p);
            }
        }
    }
}

/// Collects the first range violation.
#[derive(Default)]
struct Checker {
    first: Option<String>,
}

impl Checker {
    fn fail(&mut self, field: &str, value: impl std::fmt::Display, expected: &str) {
        if self.first.is_none() {
            self.first = Some(format!(
                "{field} = {value} is out of range: expected {expected}"
            ));
        }
    }

    fn range(&mut self, field: &str, v: f32, lo: f32, hi: f32) {
        if !(v >= lo && v <= hi) {
            self.fail(field, v, &format!("{lo}..={hi}"));
        }
    }

    fn mean_spread(&mut self, field: &str, v: MeanSpread, lo: f32, hi: f32, max_spread: f32) {
        self.range(&format!("{field}.mean"), v.mean, lo, hi);
        self.range(&format!("{field}.spread"), v.spread, 0.0, max_spread);
    }
}

/// The first field of `value` that `schema` (the default project as JSON) does not have,
/// named by its JSON path, with the fields that would be accepted there.
fn check_known_fields(
    value: &serde_json::Value,
    schema: &serde_json::Value,
    at: &str,
) -> Result<Option<String>, Error> {
    let (serde_json::Value::Object(v), serde_json::Value::Object(s)) = (value, schema) else {
        return Ok(None);
    };
    for (key, child) in v {
        let path = if at.is_empty() {
            key.clone()
        } else {
            format!("{at}.{key}")
        };
        match s.get(key) {
            None => {
                let known: Vec<&str> = s.keys().map(String::as_str).collect();
                return Ok(Some(format!(
                    "unknown field `{path}`; expected one of: {}",
                    known.join(", ")
                )));
            }
            Some(sub) => {
                if let Some(m) = check_known_fields(child, sub, &path)? {
                    return Ok(Some(m));
                }
            }
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_and_partial_files_load_with_defaults() {
        let p = Project::from_json_str("{}", "t").unwrap();
        assert_eq!(p, Project::default());
        let q = Project::from_json_str(
            r#"{"version": 1, "pores": {"count": 12, "radius_mm": {"mean": 0.5}}}"#,
            "t",
        )
        .unwrap();
        assert_eq!(q.pores.count, 12);
        assert_eq!(q.pores.radius_mm, MeanSpread::new(0.5, 0.0));
        assert_eq!(q.noise, NoiseSection::default());
    }

    #[test]
    fn round_trips_through_json() {
        let mut p = Project::default();
        p.pores.density_per_cm2 = Some(60.0);
        p.furrows.max_count = Some(500);
        p.large.mask = Some("m.png".into());
        let back = Project::from_json_str(&p.to_json_pretty(), "t").unwrap();
        assert_eq!(back, p);
    }

    #[test]
    fn unknown_fields_are_named_by_path() {
        let e = Project::from_json_str(r#"{"pores": {"cuont": 3}}"#, "x.agesim.json")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("x.agesim.json") && e.contains("`pores.cuont`") && e.contains("count"),
            "{e}"
        );
        let e = Project::from_json_str(r#"{"colour": 3}"#, "t")
            .unwrap_err()
            .to_string();
        assert!(e.contains("`colour`"), "{e}");
    }

    #[test]
    fn out_of_range_values_name_field_and_range() {
        let e = Project::from_json_str(r#"{"pores": {"radius_mm": {"mean": 1.5}}}"#, "t")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("pores.radius_mm.mean = 1.5") && e.contains("0..=1"),
            "{e}"
        );
        let e = Project::from_json_str(r#"{"version": 2}"#, "t")
            .unwrap_err()
            .to_string();
        assert!(e.contains("version = 2"), "{e}");
        let e = Project::from_json_str(
            r#"{"overlap": {"beta": 40}, "pores": {"depth": {"mean": 3}}}"#,
            "t",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("overlap.beta"), "{e}");
        let e = Project::from_json_str(r#"{"noise": {"details": "many"}}"#, "t")
            .unwrap_err()
            .to_string();
        assert!(e.contains("invalid type"), "{e}");
    }

    #[test]
    fn set_edits_by_path_with_the_same_validation() {
        let p = Project::default()
            .set("pores.count", "1000")
            .unwrap()
            .set("noise.details", "5.5")
            .unwrap();
        assert_eq!((p.pores.count, p.noise.details), (1000, 5.5));
        let p = p.set("pores.placement", "uniform").unwrap();
        assert_eq!(p.pores.placement, Placement::Uniform);
        let p = p
            .set("furrows.max_count", "500")
            .unwrap()
            .set("pores.radius_mm.mean", "0.2")
            .unwrap();
        assert_eq!(
            (p.furrows.max_count, p.pores.radius_mm.mean),
            (Some(500), 0.2)
        );
        let e = p.set("pores.radius_mm.mean", "7").unwrap_err().to_string();
        assert!(
            e.contains("--set pores.radius_mm.mean=7") && e.contains("0..=1"),
            "{e}"
        );
        let e = p.set("pores.size", "3").unwrap_err().to_string();
        assert!(e.contains("unknown field `pores.size`"), "{e}");
        assert!(p.set("seed.x", "3").is_err());
    }

    #[test]
    fn density_sets_the_count() {
        let p = Project::default()
            .set("pores.density_per_cm2", "40")
            .unwrap();
        // 50 mm × 50 mm = 25 cm² → 1000 pores
        assert_eq!(p.pore_count(), 1000);
    }
}
