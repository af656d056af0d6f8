//! The `agesim` binary: the editor (no subcommand) and the command line.

use clap::Parser as _;

fn main() -> std::process::ExitCode {
    // Ctrl-C or a kill during an export removes its temporaries; the old files stay whole.
    agesim_core::output::export::remove_temporaries_on_signals();
    let args = agesim::cli::Cli::parse();
    match agesim::cli::run(args) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
