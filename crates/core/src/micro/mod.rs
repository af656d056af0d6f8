//! Skin micro-relief, SPEC §3 [P]: pores, furrows between pores, fractal noise, and their
//! log-smoothed overlaps, baked into a [`HeightMap`](crate::HeightMap).
//!
//! - [`pores`]: placement (blue noise / uniform) and the profiles of eqs. 15, 3, 11;
//! - [`furrows`]: the furrow network and eq. 16;
//! - [`noise`]: periodic fBm of gradient noise (eq. 17) with a row-coherent fast path;
//! - [`overlap`]: the log-mean-exp combination of eq. 18;
//! - [`bake`]: the band-parallel baker that puts them together;
//! - `fastmath`: portable, vectorisable `exp`/`ln` used by the hot loops.

pub mod bake;
mod fastmath;
pub mod furrows;
pub mod noise;
pub mod overlap;
pub mod pores;

pub use bake::{BakeTimings, MicroRelief};
