//! `agesim hair`: the hair transition texture and hair instances of a head (docs/models.md §9).
//!
//! Writes `DIR/transition.png` (16-bit grey: the disappearance age a per texel, white =
//! inner hair that never goes, black = no hair; see `agesim_core::layers::hair::transition`)
//! over the head's own UVs — one file per tile of a UDIM head (`transition.1001.png`, …,
//! named like the bakes) — and `DIR/hair.json` (the inputs, the files, the hair counts at
//! t = 0, 0.25, 0.5, 0.75, 1 and timings); all or nothing.

use std::path::{Path, PathBuf};
use std::time::Instant;

use agesim_core::base::cancel::CancelToken;
use agesim_core::defaults;
use agesim_core::head::mesh::udim::Udim;
use agesim_core::layers::hair::HairInstances;
use agesim_core::layers::hair::transition::{DistanceMetric, TransitionTexture};
use agesim_core::output::export::{self, OutputSet};
use agesim_core::project::Project;
use agesim_core::scene::{BakeRequest, Scene};
use anyhow::Context as _;

/// The ages at which `hair.json` reports the number of hairs present.
const REPORT_AGES: [f32; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

#[derive(Debug, clap::Args)]
pub struct HairArgs {
    /// Outer hair mask (hair at age 0), any grey image. Default: the default head's.
    #[arg(long)]
    pub outer: Option<PathBuf>,
    /// Inner hair mask (hair that stays at age 1). Default: the default head's.
    #[arg(long)]
    pub inner: Option<PathBuf>,
    /// Hair density, hairs per cm² of surface (`hair.density_per_cm2`). Default: the
    /// project's (a new project's: 200).
    #[arg(long)]
    pub density: Option<f32>,
    /// How hair fronts advance (`hair.metric`): chebyshev (the 8-neighbourhood growth of
    /// docs/models.md §9) or euclidean (rounder fronts). Default: the project's.
    #[arg(long)]
    pub metric: Option<DistanceMetric>,
    /// Working size of the transition texture, pixels per side. Default: the larger side
    /// of the two masks.
    #[arg(long)]
    pub size: Option<u32>,
    /// Seed of the hair placement (`hair.seed`). Default: the project's.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Also write `DIR/hair-uv.png`: every hair at its UV, coloured by its disappearance
    /// age (red goes first, yellow, green goes last, blue never), over the texture.
    #[arg(long)]
    pub preview: bool,
    /// Output folder (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// The project, the head and the age (whose hair count is printed besides the table's).
    #[command(flatten)]
    pub head: super::HeadArgs,
}

/// The project of `args`: the project's hair with the flags over it (the `--set`s last),
/// every other layer off.
fn project(args: &HairArgs) -> anyhow::Result<Project> {
    let mut p = args.head.loaded()?;
    if args.outer.is_some() {
        p.hair.outer_mask = args.outer.clone();
    }
    if args.inner.is_some() {
        p.hair.inner_mask = args.inner.clone();
    }
    p.hair.density_per_cm2 = args.density.unwrap_or(p.hair.density_per_cm2);
    p.hair.metric = args.metric.unwrap_or(p.hair.metric);
    p.hair.transition_size_px = args.size.or(p.hair.transition_size_px);
    p.hair.seed = args.seed.unwrap_or(p.hair.seed);
    let mut p = args.head.sets.apply(p)?;
    p.large.enabled = false;
    p.pores.enabled = false;
    p.furrows.enabled = false;
    p.noise.details = 0.0;
    // The same checks as a project file, naming the flag's field.
    p.validate()
        .map_err(|e| anyhow::anyhow!("invalid hair settings: {e}"))?;
    Ok(p)
}

pub fn run(args: &HairArgs) -> anyhow::Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let start = Instant::now();
    let mut scene = Scene::new(project(args)?)?;
    super::MeshArgs::report_units(&scene);
    let mesh_name = match &scene.project().mesh.path {
        Some(path) => path.display().to_string(),
        None => "default head".to_owned(),
    };
    let load_ms = ms(start);
    let start = Instant::now();
    scene.bake(&BakeRequest::hair_only(0.0), &CancelToken::never())?;
    let bake_ms = ms(start);
    let (Some(transition), Some(hairs)) = (scene.transition(), scene.hair()) else {
        anyhow::bail!("no hair was generated (hair is disabled)");
    };
    let project = scene.project();
    let hair = &project.hair;
    // The asked age's count, besides the table's.
    let asked = if args.head.age.given() {
        let t = args.head.age.t(project)?;
        let years = project.age.mapping().years(t);
        Some((t, years, hairs.count(t)))
    } else {
        None
    };
    let size = transition.width_px();
    let transition_ms = bake_ms;
    let surface_triangles = scene.mesh().triangle_count();

    let start = Instant::now();
    let udim = scene.mesh().udim();
    let outputs = OutputSet::new();
    let mut files = export::stage_tiled_grey16(
        &outputs,
        &args.out.join("transition.png"),
        &transition.to_luma16(),
        size,
        udim,
    )?;
    let counts: Vec<serde_json::Value> = REPORT_AGES
        .iter()
        .map(|&t| serde_json::json!({ "t": t, "count": hairs.count(t) }))
        .collect();
    let mut report = serde_json::json!({
        "mesh": mesh_name,
        "triangles": surface_triangles,
        "metres_per_unit": scene.metres_per_unit(),
        "outer": mask_name(hair.outer_mask.as_deref(), defaults::HAIR_OUTER_MASK),
        "inner": mask_name(hair.inner_mask.as_deref(), defaults::HAIR_INNER_MASK),
        "size_px": size,
        "metric": hair.metric,
        "density_per_cm2": hair.density_per_cm2,
        "seed": hair.seed,
        "max_generation_px": transition.max_generation_px(),
        "unreachable_px": transition.unreachable_px(),
        "candidates": hairs.candidates(),
        "instances": hairs.len(),
        "instance_bytes": hairs.as_bytes().len(),
        "age_levels": hairs.levels().len(),
        "counts": counts,
        "at_age": asked.map(|(t, years, count)| serde_json::json!({ "t": t, "years": years, "count": count })),
    });
    let write_ms = ms(start);
    report["timings_ms"] = serde_json::json!({
        "load": load_ms,
        "transition_and_instances": transition_ms,
        "write_png": write_ms,
    });
    if args.preview {
        let preview = args.out.join("hair-uv.png");
        files.extend(stage_uv_preview(
            &outputs, &preview, transition, hairs, udim,
        )?);
    }
    let names: Vec<String> = files
        .iter()
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    report["outputs"] = serde_json::json!(names);
    report["udim_tiles"] = serde_json::json!(udim.filter(|u| u.multi_tile()).map(|u| u.numbers()));
    let json = serde_json::to_vec_pretty(&report)?;
    outputs.stage(&args.out.join("hair.json"), |w| {
        std::io::Write::write_all(w, &json)
    })?;
    outputs.commit()?;
    println!(
        "{} hairs ({} at t = 1), transition {size}² and instances in {transition_ms:.0} ms → {}",
        hairs.len(),
        hairs.count(1.0),
        args.out.display()
    );
    if let Some((t, years, count)) = asked {
        println!("{count} hairs at {years:.0} years (t = {t:.3})");
    }
    Ok(())
}

