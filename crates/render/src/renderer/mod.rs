//! The long-lived renderer: pipelines, layouts and samplers made once; assets uploaded
//! on request; per frame a skin shading pass and one instanced hair pass into its own
//! colour + depth targets (the editor shows the colour target through a paint callback).
//!
//! The skin is drawn in two steps. The *surface pass* rasterises the mesh into a small
//! G-buffer: per pixel the UV, its derivatives, the geometric frame and the depth
//! (`fs_surface` in skin.wgsl). The *shading pass* runs the skin shader once per covered
//! pixel from it (`fs_shade`), the eye direction coming from the pixel's view ray; a depth
//! pass (`fs_depth`) restores the skin's depth for the hair and the wireframe. The surface pass runs only when what it stores
//! changes (the camera, the size, the mesh, displacement): an age step or a re-baked map
//! is one full-screen pass, whatever the mesh's triangle count. On a CPU rasteriser the
//! head's 128k triangles cost more than shading the pixels they cover.

mod layers;
mod pipelines;
mod readback;
mod targets;
mod textures;
mod views;

use agesim_core::head::mesh::SurfaceScale;
use agesim_core::layers::hair::AgeLevel;

use crate::RenderError;
use crate::hair::{SEGMENTS, SPARSE_SEGMENTS, count_at, vertices_per_hair};
use crate::mesh::{MeshData, subdivide};
use crate::params::{FrameParams, PomMode};
use crate::uniforms::{FrameContext, FrameUniform};

pub use layers::ShapeUpload;
pub use textures::PreparedLayer;
pub use views::ViewId;

use pipelines::Pipelines;
use textures::{FLAT_NORMAL, Layer, create_r16f, create_rgba8, prepare_r16f};
use views::View;

/// The colour format of headless renders ([`Renderer::render_to_image`]): 8-bit sRGB,
/// so the hardware encodes and blending would happen in linear light.
pub const COLOUR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// The depth target's format.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Which tile an upload replaces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TileLayer {
    /// Skin micro-relief ([P], docs/models.md §4).
    Micro,
    /// Fine wrinkles ([T] §5.2, docs/models.md §10).
    Fine,
}

/// A prepared layer and where it goes ([`Renderer::upload_prepared`]).
#[derive(Clone, Copy, Debug)]
pub enum Upload<'a> {
    /// The large-wrinkle heights ([`PreparedLayer::large_wrinkles`]).
    LargeWrinkles(&'a PreparedLayer),
    /// A tile ([`PreparedLayer::tile`]); where it lies on the skin is the frame's
    /// ([`crate::SkinParams::micro_tile`], [`crate::SkinParams::fine_tile`]).
    Tile {
        layer: TileLayer,
        tile: &'a PreparedLayer,
    },
}

struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    /// A zero shape of its vertices (the second vertex buffer when a view has no shape).
    no_shape: wgpu::Buffer,
    /// A subdivided mesh's new vertices' parents ([`crate::mesh::subdivide_shape`]).
    parents: Vec<(u32, u32)>,
}

impl GpuMesh {
    fn vertex_count_of(&self) -> u32 {
        (self.no_shape.size() / std::mem::size_of::<crate::mesh::ShapeVertex>() as u64) as u32
    }
}

