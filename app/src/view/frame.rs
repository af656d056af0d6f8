//! The renderer's per-frame numbers from a project at an age: the camera, the light, the
//! skin (relief mode, depth, fine blend, paling, tiles) and the hair.

use agesim_core::layers::hair::GrayingRamp;
use agesim_core::maps::normal_map::Convention;
use agesim_core::project::{Colour, PomMode as ProjectPom, Project};
use agesim_render::{
    Camera, FrameParams, GrayingRampParam, HairShading, Light, PomMode, SkinParams, TilePlacement,
};
use glam::Vec3;

fn linear(c: Colour) -> Vec3 {
    Vec3::from(c.linear())
}

/// The renderer's relief mode of the project's `view.pom`.
pub fn pom_mode(p: ProjectPom) -> PomMode {
    match p {
        ProjectPom::Linear => PomMode::Linear,
        ProjectPom::Binary => PomMode::Binary,
        ProjectPom::Combined => PomMode::Combined,
        ProjectPom::Normal => PomMode::NormalOnly,
        ProjectPom::Displacement => PomMode::Displacement,
    }
}

/// The camera of the project's `view` section, around `target` (the head's centre), for a
/// mesh of `metres_per_unit` ([`agesim_core::scene::Scene::metres_per_unit`]).
pub fn camera(project: &Project, metres_per_unit: f32, target: Vec3) -> Camera {
    let v = &project.view;
    Camera {
        yaw_rad: v.camera_yaw_deg.to_radians(),
        pitch_rad: v.camera_pitch_deg.to_radians(),
        distance: (v.camera_distance_m / metres_per_unit.max(1e-9)).max(1e-3),
        target,
        fov_y_rad: v.fov_deg.to_radians(),
    }
}

/// The fill light's elevation, radians.
const FILL_PITCH: f32 = 0.087;
/// How far the skin looks toward the key light for what shadows it, metres: farther than
/// the nose stands off the cheek.
const SHADOW_REACH_M: f32 = 0.04;

/// Wrap lighting per channel: `wrap` scaled so 0.35 wraps the subsurface colour's
/// strongest channel by 0.45, the others in proportion to the colour (sRGB values; the
/// default #ff9a78 gives 0.45, 0.27, 0.21).
pub fn wrap_rgb(wrap: f32, subsurface: Colour) -> Vec3 {
    let c = Vec3::from(subsurface.0.map(f32::from)) / 255.0;
    let c = c / c.max_element().max(1e-6);
    (c * wrap * (0.45 / 0.35)).clamp(Vec3::ZERO, Vec3::ONE)
}

/// [`wrap_rgb`] for skin of CIELAB lightness `skin_l`: melanin absorbs the red light that
/// scatters back out of a fold, so on dark skin the wrap is nearly the same for every
/// channel (a red-wrapped fold read, blind, as "red drawn-looking forehead lines" on a
/// dark-skinned head). Full at L* 60 and over, a third of the red's excess at L* 30.
pub fn wrap_for_skin(wrap: Vec3, skin_l: f32) -> Vec3 {
    let scatter = ((skin_l - 20.0) / 40.0).clamp(0.3, 1.0);
    Vec3::splat(wrap.z).lerp(wrap, scatter)
}

/// What a frame needs to know of the head beyond the project: its unit length, how
/// deep its UV units make the template's relief, and the person's hair and brows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadScale {
    /// Metres per mesh unit ([`agesim_core::scene::Scene::metres_per_unit`]).
    pub metres_per_unit: f32,
    /// The head's UV depth of one template UV unit of relief
    /// ([`agesim_core::scene::Scene::relief_scale`]; 1 for the template itself).
    pub relief_scale: f32,
    /// The person's hair and brow colours and graying delay
    /// ([`agesim_core::scene::Scene::person`]); `None`: the project's values, else the
    /// defaults.
    pub person: Option<agesim_core::scene::Person>,
}

impl HeadScale {
    /// A head in metres read at its own UVs (the built-in meshes).
    pub const METRES: Self = Self {
        metres_per_unit: 1.0,
        relief_scale: 1.0,
        person: None,
    };

    /// The scene's head.
    pub fn of(scene: &agesim_core::scene::Scene) -> Self {
        Self {
            metres_per_unit: scene.metres_per_unit(),
            relief_scale: scene.relief_scale(),
            person: Some(scene.person()),
        }
    }
}

/// The relief depth of a normalised large-wrinkle height of 1, UV units: `view.disp_scale`
/// (the depth the renderer gives the layer, in the template's UV units) × `large.depth`
/// (the layer's own depth; the baked map is normalised, so this is where the depth slider
/// acts) at the age `t` (deeper in old age: `Project::large_depth_at`) × the head's
/// `relief_scale` (the same millimetres in its own UV units).
pub fn relief_depth(project: &Project, head: HeadScale, t: f32) -> f32 {
    let years = project.age.mapping().years(t);
    project.view.disp_scale * project.large_depth_at(years) * head.relief_scale
}

