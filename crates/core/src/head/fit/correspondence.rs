//! The correspondence map: for each texel of the head's UV layout, the template UV its
//! layers are read at (see the module docs of [`crate::head::fit`]).

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::{Fit, unwrap_u};
use crate::base::cancel::CancelToken;
use crate::base::error::Error;
use crate::head::mesh::Mesh;
use crate::maps::raster::raster_banded;

/// How far (pixels) outside its triangle a texel still takes the triangle's extrapolated
/// template UV.
const GUARD_PX: f32 = 1.5;

/// How much farther apart (template UV) two corners of one head triangle may lie than
/// their 3D distance says before they count as lying on two islands of the template.
const SEAM_SLACK_UV: f32 = 0.01;

/// No template point: the layers are 0 there (no wrinkle, no hair).
const NONE: [f32; 2] = [f32::NAN, f32::NAN];

/// A texel while the head's triangles are rasterised: the template UV written, whether
/// it is inside an island, how far outside the triangle that wrote it it lies (∞: none
/// did).
#[derive(Clone, Copy)]
struct Written {
    uv: [f32; 2],
    covered: bool,
    distance: f32,
}

impl Default for Written {
    fn default() -> Self {
        Self {
            uv: NONE,
            covered: false,
            distance: f32::INFINITY,
        }
    }
}

/// Per texel of a `size × size` map in the head's UV layout (rows from the top, v up:
/// docs/models.md §1): the template UV, NaN where the head has no template point.
#[derive(Clone, Debug, PartialEq)]
pub struct Correspondence {
    size: u32,
    texels: Vec<[f32; 2]>,
    /// Whether each texel is inside a UV island of the head's skin (before padding).
    covered: Vec<bool>,
}

impl Correspondence {
    /// Rasterises `fit` in `head`'s UV layout at `size`² (each triangle's template UVs
    /// extrapolated [`GUARD_PX`] beyond its edges where no triangle covers), then pads:
    /// every texel still unwritten takes the value of the nearest written one.
    pub fn new(head: &Mesh, fit: &Fit, size: u32, cancel: &CancelToken) -> Result<Self, Error> {
        crate::maps::heightmap::check_size(size, size)?;
        let n = size as usize;
        let uvs = head.uvs();
        let positions = head.positions();
        let idx = head.skin_indices();
        let template_m_per_uv = super::template().metres_per_uv.unwrap_or(1.0);
        let mut state = vec![Written::default(); n * n];
        // Every guard write as (texel, the 3D point it stands for in the writing
        // triangle's plane just beyond its edge, distance outside), for the surface's
        // continuation below: a short list per band of rows beside the map.
        let guard_points: Vec<Vec<(u32, Vec3, f32)>> = raster_banded(
            size,
            &mut state,
            idx.len() / 3,
            GUARD_PX,
            |k| {
                let c = |i: usize| uvs.get(idx[k * 3 + i] as usize).copied();
                Some([c(0)?, c(1)?, c(2)?])
            },
            |k, band, guard_points: &mut Vec<(u32, Vec3, f32)>| {
                if k % 4096 == 0 {
                    cancel.check()?;
                }
                let tri = &idx[k * 3..k * 3 + 3];
                let corner = |i: usize| tri[i] as usize;
                let (Some(a), Some(b), Some(c)) =
                    (uvs.get(corner(0)), uvs.get(corner(1)), uvs.get(corner(2)))
                else {
                    return Ok(());
                };
                let t = |i: usize| fit.template_uv.get(corner(i)).copied().flatten();
                let template = match (t(0), t(1), t(2)) {
                    (Some(x), Some(y), Some(z)) => Some(unwrap_u([x, y, z])),
                    _ => None,
                };
                // Corners whose template points lie on different islands of the
                // template's layout (the head's triangle spans a template seam): mixing
                // their UVs would read somewhere unrelated in between, so each texel
                // reads only the corners on the island of its nearest corner.
                let p3 = |i: usize| positions.get(corner(i)).copied().unwrap_or(Vec3::ZERO);
                let same_island = template.map(|(ta, tb, tc)| {
                    let t = [ta, tb, tc];
                    let near = |i: usize, j: usize| {
                        let metres = p3(i).distance(p3(j)) * fit.similarity.scale;
                        t[i].distance(t[j]) <= 4.0 * metres / template_m_per_uv + SEAM_SLACK_UV
                    };
                    [
                        [true, near(0, 1), near(0, 2)],
                        [near(1, 0), true, near(1, 2)],
                        [near(2, 0), near(2, 1), true],
                    ]
                });
                // The triangle and a guard band around it: texels just outside every
                // island take the triangle's template UV extrapolated (the surface's
                // continuation across a seam), so bilinear reads at an island's border
                // mix no copied values.
                let guard = if template.is_some() { GUARD_PX } else { 0.0 };
                let one_island = same_island.is_none_or(|s| s.iter().flatten().all(|&b| b));
                let (pa, pb, pc) = (p3(0), p3(1), p3(2));
                band.raster([*a, *b, *c], guard, |x, y, [w0, w1, w2], outside, texel| {
                    if outside >= texel.distance {
                        return;
                    }
                    texel.distance = outside;
                    texel.covered |= outside == 0.0;
                    if outside > 0.0 {
                        let i = (y * n + x) as u32;
                        guard_points.push((i, pa * w0 + pb * w1 + pc * w2, outside));
                    }
                    texel.uv = match (template, same_island) {
                        (Some((ta, tb, tc)), Some(_)) if one_island => {
                            let uv = ta * w0 + tb * w1 + tc * w2;
                            [uv.x.rem_euclid(1.0), uv.y]
                        }
                        (Some((ta, tb, tc)), Some(same)) => {
                            let w = [w0, w1, w2];
                            let k = (0..3).fold(0, |k, j| if w[j] > w[k] { j } else { k });
                            let w: [f32; 3] =
                                std::array::from_fn(|j| if same[k][j] { w[j] } else { 0.0 });
                            let sum = w[0] + w[1] + w[2];
                            let uv = (ta * w[0] + tb * w[1] + tc * w[2]) / sum;
                            [uv.x.rem_euclid(1.0), uv.y]
                        }
                        _ => NONE,
                    };
                });
                Ok(())
            },
        )?;
        let mut texels: Vec<[f32; 2]> = state.iter().map(|t| t.uv).collect();
        let covered: Vec<bool> = state.iter().map(|t| t.covered).collect();
        let filled: Vec<bool> = state.iter().map(|t| t.distance.is_finite()).collect();
        // A guard texel across a seam stands for the surface on the other side of it: its
        // template UV is read where its point lies on the head (the neighbouring
        // triangle, wherever that is in the UV layout), not extrapolated from one
        // triangle, so heights on both sides of a seam agree (docs/models.md §7a). Each
        // texel outside every island, at its last write.
        let across: Vec<(u32, Vec3)> = guard_points
            .par_iter()
            .flatten()
            .filter(|(i, _, outside)| {
                !covered[*i as usize] && *outside == state[*i as usize].distance
            })
            .map(|&(i, q, _)| (i, q))
            .collect();
        drop(state);
        cancel.check()?;
        if !across.is_empty() {
            // The head's tree, only when a texel asks for it.
            let bvh = super::bvh::Bvh::new(positions, &idx);
            // A texel's width in 3D is far below this: farther is no continuation.
            let reach = 0.05 * head.bounds().size().max_element();
            let continued: Vec<(usize, [f32; 2])> = across
                .par_iter()
                .filter_map(|&(i, q)| {
                    let hit = bvh.closest(q, reach)?;
                    let t = hit.triangle as usize * 3;
                    let uv = |k: usize| fit.template_uv.get(idx[t + k] as usize).copied().flatten();
                    let (ta, tb, tc) = unwrap_u([uv(0)?, uv(1)?, uv(2)?]);
                    let w = hit.bary;
                    let uv = ta * w.x + tb * w.y + tc * w.z;
                    Some((i as usize, [uv.x.rem_euclid(1.0), uv.y]))
                })
                .collect();
            for (i, uv) in continued {
                texels[i] = uv;
            }
        }
        pad(&mut texels, &filled, n);
        Ok(Self {
            size,
            texels,
            covered,
        })
    }

