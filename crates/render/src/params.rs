//! Per-frame parameters: everything a frame needs that is not an uploaded asset. The
//! caller (the engine's age model, the editor's widgets, the command line) computes the
//! numbers; the renderer only takes them.

use glam::{Mat4, Vec3};

/// Physical side of the fine-wrinkle tile on the skin, metres. [T] gives only repeat
/// counts; 4 cm puts the default tile's creases (≈ 0.12 of the tile, docs/models.md §10) at ≈ 5 mm,
/// the length of crow's-feet and forehead fine lines.
pub const DEFAULT_FINE_TILE_SIZE_M: f32 = 0.04;

/// How the large wrinkles are drawn (docs/models.md §10).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PomMode {
    /// L linear steps, the first one below the surface.
    Linear,
    /// B halvings of the whole depth (misses nearer crossings, [T]).
    Binary,
    /// L linear steps, then B halvings around the crossing: POM proper.
    Combined,
    /// No offset: the large-wrinkle normal only.
    NormalOnly,
    /// The subdivided mesh displaced along its normals ([P] eq. 14), normals as above.
    Displacement,
}

impl PomMode {
    /// Every mode, in the order of the benchmark table.
    pub const ALL: [PomMode; 5] = [
        PomMode::Linear,
        PomMode::Binary,
        PomMode::Combined,
        PomMode::NormalOnly,
        PomMode::Displacement,
    ];

    /// The value of `Frame.pom.x` in the shaders.
    pub(crate) fn shader_code(self) -> u32 {
        match self {
            PomMode::Linear => 0,
            PomMode::Binary => 1,
            PomMode::Combined => 2,
            PomMode::NormalOnly => 3,
            PomMode::Displacement => 4,
        }
    }

    /// Short lower-case name (the command line's `--pom` values).
    pub fn name(self) -> &'static str {
        match self {
            PomMode::Linear => "linear",
            PomMode::Binary => "binary",
            PomMode::Combined => "combined",
            PomMode::NormalOnly => "normal",
            PomMode::Displacement => "displacement",
        }
    }
}

/// Orbit camera around `target` (docs/models.md §1 axes: +Y up, the face toward +Z).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Rotation around +Y, radians; 0 looks at the face from +Z, positive turns toward +X.
    pub yaw_rad: f32,
    /// Elevation, radians, clamped to ±1.55 (just short of the poles).
    pub pitch_rad: f32,
    /// Distance from the target, mesh units, > 0.
    pub distance: f32,
    /// The orbit centre, mesh units.
    pub target: Vec3,
    /// Vertical field of view, radians, clamped to [0.01, 3.0].
    pub fov_y_rad: f32,
}

impl Default for Camera {
    /// The default head (metres) seen from the front, face filling most of a frame.
    fn default() -> Self {
        Self {
            yaw_rad: 0.35,
            pitch_rad: 0.08,
            distance: 0.62,
            target: Vec3::new(0.0, 0.02, 0.0),
            fov_y_rad: 30f32.to_radians(),
        }
    }
}

impl Camera {
    /// Eye position, mesh units.
    pub fn eye(&self) -> Vec3 {
        let pitch = self.pitch_rad.clamp(-1.55, 1.55);
        let dir = Vec3::new(
            pitch.cos() * self.yaw_rad.sin(),
            pitch.sin(),
            pitch.cos() * self.yaw_rad.cos(),
        );
        self.target + dir * self.distance.max(1e-6)
    }

    /// Clip from world for a viewport of `aspect` = width / height; wgpu's depth range 0..1.
    pub fn clip_from_world(&self, aspect: f32) -> Mat4 {
        let d = self.distance.max(1e-6);
        // Near/far scaled with the distance keep depth precision for a 5 cm patch as for
        // a whole head.
        let proj = Mat4::perspective_rh(
            self.fov_y_rad.clamp(0.01, 3.0),
            aspect.max(1e-3),
            d * 0.02,
            d * 20.0,
        );
        let view = Mat4::look_at_rh(self.eye(), self.target, Vec3::Y);
        proj * view
    }
}

/// A key light, a fill light from the other side and a hemisphere ambient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Direction toward the light (world), normalised by the renderer.
    pub direction: Vec3,
    /// Light colour, linear RGB.
    pub colour: Vec3,
    /// Multiplier of `colour`, ≥ 0.
    pub intensity: f32,
    /// Ambient intensity, ≥ 0 (white, brighter from above).
    pub ambient: f32,
    /// Direction toward the fill light (world), normalised by the renderer.
    pub fill_direction: Vec3,
    /// The fill light's intensity as a fraction of the key's, 0–1 (diffuse only, no
    /// highlight: a large soft source).
    pub fill: f32,
    /// How far (mesh units) the skin looks toward the key light for what shadows it (the
    /// nose on the cheek, the brow over the lid, the jowl on the neck): traced through the
    /// stored surface, so only what is in view casts. 0: no shadows.
    pub shadow_reach: f32,
}

