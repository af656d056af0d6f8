//! The sections of the project file, one struct each, with their defaults (what each
//! field means, its unit and range: `fields::FIELDS` and `docs/project-file.md`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::age::{AgeCurve, AgeFactors, AgeMapping, CurveShape};
use crate::layers::hair::GrayingRamp;
use crate::layers::hair::transition::DistanceMetric;
use crate::maps::normal_map::Convention;

/// Where a head's landmarks come from (`mesh.landmarks`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum LandmarkSource {
    /// A landmark file ([`crate::head::landmarks::Landmarks::load`]).
    File(PathBuf),
    /// The points themselves, `{name: [x, y, z]}` in the mesh file's units (the names of
    /// [`crate::head::landmarks::NAMES`]).
    Points(BTreeMap<String, [f32; 3]>),
}

impl LandmarkSource {
    /// The landmark file, when the landmarks are in one.
    pub fn file(&self) -> Option<&Path> {
        match self {
            Self::File(p) => Some(p),
            Self::Points(_) => None,
        }
    }

    pub(crate) fn file_mut(&mut self) -> Option<&mut PathBuf> {
        match self {
            Self::File(p) => Some(p),
            Self::Points(_) => None,
        }
    }
}

impl From<PathBuf> for LandmarkSource {
    fn from(path: PathBuf) -> Self {
        Self::File(path)
    }
}

impl MeshSection {
    /// The landmark file the project names (`mesh.landmarks` as a path).
    pub fn landmark_file(&self) -> Option<&Path> {
        self.landmarks.as_ref().and_then(LandmarkSource::file)
    }
}

/// The head the maps are made for.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MeshSection {
    /// A mesh file (OBJ, glTF, GLB); `null` = the built-in mesh of `builtin`.
    pub path: Option<PathBuf>,
    /// The built-in mesh used when `path` is null.
    pub builtin: BuiltinMesh,
    /// Metres per mesh unit; `null` = measured from the mesh ([`crate::scene::Scene::units`]:
    /// 1 for the built-in meshes, a mesh file's from its landmarks or its size).
    pub metres_per_unit: Option<f32>,
    /// The head's landmarks ([`crate::head::landmarks`], in the mesh file's units): a landmark
    /// file, or the points themselves; `null` = none.
    pub landmarks: Option<LandmarkSource>,
    /// The mesh file's up axis; `auto` = from the landmarks, else +Y.
    pub up: AxisChoice,
    /// The mesh file's forward axis (where the face looks); `auto` = from the landmarks,
    /// else +Z.
    pub forward: AxisChoice,
    /// Where the layers (fibres, masks, hair) are read: on the template fitted to the
    /// head (`template`), or at the head's own UVs as if they were the template's
    /// (`own-uvs`).
    pub layout: Layout,
    /// The head's base colour map (any image; sRGB) over its own UVs; `null` = the
    /// skin colour (`skin.albedo`).
    pub colour_map: Option<PathBuf>,
    /// The head's tangent-space normal map over its own UVs; `null` = none. Our layers
    /// are combined onto it (reoriented normal mapping) in the view and the exports.
    pub normal_map: Option<PathBuf>,
    /// The normal map's green channel: up (`opengl`, glTF's) or down (`directx`).
    pub normal_map_convention: Convention,
    /// The parts (objects, materials) that are skin, by name (a part is skin when its
    /// name contains one of these, case-insensitive); `null` = by their names: all but
    /// eyes, teeth, tongue, lashes and brows.
    pub skin_parts: Option<Vec<String>>,
    /// Turn the colour and normal maps upside down (a head whose UVs use the other v
    /// convention than its pictures).
    pub maps_flip_v: bool,
}

/// How a head's UVs relate to the layout the layers are authored in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Layout {
    /// The template (the default head) fitted to the head by landmarks
    /// ([`crate::head::fit`]); a built-in mesh is read at its own UVs.
    #[default]
    Template,
    /// The head's own UVs, read as the template's layout.
    OwnUvs,
}

/// A mesh file's axis as the project names it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum AxisChoice {
    /// From the landmarks, else agesim's own (+Y up, +Z forward).
    #[default]
    #[serde(rename = "auto")]
    Auto,
    #[serde(rename = "+x")]
    PosX,
    #[serde(rename = "-x")]
    NegX,
    #[serde(rename = "+y")]
    PosY,
    #[serde(rename = "-y")]
    NegY,
    #[serde(rename = "+z")]
    PosZ,
    #[serde(rename = "-z")]
    NegZ,
}

