//! `agesim render`: headless renders of the head with the wgpu renderer, and `--bench`,
//! the frame-time table of the thesis's fig. 8.5 (BENCHMARKS.md; the full tables in docs/benchmarks-history.md).
//!
//! The scene, its layers and every per-frame number go through [`crate::view`], as in
//! the editor: the project's view section (light, camera, relief mode) unless a flag
//! says otherwise.

use std::path::{Path, PathBuf};
use std::time::Instant;

use agesim_core::HeightMap;
use agesim_core::head::landmarks::NAMES;
use agesim_core::layers::hair::DEFAULT_DENSITY_PER_CM2;
use agesim_core::project::{BuiltinMesh, Project, ViewSection};
use agesim_core::scene::Scene;
use agesim_render::{FrameParams, Gpu, PomMode, Renderer};
use anyhow::{Context as _, bail};

use crate::view::{self, HeadlessView};

/// Render the head with the GPU renderer (wgpu; lavapipe works).
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// Draw the 5 cm skin patch instead of the head (close-ups of the relief).
    #[arg(long, conflicts_with = "mesh")]
    pub patch: bool,
    /// Several ages t, comma separated: writes FILE_0000.png, FILE_0001.png, ….
    #[arg(long, value_delimiter = ',', conflicts_with_all = ["age", "age_years"])]
    pub ages: Vec<f32>,
    /// How the large wrinkles are drawn (default: the project's `view.pom`).
    #[arg(long, value_enum)]
    pub pom: Option<PomArg>,
    /// Linear search steps L (default: the project's `view.linear_steps`).
    #[arg(long)]
    pub linear: Option<u32>,
    /// Binary search steps B (default: the project's `view.binary_steps`).
    #[arg(long)]
    pub binary: Option<u32>,
    /// dispScale: depth of the large wrinkles in UV units (default: the project's
    /// `view.disp_scale`, 0.0035 ≈ 1.7 mm on the default head; 0.02 on the 5 cm patch,
    /// ≈ 1 mm). The drawn depth is this × `large.depth`.
    #[arg(long)]
    pub disp_scale: Option<f32>,
    /// Image size, WxH pixels.
    #[arg(long, default_value = "800x800", value_parser = super::parse_size)]
    pub size: (u32, u32),
    /// Samples per pixel along each axis (1–4): the frame drawn this many times larger and
    /// averaged down, so silhouettes (the lids' seam, the ear's rim) and hair strands are
    /// antialiased.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=4))]
    pub supersample: u32,
    /// Camera yaw, degrees (0 = from the front, positive = from the subject's left).
    #[arg(long, allow_hyphen_values = true)]
    pub yaw: Option<f32>,
    /// Camera pitch, degrees.
    #[arg(long, allow_hyphen_values = true)]
    pub pitch: Option<f32>,
    /// Camera distance, mesh units.
    #[arg(long)]
    pub distance: Option<f32>,
    /// Vertical field of view, degrees (default: the project's `view.fov_deg`).
    #[arg(long)]
    pub fov: Option<f32>,
    /// Aim the camera at the head's landmarks (their mean), e.g. `cheilion_r,cheilion_l`
    /// for the mouth, instead of the head's centre: close-ups framed alike on any head
    /// (the landmarks are the project's or those found; `agesim landmarks` lists them).
    #[arg(long, value_delimiter = ',', value_name = "NAME,…")]
    pub look_at: Vec<String>,
    /// Young and old side by side with their ages printed: T0,T1.
    #[arg(
        long,
        value_delimiter = ',',
        conflicts_with_all = ["ages", "age", "age_years"],
        value_name = "T0,T1"
    )]
    pub compare: Vec<f32>,
    /// No hair pass.
    #[arg(long)]
    pub no_hair: bool,
    /// Hair density, hairs per cm².
    #[arg(long, default_value_t = DEFAULT_DENSITY_PER_CM2)]
    pub hair_density: f32,
    /// Side of the large-wrinkle and micro-relief maps, pixels.
    #[arg(long, default_value_t = 1024)]
    pub map_size: u32,
    /// Print the frame-time table (POM modes × iteration counts, normal-only,
    /// displacement, hair on/off) instead of writing an image.
    #[arg(long)]
    pub bench: bool,
    /// Output PNG (not needed with --bench).
    #[arg(long, required_unless_present = "bench")]
    pub out: Option<PathBuf>,
    /// The project, the head and the age.
    #[command(flatten)]
    pub head: super::HeadArgs,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PomArg {
    Linear,
    Binary,
    Combined,
    Normal,
    Displacement,
}

