//! `agesim render`: headless renders of the head with the wgpu renderer (issue 11 §4),
//! and `--bench`, the frame-time table of [T] fig. 8.5 (BENCHMARKS.md).
//!
//! The CPU inputs (mesh, large-wrinkle heights at an age, micro-relief and fine tiles,
//! hair instances) come from the engine's `Scene`, and every age-dependent number from its
//! age model ([`crate::frame::frame_params`]), as in the editor.

use std::path::{Path, PathBuf};
use std::time::Instant;

use agesim_core::cancel::CancelToken;
use agesim_core::hair::DEFAULT_DENSITY_PER_CM2;
use agesim_core::project::{BuiltinMesh, Project};
use agesim_core::scene::{BakeRequest, Scene};
use agesim_core::{HeightMap, Mesh};
use agesim_render::{FrameParams, Gpu, HairShading, PomMode, Renderer, TileLayer};
use anyhow::{Context as _, bail};

/// Render the head with the GPU renderer (wgpu; lavapipe works).
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// Project file (`*.agesim.json`): wrinkles, mask, micro-relief. Default: the default project.
    #[arg(long, value_name = "FILE")]
    pub project: Option<PathBuf>,
    /// Head mesh (OBJ, glTF, GLB). Default: the built-in default head (metres).
    #[arg(long, value_name = "FILE")]
    pub mesh: Option<PathBuf>,
    /// Length of one mesh unit in metres (0.01 for a mesh in centimetres).
    #[arg(long, default_value_t = 1.0)]
    pub metres_per_unit: f32,
    /// Draw the 5 cm skin patch instead of the head (close-ups of the relief).
    #[arg(long, conflicts_with = "mesh")]
    pub patch: bool,
    /// Age t in [0, 1].
    #[arg(long, conflicts_with_all = ["age_years", "ages"])]
    pub age: Option<f32>,
    /// Age in years, 20..=80 (t = (Y − 20)/60).
    #[arg(long, conflicts_with = "ages")]
    pub age_years: Option<f32>,
    /// Several ages t, comma separated: writes FILE_0000.png, FILE_0001.png, ….
    #[arg(long, value_delimiter = ',')]
    pub ages: Vec<f32>,
    /// How the large wrinkles are drawn.
    #[arg(long, value_enum, default_value = "combined")]
    pub pom: PomArg,
    /// Linear search steps L.
    #[arg(long, default_value_t = 8)]
    pub linear: u32,
    /// Binary search steps B.
    #[arg(long, default_value_t = 4)]
    pub binary: u32,
    /// dispScale: depth of the large wrinkles in UV units. Default 0.005 on a head ([T];
    /// ≈ 2.5 mm on the default head), 0.02 on the 5 cm patch (≈ 1 mm).
    #[arg(long)]
    pub disp_scale: Option<f32>,
    /// Image size, WxH pixels.
    #[arg(long, default_value = "800x800", value_parser = super::parse_size)]
    pub size: (u32, u32),
    /// Camera yaw, degrees (0 = from the front, positive = from the subject's left).
    #[arg(long, allow_hyphen_values = true)]
    pub yaw: Option<f32>,
    /// Camera pitch, degrees.
    #[arg(long, allow_hyphen_values = true)]
    pub pitch: Option<f32>,
    /// Camera distance, mesh units.
    #[arg(long)]
    pub distance: Option<f32>,
    /// Vertical field of view, degrees.
    #[arg(long, default_value_t = 30.0)]
    pub fov: f32,
    /// Young and old side by side with their ages printed: T0,T1.
    #[arg(
        long,
        value_delimiter = ',',
        conflicts_with = "ages",
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
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PomArg {
    Linear,
    Binary,
    Combined,
    Normal,
    Displacement,
}

