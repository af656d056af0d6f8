//! The command line: one binary, one subcommand per task.

pub mod bake;
pub mod export;
pub mod gen_assets;
pub mod hair;
pub mod landmarks;
pub mod mesh_info;
pub mod render;

use clap::{Parser, Subcommand};

/// agesim: age a human head — wrinkles, skin micro-relief, hair recession and graying.
#[derive(Debug, Parser)]
#[command(name = "agesim", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,

    /// Open this project (`*.agesim.json`) in the editor.
    #[arg(long, value_name = "FILE")]
    pub project: Option<std::path::PathBuf>,

    /// Editor: write a screenshot of the window (PNG) once maps are shown, then quit.
    #[arg(long, value_name = "FILE.png")]
    pub screenshot: Option<std::path::PathBuf>,

    /// Editor: frames to draw (after the first bake) before the screenshot.
    #[arg(long, default_value_t = 5, value_name = "N")]
    pub frames: u32,

    /// Editor: open at this age in years.
    #[arg(long, value_name = "Y")]
    pub age_years: Option<f32>,

    /// Editor: open the compare view with this age (years) on the right.
    #[arg(long, value_name = "Y")]
    pub compare_years: Option<f32>,

    /// Editor: run the scripted UI benchmark (frame time during a 4096² bake, slider to
    /// visible, scrubbing), print its table and quit.
    #[arg(long)]
    pub bench_ui: bool,

    /// Editor: once the first maps are up, drive the editor at random for SECONDS (slider
    /// and fibre drags, age scrubs, undo/redo, wrinkle files rewritten on disk), print its
    /// figures (bake requests answered, memory) and quit; exits with an error when a check
    /// failed.
    #[arg(long, value_name = "SECONDS")]
    pub soak: Option<f64>,

    /// Editor: write the unsaved session to the recovery folder at most every N seconds
    /// (`$XDG_DATA_HOME/agesim/recovery/`); 0 turns autosave off.
    #[arg(long, default_value_t = 60.0, value_name = "N")]
    pub autosave_seconds: f64,

    /// Editor: restore the session a crash left in the recovery folder without asking.
    #[arg(long)]
    pub recover: bool,

    /// Editor: one edit made once the editor is up (`noise.strength=0.7`), as if by
    /// hand: for scripted runs and tests.
    #[arg(long, value_name = "FIELD=VALUE", hide = true)]
    pub edit: Option<String>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Bake height and normal maps: large wrinkles and skin micro-relief, from a project.
    Bake(bake::BakeArgs),
    /// Hair aging (docs/models.md §9): transition texture, hair instances and their counts per age.
    Hair(hair::HairArgs),
    /// Print what a head mesh (OBJ, glTF, GLB) contains: counts, size, attributes, repairs.
    MeshInfo(mesh_info::MeshInfoArgs),
    /// Find a head's facial landmarks automatically and write them as a landmark file
    /// (to check, correct and give back with --landmarks).
    Landmarks(landmarks::LandmarksArgs),
    /// Export maps, renders and the aged head (GLB) at an age: what the editor's Export
    /// window writes, as one all-or-nothing set of files.
    Export(export::ExportArgs),
    /// Render the head with the GPU renderer (wgpu; works on lavapipe): PNGs or --bench.
    Render(render::RenderArgs),
    /// Regenerate the default assets (masks, fine-wrinkle tile, pictures) into a folder.
    #[command(hide = true)]
    GenAssets(gen_assets::GenAssetsArgs),
}

pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Some(Command::MeshInfo(args)) => mesh_info::run(&args),
        Some(Command::Landmarks(args)) => landmarks::run(&args),
        Some(Command::GenAssets(args)) => gen_assets::run(&args),
        Some(Command::Hair(args)) => hair::run(&args),
        // No subcommand: the editor.
        None => run_editor(crate::editor::EditorOptions {
            project: cli.project,
            screenshot: cli.screenshot,
            frames: cli.frames,
            age_years: cli.age_years,
            compare_years: cli.compare_years,
            bench_ui: cli.bench_ui,
            autosave_seconds: cli.autosave_seconds.max(0.0),
            recover: cli.recover,
            edit: cli.edit,
            soak_seconds: cli.soak.map(|s| s.max(0.0)),
            ..Default::default()
        }),
        Some(Command::Bake(args)) => bake::run(&args),
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Export(args)) => export::run(&args),
    }
}

/// The editor, until its window closes; a failed soak run is an error.
fn run_editor(options: crate::editor::EditorOptions) -> anyhow::Result<()> {
    let soak = options.soak_seconds.is_some();
    crate::editor::run(options)?;
    if soak && crate::editor::soak_failed() {
        anyhow::bail!("the soak run failed (see above)");
    }
    Ok(())
}

/// The age flags of `bake`, `render` and `export`: one of them, or the project's age.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct AgeArgs {
    /// Age t ∈ [0, 1] (0 = `age.young_years`, 1 = `age.old_years`); default: the
    /// project's `age.t` (0.5 for a new project).
    #[arg(long, value_name = "T", conflicts_with = "age_years")]
    pub age: Option<f32>,
    /// Age in years (mapped to t through the project's `age` section).
    #[arg(long, value_name = "Y")]
    pub age_years: Option<f32>,
}

impl AgeArgs {
    /// The age t these flags ask for, checked; the project's `age.t` when neither is given.
    pub fn t(&self, project: &agesim_core::project::Project) -> anyhow::Result<f32> {
        Ok(match (self.age, self.age_years) {
            (Some(t), _) if (0.0..=1.0).contains(&t) => t,
            (Some(t), _) => {
                anyhow::bail!("--age {t}: expected an age t in 0..=1 (or use --age-years)")
            }
            (None, Some(y)) if (0.0..=150.0).contains(&y) => project.age.mapping().t(y),
            (None, Some(y)) => anyhow::bail!("--age-years {y}: expected years in 0..=150"),
            (None, None) => project.age.t,
        })
    }
}