/// Where the micro-relief tile and the fine-wrinkle tile lie on the skin.
pub fn tile_placements(project: &Project) -> (TilePlacement, TilePlacement) {
    (
        TilePlacement {
            size_m: project.map_size_mm * 1e-3,
            strength: project.normal.strength,
        },
        TilePlacement {
            size_m: project.fine.size_mm * 1e-3,
            strength: project.fine.strength,
        },
    )
}

/// The fine-wrinkle blend at age `t`: the `age.fine` curve, 0 when the layer is off.
pub fn fine_blend(project: &Project, t: f32) -> f32 {
    frame_params(project, HeadScale::METRES, t, Camera::default())
        .skin
        .fine_blend
}

/// Everything a frame of `project` (its mesh's `head` scale) at age `t` needs, seen
/// through `camera`. Every
/// age-dependent number comes from the project's age curves at `t` itself (not from the
/// last bake's factors), so the fine blend, the paling and the hair follow the age
/// slider at once while the maps catch up.
pub fn frame_params(project: &Project, head: HeadScale, t: f32, camera: Camera) -> FrameParams {
    let metres_per_unit = head.metres_per_unit;
    let v = &project.view;
    let (ly, lp) = (v.light_yaw_deg.to_radians(), v.light_pitch_deg.to_radians());
    let h = &project.hair;
    let s = &project.skin;
    let factors = project.age.factors(t, &[]);
    // Paling (docs/models.md "Age"): the albedo moves toward the pale tone by amount × curve.
    let pale = s.pale_amount * factors.paleness;
    let albedo = linear(s.albedo).lerp(linear(s.pale_albedo), pale);
    let (micro_tile, fine_tile) = tile_placements(project);
    let (hair, brows, graying_delay, skin_l, curl) = match head.person {
        Some(p) => (
            Vec3::from(p.hair),
            Vec3::from(p.brows),
            p.graying_delay_years,
            p.skin_l,
            p.curl,
        ),
        None => {
            let hair = linear(h.base_colour.unwrap_or(agesim_core::scene::FALLBACK_HAIR));
            let brows = h
                .brow_colour
                .map_or(hair * agesim_core::scene::BROW_DARKNESS, linear);
            let skin = agesim_core::base::lab::lab(linear(s.albedo));
            let curl = h.curl.unwrap_or_else(|| {
                agesim_core::layers::hair::guess_curl(agesim_core::base::lab::ita_degrees(skin))
            });
            (hair, brows, 0.0, skin.x, curl)
        }
    };
    let sheen =
        agesim_core::layers::skin_colour::aged_sheen(s.roughness, s.specular, factors.paleness);
    FrameParams {
        camera,
        light: Light {
            direction: Vec3::new(lp.cos() * ly.sin(), lp.sin(), lp.cos() * ly.cos()),
            // The key's mirror image across the face's midline, 5 degrees up.
            fill_direction: Vec3::new(
                -FILL_PITCH.cos() * ly.sin(),
                FILL_PITCH.sin(),
                FILL_PITCH.cos() * ly.cos(),
            ),
            fill: v.fill_light,
            shadow_reach: if v.shadows {
                SHADOW_REACH_M / metres_per_unit.max(1e-9)
            } else {
                0.0
            },
            ..Light::default()
        },
        skin: SkinParams {
            pom_mode: pom_mode(v.pom),
            linear_steps: v.linear_steps,
            binary_steps: v.binary_steps,
            disp_scale: relief_depth(project, head, t),
            fine_blend: if project.fine.enabled {
                factors.fine_blend
            } else {
                0.0
            },
            albedo,
            pale_albedo: linear(s.pale_albedo),
            // The colour map shown is the scene's aged colour (`Scene::bake_colour`),
            // paled already; `albedo` is paled for a frame drawn before it is baked.
            pale: 0.0,
            head_normal_green_down: project.mesh.normal_map_convention == Convention::DirectX,
            micro_relief: project.micro_enabled(),
            micro_tile,
            fine_tile,
            wrap: wrap_for_skin(wrap_rgb(s.wrap, s.subsurface_colour), skin_l),
            // Old skin is drier: less sheen (docs/models.md "Skin colour", "Sheen").
            roughness: sheen.0,
            // The Fresnel reflectance of a dielectric, 0.08·specular (skin: 0.35 → 0.028).
            f0: 0.08 * sheen.1,
        },
        hair: HairShading {
            enabled: h.enabled && v.show_hair,
            k_diff: h.k_diff,
            k_spec: h.k_spec,
            shininess: h.shininess,
            k_amb: h.k_amb,
            base_colour: hair,
            gray_colour: linear(h.gray_colour),
            brow_colour: brows,
            ramp: match h.graying_ramp {
                GrayingRamp::Linear => GrayingRampParam::Linear,
                GrayingRamp::Smoothstep => GrayingRampParam::Smoothstep,
            },
            length: h.length_mm / 1000.0 / metres_per_unit.max(1e-9),
            diameter: agesim_core::layers::hair::SCALP_HAIR_COVER_MM
                / 1000.0
                / metres_per_unit.max(1e-9),
            white_brow_width: agesim_core::layers::hair::WHITE_BROW_HAIR_COVER_MM
                / 1000.0
                / metres_per_unit.max(1e-9),
            curl,
            // The scalp's tint follows the hair left by thinning (docs/models.md §9).
            scalp_tint: h.scalp_tint
                * (1.0
                    - h.thinning
                        * ((factors.t - agesim_core::layers::hair::THINNING_FROM)
                            / (1.0 - agesim_core::layers::hair::THINNING_FROM))
                            .clamp(0.0, 1.0)),
            gray_fraction: project
                .colour_factors_with_delay(factors.t, graying_delay)
                .brow_gray,
            ..HairShading::default()
        },
        age: factors.t,
        wireframe: v.wireframe,
        ..FrameParams::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(project: &Project, t: f32) -> FrameParams {
        frame_params(project, HeadScale::METRES, t, Camera::default())
    }

    /// Noise with no octave bakes no tile (the scene's rule), so the renderer must not
    /// turn the layer on either: it would show the last tile baked before.
    #[test]
    fn micro_relief_is_off_when_only_noise_without_octaves_is_left() {
        let mut p = Project::default();
        p.pores.enabled = false;
        p.furrows.enabled = false;
        p.noise.details = 0.0;
        p.noise.strength = 0.5;
        assert!(!p.micro_enabled());
        assert!(!params(&p, 0.5).skin.micro_relief);
        p.noise.details = 2.0;
        assert!(params(&p, 0.5).skin.micro_relief);
    }

    /// The depth slider acts on the relief the renderer draws, with no bake.
    #[test]
    fn the_large_depth_scales_the_drawn_relief() {
        let mut p = Project::default();
        let base = params(&p, 0.5).skin.disp_scale;
        p.large.depth = 2.5;
        assert_eq!(params(&p, 0.5).skin.disp_scale, base * 2.5);
        p.large.depth = 0.0;
        assert_eq!(params(&p, 0.5).skin.disp_scale, 0.0);
    }

    /// Past 80 the wrinkles are drawn deeper (`age::wrinkle_depth_gain`): none up to the
    /// default range's old end, the whole gain at 90.
    #[test]
    fn old_age_draws_the_wrinkles_deeper() {
        let mut p = Project::default();
        let at_80 = params(&p, 1.0).skin.disp_scale;
        assert_eq!(params(&p, 0.9).skin.disp_scale, at_80 * 1.0);
        p.age.old_years = 90.0;
        let gain = agesim_core::age::WRINKLE_LATE_DEPTH;
        let at = |t: f32| params(&p, t).skin.disp_scale;
        assert!((at(1.0) / at_80 - gain).abs() < 1e-5, "{}", at(1.0) / at_80);
        assert!((at(65.0 / 70.0) / at_80 - 0.5 * (1.0 + gain)).abs() < 1e-5);
        assert_eq!(at(60.0 / 70.0), at_80);
    }

    /// Old skin is drier: the project's roughness and specular young, rougher and less
    /// specular old (docs/models.md "Skin colour", "Sheen").
    #[test]
    fn old_skin_has_less_sheen() {
        let p = Project::default();
        let (young, old) = (params(&p, 0.0), params(&p, 1.0));
        assert_eq!(young.skin.roughness, p.skin.roughness);
        assert_eq!(young.skin.f0, 0.08 * p.skin.specular);
        assert!(old.skin.roughness > young.skin.roughness + 0.1, "{old:?}");
        assert!(old.skin.f0 < 0.6 * young.skin.f0, "{old:?}");
    }

    /// The fine blend, the paling and the age follow `t` itself.
    #[test]
    fn fine_blend_and_paling_follow_the_age() {
        let mut p = Project::default();
        p.skin.pale_amount = 1.0;
        let (young, old) = (params(&p, 0.1), params(&p, 0.9));
        assert!(old.skin.fine_blend > young.skin.fine_blend, "{old:?}");
        assert_ne!(old.skin.albedo, young.skin.albedo);
        assert_eq!(old.age, 0.9);
        p.fine.enabled = false;
        assert_eq!(params(&p, 0.9).skin.fine_blend, 0.0);
    }
}
