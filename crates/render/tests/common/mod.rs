//! Shared by the GPU tests of agesim-render.

pub use agesim_render::ci::gpu_or_skip;
