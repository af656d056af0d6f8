//! Wrinkles: the muscle-fibre model of large wrinkles (docs/models.md §2), the wrinkle
//! description file (§3), a group laid straight on the surface, the large layer kept
//! between bakes, and the tileable fine wrinkles (§8).

pub mod fibre_params;
pub mod fine_wrinkles;
pub mod large_layer;
pub mod muscle;
pub mod surface_warp;
pub mod wrinkle_file;
