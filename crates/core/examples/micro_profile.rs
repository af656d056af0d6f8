//! Profiling loop (not a benchmark; that is `benches/micro.rs`): re-bakes [P]'s workload,
//! for `perf record` or A/B timing of two builds.
//!
//! `cargo run --release -p agesim-core --example micro_profile -- [SIZE] [ITERS] [cold]`
#![allow(clippy::unwrap_used, clippy::expect_used)]
use agesim_core::maps::normal_map::NormalSettings;

#[path = "../benches/common/workload.rs"]
mod common;

fn main() {
    let size: u32 = std::env::args().nth(1).map_or(4096, |s| s.parse().unwrap());
    let iters: usize = std::env::args().nth(2).map_or(30, |s| s.parse().unwrap());
    // "cold": fresh buffers every bake (`bake_with_normals`); otherwise `bake_into`.
    let cold = std::env::args().nth(3).is_some_and(|m| m == "cold");
    let p = common::workload();
    let relief = p.micro_relief().unwrap();
    let normals = NormalSettings {
        strength: p.normal.strength,
        tiling: p.tile,
        ..Default::default()
    };
    let mut map = agesim_core::HeightMap::zeros(1, 1).unwrap();
    let mut rgb = Vec::new();
    let mut times = Vec::new();
    for _ in 0..iters {
        let t = std::time::Instant::now();
        if cold {
            std::hint::black_box(relief.bake_with_normals(size, &normals).unwrap());
        } else {
            relief
                .bake_into(size, &mut map, &mut rgb, &normals)
                .unwrap();
        }
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    println!(
        "{size}²: median {:.2} ms, min {:.2} ms",
        times[times.len() / 2],
        times[0]
    );
}
