//! The long-lived renderer: pipelines, layouts and samplers made once; assets uploaded
//! on request; per frame a skin shading pass and one instanced hair pass into its own
//! colour + depth targets (issue 11 §1; the editor composites the colour target,
//! EGUI-0.37.md).
//!
//! The skin is drawn in two steps. The *surface pass* rasterises the mesh into a small
//! G-buffer: per pixel the UV, its derivatives, the geometric frame and the depth
//! (`fs_surface` in skin.wgsl). The *shading pass* runs the skin shader once per covered
//! pixel from it (`fs_shade`), the eye direction coming from the pixel's view ray; a depth
//! pass (`fs_depth`) restores the skin's depth for the hair and the wireframe. The surface pass runs only when what it stores
//! changes (the camera, the size, the mesh, displacement): an age step or a re-baked map
//! is one full-screen pass, whatever the mesh's triangle count. On a CPU rasteriser the
//! head's 128k triangles cost more than shading the pixels they cover.

use agesim_core::hair::{AgeLevel, HairInstances};
use agesim_core::{HeightMap, Mask, Mesh};
use wgpu::util::DeviceExt as _;

use crate::RenderError;
use crate::f16::to_f16_bytes;
use crate::hair::{
    INSTANCE_ATTRIBUTES, INSTANCE_STRIDE, SEGMENTS, SPARSE_SEGMENTS, count_at, vertices_per_hair,
};
use crate::mesh::{MeshData, SurfaceScale, VERTEX_ATTRIBUTES, Vertex, subdivide};
use crate::params::{DEFAULT_FINE_TILE_SIZE_M, FrameParams, PomMode, SPARSE_HAIR_STRIDE};
use crate::shaders;
use crate::uniforms::{FrameContext, FrameUniform};

/// The colour format of headless renders ([`Renderer::render_to_image`]): 8-bit sRGB,
/// so the hardware encodes and blending would happen in linear light.
pub const COLOUR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// The depth target's format.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Which tile an upload replaces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TileLayer {
    /// Skin micro-relief ([P], SPEC §3).
    Micro,
    /// Fine wrinkles ([T] §5.2, SPEC §5).
    Fine,
}

/// A prepared layer and where it goes ([`Renderer::upload_prepared`]).
#[derive(Clone, Copy, Debug)]
pub enum Upload<'a> {
    /// The large-wrinkle heights ([`PreparedLayer::large_wrinkles`]).
    LargeWrinkles(&'a PreparedLayer),
    /// A tile ([`PreparedLayer::tile`]) with its side on the skin (m) and its normal
    /// strength, as [`Renderer::upload_tile`] takes them.
    Tile {
        layer: TileLayer,
        tile: &'a PreparedLayer,
        size_m: f32,
        strength: f32,
    },
}

/// A height or mask texture (the view keeps its texture alive).
struct Layer {
    view: wgpu::TextureView,
}

/// A tileable layer's physical size and normal strength.
#[derive(Clone, Copy)]
struct TileInfo {
    size_m: f32,
    strength: f32,
}

struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
}

/// The unique edges of a triangle list as a line list (each edge once).
fn edge_indices(indices: &[u32]) -> Vec<u32> {
    let mut edges: Vec<(u32, u32)> = indices
        .chunks_exact(3)
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges.into_iter().flat_map(|(a, b)| [a, b]).collect()
}

struct Targets {
    size_px: (u32, u32),
    colour: wgpu::Texture,
    colour_view: wgpu::TextureView,
    /// The surface pass's G-buffer ([`SURFACE_FORMATS`], skin.wgsl `SurfaceOut`).
    surface_views: [wgpu::TextureView; 3],
    /// The shading pass's group 1: the surface targets.
    surface_bind_group: wgpu::BindGroup,
    /// The surface pass's depth test.
    surface_depth_view: wgpu::TextureView,
    /// The skin's depth restored from the stored surface each frame (`fs_depth`), which
    /// the hair and the wireframe test and write.
    depth_view: wgpu::TextureView,
}

/// The G-buffer's formats (skin.wgsl `SurfaceOut`): 32 bytes a pixel, wgpu's lowest
/// per-sample limit. UV in f32 (POM marches it), its derivatives and the frame in f16.
const SURFACE_FORMATS: [wgpu::TextureFormat; 3] = [
    wgpu::TextureFormat::Rgba32Float,
    wgpu::TextureFormat::Rgba16Float,
    wgpu::TextureFormat::Rgba16Float,
];

