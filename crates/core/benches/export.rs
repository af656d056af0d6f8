//! Writing a 4096² bake's three maps (issue 10 §5): the sequential writers one after the
//! other (the baseline, as `agesim bake` wrote them before) against an [`OutputSet`]
//! staging them concurrently and committing the set, in the same run; file sizes printed.
//!
//! `cargo bench -p agesim-core --bench export`
#![allow(clippy::unwrap_used, clippy::expect_used)]

#[path = "common/workload.rs"]
mod common;

use std::time::Instant;

use agesim_core::export::{self, OutputSet};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let relief = common::workload().micro_relief().unwrap();
    let (height, rgb, _) = relief
        .bake_with_normals(4096, &relief.normal_settings())
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("seq"), dir.path().join("set"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    let runs = 5;
    let sequential = median(
        (0..runs)
            .map(|_| {
                let t = Instant::now();
                export::write_height_png16(&a.join("height.png"), &height).unwrap();
                export::write_height_exr(&a.join("height.exr"), &height).unwrap();
                export::write_rgb8_png(&a.join("normal.png"), 4096, 4096, &rgb).unwrap();
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect(),
    );
    let concurrent = median(
        (0..runs)
            .map(|_| {
                let t = Instant::now();
                let set = OutputSet::new();
                rayon::scope(|s| {
                    s.spawn(|_| {
                        export::stage_height_png16(&set, &b.join("height.png"), &height).unwrap();
                    });
                    s.spawn(|_| {
                        export::stage_height_exr(&set, &b.join("height.exr"), &height).unwrap()
                    });
                    s.spawn(|_| {
                        export::stage_rgb8_png(&set, &b.join("normal.png"), 4096, 4096, &rgb)
                            .unwrap()
                    });
                });
                set.commit().unwrap();
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect(),
    );
    println!(
        "4096² height PNG16 + height EXR + normal PNG, {} threads, median of {runs}",
        rayon::current_num_threads()
    );
    println!("| writer | wall | ratio |\n|---|---|---|");
    println!("| sequential, one file after the other (baseline) | {sequential:.0} ms | 1.00 |");
    println!(
        "| OutputSet, staged concurrently, committed as a set | {concurrent:.0} ms | {:.2} |",
        concurrent / sequential
    );
    for name in ["height.png", "height.exr", "normal.png"] {
        let size = std::fs::metadata(b.join(name)).unwrap().len();
        println!("{name}: {:.1} MB", size as f64 / 1e6);
    }
}
