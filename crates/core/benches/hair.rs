//! Hair aging (docs/models.md §9): the 4096² transition texture against docs/models.md's naive iterative
//! dilation, and the generation of 1,000,000 hair instances against the same generation on
//! one thread. Run with `cargo bench -p agesim-core --bench hair`
//! (`HAIR_BENCH_SKIP_NAIVE_4096=1` skips the 5-minute naive run at 4096²).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::{Duration, Instant};

use agesim_core::Mask;
use agesim_core::layers::hair::transition::{
    DistanceMetric, HairRegions, TransitionTexture, generations_by_dilation, geodesic_distances,
};
use agesim_core::layers::hair::{self, HairInstances, HairParams, SurfaceRef};
use glam::{Vec2, Vec3};

fn median(mut f: impl FnMut() -> Duration, runs: usize) -> Duration {
    let mut t: Vec<Duration> = (0..runs).map(|_| f()).collect();
    t.sort();
    t[runs / 2]
}

fn time<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let start = Instant::now();
    let out = f();
    (out, start.elapsed())
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// A scalp-like pair of masks at 1024² (resampled by the code under test): outer = an
/// ellipse over the upper two thirds with a notch (a concave front), inner = a horseshoe
/// band along its lower rim, so fronts must travel around the notch.
fn scalp_masks() -> (Mask, Mask) {
    let n = 1024u32;
    let mut outer = vec![0.0f32; (n * n) as usize];
    let mut inner = vec![0.0f32; (n * n) as usize];
    for y in 0..n {
        for x in 0..n {
            let u = (x as f32 + 0.5) / n as f32;
            let v = 1.0 - (y as f32 + 0.5) / n as f32;
            let e = ((u - 0.5) / 0.45).powi(2) + ((v - 0.55) / 0.42).powi(2);
            let notch = (u - 0.5).abs() < 0.05 && v > 0.6 && v < 0.9;
            let i = (y * n + x) as usize;
            if e < 1.0 && !notch {
                outer[i] = 1.0;
            }
            if e < 1.0 && v < 0.35 {
                inner[i] = 1.0;
            }
        }
    }
    (
        Mask::from_values(n, n, outer).unwrap(),
        Mask::from_values(n, n, inner).unwrap(),
    )
}

struct Grid {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    indices: Vec<u32>,
}

/// A curved sheet of `n × n` quads over 0.3 m × 0.3 m, UV = its parameterisation.
fn sheet(n: u32) -> Grid {
    let mut g = Grid {
        positions: vec![],
        normals: vec![],
        uvs: vec![],
        indices: vec![],
    };
    for y in 0..=n {
        for x in 0..=n {
            let (u, v) = (x as f32 / n as f32, y as f32 / n as f32);
            let a = (u - 0.5) * 1.5;
            g.positions
                .push(Vec3::new(0.2 * a.sin(), v * 0.3, 0.2 * a.cos()));
            g.normals.push(Vec3::new(a.sin(), 0.0, a.cos()));
            g.uvs.push(Vec2::new(u, v));
        }
    }
    for y in 0..n {
        for x in 0..n {
            let i = y * (n + 1) + x;
            g.indices
                .extend([i, i + 1, i + n + 2, i, i + n + 2, i + n + 1]);
        }
    }
    g
}

