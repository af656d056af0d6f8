//! Renders the default head from four sides into a directory (default /tmp):
//! `cargo run -p agesim --example head_preview -- /tmp`.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use agesim::assets::preview::{View, render};
use glam::Vec3;

fn main() {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "/tmp".into());
    let t = std::time::Instant::now();
    let head = agesim_core::head::default::default_head();
    println!(
        "{} vertices, {} triangles, {:?} in {:?}; size {:?}",
        head.vertex_count(),
        head.triangle_count(),
        head.report().warnings,
        t.elapsed(),
        head.bounds().size()
    );
    for (name, view) in [
        ("front", View::FRONT),
        ("three-quarter", View::THREE_QUARTER),
        ("side", View::SIDE),
        ("back", View::BACK),
    ] {
        let img = render(&head, view, 512, |_| Vec3::splat(0.8));
        img.save(format!("{dir}/head-{name}.png")).unwrap();
    }
}
