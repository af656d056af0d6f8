//! Start-up cost of the default head and the skin patch (budget: 100 ms).
//!
//! Ours: `head::default_head()` (reads the shipped GLB built into the binary) and
//! `head::skin_patch()` (exact analytic tangents). Baselines, measured in the same run:
//! converting the scan afresh (`scan::convert_scan`: reading the scan's GLB, its frame,
//! `Mesh::build` with MikkTSpace) and the skin patch built through MikkTSpace. The cost of
//! smooth normals and MikkTSpace on the head is printed too.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use agesim::assets::scan;
use agesim_core::Mesh;
use agesim_core::head::default as head;

mod common;
use common::{ms, time};

fn main() {
    let threads = rayon::current_num_threads();
    // Ours.
    let head = time(21, || {
        std::hint::black_box(head::default_head());
    });
    let patch = time(21, || {
        std::hint::black_box(head::skin_patch());
    });
    // Baselines: the old generation paths.
    let assets = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets");
    let generated = time(7, || {
        std::hint::black_box(scan::convert_scan(&assets).unwrap());
    });
    let patch_mikk = time(7, || {
        std::hint::black_box(Mesh::build(head::skin_patch_raw(), "skin patch").unwrap());
    });
    // What the conversion spends on the frame.
    let m = head::default_head();
    let normals = time(7, || {
        std::hint::black_box(agesim_core::head::mesh::normals::smooth_normals(
            m.positions(),
            m.indices(),
        ));
    });
    let mikk = time(7, || {
        std::hint::black_box(agesim_core::head::mesh::tangents::mikktspace(
            m.positions(),
            m.normals(),
            m.uvs(),
            m.indices(),
        ));
    });
    println!("threads: {threads}");
    println!(
        "default head ({} triangles, {} vertices) from the shipped GLB ({:.2} MB): median {:.1} ms",
        m.triangle_count(),
        m.vertex_count(),
        head::DEFAULT_HEAD_GLB.len() as f64 / 1e6,
        ms(head)
    );
    println!(
        "  baseline convert_scan(): median {:.1} ms (smooth normals {:.1} ms, MikkTSpace {:.1} ms)",
        ms(generated),
        ms(normals),
        ms(mikk)
    );
    println!(
        "  ratio shipped / converted: {:.4} ({:.0}× faster)",
        ms(head) / ms(generated),
        ms(generated) / ms(head)
    );
    println!(
        "skin patch (analytic tangents): median {:.1} ms; baseline through MikkTSpace {:.1} ms; ratio {:.4} ({:.0}× faster)",
        ms(patch),
        ms(patch_mikk),
        ms(patch) / ms(patch_mikk),
        ms(patch_mikk) / ms(patch)
    );
}
