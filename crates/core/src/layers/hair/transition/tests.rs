use super::*;
use crate::base::rng::Rng;
use proptest::prelude::*;

fn regions_from_ascii(rows: &[&str]) -> HairRegions {
    // 'O' outer only, 'I' inner and outer, 'i' inner only, '.' nothing.
    let h = rows.len() as u32;
    let w = rows[0].len() as u32;
    let chars: Vec<char> = rows.iter().flat_map(|r| r.chars()).collect();
    let outer: Vec<bool> = chars.iter().map(|&c| c == 'O' || c == 'I').collect();
    let inner: Vec<bool> = chars.iter().map(|&c| c == 'I' || c == 'i').collect();
    HairRegions::from_bools(w, h, &outer, &inner).unwrap()
}

/// Random regions: blobs (discs and rectangles) of outer hair with holes cut out, and a
/// few inner blobs, some inside the outer region, some outside, some absent.
fn random_regions(seed: u64, w: u32, h: u32) -> HairRegions {
    let mut rng = Rng::new(seed);
    let n = (w * h) as usize;
    let mut outer = vec![false; n];
    let mut inner = vec![false; n];
    let paint = |target: &mut Vec<bool>, value: bool, rng: &mut Rng| {
        let cx = rng.range_f32(0.0, w as f32);
        let cy = rng.range_f32(0.0, h as f32);
        let r = rng.range_f32(1.0, (w.max(h) as f32 / 3.0).max(1.5));
        let disc = rng.next_f32() < 0.5;
        for y in 0..h {
            for x in 0..w {
                let (dx, dy) = (x as f32 - cx, y as f32 - cy);
                let inside = if disc {
                    dx * dx + dy * dy <= r * r
                } else {
                    dx.abs() <= r && dy.abs() <= r * 0.5
                };
                if inside {
                    target[(y * w + x) as usize] = value;
                }
            }
        }
    };
    for _ in 0..1 + rng.below(4) {
        paint(&mut outer, true, &mut rng);
    }
    for _ in 0..rng.below(5) {
        paint(&mut outer, false, &mut rng); // holes
    }
    for _ in 0..rng.below(4) {
        paint(&mut inner, true, &mut rng);
    }
    // Salt: isolated pixels of either kind.
    for _ in 0..rng.below(8) {
        let i = rng.below(n as u64) as usize;
        if rng.next_f32() < 0.5 {
            outer[i] = !outer[i];
        } else {
            inner[i] = !inner[i];
        }
    }
    HairRegions::from_bools(w, h, &outer, &inner).unwrap()
}

#[test]
fn hand_computed_generations_go_around_a_hole() {
    // The inner pixel is at the left; a wall of non-hair pixels forces growth around it.
    let r = regions_from_ascii(&[
        "OOOOO", //
        "I.OOO", //
        "O.OOO", //
        "OOOOO",
    ]);
    const N: u32 = NO_GENERATION;
    let want = vec![
        1, 1, 2, 3, 4, //
        0, N, 2, 3, 4, //
        1, N, 3, 3, 4, //
        2, 2, 3, 4, 4,
    ];
    assert_eq!(
        geodesic_distances(&r, DistanceMetric::Chebyshev).unwrap(),
        want
    );
    assert_eq!(generations_by_dilation(&r), want);
}

#[test]
fn unconstrained_distance_would_be_wrong_here() {
    // A U-shaped corridor: the pixel at the top right is 2 away in a straight line but
    // 6 generations away through the corridor. Guards against a plain (unconstrained)
    // transform.
    let r = regions_from_ascii(&[
        "I.O", //
        "O.O", //
        "O.O", //
        "OOO",
    ]);
    let d = geodesic_distances(&r, DistanceMetric::Chebyshev).unwrap();
    // (0,0) → (0,1) → (0,2) → (1,3) → (2,2) → (2,1) → (2,0): generations 1 to 6.
    assert_eq!(d[2], 6, "{d:?}");
    assert_eq!(d, generations_by_dilation(&r));
}

#[test]
fn chebyshev_equals_dilation_on_random_masks() {
    for (seed, (w, h)) in [
        (1, 1),
        (2, 1),
        (1, 7),
        (9, 4),
        (17, 17),
        (32, 20),
        (64, 64),
        (5, 90),
    ]
    .into_iter()
    .cycle()
    .take(160)
    .enumerate()
    {
        let r = random_regions(seed as u64, w, h);
        let fast = geodesic_distances(&r, DistanceMetric::Chebyshev).unwrap();
        let naive = generations_by_dilation(&r);
        assert_eq!(fast, naive, "seed {seed}, {w}×{h}");
    }
}

