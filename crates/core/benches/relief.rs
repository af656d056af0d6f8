//! The shape's relief finer than the triangles (docs/models.md §13 "Relief finer than the
//! triangles"): `ShapeRelief::new` on the default head at 2048² and 4096², against a
//! simple baseline measured in the same run: the same relief (the rolls' height less its
//! blurred mean, 25 taps) at every texel of every skin triangle, without the test that
//! keeps the triangles near a roll, at 1024² and scaled up by the texels' count.
//!
//! `cargo bench -p agesim-core --bench relief` prints the medians and their ratio.

#![allow(clippy::unwrap_used, clippy::expect_used)]

#[path = "common/timing.rs"]
mod timing;

use agesim_core::base::cancel::CancelToken;
use agesim_core::head::frame::Regions;
use agesim_core::layers::shape::REGIONS;
use agesim_core::layers::shape::relief::ShapeRelief;
use agesim_core::project::Project;
use agesim_core::scene::Scene;
use glam::{Vec2, Vec3};
use timing::time_ms;

const RUNS: usize = 5;

fn main() {
    let scene = Scene::new(Project::default()).unwrap();
    let mesh = scene.mesh().clone();
    let strengths = [1.0; REGIONS.len()];
    let never = CancelToken::never();
    let ours = |size: u32| {
        time_ms(RUNS, || {
            let m = mesh.clone();
            std::hint::black_box(
                ShapeRelief::new(
                    &mesh,
                    &|v| m.positions().get(v).copied(),
                    &strengths,
                    1.0,
                    size,
                    &never,
                )
                .unwrap(),
            );
        })
    };
    let (ours_2048, ours_4096) = (ours(2048), ours(4096));

    // Baseline: every skin triangle, every rolled region, the 25 taps at every texel.
    let frame = Regions::template().unwrap();
    let q: Vec<Vec3> = mesh
        .positions()
        .iter()
        .map(|p| frame.relative(*p))
        .collect();
    let size = 1024u32;
    let baseline_1024 = time_ms(RUNS, || {
        let mut out = vec![0.0f32; (size * size) as usize];
        for region in REGIONS.iter().filter(|r| !r.rolls.is_empty()) {
            let h = |q: Vec3| region.rolls.iter().map(|l| l.height_mm(q)).sum::<f32>();
            for tri in mesh.skin_indices().chunks_exact(3) {
                let v = [0, 1, 2].map(|i| tri[i] as usize);
                let uv = v.map(|i| mesh.uvs()[i]);
                let qs = v.map(|i| q[i]);
                let sigma = 0.5 * (qs[0].distance(qs[1]) + qs[1].distance(qs[2])) * 0.5;
                agesim_core::maps::raster::raster_uv(uv, size, 1.5, |x, y, w, _| {
                    let here = qs[0] * w[0] + qs[1] * w[1] + qs[2] * w[2];
                    let mut mean = 0.0;
                    for k in 0..25 {
                        let d = Vec2::new((k % 5) as f32 - 2.0, (k / 5) as f32 - 2.0) * sigma;
                        mean += h(here + d.extend(0.0)) / 25.0;
                    }
                    out[y * size as usize + x] += h(here) - mean;
                });
            }
        }
        std::hint::black_box(out);
    });
    let scale = |s: u32| (s as f64 / size as f64).powi(2);
    println!(
        "relief, default head ({} vertices), median of {RUNS}:",
        mesh.vertex_count()
    );
    for (s, t) in [(2048, ours_2048), (4096, ours_4096)] {
        let base = baseline_1024 * scale(s);
        println!(
            "  {s}²: {t:8.1} ms   baseline (every skin triangle, {baseline_1024:.0} ms at 1024², scaled) {base:8.1} ms   ×{:.1} faster",
            base / t
        );
    }
}