impl From<PomArg> for agesim_core::project::PomMode {
    fn from(p: PomArg) -> Self {
        use agesim_core::project::PomMode as P;
        match p {
            PomArg::Linear => P::Linear,
            PomArg::Binary => P::Binary,
            PomArg::Combined => P::Combined,
            PomArg::Normal => P::Normal,
            PomArg::Displacement => P::Displacement,
        }
    }
}

/// The mean of the head's landmarks named in `names`, in the scene's coordinates.
fn look_at(scene: &Scene, names: &[String]) -> anyhow::Result<glam::Vec3> {
    // The built-in head is the template itself: its landmarks are the template's.
    let builtin = (scene.project().mesh.path.is_none()
        && scene.project().mesh.builtin == BuiltinMesh::Head)
        .then(|| &agesim_core::head::fit::template().landmarks);
    let Some(marks) = scene.layout().landmarks.as_deref().or(builtin) else {
        bail!("--look-at: this head has no landmarks (none given and none found)");
    };
    let mut sum = glam::Vec3::ZERO;
    for name in names {
        sum += marks.get(name).ok_or_else(|| {
            anyhow::anyhow!(
                "--look-at: the head has no landmark `{name}` (names: {})",
                NAMES.join(", ")
            )
        })?;
    }
    Ok(sum / names.len() as f32)
}

/// The project with the command line's mesh, hair and view flags applied.
fn project_of(args: &RenderArgs) -> anyhow::Result<Project> {
    let mut p = args.head.loaded()?;
    if args.patch && args.head.mesh().is_none() {
        p.mesh.builtin = BuiltinMesh::SkinPatch;
        // The patch shows its own creases (its UV square is 5 cm of skin, not a face).
        p.large.enabled = false;
    }
    let density = if args.no_hair { 0.0 } else { args.hair_density };
    p.hair.enabled = density > 0.0 && !args.patch;
    if p.hair.enabled {
        p.hair.density_per_cm2 = density;
    }
    let mut p = args.head.sets.apply(p)?;
    let v = &mut p.view;
    if let Some(pom) = args.pom {
        v.pom = pom.into();
    }
    v.linear_steps = args.linear.unwrap_or(v.linear_steps);
    v.binary_steps = args.binary.unwrap_or(v.binary_steps);
    v.disp_scale = args
        .disp_scale
        .unwrap_or(if args.patch { 0.02 } else { v.disp_scale });
    v.fov_deg = args.fov.unwrap_or(v.fov_deg);
    v.show_hair = !args.no_hair;
    Ok(p)
}

/// Horizontal creases with a rounded valley profile over the patch, heights in [0, 1].
fn patch_wrinkles(size_px: u32) -> anyhow::Result<HeightMap> {
    let n = size_px as usize;
    let mut data = Vec::with_capacity(n * n);
    for y in 0..size_px {
        let v = agesim_core::maps::heightmap::pixel_to_v(y, size_px);
        for x in 0..size_px {
            let u = agesim_core::maps::heightmap::pixel_to_u(x, size_px);
            // 5 creases over 5 cm, gently waving; crest = 1, valley floor = 0.
            let phase = (v * 5.0 + 0.04 * (u * 9.0).sin()) * std::f32::consts::TAU;
            data.push((0.5 + 0.5 * phase.cos()).powf(0.4));
        }
    }
    Ok(HeightMap::from_vec(size_px, size_px, data)?)
}

/// The command's scene on a renderer: the patch's creases follow the layer's default age
/// curve, the head's wrinkles the scene's.
struct Shown {
    view: HeadlessView,
    patch: Option<HeightMap>,
    camera: agesim_render::Camera,
}

