//! Tests of the micro-relief baker.

use super::*;
use crate::project::Project;

fn project(tile: bool) -> Project {
    let mut p = Project {
        tile,
        ..Project::default()
    };
    p.pores.count = 300;
    p
}

#[test]
fn byte_identical_on_1_and_2_threads_and_across_runs() {
    let relief = project(true).micro_relief().unwrap();
    let pool1 = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let pool2 = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let a = pool1.install(|| relief.bake(256).unwrap().0);
    let b = pool2.install(|| relief.bake(256).unwrap().0);
    let c = project(true).micro_relief().unwrap().bake(256).unwrap().0;
    let bits = |m: &HeightMap| m.data().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(bits(&a), bits(&c));
    let (lo, hi) = a.min_max();
    assert!(lo < -0.5 && hi > 0.0, "range {lo}..{hi}");
}

#[test]
fn simd_and_scalar_paths_give_the_same_bytes() {
    // Every level this CPU has (AVX-512, AVX2) against the baseline, height and normals,
    // tiled and not, at a width that is not a whole number of chunks.
    for tile in [false, true] {
        let relief = project(tile).micro_relief().unwrap();
        let settings = relief.normal_settings();
        let bake = |level| {
            relief
                .bake_at(200, Parts::default(), Some(&settings), level)
                .unwrap()
        };
        let (base_h, base_n, _) = bake(Level::Baseline);
        let bits = |m: &HeightMap| m.data().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
        for level in [Level::Avx2, Level::Avx512] {
            let (h, n, _) = bake(level);
            assert_eq!(bits(&h), bits(&base_h), "heights, {level:?}, tile {tile}");
            assert_eq!(n, base_n, "normals, {level:?}, tile {tile}");
        }
    }
}

#[test]
fn fused_normals_equal_encoding_the_baked_heights() {
    for (tile, convention) in [
        (false, crate::maps::normal_map::Convention::OpenGl),
        (true, crate::maps::normal_map::Convention::DirectX),
    ] {
        let relief = project(tile).micro_relief().unwrap();
        let settings = NormalSettings {
            strength: 0.01,
            convention,
            tiling: tile,
        };
        // 2 full bands and a short one, so halos cross band and map edges.
        let size = 2 * BAND_ROWS as u32 + 7;
        let (h, rgb, _) = relief.bake_with_normals(size, &settings).unwrap();
        let (plain, _) = relief.bake(size).unwrap();
        assert_eq!(h.data(), plain.data());
        let want = crate::maps::normal_map::encode_rgb8(&h, &settings).unwrap();
        assert_eq!(rgb.len(), want.len());
        let first_diff = rgb.iter().zip(&want).position(|(a, b)| a != b);
        assert_eq!(first_diff, None, "first differing byte");
        // Not flat: the relief shows in the normals.
        assert!(rgb.iter().step_by(3).any(|&r| r < 100) && rgb.iter().step_by(3).any(|&r| r > 156));
    }
}

#[test]
fn bake_into_reuses_buffers_and_equals_a_fresh_bake() {
    let relief = project(true).micro_relief().unwrap();
    let settings = relief.normal_settings();
    // Stale buffers of another size, full of values a bake never writes (NaN, 0xAB):
    // growing, shrinking and an unchanged size must all overwrite every value.
    let mut map = HeightMap::from_vec(3, 3, vec![f32::NAN; 9]).unwrap();
    let mut rgb = vec![0xAB; 5];
    let bits = |m: &HeightMap| m.data().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
    for size in [2 * BAND_ROWS as u32 + 7, 40, 40] {
        let (want_h, want_rgb, _) = relief.bake_with_normals(size, &settings).unwrap();
        map.data_mut().fill(f32::NAN);
        rgb.fill(0xAB);
        relief
            .bake_into(size, &mut map, &mut rgb, &settings)
            .unwrap();
        assert_eq!((map.width_px(), map.height_px()), (size, size));
        assert_eq!(bits(&map), bits(&want_h), "heights at {size}²");
        assert_eq!(rgb, want_rgb, "normals at {size}²");
    }
    // Bad sizes are errors and leave the buffers as they were.
    let before = (bits(&map), rgb.clone());
    assert!(relief.bake_into(0, &mut map, &mut rgb, &settings).is_err());
    assert_eq!((bits(&map), rgb.clone()), before);
}

