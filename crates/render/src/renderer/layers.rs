//! The uploaded inputs: height layers converted for the GPU, the mesh and its wireframe
//! edges, the hair instances, and the skin bind group over them.

use agesim_core::head::mesh::SurfaceScale;
use agesim_core::layers::hair::HairInstances;
use agesim_core::{HeightMap, Mesh};
use wgpu::util::DeviceExt as _;

use crate::RenderError;
use crate::mesh::{MeshData, ShapeVertex};

use super::textures::{FLAT_NORMAL, Layer, PreparedLayer, create_r16f, create_rgba8};
use super::views::ViewShape;
use super::{GpuMesh, Hair, Renderer, TileLayer, Upload, ViewId};

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

/// The shape of one age, per vertex of the uploaded mesh (docs/models.md §13): the
/// regions' displacement (mesh units), the displaced normal, how far the deflating regions
/// took it in (mm, the hollow the skin pass darkens) and how much of the sky it sees over
/// how much it saw undisplaced (the skin pass multiplies the skin by it).
#[derive(Clone, Copy, Debug)]
pub struct ShapeUpload<'a> {
    pub delta: &'a [glam::Vec3],
    pub normals: &'a [glam::Vec3],
    pub hollow_mm: &'a [f32],
    pub occlusion: &'a [f32],
}

