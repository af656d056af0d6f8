//! The crate's one error type.

/// What can go wrong in the renderer.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No GPU adapter (not even lavapipe, the CPU Vulkan driver) was found.
    #[error("no GPU adapter available: {0}")]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("cannot create a GPU device: {0}")]
    Device(String),
    /// A size is zero or larger than the device allows.
    #[error("{what} is {width}×{height} px; it must be between 1 and {max} px per side")]
    InvalidSize {
        what: &'static str,
        width: u32,
        height: u32,
        max: u32,
    },
    /// A mesh with nothing to draw, or with mismatched attribute arrays.
    #[error("invalid mesh: {0}")]
    InvalidMesh(String),
    /// A parameter outside its documented range (NaN included).
    #[error("{what} = {value} is outside {range}")]
    OutOfRange {
        what: &'static str,
        value: f32,
        range: &'static str,
    },
    /// Reading the rendered frame back from the GPU failed.
    #[error("reading the frame back failed: {0}")]
    Readback(String),
    /// An input from agesim-core was rejected by core's own checks.
    #[error(transparent)]
    Core(#[from] agesim_core::Error),
    /// The GPU reported a validation or out-of-memory error.
    #[error("GPU error: {0}")]
    Gpu(String),
}
