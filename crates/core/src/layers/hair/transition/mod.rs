//! The hair transition texture (docs/models.md §9 "Transition texture", [T §6.1]).
//!
//! Two masks in UV space give the *outer* region (hair at age t = 0) and the *inner* region
//! (hair that remains at t = 1). The inner region is grown outward one generation at a time
//! through the 8-neighbourhood, only into pixels of the outer region; a pixel's generation
//! number r is its distance from the inner region along that growth. The texture stores,
//! per pixel, the **disappearance age** `a` derived from r, so that the hair present at age
//! t is exactly the threshold `a ≥ t` (see [`hair_present`]).
//!
//! # Value convention (the mapping r → a)
//!
//! | pixel | generation | stored age `a` |
//! |---|---|---|
//! | inner region (inside or outside the outer one) | r = 0 | `1.0` — never disappears |
//! | outer \ inner, reached by growth | r ≥ 1 | `1 − r/(R + 1)`, in (0, 1) |
//! | outer \ inner, not reachable from the inner region | r = R_reach + 1 | `1 − r/(R + 1)` |
//! | neither region | — | `0.0` — never has hair |
//!
//! R is the largest generation assigned (including the unreachable rule below), so
//! `r/(R + 1)` is docs/models.md §9's generation normalised to (0, 1) and `a = 1 − r/(R + 1)` runs
//! from `R/(R + 1)` (next to the inner region, goes last) down to `1/(R + 1)` (outer-most,
//! goes first). Ages are linear in r: the hairline recedes at a constant number of pixels
//! per unit of age.
//!
//! **Choice** (docs/models.md §9 does not say): outer pixels that growth can never reach — islands of
//! outer hair with no inner hair connected to them through the outer region (for example a
//! UV island of the scalp that the inner mask does not touch) — get `r = R_reach + 1`, one
//! generation beyond the farthest reached pixel. They are outer-most hair in the sense of
//! docs/models.md §9 ("outer-most pixels lose their hair first"), so they disappear first, all at
//! once. With an empty inner mask every outer pixel is such an island: R = 1, a = 0.5.
//!
//! **Choice**: a mask pixel belongs to its region when the mask, bilinearly resampled to
//! the working size (docs/models.md §1 pixel centres), is ≥ 0.5 — the region boundary is where the
//! interpolated grey crosses mid-grey, whatever the mask's own size.
//!
//! # Algorithms
//!
//! docs/models.md §9 defines r by iterative whole-image dilation, O(generations × pixels); it is kept
//! as [`generations_by_dilation`], the reference for the tests and the benchmark.
//!
//! [`DistanceMetric::Chebyshev`] computes the same numbers in O(pixels) with a multi-source
//! breadth-first search over the 8-neighbourhood graph of outer pixels, seeded with every
//! inner pixel: the geodesic Chebyshev distance transform of the inner region *constrained
//! to the outer region*. BFS visits pixels in order of their distance and assigns each the
//! first time a neighbour at distance d − 1 is dequeued, which is exactly "the generation in
//! which the dilation first reaches it"; the tests check pixel-for-pixel equality on random
//! masks with holes and several islands. (An unconstrained two-pass Chebyshev transform
//! gives the same numbers only when the outer region is convex; with holes or concave
//! boundaries the growth has to go around them and the plain transform is wrong.)
//!
//! [`DistanceMetric::Euclidean`] gives rounder fronts: the geodesic **5-7-11 chamfer**
//! distance (Borgefors 1986) through the outer region — shortest paths over the
//! 16-neighbourhood with weights 5 (axis step), 7 (diagonal step) and 11 (knight step
//! (±1, ±2)/(±2, ±1)), divided by 5 — computed exactly by Dijkstra with a 12-bucket
//! circular queue (Dial's algorithm), O(pixels + largest distance). A knight step is
//! allowed only when one of the two pixels it passes between is passable, so fronts do not
//! jump walls that the 8-neighbourhood growth could not cross. In open space its distance
//! is within 2.02 % of the Euclidean one (tested: a point source in an open square); around
//! obstacles it follows the shortest path, as the growth does. **Choice** over an exact
//! Euclidean transform, which is not geodesic (it would let fronts pass through holes),
//! and over fast marching, which is O(n log n) and harder to make byte-identical.
//!
//! # Limits
//!
//! Growth happens in UV pixels, as docs/models.md §9 says, so it inherits the UV layout's stretch:
//! where the layout squeezes the surface (near a pole, e.g. the crown row of the default
//! head) a generation covers less skin than elsewhere. Growth does not wrap around UV
//! seams: a front stops at u = 0/1 even where the mesh continues across the seam. Ages are
//! constant per texel; the working size sets how fine the steps of the recession are.

