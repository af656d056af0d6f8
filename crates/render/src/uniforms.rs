//! The GPU side of [`FrameParams`]: `struct Frame` of `shaders/frame.wgsl` (shared by the
//! skin and hair shaders). Every member is a 16-byte vector so no implicit WGSL padding
//! exists to get wrong; `tests/shaders.rs` compares [`FrameUniform::MEMBERS`] (every
//! member's name and offset) with the layout naga computes.

use crate::params::{FrameOutput, FrameParams, GrayingRampParam};

/// `struct Frame` of `shaders/frame.wgsl` (see the member comments there). 400 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniform {
    pub clip_from_world: [[f32; 4]; 4],
    pub world_from_clip: [[f32; 4]; 4],
    pub camera_pos: [f32; 4],
    pub light_dir: [f32; 4],
    pub light_colour: [f32; 4],
    pub skin_albedo: [f32; 4],
    pub pom: [u32; 4],
    pub disp: [f32; 4],
    pub tiling: [f32; 4],
    pub layers: [f32; 4],
    pub hair_base: [f32; 4],
    pub hair_gray: [f32; 4],
    pub hair_k: [f32; 4],
    pub hair_misc: [f32; 4],
    pub skin_wrap: [f32; 4],
    pub skin_spec: [f32; 4],
    pub scalp: [f32; 4],
    pub fill_dir: [f32; 4],
    pub shadow: [f32; 4],
    pub hair_brow: [f32; 4],
}

macro_rules! members {
    ($($name:ident),* $(,)?) => {
        &[$((stringify!($name), std::mem::offset_of!(FrameUniform, $name))),*]
    };
}

impl FrameUniform {
    /// Every member as (name, byte offset), in declaration order: what the WGSL struct
    /// must match member for member.
    pub const MEMBERS: &'static [(&'static str, usize)] = members!(
        clip_from_world,
        world_from_clip,
        camera_pos,
        light_dir,
        light_colour,
        skin_albedo,
        pom,
        disp,
        tiling,
        layers,
        hair_base,
        hair_gray,
        hair_k,
        hair_misc,
        skin_wrap,
        skin_spec,
        scalp,
        fill_dir,
        shadow,
        hair_brow,
    );
}

/// What the renderer knows beyond the frame parameters.
pub(crate) struct FrameContext {
    pub size_px: (u32, u32),
    /// The target is not an sRGB format, so the shader encodes.
    pub encode_srgb: bool,
    /// Micro-relief and fine-wrinkle tile repeats over the mesh UV.
    pub micro_repeats: [f32; 2],
    pub fine_repeats: [f32; 2],
    /// Strengths (tile UV per height unit) of the two tiles.
    pub micro_strength: f32,
    pub fine_strength: f32,
    /// Mesh units per UV unit (mean of u and v) of the uploaded mesh, for displacement.
    pub mesh_units_per_uv: f32,
    /// A colour map is bound: it replaces the skin albedo.
    pub colour_map: bool,
    /// A head normal map is bound: the layers are combined onto it.
    pub normal_map: bool,
    /// One scalp hair drawn in how many (a sparse frame's stride, else 1): each drawn
    /// hair covers for as many.
    pub hair_stride: u32,
}

