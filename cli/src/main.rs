//! `rocking`: the command-line program over the library — time histories of columns under
//! pulses and records, the thesis's reference values, overturning spectra and design.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod args;
/// The impact and opening models allocate a few small vectors per event, and sweeps of
/// event-heavy records spent a quarter of their time in glibc's allocator; with mimalloc the OAS
/// of Imperial Valley H-DLT262 takes 10 % less time, the bundled record's 15 % less (same
/// results).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod bench_cmd;
mod design_cmd;
mod output;
mod plot;
mod scene;
mod simulate;
mod spectra_bench;
mod spectra_cmd;
mod spectra_svg;
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
    /// Overturning curve of a pulse (thesis Fig. 8, 33, 40): `rocking oc --help`.
    #[command(disable_help_flag = true)]
    Oc {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Overturning acceleration spectrum of a record (Fig. 36, 37, 43): `rocking oas --help`.
    #[command(disable_help_flag = true)]
    Oas {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Replacement impulse duration t_1, t_1', beta of records (Eq. 20, 28): `rocking t1 --help`.
    #[command(disable_help_flag = true)]
    T1 {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Pier width (Eq. 23, 24) and the Eq. 31 check: `rocking design --help`.
    #[command(disable_help_flag = true)]
    Design {
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Benchmarks: the driver's accuracy against run time, the spectra's wall time.
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
    /// Wall time of the OAS of records with the thesis's grid (target: 5 s per record).
    Spectra {
        /// Records (.AT2 or plain text); none: the bundled synthetic record.
        records: Vec<PathBuf>,
        /// Run each record again with every simulation run to its end (no energy-bound stop):
        /// the speed ratio, and a check that both spectra are identical.
        #[arg(long)]
        compare: bool,
        /// Also write the Markdown report to this file.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Threads (default: every core).
        #[arg(long)]
        threads: Option<usize>,
    },
}

fn wants_help(args: &[String]) -> bool {
    args.iter().any(|a| a == "--help" || a == "-h")
}

fn usage(text: &str) -> ExitCode {
    println!("{text}");
    ExitCode::SUCCESS
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Thesis => return thesis::run(),
        Command::Oc { args } if wants_help(&args) => return usage(spectra_cmd::OC_USAGE),
        Command::Oas { args } if wants_help(&args) => return usage(spectra_cmd::OAS_USAGE),
        Command::T1 { args } if wants_help(&args) => return usage(spectra_cmd::T1_USAGE),
        Command::Design { args } if wants_help(&args) => return usage(design_cmd::DESIGN_USAGE),
        Command::Oc { args } => return spectra_cmd::run_oc(&args),
        Command::Oas { args } => return spectra_cmd::run_oas(&args),
        Command::T1 { args } => return spectra_cmd::run_t1(&args),
        Command::Design { args } => return design_cmd::run_design(&args),
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
        Command::Bench {
            bench:
                Bench::Spectra {
                    records,
                    compare,
                    out,
                    threads,
                },
        } => spectra_bench::run(&spectra_bench::SpectraBenchArgs {
            records,
            compare,
            out,
            threads,
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