impl Default for Light {
    /// A key light from the upper right front.
    fn default() -> Self {
        Self {
            direction: Vec3::new(0.55, 0.6, 0.6),
            colour: Vec3::new(1.0, 0.97, 0.92),
            intensity: 1.5,
            ambient: 0.22,
            fill_direction: Vec3::new(-0.55, 0.1, 0.6),
            fill: 0.0,
            shadow_reach: 0.0,
        }
    }
}

/// Skin parameters of a frame (docs/models.md §10).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkinParams {
    /// How the large wrinkles are drawn.
    pub pom_mode: PomMode,
    /// L, linear search steps, 1..=256 ([T]: at least 8, more than binary).
    pub linear_steps: u32,
    /// B, binary search halvings, 0..=32 ([T]: at least 4).
    pub binary_steps: u32,
    /// dispScale: depth of the large-wrinkle height field in UV units ([T]: 0.005 at half
    /// intensity). Also the slope scale of the large-wrinkle normals, so the lit relief
    /// matches the marched one. ≥ 0.
    pub disp_scale: f32,
    /// Fine-wrinkle normal blend in [0, 1] (the age model's curve; docs/models.md §8).
    pub fine_blend: f32,
    /// Skin albedo, linear RGB in [0, 1], paling with age already applied by the caller.
    pub albedo: Vec3,
    /// The tone a head's colour map pales toward with age (linear RGB).
    pub pale_albedo: Vec3,
    /// How far a head's colour map pales toward `pale_albedo` at this age, 0–1 (the
    /// age's paling; `albedo` already has it).
    pub pale: f32,
    /// The head's normal map has its green pointing down (DirectX).
    pub head_normal_green_down: bool,
    /// Draw the micro-relief layer.
    pub micro_relief: bool,
    /// Where the micro-relief tile lies on the skin (its side, its normal strength).
    pub micro_tile: TilePlacement,
    /// Where the fine-wrinkle tile lies on the skin.
    pub fine_tile: TilePlacement,
    /// Wrap lighting per channel in [0, 1] (red scatters farthest under the skin, so its
    /// terminator wraps widest; GPU Gems 1 ch. 16).
    pub wrap: Vec3,
    /// Specular roughness (GGX α = roughness²), [0.05, 1].
    pub roughness: f32,
    /// Specular reflectance at normal incidence (skin ≈ 0.028).
    pub f0: f32,
}

impl Default for SkinParams {
    fn default() -> Self {
        Self {
            pom_mode: PomMode::Combined,
            linear_steps: 8,
            binary_steps: 4,
            disp_scale: 0.005,
            fine_blend: 0.5,
            albedo: Vec3::new(0.50, 0.30, 0.22),
            pale_albedo: Vec3::new(0.69, 0.48, 0.37),
            pale: 0.0,
            head_normal_green_down: false,
            wrap: Vec3::new(0.45, 0.27, 0.21),
            roughness: 0.42,
            f0: 0.028,
            micro_relief: true,
            micro_tile: TilePlacement {
                size_m: 0.05,
                strength: 0.002,
            },
            fine_tile: TilePlacement {
                size_m: DEFAULT_FINE_TILE_SIZE_M,
                strength: 0.0015,
            },
        }
    }
}

/// A repeated tile's physical side and normal strength: the tile repeats a whole number
/// of times across the mesh's UV square so that one tile covers about `size_m` of skin
/// ([`agesim_core::head::mesh::SurfaceScale::repeats`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TilePlacement {
    /// The tile's side on the skin, metres, > 0.
    pub size_m: f32,
    /// The normal strength s of docs/models.md §4 (tile UV units per height unit), ≥ 0.
    pub strength: f32,
}

/// Graying ramp of docs/models.md §9.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GrayingRampParam {
    /// y_k as is.
    #[default]
    Linear,
    /// 3y² − 2y³.
    Smoothstep,
}

