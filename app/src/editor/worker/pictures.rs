//! The maps as egui pictures for the 2D view, made on the worker thread (the UI thread
//! only uploads them), each remade only when its map changed.

use std::sync::Arc;

/// Display pictures of the maps (at most [`IMAGE_MAX_PX`] on a side).
#[derive(Clone, Debug, Default)]
pub struct MapImages {
    pub large_height: Option<Arc<egui::ColorImage>>,
    pub large_normal: Option<Arc<egui::ColorImage>>,
    pub micro_height: Option<Arc<egui::ColorImage>>,
    pub micro_normal: Option<Arc<egui::ColorImage>>,
    pub transition: Option<Arc<egui::ColorImage>>,
    pub fine: Option<Arc<egui::ColorImage>>,
    /// The UV layout (triangle edges) of the chart the fibres are drawn on — the
    /// template's for a fitted head, else the mesh's — white lines on transparent.
    pub uv_layout: Option<Arc<egui::ColorImage>>,
    /// A fitted head's own UV layout (the overlay of its own maps).
    pub head_uv_layout: Option<Arc<egui::ColorImage>>,
    /// A fitted head's large-wrinkle heights in its own UV layout.
    pub large_head: Option<Arc<egui::ColorImage>>,
    /// The large-wrinkle mask.
    pub mask: Option<Arc<egui::ColorImage>>,
    /// How far the shape moves each point of the head at full age, in its own UVs
    /// (docs/models.md §13): black still, red to yellow up to [`SHAPE_FULL_MM`].
    pub shape: Option<Arc<egui::ColorImage>>,
}

/// The movement that shows as full yellow in the shape pictures, mm.
pub const SHAPE_FULL_MM: f32 = 8.0;

/// The least movement shown, as a fraction of [`SHAPE_FULL_MM`] (0.2 mm): below it a
/// region's far edge reaches only a few vertices, whose triangles would show as patches.
const SHAPE_LEAST: f32 = 0.025;

/// The heat colour of a movement `w` in [0, 1] (sRGB): dark red to yellow.
fn heat(w: f32) -> [u8; 3] {
    let w = w.clamp(0.0, 1.0);
    [
        (90.0 + 165.0 * w.min(0.5) * 2.0) as u8,
        (255.0 * (w - 0.5).max(0.0) * 2.0) as u8,
        0,
    ]
}

/// The shape's movement (`mm`, a `size`² picture in the head's UVs) as a map-view picture,
/// and over `colour` (the aged colour, same size) as the head's colour while the map view
/// shows it: where and how much the shape moves, on the head.
pub(super) fn shape_pictures(
    mm: &[f32],
    size: u32,
    colour: &agesim_core::maps::mask::HeadImage,
) -> (
    Arc<egui::ColorImage>,
    Arc<agesim_core::maps::mask::HeadImage>,
) {
    let n = size as usize;
    let step = n.div_ceil(IMAGE_MAX_PX as usize).max(1);
    let m = n / step;
    let mut pixels = Vec::with_capacity(m * m);
    for y in 0..m {
        for x in 0..m {
            let v = mm[y * step * n + x * step] / SHAPE_FULL_MM;
            let [r, g, b] = if v > SHAPE_LEAST { heat(v) } else { [0, 0, 0] };
            pixels.push(egui::Color32::from_rgb(r, g, b));
        }
    }
    let picture = Arc::new(egui::ColorImage::new([m, m], pixels));
    let mut tinted = colour.clone();
    if tinted.width_px as usize == n && tinted.height_px as usize == n {
        for (px, &v) in tinted.rgba.chunks_exact_mut(4).zip(mm) {
            let w = (v / SHAPE_FULL_MM).clamp(0.0, 1.0);
            if w > SHAPE_LEAST {
                let h = heat(w);
                // Fading in from the least shown: no edge where the field starts.
                let a = 0.8 * ((w - SHAPE_LEAST) / (1.0 - SHAPE_LEAST)).sqrt();
                for c in 0..3 {
                    px[c] = (f32::from(px[c]) * (1.0 - a) + f32::from(h[c]) * a) as u8;
                }
            }
        }
    }
    (picture, Arc::new(tinted))
}

