//! What leaves the engine: the normal map composed at an age as the renderer composes it,
//! and the maps written to disk (PNG, OpenEXR, texture sets).

pub mod compose;
pub mod export;
pub mod names;
