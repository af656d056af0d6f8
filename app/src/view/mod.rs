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

/// The largest aged colour map the view bakes (the 3D view and `agesim render`): at the
/// large map's size up to this, 2048² (≈ 0.7 s on two cores); exports bake theirs at
/// their own size.
pub const MAX_COLOUR_PX: u32 = 2048;

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
