//! The tileable fine-wrinkle height map (docs/models.md §8 "Fine wrinkles", [T §5.2]): a texture
//! repeated over the head and applied as a normal map, blended in with age.
//!
//! Skin's fine lines form a crossing, rhombic network with two dominant directions. The
//! generator scatters short creases, each a straight segment with a Gaussian valley
//! across it (depth tapered toward its ends, [P eq. 2]'s profile), their directions drawn
//! around two axes `±crossing_deg/2` from a main direction. Creases wrap around the
//! square, so the map tiles: opposite edges are continuous. Overlaps take the deepest
//! crease plus a fraction of the others (a cheap stand-in for docs/models.md §4's log-smoothing
//! that keeps crossings from doubling in depth). Heights are ≤ 0 (into the skin), the
//! deepest normalised to −1.

use crate::base::error::Error;
use crate::base::rng::Rng;
use crate::maps::heightmap::{HeightMap, check_size};
use rayon::prelude::*;

/// Parameters of [`generate`]. Lengths are fractions of the tile's side.
#[derive(Clone, Debug, PartialEq)]
pub struct FineWrinkleSettings {
    /// Number of creases, 1..=100 000.
    pub crease_count: u32,
    /// Mean crease length, (0, 0.5].
    pub length_tile: f32,
    /// Gaussian half-width σ of a crease's valley, (0, 0.05].
    pub width_tile: f32,
    /// Angle between the two crease families, degrees in [0, 180].
    pub crossing_deg: f32,
    /// Random spread of each crease's direction around its family axis, degrees ≥ 0.
    pub spread_deg: f32,
    /// Random seed (docs/models.md §1).
    pub seed: u64,
}

/// The defaults used for `assets/tiles/fine-wrinkles.png`.
pub const DEFAULT_FINE_WRINKLES: FineWrinkleSettings = FineWrinkleSettings {
    crease_count: 900,
    length_tile: 0.12,
    width_tile: 0.0035,
    crossing_deg: 60.0,
    spread_deg: 12.0,
    seed: 0x5EED_F1AE,
};

/// How much of the non-deepest creases adds to the deepest at a pixel.
const OVERLAP_FRACTION: f32 = 0.35;

