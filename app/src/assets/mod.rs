//! What makes the shipped assets (`agesim gen-assets`): the default head converted from
//! the Lee Perry-Smith scan, the mask painter, and the small CPU rasteriser that draws the
//! pictures in `assets/docs/`. The engine never links this: it reads the files these write
//! (`agesim_core::head::default`, `agesim_core::defaults`).

pub mod masks;
pub mod preview;
pub mod scan;