impl AxisChoice {
    /// The axis named, `None` for `auto`.
    pub fn axis(self) -> Option<crate::head::mesh::units::Axis> {
        use crate::head::mesh::units::Axis;
        match self {
            Self::Auto => None,
            Self::PosX => Some(Axis::PosX),
            Self::NegX => Some(Axis::NegX),
            Self::PosY => Some(Axis::PosY),
            Self::NegY => Some(Axis::NegY),
            Self::PosZ => Some(Axis::PosZ),
            Self::NegZ => Some(Axis::NegZ),
        }
    }
}

/// The meshes that ship inside agesim.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BuiltinMesh {
    /// The default head (`assets/meshes/default-head.glb`).
    #[default]
    Head,
    /// The flat 5 cm skin patch.
    SkinPatch,
}

/// The fine-wrinkle tile (docs/models.md §10 "Fine wrinkles", [T] §5.2).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FineSection {
    pub enabled: bool,
    /// A tileable grey height image; `null` = generated from the parameters below.
    pub tile: Option<PathBuf>,
    /// Side of one tile on the skin, mm.
    pub size_mm: f32,
    /// Normal-map strength of the tile (UV of the tile per height unit).
    pub strength: f32,
    /// Resolution of the generated tile, px.
    pub size_px: u32,
    pub creases: u32,
    pub length: f32,
    pub width: f32,
    pub crossing_deg: f32,
    pub spread_deg: f32,
    pub seed: u64,
}

/// Hair recession and graying (docs/models.md §9).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HairSection {
    pub enabled: bool,
    /// Grey mask of the hair at t = 0; `null` = the default head's.
    pub outer_mask: Option<PathBuf>,
    /// Grey mask of the hair that remains at t = 1; `null` = the default head's.
    pub inner_mask: Option<PathBuf>,
    pub density_per_cm2: f32,
    pub metric: DistanceMetric,
    /// Transition-texture side, px; `null` = the masks' size.
    pub transition_size_px: Option<u32>,
    pub seed: u64,
    pub max_deviation_deg: f32,
    pub length_mm: f32,
    /// `null`: measured on the head ([`crate::scene::Scene::own_colours`]).
    pub base_colour: Option<Colour>,
    /// `null`: measured on the head, else the hair's, darker.
    pub brow_colour: Option<Colour>,
    /// `null`: guessed from the face ([`crate::layers::hair::HairLoss::guess`]).
    pub loss: Option<crate::layers::hair::HairLoss>,
    /// How curled the hair is, 0 (straight) to 1 (coily); `null`: guessed
    /// ([`crate::layers::hair::guess_curl`]).
    pub curl: Option<f32>,
    pub gray_colour: Colour,
    pub graying_onset_min_years: f32,
    pub graying_onset_max_years: f32,
    pub graying_ramp: GrayingRamp,
    /// The fraction of the hair lost to thinning by the old end, 0–1.
    pub thinning: f32,
    /// How far from the edge of its region the hair shortens (a barber's taper), mm.
    pub taper_mm: f32,
    /// How far the scalp under the hair takes the hair's colour in the 3D view, 0–1.
    pub scalp_tint: f32,
    /// Draw eyebrow hairs and eyelashes in the 3D view (docs/models.md §9 "Eyebrows",
    /// "Eyelashes"; a fitted head).
    pub brows: bool,
    pub k_diff: f32,
    pub k_spec: f32,
    pub shininess: f32,
    pub k_amb: f32,
}

/// Skin shading and paling with age ([T] §3.1.1).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SkinSection {
    pub albedo: Colour,
    /// The tone the albedo pales toward with age.
    pub pale_albedo: Colour,
    /// How far toward `pale_albedo` the skin goes at full paling, 0–1.
    pub pale_amount: f32,
    /// Age spots (solar lentigines) per cm² of sun-exposed skin at full age.
    pub spots_per_cm2: f32,
    /// How dark an age spot is, 0–1.
    pub spot_strength: f32,
    /// Mottled melanin on sun-exposed skin at full age, 0–1.
    pub mottle: f32,
    /// Redness and thread veins on the cheeks and nose at full age, 0–1.
    pub redness: f32,
    /// Yellowing at full paling, 0–1.
    pub yellowing: f32,
    /// How far lips and brows fade toward the skin at full age, 0–1.
    pub contrast_loss: f32,
    /// The shadow under the eyes (lower lid, tear trough) at full age, 0–1.
    pub under_eye: f32,
    /// Seed of the spots and the uneven tone.
    pub colour_seed: u64,
    pub subsurface_colour: Colour,
    /// Wrap-lighting amount (cheap subsurface scattering), 0–1.
    pub wrap: f32,
    pub roughness: f32,
    pub specular: f32,
}