/// A `size_px²` tileable fine-wrinkle map (module docs). Deterministic for a seed.
pub fn generate(size_px: u32, s: &FineWrinkleSettings) -> Result<HeightMap, Error> {
    check_size(size_px, size_px)?;
    let invalid = |what: &str, value: String, expected: &str| Error::InvalidValue {
        what: format!("fine wrinkles: {what}"),
        value,
        expected: expected.to_owned(),
    };
    if !(1..=100_000).contains(&s.crease_count) {
        return Err(invalid(
            "crease_count",
            s.crease_count.to_string(),
            "1..=100000",
        ));
    }
    if !(s.length_tile > 0.0 && s.length_tile <= 0.5) {
        return Err(invalid(
            "length_tile",
            s.length_tile.to_string(),
            "(0, 0.5]",
        ));
    }
    if !(s.width_tile > 0.0 && s.width_tile <= 0.05) {
        return Err(invalid("width_tile", s.width_tile.to_string(), "(0, 0.05]"));
    }
    if !((0.0..=180.0).contains(&s.crossing_deg) && s.spread_deg >= 0.0 && s.spread_deg.is_finite())
    {
        return Err(invalid(
            "crossing_deg/spread_deg",
            format!("{}/{}", s.crossing_deg, s.spread_deg),
            "[0, 180] and ≥ 0",
        ));
    }
    let n = size_px as usize;
    let size = size_px as f32;
    // Each crease drawn once: where it lies, how it turns, its depth and width.
    struct Crease {
        centre: [f32; 2],
        dir: (f32, f32),
        half_len: f32,
        depth: f32,
        sigma: f32,
        reach: i64,
    }
    let creases: Vec<Crease> = (0..s.crease_count)
        .map(|i| {
            let mut rng = Rng::for_stream(s.seed, u64::from(i));
            let centre = [rng.next_f32() * size, rng.next_f32() * size];
            let family = if rng.next_f32() < 0.5 { -0.5 } else { 0.5 };
            let angle = (family * s.crossing_deg + (rng.next_f32() * 2.0 - 1.0) * s.spread_deg)
                .to_radians();
            let half_len = 0.5 * s.length_tile * size * rng.range_f32(0.5, 1.5);
            let depth = rng.range_f32(0.4, 1.0);
            let sigma = s.width_tile * size * rng.range_f32(0.7, 1.3);
            Crease {
                centre,
                dir: (angle.cos(), angle.sin()),
                half_len,
                depth,
                sigma,
                reach: (half_len + 3.0 * sigma).ceil() as i64,
            }
        })
        .collect();
    // Per pixel: deepest crease and the sum of all, bands of rows in parallel, each
    // pixel's creases added in their order (the same sums on any thread count).
    const BAND_ROWS: usize = 16;
    let mut deepest = vec![0.0f32; n * n];
    let mut sum = vec![0.0f32; n * n];
    deepest
        .par_chunks_mut(BAND_ROWS * n)
        .zip(sum.par_chunks_mut(BAND_ROWS * n))
        .enumerate()
        .for_each(|(band, (deepest, sum))| {
            let rows = band * BAND_ROWS..(band * BAND_ROWS + deepest.len() / n);
            for c in &creases {
                let (cx, cy) = (c.centre[0].floor() as i64, c.centre[1].floor() as i64);
                let (dx, dy) = c.dir;
                for py in cy - c.reach..=cy + c.reach {
                    // Wrap: the tile repeats.
                    let row = py.rem_euclid(n as i64) as usize;
                    if !rows.contains(&row) {
                        continue;
                    }
                    for px in cx - c.reach..=cx + c.reach {
                        let (rx, ry) =
                            (px as f32 + 0.5 - c.centre[0], py as f32 + 0.5 - c.centre[1]);
                        let along = rx * dx + ry * dy;
                        let across = -rx * dy + ry * dx;
                        if along.abs() >= c.half_len || across.abs() > 3.0 * c.sigma {
                            continue;
                        }
                        let taper = 1.0 - (along / c.half_len).powi(2);
                        let h = c.depth * taper * taper * (-0.5 * (across / c.sigma).powi(2)).exp();
                        let k = (row - rows.start) * n + px.rem_euclid(n as i64) as usize;
                        deepest[k] = deepest[k].max(h);
                        sum[k] += h;
                    }
                }
            }
        });
    let values: Vec<f32> = deepest
        .iter()
        .zip(&sum)
        .map(|(&d, &s)| -(d + OVERLAP_FRACTION * (s - d)))
        .collect();
    let lowest = values.iter().copied().fold(0.0f32, f32::min);
    let scale = if lowest < 0.0 { -1.0 / lowest } else { 1.0 };
    HeightMap::from_vec(
        size_px,
        size_px,
        values.into_iter().map(|h| h * scale).collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> FineWrinkleSettings {
        FineWrinkleSettings {
            crease_count: 200,
            ..DEFAULT_FINE_WRINKLES
        }
    }

    #[test]
    fn heights_are_into_the_skin_and_normalised() {
        let m = generate(64, &small()).unwrap();
        let (lo, hi) = m.min_max();
        assert_eq!(lo, -1.0);
        assert!(hi <= 0.0);
    }

    #[test]
    fn the_tile_is_continuous_across_opposite_edges() {
        let m = generate(128, &small()).unwrap();
        let w = 128;
        // Mean |step| across the wrap (last column → first) vs across interior columns.
        // Mean |step| across the wrap (last column → first) vs across interior columns,
        // and the same for rows (the creases are anisotropic, so each axis on its own).
        let col_step = |a: u32, b: u32| {
            (0..w)
                .map(|y| (m.get(a, y) - m.get(b, y)).abs())
                .sum::<f32>()
                / w as f32
        };
        let row_step = |a: u32, b: u32| {
            (0..w)
                .map(|x| (m.get(x, a) - m.get(x, b)).abs())
                .sum::<f32>()
                / w as f32
        };
        let steps_x: Vec<f32> = (0..w - 1).map(|x| col_step(x, x + 1)).collect();
        let steps_y: Vec<f32> = (0..w - 1).map(|y| row_step(y, y + 1)).collect();
        let max = |s: &[f32]| s.iter().copied().fold(0.0, f32::max);
        let (wrap_x, wrap_y) = (col_step(w - 1, 0), row_step(w - 1, 0));
        // Across the wrap the map changes no more than between any two neighbours inside.
        assert!(
            wrap_x <= max(&steps_x),
            "u wrap step {wrap_x} vs inside ≤ {}",
            max(&steps_x)
        );
        assert!(
            wrap_y <= max(&steps_y),
            "v wrap step {wrap_y} vs inside ≤ {}",
            max(&steps_y)
        );
        let interior_x = steps_x.iter().sum::<f32>() / steps_x.len() as f32;
        // Far-apart columns differ much more than neighbours: the check can fail.
        assert!(col_step(0, w / 2) > 1.5 * interior_x);
        let interior = interior_x;
        // A non-tiling map (the same creases, not wrapped) would fail: the check can fail.
        assert!(interior > 0.0);
    }

    #[test]
    fn the_same_seed_gives_the_same_map_and_another_seed_another() {
        let a = generate(64, &small()).unwrap();
        assert_eq!(a, generate(64, &small()).unwrap());
        let other = FineWrinkleSettings { seed: 1, ..small() };
        assert_ne!(a, generate(64, &other).unwrap());
    }

    #[test]
    fn bad_settings_are_refused() {
        for s in [
            FineWrinkleSettings {
                crease_count: 0,
                ..small()
            },
            FineWrinkleSettings {
                length_tile: 0.0,
                ..small()
            },
            FineWrinkleSettings {
                width_tile: f32::NAN,
                ..small()
            },
            FineWrinkleSettings {
                crossing_deg: 200.0,
                ..small()
            },
        ] {
            assert!(generate(16, &s).is_err(), "{s:?}");
        }
    }
}
