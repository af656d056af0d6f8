//! `agesim bake`: a project (or flags) in, height and normal maps out (docs/models.md §2–§4).
//!
//! Settings resolve in this order, each step validated like the project file:
//! the default project, or `--preset NAME`, or `--project FILE`; then the head flags
//! (`--mesh`, `--landmarks`, `--colour-map`, …: [`super::HeadArgs`]); then the shorthand flags
//! (`--wrinkles`, `--mask`, `--gamma`, `--tile`, `--seed`, `--normal-*`); then every
//! `--set path=value` in order; then `--layers`. The resolved project is recorded in
//! `bake.json`, so a bake can be reproduced from that file alone.

use std::path::PathBuf;
use std::time::Instant;

use agesim_core::base::cancel::CancelToken;
use agesim_core::output::names::{MapKind, Naming};
use agesim_core::project::Project;
use agesim_core::scene::Scene;
use agesim_core::{defaults, maps::heightmap, output::export};
use anyhow::{Context as _, bail};
use serde_json::json;

/// Bake height and normal maps: large wrinkles and skin micro-relief, from a project.
#[derive(Debug, clap::Args)]
pub struct BakeArgs {
    /// Wrinkle description file (repeatable); sets `large.wrinkles`. Default: the default
    /// head's wrinkle files and mask shipped in assets/.
    #[arg(long = "wrinkles", value_name = "FILE.wrk")]
    pub wrinkles: Vec<PathBuf>,

    /// Grey-scale mask multiplied into the large-wrinkle layer (any image, any size).
    #[arg(long, value_name = "MASK.png")]
    pub mask: Option<PathBuf>,

    /// Side of the square maps in pixels, 1..=16384.
    #[arg(long, default_value_t = 2048, value_name = "N",
          value_parser = clap::value_parser!(u32).range(1..=16384))]
    pub size: u32,

    /// Crest-flattening exponent γ of the large wrinkles, in [0.01, 10] (`large.gamma`).
    #[arg(long, value_name = "G")]
    pub gamma: Option<f32>,

    /// Normal-map strength: UV units per height unit, in [0, 1000] (`normal.strength`).
    #[arg(long, value_name = "S")]
    pub normal_strength: Option<f32>,

    /// Green-channel convention of normal.png (`normal.convention`).
    #[arg(long, value_enum)]
    pub normal_convention: Option<ConventionArg>,

    /// Layers in the height map. Default: `large` without --project/--preset, otherwise
    /// the layers the project enables.
    #[arg(long, value_enum)]
    pub layers: Option<LayersArg>,

    /// Make the map tile (periodic noise, features wrap around the edges).
    #[arg(long)]
    pub tile: bool,

    /// Seed of every random choice (`seed`).
    #[arg(long, value_name = "S")]
    pub seed: Option<u64>,

    /// Compression of height.exr (all lossless): rle (default; coded on all cores, usually
    /// the fastest), none (4 bytes per pixel), zip (smallest, slowest).
    #[arg(long, value_enum, default_value = "rle")]
    pub exr_compression: ExrCompressionArg,

    /// How the maps are named: texture-set (`head_BaseColor.png`, `head_Normal.png`,
    /// `head_Height.png`/`.exr`, `head_Roughness.png`, `head_AO.png`, as Substance,
    /// Marmoset and the engines name a texture set's maps) or agesim (`albedo.png`,
    /// `normal.png`, `height.png`/`.exr`, `roughness.png`, `ao.png`).
    #[arg(long, value_enum, default_value = "texture-set")]
    pub names: NamesArg,

    /// The texture set's name, the maps' file names' start (default: `head` for
    /// texture-set names, none for agesim's).
    #[arg(long, value_name = "NAME")]
    pub texture_set: Option<String>,

    /// Output directory (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The project, the head and the age (the flags every command that reads a head takes).
    #[command(flatten)]
    pub head: super::HeadArgs,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum NamesArg {
    TextureSet,
    Agesim,
}

impl From<NamesArg> for Naming {
    fn from(n: NamesArg) -> Self {
        match n {
            NamesArg::TextureSet => Self::TextureSet,
            NamesArg::Agesim => Self::Agesim,
        }
    }
}