#[test]
fn random_masks_exercise_holes_islands_and_unreachable_pixels() {
    // Keeps the equality test honest: over its masks, there are unreachable outer
    // pixels (islands without inner hair), long detours and several inner islands.
    let (mut unreachable, mut max_gen) = (0, 0);
    for seed in 0..40 {
        let r = random_regions(seed, 64, 64);
        let d = generations_by_dilation(&r);
        unreachable += (0..d.len())
            .filter(|&i| r.is_outer(i) && d[i] == NO_GENERATION)
            .count();
        max_gen = max_gen.max(
            d.iter()
                .filter(|&&g| g != NO_GENERATION)
                .max()
                .copied()
                .unwrap_or(0),
        );
    }
    assert!(unreachable > 100, "{unreachable}");
    assert!(max_gen > 30, "{max_gen}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn chebyshev_equals_dilation_on_arbitrary_pixels(
        w in 1u32..24, h in 1u32..24, seed in any::<u64>(), fill in 0.3f32..0.9
    ) {
        // Noise masks: many tiny islands and holes, diagonal-only contacts.
        let mut rng = Rng::new(seed);
        let n = (w * h) as usize;
        let outer: Vec<bool> = (0..n).map(|_| rng.next_f32() < fill).collect();
        let inner: Vec<bool> = (0..n).map(|_| rng.next_f32() < 0.05).collect();
        let r = HairRegions::from_bools(w, h, &outer, &inner).unwrap();
        prop_assert_eq!(
            geodesic_distances(&r, DistanceMetric::Chebyshev).unwrap(),
            generations_by_dilation(&r)
        );
    }
}

#[test]
fn chamfer_is_within_two_percent_of_euclidean_in_open_space() {
    let n = 101;
    let mut inner = vec![false; n * n];
    inner[50 * n + 50] = true;
    let r = HairRegions::from_bools(n as u32, n as u32, &vec![true; n * n], &inner).unwrap();
    let d = geodesic_distances(&r, DistanceMetric::Euclidean).unwrap();
    let mut worst = 0.0f64;
    for y in 0..n {
        for x in 0..n {
            let e = ((x as f64 - 50.0).powi(2) + (y as f64 - 50.0).powi(2)).sqrt();
            if e >= 10.0 {
                worst = worst.max((d[y * n + x] as f64 / 5.0 - e).abs() / e);
            }
        }
    }
    assert!(worst < 0.0203, "worst relative error {worst}");
    assert!(worst > 0.01, "a chamfer metric is not exact: {worst}");
    // Hand-computed: (3, 1) is one knight step plus one axis step: 11 + 5.
    assert_eq!(d[51 * n + 53], 16);
    assert_eq!(d[50 * n + 53], 15);
    assert_eq!(d[53 * n + 53], 21);
}

#[test]
fn chamfer_reaches_exactly_the_pixels_the_growth_reaches() {
    for seed in 0..60 {
        let r = random_regions(seed, 40, 33);
        let c = geodesic_distances(&r, DistanceMetric::Chebyshev).unwrap();
        let e = geodesic_distances(&r, DistanceMetric::Euclidean).unwrap();
        for i in 0..c.len() {
            assert_eq!(
                c[i] == NO_GENERATION,
                e[i] == NO_GENERATION,
                "seed {seed} pixel {i}"
            );
            if c[i] != NO_GENERATION {
                // Chebyshev ≤ chamfer/5 ≤ ... (a chamfer path has ≥ as many pixels).
                assert!(5 * c[i] <= e[i] || c[i] == 0, "seed {seed} pixel {i}");
            }
        }
    }
}

#[test]
fn knight_steps_do_not_jump_walls() {
    // A diagonal wall between the inner pixel and the right part; the knight step from
    // (0,0) to (2,1) passes between (1,0) and (1,1), both wall: not allowed.
    let r = regions_from_ascii(&[
        "I..", //
        "O.O", //
        "OOO",
    ]);
    let d = geodesic_distances(&r, DistanceMetric::Euclidean).unwrap();
    // Best allowed path: knight (0,0) → (1,2) (passes beside (0,1), open) = 11, then the
    // diagonal to (2,1) = 7. The forbidden knight step would have given 11.
    assert_eq!(d[5], 18, "{d:?}");
}

