//! Views of one renderer: each its own targets, frame uniform and the two layers that
//! differ between ages (the large-wrinkle map, the micro-relief tile). The editor's
//! compare view draws its second age into a second view; the pipelines, the mesh, the
//! hair and the fine-wrinkle tile are uploaded once and shared.

use crate::RenderError;
use crate::uniforms::FrameUniform;

use super::targets::Targets;
use super::textures::{Layer, create_r16f, prepare_r16f};
use super::{Renderer, SurfaceKey};

/// A view of a [`Renderer`]: [`ViewId::MAIN`] always exists, [`Renderer::add_view`]
/// makes more.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ViewId(usize);

impl ViewId {
    /// The view every renderer starts with, the one [`Renderer::encode`] draws.
    pub const MAIN: Self = Self(0);
}

pub(super) struct View {
    pub(super) frame_buffer: wgpu::Buffer,
    /// The hair pass's group 0 (this view's frame uniform).
    pub(super) hair_bind_group: wgpu::BindGroup,
    pub(super) large: Layer,
    pub(super) micro: Layer,
    /// This view's own base colour map (the aged colour of its age), else the shared one.
    pub(super) colour: Option<Layer>,
    /// The shape of this view's age (`None`: the mesh as it is).
    pub(super) shape: Option<ViewShape>,
    /// The brow hairs of this view's age, and how many.
    pub(super) brows: Option<(wgpu::Buffer, u32)>,
    /// Bumped on every shape upload (the surface is drawn again).
    pub(super) shape_generation: u64,
    /// Bumped on every large-wrinkle upload (displacement moves the surface with it).
    pub(super) large_generation: u64,
    /// Rebuilt lazily when one of its textures is replaced.
    pub(super) skin_bind_group: Option<wgpu::BindGroup>,
    /// What the surface targets hold (None: nothing yet, or stale).
    pub(super) surface_key: Option<SurfaceKey>,
    pub(super) targets: Option<Targets>,
    /// Bumped whenever the targets are recreated (see [`Renderer::target_generation`]).
    pub(super) target_generation: u64,
}

/// A view's shape on the GPU: per vertex of the mesh, and of the subdivided mesh once the
/// displacement mode asks for it.
pub(super) struct ViewShape {
    pub(super) data: Vec<crate::mesh::ShapeVertex>,
    pub(super) base: wgpu::Buffer,
    pub(super) subdivided: Option<wgpu::Buffer>,
}

impl View {
    /// A view with no targets yet and flat placeholder layers.
    pub(super) fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        hair_layout: &wgpu::BindGroupLayout,
    ) -> Self {
        let frame_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("agesim frame uniform"),
            size: std::mem::size_of::<FrameUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let hair_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("agesim hair bind group"),
            layout: hair_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: frame_buffer.as_entire_binding(),
            }],
        });
        let flat = |label: &str, value: f32| {
            create_r16f(device, queue, label, &prepare_r16f((1, 1), &[value], false))
        };
        Self {
            frame_buffer,
            hair_bind_group,
            large: flat("agesim large-wrinkle heights (placeholder)", 1.0),
            micro: flat("agesim micro-relief tile (placeholder)", 0.0),
            colour: None,
            shape: None,
            brows: None,
            shape_generation: 0,
            large_generation: 0,
            skin_bind_group: None,
            surface_key: None,
            targets: None,
            target_generation: 0,
        }
    }
}

impl Renderer {
    /// Adds a view: targets, a large-wrinkle map and a micro-relief tile of its own
    /// (flat until uploaded with [`Renderer::upload_prepared_to`]); the mesh, the hair,
    /// the fine-wrinkle tile and the pipelines are the renderer's.
    pub fn add_view(&mut self) -> ViewId {
        self.views.push(View::new(
            &self.device,
            &self.queue,
            &self.pipelines.hair_layout,
        ));
        ViewId(self.views.len() - 1)
    }

    /// The view's state; an id of another renderer is refused, not a panic.
    pub(super) fn view_index(&self, view: ViewId) -> Result<usize, RenderError> {
        if view.0 < self.views.len() {
            Ok(view.0)
        } else {
            Err(RenderError::OutOfRange {
                what: "view id",
                value: view.0 as f32,
                range: "a view of this renderer",
            })
        }
    }
}