/// The texture set's name of `args`, checked: a file name's start.
fn texture_set(args: &BakeArgs) -> anyhow::Result<String> {
    let set = match (&args.texture_set, args.names) {
        (Some(s), _) => s.trim().to_owned(),
        (None, NamesArg::TextureSet) => "head".to_owned(),
        (None, NamesArg::Agesim) => String::new(),
    };
    if args.texture_set.is_some()
        && (set.is_empty() || set.contains(['/', '\\', ':']) || set.starts_with('.'))
    {
        bail!("--texture-set `{set}`: expected a file name's start without folders, e.g. head");
    }
    Ok(set)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ExrCompressionArg {
    Rle,
    None,
    Zip,
}

impl From<ExrCompressionArg> for export::ExrCompression {
    fn from(c: ExrCompressionArg) -> Self {
        match c {
            ExrCompressionArg::Rle => Self::Rle,
            ExrCompressionArg::None => Self::None,
            ExrCompressionArg::Zip => Self::Zip,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ConventionArg {
    Opengl,
    Directx,
}

impl From<ConventionArg> for agesim_core::maps::normal_map::Convention {
    fn from(c: ConventionArg) -> Self {
        match c {
            ConventionArg::Opengl => Self::OpenGl,
            ConventionArg::Directx => Self::DirectX,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LayersArg {
    /// Large wrinkles (muscle fibres) only.
    Large,
    /// Skin micro-relief only: pores, furrows, noise.
    Micro,
    /// Both.
    All,
}

/// The project of `args`, fully resolved and validated.
fn resolve_project(args: &BakeArgs) -> anyhow::Result<Project> {
    let mut project = args.head.loaded()?;
    // (field, value as JSON, what the user typed): errors quote the flag as typed.
    let mut edits: Vec<(&str, String, String)> = Vec::new();
    if !args.wrinkles.is_empty() {
        let typed: Vec<String> = args
            .wrinkles
            .iter()
            .map(|w| format!("--wrinkles {}", w.display()))
            .collect();
        edits.push((
            "large.wrinkles",
            json!(args.wrinkles).to_string(),
            typed.join(" "),
        ));
    }
    if let Some(mask) = &args.mask {
        edits.push((
            "large.mask",
            json!(mask).to_string(),
            format!("--mask {}", mask.display()),
        ));
    }
    if let Some(g) = args.gamma {
        edits.push(("large.gamma", g.to_string(), format!("--gamma {g}")));
    }
    if let Some(s) = args.normal_strength {
        edits.push((
            "normal.strength",
            s.to_string(),
            format!("--normal-strength {s}"),
        ));
    }
    if let Some(c) = args.normal_convention {
        let name = if c == ConventionArg::Directx {
            "directx"
        } else {
            "opengl"
        };
        edits.push((
            "normal.convention",
            name.into(),
            format!("--normal-convention {name}"),
        ));
    }
    if args.tile {
        edits.push(("tile", "true".into(), "--tile".into()));
    }
    if let Some(seed) = args.seed {
        edits.push(("seed", seed.to_string(), format!("--seed {seed}")));
    }
    for (path, value, typed) in edits {
        project = project.set_as(path, &value, &typed)?;
    }
    let mut project = args.head.sets.apply(project)?;
    // One rule, so nothing the user asked for is dropped: without --layers, a bake with
    // neither project nor preset is large wrinkles only *unless* a --set names a
    // micro-relief field (then it is everything); an explicit --wrinkles or --mask turns
    // the large-wrinkle layer on even where a preset had it off. An explicit --layers is
    // the user's own choice and wins (the fields stay in bake.json's project).
    let micro_asked = args.head.sets.paths().any(|path| {
        [
            "pores.",
            "furrows.",
            "noise.",
            "warp.",
            "overlap.",
            "map_size_mm",
        ]
        .iter()
        .any(|prefix| path.starts_with(prefix))
    });
    if !args.wrinkles.is_empty() || args.mask.is_some() {
        project.large.enabled = true;
    }
    let layers = args.layers.or(if !args.head.has_project() {
        Some(if micro_asked {
            LayersArg::All
        } else {
            LayersArg::Large
        })
    } else {
        None
    });
    if let Some(layers) = layers {
        let large = layers != LayersArg::Micro;
        let micro = layers != LayersArg::Large;
        project.large.enabled = large;
        project.pores.enabled &= micro;
        project.furrows.enabled &= micro;
        if !micro {
            project.noise.details = 0.0;
        }
    }
    Ok(project)
}

/// The layer names a resolved project bakes.
fn layer_names(project: &Project) -> Vec<&'static str> {
    let mut names = Vec::new();
    if project.large.enabled {
        names.push("large");
    }
    if project.pores.enabled {
        names.push("pores");
    }
    if project.furrows.enabled {
        names.push("furrows");
    }
    if project.noise.details > 0.0 && project.noise.strength > 0.0 {
        names.push("noise");
    }
    names
}

pub fn run(args: &BakeArgs) -> anyhow::Result<()> {
    let total = Instant::now();
    // Everything that can be checked is checked before any output exists.
    heightmap::check_size(args.size, args.size)?;
    crate::export::check_map_size(args.size, "--size")?;
    let t = Instant::now();
    let project = resolve_project(args)?;
    let set = texture_set(args)?;
    let age_t = args.head.age.t(&project)?;
    let tileable = project.tile;
    // Loads the mesh, wrinkle files and masks, and checks every setting.
    let mut scene = Scene::new(project)?;
    let parse_ms = ms(t);
    // The export's path: the maps over the head's layout (its UDIM atlas, `--size` per
    // tile), and the aged base colour (docs/models.md "Skin colour") at the scene's size
    // for them (`Scene::colour_px`), not the maps'.
    let baked = crate::export::bake_maps(
        &mut scene,
        age_t,
        args.size,
        tileable,
        crate::export::Wanted {
            colour: true,
            crease: true,
        },
        "--size",
        &CancelToken::never(),
    )?;
    let (bake_ms, colour_ms, sum_ms) = (baked.bake_ms, baked.colour_ms, baked.take_ms);
    let udim = baked.udim.clone();
    let project = scene.project();
    let (fibres, _) = scene.fibres();
    let (pores, furrows) = scene
        .relief()
        .map_or((0, 0), |r| (r.pores().len(), r.furrows().len()));
    if project.large.enabled && fibres.is_empty() {
        let files: Vec<&str> = scene.wrinkles().iter().map(|w| w.name.as_str()).collect();
        if !scene.micro_enabled() {
            bail!(
                "nothing to bake: the wrinkle files ({}) hold no fibre and no micro-relief layer is on; nothing was written",
                files.join(", ")
            );
        }
        eprintln!(
            "warning: the wrinkle files ({}) hold no fibre: the large-wrinkle layer is flat",
            files.join(", ")
        );
    }

    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    // The whole set is old or new: each map goes to a temporary (the three encoded at
    // once), and only when all are written are they renamed into place, bake.json last.
    let outputs = export::OutputSet::new();
    let write_start = Instant::now();
    let file = |kind: MapKind| args.out.join(kind.file_name(args.names.into(), &set));
    let names = [
        MapKind::Height,
        MapKind::HeightExr,
        MapKind::Normal,
        MapKind::BaseColour,
        MapKind::Roughness,
        MapKind::Ao,
    ]
    .map(file);
    let paths = crate::export::MapPaths {
        height_png: Some(&names[0]),
        height_exr: Some(&names[1]),
        normal_png: Some(&names[2]),
        base_colour_png: baked.colour.as_ref().map(|_| names[3].as_path()),
        roughness_png: Some(&names[4]),
        ao_png: Some(&names[5]),
    };
    let (staged, written) =
        crate::export::stage_maps(&outputs, paths, &baked, args.exr_compression.into())?;
    let mut files: Vec<String> = written
        .iter()
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    files.push("bake.json".to_owned());
    let (lo, hi) = staged.height_png_range.unwrap_or_default();
    let maps_ms = ms(write_start);

    let report = json!({
        "agesim_version": env!("CARGO_PKG_VERSION"),
        "inputs": {
            "project_source": args.head.source(),
            "wrinkles": if project.large.enabled {
                scene.wrinkles().iter().map(|w| json!({"file": w.name, "fibres": w.file.groups.len()})).collect::<Vec<_>>()
            } else {
                Vec::new()
            },
            "mask": match (&project.large.mask, project.large.enabled && project.large.wrinkles.is_empty()) {
                (Some(p), _) => Some(p.display().to_string()),
                (None, true) => Some(defaults::WRINKLE_MASK.0.to_string()),
                (None, false) => None,
            },
            "size": args.size,
            "size_meaning": if udim.as_ref().is_some_and(|u| u.multi_tile()) { "per UDIM tile" } else { "the map's side" },
            "gamma": f32_json(project.large.gamma),
            "normal_strength": f32_json(project.normal.strength),
            "normal_convention": baked.normal.convention,
            "layers": layer_names(project),
            "pores": pores,
            "furrows": furrows,
            "exr_compression": export::ExrCompression::from(args.exr_compression),
            "names": Naming::from(args.names),
            "texture_set": set,
            "age_t": age_t,
            "age_years": project.age.mapping().years(age_t),
        },
        "seed": project.seed,
        // Paths relative to the output folder: save it as a project there (or anywhere
        // with the inputs beside it) and bake it again.
        "project": project.to_value_relative_to(&args.out),
        "height_range": [lo, hi],
        "height_range_meaning": "height = lo + (hi - lo) * p / 65535 for a height.png value p",
        "outputs": files,
        "udim_tiles": udim.as_ref().filter(|u| u.multi_tile()).map(|u| u.numbers()),
        "timings_ms": {
            "parse_and_features": parse_ms,
            "bake": bake_ms,
            "bake_colour": colour_ms,
            "export_sum": sum_ms,
            "write_height_png": staged.height_png_ms,
            "write_height_exr": staged.height_exr_ms,
            "write_normal_png": staged.normal_png_ms,
            "write_maps_concurrently": maps_ms,
            "total": ms(total),
        },
        "threads": rayon::current_num_threads(),
    });
    let text = serde_json::to_string_pretty(&report)?;
    outputs.stage(&args.out.join("bake.json"), |w| {
        std::io::Write::write_all(w, text.as_bytes())
    })?;
    outputs.commit()?;
    println!(
        "baked {layers} ({fibres} fibres, {pores} pores, {furrows} furrows) at {size}×{size}{tiles} in {total_ms:.0} ms → {out}",
        layers = layer_names(project).join("+"),
        fibres = if project.large.enabled {
            fibres.len()
        } else {
            0
        },
        size = args.size,
        tiles = match &udim {
            Some(u) if u.multi_tile() => format!(" per tile, UDIM tiles {:?}", u.numbers()),
            _ => String::new(),
        },
        total_ms = ms(total),
        out = args.out.display()
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
