//! The map view's picture on the GPU adapter: the map and its UV layout over it drawn in
//! one unblended pass by a paint callback (`agesim_render::Blit::new_over`), instead of
//! two egui images blended over each other. On a CPU rasteriser egui's image shader and
//! blending cost every shown pixel: the map view's two images were about 10 ms of every
//! editor frame on llvmpipe (BENCHMARKS.md).

use std::sync::Arc;

use agesim_core::base::arc_key::ArcKey;
use eframe::{egui_wgpu, wgpu};

/// The textures of the last pictures shown and their bind group.
pub struct MapGpu {
    blit: Arc<agesim_render::Blit>,
    map: Option<Picture>,
    layout: Option<Picture>,
    /// A 1 × 1 transparent texture: the overlay when the layout is not shown.
    none: wgpu::TextureView,
    bound: Option<(Option<ArcKey<egui::ColorImage>>, Arc<wgpu::BindGroup>)>,
}

/// One picture's texture, and which picture it holds.
struct Picture {
    key: ArcKey<egui::ColorImage>,
    size: [usize; 2],
    texture: wgpu::Texture,
    view: wgpu::TextureView,
}

impl MapGpu {
    pub fn new(rs: &egui_wgpu::RenderState) -> Self {
        let none = texture(&rs.device, [1, 1]);
        rs.queue.write_texture(
            none.as_image_copy(),
            &[0; 4],
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4),
                rows_per_image: None,
            },
            wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 1,
            },
        );
        Self {
            blit: Arc::new(agesim_render::Blit::new_over(&rs.device, rs.target_format)),
            map: None,
            layout: None,
            none: none.create_view(&Default::default()),
            bound: None,
        }
    }

    /// The paint callback drawing `map` with `layout` over it (premultiplied, as egui's
    /// pictures are) into `rect`; each picture uploaded when it is not the one shown.
    pub fn callback(
        &mut self,
        rs: &egui_wgpu::RenderState,
        map: &Arc<egui::ColorImage>,
        layout: Option<&Arc<egui::ColorImage>>,
        rect: egui::Rect,
    ) -> egui::PaintCallback {
        let map_changed = upload(rs, &mut self.map, map);
        let layout_changed = layout.is_some_and(|l| upload(rs, &mut self.layout, l));
        let layout_key = layout.map(ArcKey::of);
        let bind_group = match (&self.bound, &self.map) {
            (Some((k, b)), _) if !map_changed && !layout_changed && *k == layout_key => b.clone(),
            (_, Some(m)) => {
                let overlay = match (layout, &self.layout) {
                    (Some(_), Some(l)) => &l.view,
                    _ => &self.none,
                };
                let b = Arc::new(self.blit.bind_over(&rs.device, &m.view, overlay));
                self.bound = Some((layout_key, b.clone()));
                b
            }
            // (`upload` always leaves a map.)
            (_, None) => Arc::new(self.blit.bind_over(&rs.device, &self.none, &self.none)),
        };
        egui_wgpu::Callback::new_paint_callback(
            rect,
            ShowMap {
                blit: self.blit.clone(),
                bind_group,
            },
        )
    }
}

/// Puts `image` in `slot`'s texture (a new one when its size changed); whether it changed.
fn upload(
    rs: &egui_wgpu::RenderState,
    slot: &mut Option<Picture>,
    image: &Arc<egui::ColorImage>,
) -> bool {
    if slot.as_ref().is_some_and(|p| p.key.is(image)) {
        return false;
    }
    let size = image.size;
    if slot.as_ref().is_none_or(|p| p.size != size) {
        let texture = texture(&rs.device, size);
        let view = texture.create_view(&Default::default());
        *slot = Some(Picture {
            key: ArcKey::of(image),
            size,
            texture,
            view,
        });
    }
    if let Some(p) = slot {
        p.key = ArcKey::of(image);
        rs.queue.write_texture(
            p.texture.as_image_copy(),
            image.as_raw(),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * size[0] as u32),
                rows_per_image: None,
            },
            wgpu::Extent3d {
                width: size[0] as u32,
                height: size[1] as u32,
                depth_or_array_layers: 1,
            },
        );
    }
    true
}

/// An RGBA8 texture of `size` (its bytes as egui's pictures hold them: sRGB-encoded,
/// premultiplied; sampled as they are).
fn texture(device: &wgpu::Device, size: [usize; 2]) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("agesim map view picture"),
        size: wgpu::Extent3d {
            width: size[0].max(1) as u32,
            height: size[1].max(1) as u32,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

/// The paint callback that blits the map view's picture into egui's render pass.
struct ShowMap {
    blit: Arc<agesim_render::Blit>,
    bind_group: Arc<wgpu::BindGroup>,
}

impl egui_wgpu::CallbackTrait for ShowMap {
    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        render_pass: &mut wgpu::RenderPass<'static>,
        _resources: &egui_wgpu::CallbackResources,
    ) {
        self.blit.draw(render_pass, &self.bind_group);
    }
}