use rayon::prelude::*;

use crate::base::error::Error;
use crate::maps::heightmap::{check_size, pixel_to_u, pixel_to_v};
use crate::maps::mask::Mask;

/// Mask value at or above which a pixel belongs to its region (see the module's Choice).
pub const REGION_THRESHOLD: f32 = 0.5;

/// The distance in which hair fronts advance (docs/models.md §9: "Chebyshev for the 8-neighbourhood,
/// a Euclidean one gives rounder fronts").
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "lowercase")]
pub enum DistanceMetric {
    /// 8-neighbourhood growth, exactly the generations of docs/models.md §9 (square fronts).
    #[default]
    Chebyshev,
    /// Geodesic 5-7-11 chamfer distance, within 2.02 % of Euclidean (round fronts).
    Euclidean,
}

impl DistanceMetric {
    /// The distance of one axis step in this metric's integer units.
    pub fn units_per_px(self) -> u32 {
        match self {
            Self::Chebyshev => 1,
            Self::Euclidean => 5,
        }
    }
}

impl std::str::FromStr for DistanceMetric {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self, Error> {
        match s.to_ascii_lowercase().as_str() {
            "chebyshev" => Ok(Self::Chebyshev),
            "euclidean" => Ok(Self::Euclidean),
            _ => Err(Error::InvalidValue {
                what: "distance metric".into(),
                value: s.into(),
                expected: "chebyshev or euclidean".into(),
            }),
        }
    }
}

/// Region bit: the pixel is in the outer region (hair at t = 0).
const OUTER: u8 = 1;
/// Region bit: the pixel is in the inner region (hair at t = 1).
const INNER: u8 = 2;

fn region_bits(outer: bool, inner: bool) -> u8 {
    (if outer { OUTER } else { 0 }) | (if inner { INNER } else { 0 })
}

/// The outer and inner hair regions as binary images at the working size, row 0 at the top.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HairRegions {
    width_px: u32,
    height_px: u32,
    /// Per pixel, `OUTER | INNER` bits.
    bits: Vec<u8>,
}