/// Hair parameters of a frame (docs/models.md §9).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairShading {
    /// Draw the hair pass at all.
    pub enabled: bool,
    /// Kajiya–Kay K_diff, K_spec, shininess, K_amb.
    pub k_diff: f32,
    pub k_spec: f32,
    pub shininess: f32,
    pub k_amb: f32,
    /// Base and gray colours, linear RGB.
    pub base_colour: Vec3,
    pub gray_colour: Vec3,
    /// The brows' colour before graying, linear RGB.
    pub brow_colour: Vec3,
    /// Graying ramp.
    pub ramp: GrayingRampParam,
    /// Hair length, mesh units (each hair varies ±15 % by its random number), ≥ 0.
    pub length: f32,
    /// Ribbon width at the root, pixels, ≥ 0.
    pub width_px: f32,
    /// How wide a scalp hair is, mesh units, ≥ 0: a ribbon wider than the hair covers
    /// only the hair's share of it (docs/models.md §9 "Cover"); 0: all of it.
    pub diameter: f32,
    /// How wide a white brow hair is, mesh units, ≥ 0: a white hair lets the skin behind
    /// it show, covering only that share of its ribbon; 0: as a pigmented one.
    pub white_brow_width: f32,
    /// How far the hair bends from its growth direction down along the scalp, in [0, 1]
    /// (0: straight out; 1: combed flat after the first third).
    pub droop: f32,
    /// How curled the hair is, in [0, 1]: 0 straight (combed along the scalp), 1 tightly
    /// coiled (each hair a helix of two turns, a little over half as long seen whole,
    /// standing off the scalp every way, matte).
    pub curl: f32,
    /// How far the scalp under the hair present takes the hair's colour, in [0, 1] (the
    /// colour map's alpha holds each texel's hair disappearance age:
    /// `agesim_core::layers::skin_colour::hair_age_alpha`); 0 leaves the skin as it is.
    pub scalp_tint: f32,
    /// The hair's mean gray fraction at this age, in [0, 1]: the scalp's hair colour.
    pub gray_fraction: f32,
    /// Draw every [`SPARSE_HAIR_STRIDE`]-th of the hairs of the age instead of all: a
    /// lighter pass while the age plays or the view moves (on a CPU adapter the hair pass
    /// costs ≈ 2.6 ms per 1,000 hairs whatever the resolution). The same hairs, evenly
    /// thinned: every one drawn is one of count(t), in the same order, as a ribbon of
    /// half the quads.
    pub sparse: bool,
}

/// Of the hairs of an age, a sparse frame ([`HairShading::sparse`]) draws one in this many
/// (or fewer where the device's vertex stride limit is lower: `Renderer::sparse_hair_stride`).
pub const SPARSE_HAIR_STRIDE: u32 = 8;

impl Default for HairShading {
    fn default() -> Self {
        Self {
            enabled: true,
            k_diff: 0.7,
            k_spec: 0.35,
            shininess: 40.0,
            k_amb: 0.08,
            base_colour: Vec3::new(0.09, 0.05, 0.03),
            gray_colour: Vec3::new(0.32, 0.315, 0.30),
            brow_colour: Vec3::new(0.063, 0.035, 0.021),
            ramp: GrayingRampParam::Linear,
            length: 0.03,
            width_px: 0.9,
            diameter: 0.0,
            white_brow_width: 0.0,
            droop: 0.85,
            curl: 0.0,
            scalp_tint: 0.0,
            gray_fraction: 0.0,
            sparse: false,
        }
    }
}

/// What the skin pass writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FrameOutput {
    /// The lit, tone-mapped picture.
    #[default]
    Shaded,
    /// For tests and tools, on an `Rgba32Float` target: (u, v) where POM hit the height
    /// field, then (u, v) where the view ray met the polygon, unshaded.
    PomHit,
    /// For tests and tools, on an `Rgba32Float` target: the composed tangent-space normal
    /// (large and fine wrinkles, micro-relief) in xyz, unshaded; w = 1. What
    /// `agesim_core::output::compose` computes on the CPU for the exported normal map.
    TangentNormal,
}

/// Everything per frame in one struct.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameParams {
    pub camera: Camera,
    pub light: Light,
    pub skin: SkinParams,
    pub hair: HairShading,
    /// Age t in [0, 1] (docs/models.md §1): which hairs are drawn (count(t)) and how gray they are.
    pub age: f32,
    /// Background colour, linear RGB.
    pub background: Vec3,
    /// Draw the mesh's triangle edges over the skin (the undisplaced mesh).
    pub wireframe: bool,
    /// The picture, or the POM hit coordinates.
    pub output: FrameOutput,
}

impl Default for FrameParams {
    fn default() -> Self {
        Self {
            camera: Camera::default(),
            light: Light::default(),
            skin: SkinParams::default(),
            hair: HairShading::default(),
            age: 0.5,
            background: Vec3::new(0.035, 0.04, 0.05),
            wireframe: false,
            output: FrameOutput::Shaded,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orbit_camera_positions() {
        let mut c = Camera {
            yaw_rad: 0.0,
            pitch_rad: 0.0,
            distance: 2.0,
            target: Vec3::new(0.0, 1.0, 0.0),
            fov_y_rad: 1.0,
        };
        assert!(
            (c.eye() - Vec3::new(0.0, 1.0, 2.0)).length() < 1e-6,
            "front: {}",
            c.eye()
        );
        c.yaw_rad = std::f32::consts::FRAC_PI_2;
        assert!(
            (c.eye() - Vec3::new(2.0, 1.0, 0.0)).length() < 1e-5,
            "+x: {}",
            c.eye()
        );
        // The target projects to the centre of the frame, in front of the camera.
        let clip = c.clip_from_world(1.5) * c.target.extend(1.0);
        let ndc = clip.truncate() / clip.w;
        assert!(ndc.x.abs() < 1e-5 && ndc.y.abs() < 1e-5, "{ndc}");
        assert!((0.0..1.0).contains(&ndc.z), "depth {}", ndc.z);
        // Pitch is clamped short of the pole, so look_at never degenerates.
        c.pitch_rad = 10.0;
        assert!(c.clip_from_world(1.0).is_finite());
    }
}
