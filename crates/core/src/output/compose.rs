//! The head's tangent-space normal map at one age, composed from the layers the way the
//! renderer's skin pass composes them (docs/models.md "Rendering"), without parallax: the
//! exported GLB's `normalTexture`.
//!
//! - Large wrinkles: the normal of the normalised heights by central differences, with
//!   the relief depth `disp_scale` (docs/models.md §5).
//! - Fine wrinkles: the tile's normal in the large wrinkles' frame, blended in by the age.
//! - Micro-relief: the tile's normal on top by reoriented normal mapping.
//!
//! The tiles repeat a whole number of times across the UV square (as in the renderer)
//! and are box-filtered to about one texel per output pixel first (the GPU's mip level).
//! A GPU test (`crates/render/tests/compose.rs`) compares this with the skin pass.

use glam::Vec3;
use rayon::prelude::*;

use crate::Error;
use crate::base::cancel::CancelToken;
use crate::maps::heightmap::{self, HeightMap};
use crate::maps::normal_map::encode_unorm8;

/// How much a crease's bottom is darkened per unit of depth below the skin around it
/// (docs/models.md §10 "Cavity occlusion"; the skin shader's `CAVITY`).
pub const CAVITY: f32 = 2.0;
/// The most a cavity darkens.
pub const CAVITY_MAX: f32 = 0.7;
/// The relief depth (UV units) at which [`CAVITY`] applies in full.
pub const CAVITY_REFERENCE_DISP: f32 = 0.005;
/// The radius of the ring of skin a point's depth is compared with, in relief depths
/// (`disp_scale`; about 1.5 mm on the default head): a crease narrower than it is a
/// cavity over its whole width, a wider hollow or fold only along its sharp bottom.
pub const CAVITY_RING: f32 = 0.5;
/// How much rougher the bottom of the deepest crease (a cavity of [`CAVITY_MAX`]) is than
/// the open skin around it (docs/models.md §10 "Crease roughness"): a furrow's floor is
/// dry, uneven stratum corneum that keeps no sebum film, so it does not shine.
pub const CREASE_ROUGHNESS: f32 = 0.2;
/// The ring's eight directions, 45° apart, starting along +u (the shader's order).
const RING: [[f32; 2]; 8] = [
    [1.0, 0.0],
    [
        std::f32::consts::FRAC_1_SQRT_2,
        std::f32::consts::FRAC_1_SQRT_2,
    ],
    [0.0, 1.0],
    [
        -std::f32::consts::FRAC_1_SQRT_2,
        std::f32::consts::FRAC_1_SQRT_2,
    ],
    [-1.0, 0.0],
    [
        -std::f32::consts::FRAC_1_SQRT_2,
        -std::f32::consts::FRAC_1_SQRT_2,
    ],
    [0.0, -1.0],
    [
        std::f32::consts::FRAC_1_SQRT_2,
        -std::f32::consts::FRAC_1_SQRT_2,
    ],
];

/// The ambient occlusion of a point `local` deeper than the mean of the ring around it
/// (normalised depths, see [`local_depth`]) drawn `disp_scale` deep:
/// 1 − min(CAVITY · local · disp_scale / 0.005, 0.7), as the skin pass darkens it.
pub fn cavity(local: f32, disp_scale: f32) -> f32 {
    let d = local.max(0.0) * disp_scale.max(0.0) / CAVITY_REFERENCE_DISP;
    1.0 - (CAVITY * d).clamp(0.0, CAVITY_MAX)
}

