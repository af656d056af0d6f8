//! agesim-core: the models of agesim, pure CPU (no GPU, no UI).
//!
//! Every model follows `docs/models.md` (kept in the project's shared docs); each module cites
//! the section it implements. Conventions (docs/models.md §1): UV with v up, pixel centres at
//! ((x + 0.5)/W, 1 − (y + 0.5)/H), heights in signed height units, age t ∈ [0,1].

pub mod age;
pub mod brows;
pub mod cancel;
pub mod compose;
pub mod defaults;
pub mod diagnostic;
pub mod error;
pub mod export;
pub mod fine_wrinkles;
pub mod fit;
pub mod hair;
pub mod head;
pub mod heightmap;
pub mod landmarks;
pub mod large_layer;
pub mod lashes;
pub mod limits;
pub mod mask;
pub mod mesh;
pub mod micro;
pub mod muscle;
pub mod normal_map;
pub mod project;
pub mod rng;
pub mod scene;
pub mod shape;
mod simd;
pub mod skin_colour;
pub mod surface_warp;
#[cfg(test)]
mod test_util;
pub mod transition;
pub mod wrinkle_file;

pub use error::Error;
pub use heightmap::HeightMap;
pub use mask::Mask;
pub use mesh::Mesh;
/// The instruction set the vectorised kernels run with here (for benchmark reports).
pub use simd::Level as SimdLevel;