/// The age: the current value, the years it stands for, and the curves of every layer.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AgeSection {
    /// The current age t ∈ [0, 1].
    pub t: f32,
    pub young_years: f32,
    pub old_years: f32,
    /// Large-wrinkle depth of fibres whose wrinkle file gives no `ageOnset`/`ageFull`.
    pub large: AgeCurve,
    /// Fine-wrinkle blend.
    pub fine: AgeCurve,
    /// Pore widening.
    pub pores: AgeCurve,
    /// Pore radius at the young end, relative to the project's radius.
    pub pores_young_scale: f32,
    /// Furrow deepening.
    pub furrows: AgeCurve,
    /// Furrow depth at the young end, relative to the project's depth.
    pub furrows_young_scale: f32,
    /// Skin paling and yellowing.
    pub pale: AgeCurve,
    /// Age spots appearing (each spot its own draw under this curve).
    pub spots: AgeCurve,
    /// Mottled melanin.
    pub mottle: AgeCurve,
    /// Redness and thread veins.
    pub redness: AgeCurve,
    /// Lips and brows fading toward the skin.
    pub contrast: AgeCurve,
}

/// How the head is shown (the renderer's settings, saved with the project).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ViewSection {
    pub pom: PomMode,
    pub linear_steps: u32,
    pub binary_steps: u32,
    /// POM depth of the full large-wrinkle height, in UV units (docs/models.md §10 dispScale).
    pub disp_scale: f32,
    pub light_yaw_deg: f32,
    pub light_pitch_deg: f32,
    /// The fill light, a fraction of the key light's intensity, 0–1: diffuse light from
    /// the key's mirror image across the face's midline, near eye level.
    pub fill_light: f32,
    /// The key light's contact shadows (the nose on the cheek, the brow over the lids).
    pub shadows: bool,
    pub camera_yaw_deg: f32,
    pub camera_pitch_deg: f32,
    /// Camera distance from the head's centre, m.
    pub camera_distance_m: f32,
    pub fov_deg: f32,
    pub show_hair: bool,
    /// Draw the mesh's triangle edges over the skin.
    pub wireframe: bool,
}

/// How the large-wrinkle relief is drawn (docs/models.md §10).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PomMode {
    /// Linear search only.
    Linear,
    /// Binary search only.
    Binary,
    /// Linear then binary ([T]'s POM).
    #[default]
    Combined,
    /// No parallax: the normal map only.
    Normal,
    /// A subdivided mesh displaced along its normals ([P] eq. 14).
    Displacement,
}

/// An sRGB colour written `"#rrggbb"`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Colour(pub [u8; 3]);

impl Colour {
    /// Parses `#rrggbb`.
    pub fn parse(s: &str) -> Option<Self> {
        let hex = s.strip_prefix('#')?;
        if hex.len() != 6 || !hex.is_ascii() {
            return None;
        }
        let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        Some(Self([byte(0)?, byte(2)?, byte(4)?]))
    }

    /// The colour in linear light, each channel in [0, 1] (the sRGB transfer undone).
    pub fn linear(self) -> [f32; 3] {
        self.0.map(|c| {
            let c = c as f32 / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        })
    }
}

impl std::fmt::Display for Colour {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [r, g, b] = self.0;
        write!(f, "#{r:02x}{g:02x}{b:02x}")
    }
}

impl Serialize for Colour {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl<'de> Deserialize<'de> for Colour {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        Colour::parse(&s)
            .ok_or_else(|| serde::de::Error::custom(format!("expected \"#rrggbb\", found {s:?}")))
    }
}