impl Shown {
    /// Bakes and uploads age `t` and returns its frame.
    fn at(&mut self, renderer: &mut Renderer, t: f32) -> anyhow::Result<FrameParams> {
        self.view.bake_and_upload(renderer, t)?;
        if let Some(patch) = &self.patch {
            let f = self.view.project().age.factors(t, &[None]).large[0];
            let data = patch.data().iter().map(|h| h * f).collect();
            renderer.upload_large_wrinkles(&HeightMap::from_vec(
                patch.width_px(),
                patch.height_px(),
                data,
            )?)?;
        }
        Ok(self.view.frame_params(t, self.camera))
    }
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    for &t in args.ages.iter().chain(&args.compare) {
        if !(0.0..=1.0).contains(&t) {
            bail!("age t = {t} is outside [0, 1]");
        }
    }
    if !args.compare.is_empty() && args.compare.len() != 2 {
        bail!("--compare takes two ages, T0,T1");
    }
    let project = project_of(args)?;
    let single_t = args.head.age.t(&project)?;
    let start = Instant::now();
    let scene = Scene::new(project)?;
    super::MeshArgs::report_units(&scene);
    let project = scene.project().clone();
    let bounds = scene.mesh().bounds();
    let mut camera = view::camera(&project, scene.metres_per_unit(), bounds.centre());
    let framed = bounds.size().length() * 1.6;
    if args.patch || args.head.mesh().is_some() {
        // Framed: the whole mesh in view, face on (the patch lies in the z = 0 plane
        // facing +z, so `--pitch 70` grazes it).
        camera.distance = framed;
        camera.yaw_rad = 0.0;
        camera.pitch_rad = 0.0;
    } else if project.mesh.path.is_some()
        && project.view.camera_distance_m == ViewSection::default().camera_distance_m
    {
        // A project's own head at the default camera distance (set for the built-in
        // head, in metres): framed at its own size and units, from the project's angle.
        camera.distance = framed;
    }
    if let Some(y) = args.yaw {
        camera.yaw_rad = y.to_radians();
    }
    if let Some(p) = args.pitch {
        camera.pitch_rad = p.to_radians();
    }
    if let Some(d) = args.distance {
        camera.distance = d;
    }
    if !args.look_at.is_empty() {
        camera.target = look_at(&scene, &args.look_at)?;
    }
    let mut shown = Shown {
        view: HeadlessView::new(scene, args.map_size, project.hair.enabled),
        patch: if args.patch {
            Some(patch_wrinkles(args.map_size)?)
        } else {
            None
        },
        camera,
    };
    let gather_ms = start.elapsed().as_secs_f64() * 1e3;

    let gpu = Gpu::new()?;
    println!("adapter: {}", gpu.adapter_description());
    let start = Instant::now();
    let mut renderer = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT)?;
    let setup_ms = start.elapsed().as_secs_f64() * 1e3;

    if args.bench {
        return bench(&mut shown, &mut renderer, &gpu);
    }
    let Some(out) = &args.out else {
        bail!("--out is required");
    };
    let mapping = project.age.mapping();
    let factor = view::supersample_factor(renderer.max_target_side(), args.size, args.supersample);
    if factor < args.supersample {
        println!(
            "--supersample {} lowered to {factor}: {}×{} × {} is beyond the device's {} px target limit",
            args.supersample,
            args.size.0,
            args.size.1,
            args.supersample,
            renderer.max_target_side()
        );
    }

    if let &[t0, t1] = args.compare.as_slice() {
        let mut images = Vec::new();
        for t in [t0, t1] {
            let params = shown.at(&mut renderer, t)?;
            let img =
                view::render_supersampled(&mut renderer, &params, args.size, args.supersample)?;
            images.push((format!("T={t:.2} {:.0}Y", mapping.years(t)), img));
        }
        save(&view::side_by_side(images), out)?;
        println!(
            "{} (t = {t0} | t = {t1}) in {gather_ms:.0} ms + render",
            out.display()
        );
        return Ok(());
    }

    let ages = if args.ages.is_empty() {
        vec![single_t]
    } else {
        args.ages.clone()
    };
    for (i, &t) in ages.iter().enumerate() {
        let params = shown.at(&mut renderer, t)?;
        let start = Instant::now();
        let img = view::render_supersampled(&mut renderer, &params, args.size, args.supersample)?;
        let render_ms = start.elapsed().as_secs_f64() * 1e3;
        let path = if ages.len() > 1 {
            view::numbered(out, i)
        } else {
            out.clone()
        };
        save(&img, &path)?;
        println!(
            "{}: t = {t:.2} ({:.0} years), {} hairs, {} {}+{}, inputs {gather_ms:.0} ms, \
             renderer + uploads {setup_ms:.0} ms, frame {render_ms:.0} ms",
            path.display(),
            mapping.years(t),
            renderer.hair_count(t) * u32::from(params.hair.enabled),
            params.skin.pom_mode.name(),
            params.skin.linear_steps,
            params.skin.binary_steps,
        );
    }
    Ok(())
}

