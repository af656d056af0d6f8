//! `agesim gen-assets --out assets` (hidden): regenerates the default head's generated
//! assets — the head itself (`meshes/default-head.glb`), masks, the fine-wrinkle tile and
//! the pictures of `assets/README.md` — from
//! the code in agesim-core, so they can be rebuilt and reviewed.

use std::path::{Path, PathBuf};

use agesim_core::export::{write_grey8_png, write_height_png16, write_rgb8_png};
use agesim_core::{HeightMap, Mask, fine_wrinkles, head, muscle, wrinkle_file};
use anyhow::Context as _;

use crate::assets::head as generator;
use crate::assets::masks as head_assets;
use crate::assets::preview::{self, View};
use glam::{Vec2, Vec3};

#[derive(Debug, clap::Args)]
pub struct GenAssetsArgs {
    /// The assets folder to write into (its `wrinkles/*.wrk` are read for the pictures).
    #[arg(long, default_value = "assets")]
    pub out: PathBuf,
}

/// Mask resolution, pixels per side.
const MASK_PX: u32 = 1024;
/// Fine-wrinkle tile resolution.
const TILE_PX: u32 = 512;
/// Picture resolution (assets/docs).
const DOC_PX: u32 = 512;

/// The wrinkle files, in the order of the README, with their picture colours.
pub const WRINKLE_FILES: &[(&str, [f32; 3])] = &[
    ("forehead", [0.95, 0.25, 0.2]),
    ("glabella", [1.0, 0.75, 0.1]),
    ("crows-feet", [0.2, 0.8, 0.3]),
    ("nasolabial", [0.2, 0.6, 1.0]),
    ("marionette", [0.8, 0.3, 0.9]),
    ("neck", [0.1, 0.9, 0.9]),
];

pub fn run(args: &GenAssetsArgs) -> anyhow::Result<()> {
    let out = &args.out;
    for dir in ["masks", "tiles", "docs", "meshes"] {
        std::fs::create_dir_all(out.join(dir))
            .with_context(|| format!("cannot create {}", out.join(dir).display()))?;
    }
    // The default head, built into agesim-core (include_bytes!) for a fast start-up.
    let mesh = generator::generate_default_head()?;
    let glb = out.join(head::DEFAULT_HEAD_ASSET);
    std::fs::write(&glb, agesim_core::mesh::gltf::write_glb(&mesh))
        .with_context(|| format!("cannot write {}", glb.display()))?;

    // Masks.
    let outer = head_assets::paint(MASK_PX, head_assets::hair_outer)?;
    let inner = head_assets::paint(MASK_PX, head_assets::hair_inner)?;
    let wrinkles = head_assets::paint(MASK_PX, head_assets::wrinkle_region)?;
    write_mask(&out.join("masks/hair-outer.png"), &outer)?;
    write_mask(&out.join("masks/hair-inner.png"), &inner)?;
    write_mask(&out.join("masks/wrinkles.png"), &wrinkles)?;
    // Fine-wrinkle tile.
    let tile = fine_wrinkles::generate(TILE_PX, &fine_wrinkles::DEFAULT_FINE_WRINKLES)?;
    write_height_png16(&out.join("tiles/fine-wrinkles.png"), &tile)?;

    // Pictures.
    let layout = head_assets::lit_layout(DOC_PX)?;
    let grey = |m: &Mask, k: usize| m.values()[k];
    let n = (DOC_PX * DOC_PX) as usize;
    let mut pixels = vec![Vec3::ZERO; n];
    for (k, p) in pixels.iter_mut().enumerate() {
        *p = Vec3::splat(grey(&layout, k));
    }
    draw_layout_guides(&mut pixels);
    write_rgb(&out.join("docs/uv-layout.png"), &pixels)?;

    // Every wrinkle file baked onto the layout, one colour per file.
    let mut pixels: Vec<Vec3> = (0..n)
        .map(|k| Vec3::splat(0.8 * grey(&layout, k)))
        .collect();
    for (name, colour) in WRINKLE_FILES {
        let path = out.join(format!("wrinkles/{name}.wrk"));
        let file = wrinkle_file::load(&path)?;
        let fibres: Vec<_> = file.fibres().cloned().collect();
        let map = muscle::rasterize(
            &fibres,
            DOC_PX,
            DOC_PX,
            &muscle::LargeWrinkleSettings::default(),
        )?;
        tint(&mut pixels, &map, Vec3::from_array(*colour));
    }
    write_rgb(&out.join("docs/wrinkles.png"), &pixels)?;

    let mask_over_layout = |mask: &Mask, colour: Vec3| -> Vec<Vec3> {
        let small = mask
            .resampled(DOC_PX, DOC_PX)
            .unwrap_or_else(|_| mask.clone());
        (0..n)
            .map(|k| Vec3::splat(grey(&layout, k)).lerp(colour, 0.6 * small.values()[k]))
            .collect()
    };
    write_rgb(
        &out.join("docs/mask-wrinkles.png"),
        &mask_over_layout(&wrinkles, Vec3::new(1.0, 0.35, 0.2)),
    )?;
    let mut hair = mask_over_layout(&outer, Vec3::new(0.95, 0.8, 0.2));
    let inner_small = inner.resampled(DOC_PX, DOC_PX)?;
    for (p, &v) in hair.iter_mut().zip(inner_small.values()) {
        *p = p.lerp(Vec3::new(0.45, 0.25, 0.1), 0.8 * v);
    }
    write_rgb(&out.join("docs/mask-hair.png"), &hair)?;
    let tile_small = tile.downsample_box(TILE_PX / DOC_PX)?;
    let pixels: Vec<Vec3> = tile_small
        .data()
        .iter()
        .map(|&h| Vec3::splat(1.0 + h))
        .collect();
    write_rgb(&out.join("docs/fine-wrinkles.png"), &pixels)?;

    // Renders of the head: plain, and with the hair masks and the wrinkle mask painted.
    let clay = |_: Vec2| Vec3::splat(0.8);
    let painted = |uv: Vec2| {
        let skin = Vec3::new(0.85, 0.7, 0.62);
        let with_wrinkle_area = skin.lerp(
            Vec3::new(0.9, 0.45, 0.35),
            0.5 * wrinkles.sample(uv.x, uv.y),
        );
        let outer_hair =
            with_wrinkle_area.lerp(Vec3::new(0.75, 0.6, 0.25), outer.sample(uv.x, uv.y));
        outer_hair.lerp(Vec3::new(0.3, 0.18, 0.08), inner.sample(uv.x, uv.y))
    };
    for (name, view) in [
        ("front", View::FRONT),
        ("three-quarter", View::THREE_QUARTER),
        ("side", View::SIDE),
    ] {
        let img = preview::render(&mesh, view, DOC_PX, clay);
        write_rgb8_png(
            &out.join(format!("docs/head-{name}.png")),
            DOC_PX,
            DOC_PX,
            img.as_raw(),
        )?;
    }
    for (name, view) in [("three-quarter", View::THREE_QUARTER), ("back", View::BACK)] {
        let img = preview::render(&mesh, view, DOC_PX, painted);
        write_rgb8_png(
            &out.join(format!("docs/head-masks-{name}.png")),
            DOC_PX,
            DOC_PX,
            img.as_raw(),
        )?;
    }
    println!("wrote the generated assets to {}", out.display());
    Ok(())
}