/// What the stored surface depends on: the camera, the targets and the mesh (a
/// generation bumped when either is replaced), and when displacing, the depth and the
/// large-wrinkle map that move the vertices.
#[derive(Clone, Copy, PartialEq)]
struct SurfaceKey {
    clip_from_world: [[f32; 4]; 4],
    camera_pos: [f32; 4],
    generation: u64,
    /// (displacement depth, large-map generation) in displacement mode.
    displacement: Option<(f32, u64)>,
}

struct Hair {
    instances: wgpu::Buffer,
    levels: Vec<AgeLevel>,
}

/// The renderer. Create once per device; see the crate docs for the call order.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    colour_format: wgpu::TextureFormat,
    wire_pipeline: wgpu::RenderPipeline,
    /// The uploaded mesh's edges (line list), for the wireframe overlay.
    wire_edges: Option<(wgpu::Buffer, u32)>,
    frame_buffer: wgpu::Buffer,
    skin_layout: wgpu::BindGroupLayout,
    /// Rasterises the mesh into the surface targets (`fs_surface`).
    surface_pipeline: wgpu::RenderPipeline,
    surface_layout: wgpu::BindGroupLayout,
    /// Shades the stored surface in one full-screen triangle (`fs_shade`).
    shade_pipeline: wgpu::RenderPipeline,
    /// Writes the stored surface's depth into the depth target (`fs_depth`).
    depth_pipeline: wgpu::RenderPipeline,
    /// What the surface targets hold (None: nothing yet, or stale).
    surface_key: Option<SurfaceKey>,
    /// Bumped when the targets or the mesh are replaced (see [`SurfaceKey`]).
    surface_generation: u64,
    /// Bumped on every large-wrinkle upload (displacement moves the surface with it).
    large_generation: u64,
    /// Surface passes run so far ([`Renderer::surface_passes`]).
    surface_passes: u64,
    hair_pipeline: wgpu::RenderPipeline,
    /// The hair pipeline reading every `sparse_hair_stride`-th instance (None where the
    /// device allows no wider stride than one instance).
    sparse_hair_pipeline: Option<wgpu::RenderPipeline>,
    /// [`SPARSE_HAIR_STRIDE`], or less where the device's vertex stride limit is lower.
    sparse_hair_stride: u32,
    hair_bind_group: wgpu::BindGroup,
    surface_sampler: wgpu::Sampler,
    tile_sampler: wgpu::Sampler,
    large: Layer,
    micro: Layer,
    fine: Layer,
    mask: Layer,
    micro_info: TileInfo,
    fine_info: TileInfo,
    /// Rebuilt lazily when a texture is replaced.
    skin_bind_group: Option<wgpu::BindGroup>,
    mesh: Option<GpuMesh>,
    /// The subdivided copy, made on the first displacement frame (4× the triangles:
    /// editors that never use the mode never pay for it).
    displaced_mesh: Option<GpuMesh>,
    /// The uploaded mesh kept on the CPU until it is subdivided.
    mesh_to_subdivide: Option<MeshData>,
    surface_scale: SurfaceScale,
    metres_per_unit: f32,
    hair: Option<Hair>,
    targets: Option<Targets>,
    /// Bumped whenever the targets are recreated (see [`Renderer::target_generation`]).
    target_generation: u64,
}