/// What the stored surface depends on: the camera, the mesh and the targets (the
/// generations bumped when either is replaced), and when displacing, the depth and the
/// large-wrinkle map that move the vertices.
#[derive(Clone, Copy, PartialEq)]
struct SurfaceKey {
    clip_from_world: [[f32; 4]; 4],
    camera_pos: [f32; 4],
    /// (mesh generation, the view's target generation, its shape generation).
    generation: (u64, u64, u64),
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
    /// Layouts, pipelines and samplers, made once.
    pipelines: Pipelines,
    /// The uploaded mesh's edges (line list), for the wireframe overlay.
    wire_edges: Option<(wgpu::Buffer, u32)>,
    /// Bumped when the mesh is replaced (see [`SurfaceKey`]).
    mesh_generation: u64,
    /// Surface passes run so far, every view ([`Renderer::surface_passes`]).
    surface_passes: u64,
    /// The fine-wrinkle tile, shared by every view.
    fine: Layer,
    /// The head's base colour map (sRGB RGBA8; a white texel when there is none).
    colour: Layer,
    has_colour_map: bool,
    /// The head's tangent-space normal map (linear RGBA8; flat when there is none).
    head_normal: Layer,
    has_normal_map: bool,
    /// Where the micro-relief lies over the head's UVs (linear RGBA8, the weight in red;
    /// a white texel, everywhere, when there is none).
    micro_weight: Layer,
    mesh: Option<GpuMesh>,
    /// The subdivided copy, made on the first displacement frame (4× the triangles:
    /// editors that never use the mode never pay for it).
    displaced_mesh: Option<GpuMesh>,
    /// The uploaded mesh kept on the CPU until it is subdivided.
    mesh_to_subdivide: Option<MeshData>,
    surface_scale: SurfaceScale,
    metres_per_unit: f32,
    hair: Option<Hair>,
    /// [`ViewId::MAIN`] and the views added since: targets and age-dependent layers.
    views: Vec<View>,
}

