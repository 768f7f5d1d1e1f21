//! `rocking`: the command-line program over the library — time histories of columns under
//! pulses and records, the thesis's reference values, overturning spectra and design.
//!
//! Every command's arguments are a clap derive (`--help`, checks, errors as clap prints them);
//! the commands live in `commands/` and `bench/`, one module each.

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};

mod bench;
mod commands;
mod output;
mod plot;
mod progress;

use commands::{arch, design, oas, oc, simulate, suite, t1, thesis, tp};

/// The impact and opening models allocate a few small vectors per event, and sweeps of
/// event-heavy records spent a quarter of their time in glibc's allocator; with mimalloc the OAS
/// of Imperial Valley H-DLT262 takes 10 % less time, the bundled record's 15 % less (same
/// results).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[derive(Parser, Debug)]
#[command(
    name = "rocking",
    version,
    about = "Rocking columns of rigid blocks: time histories, spectra, design"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Reproduce the thesis's reference values through the library (SPEC §8).
    Thesis,
    /// Time history of a scene (JSON): writes history.csv, events.jsonl and summary.json.
    Simulate(simulate::SimulateArgs),
    /// Overturning curve of a pulse (thesis Fig. 8, 33, 40): safe/unsafe on a grid of p t_p
    /// (log) x a_p / a_p,min (linear, from 1); CSV, or JSON with --json.
    Oc(oc::OcArgs),
    /// Overturning acceleration spectrum of a record (Fig. 36, 37, 43); JSON, or CSV with --csv.
    /// One OAS at the step rule (its t_1 is `rocking t1 --single-step`'s), or converged in
    /// the step with --converge-step; --band adds t_1's band.
    #[command(
        override_usage = "rocking oas [OPTIONS] RECORD\n       rocking oas --merge SHARD.json... [--csv] [--svg PREFIX]"
    )]
    Oas(oas::OasArgs),
    /// Replacement impulse duration t_1, t_1', beta, f_min of records (Eq. 20, 28), converged
    /// in the time step (--single-step: one OAS at the step rule).
    #[command(
        override_usage = "rocking t1 [OPTIONS] RECORD...\n       rocking t1 --merge SHARD.json... [--json]"
    )]
    T1(t1::T1Args),
    /// Replacement sine duration t_p of records (Eq. 25, Fig. 52): a_max, the largest
    /// single-lobe impulse I_max, t_p = I_max / (F a_max), F = 2/pi. No simulation.
    Tp(tp::TpArgs),
    /// Site design curves of a record suite (5.3.1, Fig. 44, 47-49): every record's OAS, the
    /// characteristic OAS and design t_1 at each fractile, the convex hulls of the transformed
    /// OAS, and Eq. 21, 29, 30 checked against every record. Each record's OAS at the step
    /// rule (its t_1 is `rocking t1 --single-step`'s).
    #[command(
        override_usage = "rocking suite [OPTIONS] RECORD...\n       rocking suite --merge FILE.json... [--json] [--svg PREFIX] [--csv PREFIX]"
    )]
    Suite(suite::SuiteArgs),
    /// Spectra of a voussoir arch (loop driver): OAS of a record, OC of a pulse; level
    /// a_p / (λ g), size the radius at fixed t/R, embrace angle and voussoirs.
    #[command(subcommand)]
    Arch(arch::Arch),
    /// Pier width (Eq. 23, 24) and the Eq. 31 check.
    #[command(subcommand)]
    Design(design::Design),
    /// Benchmarks: the driver's accuracy against run time, the spectra's wall time.
    #[command(subcommand)]
    Bench(bench::Bench),
}

/// `cmd` and its subcommands with every option that takes a value accepting a negative number
/// as that value (`--pga -1`, `--size -2`), so that its own check refuses it naming the option
/// and the rule ("must be finite and > 0, got -1"). clap's default read `-1` as an unknown
/// flag: "unexpected argument '-1' found", which names neither.
fn negative_values_reach_their_checks(cmd: clap::Command) -> clap::Command {
    cmd.mut_args(|arg| {
        if arg.get_action().takes_values() {
            arg.allow_negative_numbers(true)
        } else {
            arg
        }
    })
    .mut_subcommands(negative_values_reach_their_checks)
}

/// The command line, parsed as [`Cli::parse`] with [`negative_values_reach_their_checks`].
fn parse() -> Cli {
    let matches = negative_values_reach_their_checks(Cli::command()).get_matches();
    Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
}

/// A reader that closes the pipe early (`rocking oas R --csv | head -3`) ends the program as a
/// broken pipe ends any Unix filter: quietly, with the status of SIGPIPE (141). `println!`
/// panicked instead, "failed printing to stdout: Broken pipe", with a backtrace.
fn quiet_on_broken_pipe() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(141);
        }
        default(info);
    }));
}

fn main() -> ExitCode {
    quiet_on_broken_pipe();
    let cli = parse();
    let result = match &cli.command {
        Command::Thesis => return thesis::run(),
        Command::Simulate(a) => simulate::run(a),
        Command::Oc(a) => oc::run(a),
        Command::Oas(a) => oas::run(a),
        Command::T1(a) => t1::run(a),
        Command::Tp(a) => tp::run(a),
        Command::Suite(a) => suite::run(a),
        Command::Arch(a) => a.run(),
        Command::Design(d) => d.run(),
        Command::Bench(b) => b.run(),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rocking: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_arguments_are_consistent() {
        Cli::command().debug_assert();
        negative_values_reach_their_checks(Cli::command()).debug_assert();
    }
}