/// Clamps to [0, 1]; NaN (which `clamp` keeps) becomes 0, so no NaN reaches the GPU.
fn unit(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

/// ≥ 0, NaN → 0 (`f32::max` already drops the NaN operand).
fn non_negative(x: f32) -> f32 {
    x.max(0.0)
}

impl FrameUniform {
    pub(crate) fn new(p: &FrameParams, ctx: &FrameContext) -> Self {
        let (w, h) = ctx.size_px;
        let clip = p.camera.clip_from_world(w as f32 / h.max(1) as f32);
        let eye = p.camera.eye();
        let l = p.light.direction.normalize_or(glam::Vec3::Y);
        let s = &p.skin;
        let hr = &p.hair;
        let v3 = |v: glam::Vec3, w: f32| [v.x, v.y, v.z, w];
        Self {
            clip_from_world: clip.to_cols_array_2d(),
            world_from_clip: clip.inverse().to_cols_array_2d(),
            camera_pos: [eye.x, eye.y, eye.z, if ctx.encode_srgb { 1.0 } else { 0.0 }],
            light_dir: v3(l, non_negative(p.light.intensity)),
            light_colour: v3(p.light.colour, non_negative(p.light.ambient)),
            skin_albedo: v3(s.albedo, unit(s.pale)),
            pom: [
                s.pom_mode.shader_code(),
                s.linear_steps.clamp(1, 256),
                s.binary_steps.min(32),
                match hr.ramp {
                    GrayingRampParam::Linear => 0,
                    GrayingRampParam::Smoothstep => 1,
                },
            ],
            disp: [
                non_negative(s.disp_scale),
                // dispScale is depth in UV units; in mesh units through the UV density,
                // so POM and displaced geometry show the same relief.
                non_negative(s.disp_scale) * ctx.mesh_units_per_uv,
                unit(s.fine_blend),
                unit(p.age),
            ],
            tiling: [
                ctx.micro_repeats[0],
                ctx.micro_repeats[1],
                ctx.fine_repeats[0],
                ctx.fine_repeats[1],
            ],
            layers: [
                ctx.micro_strength,
                ctx.fine_strength,
                if s.micro_relief { 1.0 } else { 0.0 },
                h as f32,
            ],
            hair_base: v3(hr.base_colour, non_negative(hr.length)),
            hair_gray: v3(hr.gray_colour, non_negative(hr.width_px)),
            hair_k: [hr.k_diff, hr.k_spec, non_negative(hr.shininess), hr.k_amb],
            hair_misc: [
                w as f32,
                unit(hr.droop),
                match p.output {
                    FrameOutput::Shaded => 0.0,
                    FrameOutput::PomHit => 1.0,
                    FrameOutput::TangentNormal => 2.0,
                },
                // Bits: 1 colour map, 2 head normal map, 4 its green points down.
                (u32::from(ctx.colour_map)
                    | u32::from(ctx.normal_map) << 1
                    | u32::from(s.head_normal_green_down) << 2) as f32,
            ],
            skin_wrap: [
                unit(s.wrap.x),
                unit(s.wrap.y),
                unit(s.wrap.z),
                s.roughness.clamp(0.05, 1.0),
            ],
            skin_spec: [
                unit(s.f0),
                unit(s.pale_albedo.x),
                unit(s.pale_albedo.y),
                unit(s.pale_albedo.z),
            ],
            scalp: [
                if hr.enabled { unit(hr.scalp_tint) } else { 0.0 },
                unit(hr.gray_fraction),
                // A sparse frame's hair covers for the hairs it leaves out.
                non_negative(hr.diameter) * ctx.hair_stride.max(1) as f32,
                non_negative(hr.white_brow_width),
            ],
            fill_dir: v3(
                p.light.fill_direction.normalize_or(glam::Vec3::Y),
                non_negative(p.light.intensity) * unit(p.light.fill),
            ),
            shadow: [
                non_negative(p.light.shadow_reach),
                // An occluder's thickness: a quarter of the reach (a nose, a brow, an ear
                // or a fold of the cheek, not the head behind them).
                0.25 * non_negative(p.light.shadow_reach),
                0.0,
                0.0,
            ],
            hair_brow: v3(hr.brow_colour, unit(hr.curl)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::PomMode;

    fn ctx() -> FrameContext {
        FrameContext {
            size_px: (200, 100),
            encode_srgb: false,
            micro_repeats: [12.0, 10.0],
            fine_repeats: [15.0, 12.0],
            micro_strength: 0.002,
            fine_strength: 0.0015,
            mesh_units_per_uv: 0.5,
            colour_map: false,
            normal_map: false,
            hair_stride: 1,
        }
    }

    #[test]
    fn nan_parameters_never_reach_the_gpu() {
        let mut p = FrameParams {
            age: f32::NAN,
            ..Default::default()
        };
        p.skin.fine_blend = f32::NAN;
        p.skin.disp_scale = f32::NAN;
        p.hair.droop = f32::NAN;
        p.hair.length = f32::NAN;
        let u = FrameUniform::new(&p, &ctx());
        let floats: &[f32] = bytemuck::cast_slice(std::slice::from_ref(&u));
        for (i, f) in floats.iter().enumerate() {
            // The `pom` member holds integers; reinterpreted they are small finite floats.
            assert!(f.is_finite(), "member float {i} is {f}");
        }
    }

    #[test]
    fn modes_steps_and_depth_reach_the_uniform() {
        let mut p = FrameParams::default();
        p.skin.pom_mode = PomMode::Binary;
        p.skin.linear_steps = 1000;
        p.skin.binary_steps = 5;
        p.skin.disp_scale = 0.01;
        let u = FrameUniform::new(&p, &ctx());
        assert_eq!(u.pom[..3], [1, 256, 5]);
        // Depth in mesh units = dispScale × mesh units per UV.
        assert!((u.disp[1] - 0.005).abs() < 1e-7, "{}", u.disp[1]);
        assert_eq!(u.hair_misc[0], 200.0);
        assert_eq!(u.layers[3], 100.0);
    }
}
