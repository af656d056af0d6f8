//! The aging layers. Each room is one layer and imports none of the others: they share only
//! what lies below them (`base`, `maps`, `head`, `age`). The scene (`crate::scene`) is the
//! one module that knows them all.
//!
//! - `wrinkles`: large wrinkles (muscle fibres, wrinkle files, the surface warp) and the
//!   tileable fine wrinkles;
//! - `micro`: pores, furrows and fractal noise;
//! - `skin_colour`: the aged base colour;
//! - `shape`: regions that descend, deflate and bulge, their rolls, relief and occlusion;
//! - `hair`: the transition texture, the instances and graying, brows and lashes.

pub mod hair;
pub mod micro;
pub mod shape;
pub mod skin_colour;
pub mod wrinkles;
