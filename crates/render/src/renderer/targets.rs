//! The renderer's own targets: the colour and depth targets, the stored surface (the
//! surface pass's G-buffer) and what they tell about themselves.

use crate::RenderError;

use super::pipelines::SURFACE_FORMATS;
use super::{DEPTH_FORMAT, Renderer, ViewId};

pub(super) struct Targets {
    pub(super) size_px: (u32, u32),
    pub(super) colour: wgpu::Texture,
    pub(super) colour_view: wgpu::TextureView,
    /// The surface pass's G-buffer ([`SURFACE_FORMATS`], skin.wgsl `SurfaceOut`).
    pub(super) surface_views: [wgpu::TextureView; 3],
    /// The shading pass's group 1: the surface targets.
    pub(super) surface_bind_group: wgpu::BindGroup,
    /// The surface pass's depth test.
    pub(super) surface_depth_view: wgpu::TextureView,
    /// The skin's depth restored from the stored surface each frame (`fs_depth`), which
    /// the hair and the wireframe test against (the wireframe writes it; blended hair
    /// does not).
    pub(super) depth_view: wgpu::TextureView,
}

impl Renderer {
    /// The largest side of a render target (the device's 2D texture limit).
    pub fn max_target_side(&self) -> u32 {
        self.device.limits().max_texture_dimension_2d
    }

    /// Makes sure view `vi`'s targets are `size_px`, recreating them if needed.
    pub(super) fn ensure_targets(
        &mut self,
        vi: usize,
        size_px: (u32, u32),
    ) -> Result<(), RenderError> {
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
        if self.views[vi]
            .targets
            .as_ref()
            .is_some_and(|t| t.size_px == size_px)
        {
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
            layout: &self.pipelines.surface_layout,
            entries: &[0, 1, 2].map(|i| wgpu::BindGroupEntry {
                binding: i,
                resource: wgpu::BindingResource::TextureView(&surface_views[i as usize]),
            }),
        });
        let surface_depth = texture("agesim surface depth", DEPTH_FORMAT, attachment);
        let depth = texture("agesim depth target", DEPTH_FORMAT, attachment);
        let view = |t: &wgpu::Texture| t.create_view(&wgpu::TextureViewDescriptor::default());
        let v = &mut self.views[vi];
        v.target_generation += 1;
        v.targets = Some(Targets {
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
    pub(super) fn encodes_srgb(&self) -> bool {
        matches!(
            self.colour_format,
            wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Bgra8Unorm
        )
    }

    /// Changes whenever [`Renderer::encode`] recreated the targets (first frame, new
    /// size): a view registered elsewhere (a bind group of the colour view) must then be
    /// made again. [`ViewId::MAIN`]'s; [`Renderer::target_generation_of`] for another.
    pub fn target_generation(&self) -> u64 {
        self.target_generation_of(ViewId::MAIN)
    }

    /// [`Renderer::target_generation`] of `view` (0 for an id of another renderer).
    pub fn target_generation_of(&self, view: ViewId) -> u64 {
        self.view_index(view)
            .map_or(0, |vi| self.views[vi].target_generation)
    }

    /// How many frames rasterised the mesh (the surface pass) so far; the others shaded
    /// the stored surface. For diagnostics and tests.
    pub fn surface_passes(&self) -> u64 {
        self.surface_passes
    }

    /// [`ViewId::MAIN`]'s colour target (None before its first frame).
    pub fn colour_texture(&self) -> Option<&wgpu::Texture> {
        self.views[0].targets.as_ref().map(|t| &t.colour)
    }

    /// A view of [`ViewId::MAIN`]'s colour target, for compositing (e.g. a full-screen
    /// blit in a paint callback).
    pub fn colour_view(&self) -> Option<&wgpu::TextureView> {
        self.colour_view_of(ViewId::MAIN)
    }

    /// [`Renderer::colour_view`] of `view`.
    pub fn colour_view_of(&self, view: ViewId) -> Option<&wgpu::TextureView> {
        let vi = self.view_index(view).ok()?;
        self.views[vi].targets.as_ref().map(|t| &t.colour_view)
    }
}