    pub fn size(&self) -> u32 {
        self.size
    }

    /// The template UV of texel (x, y), `None` where the head has no template point.
    pub fn get(&self, x: u32, y: u32) -> Option<Vec2> {
        let t = self.texels[(y * self.size + x) as usize];
        (!t[0].is_nan()).then(|| Vec2::new(t[0], t[1]))
    }

    /// Whether texel (x, y) is inside one of the head skin's UV islands.
    pub fn covered(&self, x: u32, y: u32) -> bool {
        self.covered[(y * self.size + x) as usize]
    }

    /// The template UV at the head UV `uv` (its texel's), `None` where the head has none
    /// or outside the map.
    pub fn template_uv_at(&self, uv: Vec2) -> Option<Vec2> {
        let n = self.size as f32;
        let (x, y) = ((uv.x * n).floor(), ((1.0 - uv.y) * n).floor());
        if !(0.0..n).contains(&x) || !(0.0..n).contains(&y) {
            return None;
        }
        self.get(x as u32, y as u32)
    }

    /// The head UV (a texel centre inside an island) whose template UV is nearest
    /// `template_uv` (u wrapping), searched every `stride` texels; `None` when no texel
    /// is within `max_distance` (template UV units).
    pub fn head_uv_of(&self, template_uv: Vec2, stride: u32, max_distance: f32) -> Option<Vec2> {
        let n = self.size;
        let stride = stride.max(1);
        let mut best: Option<(f32, u32, u32)> = None;
        for y in (0..n).step_by(stride as usize) {
            for x in (0..n).step_by(stride as usize) {
                if !self.covered(x, y) {
                    continue;
                }
                let Some(t) = self.get(x, y) else { continue };
                let du = (t.x - template_uv.x).abs();
                let d = Vec2::new(du.min(1.0 - du), t.y - template_uv.y).length_squared();
                if best.is_none_or(|b| d < b.0) {
                    best = Some((d, x, y));
                }
            }
        }
        let (d, x, y) = best?;
        (d <= max_distance * max_distance).then(|| {
            Vec2::new(
                (x as f32 + 0.5) / n as f32,
                1.0 - (y as f32 + 0.5) / n as f32,
            )
        })
    }