fn main() {
    let threads = rayon::current_num_threads();
    println!("hair benchmark — {threads} threads");
    let (outer, inner) = scalp_masks();

    // --- Transition texture -----------------------------------------------------------
    let size = 4096;
    let (regions, resample) = time(|| HairRegions::from_masks(&outer, &inner, size, size).unwrap());
    let cheb = median(
        || time(|| geodesic_distances(&regions, DistanceMetric::Chebyshev).unwrap()).1,
        5,
    );
    let eucl = median(
        || time(|| geodesic_distances(&regions, DistanceMetric::Euclidean).unwrap()).1,
        5,
    );
    let full = median(
        || {
            time(|| {
                TransitionTexture::from_masks(&outer, &inner, size, size, DistanceMetric::Chebyshev)
                    .unwrap()
            })
            .1
        },
        5,
    );
    let tex = TransitionTexture::from_masks(&outer, &inner, size, size, DistanceMetric::Chebyshev)
        .unwrap();
    println!(
        "transition {size}²: R = {} generations; resample+threshold {:.1} ms",
        tex.max_generation_px(),
        ms(resample)
    );
    println!(
        "  Chebyshev BFS (distances)      median {:8.1} ms",
        ms(cheb)
    );
    println!(
        "  Euclidean 5-7-11 (distances)   median {:8.1} ms",
        ms(eucl)
    );
    println!(
        "  full texture (masks → ages)    median {:8.1} ms",
        ms(full)
    );

    // The naive dilation is O(generations × pixels): one run at 4096², a median at 1024².
    let small = HairRegions::from_masks(&outer, &inner, 1024, 1024).unwrap();
    let naive_small = median(|| time(|| generations_by_dilation(&small)).1, 3);
    let cheb_small = median(
        || time(|| geodesic_distances(&small, DistanceMetric::Chebyshev).unwrap()).1,
        5,
    );
    println!(
        "  1024²: naive dilation median {:.1} ms, BFS median {:.2} ms, ratio {:.0}×",
        ms(naive_small),
        ms(cheb_small),
        naive_small.as_secs_f64() / cheb_small.as_secs_f64()
    );
    // About 5 minutes on the reference machine; `HAIR_BENCH_SKIP_NAIVE_4096=1` skips it.
    if std::env::var_os("HAIR_BENCH_SKIP_NAIVE_4096").is_none() {
        let (naive, naive_t) = time(|| generations_by_dilation(&regions));
        let fast = geodesic_distances(&regions, DistanceMetric::Chebyshev).unwrap();
        assert_eq!(naive, fast, "the fast path must equal the reference");
        println!(
            "  4096²: naive dilation (1 run) {:.0} ms, BFS median {:.1} ms, ratio {:.0}× (outputs equal)",
            ms(naive_t),
            ms(cheb),
            naive_t.as_secs_f64() / cheb.as_secs_f64()
        );
    }

    // --- Hair instances --------------------------------------------------------------
    let g = sheet(256);
    let surface = SurfaceRef::new(&g.positions, &g.normals, &g.uvs, &g.indices).unwrap();
    // Area ≈ 0.2·1.5 × 0.3 = 0.09 m² = 900 cm²; the masks keep part of it. Calibrate the
    // density so that about 1,000,000 hairs survive.
    let probe =
        HairInstances::generate(&surface, &tex, &HairParams::new(100.0, 1.0).unwrap()).unwrap();
    let density = 100.0 * 1.0e6 / probe.len() as f32;
    let params = HairParams::new(density, 1.0).unwrap().with_seed(1);
    let many = median(
        || time(|| HairInstances::generate(&surface, &tex, &params).unwrap()).1,
        5,
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = median(
        || pool.install(|| time(|| HairInstances::generate(&surface, &tex, &params).unwrap()).1),
        5,
    );
    let hairs = HairInstances::generate(&surface, &tex, &params).unwrap();
    println!(
        "instances: {} hairs ({} candidates, {} triangles, {:.0} /cm²)",
        hairs.len(),
        hairs.candidates(),
        surface.triangle_count(),
        density
    );
    println!(
        "  {threads} threads median {:.1} ms, 1 thread median {:.1} ms, ratio {:.2}×",
        ms(many),
        ms(one),
        one.as_secs_f64() / many.as_secs_f64()
    );
    let counts: Vec<usize> = [0.0, 0.25, 0.5, 0.75, 1.0]
        .iter()
        .map(|&t| hairs.count(t))
        .collect();
    println!("  count(0, .25, .5, .75, 1) = {counts:?}");

    // The project's hair: thinning, the ragged fringe and the taper (two ring searches of
    // the transition texture per hair), against [T]'s bare model above.
    let project = params
        .clone()
        .with_thinning(hair::DEFAULT_THINNING, hair::RECESSION_SPREAD)
        .unwrap()
        .with_taper_mm(hair::DEFAULT_TAPER_MM)
        .unwrap();
    let tapered = median(
        || time(|| HairInstances::generate(&surface, &tex, &project).unwrap()).1,
        5,
    );
    println!(
        "  with thinning and taper ({:.0} mm): median {:.1} ms, {:.2}× the bare model",
        hair::DEFAULT_TAPER_MM,
        ms(tapered),
        tapered.as_secs_f64() / many.as_secs_f64()
    );
}
