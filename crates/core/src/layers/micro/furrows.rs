//! Furrows between pores, docs/models.md §4 "Wrinkles between pores" [P §3.3, eq. 16].
//!
//! **Choice** (after docs/models.md's prototype notes and Weiss et al. 2023): every pore is linked to
//! its `links_per_pore` nearest neighbours (the union of these k-nearest-neighbour links is
//! a Delaunay-like mesh of polygonal cells, the micro-relief of real skin). A link's depth
//! depends on its direction: links along the preferred direction θ are primary lines of
//! full depth, links across it secondary, weighted by 1 − strength·sin²(angle − θ).
//! Across a furrow, at distance x from its axis, eq. 16: s(x) = −A·(1 − x²/ω²) for |x| < ω.
//! **Choice** (docs/models.md §4 asks to taper toward the ends): tapering the *depth* to 0 at both ends
//! made every furrow an isolated dash between two pores, with a light gap at each pore
//! (docs/models.md §4's "tubes"), even when the taper stopped at the pore rim (tried: the pore is
//! shallower than the furrows meeting in it, so the gap stays). So the depth stays full to
//! the ends, x is the distance to the *segment* (round caps, so the furrows meeting at a pore
//! join smoothly through it), and what tapers is the *width*: from ω in the middle down to
//! ω/2 at the ends, over `taper` of the length at each end (a smoothstep). The network then
//! reads as connected polygonal cells with pores at the junctions, as in Weiss et al. 2023.
//! Furrows are straight in the warped domain (see `micro::bake`), so on the map they bend
//! with the domain warp.

use crate::base::rng::Rng;

use super::pores::{Pore, delta};

/// Settings of the furrow network (validated by `project::FurrowSection`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FurrowParams {
    /// k of the k-nearest-neighbour links, 1–8.
    pub links_per_pore: u32,
    /// Keep at most this many links (a seeded random subset), all when `None`.
    pub max_count: Option<u32>,
    /// A (height units): mean ± spread.
    pub depth: (f32, f32),
    /// ω (mm, half-width): mean ± spread.
    pub width_mm: (f32, f32),
    /// Preferred direction θ, degrees counter-clockwise from +u.
    pub direction_deg: f32,
    /// 0 = all links equal, 1 = links across θ vanish.
    pub direction_strength: f32,
    /// Fraction of the length over which the width narrows at each end, 0–0.5.
    pub taper: f32,
}

/// One furrow: a straight segment from `start_mm` to `end_mm` (the end may lie outside the
/// map when the link wraps around a tiled map).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Furrow {
    pub start_mm: [f32; 2],
    pub end_mm: [f32; 2],
    /// A in height units, ≥ 0 (direction weight included).
    pub depth: f32,
    /// ω in mm, > 0.
    pub width_mm: f32,
    /// Fraction of the length over which the width narrows at each end.
    pub taper: f32,
}

/// Eq. 16's shape in units of A, as a function of q = x²/ω²: 1 − q inside, 0 outside.
/// The one copy of the formula: [`cross_section`] and the baker both use it.
#[inline(always)]
pub fn profile(q: f32) -> f32 {
    if q < 1.0 { 1.0 - q } else { 0.0 }
}

/// The width factor (1/2 at an end, 1 from the taper length on) from `e`, the distance to
/// the nearer end over the taper length: 0.5 + 0.5·smoothstep(e). The one copy of the
/// taper, shared by [`width_factor`] and the baker.
#[inline(always)]
pub fn taper(e: f32) -> f32 {
    let e = e.clamp(0.0, 1.0);
    0.5 + 0.5 * (e * e * (3.0 - 2.0 * e))
}

/// Eq. 16: the height −A·(1 − x²/ω²) at distance `x_mm` from the axis, 0 for |x| ≥ ω.
#[inline(always)]
pub fn cross_section(x_mm: f32, depth: f32, width_mm: f32) -> f32 {
    -depth * profile(x_mm * x_mm / (width_mm * width_mm))
}

