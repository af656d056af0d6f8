//! The agesim renderer (SPEC §5–§6, issue 11): wgpu 30, shared with the editor's eframe
//! device. The skin pass does parallax occlusion mapping of the large wrinkles with fine
//! wrinkles and micro-relief on top, shading a stored surface (the mesh is rasterised
//! again only when the view, the size or the mesh change); the hair pass draws every hair
//! present at age t in one instanced draw with Kajiya–Kay shading.
//!
//! Use: create one [`Renderer`] from the device, queue and colour format; upload each
//! input once and again only when it changes ([`Renderer::upload_mesh`],
//! [`Renderer::upload_large_wrinkles`], [`Renderer::upload_tile`] (micro-relief, fine
//! wrinkles), [`Renderer::upload_wrinkle_mask`],
//! [`Renderer::upload_hair`]); each frame call [`Renderer::encode`] (into the caller's
//! encoder, e.g. in an egui callback's `prepare`) with a [`FrameParams`], then composite
//! [`Renderer::colour_view`] (re-register it when [`Renderer::target_generation`]
//! changes). Headless: [`Gpu::new`] and [`Renderer::render_to_image`].
//!
//! In the editor (EGUI-0.37.md): keep the `Renderer` in egui-wgpu's `callback_resources`,
//! call `encode(egui_encoder, …)` in the callback's `prepare`, and composite the colour
//! target in `paint` (or show it through `register_native_texture` with a renderer made
//! for `Rgba8Unorm`, for which the shader writes sRGB values itself).

mod blit;
mod error;
mod f16;
mod gpu;
mod hair;
mod mesh;
mod params;
mod renderer;
pub mod shaders;
mod uniforms;

pub use blit::Blit;
pub use error::RenderError;
pub use gpu::Gpu;
pub use mesh::SurfaceScale;
pub use params::{
    Camera, DEFAULT_FINE_TILE_SIZE_M, FrameOutput, FrameParams, GrayingRampParam, HairShading,
    Light, PomMode, SPARSE_HAIR_STRIDE, SkinParams,
};
pub use renderer::{COLOUR_FORMAT, DEPTH_FORMAT, PreparedLayer, Renderer, TileLayer, Upload};
pub use uniforms::FrameUniform;
