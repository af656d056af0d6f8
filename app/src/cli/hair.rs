//! `agesim hair`: the hair transition texture and hair instances of a head (docs/models.md §9).
//!
//! Writes `DIR/transition.png` (16-bit grey: the disappearance age a per texel, white =
//! inner hair that never goes, black = no hair; see `agesim_core::layers::hair::transition`) and
//! `DIR/hair.json` (the inputs, the hair counts at t = 0, 0.25, 0.5, 0.75, 1 and timings).

use std::path::{Path, PathBuf};
use std::time::Instant;

use agesim_core::base::cancel::CancelToken;
use agesim_core::defaults;
use agesim_core::layers::hair::transition::{DistanceMetric, TransitionTexture};
use agesim_core::layers::hair::{DEFAULT_DENSITY_PER_CM2, HairInstances};
use agesim_core::project::Project;
use agesim_core::scene::{BakeRequest, Scene};
use anyhow::Context as _;

/// The ages at which `hair.json` reports the number of hairs present.
const REPORT_AGES: [f32; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

#[derive(Debug, clap::Args)]
pub struct HairArgs {
    /// The head: its mesh, units and landmarks.
    #[command(flatten)]
    pub head: super::MeshArgs,
    /// Project fields set on the command line (`hair.loss`, …; the flags below win).
    #[command(flatten)]
    pub sets: super::SetArgs,
    /// Outer hair mask (hair at age 0), any grey image. Default: the default head's.
    #[arg(long)]
    pub outer: Option<PathBuf>,
    /// Inner hair mask (hair that stays at age 1). Default: the default head's.
    #[arg(long)]
    pub inner: Option<PathBuf>,
    /// Hair density, hairs per cm² of surface.
    #[arg(long, default_value_t = DEFAULT_DENSITY_PER_CM2)]
    pub density: f32,
    /// How hair fronts advance: chebyshev (the 8-neighbourhood growth of docs/models.md §9) or euclidean
    /// (rounder fronts).
    #[arg(long, default_value = "chebyshev")]
    pub metric: DistanceMetric,
    /// Working size of the transition texture, pixels per side. Default: the larger side
    /// of the two masks.
    #[arg(long)]
    pub size: Option<u32>,
    /// Seed of the hair placement.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Also write `DIR/hair-uv.png`: every hair at its UV, coloured by its disappearance
    /// age (red goes first, yellow, green goes last, blue never), over the texture.
    #[arg(long)]
    pub preview: bool,
    /// Output folder (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

/// The project of `args`: the hair settings from the flags, every other layer off.
fn project(args: &HairArgs) -> anyhow::Result<Project> {
    let mut p = args.sets.apply(Project::default())?;
    args.head.apply_to(&mut p)?;
    p.hair.outer_mask = args.outer.clone();
    p.hair.inner_mask = args.inner.clone();
    p.hair.density_per_cm2 = args.density;
    p.hair.metric = args.metric;
    p.hair.transition_size_px = args.size;
    p.hair.seed = args.seed;
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
    let mesh_name = match &args.head.mesh {
        Some(path) => path.display().to_string(),
        None => "default head".to_owned(),
    };
    let load_ms = ms(start);
    let start = Instant::now();
    let request = BakeRequest {
        large_size_px: 1,
        micro_size_px: 1,
        t: 0.0,
        tileable: false,
        fine: false,
        hair: true,
        packed: false,
        one_off: true,
        micro_normals: false,
        shape_relief: false,
    };
    scene.bake(&request, &CancelToken::never())?;
    let bake_ms = ms(start);
    let (Some(transition), Some(hairs)) = (scene.transition(), scene.hair()) else {
        anyhow::bail!("no hair was generated (hair is disabled)");
    };
    let size = transition.width_px();
    let transition_ms = bake_ms;
    let surface_triangles = scene.mesh().triangle_count();

    let start = Instant::now();
    transition.write_png16(&args.out.join("transition.png"))?;
    let counts: Vec<serde_json::Value> = REPORT_AGES
        .iter()
        .map(|&t| serde_json::json!({ "t": t, "count": hairs.count(t) }))
        .collect();
    let mut report = serde_json::json!({
        "mesh": mesh_name,
        "triangles": surface_triangles,
        "metres_per_unit": scene.metres_per_unit(),
        "outer": mask_name(args.outer.as_deref(), defaults::HAIR_OUTER_MASK),
        "inner": mask_name(args.inner.as_deref(), defaults::HAIR_INNER_MASK),
        "size_px": size,
        "metric": args.metric,
        "density_per_cm2": args.density,
        "seed": args.seed,
        "max_generation_px": transition.max_generation_px(),
        "unreachable_px": transition.unreachable_px(),
        "candidates": hairs.candidates(),
        "instances": hairs.len(),
        "instance_bytes": hairs.as_bytes().len(),
        "age_levels": hairs.levels().len(),
        "counts": counts,
    });
    let write_ms = ms(start);
    report["timings_ms"] = serde_json::json!({
        "load": load_ms,
        "transition_and_instances": transition_ms,
        "write_png": write_ms,
    });
    if args.preview {
        write_uv_preview(&args.out.join("hair-uv.png"), transition, hairs)?;
    }
    let json = serde_json::to_vec_pretty(&report)?;
    agesim_core::output::export::write_atomically(&args.out.join("hair.json"), |w| {
        std::io::Write::write_all(w, &json)
    })?;
    println!(
        "{} hairs ({} at t = 1), transition {size}² and instances in {transition_ms:.0} ms → {}",
        hairs.len(),
        hairs.count(1.0),
        args.out.display()
    );
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

/// The UV scatter of `--preview`: the texture as dim grey, each hair one pixel.
fn write_uv_preview(
    path: &Path,
    transition: &TransitionTexture,
    hairs: &HairInstances,
) -> anyhow::Result<()> {
    let n = PREVIEW_PX as usize;
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
    agesim_core::output::export::write_rgb8_png(path, PREVIEW_PX, PREVIEW_PX, &rgb)?;
    Ok(())
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