impl From<PomArg> for PomMode {
    fn from(p: PomArg) -> Self {
        match p {
            PomArg::Linear => PomMode::Linear,
            PomArg::Binary => PomMode::Binary,
            PomArg::Combined => PomMode::Combined,
            PomArg::Normal => PomMode::NormalOnly,
            PomArg::Displacement => PomMode::Displacement,
        }
    }
}

/// Everything on the CPU the renderer needs: the engine's [`Scene`] of the project (mesh,
/// large wrinkles at an age, micro-relief and fine tiles, hair), baked at `map_px`.
pub struct SceneInputs {
    scene: Scene,
    map_px: u32,
    hair: bool,
    /// The skin patch's own creases (its UV square is 5 cm of skin, not a face).
    patch_large: Option<HeightMap>,
}

impl SceneInputs {
    /// The scene of `project` with the command line's mesh and hair settings. The
    /// micro-relief tile is repeated over the surface, so it is baked tileable.
    pub fn gather(
        project: &Project,
        mesh: Option<&Path>,
        patch: bool,
        metres_per_unit: f32,
        map_px: u32,
        density: f32,
    ) -> anyhow::Result<Self> {
        let mut p = project.clone();
        p.tile = true;
        if let Some(path) = mesh {
            p.mesh.path = Some(path.to_owned());
            p.mesh.metres_per_unit = metres_per_unit;
        } else if patch {
            p.mesh.builtin = BuiltinMesh::SkinPatch;
        }
        p.hair.enabled = density > 0.0 && !patch;
        if p.hair.enabled {
            p.hair.density_per_cm2 = density;
        }
        Ok(Self {
            scene: Scene::new(p)?,
            map_px,
            hair: density > 0.0 && !patch,
            patch_large: if patch {
                Some(patch_wrinkles(map_px)?)
            } else {
                None
            },
        })
    }

    pub fn mesh(&self) -> &Mesh {
        self.scene.mesh()
    }

    /// Replaces the wrinkle files' contents (the editor's fibre edits).
    pub fn set_wrinkles(&mut self, wrinkles: Vec<agesim_core::scene::WrinkleSource>) {
        self.scene.set_wrinkles(wrinkles);
    }

    pub fn project(&self) -> &Project {
        self.scene.project()
    }

    /// Bakes at age `t`, uploads what changed (everything, the first time), and fills
    /// `params`' age-dependent fields from the engine's age model.
    pub fn upload_age(
        &mut self,
        renderer: &mut Renderer,
        t: f32,
        params: &mut FrameParams,
    ) -> anyhow::Result<()> {
        let request = BakeRequest {
            large_size_px: self.map_px,
            micro_size_px: self.map_px,
            t,
            fine: true,
            hair: self.hair,
            packed: false,
            one_off: true,
            micro_normals: false,
        };
        let first = self.scene.large().is_none() && self.scene.micro().is_none();
        let changed = self.scene.bake(&request, &CancelToken::never())?;
        let project = self.scene.project().clone();
        if first {
            renderer.upload_mesh(self.scene.mesh(), project.mesh.metres_per_unit)?;
        }
        if first || changed.large {
            match (&self.patch_large, self.scene.large()) {
                (Some(patch), _) => {
                    // The patch's creases follow the layer's default age curve.
                    let f = project.age.factors(t, &[None]).large[0];
                    let data = patch.data().iter().map(|h| h * f).collect();
                    renderer.upload_large_wrinkles(&HeightMap::from_vec(
                        patch.width_px(),
                        patch.height_px(),
                        data,
                    )?)?;
                }
                (None, Some(large)) => {
                    let depth = project.large.depth;
                    let inv = if depth > 0.0 { 1.0 / depth } else { 0.0 };
                    let data = large.height.data().iter().map(|h| h * inv).collect();
                    renderer.upload_large_wrinkles(&HeightMap::from_vec(
                        large.height.width_px(),
                        large.height.height_px(),
                        data,
                    )?)?;
                }
                (None, None) => {}
            }
        }
        if (first || changed.micro)
            && let Some(micro) = self.scene.micro()
        {
            renderer.upload_tile(
                TileLayer::Micro,
                &micro.height,
                project.map_size_mm * 1e-3,
                project.normal.strength,
            )?;
        }
        if (first || changed.fine)
            && let Some(fine) = self.scene.fine()
        {
            renderer.upload_tile(
                TileLayer::Fine,
                fine,
                project.fine.size_mm * 1e-3,
                project.fine.strength,
            )?;
        }
        if (first || changed.hair)
            && let Some(hair) = self.scene.hair()
        {
            renderer.upload_hair(hair);
        }
        let p = crate::frame::frame_params(&project, self.scene.factors(), params.camera);
        params.age = p.age;
        params.skin.fine_blend = p.skin.fine_blend;
        params.skin.paleness = p.skin.paleness;
        params.skin.albedo = p.skin.albedo;
        params.skin.micro_relief = p.skin.micro_relief;
        params.hair = HairShading {
            enabled: params.hair.enabled,
            ..p.hair
        };
        Ok(())
    }
}