impl HairRegions {
    /// Resamples both masks (any sizes, docs/models.md §1 pixel centres, bilinear) to
    /// `width_px × height_px` and thresholds them at [`REGION_THRESHOLD`].
    /// Fails when the size is 0 or above [`crate::maps::heightmap::MAX_SIZE_PX`].
    pub fn from_masks(
        outer: &Mask,
        inner: &Mask,
        width_px: u32,
        height_px: u32,
    ) -> Result<Self, Error> {
        check_size(width_px, height_px)?;
        let w = width_px as usize;
        let mut bits = try_vec(w * height_px as usize, 0u8, "hair region image")?;
        let (outer_x, inner_x) = (
            BilinearAxis::columns(outer, width_px),
            BilinearAxis::columns(inner, width_px),
        );
        bits.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
            let (oy, iy) = (
                BilinearAxis::row(outer, y as u32, height_px),
                BilinearAxis::row(inner, y as u32, height_px),
            );
            for (x, b) in row.iter_mut().enumerate() {
                let o = sample_at(outer, &outer_x[x], &oy) >= REGION_THRESHOLD;
                let i = sample_at(inner, &inner_x[x], &iy) >= REGION_THRESHOLD;
                *b = region_bits(o, i);
            }
        });
        Ok(Self {
            width_px,
            height_px,
            bits,
        })
    }

    /// Builds regions from per-pixel booleans (row-major, row 0 at the top); both slices
    /// must hold `width_px × height_px` values.
    pub fn from_bools(
        width_px: u32,
        height_px: u32,
        outer: &[bool],
        inner: &[bool],
    ) -> Result<Self, Error> {
        check_size(width_px, height_px)?;
        let n = width_px as usize * height_px as usize;
        for (what, len) in [("outer region", outer.len()), ("inner region", inner.len())] {
            if len != n {
                return Err(Error::InvalidValue {
                    what: format!("{what} pixel count"),
                    value: len.to_string(),
                    expected: format!("{width_px}×{height_px} = {n}"),
                });
            }
        }
        let bits = outer
            .iter()
            .zip(inner)
            .map(|(&o, &i)| region_bits(o, i))
            .collect();
        Ok(Self {
            width_px,
            height_px,
            bits,
        })
    }

    pub fn width_px(&self) -> u32 {
        self.width_px
    }

    pub fn height_px(&self) -> u32 {
        self.height_px
    }

    /// Whether pixel `i` (row-major index) is in the outer region.
    pub fn is_outer(&self, i: usize) -> bool {
        self.bits[i] & OUTER != 0
    }

    /// Whether pixel `i` (row-major index) is in the inner region.
    pub fn is_inner(&self, i: usize) -> bool {
        self.bits[i] & INNER != 0
    }

    /// The bits surrounded by `pad` pixels of "no region" on every side, so that neighbour
    /// loops need no bounds checks.
    fn padded(&self, pad: usize) -> (Vec<u8>, usize) {
        let (w, h) = (self.width_px as usize, self.height_px as usize);
        let pw = w + 2 * pad;
        let mut out = vec![0u8; pw * (h + 2 * pad)];
        for y in 0..h {
            let dst = (y + pad) * pw + pad;
            out[dst..dst + w].copy_from_slice(&self.bits[y * w..(y + 1) * w]);
        }
        (out, pw)
    }
}

/// One axis of [`Mask::sample`] at a pixel centre of the working size, precomputed once
/// per column (and per row) instead of once per pixel. Same arithmetic as `Mask::sample`,
/// so the result is bit-identical to sampling each pixel.
struct BilinearAxis {
    i0: usize,
    i1: usize,
    t: f32,
}

impl BilinearAxis {
    fn from_continuous(f: f32, len: u32) -> Self {
        let f = f.clamp(0.0, (len - 1) as f32);
        let i0 = f.floor() as usize;
        Self {
            i0,
            i1: (i0 + 1).min(len as usize - 1),
            t: f - i0 as f32,
        }
    }

    fn columns(mask: &Mask, width_px: u32) -> Vec<Self> {
        let w = mask.width_px();
        (0..width_px)
            .map(|x| Self::from_continuous(pixel_to_u(x, width_px) * w as f32 - 0.5, w))
            .collect()
    }

    fn row(mask: &Mask, y: u32, height_px: u32) -> Self {
        let h = mask.height_px();
        Self::from_continuous((1.0 - pixel_to_v(y, height_px)) * h as f32 - 0.5, h)
    }
}

fn sample_at(mask: &Mask, x: &BilinearAxis, y: &BilinearAxis) -> f32 {
    let w = mask.width_px() as usize;
    let values = mask.values();
    let at = |xi: usize, yi: usize| values[yi * w + xi];
    let top = at(x.i0, y.i0) + (at(x.i1, y.i0) - at(x.i0, y.i0)) * x.t;
    let bottom = at(x.i0, y.i1) + (at(x.i1, y.i1) - at(x.i0, y.i1)) * x.t;
    top + (bottom - top) * y.t
}

