//! GPU textures of the renderer: a height layer converted on any thread (f16 texels and
//! their mip chain), and the 2D textures made from it or from RGBA8 pictures.

use agesim_core::HeightMap;
use wgpu::util::DeviceExt as _;

use crate::f16::to_f16_bytes;

#[cfg(doc)]
use super::Renderer;

/// A height texture (the view keeps its texture alive).
pub(super) struct Layer {
    pub(super) view: wgpu::TextureView,
}

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
    /// The large wrinkles' depth map, clamped to [−1, 1], as the height field 1 − depth (see
    /// [`Renderer::upload_large_wrinkles`]), one level.
    pub fn large_wrinkles(heights01: &HeightMap) -> Self {
        // The map is the wrinkles' depth (0 = unwrinkled skin); the shader's height field
        // has the polygon on top (1), so skin stays on the polygon and wrinkles cut in. A
        // fold's raised side (depth < 0) rises above 1: the march meets it at once, its
        // normals show it.
        let data: Vec<f32> = heights01
            .data()
            .iter()
            .map(|h| 1.0 - h.clamp(-1.0, 1.0))
            .collect();
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
pub(super) fn prepare_r16f((width, height): (u32, u32), data: &[f32], mips: bool) -> PreparedLayer {
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

/// A flat tangent-space normal, (0, 0, 1) encoded.
pub(super) const FLAT_NORMAL: [u8; 4] = [128, 128, 255, 255];

/// An RGBA8 texture of one level (a head's colour map, `srgb`, or normal map).
pub(super) fn create_rgba8(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    size: (u32, u32),
    rgba: &[u8],
    srgb: bool,
) -> Layer {
    let format = if srgb {
        wgpu::TextureFormat::Rgba8UnormSrgb
    } else {
        wgpu::TextureFormat::Rgba8Unorm
    };
    create_texture(device, queue, label, size, 1, format, rgba)
}

/// A 2D texture of `levels` mip levels (their bytes one after another) and its view.
fn create_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    (width, height): (u32, u32),
    levels: u32,
    format: wgpu::TextureFormat,
    bytes: &[u8],
) -> Layer {
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: levels,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytes,
    );
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some(label),
        ..Default::default()
    });
    Layer { view }
}

/// A 1-channel f16 texture (filterable everywhere) holding a prepared layer, with its mip
/// chain when it has one (halving while both sides are even): `textureSampleGrad` then
/// averages micro-relief and fine wrinkles smaller than a pixel instead of aliasing them
/// into speckle. The large-wrinkle map has no mips: POM marches the exact height field
/// (`tests/pom_reference.rs`), and at ≈ 1 texel per pixel on a whole-head view it does not
/// alias much.
pub(super) fn create_r16f(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    layer: &PreparedLayer,
) -> Layer {
    create_texture(
        device,
        queue,
        label,
        (layer.width, layer.height),
        layer.levels,
        wgpu::TextureFormat::R16Float,
        &layer.bytes,
    )
}
