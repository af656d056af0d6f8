//! `agesim bake`: wrinkle files in, height and normal maps out (SPEC §1, §2, §4).

use std::path::{Path, PathBuf};
use std::time::Instant;

use agesim_core::muscle::{self, Fibre, LargeWrinkleSettings};
use agesim_core::normal_map::{self, Convention, NormalSettings};
use agesim_core::wrinkle_file::{self, ParseErrors};
use agesim_core::{HeightMap, Mask, export, heightmap};
use anyhow::{Context as _, bail};
use serde_json::json;

/// Bake height and normal maps from wrinkle description files.
#[derive(Debug, clap::Args)]
pub struct BakeArgs {
    /// Wrinkle description file (repeatable). Default: the wrinkle files shipped in assets/.
    #[arg(long = "wrinkles", value_name = "FILE.wrk")]
    pub wrinkles: Vec<PathBuf>,

    /// Grey-scale mask multiplied into the large-wrinkle layer (any image, any size).
    #[arg(long, value_name = "MASK.png")]
    pub mask: Option<PathBuf>,

    /// Side of the square maps in pixels, 1..=16384.
    #[arg(long, default_value_t = 2048, value_name = "N")]
    pub size: u32,

    /// Crest-flattening exponent γ of the large wrinkles, in [0.01, 10].
    #[arg(long, default_value_t = muscle::DEFAULT_GAMMA, value_name = "G")]
    pub gamma: f32,

    /// Normal-map strength: UV units per height unit, in [0, 1000].
    #[arg(long, default_value_t = normal_map::DEFAULT_STRENGTH, value_name = "S")]
    pub normal_strength: f32,

    /// Green-channel convention of normal.png.
    #[arg(long, value_enum, default_value_t = ConventionArg::Opengl)]
    pub normal_convention: ConventionArg,

    /// Layers to bake into the height map.
    #[arg(long, value_enum, default_value_t = LayersArg::Large)]
    pub layers: LayersArg,