/// Marks a pixel with no generation: outside both regions, or (before the unreachable rule
/// is applied) an outer pixel growth has not reached.
pub const NO_GENERATION: u32 = u32::MAX;

/// Geodesic distance from the inner region through the outer region, per pixel, in the
/// metric's integer units ([`DistanceMetric::units_per_px`] per axis step): 0 on the inner
/// region, ≥ 1 on reached outer pixels, [`NO_GENERATION`] on outer pixels growth cannot
/// reach and on pixels outside both regions. For Chebyshev these are docs/models.md §9's generation
/// numbers r. O(pixels).
pub fn geodesic_distances(
    regions: &HairRegions,
    metric: DistanceMetric,
) -> Result<Vec<u32>, Error> {
    match metric {
        DistanceMetric::Chebyshev => chebyshev_bfs(regions),
        DistanceMetric::Euclidean => chamfer_5_7_11(regions),
    }
}

/// The 8 neighbour offsets (dx, dy).
const NEIGHBOURS_8: [(isize, isize); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// Multi-source BFS over the 8-neighbourhood, constrained to outer pixels.
fn chebyshev_bfs(regions: &HairRegions) -> Result<Vec<u32>, Error> {
    let (w, h) = (regions.width_px as usize, regions.height_px as usize);
    let (bits, pw) = regions.padded(1);
    let mut dist = try_vec(bits.len(), NO_GENERATION, "transition distances")?;
    let mut queue: Vec<u32> = Vec::new();
    queue
        .try_reserve_exact(w * h)
        .map_err(|_| oom(w * h * 4, "transition queue"))?;
    for (i, &b) in bits.iter().enumerate() {
        if b & INNER != 0 {
            dist[i] = 0;
            queue.push(i as u32);
        }
    }
    let offsets = NEIGHBOURS_8.map(|(dx, dy)| dy * pw as isize + dx);
    let mut head = 0;
    while head < queue.len() {
        let p = queue[head] as usize;
        head += 1;
        let d = dist[p] + 1;
        for off in offsets {
            // The padding holds no region, so `q` stays inside and never passes the test
            // on the border.
            let q = p.wrapping_add_signed(off);
            if bits[q] & OUTER != 0 && dist[q] == NO_GENERATION {
                dist[q] = d;
                queue.push(q as u32);
            }
        }
    }
    Ok(unpad(&dist, pw, 1, w, h))
}

/// Chamfer steps (dx, dy, weight) of the 5-7-11 mask.
const CHAMFER_STEPS: [(isize, isize, u32); 16] = [
    (1, 0, 5),
    (-1, 0, 5),
    (0, 1, 5),
    (0, -1, 5),
    (1, 1, 7),
    (1, -1, 7),
    (-1, 1, 7),
    (-1, -1, 7),
    (2, 1, 11),
    (2, -1, 11),
    (-2, 1, 11),
    (-2, -1, 11),
    (1, 2, 11),
    (-1, 2, 11),
    (1, -2, 11),
    (-1, -2, 11),
];

/// The two pixels a knight step (dx, dy) passes between: the axis step and the diagonal
/// step that both lead to it in two moves. Axis and diagonal steps return themselves.
fn knight_via(dx: isize, dy: isize) -> [(isize, isize); 2] {
    if dx.abs() == 2 {
        [(dx.signum(), 0), (dx.signum(), dy)]
    } else if dy.abs() == 2 {
        [(0, dy.signum()), (dx, dy.signum())]
    } else {
        [(dx, dy), (dx, dy)]
    }
}

/// Dijkstra with Dial's circular bucket queue over the 16-neighbourhood (weights 5/7/11),
/// constrained to outer pixels.
fn chamfer_5_7_11(regions: &HairRegions) -> Result<Vec<u32>, Error> {
    const BUCKETS: usize = 12; // > the largest step weight, so a push never hits the current bucket
    let (w, h) = (regions.width_px as usize, regions.height_px as usize);
    let (bits, pw) = regions.padded(2);
    let mut dist = try_vec(bits.len(), NO_GENERATION, "transition distances")?;
    let mut buckets: [Vec<u32>; BUCKETS] = Default::default();
    for (i, &b) in bits.iter().enumerate() {
        if b & INNER != 0 {
            dist[i] = 0;
            buckets[0].push(i as u32);
        }
    }
    let at = |dx: isize, dy: isize| dy * pw as isize + dx;
    let steps = CHAMFER_STEPS.map(|(dx, dy, wgt)| {
        let [a, b] = knight_via(dx, dy);
        (at(dx, dy), wgt, at(a.0, a.1), at(b.0, b.1))
    });
    let mut pending: usize = buckets[0].len();
    let mut current: u32 = 0;
    let mut taken = Vec::new();
    while pending > 0 {
        let slot = current as usize % BUCKETS;
        std::mem::swap(&mut taken, &mut buckets[slot]);
        pending -= taken.len();
        for &p in &taken {
            let p = p as usize;
            if dist[p] != current {
                continue; // a stale entry: p was reached by a shorter path meanwhile
            }
            for &(off, wgt, via_a, via_b) in &steps {
                let q = p.wrapping_add_signed(off);
                if bits[q] & OUTER == 0 {
                    continue;
                }
                let passable = |o: isize| bits[p.wrapping_add_signed(o)] & (OUTER | INNER) != 0;
                if wgt == 11 && !passable(via_a) && !passable(via_b) {
                    continue;
                }
                let nd = current + wgt;
                if nd < dist[q] {
                    dist[q] = nd;
                    buckets[nd as usize % BUCKETS].push(q as u32);
                    pending += 1;
                }
            }
        }
        taken.clear();
        current += 1;
    }
    Ok(unpad(&dist, pw, 2, w, h))
}

/// docs/models.md §9's reference algorithm, literally: grow the inner region one generation at a
/// time by whole-image 8-neighbourhood dilation, only into outer pixels, until nothing
/// changes. Same output convention as [`geodesic_distances`] with Chebyshev.
/// O(generations × pixels): use it to check the fast path, not in production.
pub fn generations_by_dilation(regions: &HairRegions) -> Vec<u32> {
    let (w, h) = (regions.width_px as usize, regions.height_px as usize);
    let mut gen_of: Vec<u32> = (0..w * h)
        .map(|i| {
            if regions.is_inner(i) {
                0
            } else {
                NO_GENERATION
            }
        })
        .collect();
    let mut generation = 0u32;
    loop {
        generation += 1;
        let mut grew = false;
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                if !regions.is_outer(i) || gen_of[i] != NO_GENERATION {
                    continue;
                }
                let touches_previous = NEIGHBOURS_8.iter().any(|&(dx, dy)| {
                    let (nx, ny) = (x as isize + dx, y as isize + dy);
                    (0..w as isize).contains(&nx)
                        && (0..h as isize).contains(&ny)
                        && gen_of[ny as usize * w + nx as usize] == generation - 1
                });
                if touches_previous {
                    gen_of[i] = generation;
                    grew = true;
                }
            }
        }
        if !grew {
            return gen_of;
        }
    }
}

