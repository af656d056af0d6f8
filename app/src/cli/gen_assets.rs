//! `agesim gen-assets --out assets` (hidden): regenerates the default head's generated
//! assets — the head itself (`meshes/default-head.glb`), masks, the fine-wrinkle tile and
//! the pictures of `assets/README.md` — from
//! the code in agesim-core, so they can be rebuilt and reviewed.

use std::path::{Path, PathBuf};

use agesim_core::output::export::{write_grey8_png, write_height_png16, write_rgb8_png};
use agesim_core::{
    HeightMap, Mask, head, layers::wrinkles::fine_wrinkles, layers::wrinkles::muscle,
    layers::wrinkles::wrinkle_file,
};
use anyhow::Context as _;

use crate::assets::masks as head_assets;
use crate::assets::preview::{self, View};
use crate::assets::scan;
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
    ("under-eye", [0.6, 0.9, 0.2]),
    ("nasolabial", [0.2, 0.6, 1.0]),
    ("perioral", [1.0, 0.45, 0.6]),
    ("marionette", [0.8, 0.3, 0.9]),
    ("neck", [0.1, 0.9, 0.9]),
];

pub fn run(args: &GenAssetsArgs) -> anyhow::Result<()> {
    let out = &args.out;
    for dir in ["masks", "tiles", "docs", "meshes"] {
        std::fs::create_dir_all(out.join(dir))
            .with_context(|| format!("cannot create {}", out.join(dir).display()))?;
    }
    // The default head, converted from the scan; built into agesim-core (include_bytes!).
    let head = scan::convert_scan(out)?;
    let glb = out.join(head::default::DEFAULT_HEAD_ASSET);
    std::fs::write(&glb, default_head_glb(&head))
        .with_context(|| format!("cannot write {}", glb.display()))?;
    let landmarks_path = out.join(head::default::DEFAULT_HEAD_LANDMARKS_ASSET);
    std::fs::write(&landmarks_path, head.landmarks.to_json_pretty() + "\n")
        .with_context(|| format!("cannot write {}", landmarks_path.display()))?;
    let mesh = &head.mesh;
    let face = head_assets::Face::new(&head.landmarks)
        .context("the converted scan lacks the eye, mouth or ear landmarks")?;

    // Masks.
    let surface = head_assets::Surface::new(mesh, MASK_PX)?;
    let outer = surface.paint(|p| face.hair_outer(p))?;
    let inner = surface.paint(|p| face.hair_inner(p))?;
    let wrinkles = surface.paint(|p| face.wrinkle_region(p))?;
    let order = surface.paint(|p| face.hair_order(p))?;
    write_mask(&out.join("masks/hair-order.png"), &order)?;
    write_mask(&out.join("masks/hair-outer.png"), &outer)?;
    write_mask(&out.join("masks/hair-inner.png"), &inner)?;
    write_mask(&out.join("masks/wrinkles.png"), &wrinkles)?;
    // Fine-wrinkle tile.
    let tile = fine_wrinkles::generate(TILE_PX, &fine_wrinkles::DEFAULT_FINE_WRINKLES)?;
    write_height_png16(&out.join("tiles/fine-wrinkles.png"), &tile)?;

    // Pictures: the layout is the scan's colour map, with the landmarks on it.
    let colour =
        agesim_core::maps::mask::HeadImage::decode(&head.colour_jpeg, Path::new("Map-COL.jpg"))?;
    let albedo = |uv: Vec2| colour_at(&colour, uv);
    let n = (DOC_PX * DOC_PX) as usize;
    let layout: Vec<Vec3> = (0..n)
        .map(|k| {
            let (x, y) = (k as u32 % DOC_PX, k as u32 / DOC_PX);
            albedo(Vec2::new(
                agesim_core::maps::heightmap::pixel_to_u(x, DOC_PX),
                agesim_core::maps::heightmap::pixel_to_v(y, DOC_PX),
            ))
        })
        .collect();
    let mut pixels = layout.clone();
    for name in agesim_core::head::landmarks::NAMES {
        if let Some(uv) = head
            .landmarks
            .get(name)
            .and_then(|p| head_assets::uv_near(mesh, p))
        {
            draw_dot(&mut pixels, uv, Vec3::new(0.1, 0.9, 0.2));
        }
    }
    write_rgb(&out.join("docs/uv-layout.png"), &pixels)?;

    // Every wrinkle file baked onto the layout, one colour per file.
    let mut pixels: Vec<Vec3> = layout.iter().map(|&c| 0.8 * c).collect();
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

    let mask_over_layout = |mask: &Mask, colour: Vec3| -> anyhow::Result<Vec<Vec3>> {
        let small = mask.resampled(DOC_PX, DOC_PX)?;
        Ok(layout
            .iter()
            .zip(small.values())
            .map(|(&c, &m)| c.lerp(colour, 0.6 * m))
            .collect())
    };
    write_rgb(
        &out.join("docs/mask-wrinkles.png"),
        &mask_over_layout(&wrinkles, Vec3::new(1.0, 0.35, 0.2))?,
    )?;
    let mut hair = mask_over_layout(&outer, Vec3::new(0.95, 0.8, 0.2))?;
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

    // Renders of the head: with its colour map, and with the hair masks and the wrinkle
    // mask painted over it.
    let painted = |uv: Vec2| {
        let skin = albedo(uv);
        let with_wrinkle_area = skin.lerp(
            Vec3::new(0.9, 0.45, 0.35),
            0.5 * wrinkles.sample(uv.x, uv.y),
        );
        let outer_hair =
            with_wrinkle_area.lerp(Vec3::new(0.75, 0.6, 0.25), 0.8 * outer.sample(uv.x, uv.y));
        outer_hair.lerp(Vec3::new(0.3, 0.18, 0.08), 0.8 * inner.sample(uv.x, uv.y))
    };
    for (name, view) in [
        ("front", View::FRONT),
        ("three-quarter", View::THREE_QUARTER),
        ("side", View::SIDE),
    ] {
        let img = preview::render(mesh, view, DOC_PX, albedo);
        write_rgb8_png(
            &out.join(format!("docs/head-{name}.png")),
            DOC_PX,
            DOC_PX,
            img.as_raw(),
        )?;
    }
    for (name, view) in [
        ("front", View::FRONT),
        ("three-quarter", View::THREE_QUARTER),
        ("back", View::BACK),
    ] {
        let img = preview::render(mesh, view, DOC_PX, painted);
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

/// The default head as GLB, with the scan's maps embedded as its material.
pub fn default_head_glb(head: &scan::DefaultHead) -> Vec<u8> {
    let material = agesim_core::head::mesh::gltf::GlbMaterial {
        name: "skin (Lee Perry-Smith scan, CC BY 3.0)".to_owned(),
        base_colour: [1.0; 4],
        base_colour_png: Some(head.colour_jpeg.clone()),
        roughness: 0.6,
        metallic: 0.0,
        normal_png: Some(head.normal_jpeg.clone()),
        orm_png: None,
        extras: serde_json::json!({
            "credit": "Infinite, 3D Head Scan by Lee Perry-Smith, licensed under CC BY 3.0, based on a work at triplegangers.com"
        }),
    };
    agesim_core::head::mesh::gltf::write_glb_with_material(&head.mesh, Some(&material))
}

/// The colour map at `uv` (linear, nearest texel; v up).
fn colour_at(image: &agesim_core::maps::mask::HeadImage, uv: Vec2) -> Vec3 {
    let (w, h) = (image.width_px as f32, image.height_px as f32);
    let x = ((uv.x * w) as u32).min(image.width_px - 1);
    let y = (((1.0 - uv.y) * h) as u32).min(image.height_px - 1);
    let i = 4 * (y * image.width_px + x) as usize;
    let px = &image.rgba[i..i + 3];
    Vec3::new(px[0] as f32, px[1] as f32, px[2] as f32) / 255.0
}

/// A 5-pixel dot at `uv` on a DOC_PX² picture.
fn draw_dot(pixels: &mut [Vec3], uv: Vec2, colour: Vec3) {
    let n = DOC_PX as i64;
    let (cx, cy) = ((uv.x * n as f32) as i64, ((1.0 - uv.y) * n as f32) as i64);
    for dy in -2..=2 {
        for dx in -2..=2 {
            let (x, y) = (cx + dx, cy + dy);
            if (0..n).contains(&x) && (0..n).contains(&y) && dx * dx + dy * dy <= 5 {
                pixels[(y * n + x) as usize] = colour;
            }
        }
    }
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