/// Horizontal creases with a rounded valley profile over the patch, heights in [0, 1].
fn patch_wrinkles(size_px: u32) -> anyhow::Result<HeightMap> {
    let n = size_px as usize;
    let mut data = Vec::with_capacity(n * n);
    for y in 0..size_px {
        let v = agesim_core::heightmap::pixel_to_v(y, size_px);
        for x in 0..size_px {
            let u = agesim_core::heightmap::pixel_to_u(x, size_px);
            // 5 creases over 5 cm, gently waving; crest = 1, valley floor = 0.
            let phase = (v * 5.0 + 0.04 * (u * 9.0).sin()) * std::f32::consts::TAU;
            data.push((0.5 + 0.5 * phase.cos()).powf(0.4));
        }
    }
    Ok(HeightMap::from_vec(size_px, size_px, data)?)
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    for &t in args.ages.iter().chain(&args.compare).chain(&args.age) {
        if !(0.0..=1.0).contains(&t) {
            bail!("age t = {t} is outside [0, 1]");
        }
    }
    if !args.compare.is_empty() && args.compare.len() != 2 {
        bail!("--compare takes two ages, T0,T1");
    }
    let project = match &args.project {
        Some(path) => Project::load(path)?,
        None => Project::default(),
    };
    let start = Instant::now();
    let density = if args.no_hair { 0.0 } else { args.hair_density };
    let mut inputs = SceneInputs::gather(
        &project,
        args.mesh.as_deref(),
        args.patch,
        args.metres_per_unit,
        args.map_size,
        density,
    )?;
    let gather_ms = start.elapsed().as_secs_f64() * 1e3;

    let gpu = Gpu::new()?;
    println!("adapter: {}", gpu.adapter_description());
    let start = Instant::now();
    let mut renderer = Renderer::new(&gpu.device, &gpu.queue, agesim_render::COLOUR_FORMAT)?;
    let setup_ms = start.elapsed().as_secs_f64() * 1e3;

    let mut params = FrameParams::default();
    params.skin.pom_mode = args.pom.into();
    params.skin.linear_steps = args.linear;
    params.skin.binary_steps = args.binary;
    params.skin.disp_scale = args
        .disp_scale
        .unwrap_or(if args.patch { 0.02 } else { 0.005 });
    params.hair.enabled = !args.no_hair;
    let bounds = inputs.mesh().bounds();
    if args.patch || args.mesh.is_some() {
        params.camera.target = bounds.centre();
        params.camera.distance = bounds.size().length() * 1.6;
        // Face on: the patch lies in the z = 0 plane facing +z, so `--pitch 70` grazes it.
        params.camera.yaw_rad = 0.0;
        params.camera.pitch_rad = 0.0;
    }
    if let Some(y) = args.yaw {
        params.camera.yaw_rad = y.to_radians();
    }
    if let Some(p) = args.pitch {
        params.camera.pitch_rad = p.to_radians();
    }
    if let Some(d) = args.distance {
        params.camera.distance = d;
    }
    params.camera.fov_y_rad = args.fov.to_radians();

    if args.bench {
        return bench(&mut inputs, &mut renderer, params, &gpu);
    }
    let Some(out) = &args.out else {
        bail!("--out is required");
    };

    if !args.compare.is_empty() {
        let &[t0, t1] = args.compare.as_slice() else {
            bail!("--compare takes two ages, T0,T1");
        };
        let mut images = Vec::new();
        for t in [t0, t1] {
            inputs.upload_age(&mut renderer, t, &mut params)?;
            let img = renderer.render_to_image(&params, args.size)?;
            let label = format!("T={t:.2} {:.0}Y", inputs.project().age.mapping().years(t));
            images.push((label, img));
        }
        save(&side_by_side(images), out)?;
        println!(
            "{} (t = {t0} | t = {t1}) in {gather_ms:.0} ms + render",
            out.display()
        );
        return Ok(());
    }

    let ages: Vec<f32> = if !args.ages.is_empty() {
        args.ages.clone()
    } else if let Some(y) = args.age_years {
        vec![project.age.mapping().t(y)]
    } else {
        vec![args.age.unwrap_or(0.5)]
    };
    for (i, &t) in ages.iter().enumerate() {
        inputs.upload_age(&mut renderer, t, &mut params)?;
        let start = Instant::now();
        let img = renderer.render_to_image(&params, args.size)?;
        let render_ms = start.elapsed().as_secs_f64() * 1e3;
        let path = if ages.len() > 1 {
            crate::export::numbered(out, i)
        } else {
            out.clone()
        };
        save(&img, &path)?;
        println!(
            "{}: t = {t:.2} ({:.0} years), {} hairs, {} {}+{}, inputs {gather_ms:.0} ms, \
             renderer + uploads {setup_ms:.0} ms, frame {render_ms:.0} ms",
            path.display(),
            inputs.project().age.mapping().years(t),
            renderer.hair_count(t) * u32::from(params.hair.enabled),
            params.skin.pom_mode.name(),
            params.skin.linear_steps,
            params.skin.binary_steps,
        );
    }
    Ok(())
}