impl Renderer {
    /// Builds pipelines, layouts, samplers and placeholder layers (flat heights, full
    /// mask) for targets of `colour_format`. An sRGB format gets linear output encoded
    /// by the hardware; `Rgba8Unorm`/`Bgra8Unorm` get sRGB-encoded values from the
    /// shader; float formats get linear values.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        colour_format: wgpu::TextureFormat,
    ) -> Result<Self, RenderError> {
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let frame_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("agesim frame uniform"),
            size: std::mem::size_of::<FrameUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
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
                texture_entry(4),
                sampler_entry(5),
                sampler_entry(6),
            ],
        });
        let hair_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("agesim hair bind group layout"),
            entries: &[uniform_entry],
        });
        let hair_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("agesim hair bind group"),
            layout: &hair_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buffer.as_entire_binding(),
            }],
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

        let skin_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("agesim skin.wgsl"),
            source: wgpu::ShaderSource::Wgsl(shaders::SKIN_WGSL.into()),
        });
        let skin_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("agesim skin pipeline layout"),
            bind_group_layouts: &[Some(&skin_layout)],
            immediate_size: 0,
        });
        let skin_vertex_buffers = [Some(wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &VERTEX_ATTRIBUTES,
        })];
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
        let hair_pipeline_with = |label: &str, stride: u64, segments: u32| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&hair_pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &hair_module,
                    entry_point: Some("vs_main"),
                    buffers: &[Some(wgpu::VertexBufferLayout {
                        array_stride: stride,
                        step_mode: wgpu::VertexStepMode::Instance,
                        attributes: &INSTANCE_ATTRIBUTES,
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
                depth_stencil: Some(depth_stencil.clone()),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &hair_module,
                    entry_point: Some("fs_main"),
                    targets: &colour_target,
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let hair_pipeline = hair_pipeline_with("agesim hair pipeline", INSTANCE_STRIDE, SEGMENTS);
        // The device bounds the instance stride (WebGL2-level limits, as eframe asks for
        // on OpenGL, allow 255 bytes: one hair in 7 there).
        let sparse_hair_stride = (u64::from(device.limits().max_vertex_buffer_array_stride)
            / INSTANCE_STRIDE)
            .clamp(1, u64::from(SPARSE_HAIR_STRIDE)) as u32;
        let sparse_hair_pipeline = (sparse_hair_stride > 1).then(|| {
            hair_pipeline_with(
                "agesim sparse hair pipeline",
                INSTANCE_STRIDE * u64::from(sparse_hair_stride),
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

        let flat = |label: &str, value: f32| {
            create_r16f(device, queue, label, &prepare_r16f((1, 1), &[value], false))
        };
        let large = flat("agesim large-wrinkle heights (placeholder)", 1.0);
        let micro = flat("agesim micro-relief tile (placeholder)", 0.0);
        let fine = flat("agesim fine-wrinkle tile (placeholder)", 0.0);
        let mask = flat("agesim wrinkle mask (placeholder)", 1.0);

        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(RenderError::Gpu(err.to_string()));
        }
        Ok(Self {
            device: device.clone(),
            queue: queue.clone(),
            colour_format,
            frame_buffer,
            skin_layout,
            surface_pipeline,
            surface_layout,
            shade_pipeline,
            depth_pipeline,
            surface_key: None,
            surface_generation: 0,
            large_generation: 0,
            surface_passes: 0,
            hair_pipeline,
            sparse_hair_pipeline,
            sparse_hair_stride,
            wire_pipeline,
            wire_edges: None,
            hair_bind_group,
            surface_sampler,
            tile_sampler,
            large,
            micro,
            fine,
            mask,
            micro_info: TileInfo {
                size_m: agesim_core::project::DEFAULT_MAP_SIZE_MM * 1e-3,
                strength: 0.0,
            },
            fine_info: TileInfo {
                size_m: DEFAULT_FINE_TILE_SIZE_M,
                strength: 0.0,
            },
            skin_bind_group: None,
            mesh: None,
            displaced_mesh: None,
            mesh_to_subdivide: None,
            surface_scale: SurfaceScale {
                units_per_u: 1.0,
                units_per_v: 1.0,
            },
            metres_per_unit: 1.0,
            hair: None,
            targets: None,
            target_generation: 0,
        })
    }

    /// The colour format the pipelines were built for.
    pub fn colour_format(&self) -> wgpu::TextureFormat {
        self.colour_format
    }

    /// Uploads the head (positions, normals, UVs, tangents with sign; SPEC §0, §4) —
    /// its once-subdivided copy for [`PomMode::Displacement`] follows on the first frame
    /// in that mode — and measures its UV density so the tiles appear at their physical
    /// size. `metres_per_unit` is the mesh's unit length
    /// (1 for the default head), > 0.
    pub fn upload_mesh(&mut self, mesh: &Mesh, metres_per_unit: f32) -> Result<(), RenderError> {
        if !(metres_per_unit.is_finite() && metres_per_unit > 0.0) {
            return Err(RenderError::OutOfRange {
                what: "metres per unit",
                value: metres_per_unit,
                range: "(0, ∞)",
            });
        }
        if mesh.indices().is_empty() || mesh.tangents().len() != mesh.vertex_count() {
            return Err(RenderError::InvalidMesh(format!(
                "{} triangles, {} vertices, {} tangents",
                mesh.triangle_count(),
                mesh.vertex_count(),
                mesh.tangents().len()
            )));
        }
        let scale = SurfaceScale::measure(mesh.positions(), mesh.uvs(), mesh.indices())
            .ok_or_else(|| RenderError::InvalidMesh("every triangle has degenerate UVs".into()))?;
        let data = MeshData::from_mesh(mesh);
        self.mesh = Some(self.create_mesh("agesim mesh", &data));
        let edges = edge_indices(mesh.indices());
        self.wire_edges = Some((
            self.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("agesim mesh edges"),
                    contents: bytemuck::cast_slice(&edges),
                    usage: wgpu::BufferUsages::INDEX,
                }),
            edges.len() as u32,
        ));
        self.displaced_mesh = None;
        self.mesh_to_subdivide = Some(data);
        self.surface_generation += 1;
        self.surface_scale = scale;
        self.metres_per_unit = metres_per_unit;
        Ok(())
    }

    /// The uploaded mesh's measured UV density (mesh units per UV unit).
    pub fn surface_scale(&self) -> SurfaceScale {
        self.surface_scale
    }

    fn create_mesh(&self, label: &str, data: &MeshData) -> GpuMesh {
        let vertices = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{label} vertices")),
                contents: bytemuck::cast_slice(&data.vertices),
                usage: wgpu::BufferUsages::VERTEX,
            });
        let indices = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("{label} indices")),
                contents: bytemuck::cast_slice(&data.indices),
                usage: wgpu::BufferUsages::INDEX,
            });
        GpuMesh {
            vertices,
            indices,
            index_count: data.indices.len() as u32,
        }
    }

    /// Uploads the large-wrinkle heights over the mesh UV (SPEC §1, §5), normalised to
    /// [0, 1] (values outside are clamped): 1 = the polygon's surface (wrinkle crest),
    /// 0 = `disp_scale` below it. Stored as f16 heights only; the normals are derived in
    /// the shader with the frame's `disp_scale`, so the lit relief always matches the
    /// marched and the displaced one, at any age scaling of the heights.
    pub fn upload_large_wrinkles(&mut self, heights01: &HeightMap) -> Result<(), RenderError> {
        self.upload_prepared(&Upload::LargeWrinkles(&PreparedLayer::large_wrinkles(
            heights01,
        )))
    }

    /// Uploads a layer prepared on another thread (the editor's worker converts to f16
    /// and builds mips there, so the drawing thread only copies bytes).
    pub fn upload_prepared(&mut self, upload: &Upload<'_>) -> Result<(), RenderError> {
        match *upload {
            Upload::LargeWrinkles(layer) => {
                self.large = self.create_layer("agesim large-wrinkle heights", layer)?;
                self.large_generation += 1;
            }
            Upload::Tile {
                layer,
                tile,
                size_m,
                strength,
            } => {
                if !(size_m.is_finite() && size_m > 0.0) {
                    return Err(RenderError::OutOfRange {
                        what: "tile size (m)",
                        value: size_m,
                        range: "(0, ∞)",
                    });
                }
                if !(strength.is_finite() && strength >= 0.0) {
                    return Err(RenderError::OutOfRange {
                        what: "tile normal strength",
                        value: strength,
                        range: "[0, ∞)",
                    });
                }
                let info = TileInfo { size_m, strength };
                match layer {
                    TileLayer::Micro => {
                        self.micro = self.create_layer("agesim micro-relief tile", tile)?;
                        self.micro_info = info;
                    }
                    TileLayer::Fine => {
                        self.fine = self.create_layer("agesim fine-wrinkle tile", tile)?;
                        self.fine_info = info;
                    }
                }
            }
        }
        self.skin_bind_group = None;
        Ok(())
    }

    /// Uploads a tileable height tile: the skin micro-relief (one tile covers the
    /// project's `map_size_mm`) or the fine wrinkles. `size_m` is the tile's side on the
    /// skin, metres, > 0; `strength` the normal strength s of SPEC §4 (tile UV units per
    /// height unit, the project's `normal.strength` for the micro-relief), ≥ 0.
    pub fn upload_tile(
        &mut self,
        layer: TileLayer,
        heights: &HeightMap,
        size_m: f32,
        strength: f32,
    ) -> Result<(), RenderError> {
        self.upload_prepared(&Upload::Tile {
            layer,
            tile: &PreparedLayer::tile(heights),
            size_m,
            strength,
        })
    }

    /// Uploads the wrinkle mask (white = fine wrinkles may show) over the mesh UV.
    pub fn upload_wrinkle_mask(&mut self, mask: &Mask) -> Result<(), RenderError> {
        let map = HeightMap::from_vec(mask.width_px(), mask.height_px(), mask.values().to_vec())
            .map_err(RenderError::Core)?;
        self.mask = self.create_layer("agesim wrinkle mask", &PreparedLayer::tile(&map))?;
        self.skin_bind_group = None;
        Ok(())
    }

    /// Uploads the hair instances (SPEC §6: sorted by a_k, 32 bytes each) and keeps
    /// their count table, so a frame draws the first count(t) in one instanced call.
    pub fn upload_hair(&mut self, hairs: &HairInstances) {
        if hairs.is_empty() {
            self.hair = None;
            return;
        }
        let instances = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("agesim hair instances"),
                contents: hairs.as_bytes(),
                usage: wgpu::BufferUsages::VERTEX,
            });
        self.hair = Some(Hair {
            instances,
            levels: hairs.levels().to_vec(),
        });
    }

    /// One hair in how many a sparse frame draws (`HairShading::sparse`); 1 where the
    /// device cannot draw sparse frames.
    pub fn sparse_hair_stride(&self) -> u32 {
        self.sparse_hair_stride
    }

    /// count(t): the hairs drawn at age `t` (0 without hair).
    pub fn hair_count(&self, t: f32) -> u32 {
        self.hair.as_ref().map_or(0, |h| count_at(&h.levels, t))
    }

    fn create_layer(&self, label: &str, layer: &PreparedLayer) -> Result<Layer, RenderError> {
        let max = self.device.limits().max_texture_dimension_2d;
        let (w, h) = layer.size_px();
        if w == 0 || h == 0 || w > max || h > max {
            return Err(RenderError::InvalidSize {
                what: "texture",
                width: w,
                height: h,
                max,
            });
        }
        Ok(create_r16f(&self.device, &self.queue, label, layer))
    }

    fn skin_bind_group(&mut self) -> wgpu::BindGroup {
        if let Some(bg) = &self.skin_bind_group {
            return bg.clone();
        }
        let bg = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("agesim skin bind group"),
            layout: &self.skin_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.frame_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&self.large.view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&self.micro.view),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&self.fine.view),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::TextureView(&self.mask.view),
                },
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: wgpu::BindingResource::Sampler(&self.surface_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 6,
                    resource: wgpu::BindingResource::Sampler(&self.tile_sampler),
                },
            ],
        });
        self.skin_bind_group = Some(bg.clone());
        bg
    }

    /// Makes sure the colour + depth targets are `size_px`, recreating them if needed.
    fn ensure_targets(&mut self, size_px: (u32, u32)) -> Result<(), RenderError> {
        let max = self.device.limits().max_texture_dimension_2d;
        let (w, h) = size_px;
        if w == 0 || h == 0 || w > max || h > max {
            return Err(RenderError::InvalidSize {
                what: "render target",
                width: w,
                height: h,
                max,
            });
        }
        if self.targets.as_ref().is_some_and(|t| t.size_px == size_px) {
            return Ok(());
        }
        let extent = wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        };
        let colour = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("agesim colour target"),
            size: extent,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.colour_format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let texture = |label: &str, format, usage| {
            self.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let labels = [
            "agesim surface target 0 (uv, bitangent sign, coverage)",
            "agesim surface target 1 (uv derivatives)",
            "agesim surface target 2 (normal, tangent)",
        ];
        let surface_views = [0, 1, 2].map(|i| {
            texture(
                labels[i],
                SURFACE_FORMATS[i],
                attachment | wgpu::TextureUsages::TEXTURE_BINDING,
            )
            .create_view(&wgpu::TextureViewDescriptor::default())
        });
        let surface_bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("agesim stored surface bind group"),
            layout: &self.surface_layout,
            entries: &[0, 1, 2].map(|i| wgpu::BindGroupEntry {
                binding: i,
                resource: wgpu::BindingResource::TextureView(&surface_views[i as usize]),
            }),
        });
        let surface_depth = texture("agesim surface depth", DEPTH_FORMAT, attachment);
        let depth = texture("agesim depth target", DEPTH_FORMAT, attachment);
        let view = |t: &wgpu::Texture| t.create_view(&wgpu::TextureViewDescriptor::default());
        self.target_generation += 1;
        self.surface_generation += 1;
        self.targets = Some(Targets {
            size_px,
            colour_view: view(&colour),
            colour,
            surface_views,
            surface_bind_group,
            surface_depth_view: view(&surface_depth),
            depth_view: view(&depth),
        });
        Ok(())
    }

    /// 8-bit targets without hardware sRGB encoding (eframe's `Bgra8Unorm`) get sRGB
    /// values from the shader; sRGB formats are encoded by the hardware, float formats
    /// keep linear values.
    fn encodes_srgb(&self) -> bool {
        matches!(
            self.colour_format,
            wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Bgra8Unorm
        )
    }

    /// Changes whenever [`Renderer::encode`] recreated the targets (first frame, new
    /// size): a view registered elsewhere (egui's `register_native_texture`) must then be
    /// registered again.
    pub fn target_generation(&self) -> u64 {
        self.target_generation
    }

    /// How many frames rasterised the mesh (the surface pass) so far; the others shaded
    /// the stored surface. For diagnostics and tests.
    pub fn surface_passes(&self) -> u64 {
        self.surface_passes
    }

    /// The colour target of the last [`Renderer::encode`] (None before the first).
    pub fn colour_texture(&self) -> Option<&wgpu::Texture> {
        self.targets.as_ref().map(|t| &t.colour)
    }

    /// A view of the colour target, for compositing (e.g. egui's
    /// `register_native_texture` or a full-screen blit in a paint callback).
    pub fn colour_view(&self) -> Option<&wgpu::TextureView> {
        self.targets.as_ref().map(|t| &t.colour_view)
    }

    /// Records one frame at `size_px` into the renderer's own targets: the skin pass,
    /// then (if enabled and uploaded) the hair pass with count(`params.age`) instances
    /// in one draw. Writes the frame uniform through the queue, so submit `encoder`
    /// after this call, and encode one view per submission (a second `encode` before the
    /// submit would overwrite the first's uniform). The stored surface counts as drawn
    /// once recorded: an encoder dropped without being submitted leaves it stale until
    /// the view, the size or the mesh change. Draws only the background until a mesh is
    /// uploaded.
    pub fn encode(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<(), RenderError> {
        self.ensure_targets(size_px)?;
        if params.skin.pom_mode == PomMode::Displacement
            && let Some(data) = self.mesh_to_subdivide.take()
        {
            self.displaced_mesh =
                Some(self.create_mesh("agesim subdivided mesh", &subdivide(&data)));
            self.surface_generation += 1;
        }
        let ctx = FrameContext {
            size_px,
            encode_srgb: self.encodes_srgb(),
            micro_repeats: self
                .surface_scale
                .repeats(self.metres_per_unit, self.micro_info.size_m),
            fine_repeats: self
                .surface_scale
                .repeats(self.metres_per_unit, self.fine_info.size_m),
            micro_strength: self.micro_info.strength,
            fine_strength: self.fine_info.strength,
            mesh_units_per_uv: 0.5
                * (self.surface_scale.units_per_u + self.surface_scale.units_per_v),
        };
        let uniform = FrameUniform::new(params, &ctx);
        self.queue
            .write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&uniform));
        let skin_bind_group = self.skin_bind_group();
        let Some(targets) = &self.targets else {
            return Ok(());
        };
        let bg = params.background;
        let encode = self.encodes_srgb();
        let to_target = |c: f32| {
            if !encode {
                f64::from(c)
            } else {
                f64::from(if c <= 0.003_130_8 {
                    c * 12.92
                } else {
                    1.055 * c.powf(1.0 / 2.4) - 0.055
                })
            }
        };
        let mesh = if params.skin.pom_mode == PomMode::Displacement {
            self.displaced_mesh.as_ref()
        } else {
            self.mesh.as_ref()
        };
        let key = SurfaceKey {
            clip_from_world: uniform.clip_from_world,
            camera_pos: uniform.camera_pos,
            generation: self.surface_generation,
            displacement: (params.skin.pom_mode == PomMode::Displacement)
                .then_some((uniform.disp[1], self.large_generation)),
        };
        if self.surface_key != Some(key) {
            // The surface pass: the mesh into the G-buffer. The first target's alpha (the
            // depth) is cleared to 2: the background.
            let clear = |a: f64| wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color {
                    a,
                    ..wgpu::Color::TRANSPARENT
                }),
                store: wgpu::StoreOp::Store,
            };
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("agesim surface pass"),
                color_attachments: &[0, 1, 2].map(|k| {
                    Some(wgpu::RenderPassColorAttachment {
                        view: &targets.surface_views[k],
                        depth_slice: None,
                        resolve_target: None,
                        ops: clear(if k == 0 { 2.0 } else { 0.0 }),
                    })
                }),
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.surface_depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if let Some(mesh) = mesh {
                pass.set_pipeline(&self.surface_pipeline);
                pass.set_bind_group(0, &skin_bind_group, &[]);
                pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..mesh.index_count, 0, 0..1);
            }
            drop(pass);
            self.surface_key = Some(key);
            self.surface_passes += 1;
        }
        {
            // The shading pass: the background, then the skin from the stored surface.
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("agesim skin shading pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &targets.colour_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: to_target(bg.x),
                            g: to_target(bg.y),
                            b: to_target(bg.z),
                            a: 1.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.shade_pipeline);
            pass.set_bind_group(0, &skin_bind_group, &[]);
            pass.set_bind_group(1, &targets.surface_bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        let wire = params.wireframe && params.skin.pom_mode != PomMode::Displacement;
        let hair = self.hair.as_ref().and_then(|hair| {
            let count = count_at(&hair.levels, params.age);
            if !params.hair.enabled || count == 0 {
                return None;
            }
            // Sparse: instances 0, S, 2S, … of the first `count` (the last one read,
            // (⌈count/S⌉ − 1)·S, is below count).
            Some(match &self.sparse_hair_pipeline {
                Some(sparse) if params.hair.sparse => (
                    hair,
                    sparse,
                    count.div_ceil(self.sparse_hair_stride),
                    SPARSE_SEGMENTS,
                ),
                _ => (hair, &self.hair_pipeline, count, SEGMENTS),
            })
        });
        if !wire && hair.is_none() {
            return Ok(());
        }
        // The hair and the wireframe are tested against the skin's depth and write their
        // own: the skin's depth is restored from the stored surface into the depth target
        // (a draw, not a depth-texture copy, which OpenGL backends cannot do).
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("agesim skin depth pass"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.depth_pipeline);
            pass.set_bind_group(0, &skin_bind_group, &[]);
            pass.set_bind_group(1, &targets.surface_bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("agesim hair and wireframe pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &targets.colour_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &targets.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if wire && let (Some(mesh), Some((edges, count))) = (&self.mesh, &self.wire_edges) {
            pass.set_pipeline(&self.wire_pipeline);
            pass.set_bind_group(0, &skin_bind_group, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(edges.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..*count, 0, 0..1);
        }
        if let Some((hair, pipeline, drawn, segments)) = hair {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &self.hair_bind_group, &[]);
            pass.set_vertex_buffer(0, hair.instances.slice(..));
            pass.draw(0..vertices_per_hair(segments), 0..drawn);
        }
        Ok(())
    }

    /// Renders one frame offscreen and reads it back (issue 11 §4): the copy's rows are
    /// padded to 256 bytes as wgpu requires and unpadded here. Blocks until done. Needs
    /// an 8-bit RGBA or BGRA colour format.
    pub fn render_to_image(
        &mut self,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<image::RgbaImage, RenderError> {
        let (mut pixels, bytes_per_pixel) = self.render_and_read(params, size_px)?;
        if bytes_per_pixel != 4 {
            return Err(RenderError::Readback(format!(
                "render_to_image needs an 8-bit RGBA target, not {:?}",
                self.colour_format
            )));
        }
        if matches!(
            self.colour_format,
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
        ) {
            for px in pixels.chunks_exact_mut(4) {
                px.swap(0, 2);
            }
        }
        image::RgbaImage::from_raw(size_px.0, size_px.1, pixels)
            .ok_or_else(|| RenderError::Readback("pixel count mismatch".into()))
    }

    /// Like [`Renderer::render_to_image`] for a renderer made with
    /// `wgpu::TextureFormat::Rgba32Float`: the raw values, row-major from the top. With
    /// [`crate::FrameOutput::PomHit`] they are (hit u, hit v, polygon u, polygon v).
    pub fn render_to_f32(
        &mut self,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<Vec<[f32; 4]>, RenderError> {
        let (bytes, bytes_per_pixel) = self.render_and_read(params, size_px)?;
        if bytes_per_pixel != 16 {
            return Err(RenderError::Readback(format!(
                "render_to_f32 needs an Rgba32Float target, not {:?}",
                self.colour_format
            )));
        }
        Ok(bytes
            .chunks_exact(16)
            .map(|px| {
                let mut v = [0f32; 4];
                for (c, b) in v.iter_mut().zip(px.chunks_exact(4)) {
                    *c = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                }
                v
            })
            .collect())
    }

    /// Encodes, copies the colour target to a buffer (rows padded to 256 bytes), waits,
    /// and returns the unpadded bytes with the bytes per pixel.
    fn render_and_read(
        &mut self,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<(Vec<u8>, u32), RenderError> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("agesim render_to_image"),
            });
        self.encode(&mut encoder, params, size_px)?;
        let (w, h) = size_px;
        let bytes_per_pixel = self.colour_format.block_copy_size(None).ok_or_else(|| {
            RenderError::Readback(format!(
                "unsupported colour format {:?}",
                self.colour_format
            ))
        })?;
        let unpadded = w * bytes_per_pixel;
        let padded = unpadded.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
            * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("agesim readback buffer"),
            size: u64::from(padded) * u64::from(h),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let Some(targets) = &self.targets else {
            return Err(RenderError::Readback("no render target".into()));
        };
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &targets.colour,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        let submission = self.queue.submit([encoder.finish()]);
        let slice = buffer.slice(..);
        let (sender, receiver) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| drop(sender.send(r)));
        self.device
            .poll(wgpu::PollType::Wait {
                submission_index: Some(submission),
                timeout: None,
            })
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        receiver
            .recv()
            .map_err(|e| RenderError::Readback(e.to_string()))?
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(RenderError::Gpu(err.to_string()));
        }
        let mut pixels = Vec::with_capacity((unpadded * h) as usize);
        {
            let data = slice
                .get_mapped_range()
                .map_err(|e| RenderError::Readback(e.to_string()))?;
            for row in data.chunks(padded as usize) {
                pixels.extend_from_slice(&row[..unpadded as usize]);
            }
        }
        buffer.unmap();
        Ok((pixels, bytes_per_pixel))
    }
}

