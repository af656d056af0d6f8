//! Shared by the GPU tests of agesim-render (each test file uses a part of it).
#![allow(dead_code)]

use agesim_core::{HeightMap, Mesh};
use agesim_render::{FrameParams, Gpu, Renderer};

pub use agesim_render::ci::gpu_or_skip;

/// A height map of `size`² from a function of (u, v).
pub fn map_from_fn(size: u32, f: impl Fn(f32, f32) -> f32) -> HeightMap {
    let mut data = Vec::new();
    for y in 0..size {
        for x in 0..size {
            data.push(f(
                agesim_core::maps::heightmap::pixel_to_u(x, size),
                agesim_core::maps::heightmap::pixel_to_v(y, size),
            ));
        }
    }
    HeightMap::from_vec(size, size, data).unwrap()
}

/// Parallel creases across v: crest 1, valley 0.
pub fn creases(size: u32, count: f32) -> HeightMap {
    map_from_fn(size, |_, v| {
        (0.5 + 0.5 * (v * count * std::f32::consts::TAU).cos()).powf(0.4)
    })
}

/// The background colour a frame clears to, as the sRGB bytes read back.
pub fn background(p: &FrameParams) -> [u8; 3] {
    let enc = |c: f32| {
        let s = if c <= 0.003_130_8 {
            c * 12.92
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        };
        (s * 255.0).round() as u8
    };
    [
        enc(p.background.x),
        enc(p.background.y),
        enc(p.background.z),
    ]
}

/// Whether a pixel is the background.
pub fn is_background(px: &image::Rgba<u8>, bg: [u8; 3]) -> bool {
    px.0[..3].iter().zip(bg).all(|(&a, b)| a.abs_diff(b) <= 2)
}

/// A renderer with `mesh` and parallel creases as its large wrinkles.
pub fn head_renderer(gpu: &Gpu, mesh: &Mesh) -> Renderer {
    let mut r = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT).unwrap();
    r.upload_mesh(mesh, 1.0).unwrap();
    r.upload_large_wrinkles(&creases(256, 40.0)).unwrap();
    r
}