fn write_mask(path: &Path, mask: &Mask) -> anyhow::Result<()> {
    let bytes: Vec<u8> = mask
        .values()
        .iter()
        .map(|&v| (v * 255.0 + 0.5) as u8)
        .collect();
    write_grey8_png(path, mask.width_px(), mask.height_px(), &bytes)?;
    Ok(())
}

fn write_rgb(path: &Path, pixels: &[Vec3]) -> anyhow::Result<()> {
    let bytes: Vec<u8> = pixels
        .iter()
        .flat_map(|c| {
            c.clamp(Vec3::ZERO, Vec3::ONE)
                .to_array()
                .map(|x| (x * 255.0 + 0.5) as u8)
        })
        .collect();
    write_rgb8_png(path, DOC_PX, DOC_PX, &bytes)?;
    Ok(())
}

/// Paints `colour` where the wrinkle layer `map` (in [0,1]) is high.
fn tint(pixels: &mut [Vec3], map: &HeightMap, colour: Vec3) {
    for (p, &h) in pixels.iter_mut().zip(map.data()) {
        *p = p.lerp(colour, h.clamp(0.0, 1.0));
    }
}

/// Outlines the documented regions of the layout (face rectangle, forehead, neck line).
fn draw_layout_guides(pixels: &mut [Vec3]) {
    let n = DOC_PX as usize;
    let to_px = |u: f32, v: f32| {
        (
            (u * n as f32) as usize,
            (((1.0 - v) * n as f32) as usize).min(n - 1),
        )
    };
    let mut rect = |u0: f32, v0: f32, u1: f32, v1: f32, c: Vec3| {
        let (x0, y1) = to_px(u0, v0);
        let (x1, y0) = to_px(u1, v1);
        for x in x0..=x1.min(n - 1) {
            pixels[y0 * n + x] = c;
            pixels[y1 * n + x] = c;
        }
        for y in y0..=y1 {
            pixels[y * n + x0] = c;
            pixels[y * n + x1.min(n - 1)] = c;
        }
    };
    rect(0.36, 0.25, 0.64, 0.78, Vec3::new(1.0, 0.3, 0.2));
    rect(0.40, 0.61, 0.60, 0.77, Vec3::new(0.2, 0.8, 0.3));
    rect(0.35, 0.0, 0.65, 0.24, Vec3::new(0.2, 0.6, 1.0));
}