/// How much deeper texel (`x`, `y`) of the normalised depth map `large` lies than the
/// mean of the eight points [`CAVITY_RING`] · `disp_scale` UV units around it, each depth
/// clamped to [0, 1] (a fold's raised side counts as open skin) and sampled bilinearly as
/// the view's sampler does (u wraps, v clamps). 0 or more.
pub fn local_depth(large: &HeightMap, x: u32, y: u32, disp_scale: f32) -> f32 {
    let (w, h) = (large.width_px(), large.height_px());
    let depth = |x: u32, y: u32| large.get(x, y).clamp(0.0, 1.0);
    // Open skin (most of a head) is no deeper than any ring: nothing to sample.
    let here = depth(x, y);
    if here <= 0.0 {
        return 0.0;
    }
    let r = CAVITY_RING * disp_scale.max(0.0);
    let mut ring = 0.0;
    for [du, dv] in RING {
        // Texel space: u to the right, v up (row 0 at v = 1).
        let fx = x as f32 + du * r * w as f32;
        let fy = y as f32 - dv * r * h as f32;
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = (fx - x0, fy - y0);
        let wrap = |i: f32| (i as i64).rem_euclid(i64::from(w)) as u32;
        let clamp = |j: f32| (j as i64).clamp(0, i64::from(h) - 1) as u32;
        let (xa, xb, ya, yb) = (wrap(x0), wrap(x0 + 1.0), clamp(y0), clamp(y0 + 1.0));
        let top = depth(xa, ya) * (1.0 - tx) + depth(xb, ya) * tx;
        let bottom = depth(xa, yb) * (1.0 - tx) + depth(xb, yb) * tx;
        ring += top * (1.0 - ty) + bottom * ty;
    }
    (here - ring / 8.0).max(0.0)
}

/// The occlusion map of a large-wrinkle depth map, 8-bit grey (255 = open skin): the
/// exported GLB's `occlusionTexture`, so the exported head darkens its creases as the view
/// does.
///
/// [`local_depth`] per texel, its eight ring taps found once: a ring point lies the same
/// whole texels and fraction from every texel, so each tap is four loads with fixed
/// weights; open skin (no depth) is skipped. Row by row on every core.
pub fn occlusion_map(large: &HeightMap, disp_scale: f32) -> Vec<u8> {
    let (w, h) = (large.width_px() as usize, large.height_px() as usize);
    let r = CAVITY_RING * disp_scale.max(0.0);
    // Per ring point: the whole-texel offset (x, y) and the bilinear fractions.
    let taps = RING.map(|[du, dv]| {
        let (cx, cy) = (du * r * w as f32, -dv * r * h as f32);
        let (fx, fy) = (cx.floor(), cy.floor());
        (fx as i64, fy as i64, cx - fx, cy - fy)
    });
    let data = large.data();
    let depth = |x: usize, y: usize| data[y * w + x].clamp(0.0, 1.0);
    let mut out = vec![255u8; w * h];
    out.par_chunks_mut(w.max(1))
        .enumerate()
        .for_each(|(y, row)| {
            for (x, ao) in row.iter_mut().enumerate() {
                let here = depth(x, y);
                if here <= 0.0 {
                    continue;
                }
                let mut ring = 0.0;
                for &(ox, oy, tx, ty) in &taps {
                    let xa = (x as i64 + ox).rem_euclid(w as i64) as usize;
                    let xb = (xa + 1) % w;
                    let clamp = |j: i64| j.clamp(0, h as i64 - 1) as usize;
                    let (ya, yb) = (clamp(y as i64 + oy), clamp(y as i64 + oy + 1));
                    let top = depth(xa, ya) * (1.0 - tx) + depth(xb, ya) * tx;
                    let bottom = depth(xa, yb) * (1.0 - tx) + depth(xb, yb) * tx;
                    ring += top * (1.0 - ty) + bottom * ty;
                }
                let local = (here - ring / 8.0).max(0.0);
                *ao = (cavity(local, disp_scale) * 255.0).round() as u8;
            }
        });
    out
}

/// The skin's roughness where the cavity occlusion is `ao` (1 = open skin, down to
/// 1 − [`CAVITY_MAX`]): `roughness` on open skin, up to [`CREASE_ROUGHNESS`] rougher at the
/// bottom of the deepest crease, as the skin pass shades it.
pub fn crease_roughness(roughness: f32, ao: f32) -> f32 {
    let loss = (1.0 - ao).clamp(0.0, CAVITY_MAX);
    (roughness + CREASE_ROUGHNESS * loss / CAVITY_MAX).clamp(0.0, 1.0)
}

