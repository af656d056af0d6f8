//! The shape's occlusion (docs/models.md §13 "Occlusion"): the full shape's sky ratio of the
//! default head (two visibility passes over the vertices near a movement, through the
//! mesh's bounding-volume hierarchy), against a simple baseline measured in the same run:
//! the same rays tested against every triangle, on every 32nd vertex, scaled up.
//!
//! `cargo bench -p agesim-core --bench occlusion` prints the medians and their ratio.

#![allow(clippy::unwrap_used, clippy::expect_used)]

#[path = "common/timing.rs"]
mod timing;

use agesim_core::head::fit::bvh::ray_triangle;
use agesim_core::layers::shape::{REGIONS, ShapeField, occlusion};
use agesim_core::project::Project;
use agesim_core::scene::Scene;
use glam::Vec3;
use timing::time_ms;

const RUNS: usize = 5;

fn main() {
    let scene = Scene::new(Project::default()).unwrap();
    let mesh = scene.mesh().clone();
    let field = || {
        let m = mesh.clone();
        ShapeField::new(
            &mesh,
            &|v| m.positions().get(v).copied(),
            &[1.0; REGIONS.len()],
            1.0,
        )
    };
    let vertices = mesh.vertex_count();
    let fresh = time_ms(RUNS, || {
        std::hint::black_box(field());
    });
    let with_occlusion = time_ms(RUNS, || {
        std::hint::black_box(field().occlusion_at(&mesh, 80.0));
    });
    let ours = with_occlusion - fresh;

    // Baseline: every ray of every 32nd vertex against every triangle.
    let (p, idx) = (mesh.positions(), mesh.indices());
    let normals = agesim_core::head::mesh::normals::smooth_normals(p, idx);
    let triangles: Vec<[Vec3; 3]> = idx
        .chunks_exact(3)
        .map(|t| [p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]])
        .collect();
    let sample: Vec<usize> = (0..vertices).step_by(32).collect();
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    let baseline_sample = time_ms(RUNS, || {
        let mut sum = 0.0f32;
        for &v in &sample {
            let (t, b) = normals[v].any_orthonormal_pair();
            let origin = p[v] + normals[v] * 2e-4;
            for i in 0..occlusion::RAYS {
                let r = ((i as f32 + 0.5) / occlusion::RAYS as f32).sqrt();
                let a = i as f32 * golden;
                let d = t * (r * a.cos()) + b * (r * a.sin()) + normals[v] * (1.0 - r * r).sqrt();
                let hit = triangles
                    .iter()
                    .filter_map(|tri| ray_triangle(origin, d, *tri))
                    .filter(|&h| h > 0.0 && h < 0.025)
                    .fold(f32::INFINITY, f32::min);
                if hit.is_finite() {
                    sum += 1.0 - hit / 0.025;
                }
            }
        }
        std::hint::black_box(sum);
    });
    // Two passes (rest and aged) over every vertex, one thread.
    let baseline = baseline_sample * 2.0 * vertices as f64 / sample.len() as f64;
    println!(
        "default head, {vertices} vertices, {} rays each",
        occlusion::RAYS
    );
    println!("shape field alone:                 {fresh:8.1} ms");
    println!("occlusion (rest + full age, BVH):  {ours:8.1} ms");
    println!("baseline (every triangle, 1 core): {baseline:8.1} ms (every 32nd vertex, scaled)");
    println!(
        "ratio baseline / ours:             {:8.1}×",
        baseline / ours
    );
}