    /// Output directory (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ConventionArg {
    Opengl,
    Directx,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LayersArg {
    /// Large wrinkles (muscle fibres).
    Large,
}

/// A wrinkle file as loaded: where it came from and its fibres.
struct LoadedWrinkles {
    source: String,
    fibres: Vec<Fibre>,
}

/// Bytes a bake of `size_px`² needs at its peak: f32 heights, the u16 copy and its PNG
/// byte buffer, and the RGB normals.
fn peak_bytes(size_px: u32) -> u64 {
    (size_px as u64).pow(2) * (4 + 2 + 2 + 3)
}

/// MemAvailable from /proc/meminfo, when the platform has it.
fn available_memory_bytes() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn load_wrinkles(args: &BakeArgs) -> anyhow::Result<Vec<LoadedWrinkles>> {
    let mut loaded = Vec::new();
    let mut diagnostics = Vec::new();
    let mut push =
        |source: String, result: Result<wrinkle_file::WrinkleFile, ParseErrors>| match result {
            Ok(file) => loaded.push(LoadedWrinkles {
                source,
                fibres: file.fibres().cloned().collect(),
            }),
            Err(errors) => diagnostics.extend(errors.0),
        };
    if args.wrinkles.is_empty() {
        for (name, text) in crate::defaults::WRINKLE_FILES {
            push(name.to_string(), wrinkle_file::parse(text, Path::new(name)));
        }
    } else {
        for path in &args.wrinkles {
            let bytes = std::fs::read(path)
                .with_context(|| format!("cannot read wrinkle file {}", path.display()))?;
            push(
                path.display().to_string(),
                wrinkle_file::parse_bytes(&bytes, path),
            );
        }
    }
    if !diagnostics.is_empty() {
        let n = diagnostics.len();
        bail!(
            "{n} error{} in the wrinkle files, nothing was written:\n{}",
            if n == 1 { "" } else { "s" },
            ParseErrors(diagnostics)
        );
    }
    Ok(loaded)
}

pub fn run(args: &BakeArgs) -> anyhow::Result<()> {
    let total = Instant::now();
    // Everything that can be checked is checked before any output exists.
    heightmap::check_size(args.size, args.size)?;
    if let Some(available) = available_memory_bytes() {
        let needed = peak_bytes(args.size);
        if needed > available {
            bail!(
                "a {0}×{0} bake needs about {1} MiB but only {2} MiB are available; use a smaller --size",
                args.size,
                needed >> 20,
                available >> 20
            );
        }
    }
    let t = Instant::now();
    let wrinkles = load_wrinkles(args)?;
    let mask = args.mask.as_deref().map(Mask::load).transpose()?;
    let parse_ms = ms(t);
    let fibres: Vec<Fibre> = wrinkles
        .iter()
        .flat_map(|w| w.fibres.iter().cloned())
        .collect();
    let settings = LargeWrinkleSettings {
        gamma: args.gamma,
        mask: mask.as_ref(),
    };
    let normal_settings = NormalSettings {
        strength: args.normal_strength,
        convention: match args.normal_convention {
            ConventionArg::Opengl => Convention::OpenGl,
            ConventionArg::Directx => Convention::DirectX,
        },
        tiling: false,
    };
    // Validate the numeric settings on an empty 1×1 bake before creating any file.
    muscle::rasterize(&[], 1, 1, &settings)?;
    normal_map::normals(&HeightMap::zeros(1, 1)?, &normal_settings)?;

    let t = Instant::now();
    let height = muscle::rasterize(&fibres, args.size, args.size, &settings)?;
    let rasterize_ms = ms(t);
    let t = Instant::now();
    let normal_rgb = normal_map::encode_rgb8(&height, &normal_settings)?;
    let normal_ms = ms(t);

    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let t = Instant::now();
    let (lo, hi) = export::write_height_png16(&args.out.join("height.png"), &height)?;
    let png_ms = ms(t);
    let t = Instant::now();
    export::write_height_exr(&args.out.join("height.exr"), &height)?;
    let exr_ms = ms(t);
    let t = Instant::now();
    export::write_rgb8_png(
        &args.out.join("normal.png"),
        args.size,
        args.size,
        &normal_rgb,
    )?;
    let normal_png_ms = ms(t);

    let report = json!({
        "agesim_version": env!("CARGO_PKG_VERSION"),
        "inputs": {
            "wrinkles": wrinkles.iter().map(|w| json!({"file": w.source, "fibres": w.fibres.len()})).collect::<Vec<_>>(),
            "mask": args.mask.as_ref().map(|p| p.display().to_string()),
            "size": args.size,
            "gamma": f32_json(args.gamma),
            "normal_strength": f32_json(args.normal_strength),
            "normal_convention": normal_settings.convention,
            "layers": ["large"],
        },
        "seed": 0,
        "height_range": [lo, hi],
        "height_range_meaning": "height = lo + (hi - lo) * p / 65535 for a height.png value p",
        "outputs": ["height.png", "height.exr", "normal.png", "bake.json"],
        "timings_ms": {
            "parse": parse_ms,
            "rasterize": rasterize_ms,
            "normal_map": normal_ms,
            "write_height_png": png_ms,
            "write_height_exr": exr_ms,
            "write_normal_png": normal_png_ms,
            "total": ms(total),
        },
        "threads": rayon::current_num_threads(),
    });
    let text = serde_json::to_string_pretty(&report)?;
    export::write_atomically(&args.out.join("bake.json"), |w| {
        std::io::Write::write_all(w, text.as_bytes())
    })?;
    println!(
        "baked {} fibres from {} file(s) at {2}×{2} in {3:.0} ms → {4}",
        fibres.len(),
        wrinkles.len(),
        args.size,
        ms(total),
        args.out.display()
    );
    Ok(())
}

/// An f32 as the JSON number with its shortest exact text (0.4, not 0.4000000059604645).
fn f32_json(x: f32) -> serde_json::Value {
    x.to_string()
        .parse::<f64>()
        .map_or(serde_json::Value::Null, serde_json::Value::from)
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