#[test]
fn fused_bands_reusing_their_neighbours_rows_equal_two_passes() {
    // One thread: runs of bands per task, each band taking its first row and halo above
    // from the previous band; the bytes must not change.
    let relief = project(true).micro_relief().unwrap();
    let settings = relief.normal_settings();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let size = 9 * BAND_ROWS as u32 + 5;
    let (h, rgb, _) = pool.install(|| relief.bake_with_normals(size, &settings).unwrap());
    let (plain, _) = relief.bake(size).unwrap();
    let bits = |m: &HeightMap| m.data().iter().map(|h| h.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&h), bits(&plain));
    let want = crate::maps::normal_map::encode_rgb8(&plain, &settings).unwrap();
    let first_diff = rgb.iter().zip(&want).position(|(a, b)| a != b);
    assert_eq!(first_diff, None, "first differing byte");
}

/// FNV-1a over the height bits and the normal bytes.
fn fingerprint(map: &HeightMap, rgb: &[u8]) -> u64 {
    let bytes = map.data().iter().flat_map(|h| h.to_le_bytes());
    bytes
        .chain(rgb.iter().copied())
        .fold(0xcbf2_9ce4_8422_2325, |h, b| {
            (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
        })
}

#[test]
fn output_bytes_are_pinned() {
    // Speed work must not move a single bit: the rough preset (warp, 6 octaves of
    // noise, dense furrows) at widths that are and are not whole chunks, tiled and not.
    // A deliberate change of the model updates these numbers, and says so.
    let mut seen = Vec::new();
    for (size, tile) in [(200, false), (333, true), (512, false)] {
        let text = include_str!("../../../../../../assets/presets/rough.agesim.json");
        let mut p = Project::from_json_str(text, "rough").unwrap();
        p.tile = tile;
        let relief = p.micro_relief().unwrap();
        let (map, rgb, _) = relief
            .bake_with_normals(size, &relief.normal_settings())
            .unwrap();
        seen.push(fingerprint(&map, &rgb));
    }
    assert_eq!(
        seen,
        [
            8666260400845450711,
            15775006142372411161,
            8994032868488939321
        ],
        "fingerprints changed"
    );
}

#[test]
fn a_lone_pore_bakes_to_its_profile_for_every_profile_and_rim() {
    // One pore in the middle, no furrows, noise or warp: the map is the pore's formula.
    for profile in [
        PoreProfile::Gaussian,
        PoreProfile::Quadratic,
        PoreProfile::Quartic,
    ] {
        for rim in [Rim::Smooth, Rim::Exact] {
            let mut p = Project::default();
            p.pores.count = 1;
            p.pores.radius_mm = crate::project::MeanSpread::new(5.0 / 10.0, 0.0);
            p.pores.depth = crate::project::MeanSpread::new(1.0, 0.0);
            p.pores.falloff = crate::project::MeanSpread::new(1.0, 0.0);
            p.pores.profile = profile;
            p.pores.rim = rim;
            p.furrows.enabled = false;
            p.noise.details = 0.0;
            p.warp.strength_mm = 0.0;
            let relief = p.micro_relief().unwrap();
            let pore = relief.pores()[0];
            let (map, _) = relief.bake(256).unwrap();
            let shape = PoreShape { profile, rim };
            let mut worst = 0.0f32;
            for y in 0..256 {
                for x in 0..256 {
                    let q = [
                        crate::maps::heightmap::pixel_to_u(x, 256) * 50.0,
                        crate::maps::heightmap::pixel_to_v(y, 256) * 50.0,
                    ];
                    let r2 =
                        (q[0] - pore.centre_mm[0]).powi(2) + (q[1] - pore.centre_mm[1]).powi(2);
                    worst = worst.max((map.get(x, y) - shape.height(&pore, r2)).abs());
                }
            }
            assert!(
                worst < 1e-5,
                "{profile:?}/{rim:?}: largest difference {worst}"
            );
            assert!(map.min_max().0 < -0.5, "{profile:?}/{rim:?}");
        }
    }
}

#[test]
fn a_lone_furrow_bakes_to_eq_16() {
    let mut p = Project::default();
    p.pores.count = 2;
    p.pores.placement = crate::layers::micro::pores::Placement::Uniform;
    p.pores.depth = crate::project::MeanSpread::new(0.0, 0.0);
    p.pores.radius_mm = crate::project::MeanSpread::new(0.01, 0.0);
    p.furrows.links_per_pore = 1;
    p.furrows.depth = crate::project::MeanSpread::new(1.0, 0.0);
    p.furrows.width_mm = crate::project::MeanSpread::new(0.6, 0.0);
    p.furrows.direction_strength = 0.0;
    p.noise.details = 0.0;
    p.warp.strength_mm = 0.0;
    // A large β makes the log-mean-exp the plain maximum: the furrow's own depth.
    p.overlap.beta = 40.0;
    let relief = p.micro_relief().unwrap();
    assert_eq!(relief.furrows().len(), 1);
    let f = relief.furrows()[0];
    let (map, _) = relief.bake(256).unwrap();
    let d = [f.end_mm[0] - f.start_mm[0], f.end_mm[1] - f.start_mm[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let (mut worst, mut deepest) = (0.0f32, 0.0f32);
    for y in 0..256 {
        for x in 0..256 {
            let q = [
                crate::maps::heightmap::pixel_to_u(x, 256) * 50.0 - f.start_mm[0],
                crate::maps::heightmap::pixel_to_v(y, 256) * 50.0 - f.start_mm[1],
            ];
            let along = (q[0] * d[0] + q[1] * d[1]) / len;
            let cross = (q[0] * d[1] - q[1] * d[0]) / len;
            let want = crate::layers::micro::furrows::height(&f, along, cross);
            worst = worst.max((map.get(x, y) - want).abs());
            deepest = deepest.min(map.get(x, y));
        }
    }
    assert!(worst < 1e-4, "largest difference from eq. 16: {worst}");
    assert!(deepest < -0.9, "{deepest}");
}

#[test]
fn tiled_maps_match_across_opposite_edges() {
    let relief = project(true).micro_relief().unwrap();
    let (m, _) = relief.bake(256).unwrap();
    let n = 256;
    let mean_abs = |f: &dyn Fn(u32) -> f32| (0..n).map(f).map(f32::abs).sum::<f32>() / n as f32;
    // Across the seam vs. between the two columns (rows) next to it.
    let seam_x = mean_abs(&|y| m.get(0, y) - m.get(n - 1, y));
    let inner_x = mean_abs(&|y| m.get(1, y) - m.get(0, y));
    let seam_y = mean_abs(&|x| m.get(x, 0) - m.get(x, n - 1));
    let inner_y = mean_abs(&|x| m.get(x, 1) - m.get(x, 0));
    assert!(
        seam_x < 2.0 * inner_x + 1e-3,
        "x seam {seam_x} vs neighbours {inner_x}"
    );
    assert!(
        seam_y < 2.0 * inner_y + 1e-3,
        "y seam {seam_y} vs neighbours {inner_y}"
    );
    // An untiled map has a real seam.
    let (u, _) = project(false).micro_relief().unwrap().bake(256).unwrap();
    let seam_u = (0..n)
        .map(|y| (u.get(0, y) - u.get(n - 1, y)).abs())
        .sum::<f32>()
        / n as f32;
    assert!(
        seam_u > 2.0 * seam_x,
        "untiled seam {seam_u} vs tiled {seam_x}"
    );
}

#[test]
fn resolution_independent_within_tolerance() {
    // 1024² vs 4096² box-downsampled by 4: same picture (tolerance: 3 % of the height
    // range in the mean, from sub-pixel detail that only the large bake resolves).
    let mut p = project(false);
    p.noise.details = 3.0;
    let relief = p.micro_relief().unwrap();
    let (small, _) = relief.bake(1024).unwrap();
    let (big, _) = relief.bake(4096).unwrap();
    let down = big.downsample_box(4).unwrap();
    let (lo, hi) = down.min_max();
    let mean_diff = small
        .data()
        .iter()
        .zip(down.data())
        .map(|(a, b)| (a - b).abs())
        .sum::<f32>()
        / small.data().len() as f32;
    assert!(
        mean_diff < 0.03 * (hi - lo),
        "mean |1024 − 4096↓| = {mean_diff}, range {}",
        hi - lo
    );
}