/// The triangle edges of `mesh` in UV space, drawn into a `size`² picture (v up, row 0
/// at the top) over its colour map `colour` when it has one, both translucent over the
/// map they are shown on: the chart reads as the face it is; made once per mesh on the
/// worker.
pub(super) fn uv_layout_image(
    mesh: &agesim_core::Mesh,
    colour: Option<&agesim_core::maps::mask::HeadImage>,
    size: usize,
) -> Arc<egui::ColorImage> {
    let mut pixels = vec![egui::Color32::TRANSPARENT; size * size];
    if let Some(c) = colour.filter(|c| c.width_px > 0 && c.height_px > 0) {
        for (k, p) in pixels.iter_mut().enumerate() {
            let (x, y) = (k % size, k / size);
            let cx = (x * c.width_px as usize / size).min(c.width_px as usize - 1);
            let cy = (y * c.height_px as usize / size).min(c.height_px as usize - 1);
            let i = 4 * (cy * c.width_px as usize + cx);
            let [r, g, b] = [c.rgba[i], c.rgba[i + 1], c.rgba[i + 2]];
            *p = egui::Color32::from_rgba_unmultiplied(r, g, b, LAYOUT_COLOUR_ALPHA);
        }
    }
    let uv = mesh.uvs();
    let to_px = |p: glam::Vec2| ((p.x * size as f32), ((1.0 - p.y) * size as f32));
    let line = egui::Color32::from_rgba_unmultiplied(255, 255, 255, 40);
    for [a, b, c] in mesh.triangles() {
        for (i, j) in [(a, b), (b, c), (c, a)] {
            let (x0, y0) = to_px(uv[i as usize]);
            let (x1, y1) = to_px(uv[j as usize]);
            let steps = (x1 - x0).abs().max((y1 - y0).abs()).ceil().max(1.0) as usize;
            // UV seams jump across the layout: such edges are not drawn.
            if steps > size / 4 {
                continue;
            }
            for k in 0..=steps {
                let t = k as f32 / steps as f32;
                let (x, y) = (x0 + (x1 - x0) * t, y0 + (y1 - y0) * t);
                if x >= 0.0 && y >= 0.0 && (x as usize) < size && (y as usize) < size {
                    pixels[y as usize * size + x as usize] = line;
                }
            }
        }
    }
    Arc::new(egui::ColorImage::new([size, size], pixels))
}

/// A fitted head's colour map carried onto the template's chart, `size`² (rows from the
/// top): each texel of the head's own layout inside one of its islands (`c`, the
/// correspondence) writes its colour at its template UV; template texels no head texel
/// reached take the nearest written one's. So the chart the fibres are edited on shows
/// the artist's own face.
pub(super) fn colour_on_template(
    c: &agesim_core::head::fit::Correspondence,
    colour: &agesim_core::maps::mask::HeadImage,
    size: usize,
) -> agesim_core::maps::mask::HeadImage {
    let mut rgba = vec![0u8; size * size * 4];
    let mut written = vec![false; size * size];
    let n = c.size();
    let (w, h) = (colour.width_px as usize, colour.height_px as usize);
    for y in 0..n {
        for x in 0..n {
            let Some(t) = c.get(x, y).filter(|_| c.covered(x, y)) else {
                continue;
            };
            // The head texel's colour (its own UV: the texel's centre).
            let (cx, cy) = (
                (x as usize * w / n as usize).min(w.saturating_sub(1)),
                (y as usize * h / n as usize).min(h.saturating_sub(1)),
            );
            let (tx, ty) = (
                ((t.x * size as f32) as usize).min(size - 1),
                (((1.0 - t.y) * size as f32).max(0.0) as usize).min(size - 1),
            );
            let (src, dst) = (4 * (cy * w + cx), ty * size + tx);
            if let Some(px) = colour.rgba.get(src..src + 4) {
                rgba[4 * dst..4 * dst + 4].copy_from_slice(px);
                written[dst] = true;
            }
        }
    }
    let mut texels: Vec<[u8; 4]> = rgba
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect();
    agesim_core::head::fit::pad(&mut texels, &written, size);
    agesim_core::maps::mask::HeadImage {
        width_px: size as u32,
        height_px: size as u32,
        rgba: texels.into_iter().flatten().collect(),
    }
}

/// How opaque a chart's colour map is over the map shown under it.
const LAYOUT_COLOUR_ALPHA: u8 = 110;

/// Side of the pictures of the 2D view; larger maps are shown subsampled.
pub const IMAGE_MAX_PX: u32 = 1024;

/// Grey picture of `values` (w × h), spanning their own range.
pub(super) fn grey_image(w: u32, h: u32, values: &[f32]) -> Arc<egui::ColorImage> {
    let step = w
        .div_ceil(IMAGE_MAX_PX)
        .max(h.div_ceil(IMAGE_MAX_PX))
        .max(1) as usize;
    let (iw, ih) = (w as usize / step, h as usize / step);
    let (lo, hi) = values
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let inv = if hi > lo { 255.0 / (hi - lo) } else { 0.0 };
    let mut pixels = Vec::with_capacity(iw * ih);
    for y in 0..ih {
        for x in 0..iw {
            let v = values[y * step * w as usize + x * step];
            let g = ((v - lo) * inv) as u8;
            pixels.push(egui::Color32::from_gray(g));
        }
    }
    Arc::new(egui::ColorImage::new([iw, ih], pixels))
}

/// RGB picture of interleaved bytes with `channels` per pixel (3 or 4; alpha ignored).
pub(super) fn rgb_image(w: u32, h: u32, bytes: &[u8], channels: usize) -> Arc<egui::ColorImage> {
    let step = w
        .div_ceil(IMAGE_MAX_PX)
        .max(h.div_ceil(IMAGE_MAX_PX))
        .max(1) as usize;
    let (iw, ih) = (w as usize / step, h as usize / step);
    let mut pixels = Vec::with_capacity(iw * ih);
    for y in 0..ih {
        for x in 0..iw {
            let i = (y * step * w as usize + x * step) * channels;
            pixels.push(egui::Color32::from_rgb(
                bytes[i],
                bytes[i + 1],
                bytes[i + 2],
            ));
        }
    }
    Arc::new(egui::ColorImage::new([iw, ih], pixels))
}
