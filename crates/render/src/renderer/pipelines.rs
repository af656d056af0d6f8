//! The pipelines, bind group layouts, samplers and shader modules, made once by
//! [`Renderer::new`](super::Renderer::new).

use crate::hair::{
    BROW_ATTRIBUTES, BROW_STRIDE, INSTANCE_ATTRIBUTES, INSTANCE_STRIDE, SEGMENTS, SPARSE_SEGMENTS,
};
use crate::mesh::{VERTEX_ATTRIBUTES, Vertex};
use crate::params::SPARSE_HAIR_STRIDE;
use crate::shaders;
use crate::uniforms::FrameUniform;

use super::DEPTH_FORMAT;

/// The G-buffer's formats (skin.wgsl `SurfaceOut`): 32 bytes a pixel, wgpu's lowest
/// per-sample limit. UV in f32 (POM marches it), its derivatives and the frame in f16.
pub(super) const SURFACE_FORMATS: [wgpu::TextureFormat; 3] = [
    wgpu::TextureFormat::Rgba32Float,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba16Float,
];

/// What [`Pipelines::build`] makes (the renderer keeps each as a field of the same name).
pub(super) struct Pipelines {
    /// The skin passes' group 0: the frame uniform, the height layers, the samplers.
    pub(super) skin_layout: wgpu::BindGroupLayout,
    /// Rasterises the mesh into the surface targets (`fs_surface`).
    pub(super) surface_pipeline: wgpu::RenderPipeline,
    /// The shading pass's group 1: the stored surface.
    pub(super) surface_layout: wgpu::BindGroupLayout,
    /// Shades the stored surface in one full-screen triangle (`fs_shade`).
    pub(super) shade_pipeline: wgpu::RenderPipeline,
    /// Writes the stored surface's depth into the depth target (`fs_depth`).
    pub(super) depth_pipeline: wgpu::RenderPipeline,
    pub(super) wire_pipeline: wgpu::RenderPipeline,
    pub(super) hair_pipeline: wgpu::RenderPipeline,
    /// The hair pipeline reading every `sparse_hair_stride`-th instance (None where the
    /// device allows no wider stride than one instance).
    pub(super) sparse_hair_pipeline: Option<wgpu::RenderPipeline>,
    /// Draws the brow hairs (`vs_brow`: one quadratic curve per instance).
    pub(super) brow_pipeline: wgpu::RenderPipeline,
    /// [`SPARSE_HAIR_STRIDE`], or less where the device's vertex stride limit is lower.
    ///
    /// [`SPARSE_HAIR_STRIDE`]: crate::SPARSE_HAIR_STRIDE
    pub(super) sparse_hair_stride: u32,
    /// The hair pass's group 0: the frame uniform alone (one bind group per view).
    pub(super) hair_layout: wgpu::BindGroupLayout,
    pub(super) surface_sampler: wgpu::Sampler,
    pub(super) tile_sampler: wgpu::Sampler,
}

