//! The GPU side of [`FrameParams`]: `struct Frame` of `shaders/skin.wgsl` and
//! `shaders/hair.wgsl`. Every member is a 16-byte vector so no implicit WGSL padding
//! exists to get wrong; `tests/uniforms.rs` checks the size naga computes.

use crate::params::{FrameOutput, FrameParams, GrayingRampParam};

/// `struct Frame` of the shaders (see the field comments there). 256 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniform {
    pub clip_from_world: [[f32; 4]; 4],
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
            camera_pos: [eye.x, eye.y, eye.z, if ctx.encode_srgb { 1.0 } else { 0.0 }],
            light_dir: v3(l, p.light.intensity.max(0.0)),
            light_colour: v3(p.light.colour, p.light.ambient.max(0.0)),
            skin_albedo: v3(s.albedo, s.paleness.clamp(0.0, 1.0)),
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
                s.disp_scale.max(0.0),
                // dispScale is depth in UV units; in mesh units through the UV density,
                // so POM and displaced geometry show the same relief.
                s.disp_scale.max(0.0) * ctx.mesh_units_per_uv,
                s.fine_blend.clamp(0.0, 1.0),
                p.age.clamp(0.0, 1.0),
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
            hair_base: v3(hr.base_colour, hr.length.max(0.0)),
            hair_gray: v3(hr.gray_colour, hr.width_px.max(0.0)),
            hair_k: [hr.k_diff, hr.k_spec, hr.shininess.max(0.0), hr.k_amb],
            hair_misc: [
                w as f32,
                hr.droop.clamp(0.0, 1.0),
                if p.output == FrameOutput::PomHit {
                    1.0
                } else {
                    0.0
                },
                0.0,
            ],
        }
    }
}