/// A 1-channel f16 texture (filterable everywhere) holding `data` (w·h values), with
/// `mips`, its box-filtered mip chain (halving while both sides are even):
/// `textureSampleGrad` then averages micro-relief and fine wrinkles smaller than a pixel
/// instead of aliasing them into speckle. The large-wrinkle map has no mips: POM marches
/// the exact height field (`tests/pom_reference.rs`), and at ≈ 1 texel per pixel on a
/// whole-head view it does not alias much.
/// A height layer converted for the GPU: f16 texels and, for tiles, the box-filtered mip
/// chain. Made on any thread ([`PreparedLayer::large_wrinkles`], [`PreparedLayer::tile`]),
/// so the thread that draws only copies bytes ([`Renderer::upload_prepared`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedLayer {
    width: u32,
    height: u32,
    levels: u32,
    bytes: Vec<u8>,
}

impl PreparedLayer {
    /// The large-wrinkle heights, clamped to [0, 1] (see
    /// [`Renderer::upload_large_wrinkles`]), one level.
    pub fn large_wrinkles(heights01: &HeightMap) -> Self {
        let data: Vec<f32> = heights01.data().iter().map(|h| h.clamp(0.0, 1.0)).collect();
        prepare_r16f((heights01.width_px(), heights01.height_px()), &data, false)
    }

