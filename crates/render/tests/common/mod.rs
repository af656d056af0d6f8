//! Shared by the GPU tests of agesim-render.

use agesim_render::Gpu;

/// The GPU (lavapipe here), or `None` with a printed reason on a machine without any
/// adapter; in CI (`CI=true`) a missing adapter is a failure, never a skip.
pub fn gpu_or_skip(test: &str) -> Option<Gpu> {
    match Gpu::new() {
        Ok(gpu) => Some(gpu),
        Err(e) if std::env::var("CI").is_ok_and(|v| v == "true") => {
            panic!("{test}: CI=true but no GPU adapter: {e} (install mesa-vulkan-drivers)")
        }
        Err(e) => {
            eprintln!("{test}: skipped, {e}");
            None
        }
    }
}
