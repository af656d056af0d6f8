//! The command line: one binary, one subcommand per task.

mod hair;

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
    /// Hair aging (SPEC §6): transition texture, hair instances and their counts per age.
    Hair(hair::HairArgs),
}

pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        // Until the editor exists, no subcommand prints the help.
        None => {
            Cli::command().print_help()?;
            Ok(())
        }
        Some(Command::Hair(args)) => hair::run(&args),
    }
}