/// The skin's occlusion, roughness and metallic map as glTF packs them (one RGB texture:
/// red the occlusion, [`occlusion_map`]; green the roughness, [`crease_roughness`] of the
/// skin's `roughness` at this age; blue the metallic, 0): the exported GLB's
/// `occlusionTexture` and `metallicRoughnessTexture`, 8-bit RGB over `large`'s texels.
pub fn orm_map(large: &HeightMap, disp_scale: f32, roughness: f32) -> Vec<u8> {
    occlusion_map(large, disp_scale)
        .par_iter()
        .flat_map_iter(|&ao| {
            let r = crease_roughness(roughness, f32::from(ao) / 255.0);
            [ao, (r * 255.0).round() as u8, 0]
        })
        .collect()
}

/// A height tile repeated over the UV square.
#[derive(Clone, Copy, Debug)]
pub struct RepeatedTile<'a> {
    pub heights: &'a HeightMap,
    /// Whole repeats across the UV square, along u and v
    /// ([`crate::head::mesh::SurfaceScale::repeats`]).
    pub repeats: [f32; 2],
    /// UV units of the tile per height unit (docs/models.md §5's s).
    pub strength: f32,
}

/// What the composition reads: every layer optional.
#[derive(Clone, Copy, Debug, Default)]
pub struct Layers<'a> {
    /// The large-wrinkle map, normalised: the depth below the skin (1 = the deepest point
    /// of a full-depth wrinkle; the surface is −depth, cut in).
    pub large: Option<&'a HeightMap>,
    /// The relief depth of a normalised height of 1, UV units (`view.disp_scale` ×
    /// `large.depth`).
    pub disp_scale: f32,
    pub fine: Option<RepeatedTile<'a>>,
    /// The fine-wrinkle blend in [0, 1] (0: no fine wrinkles).
    pub fine_blend: f32,
    pub micro: Option<RepeatedTile<'a>>,
    /// Where the micro-relief lies ([`crate::layers::micro::weight`]): its slopes times the
    /// map's weight at each texel; `None`: the whole tile everywhere.
    pub micro_weight: Option<&'a crate::maps::mask::HeadImage>,
    /// The head's own tangent-space normal map (its green down when the flag is set):
    /// the base every layer is combined onto by reoriented normal mapping.
    pub head_normal: Option<(&'a crate::maps::mask::HeadImage, bool)>,
}

/// The composed tangent-space normal map, `size_px`² over the UV square, OpenGL
/// convention (green = +v), RGB8, row 0 at the top (v = 1).
pub fn normal_map(
    layers: &Layers<'_>,
    size_px: u32,
    cancel: &CancelToken,
) -> Result<Vec<u8>, Error> {
    heightmap::check_size(size_px, size_px)?;
    if let Some(l) = layers.large
        && l.width_px() != l.height_px()
    {
        return Err(Error::InvalidValue {
            what: "large-wrinkle map".into(),
            value: format!("{}×{}", l.width_px(), l.height_px()),
            expected: "a square map over the UV square".into(),
        });
    }
    let n = size_px as usize;
    let large = layers.large.map(|l| (l.data(), l.width_px() as usize));
    let disp = layers.disp_scale;
    let fine_blend = layers.fine_blend.clamp(0.0, 1.0);
    let micro = layers.micro.map(|t| Placed::new(&t, size_px)).transpose()?;
    let fine = match layers.fine {
        Some(t) if fine_blend > 0.0 => Some(Placed::new(&t, size_px)?),
        _ => None,
    };
    let mut rgb = vec![0u8; n * n * 3];
    rgb.par_chunks_mut(n * 3)
        .enumerate()
        .try_for_each(|(y, row)| -> Result<(), Error> {
            if y % 64 == 0 {
                cancel.check()?;
            }
            for (x, px) in row.chunks_exact_mut(3).enumerate() {
                let n_large = match large {
                    Some((h, side)) => large_normal(h, side, x * side / n, y * side / n, disp),
                    None => Vec3::Z,
                };
                let mut n_ts = n_large;
                if let Some(f) = &fine {
                    let nf = f.tile.normal(f.columns[x], f.rows[y]);
                    n_ts = n_large.lerp(in_frame(n_large, nf), fine_blend).normalize();
                }
                let (u, v) = (
                    (x as f32 + 0.5) / n as f32,
                    1.0 - (y as f32 + 0.5) / n as f32,
                );
                if let Some(m) = &micro {
                    let mut nm = m.tile.normal(m.columns[x], m.rows[y]);
                    if let Some(map) = layers.micro_weight {
                        // The slopes scaled: the tile's strength times the weight.
                        let w = crate::layers::micro::weight::sample(map, u, v);
                        nm = Vec3::new(nm.x * w, nm.y * w, nm.z).normalize_or(Vec3::Z);
                    }
                    n_ts = rnm(n_ts, nm);
                }
                if let Some((head, green_down)) = layers.head_normal {
                    n_ts = rnm(head.normal_at(u, v, green_down), n_ts);
                }
                for (c, value) in px.iter_mut().zip(n_ts.to_array()) {
                    *c = encode_unorm8(value);
                }
            }
            Ok(())
        })?;
    Ok(rgb)
}

