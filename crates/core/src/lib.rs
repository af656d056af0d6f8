//! agesim-core: the models of agesim, pure CPU (no GPU, no UI).
//!
//! Every model follows `docs/models.md` (kept in the project's shared docs); each module cites
//! the section it implements. Conventions (docs/models.md §1): UV with v up, pixel centres at
//! ((x + 0.5)/W, 1 − (y + 0.5)/H), heights in signed height units, age t ∈ [0,1].
//!
//! The rooms, from the ground up; each imports only from the rooms above it in this list:
//!
//! - [`base`]: error, diagnostics, cancellation, limits, random numbers, SIMD, strict JSON;
//! - [`maps`]: height maps, masks, normal maps, the UV rasteriser;
//! - [`age`]: the age model;
//! - [`head`]: the mesh, the default head, landmarks, the fit, the face frame;
//! - [`defaults`]: the default assets built into the binary;
//! - [`layers`]: the aging layers (wrinkles, micro-relief, colour, shape, hair), none
//!   importing another;
//! - [`output`]: the composed normal map and the files written;
//! - [`project`]: the project file and its one field table;
//! - [`scene`]: the pipeline, the one room that knows every layer.

pub mod age;
pub mod base;
pub mod defaults;
pub mod head;
pub mod layers;
pub mod maps;
pub mod output;
pub mod project;
pub mod scene;
#[cfg(test)]
mod test_util;

pub use base::error::Error;
/// The instruction set the vectorised kernels run with here (for benchmark reports).
pub use base::simd::Level as SimdLevel;
pub use head::mesh::Mesh;
pub use maps::heightmap::HeightMap;
pub use maps::mask::Mask;
