//! Golden images: small renders compared with PNGs committed in `tests/golden/`, with a
//! tolerance (mean |Δ| ≤ 1.5 per channel and ≤ 1 % of pixels off by more than 16 levels),
//! because another lavapipe/LLVM version or a real GPU rounds differently. On a mismatch
//! the render is written beside the golden as `NAME.new.png`; `UPDATE_SNAPSHOTS=1`
//! overwrites the golden instead (then look at it before committing).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;

use agesim_core::layers::wrinkles::fine_wrinkles::{self, DEFAULT_FINE_WRINKLES};
use agesim_core::{HeightMap, head::default as head};
use agesim_render::{FrameParams, PomMode, Renderer, TileLayer, TilePlacement};
use glam::Vec3;

mod common;
use common::gpu_or_skip;

/// Five narrow creases across v: the depth of the `crease` profile (cut into the skin).
fn creases(size: u32) -> HeightMap {
    let mut data = Vec::new();
    for y in 0..size {
        let v = agesim_core::maps::heightmap::pixel_to_v(y, size);
        for _ in 0..size {
            data.push(
                agesim_core::layers::wrinkles::muscle::Profile::Crease
                    .eval(v * 5.0)
                    .powf(0.7),
            );
        }
    }
    HeightMap::from_vec(size, size, data).unwrap()
}

fn check_golden(name: &str, img: &image::RgbaImage) {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let path = dir.join(format!("{name}.png"));
    if std::env::var("UPDATE_SNAPSHOTS").is_ok_and(|v| v == "1") {
        std::fs::create_dir_all(&dir).unwrap();
        img.save(&path).unwrap();
        eprintln!("{name}: golden written to {}", path.display());
        return;
    }
    let new_path = dir.join(format!("{name}.new.png"));
    let Ok(golden) = image::open(&path) else {
        img.save(&new_path).unwrap();
        panic!(
            "{name}: no golden at {}; run with UPDATE_SNAPSHOTS=1",
            path.display()
        );
    };
    let golden = golden.to_rgba8();
    assert_eq!(
        golden.dimensions(),
        img.dimensions(),
        "{name}: size changed"
    );
    let (mut sum, mut far) = (0u64, 0usize);
    for (a, b) in golden.pixels().zip(img.pixels()) {
        let d =
            a.0.iter()
                .zip(b.0)
                .map(|(&x, y)| x.abs_diff(y))
                .max()
                .unwrap_or(0);
        far += usize::from(d > 16);
        sum +=
            a.0.iter()
                .zip(b.0)
                .map(|(&x, y)| u64::from(x.abs_diff(y)))
                .sum::<u64>();
    }
    let mean = sum as f64 / (img.as_raw().len()) as f64;
    let far_fraction = far as f64 / f64::from(img.width() * img.height());
    if mean > 1.5 || far_fraction > 0.01 {
        img.save(&new_path).unwrap();
        panic!(
            "{name}: differs from the golden (mean |Δ| {mean:.2}, {:.2} % of pixels off by > 16); \
             render written to {}",
            100.0 * far_fraction,
            new_path.display()
        );
    }
}

#[test]
fn skin_patch_matches_golden() {
    let Some(gpu) = gpu_or_skip("skin_patch_matches_golden") else {
        return;
    };
    let mut r = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT).unwrap();
    r.upload_mesh(&head::skin_patch(), 1.0).unwrap();
    r.upload_large_wrinkles(&creases(128)).unwrap();
    let fine = fine_wrinkles::generate(128, &DEFAULT_FINE_WRINKLES).unwrap();
    r.upload_tile(TileLayer::Fine, &fine).unwrap();
    for (name, mode) in [
        ("patch-combined", PomMode::Combined),
        ("patch-normal", PomMode::NormalOnly),
    ] {
        let mut p = FrameParams::default();
        p.skin.pom_mode = mode;
        p.skin.disp_scale = 0.02;
        p.skin.fine_blend = 1.0;
        p.skin.fine_tile = TilePlacement {
            size_m: 0.025,
            strength: 0.0015,
        };
        p.hair.enabled = false;
        p.camera.target = Vec3::ZERO;
        p.camera.yaw_rad = 0.0;
        p.camera.pitch_rad = 55f32.to_radians();
        p.camera.distance = 0.06;
        let img = r.render_to_image(&p, (64, 64)).unwrap();
        check_golden(name, &img);
    }
}
