//! Writing a 4096² bake's three maps: `export::stage_maps` (our EXR writer
//! with RLE lines coded on all cores, PNGs through `png` with Paeth filtering and rows
//! streamed, the normal map computed band by band as it is encoded, the three at once)
//! against the simple baseline measured in the same run: the generic encoders one file
//! after the other (`image`'s PNG encoder with adaptive filtering, the `exr` crate's RLE,
//! the normal map made in memory first), as `agesim bake` wrote them before. File sizes
//! printed for both.
//!
//! `cargo bench -p agesim-core --bench export`
#![allow(clippy::unwrap_used, clippy::expect_used)]

#[path = "common/workload.rs"]
mod common;

use std::path::Path;
use std::time::Instant;

use agesim_core::HeightMap;
use agesim_core::maps::normal_map::{self, NormalSettings};
use agesim_core::output::export::{self, ExrCompression, MapPaths, OutputSet};
use image::ImageEncoder as _;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn png_baseline(path: &Path, w: u32, h: u32, bytes: &[u8], colour: image::ExtendedColorType) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    PngEncoder::new_with_quality(file, CompressionType::Fast, FilterType::Adaptive)
        .write_image(bytes, w, h, colour)
        .unwrap();
}

/// The generic writers, one file after the other.
fn baseline(dir: &Path, height: &HeightMap, normal: &NormalSettings) {
    use exr::prelude::*;
    let n = height.width_px();
    let range = height.min_max();
    let samples: Vec<u8> = export::quantize_u16(height, range)
        .iter()
        .flat_map(|v| v.to_ne_bytes())
        .collect();
    png_baseline(
        &dir.join("height.png"),
        n,
        n,
        &samples,
        image::ExtendedColorType::L16,
    );
    let data = height.data();
    let w = n as usize;
    let channels = SpecificChannels::build()
        .with_channel("Y")
        .with_pixel_fn(|pos: Vec2<usize>| (data[pos.y() * w + pos.x()],));
    Image::from_encoded_channels((w, w), Encoding::FAST_LOSSLESS, channels)
        .write()
        .to_file(dir.join("height.exr"))
        .unwrap();
    let rgb = normal_map::encode_rgb8(height, normal).unwrap();
    png_baseline(
        &dir.join("normal.png"),
        n,
        n,
        &rgb,
        image::ExtendedColorType::Rgb8,
    );
}

fn ours(dir: &Path, height: &HeightMap, normal: &NormalSettings) {
    let set = OutputSet::new();
    let paths = (
        dir.join("height.png"),
        dir.join("height.exr"),
        dir.join("normal.png"),
    );
    export::stage_maps(
        &set,
        MapPaths {
            height_png: Some(&paths.0),
            height_exr: Some(&paths.1),
            normal_png: Some(&paths.2),
        },
        height,
        normal,
        ExrCompression::Rle,
    )
    .unwrap();
    set.commit().unwrap();
}

fn sizes(dir: &Path) -> String {
    ["height.png", "height.exr", "normal.png"]
        .iter()
        .map(|name| {
            let size = std::fs::metadata(dir.join(name)).unwrap().len();
            format!("{name} {:.1} MB", size as f64 / 1e6)
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn main() {
    let relief = common::workload().micro_relief().unwrap();
    let normal = relief.normal_settings();
    let (height, _, _) = relief.bake_with_normals(4096, &normal).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("baseline"), dir.path().join("ours"));
    std::fs::create_dir_all(&a).unwrap();
    std::fs::create_dir_all(&b).unwrap();
    let runs = 5;
    let (mut base_ms, mut ours_ms) = (Vec::new(), Vec::new());
    // Interleaved, so a drift in the machine's speed affects both alike.
    for _ in 0..runs {
        let t = Instant::now();
        baseline(&a, &height, &normal);
        base_ms.push(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        ours(&b, &height, &normal);
        ours_ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let (base, fast) = (median(base_ms), median(ours_ms));
    println!(
        "4096² height PNG16 + height EXR (RLE) + normal PNG of [P]'s workload, {} threads, median of {runs}",
        rayon::current_num_threads()
    );
    println!("| writer | wall | ratio |\n|---|---|---|");
    println!("| baseline: image + exr crates, one file after the other | {base:.0} ms | 1.00 |");
    println!(
        "| `export::stage_maps`: ours, the three at once | {fast:.0} ms | {:.2} |",
        fast / base
    );
    println!("baseline: {}", sizes(&a));
    println!("ours:     {}", sizes(&b));
}