/// The large-wrinkle normal at texel (x, y) of a `side`² depth map (row 0 = top, v up):
/// central differences of the height −depth, the neighbours clamped at the border.
fn large_normal(h: &[f32], side: usize, x: usize, y: usize, disp: f32) -> Vec3 {
    let row = |y: usize| &h[y * side..(y + 1) * side];
    let (left, right) = (x.saturating_sub(1), (x + 1).min(side - 1));
    let (up, down) = (y.saturating_sub(1), (y + 1).min(side - 1));
    let here = row(y);
    let du = (here[right] - here[left]) * 0.5 * side as f32;
    let dv = (row(up)[x] - row(down)[x]) * 0.5 * side as f32;
    Vec3::new(disp * du, disp * dv, 1.0).normalize()
}

/// A fine-wrinkle normal expressed in the large wrinkles' tangent frame.
fn in_frame(n_large: Vec3, detail: Vec3) -> Vec3 {
    let t = Vec3::new(n_large.z, 0.0, -n_large.x).normalize();
    let b = Vec3::new(0.0, n_large.z, -n_large.y).normalize();
    (t * detail.x + b * detail.y + n_large * detail.z).normalize()
}

/// Reoriented normal mapping (Barré-Brisebois & Hill 2012), as in `shaders/skin.wgsl`.
fn rnm(base: Vec3, detail: Vec3) -> Vec3 {
    let t = base + Vec3::Z;
    let u = detail * Vec3::new(-1.0, -1.0, 1.0);
    (t * t.dot(u) / t.z - u).normalize()
}

/// A tile with its column and row taps on the output map.
struct Placed {
    tile: Tile,
    columns: Vec<(usize, usize, f32)>,
    rows: Vec<(usize, usize, f32)>,
}

impl Placed {
    fn new(t: &RepeatedTile<'_>, size_px: u32) -> Result<Self, Error> {
        let map = t.heights;
        // Texels of the tile per output pixel; box-filter down to about one.
        let per_px = map.width_px() as f32 * t.repeats[0].max(t.repeats[1]) / size_px as f32;
        let side = map.width_px().min(map.height_px());
        let factor = (1..=(per_px.floor() as u32).clamp(1, side))
            .rev()
            .find(|f| map.width_px().is_multiple_of(*f) && map.height_px().is_multiple_of(*f))
            .unwrap_or(1);
        let filtered;
        let map = if factor > 1 {
            filtered = map.downsample_box(factor)?;
            &filtered
        } else {
            map
        };
        let tile = Tile::new(map, t.repeats, t.strength);
        Ok(Self {
            columns: tile.taps(size_px, false),
            rows: tile.taps(size_px, true),
            tile,
        })
    }
}

/// A height tile's tangent-space normals (docs/models.md §5, central differences on the
/// wrapped tile), made once per texel, then interpolated per output pixel.
struct Tile {
    normals: Vec<Vec3>,
    width: usize,
    height: usize,
    repeats: [f32; 2],
}