impl Default for MeshSection {
    fn default() -> Self {
        Self {
            path: None,
            builtin: BuiltinMesh::Head,
            metres_per_unit: None,
            landmarks: None,
            up: AxisChoice::Auto,
            forward: AxisChoice::Auto,
            layout: Layout::Template,
            colour_map: None,
            normal_map: None,
            normal_map_convention: Convention::OpenGl,
            skin_parts: None,
            maps_flip_v: false,
        }
    }
}

impl Default for FineSection {
    fn default() -> Self {
        let d = crate::layers::wrinkles::fine_wrinkles::DEFAULT_FINE_WRINKLES;
        Self {
            enabled: true,
            tile: None,
            size_mm: 20.0,
            strength: 0.004,
            size_px: 1024,
            creases: d.crease_count,
            length: d.length_tile,
            width: d.width_tile,
            crossing_deg: d.crossing_deg,
            spread_deg: d.spread_deg,
            seed: d.seed,
        }
    }
}

impl Default for HairSection {
    fn default() -> Self {
        Self {
            enabled: true,
            outer_mask: None,
            inner_mask: None,
            density_per_cm2: crate::layers::hair::DEFAULT_DENSITY_PER_CM2,
            metric: DistanceMetric::default(),
            transition_size_px: None,
            seed: 0,
            max_deviation_deg: crate::layers::hair::DEFAULT_MAX_DEVIATION_RAD.to_degrees(),
            length_mm: 16.0,
            base_colour: None,
            brow_colour: None,
            loss: None,
            curl: None,
            gray_colour: Colour([0xcc, 0xc6, 0xba]),
            graying_onset_min_years: 41.0,
            graying_onset_max_years: 91.0,
            graying_ramp: GrayingRamp::default(),
            thinning: crate::layers::hair::DEFAULT_THINNING,
            taper_mm: crate::layers::hair::DEFAULT_TAPER_MM,
            scalp_tint: 0.6,
            brows: true,
            k_diff: 0.7,
            k_spec: 0.35,
            shininess: 40.0,
            k_amb: 0.15,
        }
    }
}

impl Default for SkinSection {
    fn default() -> Self {
        Self {
            albedo: Colour([0xd8, 0xa0, 0x86]),
            // Duller and a little sallower rather than lighter: de Rigal et al. 2010
            // measured faces darkening and yellowing with age (docs/models.md "Age").
            pale_albedo: Colour([0xd9, 0xb8, 0xa4]),
            pale_amount: 0.25,
            spots_per_cm2: 0.6,
            spot_strength: 0.7,
            mottle: 0.3,
            redness: 0.5,
            yellowing: 0.6,
            contrast_loss: 0.7,
            under_eye: 0.65,
            colour_seed: 1,
            // With `wrap` 0.35: red wraps 0.45, green 0.27, blue 0.21 (docs/models.md
            // "Rendering"): red light scatters farthest under the skin. (#ff7d55, green
            // 0.22 and blue 0.15, drew the terminator on the neck and round the nape as
            // an orange-red band, read blind as "a reddish edge" under the fringe.)
            subsurface_colour: Colour([0xff, 0x9a, 0x78]),
            wrap: 0.35,
            // GGX roughness and F0 = 0.08 · specular = 0.028, d'Eon & Luebke's skin fit.
            roughness: 0.42,
            specular: 0.35,
        }
    }
}

impl Default for AgeSection {
    fn default() -> Self {
        Self {
            t: 0.5,
            young_years: crate::age::DEFAULT_YOUNG_YEARS,
            old_years: crate::age::DEFAULT_OLD_YEARS,
            large: AgeCurve::new(30.0, 65.0, CurveShape::Smoothstep),
            fine: AgeCurve::new(20.0, 80.0, CurveShape::Linear),
            pores: AgeCurve::new(25.0, 50.0, CurveShape::Smoothstep),
            pores_young_scale: 0.8,
            furrows: AgeCurve::new(25.0, 70.0, CurveShape::Smoothstep),
            furrows_young_scale: 0.5,
            pale: AgeCurve::new(40.0, 80.0, CurveShape::Linear),
            // docs/models.md "Skin colour": lentigines from about 50, most by 80.
            spots: AgeCurve::new(40.0, 85.0, CurveShape::Linear),
            mottle: AgeCurve::new(30.0, 80.0, CurveShape::Smoothstep),
            redness: AgeCurve::new(35.0, 80.0, CurveShape::Smoothstep),
            contrast: AgeCurve::new(35.0, 80.0, CurveShape::Linear),
        }
    }
}