/// Images of one size side by side, each labelled in its top-left corner.
pub fn side_by_side(images: Vec<(String, image::RgbaImage)>) -> image::RgbaImage {
    let (w, h) = images.first().map_or((1, 1), |(_, i)| i.dimensions());
    let mut side = image::RgbaImage::new(w * images.len().max(1) as u32, h);
    for (i, (label, mut img)) in images.into_iter().enumerate() {
        crate::cli::font::draw_text(&mut img, 8, 8, 3, &label, [255, 255, 255, 255]);
        image::imageops::replace(&mut side, &img, i as i64 * i64::from(w), 0);
    }
    side
}

fn save(img: &image::RgbaImage, path: &Path) -> anyhow::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    img.save(path)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// [T] fig. 8.5 as a table: frame time (encode + submit + wait, readback excluded) at
/// 1280×720 for each mode and iteration count, then the hair pass against the number of
/// hairs drawn. Prints the fastest of the runs (robust to other work on a shared
/// machine) and the median.
///
/// A *new view* frame moves the camera a little each run, so the mesh is rasterised into
/// the stored surface and shaded (what orbiting costs); an *age step* keeps the view and
/// changes the age, so only the shading pass and the hair run (what scrubbing costs).
fn bench(
    inputs: &mut SceneInputs,
    renderer: &mut Renderer,
    mut params: FrameParams,
    gpu: &Gpu,
) -> anyhow::Result<()> {
    const SIZE: (u32, u32) = (1280, 720);
    const RUNS: usize = 7;
    inputs.upload_age(renderer, 0.75, &mut params)?;
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