impl Tile {
    fn new(map: &HeightMap, repeats: [f32; 2], strength: f32) -> Self {
        let (w, h) = (map.width_px() as usize, map.height_px() as usize);
        let d = map.data();
        let mut normals = Vec::with_capacity(w * h);
        for y in 0..h {
            let (up, down) = ((y + h - 1) % h, (y + 1) % h);
            for x in 0..w {
                let (left, right) = ((x + w - 1) % w, (x + 1) % w);
                // Row 0 is the top (v up): +v is the row above.
                let du = (d[y * w + right] - d[y * w + left]) * 0.5 * w as f32;
                let dv = (d[up * w + x] - d[down * w + x]) * 0.5 * h as f32;
                normals.push(Vec3::new(-strength * du, -strength * dv, 1.0).normalize());
            }
        }
        Self {
            normals,
            width: w,
            height: h,
            repeats,
        }
    }

    /// Where each output column (or row) of a `size_px` map falls on the repeated tile:
    /// (texel, next texel, weight of the next), wrapping. Made once per map, so the
    /// per-pixel work is four loads and two lerps.
    fn taps(&self, size_px: u32, along_v: bool) -> Vec<(usize, usize, f32)> {
        let (side, repeats) = if along_v {
            (self.height, self.repeats[1])
        } else {
            (self.width, self.repeats[0])
        };
        (0..size_px)
            .map(|i| {
                let t = if along_v {
                    // Row 0 is the top (v up).
                    1.0 - (heightmap::pixel_to_v(i, size_px) * repeats).fract()
                } else {
                    (heightmap::pixel_to_u(i, size_px) * repeats).fract()
                };
                let t = t * side as f32 - 0.5;
                let t0 = t.floor();
                let i0 = if t0 < 0.0 {
                    side - 1
                } else {
                    (t0 as usize).min(side - 1)
                };
                (i0, if i0 + 1 == side { 0 } else { i0 + 1 }, t - t0)
            })
            .collect()
    }