impl Default for ViewSection {
    fn default() -> Self {
        Self {
            pom: PomMode::Combined,
            linear_steps: 8,
            binary_steps: 4,
            disp_scale: 0.0035,
            light_yaw_deg: 35.0,
            light_pitch_deg: 30.0,
            // A portrait's key-to-fill ratio of about 4:1 (with the ambient): without it
            // the side away from the light lost its folds and its hair against the
            // background (blind: "the fringe shows on one side only").
            fill_light: 0.25,
            shadows: true,
            camera_yaw_deg: 20.0,
            camera_pitch_deg: 5.0,
            camera_distance_m: 0.9,
            fov_deg: 30.0,
            show_hair: true,
            wireframe: false,
        }
    }
}

impl AgeSection {
    /// The age mapping of this section.
    pub fn mapping(&self) -> AgeMapping {
        AgeMapping {
            young_years: self.young_years,
            old_years: self.old_years,
        }
    }

    /// The factors of every layer at age `t` (clamped to [0, 1]). `fibre_curves` holds each
    /// large-wrinkle fibre's own curve, or `None` for the layer default `large`.
    pub fn factors(&self, t: f32, fibre_curves: &[Option<AgeCurve>]) -> AgeFactors {
        let t = t.clamp(0.0, 1.0);
        let years = self.mapping().years(t);
        AgeFactors {
            t,
            years,
            large: fibre_curves
                .iter()
                .map(|c| crate::age::wrinkle_factor(&c.unwrap_or(self.large), years))
                .collect(),
            fine_blend: self.fine.factor(years),
            pore_radius_scale: crate::age::scale(self.pores_young_scale, self.pores.factor(years)),
            furrow_depth_scale: crate::age::scale(
                self.furrows_young_scale,
                self.furrows.factor(years),
            ),
            paleness: self.pale.factor(years),
        }
    }
}

/// Age changes the shape (docs/models.md §13): the regions' strengths.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ShapeSection {
    pub enabled: bool,
    /// Every region's millimetres times this, 0–3.
    pub strength: f32,
    /// Brow descent: a multiplier of its millimetres, 0–3.
    pub brows: f32,
    /// Upper lids hooding: a multiplier of its millimetres, 0–3.
    pub lids: f32,
    /// Bags under the eyes: a multiplier of its millimetres, 0–3.
    pub bags: f32,
    /// Tear trough hollowing: a multiplier of its millimetres, 0–3.
    pub tear_trough: f32,
    /// Temples hollowing: a multiplier of its millimetres, 0–3.
    pub temples: f32,
    /// Cheeks descending over the nasolabial fold: a multiplier of its millimetres, 0–3.
    pub cheeks: f32,
    /// Jowls below the jaw line: a multiplier of its millimetres, 0–3.
    pub jowls: f32,
    /// Upper lip lengthening: a multiplier of its millimetres, 0–3.
    pub lips: f32,
    /// Nose tip drooping: a multiplier of its millimetres, 0–3.
    pub nose: f32,
    /// Earlobes lengthening: a multiplier of its millimetres, 0–3.
    pub ears: f32,
    /// Submental laxity: a multiplier of its millimetres, 0–3.
    pub neck: f32,
}

impl Default for ShapeSection {
    fn default() -> Self {
        Self {
            enabled: true,
            strength: 1.0,
            brows: 1.0,
            lids: 1.0,
            bags: 1.0,
            tear_trough: 1.0,
            temples: 1.0,
            cheeks: 1.0,
            jowls: 1.0,
            lips: 1.0,
            nose: 1.0,
            ears: 1.0,
            neck: 1.0,
        }
    }
}

impl ShapeSection {
    /// Each region's strength (its own times the overall), in `shape::REGIONS` order; all
    /// 0 when the layer is off.
    pub fn strengths(&self) -> [f32; crate::layers::shape::REGIONS.len()] {
        let on = if self.enabled { self.strength } else { 0.0 };
        [
            self.brows,
            self.lids,
            self.bags,
            self.tear_trough,
            self.temples,
            self.cheeks,
            self.jowls,
            self.lips,
            self.nose,
            self.ears,
            self.neck,
        ]
        .map(|s| s * on)
    }
}