/// A default mask of the default head: its file name in `assets/masks/` and its bytes,
/// built into the binary so that `agesim hair` works from any folder.
fn mask_name(path: Option<&Path>, default: (&str, &[u8])) -> String {
    match path {
        Some(p) => p.display().to_string(),
        None => format!("default ({})", default.0),
    }
}

/// Side of the UV preview, pixels.
const PREVIEW_PX: u32 = 1024;

/// The UV scatter of `--preview`: the texture as dim grey, each hair one pixel; per tile
/// of a UDIM head ([`PREVIEW_PX`] each), like the transition.
fn stage_uv_preview(
    outputs: &OutputSet,
    path: &Path,
    transition: &TransitionTexture,
    hairs: &HairInstances,
    udim: Option<&Udim>,
) -> anyhow::Result<Vec<PathBuf>> {
    let side = PREVIEW_PX * udim.filter(|u| u.multi_tile()).map_or(1, Udim::grid);
    let n = side as usize;
    let mut rgb = vec![0u8; n * n * 3];
    for y in 0..n {
        for x in 0..n {
            let (u, v) = (
                (x as f32 + 0.5) / n as f32,
                1.0 - (y as f32 + 0.5) / n as f32,
            );
            let grey = (transition.age_at_uv(u, v) * 70.0) as u8;
            rgb[(y * n + x) * 3..][..3].fill(grey);
        }
    }
    for h in hairs.instances() {
        let uv = h.uv();
        let x = ((uv.x * n as f32) as usize).min(n - 1);
        let y = (((1.0 - uv.y) * n as f32) as usize).min(n - 1);
        rgb[(y * n + x) * 3..][..3].copy_from_slice(&age_colour(h.disappear_age()));
    }
    let mut files = Vec::new();
    for (file, side, tile) in Udim::cut(udim, path, &rgb, side, 3) {
        export::stage_rgb8_png(outputs, &file, side, side, &tile)?;
        files.push(file);
    }
    Ok(files)
}

/// Red (goes first) → yellow → green (goes last); blue for hair that never goes.
fn age_colour(age: f32) -> [u8; 3] {
    if age >= 1.0 {
        return [90, 160, 255];
    }
    let a = age.clamp(0.0, 1.0);
    let (r, g) = if a < 0.5 {
        (1.0, 2.0 * a)
    } else {
        (2.0 - 2.0 * a, 1.0)
    };
    [(r * 255.0) as u8, (g * 230.0) as u8, 40]
}

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}
