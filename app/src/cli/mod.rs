//! The command line: one binary, one subcommand per task.

mod bake;
mod font;
mod gen_assets;
mod hair;
mod mesh_info;
mod render;

use clap::{CommandFactory as _, Parser, Subcommand};

/// agesim: age a human head — wrinkles, skin micro-relief, hair recession and graying.
#[derive(Debug, Parser)]
#[command(name = "agesim", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Bake height and normal maps: large wrinkles and skin micro-relief, from a project.
    Bake(bake::BakeArgs),
    /// Hair aging (SPEC §6): transition texture, hair instances and their counts per age.
    Hair(hair::HairArgs),
    /// Print what a head mesh (OBJ, glTF, GLB) contains: counts, size, attributes, repairs.
    MeshInfo(mesh_info::MeshInfoArgs),
    /// Render the head with the GPU renderer (wgpu; works on lavapipe): PNGs or --bench.
    Render(render::RenderArgs),
    /// Regenerate the default assets (masks, fine-wrinkle tile, pictures) into a folder.
    #[command(hide = true)]
    GenAssets(gen_assets::GenAssetsArgs),
}

pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Some(Command::MeshInfo(args)) => mesh_info::run(&args),
        Some(Command::GenAssets(args)) => gen_assets::run(&args),
        Some(Command::Hair(args)) => hair::run(&args),
        // Until the editor exists, no subcommand prints the help.
        None => {
            Cli::command().print_help()?;
            Ok(())
        }
        Some(Command::Bake(args)) => bake::run(&args),
        Some(Command::Render(args)) => render::run(&args),
    }
}
