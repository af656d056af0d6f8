//! Where on the head the micro-relief lies (docs/models.md §4 "Where on the head"): a
//! weight per vertex from the template's regions, drawn over the head's UVs as a map
//! that the view and the exported normal map read alike.
//!
//! The tile repeats over the head's UVs; the lips' red has no pores or furrows between
//! them (it is mucosa, not skin), and on the smooth, frontally lit full lower lips of the
//! African heads the tile's pores, elongated along the tension lines with age, drew
//! "vertical hatching on the lower lip" (blind rounds 55–59; not the UVs' stretch: the
//! lower lip's triangles are no more anisotropic than the cheeks').

use glam::{Vec2, Vec3};

use crate::base::error::Error;
use crate::head::frame::Regions;
use crate::maps::heightmap::check_size;
use crate::maps::mask::HeadImage;

/// How much of the micro-relief the lips' red keeps: its fine texture, not pores.
pub const ON_LIPS: f32 = 0.2;

/// How many pixels beyond a triangle's edge its values are drawn (so that bilinear
/// sampling at a chart's border reads the chart's own weights).
const GUARD_PX: f32 = 2.0;

/// How much a vertex is the lips' red (template point `t`, template metres; `None` off
/// the template), its lower lip's red reaching `lower` further down than the template's
/// ([`Regions::lips_reaching`]).
pub fn lips_at(regions: &Regions, t: Option<Vec3>, lower: f32) -> f32 {
    match t {
        Some(t) if regions.in_front(t) > 0.0 => regions.lips_reaching(t, lower),
        _ => 0.0,
    }
}

/// The micro-relief's weight where the lips' red is `lips` (0–1): 1 on the skin,
/// [`ON_LIPS`] on the red.
pub fn of_lips(lips: f32) -> f32 {
    1.0 - (1.0 - ON_LIPS) * lips.clamp(0.0, 1.0)
}

/// The weight drawn over the UV square as a `size`² map (RGBA8, grey: the weight × 255
/// in every colour channel, alpha 255; row 0 at the top, v up), from each vertex's
/// [`lips_at`] (`lips`) over the triangles of `indices`: each texel the barycentric mix
/// of its triangle's (or, within [`GUARD_PX`] outside every triangle, the nearest one's).
pub fn map(uvs: &[Vec2], indices: &[u32], lips: &[f32], size: u32) -> Result<HeadImage, Error> {
    check_size(size, size)?;
    let n = size as usize;
    let mut value = vec![0.0f32; n * n];
    let mut distance = vec![f32::INFINITY; n * n];
    for tri in indices.chunks_exact(3) {
        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| i as usize);
        let (Some(&ua), Some(&ub), Some(&uc)) = (uvs.get(a), uvs.get(b), uvs.get(c)) else {
            continue;
        };
        let w = [a, b, c].map(|i| lips.get(i).copied().unwrap_or(0.0));
        if w.iter().all(|&l| l <= 0.0) {
            continue;
        }
        crate::maps::raster::raster_uv([ua, ub, uc], size, GUARD_PX, |x, y, bary, outside| {
            let i = y * n + x;
            if outside < distance[i] {
                distance[i] = outside;
                // Outside the triangle the values are extrapolated: clamped to theirs.
                let mixed = bary[0] * w[0] + bary[1] * w[1] + bary[2] * w[2];
                value[i] = mixed.clamp(0.0, w[0].max(w[1]).max(w[2]));
            }
        });
    }
    let rgba = value
        .iter()
        .flat_map(|&l| {
            let g = (of_lips(l) * 255.0).round() as u8;
            [g, g, g, 255]
        })
        .collect();
    Ok(HeadImage {
        width_px: size,
        height_px: size,
        rgba,
    })
}

/// The weight of `map` at (u, v): its red, bilinear between texel centres, wrapping in u
/// and clamped in v, as the view's sampler reads it ([`HeadImage::rgb_at`]).
pub fn sample(map: &HeadImage, u: f32, v: f32) -> f32 {
    map.rgb_at(u, v).x / 255.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weights_are_drawn_where_their_triangle_lies() {
        // One triangle over the lower left half of the UV square, its weights 0, 1, 1.
        let uvs = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
        ];
        let lips = [1.0, 0.0, 0.0];
        let map = map(&uvs, &[0, 1, 2], &lips, 64).unwrap();
        // Near the corner on the lips' red, about ON_LIPS; at the far corner's side, about 1.
        assert!((sample(&map, 0.02, 0.02) - ON_LIPS).abs() < 0.1);
        assert!(sample(&map, 0.9, 0.05) > 0.85);
        // Midway along the edge from the first corner to the second: half the way.
        let half = 0.5 * (1.0 + ON_LIPS);
        assert!((sample(&map, 0.5, 0.02) - half).abs() < 0.06);
        // Beyond the guard band (the upper right half): 1, no triangle there.
        assert_eq!(sample(&map, 0.9, 0.9), 1.0);
        // All weights 1: nothing drawn at all.
        let flat = super::map(&uvs, &[0, 1, 2], &[0.0; 3], 16).unwrap();
        assert!(flat.rgba.iter().all(|&b| b == 255));
        assert!(super::map(&uvs, &[0, 1, 2], &lips, 80_000).is_err());
    }

    #[test]
    fn the_lips_red_keeps_a_fifth_and_the_brow_all() {
        let regions = Regions::template().unwrap();
        let marks = &crate::head::fit::template().landmarks;
        let mouth = 0.5 * (marks.get("cheilion_r").unwrap() + marks.get("cheilion_l").unwrap());
        // In front of the mouth's middle: the red of the lips.
        let lips = lips_at(regions, Some(mouth + Vec3::new(0.0, 0.0, 0.008)), 0.0);
        assert!((of_lips(lips) - ON_LIPS).abs() < 0.05, "{lips}");
        let glabella = marks.get("glabella").unwrap();
        assert_eq!(lips_at(regions, Some(glabella), 0.0), 0.0);
        assert_eq!(lips_at(regions, None, 0.0), 0.0);
        assert_eq!(of_lips(0.0), 1.0);
        // Below the lower lip's red: skin, unless the lower lip reaches further down.
        let below = mouth + Vec3::new(0.0, -0.012, 0.006);
        assert_eq!(lips_at(regions, Some(below), 0.0), 0.0);
        assert!(lips_at(regions, Some(below), 0.2) > 0.5);
    }
}