/// The transition texture: per pixel the disappearance age `a` of docs/models.md §9 (see the
/// module's table), row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct TransitionTexture {
    width_px: u32,
    height_px: u32,
    metric: DistanceMetric,
    ages: Vec<f32>,
    /// R of the module's table, in pixels (metric units / units per pixel).
    max_generation_px: f64,
    /// Outer pixels growth cannot reach (given r = R_reach + 1).
    unreachable_px: u64,
}

impl TransitionTexture {
    /// Resamples the masks to `width_px × height_px` and builds the texture. O(pixels).
    pub fn from_masks(
        outer: &Mask,
        inner: &Mask,
        width_px: u32,
        height_px: u32,
        metric: DistanceMetric,
    ) -> Result<Self, Error> {
        Self::from_regions(
            &HairRegions::from_masks(outer, inner, width_px, height_px)?,
            metric,
        )
    }

    /// The texture with the disappearance ages given by an **order** mask instead of grown
    /// from the inner region (docs/models.md §9, "order"): inner pixels 1, outer-only
    /// pixels the order mask's value (bilinear at the working size) kept inside
    /// [1/256, 255/256], so all of them go by t = 1; other pixels 0. The default head's
    /// masks come with one painted in 3D (temples and crown first): a recession that does
    /// not depend on how a UV layout stretches the scalp. O(pixels).
    pub fn from_order(
        outer: &Mask,
        inner: &Mask,
        order: &Mask,
        width_px: u32,
        height_px: u32,
    ) -> Result<Self, Error> {
        let regions = HairRegions::from_masks(outer, inner, width_px, height_px)?;
        let w = width_px as usize;
        let columns = BilinearAxis::columns(order, width_px);
        let mut ages = try_vec(w * height_px as usize, 0.0f32, "hair transition")?;
        ages.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
            let oy = BilinearAxis::row(order, y as u32, height_px);
            for (x, a) in row.iter_mut().enumerate() {
                let i = y * w + x;
                *a = if regions.is_inner(i) {
                    1.0
                } else if regions.is_outer(i) {
                    sample_at(order, &columns[x], &oy).clamp(1.0 / 256.0, 255.0 / 256.0)
                } else {
                    0.0
                };
            }
        });
        Ok(Self {
            width_px,
            height_px,
            metric: DistanceMetric::Chebyshev,
            ages,
            max_generation_px: 0.0,
            unreachable_px: 0,
        })
    }

    /// Builds the texture from binary regions. O(pixels).
    pub fn from_regions(regions: &HairRegions, metric: DistanceMetric) -> Result<Self, Error> {
        let dist = geodesic_distances(regions, metric)?;
        Ok(Self::from_distances(regions, &dist, metric))
    }

    /// Applies the unreachable rule and the mapping r → a to distances in `metric` units.
    fn from_distances(regions: &HairRegions, dist: &[u32], metric: DistanceMetric) -> Self {
        let unit = metric.units_per_px() as u64;
        let (reached_max, unreachable_px) = dist
            .par_iter()
            .enumerate()
            .map(|(i, &d)| match d {
                NO_GENERATION => (0, u64::from(regions.is_outer(i))),
                d => (d as u64, 0),
            })
            .reduce(|| (0, 0), |a, b| (a.0.max(b.0), a.1 + b.1));
        let unreachable_dist = reached_max + unit;
        let max_dist = if unreachable_px > 0 {
            unreachable_dist
        } else {
            reached_max
        };
        let denom = (max_dist + unit) as f64;
        let ages = dist
            .par_iter()
            .enumerate()
            .map(|(i, &d)| {
                let d = if d != NO_GENERATION {
                    d as u64
                } else if regions.is_outer(i) {
                    unreachable_dist
                } else {
                    return 0.0;
                };
                if d == 0 {
                    1.0
                } else {
                    (1.0 - d as f64 / denom) as f32
                }
            })
            .collect();
        Self {
            width_px: regions.width_px,
            height_px: regions.height_px,
            metric,
            ages,
            max_generation_px: max_dist as f64 / unit as f64,
            unreachable_px,
        }
    }

    pub fn width_px(&self) -> u32 {
        self.width_px
    }

    pub fn height_px(&self) -> u32 {
        self.height_px
    }

    pub fn metric(&self) -> DistanceMetric {
        self.metric
    }

    /// Per-pixel disappearance ages, row-major, row 0 at the top: 1 = inner (never),
    /// (0, 1) = receding hair, 0 = no hair.
    pub fn ages(&self) -> &[f32] {
        &self.ages
    }

    /// R, the largest generation, in pixels of the working size (0 when there is no
    /// receding hair).
    pub fn max_generation_px(&self) -> f64 {
        self.max_generation_px
    }

    /// Number of outer pixels not reachable from the inner region (module's Choice).
    pub fn unreachable_px(&self) -> u64 {
        self.unreachable_px
    }

    /// The age at pixel (x, y); panics when out of bounds like slice indexing.
    pub fn age_at_pixel(&self, x: u32, y: u32) -> f32 {
        self.ages[y as usize * self.width_px as usize + x as usize]
    }

    /// The age of the texel containing (u, v) (nearest, no interpolation: blending an inner
    /// texel with a no-hair one would make inner hair disappear). UVs outside [0,1] are
    /// clamped to the border texels; NaN reads texel 0.
    pub fn age_at_uv(&self, u: f32, v: f32) -> f32 {
        let x = ((u * self.width_px as f32) as i64).clamp(0, self.width_px as i64 - 1);
        let y = (((1.0 - v) * self.height_px as f32) as i64).clamp(0, self.height_px as i64 - 1);
        self.age_at_pixel(x as u32, y as u32)
    }

    /// Whether there is hair at (u, v) at age `t` (docs/models.md §9 threshold, see [`hair_present`]).
    pub fn hair_present(&self, u: f32, v: f32, t: f32) -> bool {
        hair_present(self.age_at_uv(u, v), t)
    }

    /// The ages quantised to 16 bits (a · 65535, rounded) for a 16-bit grey PNG: white =
    /// inner, black = no hair.
    pub fn to_luma16(&self) -> Vec<u16> {
        self.ages
            .par_iter()
            .map(|&a| (a * 65535.0).round() as u16)
            .collect()
    }

    /// Writes [`Self::to_luma16`] as a 16-bit grey PNG, atomically
    /// ([`crate::output::export::write_atomically`]).
    pub fn write_png16(&self, path: &std::path::Path) -> Result<(), Error> {
        use crate::base::png::{PngPixels, encode_png_rows};
        let values = self.to_luma16();
        let width = self.width_px as usize;
        crate::base::output_set::write_atomically(path, |w| {
            encode_png_rows(
                w,
                self.width_px,
                self.height_px,
                PngPixels::Grey16,
                |first, count, buf| {
                    let rows = &values[first as usize * width..][..count as usize * width];
                    buf.extend(rows.iter().flat_map(|v| v.to_be_bytes()));
                    Ok(())
                },
            )
        })
    }
}