fn save(img: &image::RgbaImage, path: &Path) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    img.save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// The thesis's fig. 8.5 as a table: frame time (encode + submit + wait, readback excluded) at
/// 1280×720 for each mode and iteration count, then the hair pass against the number of
/// hairs drawn. Prints the fastest of the runs (robust to other work on a shared
/// machine) and the median.
///
/// A *new view* frame moves the camera a little each run, so the mesh is rasterised into
/// the stored surface and shaded (what orbiting costs); an *age step* keeps the view and
/// changes the age, so only the shading pass and the hair run (what scrubbing costs).
fn bench(shown: &mut Shown, renderer: &mut Renderer, gpu: &Gpu) -> anyhow::Result<()> {
    const SIZE: (u32, u32) = (1280, 720);
    const RUNS: usize = 7;
    let params = shown.at(renderer, 0.75)?;
    let hairs = renderer.hair_count(0.75);
    const HAIR_AGES: [f32; 4] = [0.0, 0.5, 0.75, 1.0];
    let hair_counts = HAIR_AGES.map(|t| renderer.hair_count(t));
    #[derive(Clone, Copy, PartialEq)]
    enum Vary {
        View,
        Age,
    }
    let mut time = |p: &FrameParams, vary: Vary| -> anyhow::Result<(f64, f64)> {
        let mut samples = Vec::with_capacity(RUNS);
        for run in 0..=RUNS {
            let mut p = *p;
            match vary {
                Vary::View => p.camera.yaw_rad += 1e-4 * run as f32,
                Vary::Age => p.age += 1e-4 * run as f32,
            }
            let p = &p;
            let start = Instant::now();
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("agesim bench frame"),
                });
            renderer.encode(&mut encoder, p, SIZE)?;
            let index = gpu.queue.submit([encoder.finish()]);
            gpu.device
                .poll(wgpu::PollType::Wait {
                    submission_index: Some(index),
                    timeout: None,
                })
                .map_err(|e| anyhow::anyhow!("{e}"))?;
            // The first run warms caches and compiles the pipelines' shaders.
            if run > 0 {
                samples.push(start.elapsed().as_secs_f64() * 1e3);
            }
        }
        samples.sort_by(f64::total_cmp);
        Ok((samples[0], samples[RUNS / 2]))
    };
    println!(
        "1280×720, default head at t = 0.75 ({hairs} hairs); fastest / median of {RUNS} frames, ms"
    );
    println!("| mode | L | B | new view, hair off | age step, hair off | new view, hair on |");
    println!("|---|---|---|---|---|---|");
    let mut row = |mode: PomMode, l: u32, b: u32| -> anyhow::Result<()> {
        let mut p = params;
        p.skin.pom_mode = mode;
        p.skin.linear_steps = l;
        p.skin.binary_steps = b;
        p.hair.enabled = false;
        let off = time(&p, Vary::View)?;
        let step = time(&p, Vary::Age)?;
        p.hair.enabled = true;
        let on = time(&p, Vary::View)?;
        println!(
            "| {} | {l} | {b} | {:.0} / {:.0} | {:.0} / {:.0} | {:.0} / {:.0} |",
            mode.name(),
            off.0,
            off.1,
            step.0,
            step.1,
            on.0,
            on.1
        );
        Ok(())
    };
    for l in [4, 8, 16, 32] {
        row(PomMode::Linear, l, 0)?;
    }
    for b in [4, 8, 16] {
        row(PomMode::Binary, 0, b)?;
    }
    for (l, b) in [(4, 2), (8, 4), (16, 8), (32, 8)] {
        row(PomMode::Combined, l, b)?;
    }
    row(PomMode::NormalOnly, 0, 0)?;
    row(PomMode::Displacement, 0, 0)?;
    // One instanced draw: the hair pass should cost in proportion to count(t).
    println!();
    println!("| age t | hairs drawn | combined 8+4, hair on, age step |");
    println!("|---|---|---|");
    for (t, count) in HAIR_AGES.into_iter().zip(hair_counts) {
        let mut p = params;
        p.age = t;
        let on = time(&p, Vary::Age)?;
        println!("| {t} | {count} | {:.0} / {:.0} |", on.0, on.1);
    }
    Ok(())
}