impl Pipelines {
    /// Builds the layouts, shader modules, pipelines and samplers for targets of
    /// `colour_format`.
    pub(super) fn build(device: &wgpu::Device, colour_format: wgpu::TextureFormat) -> Self {
        // A 2D float texture: the height maps (filtered, both stages) or the stored
        // surface (read texel by texel in the shading pass).
        let float_texture_entry =
            |binding: u32, visibility, filterable| wgpu::BindGroupLayoutEntry {
                binding,
                visibility,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            };
        let texture_entry =
            |binding: u32| float_texture_entry(binding, wgpu::ShaderStages::VERTEX_FRAGMENT, true);
        let sampler_entry = |binding: u32| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
            count: None,
        };
        let uniform_entry = wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<FrameUniform>() as u64),
            },
            count: None,
        };
        let skin_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("agesim skin bind group layout"),
            entries: &[
                uniform_entry,
                texture_entry(1),
                texture_entry(2),
                texture_entry(3),
                sampler_entry(4),
                sampler_entry(5),
                texture_entry(6),
                texture_entry(7),
                texture_entry(8),
            ],
        });
        let hair_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("agesim hair bind group layout"),
            entries: &[uniform_entry],
        });

        let depth_stencil = wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: wgpu::StencilState::default(),
            bias: wgpu::DepthBiasState::default(),
        };
        let colour_target = [Some(wgpu::ColorTargetState {
            format: colour_format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })];

        // A float target that cannot blend (the tests' Rgba32Float) draws opaque strands.
        let blendable = colour_format
            .guaranteed_format_features(device.features())
            .flags
            .contains(wgpu::TextureFormatFeatureFlags::BLENDABLE);
        let hair_target = [Some(wgpu::ColorTargetState {
            format: colour_format,
            blend: blendable.then_some(wgpu::BlendState::ALPHA_BLENDING),
            write_mask: wgpu::ColorWrites::COLOR,
        })];

        let skin_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("agesim skin.wgsl"),
            source: wgpu::ShaderSource::Wgsl(shaders::SKIN_WGSL.into()),
        });
        let skin_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("agesim skin pipeline layout"),
            bind_group_layouts: &[Some(&skin_layout)],
            immediate_size: 0,
        });
        // The mesh, and the shape of the view's age beside it (docs/models.md §13).
        let skin_vertex_buffers = [
            Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &VERTEX_ATTRIBUTES,
            }),
            Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<crate::mesh::ShapeVertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &crate::mesh::SHAPE_ATTRIBUTES,
            }),
        ];
        // The skin and the wireframe overlay share the vertex stage.
        let skin_vertex = wgpu::VertexState {
            module: &skin_module,
            entry_point: Some("vs_main"),
            buffers: &skin_vertex_buffers,
            compilation_options: wgpu::PipelineCompilationOptions::default(),
        };
        // The surface pass: both sides of every triangle (imported heads disagree on
        // winding; the ears and lips are seen from both sides), the depth test keeps
        // the nearest.
        let surface_targets = SURFACE_FORMATS.map(|format| {
            Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })
        });
        let surface_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("agesim skin surface pipeline"),
            layout: Some(&skin_pipeline_layout),
            vertex: skin_vertex.clone(),
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::TriangleList,
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(depth_stencil.clone()),
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &skin_module,
                entry_point: Some("fs_surface"),
                targets: &surface_targets,
                compilation_options: wgpu::PipelineCompilationOptions::default(),
            }),
            multiview_mask: None,
            cache: None,
        });
        let surface_entry =
            |binding: u32| float_texture_entry(binding, wgpu::ShaderStages::FRAGMENT, false);
        let surface_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("agesim stored surface bind group layout"),
            entries: &[surface_entry(0), surface_entry(1), surface_entry(2)],
        });
        let shade_pipeline_layout =
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("agesim skin shading pipeline layout"),
                bind_group_layouts: &[Some(&skin_layout), Some(&surface_layout)],
                immediate_size: 0,
            });
        let shade_pipeline = crate::blit::fullscreen_pipeline(
            device,
            "agesim skin shading pipeline",
            &shade_pipeline_layout,
            &skin_module,
            ("vs_fullscreen", "fs_shade"),
            colour_format,
            &[],
        );
        let depth_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("agesim skin depth pipeline"),
            layout: Some(&shade_pipeline_layout),
            vertex: wgpu::VertexState {
                module: &skin_module,
                entry_point: Some("vs_fullscreen"),
                buffers: &[],
                compilation_options: wgpu::PipelineCompilationOptions::default(),
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                depth_compare: Some(wgpu::CompareFunction::Always),
                ..depth_stencil.clone()
            }),
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &skin_module,
                entry_point: Some("fs_depth"),
                targets: &[],
                compilation_options: wgpu::PipelineCompilationOptions::default(),
            }),
            multiview_mask: None,
            cache: None,
        });

        let wire_pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("agesim wireframe pipeline"),
            layout: Some(&skin_pipeline_layout),
            vertex: skin_vertex.clone(),
            primitive: wgpu::PrimitiveState {
                topology: wgpu::PrimitiveTopology::LineList,
                ..Default::default()
            },
            // Over the skin it was drawn from: equal depth passes, nothing is written.
            depth_stencil: Some(wgpu::DepthStencilState {
                depth_write_enabled: Some(false),
                depth_compare: Some(wgpu::CompareFunction::LessEqual),
                ..depth_stencil.clone()
            }),
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &skin_module,
                entry_point: Some("fs_wire"),
                targets: &colour_target,
                compilation_options: wgpu::PipelineCompilationOptions::default(),
            }),
            multiview_mask: None,
            cache: None,
        });

        let hair_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("agesim hair.wgsl"),
            source: wgpu::ShaderSource::Wgsl(shaders::HAIR_WGSL.into()),
        });
        let hair_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("agesim hair pipeline layout"),
            bind_group_layouts: &[Some(&hair_layout)],
            immediate_size: 0,
        });
        // Two pipelines over the same instance buffer: every hair, and every
        // SPARSE_HAIR_STRIDE-th (a wider instance stride reads one record in that many)
        // as a ribbon of fewer quads.
        let hair_pipeline_with = |label: &str,
                                  entry: &str,
                                  stride: u64,
                                  attributes: &[wgpu::VertexAttribute],
                                  segments: u32| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&hair_pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &hair_module,
                    entry_point: Some(entry),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: stride,
                        step_mode: wgpu::VertexStepMode::Instance,
                        attributes,
                    })],
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants: &[("SEGMENTS", f64::from(segments))],
                        ..Default::default()
                    },
                },
                primitive: wgpu::PrimitiveState {
                    topology: wgpu::PrimitiveTopology::TriangleStrip,
                    cull_mode: None,
                    ..Default::default()
                },
                // Blended strands over the skin's depth, writing none: unsorted (hair of
                // one head is close to one colour, so the order shows little, and the
                // draw order is fixed, so it does not flicker), and a strand behind another
                // still adds its share. Opaque strands (a target that cannot blend) write
                // depth, so a nearer one is not overdrawn by a farther one.
                depth_stencil: Some(wgpu::DepthStencilState {
                    depth_write_enabled: Some(!blendable),
                    ..depth_stencil.clone()
                }),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &hair_module,
                    entry_point: Some("fs_main"),
                    targets: &hair_target,
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let hair_pipeline = hair_pipeline_with(
            "agesim hair pipeline",
            "vs_main",
            INSTANCE_STRIDE,
            &INSTANCE_ATTRIBUTES,
            SEGMENTS,
        );
        let brow_pipeline = hair_pipeline_with(
            "agesim brow pipeline",
            "vs_brow",
            BROW_STRIDE,
            &BROW_ATTRIBUTES,
            SEGMENTS,
        );
        // The device bounds the instance stride (WebGL2-level limits, as eframe asks for
        // on OpenGL, allow 255 bytes: one hair in 7 there).
        let sparse_hair_stride = (u64::from(device.limits().max_vertex_buffer_array_stride)
            / INSTANCE_STRIDE)
            .clamp(1, u64::from(SPARSE_HAIR_STRIDE)) as u32;
        let sparse_hair_pipeline = (sparse_hair_stride > 1).then(|| {
            hair_pipeline_with(
                "agesim sparse hair pipeline",
                "vs_main",
                INSTANCE_STRIDE * u64::from(sparse_hair_stride),
                &INSTANCE_ATTRIBUTES,
                SPARSE_SEGMENTS,
            )
        });

        let sampler = |label: &str, u: wgpu::AddressMode, v: wgpu::AddressMode| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some(label),
                address_mode_u: u,
                address_mode_v: v,
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                mipmap_filter: wgpu::MipmapFilterMode::Linear,
                ..Default::default()
            })
        };
        let surface_sampler = sampler(
            "agesim surface sampler (u wraps, v clamps)",
            wgpu::AddressMode::Repeat,
            wgpu::AddressMode::ClampToEdge,
        );
        let tile_sampler = sampler(
            "agesim tile sampler (wraps)",
            wgpu::AddressMode::Repeat,
            wgpu::AddressMode::Repeat,
        );
        Self {
            skin_layout,
            surface_pipeline,
            surface_layout,
            shade_pipeline,
            depth_pipeline,
            wire_pipeline,
            hair_pipeline,
            sparse_hair_pipeline,
            brow_pipeline,
            sparse_hair_stride,
            hair_layout,
            surface_sampler,
            tile_sampler,
        }
    }
}
