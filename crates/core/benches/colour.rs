//! The aged base colour (docs/models.md "Skin colour") of the default head at 1024² and
//! 2048²: the first bake (surface, regions and noise per texel, spots placed) and an age
//! change (the kept texels re-weighted), against the plain resample of the head's colour
//! map at the same size (the least any aged map costs: a read and a write per texel),
//! measured in the same run.
//!
//! `cargo bench -p agesim-core --bench colour`
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::Instant;

use agesim_core::base::cancel::CancelToken;
use agesim_core::project::Project;
use agesim_core::scene::Scene;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn main() {
    let never = CancelToken::never();
    let runs = 7;
    println!(
        "aged colour: default head, {} rayon threads",
        rayon::current_num_threads()
    );
    println!(
        "| size | first bake | age change | plain resample (baseline) | age change / baseline |"
    );
    println!("|---|---|---|---|---|");
    let base = Scene::new(Project::default()).unwrap();
    for size in [1024u32, 2048] {
        let first = median(
            (0..runs)
                .map(|_| {
                    let mut s = base.clone();
                    let t = Instant::now();
                    s.bake_colour(size, 1.0, &never).unwrap();
                    ms(t)
                })
                .collect(),
        );
        let mut scene = base.clone();
        scene.bake_colour(size, 1.0, &never).unwrap();
        let age = median(
            (0..runs)
                .map(|i| {
                    let t = Instant::now();
                    let changed = scene
                        .bake_colour(size, 0.6 + 0.05 * i as f32, &never)
                        .unwrap();
                    assert!(changed);
                    ms(t)
                })
                .collect(),
        );
        // Baseline: the colour map resampled to the size, sRGB → linear → sRGB.
        let map = scene.colour_map().unwrap().clone();
        let plain = median(
            (0..runs)
                .map(|_| {
                    let t = Instant::now();
                    let out = plain_resample(&map, size);
                    std::hint::black_box(out);
                    ms(t)
                })
                .collect(),
        );
        println!(
            "| {size}² | {first:.0} ms | {age:.0} ms | {plain:.0} ms | {:.1}× |",
            age / plain
        );
    }
}

/// Bilinear resample of an sRGB RGBA8 picture to `size`², through linear light, on all
/// cores: what the aged bake does for a texel with nothing to age.
fn plain_resample(map: &agesim_core::maps::mask::HeadImage, size: u32) -> Vec<u8> {
    use agesim_core::maps::mask::{linear_to_srgb, srgb_to_linear};
    use rayon::prelude::*;
    let lin: Vec<f32> = (0..256).map(|c| srgb_to_linear(c as f32 / 255.0)).collect();
    let enc: Vec<u8> = (0..4096)
        .map(|i| (linear_to_srgb(i as f32 / 4095.0) * 255.0).round() as u8)
        .collect();
    let n = size as usize;
    let (w, h) = (map.width_px as usize, map.height_px as usize);
    let mut out = vec![0u8; n * n * 4];
    out.par_chunks_mut(n * 4).enumerate().for_each(|(y, row)| {
        let fy = ((y as f32 + 0.5) / n as f32 * h as f32 - 0.5).max(0.0);
        let (y0, ty) = (fy as usize, fy.fract());
        let y1 = (y0 + 1).min(h - 1);
        for (x, px) in row.chunks_exact_mut(4).enumerate() {
            let fx = ((x as f32 + 0.5) / n as f32 * w as f32 - 0.5).max(0.0);
            let (x0, tx) = (fx as usize, fx.fract());
            let x1 = (x0 + 1).min(w - 1);
            for c in 0..3 {
                let at = |xx: usize, yy: usize| lin[map.rgba[(yy * w + xx) * 4 + c] as usize];
                let top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * tx;
                let bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * tx;
                let v = top + (bottom - top) * ty;
                px[c] = enc[(v.clamp(0.0, 1.0) * 4095.0).round() as usize];
            }
            px[3] = 255;
        }
    });
    out
}