impl Renderer {
    /// Builds pipelines, layouts, samplers and placeholder layers (flat heights) for
    /// targets of `colour_format`. An sRGB format gets linear output encoded
    /// by the hardware; `Rgba8Unorm`/`Bgra8Unorm` get sRGB-encoded values from the
    /// shader; float formats get linear values.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        colour_format: wgpu::TextureFormat,
    ) -> Result<Self, RenderError> {
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let pipelines = Pipelines::build(device, colour_format);
        let fine = create_r16f(
            device,
            queue,
            "agesim fine-wrinkle tile (placeholder)",
            &prepare_r16f((1, 1), &[0.0], false),
        );
        let colour = create_rgba8(
            device,
            queue,
            "agesim colour map (none)",
            (1, 1),
            &[255; 4],
            true,
        );
        let head_normal = create_rgba8(
            device,
            queue,
            "agesim head normal map (none)",
            (1, 1),
            &FLAT_NORMAL,
            false,
        );
        let micro_weight = create_rgba8(
            device,
            queue,
            "agesim micro-relief weights (none)",
            (1, 1),
            &[255; 4],
            false,
        );
        let main = View::new(device, queue, &pipelines.hair_layout);

        if let Some(err) = pollster::block_on(scope.pop()) {
            return Err(RenderError::Gpu(err.to_string()));
        }
        Ok(Self {
            device: device.clone(),
            queue: queue.clone(),
            colour_format,
            pipelines,
            mesh_generation: 0,
            surface_passes: 0,
            wire_edges: None,
            fine,
            colour,
            has_colour_map: false,
            head_normal,
            has_normal_map: false,
            micro_weight,
            mesh: None,
            displaced_mesh: None,
            mesh_to_subdivide: None,
            surface_scale: SurfaceScale {
                units_per_u: 1.0,
                units_per_v: 1.0,
            },
            metres_per_unit: 1.0,
            hair: None,
            views: vec![main],
        })
    }

    /// The colour format the pipelines were built for.
    pub fn colour_format(&self) -> wgpu::TextureFormat {
        self.colour_format
    }

    /// One hair in how many a sparse frame draws (`HairShading::sparse`); 1 where the
    /// device cannot draw sparse frames.
    pub fn sparse_hair_stride(&self) -> u32 {
        self.pipelines.sparse_hair_stride
    }

    /// count(t): the hairs drawn at age `t` (0 without hair).
    pub fn hair_count(&self, t: f32) -> u32 {
        self.hair.as_ref().map_or(0, |h| count_at(&h.levels, t))
    }

    /// [`Renderer::encode_view`] of [`ViewId::MAIN`].
    pub fn encode(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<(), RenderError> {
        self.encode_view(ViewId::MAIN, encoder, params, size_px)
    }

    /// Records one frame at `size_px` into `view`'s targets: the skin pass, then (if
    /// enabled and uploaded) the hair pass with count(`params.age`) instances in one draw.
    /// Writes the view's frame uniform through the queue, so submit `encoder` after this
    /// call, and encode a view once per submission (a second `encode_view` of the same
    /// view before the submit would overwrite the first's uniform; other views have
    /// their own). The stored surface counts as drawn once recorded: an encoder dropped
    /// without being submitted leaves it stale until the camera, the size or the mesh
    /// change. Draws only the background until a mesh is uploaded.
    pub fn encode_view(
        &mut self,
        view: ViewId,
        encoder: &mut wgpu::CommandEncoder,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<(), RenderError> {
        let vi = self.view_index(view)?;
        self.ensure_targets(vi, size_px)?;
        if params.skin.pom_mode == PomMode::Displacement
            && let Some(data) = self.mesh_to_subdivide.take()
        {
            self.displaced_mesh =
                Some(self.create_mesh("agesim subdivided mesh", &subdivide(&data)));
            self.mesh_generation += 1;
        }
        // The view's shape for the subdivided mesh, made once per shape.
        if params.skin.pom_mode == PomMode::Displacement
            && let Some(sub) = &self.displaced_mesh
            && let Some(shape) = &self.views[vi].shape
            && shape.subdivided.is_none()
        {
            let data = crate::mesh::subdivide_shape(&shape.data, &sub.parents);
            let buffer = self.shape_buffer("agesim subdivided shape", &data);
            if let Some(shape) = &mut self.views[vi].shape {
                shape.subdivided = Some(buffer);
            }
        }
        let (micro, fine) = (params.skin.micro_tile, params.skin.fine_tile);
        for (what, value, ok) in [
            ("tile size (m)", micro.size_m, micro.size_m > 0.0),
            ("tile size (m)", fine.size_m, fine.size_m > 0.0),
            (
                "tile normal strength",
                micro.strength,
                micro.strength >= 0.0,
            ),
            ("tile normal strength", fine.strength, fine.strength >= 0.0),
        ] {
            if !(value.is_finite() && ok) {
                let range = if what.starts_with("tile size") {
                    "(0, ∞)"
                } else {
                    "[0, ∞)"
                };
                return Err(RenderError::OutOfRange { what, value, range });
            }
        }
        let ctx = FrameContext {
            size_px,
            encode_srgb: self.encodes_srgb(),
            micro_repeats: self
                .surface_scale
                .repeats(self.metres_per_unit, micro.size_m),
            fine_repeats: self
                .surface_scale
                .repeats(self.metres_per_unit, fine.size_m),
            micro_strength: micro.strength,
            fine_strength: fine.strength,
            mesh_units_per_uv: 0.5
                * (self.surface_scale.units_per_u + self.surface_scale.units_per_v),
            colour_map: self.has_colour_map || self.views[vi].colour.is_some(),
            normal_map: self.has_normal_map,
            hair_stride: match &self.pipelines.sparse_hair_pipeline {
                Some(_) if params.hair.sparse => self.pipelines.sparse_hair_stride,
                _ => 1,
            },
        };
        let uniform = FrameUniform::new(params, &ctx);
        self.queue.write_buffer(
            &self.views[vi].frame_buffer,
            0,
            bytemuck::bytes_of(&uniform),
        );
        let skin_bind_group = self.skin_bind_group(vi);
        // The stored surface counts as drawn once recorded (see above).
        let key = SurfaceKey {
            clip_from_world: uniform.clip_from_world,
            camera_pos: uniform.camera_pos,
            generation: (
                self.mesh_generation,
                self.views[vi].target_generation,
                self.views[vi].shape_generation,
            ),
            displacement: (params.skin.pom_mode == PomMode::Displacement)
                .then_some((uniform.disp[1], self.views[vi].large_generation)),
        };
        let redraw_surface = self.views[vi].surface_key.replace(key) != Some(key);
        let v = &self.views[vi];
        let Some(targets) = &v.targets else {
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
        let hair_bind_group = &v.hair_bind_group;
        // The view's shape for `mesh` (the base or the subdivided one), else none.
        let shape_of = |mesh: &'_ GpuMesh| -> wgpu::Buffer {
            let own = v.shape.as_ref().and_then(|s| {
                if mesh.parents.is_empty() {
                    Some(&s.base)
                } else {
                    s.subdivided.as_ref()
                }
            });
            own.unwrap_or(&mesh.no_shape).clone()
        };
        if redraw_surface {
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
                depth_stencil_attachment: Some(depth_attachment(
                    &targets.surface_depth_view,
                    wgpu::LoadOp::Clear(1.0),
                )),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if let Some(mesh) = mesh {
                pass.set_pipeline(&self.pipelines.surface_pipeline);
                pass.set_bind_group(0, &skin_bind_group, &[]);
                pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                pass.set_vertex_buffer(1, shape_of(mesh).slice(..));
                pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..mesh.index_count, 0, 0..1);
            }
            drop(pass);
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
            pass.set_pipeline(&self.pipelines.shade_pipeline);
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
            Some(match &self.pipelines.sparse_hair_pipeline {
                Some(sparse) if params.hair.sparse => (
                    hair,
                    sparse,
                    count.div_ceil(self.pipelines.sparse_hair_stride),
                    SPARSE_SEGMENTS,
                ),
                _ => (hair, &self.pipelines.hair_pipeline, count, SEGMENTS),
            })
        });
        let brows = v.brows.as_ref().filter(|_| params.hair.enabled);
        if !wire && hair.is_none() && brows.is_none() {
            return Ok(());
        }
        // The hair and the wireframe are tested against the skin's depth (the wireframe,
        // and hair on a target that cannot blend, write their own; blended hair does
        // not): the skin's depth is restored from the stored surface into the depth target
        // (a draw, not a depth-texture copy, which OpenGL backends cannot do).
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("agesim skin depth pass"),
                color_attachments: &[],
                depth_stencil_attachment: Some(depth_attachment(
                    &targets.depth_view,
                    wgpu::LoadOp::Clear(1.0),
                )),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipelines.depth_pipeline);
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
            depth_stencil_attachment: Some(depth_attachment(
                &targets.depth_view,
                wgpu::LoadOp::Load,
            )),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if wire && let (Some(mesh), Some((edges, count))) = (&self.mesh, &self.wire_edges) {
            pass.set_pipeline(&self.pipelines.wire_pipeline);
            pass.set_bind_group(0, &skin_bind_group, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            let shape = shape_of(mesh);
            pass.set_vertex_buffer(1, shape.slice(..));
            pass.set_index_buffer(edges.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..*count, 0, 0..1);
        }
        if let Some((hair, pipeline, drawn, segments)) = hair {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, hair_bind_group, &[]);
            pass.set_vertex_buffer(0, hair.instances.slice(..));
            pass.draw(0..vertices_per_hair(segments), 0..drawn);
        }
        if let Some((strands, count)) = brows {
            pass.set_pipeline(&self.pipelines.brow_pipeline);
            pass.set_bind_group(0, hair_bind_group, &[]);
            pass.set_vertex_buffer(0, strands.slice(..));
            pass.draw(0..vertices_per_hair(SEGMENTS), 0..*count);
        }
        Ok(())
    }
}

/// A depth attachment on `view`, loaded as `load` and stored.
fn depth_attachment(
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<f32>,
) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load,
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: None,
    }
}
