//! The ground floor: what every other room uses and that uses nothing of the engine —
//! the error type, positioned diagnostics, cancellation, input limits, the seeded random
//! numbers, the SIMD dispatch, the strict JSON parse, small maths, maps keyed by cubes of
//! space, PNG encoding and the all-or-nothing writing of a set of files.

pub mod arc_key;
pub mod cancel;
pub mod cells;
pub mod diagnostic;
pub mod error;
pub mod json;
pub mod lab;
pub mod limits;
pub mod math;
pub mod output_set;
pub mod png;
pub mod rng;
pub(crate) mod simd;