    /// The normal between the four texels of a column tap and a row tap.
    #[inline]
    fn normal(&self, (x0, x1, fx): (usize, usize, f32), (y0, y1, fy): (usize, usize, f32)) -> Vec3 {
        let (w, n) = (self.width, &self.normals);
        let top = n[y0 * w + x0].lerp(n[y0 * w + x1], fx);
        let bottom = n[y1 * w + x0].lerp(n[y1 * w + x1], fx);
        top.lerp(bottom, fy).normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(rgb: &[u8], i: usize) -> Vec3 {
        Vec3::new(
            rgb[i * 3] as f32 / 255.0 * 2.0 - 1.0,
            rgb[i * 3 + 1] as f32 / 255.0 * 2.0 - 1.0,
            rgb[i * 3 + 2] as f32 / 255.0 * 2.0 - 1.0,
        )
    }

    #[test]
    fn no_layer_is_flat() {
        let rgb = normal_map(&Layers::default(), 8, &CancelToken::never()).unwrap();
        assert!(
            rgb.chunks(3).all(|p| p == [128, 128, 255]),
            "{:?}",
            &rgb[..6]
        );
    }

    #[test]
    fn cavities_darken_with_local_depth_and_relief_only() {
        assert_eq!(cavity(0.0, 0.005), 1.0);
        // Unclamped below CAVITY_MAX (0.3 × 2 = 0.6).
        assert!((cavity(0.3, 0.005) - (1.0 - 0.3 * CAVITY)).abs() < 1e-6);
        assert_eq!(cavity(1.0, 0.0), 1.0, "no relief, no cavity");
        assert!((cavity(1.0, 1.0) - (1.0 - CAVITY_MAX)).abs() < 1e-6);
        // Half the depth darkens half as much.
        assert!((1.0 - cavity(0.15, 0.005) - 0.15 * CAVITY).abs() < 1e-6);
    }

    /// A 64² map, open skin, with `groove` (its depth by distance from the column x = 32,
    /// in texels) cut along v.
    fn groove(depth: impl Fn(f32) -> f32) -> HeightMap {
        let data = (0..64 * 64)
            .map(|i| depth(((i % 64) as f32 - 32.0).abs()))
            .collect();
        HeightMap::from_vec(64, 64, data).unwrap()
    }

    #[test]
    fn a_narrow_crease_is_a_cavity_and_a_wide_hollow_is_not() {
        // A relief whose ring lies 3 texels out.
        let disp = 3.0 / 64.0 / CAVITY_RING;
        let narrow = groove(|d| (1.0 - d / 2.0).max(0.0));
        let wide = groove(|d| (1.0 - d / 30.0).max(0.0));
        let flat = HeightMap::from_vec(64, 64, vec![0.6; 64 * 64]).unwrap();
        // The narrow crease's bottom is deeper than all of the ring but the two points
        // along the crease: three quarters of its depth.
        assert!((local_depth(&narrow, 32, 10, disp) - 0.75).abs() < 1e-6);
        // The wide hollow's bottom, 1 deep too, is only a little deeper than the ring.
        let open = local_depth(&wide, 32, 10, disp);
        assert!(open > 0.0 && open < 0.12, "{open}");
        // An even depth, however deep, and the open skin beside a crease: no cavity.
        assert!(local_depth(&flat, 20, 20, disp) < 1e-6);
        assert_eq!(local_depth(&narrow, 40, 10, disp), 0.0);
        let ao = occlusion_map(&narrow, 0.005);
        let at = |x: usize| ao[10 * 64 + x];
        // At the reference relief the ring is a fraction of a texel: the bottom is deeper
        // than its ring by the slope over that distance, and it is the darkest texel.
        assert!(
            at(32) < 255 && at(32) < at(31) && at(31) <= at(30),
            "{:?}",
            &ao[640 + 28..640 + 37]
        );
        assert_eq!(at(0), 255);
        // No relief, no cavity.
        assert!(occlusion_map(&narrow, 0.0).iter().all(|&a| a == 255));
        // The map is `local_depth` texel by texel (its taps found once), within a step of
        // the 8-bit rounding, at a relief whose ring falls between texels.
        for disp in [0.005, 0.0123, disp] {
            let fast = occlusion_map(&narrow, disp);
            for (i, &a) in fast.iter().enumerate() {
                let slow = cavity(
                    local_depth(&narrow, (i % 64) as u32, (i / 64) as u32, disp),
                    disp,
                );
                let slow = (slow * 255.0).round() as u8;
                assert!(
                    a.abs_diff(slow) <= 1,
                    "texel {i} at {disp}: {a} against {slow}"
                );
            }
        }
        // The roughness follows the creases: open skin the skin's, a crease's bottom
        // rougher, by at most CREASE_ROUGHNESS; metallic nowhere.
        let (orm, ao) = (orm_map(&narrow, disp, 0.5), occlusion_map(&narrow, disp));
        let rough: Vec<u8> = orm.chunks_exact(3).map(|p| p[1]).collect();
        for (p, &a) in orm.chunks_exact(3).zip(&ao) {
            assert_eq!(p[0], a);
            assert_eq!(p[2], 0);
        }
        let open = (0.5f32 * 255.0).round() as u8;
        let most = ((0.5 + CREASE_ROUGHNESS) * 255.0).round() as u8;
        assert!(
            rough.iter().all(|&r| (open..=most).contains(&r)),
            "{rough:?}"
        );
        let darkest = ao
            .iter()
            .position(|&a| a == *ao.iter().min().unwrap())
            .unwrap();
        assert!(rough[darkest] > open + 10, "{}", rough[darkest]);
        assert_eq!(crease_roughness(0.5, 1.0), 0.5);
        assert!((crease_roughness(0.5, 1.0 - CAVITY_MAX) - 0.7).abs() < 1e-6);
        assert_eq!(crease_roughness(0.95, 0.0), 1.0);
    }

    #[test]
    fn the_ring_wraps_in_u_and_clamps_in_v() {
        // A crease along v at u's seam (columns 0 and 63): the ring of a texel at column
        // 0 reads column 63 across the seam, as the view's sampler does.
        let data = (0..64 * 64)
            .map(|i| {
                if i % 64 == 0 || i % 64 == 63 {
                    1.0
                } else {
                    0.0
                }
            })
            .collect();
        let seam = HeightMap::from_vec(64, 64, data).unwrap();
        let disp = 1.0 / 64.0 / CAVITY_RING;
        let a = local_depth(&seam, 0, 30, disp);
        let b = local_depth(&seam, 63, 30, disp);
        assert!((a - b).abs() < 1e-6, "{a} {b}");
        // At the top row the ring's points above the map read the top row.
        let flat = HeightMap::from_vec(64, 64, vec![0.5; 64 * 64]).unwrap();
        assert!(local_depth(&flat, 10, 0, disp) < 1e-6);
    }

    #[test]
    fn a_ramp_in_u_tilts_the_normal_against_u() {
        // Depth rising with u (the surface falling): the normal leans toward +u, by disp ×
        // slope.
        let side = 16;
        let data = (0..side * side)
            .map(|i| (i % side) as f32 / side as f32)
            .collect();
        let ramp = HeightMap::from_vec(side as u32, side as u32, data).unwrap();
        let layers = Layers {
            large: Some(&ramp),
            disp_scale: 0.5,
            ..Layers::default()
        };
        let rgb = normal_map(&layers, 16, &CancelToken::never()).unwrap();
        let n = decode(&rgb, 8 * 16 + 8);
        // Slope 1 per UV unit × 0.5: n ∝ (0.5, 0, 1).
        let expected = Vec3::new(0.5, 0.0, 1.0).normalize();
        assert!((n - expected).length() < 0.02, "{n} vs {expected}");
    }

    #[test]
    fn a_flat_fine_tile_or_zero_blend_changes_nothing() {
        let flat = HeightMap::zeros(8, 8).unwrap();
        let tile = RepeatedTile {
            heights: &flat,
            repeats: [3.0, 3.0],
            strength: 0.01,
        };
        let layers = Layers {
            fine: Some(tile),
            fine_blend: 1.0,
            micro: Some(tile),
            ..Layers::default()
        };
        let rgb = normal_map(&layers, 8, &CancelToken::never()).unwrap();
        assert!(rgb.chunks(3).all(|p| p == [128, 128, 255]));
    }

    #[test]
    fn the_micro_relief_is_scaled_by_its_weight() {
        // A ramp tile: its normal leans; weighed 0 over the left half of the UV square it
        // is flat there, weighed 1 over the right half it is as it was.
        let side = 8;
        let data = (0..side * side).map(|i| (i % side) as f32).collect();
        let ramp = HeightMap::from_vec(side as u32, side as u32, data).unwrap();
        let tile = RepeatedTile {
            heights: &ramp,
            repeats: [1.0, 1.0],
            strength: 0.5,
        };
        let weights = crate::maps::mask::HeadImage {
            width_px: 4,
            height_px: 1,
            rgba: [0u8, 0, 255, 255]
                .iter()
                .flat_map(|&g| [g, g, g, 255])
                .collect(),
        };
        let plain = Layers {
            micro: Some(tile),
            ..Layers::default()
        };
        let weighed = Layers {
            micro_weight: Some(&weights),
            ..plain
        };
        let never = CancelToken::never();
        let (a, b) = (
            normal_map(&plain, 16, &never).unwrap(),
            normal_map(&weighed, 16, &never).unwrap(),
        );
        // Texel (2, 5) lies a quarter across (weight 0), (13, 5) past three quarters (1).
        let (left, right) = (5 * 16 + 2, 5 * 16 + 13);
        assert!(
            (decode(&a, left) - Vec3::Z).length() > 0.05,
            "{}",
            decode(&a, left)
        );
        assert!((decode(&b, left) - Vec3::Z).length() < 0.01);
        assert_eq!(decode(&a, right), decode(&b, right));
    }
}
