//! `rocking`: the command-line program over the library — time histories of columns under
//! pulses and records, the thesis's reference values, overturning spectra and design.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod bench_cmd;
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
    /// Benchmarks of the driver.
    Bench {
        #[command(subcommand)]
        bench: Bench,
    },
}

#[derive(Subcommand)]
enum Bench {
    /// Error against time step and run time for each integrator and event locator
    /// (writes a Markdown report and log-log charts).
    Accuracy {
        /// The Markdown report.
        #[arg(long, default_value = "docs/accuracy.md")]
        out: PathBuf,
        /// Error against run time (.svg or .png); scenes (b), (c) go to FILE_b, FILE_c.
        #[arg(long)]
        plot: Option<PathBuf>,
        /// A reduced grid (a few seconds).
        #[arg(long)]
        quick: bool,
        /// Results of the scipy peer (bench/peer/results.json) to compare with.
        #[arg(long)]
        peer: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Thesis => return thesis::run(),
        Command::Simulate { scene, out, plot } => simulate::run(&scene, &out, plot.as_deref()),
        Command::Bench {
            bench:
                Bench::Accuracy {
                    out,
                    plot,
                    quick,
                    peer,
                },
        } => bench_cmd::run(&bench_cmd::AccuracyArgs {
            out,
            plot,
            quick,
            peer,
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rocking: {e}");
            ExitCode::FAILURE
        }
    }
}
