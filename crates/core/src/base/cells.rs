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

#[cfg(test)]
mod tests {
    use super::*;

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