#[test]
fn ages_follow_the_documented_mapping() {
    // Row: inner, then generations 1, 2, 3; an unreachable island; inner outside outer.
    let r = regions_from_ascii(&["IOOO.O.i"]);
    let t = TransitionTexture::from_regions(&r, DistanceMetric::Chebyshev).unwrap();
    // R_reach = 3, the island gets r = 4 = R, denominator R + 1 = 5.
    let want = [1.0, 0.8, 0.6, 0.4, 0.0, 0.2, 0.0, 1.0];
    for (got, want) in t.ages().iter().zip(want) {
        assert!(
            (got - want).abs() < 1e-6,
            "got {got}, want {want}: {:?}",
            t.ages()
        );
    }
    assert_eq!(t.max_generation_px(), 4.0);
    assert_eq!(t.unreachable_px(), 1);
}

#[test]
fn threshold_removes_outermost_first_and_never_the_inner_region() {
    let r = regions_from_ascii(&["IOOO.O.i"]);
    let t = TransitionTexture::from_regions(&r, DistanceMetric::Chebyshev).unwrap();
    let present = |age_t: f32| -> String {
        (0..8)
            .map(|x| {
                if hair_present(t.age_at_pixel(x, 0), age_t) {
                    '#'
                } else {
                    '.'
                }
            })
            .collect()
    };
    assert_eq!(present(0.0), "####.#.#");
    assert_eq!(present(0.1), "####.#.#");
    assert_eq!(present(0.2), "####.#.#", "present while a ≥ t");
    assert_eq!(
        present(0.3),
        "####...#",
        "the unreachable island goes first"
    );
    assert_eq!(present(0.5), "###....#");
    assert_eq!(present(0.8), "##.....#");
    assert_eq!(present(0.81), "#......#");
    assert_eq!(present(1.0), "#......#");
    assert_eq!(present(7.0), "#......#", "t above 1 is clamped");
    assert_eq!(present(-1.0), "####.#.#", "t below 0 is clamped");
    assert_eq!(present(f32::NAN), "####.#.#");
}

#[test]
fn empty_masks_are_handled() {
    let none = Mask::from_values(3, 3, vec![0.0; 9]).unwrap();
    let full = Mask::from_values(5, 2, vec![1.0; 10]).unwrap();
    // No hair at all.
    let t = TransitionTexture::from_masks(&none, &none, 8, 8, DistanceMetric::Chebyshev).unwrap();
    assert!(t.ages().iter().all(|&a| a == 0.0));
    assert_eq!(t.max_generation_px(), 0.0);
    // Only inner hair.
    let t = TransitionTexture::from_masks(&none, &full, 8, 8, DistanceMetric::Euclidean).unwrap();
    assert!(t.ages().iter().all(|&a| a == 1.0));
    // Only outer hair: all of it unreachable, goes at t just above 0.5.
    let t = TransitionTexture::from_masks(&full, &none, 8, 8, DistanceMetric::Chebyshev).unwrap();
    assert!(t.ages().iter().all(|&a| a == 0.5), "{:?}", t.ages());
    assert_eq!(t.unreachable_px(), 64);
}

#[test]
fn masks_of_different_sizes_are_resampled_to_the_working_size() {
    // Outer: the left half of a 2×1 image; inner: the top-left quarter of a 4×4 image.
    let outer = Mask::from_values(2, 1, vec![1.0, 0.0]).unwrap();
    let mut inner_v = vec![0.0; 16];
    inner_v[0] = 1.0;
    inner_v[1] = 1.0;
    inner_v[4] = 1.0;
    inner_v[5] = 1.0;
    let inner = Mask::from_values(4, 4, inner_v).unwrap();
    let r = HairRegions::from_masks(&outer, &inner, 8, 8).unwrap();
    for y in 0..8 {
        for x in 0..8 {
            let i = y * 8 + x;
            assert_eq!(r.is_outer(i), x < 4, "outer at ({x},{y})");
            assert_eq!(r.is_inner(i), x < 4 && y < 4, "inner at ({x},{y})");
        }
    }
    let t = TransitionTexture::from_regions(&r, DistanceMetric::Chebyshev).unwrap();
    // Bottom-left corner is 4 generations below the inner quarter.
    assert_eq!(t.max_generation_px(), 4.0);
    assert!((t.age_at_pixel(0, 7) - 0.2).abs() < 1e-6);
    assert!(t.hair_present(0.1, 0.9, 1.0), "top-left is inner");
    assert!(!t.hair_present(0.9, 0.9, 0.0), "right half has no hair");
}

