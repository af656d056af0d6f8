//! The command line: one binary, one subcommand per task.

mod bake;

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
    /// Bake height and normal maps from wrinkle description files.
    Bake(bake::BakeArgs),
}

pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        // Until the editor exists, no subcommand prints the help.
        None => {
            Cli::command().print_help()?;
            Ok(())
        }
        Some(Command::Bake(args)) => bake::run(&args),
    }
}
