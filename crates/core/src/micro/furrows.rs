//! Furrows between pores, SPEC §3 "Wrinkles between pores" [P §3.3, eq. 16].
//!
//! **Choice** (after SPEC's prototype notes and Weiss et al. 2023): every pore is linked to
//! its `links_per_pore` nearest neighbours (the union of these k-nearest-neighbour links is
//! a Delaunay-like mesh of polygonal cells, the micro-relief of real skin). A link's depth
//! depends on its direction: links along the preferred direction θ are primary lines of
//! full depth, links across it secondary, weighted by 1 − strength·sin²(angle − θ).
//! Across a furrow, at distance x from its axis, eq. 16: s(x) = −A·(1 − x²/ω²) for |x| < ω.
//! Along it the depth tapers toward both ends (SPEC §3) with a smoothstep, but — unlike a
//! taper over a fixed fraction of the length, which made every furrow an isolated dash
//! between two pores (SPEC §3's "tubes") — the taper at each end is at most as long as the
//! radius of the pore there: the furrow reaches full depth at the pore's rim and only fades
//! inside the pore, where the pore's own depth takes over. So the furrows meeting at a pore
//! join through it, and the network reads as connected polygonal cells, as in Weiss et al.
//! 2023. `taper` (a fraction of the length) still shortens the taper of short links.
//! Furrows are straight in the warped domain (see `micro::bake`), so on the map they bend
//! with the domain warp.

use crate::rng::Rng;

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
    /// Longest taper at each end as a fraction of the length, 0–0.5 (the taper never
    /// extends past the rim of the pore at that end).
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
    /// Length of the depth taper at the start and at the end, mm: min(taper × length,
    /// radius of the pore at that end).
    pub taper_mm: [f32; 2],
}

/// Eq. 16: the height −A·(1 − x²/ω²) at distance `x_mm` from the axis, 0 for |x| ≥ ω.
#[inline(always)]
pub fn cross_section(x_mm: f32, depth: f32, width_mm: f32) -> f32 {
    let q = x_mm * x_mm / (width_mm * width_mm);
    if q < 1.0 { -depth * (1.0 - q) } else { 0.0 }
}

/// The depth factor at `along_mm` from the start of a furrow `len_mm` long: a smoothstep
/// from 0 at the start up to 1 at `taper_mm[0]`, 1 in the middle, down to 0 over the last
/// `taper_mm[1]`; 0 outside the furrow.
#[inline(always)]
pub fn taper(along_mm: f32, len_mm: f32, taper_mm: [f32; 2]) -> f32 {
    let e = (along_mm / taper_mm[0].max(1e-6))
        .min((len_mm - along_mm) / taper_mm[1].max(1e-6))
        .clamp(0.0, 1.0);
    e * e * (3.0 - 2.0 * e)
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
            let taper = |pore: u32| (params.taper * len).min(pores[pore as usize].radius_mm);
            Furrow {
                start_mm: start,
                end_mm: [start[0] + d[0], start[1] + d[1]],
                depth: depth * weight,
                width_mm: width,
                taper_mm: [taper(a), taper(b)],
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
    use crate::micro::pores::{Placement, PoreStats, place_pores};

    fn close(got: f32, want: f32, tol: f32) {
        assert!(
            (got - want).abs() <= tol,
            "got {got}, want {want}, difference {}",
            got - want
        );
    }

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
    fn ends_taper_to_zero_within_their_own_lengths() {
        // 2 mm long, tapering over 0.4 mm at the start and 0.2 mm at the end.
        let t = [0.4, 0.2];
        assert_eq!(taper(0.0, 2.0, t), 0.0);
        assert_eq!(taper(2.0, 2.0, t), 0.0);
        assert_eq!(taper(1.0, 2.0, t), 1.0);
        // Full depth from the end of each taper on (the pore rims).
        assert_eq!(taper(0.4, 2.0, t), 1.0);
        assert_eq!(taper(1.8, 2.0, t), 1.0);
        // Half way along each taper: smoothstep(0.5) = 0.5.
        close(taper(0.2, 2.0, t), 0.5, 1e-6);
        close(taper(1.9, 2.0, t), 0.5, 1e-6);
        // e = 0.25: 0.0625·2.5 = 0.15625
        close(taper(0.1, 2.0, t), 0.156_25, 1e-6);
        assert_eq!(taper(-0.1, 2.0, t), 0.0);
        assert_eq!(taper(2.1, 2.0, t), 0.0);
    }

    #[test]
    fn tapers_end_at_the_pore_rims() {
        let stats = PoreStats {
            radius_mm: (0.3, 0.1),
            depth: (1.0, 0.0),
            falloff: (1.0, 0.0),
        };
        let pores = place_pores(200, &stats, Placement::BlueNoise, 50.0, false, 9).pores;
        let net = build_network(&pores, &params(), 50.0, false, 9);
        // The pore at an end (end_mm = start + delta may differ from the centre in the
        // last bit).
        let radius_at = |p: [f32; 2]| {
            let d = |q: &Pore| super::super::pores::distance2(p, q.centre_mm, 50.0, false);
            pores
                .iter()
                .min_by(|a, b| d(a).total_cmp(&d(b)))
                .map(|q| q.radius_mm)
                .unwrap()
        };
        for f in &net {
            let len = super::super::pores::distance2(f.start_mm, f.end_mm, 50.0, false).sqrt();
            for (t, end) in f.taper_mm.into_iter().zip([f.start_mm, f.end_mm]) {
                close(t, (0.25 * len).min(radius_at(end)), 1e-6);
            }
        }
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
