//! Maps in UV space (docs/models.md §1 conventions): heights, masks, the height → normal
//! map, and the rasteriser that visits a UV triangle's texels.

pub mod heightmap;
pub mod mask;
pub mod normal_map;
pub mod raster;
