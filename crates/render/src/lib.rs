//! The agesim renderer (docs/models.md §10 and §9): wgpu 30, shared with the editor's
//! eframe device. The skin pass does parallax occlusion mapping of the large wrinkles with
//! fine wrinkles and micro-relief on top, shading a stored surface (the mesh is rasterised
//! again only when the view, the size or the mesh change); the hair pass draws every hair
//! present at age t in one instanced draw with Kajiya–Kay shading.
//!
//! Use: create one [`Renderer`] from the device, queue and colour format; upload each
//! input once and again only when it changes ([`Renderer::upload_mesh`],
//! [`Renderer::upload_large_wrinkles`], [`Renderer::upload_tile`] (micro-relief, fine
//! wrinkles), [`Renderer::upload_hair`], or [`Renderer::upload_prepared`] for layers
//! converted on another thread); each frame call [`Renderer::encode`] with a
//! [`FrameParams`] (everything per frame: camera, light, skin, where the tiles lie, hair,
//! age), then show [`Renderer::colour_view`] (the editor blits it into egui's pass with
//! [`Blit`] from a paint callback; re-bind it when [`Renderer::target_generation`]
//! changes). Headless: [`Gpu::new`] and [`Renderer::render_to_image`].

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
pub use gpu::{Gpu, ci};
pub use params::{
    Camera, DEFAULT_FINE_TILE_SIZE_M, FrameOutput, FrameParams, GrayingRampParam, HairShading,
    Light, PomMode, SPARSE_HAIR_STRIDE, SkinParams, TilePlacement,
};
pub use renderer::{
    COLOUR_FORMAT, DEPTH_FORMAT, PreparedLayer, Renderer, ShapeUpload, TileLayer, Upload, ViewId,
};
pub use uniforms::FrameUniform;
