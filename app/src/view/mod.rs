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

/// The samples per pixel along each axis [`render_supersampled`] uses for `wanted` at
/// `size`: at least 1, and no more than the largest target side allows.
pub fn supersample_factor(max_side: u32, size: (u32, u32), wanted: u32) -> u32 {
    let largest = size.0.max(size.1).max(1);
    wanted.min(max_side / largest).max(1)
}

/// Draws `params` at `size` with `factor`² samples per pixel (fewer where the device's
/// target limit allows no more: [`supersample_factor`]): the frame at `factor` times the
/// size (the hair's strands `factor` times wider, so they cover what they cover at one
/// sample), each `factor`×`factor` block averaged in linear light. Antialiasing for still
/// pictures (`agesim render`): the renderer's passes are not multisampled, so a
/// silhouette (the closed lids' seam, the ear's rim, a strand) steps from pixel to pixel
/// at one sample.
pub fn render_supersampled(
    renderer: &mut agesim_render::Renderer,
    params: &agesim_render::FrameParams,
    size: (u32, u32),
    factor: u32,
) -> Result<image::RgbaImage, agesim_render::RenderError> {
    let factor = supersample_factor(renderer.max_target_side(), size, factor);
    if factor == 1 {
        return renderer.render_to_image(params, size);
    }
    let mut big = *params;
    big.hair.width_px *= factor as f32;
    let img = renderer.render_to_image(&big, (size.0 * factor, size.1 * factor))?;
    Ok(box_downsample(&img, factor))
}

/// Each `factor`×`factor` block of an sRGB image averaged in linear light (alpha
/// averaged as it is; the colour is not weighted by it). Rows and columns beyond the
/// last whole block are dropped; a factor of 0 counts as 1.
pub fn box_downsample(img: &image::RgbaImage, factor: u32) -> image::RgbaImage {
    let factor = factor.max(1);
    use agesim_core::maps::mask::{linear_to_srgb, srgb_to_linear};
    let to_linear: Vec<f32> = (0..256).map(|c| srgb_to_linear(c as f32 / 255.0)).collect();
    let to_srgb = |c: f32| (linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0).round() as u8;
    let (w, h) = (img.width() / factor, img.height() / factor);
    let n = (factor * factor) as f32;
    image::RgbaImage::from_fn(w, h, |x, y| {
        let mut sum = [0f32; 4];
        for dy in 0..factor {
            for dx in 0..factor {
                let p = img.get_pixel(x * factor + dx, y * factor + dy).0;
                for c in 0..3 {
                    sum[c] += to_linear[usize::from(p[c])];
                }
                sum[3] += f32::from(p[3]);
            }
        }
        image::Rgba([
            to_srgb(sum[0] / n),
            to_srgb(sum[1] / n),
            to_srgb(sum[2] / n),
            (sum[3] / n).round() as u8,
        ])
    })
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A block of black and white averages to the middle of the light (sRGB 188), not of
    /// the bytes (128); the image shrinks by the factor.
    #[test]
    fn the_box_downsample_averages_in_linear_light() {
        let img = image::RgbaImage::from_fn(4, 2, |x, _| {
            let c = if x % 2 == 0 { 0 } else { 255 };
            image::Rgba([c, c, c, 255])
        });
        let small = box_downsample(&img, 2);
        assert_eq!(small.dimensions(), (2, 1));
        for p in small.pixels() {
            assert_eq!(p.0, [188, 188, 188, 255]);
        }
        // An even colour stays itself.
        let even = image::RgbaImage::from_pixel(6, 6, image::Rgba([90, 140, 200, 255]));
        assert!(
            box_downsample(&even, 3)
                .pixels()
                .all(|p| p.0 == [90, 140, 200, 255])
        );
    }
}
