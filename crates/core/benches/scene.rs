//! The engine's preview path: a `Scene` at 1024² with the default head's
//! wrinkles and the default micro-relief, timing each kind of change against a full
//! re-bake (a fresh scene) measured in the same run; cancelling a 4096² bake; and [P]'s
//! workload at 4096² through the scene against `MicroRelief` directly (today's path).
//!
//! `cargo bench -p agesim-core --bench scene`
#![allow(clippy::unwrap_used, clippy::expect_used)]

#[path = "common/workload.rs"]
mod common;

use std::time::Instant;

use agesim_core::base::cancel::CancelToken;
use agesim_core::layers::wrinkles::muscle::Fibre;
use agesim_core::project::Project;
use agesim_core::scene::{BakeRequest, Scene};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The large map and the micro tile at 1024², no hair or fine tile (what a slider drag
/// re-bakes).
fn preview(t: f32) -> BakeRequest {
    BakeRequest {
        fine: false,
        hair: false,
        ..BakeRequest::preview(t)
    }
}

fn main() {
    let never = CancelToken::never();
    let runs = 9;
    println!(
        "scene: default head wrinkles + default micro-relief, preview 1024², {} rayon threads",
        rayon::current_num_threads()
    );

    // Baseline: a full bake from a fresh scene (inputs already loaded, as in the editor).
    let base = Scene::new(Project::default()).unwrap();
    let full = median(
        (0..runs)
            .map(|_| {
                let mut s = base.clone();
                let t = Instant::now();
                s.bake(&preview(0.5), &never).unwrap();
                ms(t)
            })
            .collect(),
    );
    let mut scene = base.clone();
    scene.bake(&preview(0.5), &never).unwrap();

    // A noise slider: the tile re-baked, no pore re-placed.
    let noise = median(
        (0..runs)
            .map(|i| {
                let mut p = scene.project().clone();
                p.noise.strength = 0.2 + 0.01 * i as f32;
                scene.set_project(p).unwrap();
                let t = Instant::now();
                let c = scene.bake(&preview(0.5), &never).unwrap();
                assert!(c.micro && !c.micro_features && !c.large);
                ms(t)
            })
            .collect(),
    );

    // One fibre dragged: one fibre rasterised, the large map recombined.
    let one_fibre = median(
        (0..runs)
            .map(|i| {
                let mut w = scene.wrinkles().to_vec();
                let g = &mut w[0].file.groups[0];
                let [u, v] = g.fibre.ma();
                g.fibre = Fibre::new([u + 0.001 * (i as f32 + 1.0), v], g.fibre.mb(), g.fibre.n())
                    .unwrap();
                scene.set_wrinkles(w);
                let t = Instant::now();
                let c = scene.bake(&preview(0.5), &never).unwrap();
                assert!(c.large && c.large_stamps && !c.micro);
                ms(t)
            })
            .collect(),
    );

    // The large-wrinkle depth slider: the map is kept normalised, so nothing re-bakes
    // (the renderer scales the relief).
    let depth = median(
        (0..runs)
            .map(|i| {
                let mut p = scene.project().clone();
                p.large.depth = 1.0 + 0.1 * i as f32;
                let t = Instant::now();
                scene.set_project(p).unwrap();
                let c = scene.bake(&preview(0.5), &never).unwrap();
                assert!(!c.any(), "{c:?}");
                ms(t)
            })
            .collect(),
    );

    // The age scrubbed: large map re-weighted, micro tile re-scaled.
    let age = median(
        (0..runs)
            .map(|i| {
                let t0 = 0.3 + 0.05 * i as f32;
                let t = Instant::now();
                let c = scene.bake(&preview(t0), &never).unwrap();
                assert!(c.large && c.micro && !c.micro_features && !c.large_stamps);
                ms(t)
            })
            .collect(),
    );
    // The age change split by layer.
    let split = |large: bool| {
        let mut p = Project::default();
        if large {
            p.pores.enabled = false;
            p.furrows.enabled = false;
            p.noise.details = 0.0;
        } else {
            p.large.enabled = false;
        }
        let mut s = Scene::new(p).unwrap();
        s.bake(&preview(0.1), &never).unwrap();
        median(
            (0..runs)
                .map(|i| {
                    let t = Instant::now();
                    s.bake(&preview(0.2 + 0.02 * i as f32), &never).unwrap();
                    ms(t)
                })
                .collect(),
        )
    };
    let (age_large, age_micro) = (split(true), split(false));
    println!("age change split: large-wrinkle map {age_large:.1} ms, micro tile {age_micro:.1} ms");
    println!(
        "| change at 1024² | incremental (median of {runs}) | full re-bake, same run | ratio |"
    );
    println!("|---|---|---|---|");
    for (name, v) in [
        ("noise only", noise),
        ("large-wrinkle depth (set_project + bake)", depth),
        ("one fibre", one_fibre),
        ("age", age),
    ] {
        println!("| {name} | {v:.1} ms | {full:.1} ms | {:.1}× |", full / v);
    }

    // A shape slider dragged (the strength), what the editor's preview does at 512²: the
    // maps with the shape's relief, then the moving shape (the settled field's moves
    // scaled, its new sky left for the still bake); against the same with the field
    // settled afresh (the moving bake before the scaling) and with its sky measured too
    // (the still bake), same run.
    #[derive(Clone, Copy)]
    enum Shape {
        Moving,
        Settled,
        Still,
    }
    let shape_slider = |mode: Shape| {
        let mut s = Scene::new(Project::default()).unwrap();
        let request = BakeRequest {
            large_size_px: 512,
            micro_size_px: 512,
            ..preview(0.8)
        };
        s.bake(&request, &never).unwrap();
        s.bake_shape(0.8);
        median(
            (0..runs)
                .map(|i| {
                    let mut p = s.project().clone();
                    p.shape.strength = 1.0 + 0.05 * (i as f32 + 1.0);
                    let t = Instant::now();
                    s.set_project(p).unwrap();
                    s.bake(&request, &never).unwrap();
                    match mode {
                        Shape::Moving => {
                            s.bake_shape_moving(0.8);
                        }
                        Shape::Settled => {
                            std::hint::black_box(s.shape_field().unwrap().at(60.0));
                        }
                        Shape::Still => {
                            s.bake_shape(0.8);
                        }
                    }
                    ms(t)
                })
                .collect(),
        )
    };
    let (moving, settled, still) = (
        shape_slider(Shape::Moving),
        shape_slider(Shape::Settled),
        shape_slider(Shape::Still),
    );
    println!(
        "| shape strength dragged, preview 512² (maps, relief, moving shape) | {moving:.1} ms | the field settled afresh, same run: {settled:.1} ms; its sky measured too: {still:.1} ms | {:.1}× |",
        settled / moving
    );

    // Cancelling a 4096² bake: time from cancel() to bake() returning.
    let mut latencies = Vec::new();
    for delay_ms in [5u64, 20, 40, 60, 80] {
        let mut s = base.clone();
        let token = CancelToken::new();
        let canceller = token.clone();
        let handle = std::thread::spawn(move || {
            let r = s.bake(&BakeRequest::maps(4096, 0.5, false), &token);
            (r.is_err(), Instant::now())
        });
        std::thread::sleep(std::time::Duration::from_millis(delay_ms));
        let t = Instant::now();
        canceller.cancel();
        let (cancelled, done) = handle.join().unwrap();
        if cancelled {
            latencies.push(done.saturating_duration_since(t).as_secs_f64() * 1e3);
        }
    }
    let worst = latencies.iter().copied().fold(0.0, f64::max);
    println!(
        "cancel a 4096² bake: {} of 5 cancelled mid-bake, latency median {:.2} ms, worst {worst:.2} ms",
        latencies.len(),
        if latencies.is_empty() {
            f64::NAN
        } else {
            median(latencies.clone())
        },
    );

    // [P]'s workload at 4096², the scene against MicroRelief::bake_with_normals directly.
    let mut p = common::workload();
    p.large.enabled = false;
    let direct = median(
        (0..5)
            .map(|_| {
                let t = Instant::now();
                // Today's path: generate the features, then bake with normals.
                let relief = p.micro_relief().unwrap();
                std::hint::black_box(
                    relief
                        .bake_with_normals(4096, &relief.normal_settings())
                        .unwrap(),
                );
                ms(t)
            })
            .collect(),
    );
    let scene_base = Scene::new(p).unwrap();
    let through_scene = median(
        (0..5)
            .map(|_| {
                let mut s = scene_base.clone();
                let t = Instant::now();
                s.bake(&BakeRequest::maps(4096, 1.0, false), &never)
                    .unwrap();
                ms(t)
            })
            .collect(),
    );
    println!(
        "[P] workload 4096² + normals: scene {through_scene:.1} ms, MicroRelief::new + bake_with_normals {direct:.1} ms, ratio {:.2}",
        through_scene / direct
    );
}