    /// A tileable height tile with its mip chain (see [`Renderer::upload_tile`]).
    pub fn tile(heights: &HeightMap) -> Self {
        prepare_r16f(
            (heights.width_px(), heights.height_px()),
            heights.data(),
            true,
        )
    }

    /// (width, height) of level 0, texels.
    pub fn size_px(&self) -> (u32, u32) {
        (self.width, self.height)
    }
}

/// f16 bytes of `data` and, with `mips`, of its 2×2 box-filtered levels down to an odd
/// side.
fn prepare_r16f((width, height): (u32, u32), data: &[f32], mips: bool) -> PreparedLayer {
    let mut bytes = to_f16_bytes(data);
    let mut levels = 1;
    let (mut w, mut h) = (width as usize, height as usize);
    let mut level: Vec<f32> = data.to_vec();
    while mips && w % 2 == 0 && h % 2 == 0 && w > 1 && h > 1 {
        let (nw, nh) = (w / 2, h / 2);
        let mut next = Vec::with_capacity(nw * nh);
        for y in 0..nh {
            for x in 0..nw {
                let at = |xx: usize, yy: usize| level[yy * w + xx];
                next.push(
                    0.25 * (at(2 * x, 2 * y)
                        + at(2 * x + 1, 2 * y)
                        + at(2 * x, 2 * y + 1)
                        + at(2 * x + 1, 2 * y + 1)),
                );
            }
        }
        bytes.extend(to_f16_bytes(&next));
        level = next;
        (w, h) = (nw, nh);
        levels += 1;
    }
    PreparedLayer {
        width,
        height,
        levels,
        bytes,
    }
}

fn create_r16f(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    layer: &PreparedLayer,
) -> Layer {
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: layer.width,
                height: layer.height,
                depth_or_array_layers: 1,
            },
            mip_level_count: layer.levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R16Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &layer.bytes,
    );
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some(label),
        ..Default::default()
    });
    Layer { view }
}