/// The width factor at `along_mm` from the start of a furrow `len_mm` long whose ends
/// narrow over `taper_len_mm`: 1/2 at the ends (and beyond them, on the round caps), rising
/// with a smoothstep to 1 at `taper_len_mm` from each end.
#[inline(always)]
pub fn width_factor(along_mm: f32, len_mm: f32, taper_len_mm: f32) -> f32 {
    let a = along_mm.clamp(0.0, len_mm);
    taper(a.min(len_mm - a) / taper_len_mm.max(1e-6))
}

/// The height of a furrow (eq. 16 around the segment) at `along_mm` along its axis and
/// `cross_mm` across it: −A·(1 − d²/(ω·f)²) with d the distance to the segment and f the
/// [`width_factor`]; 0 outside.
#[inline(always)]
pub fn height(f: &Furrow, along_mm: f32, cross_mm: f32) -> f32 {
    let d = [f.end_mm[0] - f.start_mm[0], f.end_mm[1] - f.start_mm[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let beyond = along_mm - along_mm.clamp(0.0, len);
    let dist = (cross_mm * cross_mm + beyond * beyond).sqrt();
    cross_section(
        dist,
        f.depth,
        f.width_mm * width_factor(along_mm, len, f.taper * len),
    )
}

/// Links the pores into a network (see the module docs). Deterministic in `seed`.
pub fn build_network(
    pores: &[Pore],
    params: &FurrowParams,
    size_mm: f32,
    tile: bool,
    seed: u64,
) -> Vec<Furrow> {
    let k = params.links_per_pore as usize;
    if pores.len() < 2 || k == 0 {
        return Vec::new();
    }
    let centres: Vec<[f32; 2]> = pores.iter().map(|p| p.centre_mm).collect();
    let mut links: Vec<(u32, u32)> = Vec::with_capacity(pores.len() * k);
    let index = NeighbourGrid::new(&centres, size_mm);
    for a in 0..centres.len() {
        for b in index.nearest(&centres, a, k, size_mm, tile) {
            links.push((a.min(b) as u32, a.max(b) as u32));
        }
    }
    links.sort_unstable();
    links.dedup();
    if let Some(max) = params.max_count {
        let max = max as usize;
        if max < links.len() {
            // Partial Fisher–Yates, then back to index order for a stable stamping order.
            let mut rng = Rng::for_stream(seed, 0x6675_7272_0001);
            for i in 0..max {
                let j = i + rng.below((links.len() - i) as u64) as usize;
                links.swap(i, j);
            }
            links.truncate(max);
            links.sort_unstable();
        }
    }
    let theta = params.direction_deg.to_radians();
    let (ct, st) = (theta.cos(), theta.sin());
    links
        .iter()
        .enumerate()
        .map(|(n, &(a, b))| {
            let mut rng = Rng::for_stream(seed ^ 0x6675_7272_0002, n as u64);
            let start = centres[a as usize];
            let d = delta(start, centres[b as usize], size_mm, tile);
            let len = (d[0] * d[0] + d[1] * d[1]).sqrt().max(1e-9);
            let sin = (d[0] * st - d[1] * ct) / len;
            let weight = 1.0 - params.direction_strength * sin * sin;
            let depth = (params.depth.0 + params.depth.1 * (2.0 * rng.next_f32() - 1.0)).max(0.0);
            let width =
                (params.width_mm.0 + params.width_mm.1 * (2.0 * rng.next_f32() - 1.0)).max(1e-4);
            Furrow {
                start_mm: start,
                end_mm: [start[0] + d[0], start[1] + d[1]],
                depth: depth * weight,
                width_mm: width,
                taper: params.taper,
            }
        })
        .collect()
}

/// A bucket grid over the map for k-nearest-neighbour queries.
struct NeighbourGrid {
    n: usize,
    cell_mm: f32,
    buckets: Vec<Vec<u32>>,
}

impl NeighbourGrid {
    fn new(points: &[[f32; 2]], size_mm: f32) -> Self {
        // About two points per cell.
        let n = ((points.len() as f32 / 2.0).sqrt().ceil() as usize).clamp(1, 4096);
        let cell_mm = size_mm / n as f32;
        let mut buckets = vec![Vec::new(); n * n];
        for (k, p) in points.iter().enumerate() {
            let (i, j) = Self::cell_of(*p, cell_mm, n);
            buckets[j * n + i].push(k as u32);
        }
        Self {
            n,
            cell_mm,
            buckets,
        }
    }

    fn cell_of(p: [f32; 2], cell_mm: f32, n: usize) -> (usize, usize) {
        let c = |x: f32| ((x / cell_mm).max(0.0) as usize).min(n - 1);
        (c(p[0]), c(p[1]))
    }

    /// The `k` nearest other points of `a`, nearest first (ties by index).
    fn nearest(
        &self,
        points: &[[f32; 2]],
        a: usize,
        k: usize,
        size_mm: f32,
        tile: bool,
    ) -> Vec<usize> {
        let p = points[a];
        let (ci, cj) = Self::cell_of(p, self.cell_mm, self.n);
        let mut found: Vec<(f32, usize)> = Vec::new();
        let n = self.n as isize;
        for ring in 0..=n {
            for dj in -ring..=ring {
                for di in -ring..=ring {
                    if di.abs() != ring && dj.abs() != ring {
                        continue;
                    }
                    let (mut i, mut j) = (ci as isize + di, cj as isize + dj);
                    if tile {
                        if ring > n / 2 {
                            continue;
                        }
                        i = i.rem_euclid(n);
                        j = j.rem_euclid(n);
                    } else if i < 0 || j < 0 || i >= n || j >= n {
                        continue;
                    }
                    for &b in &self.buckets[j as usize * self.n + i as usize] {
                        if b as usize != a {
                            found.push((
                                super::pores::distance2(p, points[b as usize], size_mm, tile),
                                b as usize,
                            ));
                        }
                    }
                }
            }
            if found.len() >= k {
                found.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
                // Every point beyond the searched rings is farther than ring·cell.
                let reach = ring as f32 * self.cell_mm;
                if found[k - 1].0 <= reach * reach {
                    break;
                }
            }
        }
        found.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        found.dedup_by_key(|f| f.1);
        found.truncate(k);
        found.into_iter().map(|f| f.1).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layers::micro::pores::{Placement, PoreStats, place_pores};
    use crate::test_util::close;

    fn params() -> FurrowParams {
        FurrowParams {
            links_per_pore: 4,
            max_count: None,
            depth: (1.0, 0.0),
            width_mm: (0.3, 0.0),
            direction_deg: 0.0,
            direction_strength: 0.0,
            taper: 0.25,
        }
    }

    #[test]
    fn eq16_cross_section_at_hand_computed_offsets() {
        // A = 2, ω = 0.5: x = 0 → −2; x = 0.25 → −2·(1 − 0.25) = −1.5; x = 0.4 → −2·0.36 = −0.72
        close(cross_section(0.0, 2.0, 0.5), -2.0, 1e-6);
        close(cross_section(0.25, 2.0, 0.5), -1.5, 1e-6);
        close(cross_section(-0.4, 2.0, 0.5), -0.72, 1e-6);
        assert_eq!(cross_section(0.5, 2.0, 0.5), 0.0);
        assert_eq!(cross_section(0.9, 2.0, 0.5), 0.0);
    }

    #[test]
    fn width_narrows_to_half_at_the_ends_and_depth_stays_full() {
        // 2 mm long, narrowing over 0.4 mm at each end.
        assert_eq!(width_factor(0.0, 2.0, 0.4), 0.5);
        assert_eq!(width_factor(2.0, 2.0, 0.4), 0.5);
        assert_eq!(
            width_factor(-0.3, 2.0, 0.4),
            0.5,
            "round cap beyond the start"
        );
        assert_eq!(width_factor(1.0, 2.0, 0.4), 1.0);
        assert_eq!(width_factor(0.4, 2.0, 0.4), 1.0);
        // Half way along the taper: smoothstep(0.5) = 0.5 → 0.75.
        close(width_factor(0.2, 2.0, 0.4), 0.75, 1e-6);
        close(width_factor(1.9, 2.0, 0.4), 0.5 + 0.5 * 0.156_25, 1e-6);
        let f = Furrow {
            start_mm: [0.0, 0.0],
            end_mm: [2.0, 0.0],
            depth: 1.0,
            width_mm: 0.4,
            taper: 0.2,
        };
        // Full depth on the axis at the very ends: the furrows meeting at a pore join.
        close(height(&f, 0.0, 0.0), -1.0, 1e-6);
        close(height(&f, 2.0, 0.0), -1.0, 1e-6);
        // Middle, x = 0.2 = ω/2: −(1 − 0.25) = −0.75; at the end the half width is 0.2.
        close(height(&f, 1.0, 0.2), -0.75, 1e-6);
        close(height(&f, 0.0, 0.1), -0.75, 1e-6);
        assert_eq!(height(&f, 0.0, 0.2), 0.0);
        // Round cap: 0.1 mm beyond the end on the axis, like 0.1 mm across.
        close(height(&f, 2.1, 0.0), -0.75, 1e-6);
        assert_eq!(height(&f, 2.25, 0.0), 0.0);
    }

    #[test]
    fn network_links_every_pore_to_its_neighbours() {
        let stats = PoreStats {
            radius_mm: (0.3, 0.0),
            depth: (1.0, 0.0),
            falloff: (1.0, 0.0),
        };
        let pores = place_pores(400, &stats, Placement::BlueNoise, 50.0, false, 3).pores;
        let net = build_network(&pores, &params(), 50.0, false, 3);
        let mut degree = vec![0u32; pores.len()];
        let index_of = |p: [f32; 2]| {
            (0..pores.len())
                .min_by(|&a, &b| {
                    let d = |k: usize| {
                        super::super::pores::distance2(p, pores[k].centre_mm, 50.0, false)
                    };
                    d(a).total_cmp(&d(b))
                })
                .unwrap()
        };
        for f in &net {
            degree[index_of(f.start_mm)] += 1;
            degree[index_of(f.end_mm)] += 1;
        }
        assert!(
            degree.iter().all(|&d| d >= 4),
            "a pore has fewer than k links"
        );
        let mean = degree.iter().sum::<u32>() as f32 / degree.len() as f32;
        assert!((4.0..6.0).contains(&mean), "mean degree {mean}");
        // Brute-force check of one pore's nearest neighbour being linked.
        let a = 17;
        let nearest = (0..pores.len())
            .filter(|&b| b != a)
            .min_by(|&x, &y| {
                let d = |b: usize| {
                    super::super::pores::distance2(
                        pores[a].centre_mm,
                        pores[b].centre_mm,
                        50.0,
                        false,
                    )
                };
                d(x).total_cmp(&d(y))
            })
            .unwrap();
        assert!(net.iter().any(|f| {
            let (s, e) = (index_of(f.start_mm), index_of(f.end_mm));
            (s, e) == (a.min(nearest), a.max(nearest))
        }));
    }

    #[test]
    fn direction_makes_primary_lines_deeper_and_cap_is_exact() {
        let stats = PoreStats {
            radius_mm: (0.3, 0.0),
            depth: (1.0, 0.0),
            falloff: (1.0, 0.0),
        };
        let pores = place_pores(300, &stats, Placement::BlueNoise, 50.0, true, 4).pores;
        let p = FurrowParams {
            direction_deg: 90.0,
            direction_strength: 0.8,
            ..params()
        };
        let net = build_network(&pores, &p, 50.0, true, 4);
        for f in &net {
            let d = [f.end_mm[0] - f.start_mm[0], f.end_mm[1] - f.start_mm[1]];
            let sin2 = d[0] * d[0] / (d[0] * d[0] + d[1] * d[1]);
            close(f.depth, 1.0 - 0.8 * sin2, 1e-5);
            // Tiled links take the short way around: no link longer than a few spacings.
            assert!((d[0] * d[0] + d[1] * d[1]).sqrt() < 10.0);
        }
        let capped = build_network(
            &pores,
            &FurrowParams {
                max_count: Some(100),
                ..p
            },
            50.0,
            true,
            4,
        );
        assert_eq!(capped.len(), 100);
    }
}
