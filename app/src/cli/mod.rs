//! The command line: one binary, one subcommand per task.

pub mod bake;
pub mod export;
pub mod gen_assets;
pub mod hair;
mod head;
pub mod landmarks;
pub mod mesh_info;
pub mod render;

use clap::{Parser, Subcommand};

pub use head::{AgeArgs, HeadArgs, MeshArgs, SetArgs};

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
