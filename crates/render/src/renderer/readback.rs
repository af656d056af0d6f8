//! Headless frames read back to the CPU: 8-bit images ([`Renderer::render_to_image`]) and
//! raw f32 values ([`Renderer::render_to_f32`]).

use crate::RenderError;
use crate::params::FrameParams;

use super::{Renderer, ViewId};

impl Renderer {
    /// Renders one frame offscreen and reads it back: the copy's rows are
    /// padded to 256 bytes as wgpu requires and unpadded here. Blocks until done. Needs
    /// an 8-bit RGBA or BGRA colour format.
    pub fn render_to_image(
        &mut self,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<image::RgbaImage, RenderError> {
        self.render_view_to_image(ViewId::MAIN, params, size_px)
    }

    /// [`Renderer::render_to_image`] of `view`.
    pub fn render_view_to_image(
        &mut self,
        view: ViewId,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<image::RgbaImage, RenderError> {
        let (mut pixels, bytes_per_pixel) = self.render_and_read(view, params, size_px)?;
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
        let (bytes, bytes_per_pixel) = self.render_and_read(ViewId::MAIN, params, size_px)?;
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
        view: ViewId,
        params: &FrameParams,
        size_px: (u32, u32),
    ) -> Result<(Vec<u8>, u32), RenderError> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("agesim render_to_image"),
            });
        self.encode_view(view, &mut encoder, params, size_px)?;
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
        let Some(targets) = &self.views[self.view_index(view)?].targets else {
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
