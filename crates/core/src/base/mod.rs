//! The ground floor: what every other room uses and that uses nothing of the engine —
//! the error type, positioned diagnostics, cancellation, input limits, the seeded random
//! numbers, the SIMD dispatch and the strict JSON parse.

pub mod cancel;
pub mod diagnostic;
pub mod error;
pub mod json;
pub mod limits;
pub mod math;
pub mod rng;
pub(crate) mod simd;
