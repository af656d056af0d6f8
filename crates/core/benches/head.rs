//! Generation time of the default head (`head::default_head`), to decide whether it can
//! be built at start-up (budget: 100 ms). Baseline: building the skin patch, a flat grid
//! of a similar triangle count through the same `Mesh::build` (normals, MikkTSpace
//! tangents), so the ratio shows what the shape itself (profile tracing, detail search)
//! costs on top of the mesh pipeline.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::{Duration, Instant};

fn median(mut runs: Vec<Duration>) -> Duration {
    runs.sort();
    runs[runs.len() / 2]
}

fn time(n: usize, mut f: impl FnMut()) -> Duration {
    f(); // warm-up
    median(
        (0..n)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed()
            })
            .collect(),
    )
}

fn main() {
    let threads = rayon::current_num_threads();
    let head = time(9, || {
        std::hint::black_box(agesim_core::head::default_head());
    });
    let raw = time(9, || {
        std::hint::black_box(agesim_core::head::head_raw(
            agesim_core::head::HEAD_COLUMNS,
            agesim_core::head::HEAD_ROWS,
        ));
    });
    let patch = time(9, || {
        std::hint::black_box(agesim_core::head::skin_patch());
    });
    let m = agesim_core::head::default_head();
    let p = agesim_core::head::skin_patch();
    println!("threads: {threads}");
    println!(
        "default head ({} triangles): median {:.1} ms (shape only, before Mesh::build: {:.1} ms)",
        m.triangle_count(),
        head.as_secs_f64() * 1e3,
        raw.as_secs_f64() * 1e3
    );
    println!(
        "baseline skin patch ({} triangles, Mesh::build only): median {:.1} ms",
        p.triangle_count(),
        patch.as_secs_f64() * 1e3
    );
    println!(
        "ratio head / baseline: {:.2}",
        head.as_secs_f64() / patch.as_secs_f64()
    );
}
