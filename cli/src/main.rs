//! `rocking`: the command-line program over the library — time histories of columns under
//! pulses and records, the thesis's reference values, overturning spectra and design.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod output;
mod plot;
mod scene;
mod simulate;
mod thesis;

#[derive(Parser)]
#[command(
    name = "rocking",
    version,
    about = "Rocking columns of rigid blocks: time histories, spectra, design"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Reproduce the thesis's reference values through the library (SPEC §8).
    Thesis,
    /// Time history of a scene (JSON): writes history.csv, events.jsonl and summary.json.
    Simulate {
        /// The scene file.
        scene: PathBuf,
        /// Output directory (created if needed).
        #[arg(long)]
        out: PathBuf,
        /// Draw block rotations against time with the events marked (.svg or .png).
        #[arg(long)]
        plot: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Thesis => return thesis::run(),
        Command::Simulate { scene, out, plot } => simulate::run(&scene, &out, plot.as_deref()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rocking: {e}");
            ExitCode::FAILURE
        }
    }
}