    /// How many texels have a template point (padding included).
    pub fn matched(&self) -> usize {
        self.texels.iter().filter(|t| !t[0].is_nan()).count()
    }

    /// The values of a map in the template's UV layout (`width × height`, rows from the
    /// top), read at each texel's template UV (bilinear, u wrapping, v clamped): the same
    /// map in the head's layout, `0` where the head has no template point.
    pub fn resample(&self, src: &[f32], width: u32, height: u32) -> Vec<f32> {
        let n = self.size as usize;
        let mut out = vec![0.0; n * n];
        if width == 0 || height == 0 || src.len() < (width * height) as usize {
            return out;
        }
        out.par_chunks_mut(n)
            .zip(self.texels.par_chunks(n))
            .for_each(|(row, texels)| {
                for (o, t) in row.iter_mut().zip(texels) {
                    if !t[0].is_nan() {
                        *o = bilinear(src, width, height, t[0], t[1]);
                    }
                }
            });
        out
    }
}

/// Bilinear sample at (u, v): u wraps, v is clamped (docs/models.md §1 pixel centres).
fn bilinear(src: &[f32], width: u32, height: u32, u: f32, v: f32) -> f32 {
    let (w, h) = (width as i64, height as i64);
    let x = u * width as f32 - 0.5;
    let y = (1.0 - v) * height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |xi: i64, yi: i64| {
        let xi = xi.rem_euclid(w);
        let yi = yi.clamp(0, h - 1);
        src[(yi * w + xi) as usize]
    };
    let (x0, y0) = (x0 as i64, y0 as i64);
    let top = at(x0, y0) * (1.0 - fx) + at(x0 + 1, y0) * fx;
    let bottom = at(x0, y0 + 1) * (1.0 - fx) + at(x0 + 1, y0 + 1) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// Fills every texel not `filled` with the value of its nearest filled texel (two
/// chamfer passes propagating the nearest source, 8-neighbour: within a texel of the
/// Euclidean nearest). Nothing covered: nothing changes. The passes visit only the texels
/// not filled (a filled texel is its own nearest) and test the map's borders only on its
/// border rows and columns.
pub fn pad<T: Copy>(texels: &mut [T], filled: &[bool], n: usize) {
    let covered = filled;
    if n == 0 || !covered.iter().any(|&c| c) {
        return;
    }
    // The nearest covered texel found so far, as a texel index; NONE = none yet.
    const NONE: u32 = u32::MAX;
    let mut nearest: Vec<u32> = (0..n * n)
        .into_par_iter()
        .map(|i| if covered[i] { i as u32 } else { NONE })
        .collect();
    let d2 = |x: usize, y: usize, s: u32| {
        if s == NONE {
            u64::MAX
        } else {
            let (sx, sy) = ((s as usize % n) as i64, (s as usize / n) as i64);
            let (dx, dy) = (x as i64 - sx, y as i64 - sy);
            (dx * dx + dy * dy) as u64
        }
    };
    // Texel (x, y) takes the nearest of its neighbours' nearest where nearer than its
    // own, the neighbours in `offsets`' order (the first on a tie).
    let relax = |x: usize, y: usize, offsets: &[(isize, isize); 4], nearest: &mut [u32]| {
        let i = y * n + x;
        let mut best = nearest[i];
        let mut best_d = d2(x, y, best);
        let inside = x > 0 && y > 0 && x + 1 < n && y + 1 < n;
        for &(dx, dy) in offsets {
            let j = if inside {
                i.wrapping_add_signed(dy * n as isize + dx)
            } else {
                let (Some(nx), Some(ny)) = (x.checked_add_signed(dx), y.checked_add_signed(dy))
                else {
                    continue;
                };
                if nx >= n || ny >= n {
                    continue;
                }
                ny * n + nx
            };
            let s = nearest[j];
            let d = d2(x, y, s);
            if d < best_d {
                best = s;
                best_d = d;
            }
        }
        nearest[i] = best;
    };
    const FORWARD: [(isize, isize); 4] = [(-1, 0), (-1, -1), (0, -1), (1, -1)];
    const BACKWARD: [(isize, isize); 4] = [(1, 0), (1, 1), (0, 1), (-1, 1)];
    for y in 0..n {
        for x in 0..n {
            if !covered[y * n + x] {
                relax(x, y, &FORWARD, &mut nearest);
            }
        }
    }
    for y in (0..n).rev() {
        for x in (0..n).rev() {
            if !covered[y * n + x] {
                relax(x, y, &BACKWARD, &mut nearest);
            }
        }
    }
    for i in 0..n * n {
        if !covered[i] && nearest[i] != NONE {
            texels[i] = texels[nearest[i] as usize];
        }
    }
}
