//! The one bridge from a project and its [`agesim_core::scene::Scene`] to the renderer:
//! the per-frame numbers ([`frame_params`]), the prepared layers of a bake and what a
//! renderer holds of them ([`Layers`], [`Uploaded`]), a headless scene drawn age after
//! age ([`HeadlessView`]), and the helpers of rendered pictures (labelled side-by-side
//! images, numbered files). The editor's worker and 3D view, `agesim render` and every
//! export go through it, so a new input is written here once.

pub mod font;
mod frame;
mod headless;
mod layers;

use std::path::{Path, PathBuf};

pub use frame::{
    HeadScale, camera, fine_blend, frame_params, pom_mode, relief_depth, tile_placements, wrap_rgb,
};
pub use headless::HeadlessView;
pub use layers::{Layers, Uploaded};

/// The side of the aged colour map baked for maps of `map_px` (the 3D view, `agesim
/// render`, `agesim bake`'s `albedo.png`, the GLB's base colour): the head's colour map's
/// own side within 1024–2048 (1024 without one), not above the maps'. The colour map holds
/// no more detail than its own size, and a spot of 2 mm is still 4–6 texels on a face at
/// 1024²; a bake at the maps' 4096² would take ≈ 5 s and 1 GB for nothing (≈ 0.2 s at
/// 1024², 0.7 s at 2048² on two cores).
pub fn colour_px(scene: &agesim_core::scene::Scene, map_px: u32) -> u32 {
    let own = scene
        .colour_map()
        .map_or(1024, |c| c.width_px.max(c.height_px));
    own.clamp(1024, 2048).min(map_px)
}

/// Images of one size side by side, each labelled in its top-left corner.
pub fn side_by_side(images: Vec<(String, image::RgbaImage)>) -> image::RgbaImage {
    let (w, h) = images.first().map_or((1, 1), |(_, i)| i.dimensions());
    let mut side = image::RgbaImage::new(w * images.len().max(1) as u32, h);
    for (i, (label, mut img)) in images.into_iter().enumerate() {
        font::draw_text(&mut img, 8, 8, 3, &label, [255, 255, 255, 255]);
        image::imageops::replace(&mut side, &img, i as i64 * i64::from(w), 0);
    }
    side
}

/// FILE.png → FILE_0003.png.
pub fn numbered(out: &Path, i: usize) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let ext = out
        .extension()
        .map_or_else(|| "png".into(), |e| e.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}_{i:04}.{ext}"))
}
