//! The renderer's per-frame numbers from the engine's project and age factors: one place,
//! shared by the editor's 3D view and `agesim render`.

use agesim_core::age::AgeFactors;
use agesim_core::hair::GrayingRamp;
use agesim_core::project::{Colour, PomMode as ProjectPom, Project};
use agesim_render::{
    Camera, FrameParams, GrayingRampParam, HairShading, Light, PomMode, SkinParams,
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

/// The camera of the project's `view` section, around `target` (the head's centre).
pub fn camera(project: &Project, target: Vec3) -> Camera {
    let v = &project.view;
    Camera {
        yaw_rad: v.camera_yaw_deg.to_radians(),
        pitch_rad: v.camera_pitch_deg.to_radians(),
        distance: v.camera_distance_m / project.mesh.metres_per_unit.max(1e-9),
        target,
        fov_y_rad: v.fov_deg.to_radians(),
    }
}

/// Wrap lighting per channel: `wrap` scaled so 0.35 wraps the subsurface colour's
/// strongest channel by 0.45, the others in proportion to the colour (sRGB values; the
/// default #ff7d55 gives 0.45, 0.22, 0.15).
pub fn wrap_rgb(wrap: f32, subsurface: Colour) -> Vec3 {
    let c = Vec3::from(subsurface.0.map(f32::from)) / 255.0;
    let c = c / c.max_element().max(1e-6);
    (c * wrap * (0.45 / 0.35)).clamp(Vec3::ZERO, Vec3::ONE)
}

/// Everything but the camera, from the project and the age factors of the frame's age.
pub fn frame_params(project: &Project, factors: &AgeFactors, camera: Camera) -> FrameParams {
    let v = &project.view;
    let (ly, lp) = (v.light_yaw_deg.to_radians(), v.light_pitch_deg.to_radians());
    let h = &project.hair;
    let s = &project.skin;
    // Paling ([T] §3.1.1): the albedo moves toward the pale tone by amount × curve.
    let pale = s.pale_amount * factors.paleness;
    let albedo = linear(s.albedo).lerp(linear(s.pale_albedo), pale);
    FrameParams {
        camera,
        light: Light {
            direction: Vec3::new(lp.cos() * ly.sin(), lp.sin(), lp.cos() * ly.cos()),
            ..Light::default()
        },
        skin: SkinParams {
            pom_mode: pom_mode(v.pom),
            linear_steps: v.linear_steps,
            binary_steps: v.binary_steps,
            disp_scale: v.disp_scale,
            fine_blend: if project.fine.enabled {
                factors.fine_blend
            } else {
                0.0
            },
            // The albedo already carries the paling.
            paleness: 0.0,
            albedo,
            micro_relief: project.pores.enabled
                || project.furrows.enabled
                || project.noise.strength > 0.0,
            wrap: wrap_rgb(s.wrap, s.subsurface_colour),
            roughness: s.roughness,
            // The Fresnel reflectance of a dielectric, 0.08·specular (skin: 0.35 → 0.028).
            f0: 0.08 * s.specular,
        },
        hair: HairShading {
            enabled: h.enabled && v.show_hair,
            k_diff: h.k_diff,
            k_spec: h.k_spec,
            shininess: h.shininess,
            k_amb: h.k_amb,
            base_colour: linear(h.base_colour),
            gray_colour: linear(h.gray_colour),
            ramp: match h.graying_ramp {
                GrayingRamp::Linear => GrayingRampParam::Linear,
                GrayingRamp::Smoothstep => GrayingRampParam::Smoothstep,
            },
            length: h.length_mm / 1000.0 / project.mesh.metres_per_unit.max(1e-9),
            ..HairShading::default()
        },
        age: factors.t,
        wireframe: v.wireframe,
        ..FrameParams::default()
    }
}