/// `--set PATH=VALUE` (repeatable): one project field by its JSON path, on the commands
/// that make hair and renders (`render`, `hair`, `export`; `bake` has its own).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct SetArgs {
    /// Override one project field by its JSON path, e.g. `--set hair.loss=female`
    /// (repeatable; docs/project-file.md lists them).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
}

impl SetArgs {
    /// `project` with every `--set` applied, checked field by field.
    pub fn apply(
        &self,
        mut project: agesim_core::project::Project,
    ) -> anyhow::Result<agesim_core::project::Project> {
        for assignment in &self.set {
            let Some((path, value)) = assignment.split_once('=') else {
                anyhow::bail!(
                    "--set {assignment}: expected PATH=VALUE, e.g. --set hair.loss=female"
                );
            };
            project = project.set(path.trim(), value.trim())?;
        }
        Ok(project)
    }
}

/// The head flags of `hair` and `render`: the mesh, its units and its landmarks.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct MeshArgs {
    /// Head mesh (OBJ, glTF, GLB). Default: the built-in default head (metres).
    #[arg(long, value_name = "FILE")]
    pub mesh: Option<std::path::PathBuf>,
    /// Length of one mesh unit in metres (0.01 for a mesh in centimetres). Default: for
    /// --mesh, detected from --landmarks or from the head's size (`agesim mesh-info`
    /// says how); otherwise the project's.
    #[arg(long, value_name = "M")]
    pub metres_per_unit: Option<f32>,
    /// The head's landmark file (`{"landmarks": {"exocanthion_r": [x, y, z], …}}`, in the
    /// mesh file's units): its outer eye corners set the units.
    #[arg(long, value_name = "FILE")]
    pub landmarks: Option<std::path::PathBuf>,
    /// The head's base colour map (any image) over its own UVs: shown and paled with age
    /// instead of the skin colour.
    #[arg(long, value_name = "FILE")]
    pub colour_map: Option<std::path::PathBuf>,
    /// The head's tangent-space normal map (green up) over its own UVs: the wrinkles and
    /// skin relief are combined onto it.
    #[arg(long, value_name = "FILE")]
    pub normal_map: Option<std::path::PathBuf>,
    /// Turn --colour-map and --normal-map upside down (a head whose UVs use the other v
    /// convention).
    #[arg(long)]
    pub maps_flip_v: bool,
}

impl MeshArgs {
    /// Puts the flags into `p`: a --mesh with its own units (measured unless
    /// --metres-per-unit is given) and its --landmarks.
    pub fn apply_to(&self, p: &mut agesim_core::project::Project) -> anyhow::Result<()> {
        if self.landmarks.is_some() && self.mesh.is_none() {
            anyhow::bail!("--landmarks describes a --mesh: give the mesh too");
        }
        if let Some(path) = &self.mesh {
            p.mesh.path = Some(path.clone());
            p.mesh.metres_per_unit = None;
            p.mesh.landmarks = self.landmarks.clone().map(Into::into);
        }
        if let Some(m) = self.metres_per_unit {
            p.mesh.metres_per_unit = Some(m);
        }
        if let Some(c) = &self.colour_map {
            p.mesh.colour_map = Some(c.clone());
        }
        if let Some(n) = &self.normal_map {
            p.mesh.normal_map = Some(n.clone());
        }
        if self.maps_flip_v {
            p.mesh.maps_flip_v = true;
        }
        Ok(())
    }

    /// Says how the mesh's units were decided when they were measured, and how it was
    /// turned when its axes are not agesim's.
    pub fn report_units(scene: &agesim_core::scene::Scene) {
        let p = scene.project();
        if p.mesh.metres_per_unit.is_none() && p.mesh.path.is_some() {
            let units = scene.units();
            println!("metres per unit: {} ({})", units.metres_per_unit, units.how);
        }
        if p.mesh.path.is_some() {
            println!("layout: {}", scene.layout().how);
        }
        let axes = scene.axes();
        if axes != agesim_core::head::mesh::units::Axes::STANDARD {
            println!(
                "axes: up {}, forward {} (turned to +Y up, +Z forward)",
                axes.up.name(),
                axes.forward.name()
            );
        }
    }
}

/// The project a command starts from: `--project FILE`, else `--preset NAME`, else the
/// default project.
pub(crate) fn load_project_or_preset(
    project: Option<&std::path::Path>,
    preset: Option<&str>,
) -> anyhow::Result<agesim_core::project::Project> {
    use agesim_core::{defaults, project::Project};
    Ok(match (project, preset) {
        (Some(path), _) => Project::load(path)?,
        (None, Some(name)) => {
            let Some((file, text)) = defaults::preset(name) else {
                anyhow::bail!(
                    "unknown preset `{name}`: expected one of {}",
                    defaults::preset_names().join(", ")
                );
            };
            Project::from_json_str(text, file)?
        }
        (None, None) => Project::default(),
    })
}

/// A `WxH` size in pixels, each side in 1..=8192 (`1024x1024`, `1280X720`, `640×480`).
pub(crate) fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X', '×'])
        .ok_or_else(|| format!("expected WxH, e.g. 1024x1024, got `{s}`"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .ok()
            .filter(|&n| (1..=8192).contains(&n))
            .ok_or_else(|| format!("`{v}` is not a size in 1..=8192"))
    };
    Ok((parse(w)?, parse(h)?))
}
