//! The aged head's GLB export: its composed normal map (large wrinkles, fine
//! wrinkles and micro-relief in the head's UV, `agesim::export::head_normal_map`) against
//! the baseline of the large-wrinkle normal map alone (`normal_map::encode_rgb8`, what a
//! plain bake writes) at the same size, then the export's PNG encode and the whole export,
//! in one run. Every step is the export's own code (its bake request, its composition, its
//! encoder), not a copy.
//!
//! `cargo bench -p agesim --bench glb`
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Instant;

use agesim::export::{ExportRequest, GlbOut, glb_bake_request, head_normal_map};
use agesim_core::base::cancel::CancelToken;
use agesim_core::maps::normal_map::{self, NormalSettings};
use agesim_core::output::export::{PngPixels, encode_png};
use agesim_core::project::Project;
use agesim_core::scene::Scene;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time(runs: usize, mut f: impl FnMut()) -> f64 {
    median(
        (0..runs)
            .map(|_| {
                let t = Instant::now();
                f();
                t.elapsed().as_secs_f64() * 1e3
            })
            .collect(),
    )
}

fn main() {
    let never = CancelToken::never();
    let project = Project {
        tile: true,
        ..Project::default()
    };
    let t = project.age.mapping().t(70.0);
    println!(
        "GLB export of the default head at 70 years, {} threads",
        rayon::current_num_threads()
    );
    println!(
        "| size | large-only normals (baseline) | composed normals | ratio | PNG encode | whole `export --glb` |"
    );
    println!("|---|---|---|---|---|---|");
    for size in [1024u32, 2048, 4096] {
        let mut scene = Scene::new(project.clone()).unwrap();
        // The export's own bake (a single-tile head: the atlas is the texture).
        scene
            .bake(&glb_bake_request(size, size, t), &never)
            .unwrap();
        let large = scene.large().unwrap().height.clone();
        let runs = if size >= 4096 { 3 } else { 5 };
        let settings = NormalSettings::default();
        let baseline = time(runs, || {
            std::hint::black_box(normal_map::encode_rgb8(&large, &settings).unwrap());
        });
        let mut rgb = Vec::new();
        let composed = time(runs, || {
            rgb = head_normal_map(&scene, t, size, &never).unwrap();
        });
        let png = time(runs, || {
            // The export's encoder, as the GLB's normal texture is written.
            let mut out = Vec::new();
            encode_png(&mut out, size, size, PngPixels::Rgb8, &rgb).unwrap();
            std::hint::black_box(out);
        });
        let dir = tempfile::tempdir().unwrap();
        let whole = time(runs, || {
            let request = ExportRequest {
                years: 70.0,
                glb: Some(GlbOut {
                    path: dir.path().join("head.glb"),
                    size_px: size,
                    // The head alone, as measured before the hair came to the GLB.
                    hair: agesim::export::GlbHair::None,
                }),
                ..ExportRequest::default()
            };
            agesim::export::run(&project, None, &request, &|_, _| {}, &never).unwrap();
        });
        println!(
            "| {size}² | {baseline:.0} ms | {composed:.0} ms | {:.1}× | {png:.0} ms | {whole:.0} ms |",
            composed / baseline
        );
    }
}
