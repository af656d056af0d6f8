//! Large-wrinkle bake: 20 fibres at 4096² (docs/models.md §2), against the simple baseline of every
//! pixel evaluated against every fibre on one thread, measured in the same run.
//!
//! `cargo bench -p agesim-core --bench large_wrinkles`
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Instant;

use agesim_core::HeightMap;
use agesim_core::layers::wrinkles::muscle::{self, Fibre, LargeWrinkleSettings};
use agesim_core::maps::normal_map::{self, NormalSettings};

/// 20 fibres laid out like a face's wrinkle groups: forehead, frown, crow's feet, folds.
fn fibres() -> Vec<Fibre> {
    (0..20)
        .map(|i| {
            let row = (i / 5) as f32;
            let col = (i % 5) as f32;
            let (u, v) = (0.12 + col * 0.18, 0.15 + row * 0.22);
            let angle = (i as f32 * 0.7).sin() * 0.8 + std::f32::consts::FRAC_PI_2;
            let len = 0.06 + 0.02 * (i % 3) as f32;
            Fibre::new(
                [u, v],
                [u + len * angle.cos(), v - len * angle.sin()],
                3 + i % 4,
            )
            .unwrap()
            .with_rel_width(0.6 + 0.1 * (i % 4) as f32)
            .unwrap()
        })
        .collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time_ms<T>(runs: usize, mut f: impl FnMut() -> T) -> f64 {
    let mut samples = Vec::with_capacity(runs);
    for _ in 0..runs {
        let t = Instant::now();
        std::hint::black_box(f());
        samples.push(t.elapsed().as_secs_f64() * 1e3);
    }
    median(samples)
}

fn main() {
    let size = 4096;
    let fibres = fibres();
    let settings = LargeWrinkleSettings::default();
    println!(
        "large wrinkles: {} fibres at {size}², {} rayon threads",
        fibres.len(),
        rayon::current_num_threads()
    );

    let raster = time_ms(7, || {
        let mut map = HeightMap::zeros(size, size).unwrap();
        muscle::accumulate(&fibres, &mut map);
        map
    });
    let full = time_ms(7, || {
        muscle::rasterize(&fibres, size, size, &settings).unwrap()
    });
    let map = muscle::rasterize(&fibres, size, size, &settings).unwrap();
    let normal = time_ms(7, || {
        normal_map::encode_rgb8(&map, &NormalSettings::default()).unwrap()
    });
    // The shipped layout's fibres: creases with irregularity and waviness (a hashed
    // value noise per pixel on top of [T]'s model).
    let irregular: Vec<Fibre> = fibres
        .iter()
        .map(|f| {
            f.clone()
                .with_profile(muscle::Profile::Crease)
                .with_irregularity(0.5)
                .unwrap()
                .with_waviness(0.08)
                .unwrap()
        })
        .collect();
    let raster_irregular = time_ms(7, || {
        let mut map = HeightMap::zeros(size, size).unwrap();
        muscle::accumulate(&irregular, &mut map);
        map
    });
    let baseline = time_ms(1, || {
        let mut map = HeightMap::zeros(size, size).unwrap();
        muscle::accumulate_brute_force(&fibres, &mut map);
        map
    });
    println!("  accumulate (bounded, parallel)    median {raster:9.1} ms");
    println!(
        "  accumulate, creases with irregularity and waviness  median {raster_irregular:9.1} ms ({:.2}× the regular [T] fibres)",
        raster_irregular / raster
    );
    println!("  full layer (+ normalise, γ)       median {full:9.1} ms");
    println!("  normal map RGB8                   median {normal:9.1} ms");
    println!("  baseline: every pixel × fibre, 1 thread {baseline:9.1} ms");
    println!(
        "  speed-up of accumulate over baseline: {:.1}×",
        baseline / raster
    );
}
