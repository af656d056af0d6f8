//! Maps keyed by integer cubes of space (the proxy's clusters, the mirror partners'
//! search), with a hash made for such keys: the standard library's SipHash, meant for
//! keys an attacker chooses, took a second of a million-vertex head's shape.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A map from a cube (its integer coordinates) to `V`.
pub type CubeMap<V> = HashMap<[i32; 3], V, BuildHasherDefault<CubeHasher>>;

/// The cube of side `side` that holds `p`.
pub fn cube_of(p: glam::Vec3, side: f32) -> [i32; 3] {
    (p / side).floor().as_ivec3().to_array()
}

/// A multiply-and-rotate hash (as rustc's FxHash) over the key's bytes.
#[derive(Clone, Copy, Debug, Default)]
pub struct CubeHasher(u64);

const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl Hasher for CubeHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(4) {
            let mut word = [0u8; 4];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u32(u32::from_le_bytes(word));
        }
    }

    fn write_u32(&mut self, i: u32) {
        self.0 = (self.0.rotate_left(5) ^ u64::from(i)).wrapping_mul(SEED);
    }

    fn write_usize(&mut self, i: usize) {
        self.0 = (self.0.rotate_left(5) ^ i as u64).wrapping_mul(SEED);
    }
}

/// Every cube of a box, no bound: for [`for_each_in_shell`].
pub const EVERY_CUBE: ([i32; 3], [i32; 3]) = ([i32::MIN; 3], [i32::MAX; 3]);

/// Calls `f` with each cube exactly `r` cubes from `home` along its farthest axis (the
/// shell of the (2r + 1)-cube box about it; `home` itself for r = 0) that lies within the
/// box of cubes `lo`–`hi`: the nearest-point searches' rings, each cube once.
pub fn for_each_in_shell(
    home: [i32; 3],
    r: i32,
    (lo, hi): ([i32; 3], [i32; 3]),
    mut f: impl FnMut([i32; 3]),
) {
    let span =
        |a: usize| home[a].saturating_sub(r).max(lo[a])..=home[a].saturating_add(r).min(hi[a]);
    for x in span(0) {
        for y in span(1) {
            if (x - home[0]).abs() == r || (y - home[1]).abs() == r {
                for z in span(2) {
                    f([x, y, z]);
                }
            } else {
                // Inside the shell's x–y outline (so r > 0): only its two z faces.
                for z in [home[2] - r, home[2] + r] {
                    if (lo[2]..=hi[2]).contains(&z) {
                        f([x, y, z]);
                    }
                }
            }
        }
    }
}

/// Points kept by cube, for the distance from anywhere to the nearest of them: the cubes
/// round the query in rings of growing reach, until no nearer point can lie beyond.
#[derive(Clone, Debug, Default)]
pub struct NearestPoints {
    side: f32,
    cubes: CubeMap<Vec<glam::Vec3>>,
    /// The least and greatest cube holding a point.
    bounds: Option<([i32; 3], [i32; 3])>,
}

impl NearestPoints {
    /// `points` (finite) kept in cubes of side `side` (> 0; a few points a cube is best).
    pub fn new(points: &[glam::Vec3], side: f32) -> Self {
        let side = if side > 0.0 && side.is_finite() {
            side
        } else {
            1.0
        };
        let mut cubes: CubeMap<Vec<glam::Vec3>> = CubeMap::default();
        let mut bounds: Option<([i32; 3], [i32; 3])> = None;
        for &p in points {
            let c = cube_of(p, side);
            cubes.entry(c).or_default().push(p);
            bounds = Some(match bounds {
                None => (c, c),
                Some((lo, hi)) => (
                    std::array::from_fn(|a| lo[a].min(c[a])),
                    std::array::from_fn(|a| hi[a].max(c[a])),
                ),
            });
        }
        Self {
            side,
            cubes,
            bounds,
        }
    }

    /// The distance from `p` to the nearest point, infinite when there are none: the very
    /// value the least of `p.distance(q)` over all of them gives (the same distances,
    /// fewer of them).
    pub fn distance(&self, p: glam::Vec3) -> f32 {
        let Some((lo, hi)) = self.bounds else {
            return f32::INFINITY;
        };
        let c = cube_of(p, self.side);
        let reach = (0..3)
            .map(|a| (c[a] - lo[a]).abs().max((hi[a] - c[a]).abs()))
            .max()
            .unwrap_or(0);
        let mut best = f32::INFINITY;
        for r in 0..=reach {
            // A point r cubes away along some axis lies at least (r − 1) sides from p.
            if best <= (r - 1).max(0) as f32 * self.side {
                break;
            }
            for_each_in_shell(c, r, (lo, hi), |k| {
                for q in self.cubes.get(&k).into_iter().flatten() {
                    best = best.min(p.distance(*q));
                }
            });
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_point_s_distance_is_the_scan_s() {
        let mut rng = crate::base::rng::Rng::new(7);
        let mut v = || glam::Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
        let points: Vec<glam::Vec3> = (0..500).map(|_| v() * 2.0 - 1.0).collect();
        let near = NearestPoints::new(&points, 0.13);
        // Queries inside the points' box, beyond it, and far away.
        let queries: Vec<glam::Vec3> = (0..400)
            .map(|i| (v() * 2.0 - 1.0) * [1.0, 1.5, 6.0][i % 3])
            .collect();
        for p in queries {
            let scan = points
                .iter()
                .map(|q| p.distance(*q))
                .fold(f32::INFINITY, f32::min);
            assert_eq!(near.distance(p).to_bits(), scan.to_bits(), "{p}");
        }
        assert_eq!(
            NearestPoints::new(&[], 1.0).distance(glam::Vec3::ZERO),
            f32::INFINITY
        );
        let one = NearestPoints::new(&[glam::Vec3::new(3.0, 0.0, 0.0)], 0.5);
        assert_eq!(one.distance(glam::Vec3::ZERO), 3.0);
    }

    #[test]
    fn a_shell_holds_each_cube_of_its_ring_once() {
        for r in 0..4 {
            let mut seen = Vec::new();
            for_each_in_shell([1, -2, 3], r, EVERY_CUBE, |k| seen.push(k));
            let ring = |k: [i32; 3]| (k[0] - 1).abs().max((k[1] + 2).abs()).max((k[2] - 3).abs());
            assert!(seen.iter().all(|&k| ring(k) == r));
            let n = seen.len();
            seen.sort_unstable();
            seen.dedup();
            assert_eq!(seen.len(), n);
            let side = 2 * r + 1;
            assert_eq!(n as i32, side.pow(3) - (side - 2).max(0).pow(3));
        }
        let mut clipped = 0;
        for_each_in_shell([0, 0, 0], 2, ([0, 0, 0], [5, 5, 5]), |_| clipped += 1);
        assert_eq!(clipped, 27 - 8);
    }

    #[test]
    fn neighbouring_cubes_are_told_apart() {
        let mut map: CubeMap<u32> = CubeMap::default();
        let mut n = 0;
        for x in -5..5 {
            for y in -5..5 {
                for z in -5..5 {
                    map.insert([x, y, z], n);
                    n += 1;
                }
            }
        }
        assert_eq!(map.len(), 1000);
        assert_eq!(map[&[-5, -5, -5]], 0);
        assert_eq!(map[&[4, 4, 4]], 999);
        assert_eq!(cube_of(glam::Vec3::new(-0.1, 0.5, 2.0), 1.0), [-1, 0, 2]);
    }
}