impl Renderer {
    /// Uploads the head (positions, normals, UVs, tangents with sign; docs/models.md §1, §4) —
    /// its once-subdivided copy for [`PomMode::Displacement`] follows on the first frame
    /// in that mode — and measures its UV density so the tiles appear at their physical
    /// size. `metres_per_unit` is the mesh's unit length
    /// (1 for the default head), > 0.
    ///
    /// [`PomMode::Displacement`]: crate::PomMode::Displacement
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
        // A shape is per vertex of the mesh it was made for, brow strands lie on its head.
        for v in &mut self.views {
            v.shape = None;
            v.brows = None;
            v.shape_generation += 1;
        }
        self.mesh_generation += 1;
        self.surface_scale = scale;
        self.metres_per_unit = metres_per_unit;
        Ok(())
    }

    /// Sizes the repeated tiles by `scale` instead of the uploaded mesh's mean UV density
    /// (the scene's measure over the face: `Scene::surface_scale`); until the next
    /// [`Renderer::upload_mesh`].
    pub fn set_surface_scale(&mut self, scale: SurfaceScale) {
        self.surface_scale = scale;
    }

    /// The uploaded mesh's measured UV density (mesh units per UV unit).
    pub fn surface_scale(&self) -> SurfaceScale {
        self.surface_scale
    }

    pub(super) fn create_mesh(&self, label: &str, data: &MeshData) -> GpuMesh {
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
        // No shape: every vertex where the mesh has it.
        let no_shape = self.shape_buffer(
            &format!("{label} (no shape)"),
            &vec![ShapeVertex::default(); data.vertices.len()],
        );
        GpuMesh {
            vertices,
            indices,
            index_count: data.indices.len() as u32,
            no_shape,
            parents: data.parents.clone(),
        }
    }

    pub(super) fn shape_buffer(&self, label: &str, shape: &[ShapeVertex]) -> wgpu::Buffer {
        self.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytemuck::cast_slice(shape),
                usage: wgpu::BufferUsages::VERTEX,
            })
    }

    /// Uploads the shape of `view`'s age (docs/models.md §13, [`ShapeUpload`]), drawn by
    /// moving the vertices in the surface pass; `None` draws the mesh as it is. The view's
    /// stored surface is drawn again.
    pub fn upload_shape_to(
        &mut self,
        view: ViewId,
        shape: Option<ShapeUpload<'_>>,
    ) -> Result<(), RenderError> {
        let vi = self.view_index(view)?;
        let shape = match shape {
            None => None,
            Some(s) => {
                let count = self
                    .mesh
                    .as_ref()
                    .map_or(0, |m| m.vertex_count_of() as usize);
                let lens = [
                    s.delta.len(),
                    s.normals.len(),
                    s.hollow_mm.len(),
                    s.occlusion.len(),
                ];
                if lens.iter().any(|&l| l != count) {
                    return Err(RenderError::InvalidMesh(format!(
                        "a shape of {} displacements, {} normals, {} hollows and {} occlusions for a mesh of {count} vertices",
                        lens[0], lens[1], lens[2], lens[3]
                    )));
                }
                let data: Vec<ShapeVertex> = (0..count)
                    .map(|v| ShapeVertex {
                        delta: s.delta[v].to_array(),
                        normal: s.normals[v].to_array(),
                        hollow: crate::mesh::hollow_occlusion(s.hollow_mm[v]),
                        sky_lost: 1.0 - s.occlusion[v],
                    })
                    .collect();
                let base = self.shape_buffer("agesim shape", &data);
                Some(ViewShape {
                    data,
                    base,
                    subdivided: None,
                })
            }
        };
        let v = &mut self.views[vi];
        v.shape = shape;
        v.shape_generation += 1;
        Ok(())
    }

    /// Uploads the large wrinkles over the mesh UV (docs/models.md §2, §5): the scene's
    /// normalised map, the wrinkles' depth in [0, 1] (a fold's raised side down to −1;
    /// values outside are clamped), drawn cut into the skin: depth 0 lies on the polygon's
    /// surface, 1 `disp_scale` below it. Stored as f16 heights only; the normals are derived in
    /// the shader with the frame's `disp_scale`, so the lit relief always matches the
    /// marched and the displaced one, at any age scaling of the heights.
    pub fn upload_large_wrinkles(&mut self, heights01: &HeightMap) -> Result<(), RenderError> {
        self.upload_prepared(&Upload::LargeWrinkles(&PreparedLayer::large_wrinkles(
            heights01,
        )))
    }

    /// Uploads a layer prepared on another thread (the editor's worker converts to f16
    /// and builds mips there, so the drawing thread only copies bytes) to
    /// [`ViewId::MAIN`] ([`Renderer::upload_prepared_to`]).
    pub fn upload_prepared(&mut self, upload: &Upload<'_>) -> Result<(), RenderError> {
        self.upload_prepared_to(ViewId::MAIN, upload)
    }

    /// Uploads a prepared layer for `view`: the large-wrinkle map and the micro-relief
    /// tile are the view's own; the fine-wrinkle tile is shared by every view.
    pub fn upload_prepared_to(
        &mut self,
        view: ViewId,
        upload: &Upload<'_>,
    ) -> Result<(), RenderError> {
        let vi = self.view_index(view)?;
        match *upload {
            Upload::LargeWrinkles(layer) => {
                let large = self.create_layer("agesim large-wrinkle heights", layer)?;
                let v = &mut self.views[vi];
                v.large = large;
                v.large_generation += 1;
                v.skin_bind_group = None;
            }
            Upload::Tile { layer, tile } => match layer {
                TileLayer::Micro => {
                    let micro = self.create_layer("agesim micro-relief tile", tile)?;
                    let v = &mut self.views[vi];
                    v.micro = micro;
                    v.skin_bind_group = None;
                }
                TileLayer::Fine => {
                    self.fine = self.create_layer("agesim fine-wrinkle tile", tile)?;
                    for v in &mut self.views {
                        v.skin_bind_group = None;
                    }
                }
            },
        }
        Ok(())
    }

    /// Uploads a tileable height tile: the skin micro-relief or the fine wrinkles. Its
    /// size on the skin and its normal strength are the frame's
    /// ([`crate::SkinParams::micro_tile`], [`crate::SkinParams::fine_tile`]).
    pub fn upload_tile(
        &mut self,
        layer: TileLayer,
        heights: &HeightMap,
    ) -> Result<(), RenderError> {
        self.upload_prepared(&Upload::Tile {
            layer,
            tile: &PreparedLayer::tile(heights),
        })
    }

    /// Uploads the head's base colour map (sRGB RGBA8, row 0 at the top, over the mesh's
    /// UVs), shared by every view; `None` goes back to the skin colour
    /// ([`crate::SkinParams::albedo`]). The map is paled with age like the skin colour.
    pub fn upload_colour_map(&mut self, map: Option<(u32, u32, &[u8])>) -> Result<(), RenderError> {
        self.colour = self.head_picture("colour map", map, [255; 4], true)?;
        self.has_colour_map = map.is_some();
        Ok(())
    }

    /// Uploads a base colour map of `view`'s own (the aged colour at its age: the compare
    /// view's differs from the main view's), used instead of the shared one
    /// ([`Renderer::upload_colour_map`]); `None` goes back to the shared one.
    pub fn upload_colour_map_to(
        &mut self,
        view: ViewId,
        map: Option<(u32, u32, &[u8])>,
    ) -> Result<(), RenderError> {
        let vi = self.view_index(view)?;
        let layer = match map {
            Some(_) => Some(self.head_picture("colour map", map, [255; 4], true)?),
            None => None,
        };
        self.views[vi].colour = layer;
        self.views[vi].skin_bind_group = None;
        Ok(())
    }

    /// Uploads the head's tangent-space normal map (RGBA8, linear, row 0 at the top, over
    /// the mesh's UVs; green up unless [`crate::SkinParams::head_normal_green_down`]),
    /// shared by every view: the layers are combined onto it (reoriented normal
    /// mapping). `None`: no head normal map.
    pub fn upload_normal_map(&mut self, map: Option<(u32, u32, &[u8])>) -> Result<(), RenderError> {
        self.head_normal = self.head_picture("normal map", map, FLAT_NORMAL, false)?;
        self.has_normal_map = map.is_some();
        Ok(())
    }

    /// Uploads where the micro-relief lies over the head's UVs (RGBA8, linear, row 0 at
    /// the top; its weight in red, 0–1: the tile's strength times it), shared by every
    /// view. `None`: the whole tile everywhere.
    pub fn upload_micro_weight(
        &mut self,
        map: Option<(u32, u32, &[u8])>,
    ) -> Result<(), RenderError> {
        self.micro_weight = self.head_picture("micro-relief weights", map, [255; 4], false)?;
        Ok(())
    }

    /// A picture over the head's UVs as a texture (`none` for a missing one), checked;
    /// every view's bind group is made again.
    fn head_picture(
        &mut self,
        what: &'static str,
        map: Option<(u32, u32, &[u8])>,
        none: [u8; 4],
        srgb: bool,
    ) -> Result<Layer, RenderError> {
        let (w, h, rgba) = map.unwrap_or((1, 1, &none));
        let max = self.device.limits().max_texture_dimension_2d;
        if w == 0 || h == 0 || w > max || h > max || rgba.len() != (w * h * 4) as usize {
            return Err(RenderError::InvalidSize {
                what,
                width: w,
                height: h,
                max,
            });
        }
        for v in &mut self.views {
            v.skin_bind_group = None;
        }
        Ok(create_rgba8(
            &self.device,
            &self.queue,
            what,
            (w, h),
            rgba,
            srgb,
        ))
    }

    /// Uploads the hair instances (docs/models.md §9: sorted by a_k, 32 bytes each) and keeps
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

    /// Uploads the brow hairs of `view`'s age (docs/models.md §9 "Eyebrows"), drawn
    /// with the hair; none (or an empty slice) draws no brow hairs.
    pub fn upload_brows_to(
        &mut self,
        view: ViewId,
        brows: Option<&[agesim_core::layers::hair::brows::BrowStrand]>,
    ) -> Result<(), RenderError> {
        let vi = self.view_index(view)?;
        let brows = brows.filter(|b| !b.is_empty()).map(|b| {
            let buffer = self
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("agesim brow strands"),
                    contents: bytemuck::cast_slice(b),
                    usage: wgpu::BufferUsages::VERTEX,
                });
            (buffer, b.len() as u32)
        });
        self.views[vi].brows = brows;
        Ok(())
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

    /// The skin passes' group 0 of view `vi`: its frame uniform and layers, the shared
    /// fine tile and the samplers.
    pub(super) fn skin_bind_group(&mut self, vi: usize) -> wgpu::BindGroup {
        let v = &self.views[vi];
        if let Some(bg) = &v.skin_bind_group {
            return bg.clone();
        }
        let bg = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("agesim skin bind group"),
            layout: &self.pipelines.skin_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: v.frame_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&v.large.view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&v.micro.view),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&self.fine.view),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: wgpu::BindingResource::Sampler(&self.pipelines.surface_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: wgpu::BindingResource::Sampler(&self.pipelines.tile_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 6,
                    resource: wgpu::BindingResource::TextureView(
                        &v.colour.as_ref().unwrap_or(&self.colour).view,
                    ),
                },
                wgpu::BindGroupEntry {
                    binding: 7,
                    resource: wgpu::BindingResource::TextureView(&self.head_normal.view),
                },
                wgpu::BindGroupEntry {
                    binding: 8,
                    resource: wgpu::BindingResource::TextureView(&self.micro_weight.view),
                },
            ],
        });
        self.views[vi].skin_bind_group = Some(bg.clone());
        bg
    }
}