#[test]
fn fast_resampling_equals_mask_sample() {
    let mut rng = Rng::new(4);
    let (ow, oh, iw, ih) = (37, 23, 5, 61);
    let outer = Mask::from_values(ow, oh, (0..ow * oh).map(|_| rng.next_f32()).collect()).unwrap();
    let inner = Mask::from_values(iw, ih, (0..iw * ih).map(|_| rng.next_f32()).collect()).unwrap();
    for (w, h) in [(1, 1), (37, 23), (100, 77), (16, 200)] {
        let r = HairRegions::from_masks(&outer, &inner, w, h).unwrap();
        for y in 0..h {
            for x in 0..w {
                let (u, v) = (pixel_to_u(x, w), pixel_to_v(y, h));
                let i = (y * w + x) as usize;
                assert_eq!(
                    r.is_outer(i),
                    outer.sample(u, v) >= REGION_THRESHOLD,
                    "({x},{y}) of {w}×{h}"
                );
                assert_eq!(
                    r.is_inner(i),
                    inner.sample(u, v) >= REGION_THRESHOLD,
                    "({x},{y}) of {w}×{h}"
                );
            }
        }
    }
}

#[test]
fn identical_textures_on_one_and_many_threads() {
    let mut rng = Rng::new(8);
    let outer = Mask::from_values(50, 40, (0..2000).map(|_| rng.next_f32()).collect()).unwrap();
    let inner = Mask::from_values(13, 9, (0..117).map(|_| rng.next_f32() * 0.6).collect()).unwrap();
    for metric in [DistanceMetric::Chebyshev, DistanceMetric::Euclidean] {
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| {
                    TransitionTexture::from_masks(&outer, &inner, 300, 211, metric).unwrap()
                })
        };
        let (one, many) = (run(1), run(3));
        assert!(one.max_generation_px() > 3.0);
        assert_eq!(one.to_luma16(), many.to_luma16());
        assert!(
            one.ages()
                .iter()
                .zip(many.ages())
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
    }
}

#[test]
fn bad_sizes_are_errors() {
    assert!(HairRegions::from_bools(2, 2, &[true; 3], &[false; 4]).is_err());
    let m = Mask::from_values(1, 1, vec![1.0]).unwrap();
    assert!(TransitionTexture::from_masks(&m, &m, 0, 4, DistanceMetric::Chebyshev).is_err());
    assert!("manhattan".parse::<DistanceMetric>().is_err());
    assert_eq!(
        "Euclidean".parse::<DistanceMetric>().unwrap(),
        DistanceMetric::Euclidean
    );
}

#[test]
fn sixteen_bit_export_maps_inner_to_white() {
    let r = regions_from_ascii(&["IOOO.O.i"]);
    let t = TransitionTexture::from_regions(&r, DistanceMetric::Chebyshev).unwrap();
    assert_eq!(
        t.to_luma16(),
        vec![65535, 52428, 39321, 26214, 0, 13107, 0, 65535]
    );
}

#[test]
fn an_order_mask_sets_the_ages_of_the_outer_hair() {
    // 4×1: outer only with order 0.25, outer only with order 0.75, inner, neither.
    let m = |v: [f32; 4]| Mask::from_values(4, 1, v.to_vec()).unwrap();
    let outer = m([1.0, 1.0, 1.0, 0.0]);
    let inner = m([0.0, 0.0, 1.0, 0.0]);
    let order = m([0.25, 0.75, 0.1, 0.9]);
    let t = TransitionTexture::from_order(&outer, &inner, &order, 4, 1).unwrap();
    let a: Vec<f32> = (0..4).map(|i| t.ages[i]).collect();
    assert_eq!(a, vec![0.25, 0.75, 1.0, 0.0]);
    // An order of 0 or 1 still leaves the outer hair for a moment and takes it by t = 1.
    let t = TransitionTexture::from_order(&outer, &inner, &m([0.0, 1.0, 0.0, 0.0]), 4, 1).unwrap();
    assert!(t.ages[0] > 0.0 && t.ages[1] < 1.0);
}