/// docs/models.md §9's threshold: hair with disappearance age `age` is present at age `t` when
/// `age > 0` (there is hair at all) and `age ≥ t`. So at t = 0 all hair of the outer ∪
/// inner region is present, the outer-most (smallest age) goes first, and the inner region
/// (age 1) stays at t = 1. `t` outside [0,1] is clamped; NaN counts as 0.
pub fn hair_present(age: f32, t: f32) -> bool {
    age > 0.0 && age >= clamp_age(t)
}

/// Clamps an age to [0,1]; NaN becomes 0.
pub(crate) fn clamp_age(t: f32) -> f32 {
    if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) }
}

fn unpad(padded: &[u32], pw: usize, pad: usize, w: usize, h: usize) -> Vec<u32> {
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        let s = (y + pad) * pw + pad;
        out.extend_from_slice(&padded[s..s + w]);
    }
    out
}

fn oom(bytes: usize, what: &'static str) -> Error {
    Error::OutOfMemory {
        bytes: bytes as u64,
        what,
    }
}

fn try_vec<T: Clone>(len: usize, value: T, what: &'static str) -> Result<Vec<T>, Error> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| oom(len * std::mem::size_of::<T>(), what))?;
    v.resize(len, value);
    Ok(v)
}

#[cfg(test)]
mod tests;
