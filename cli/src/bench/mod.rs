//! `rocking bench`: the driver's accuracy against run time, the spectra's wall time, the drum
//! suite.

pub mod accuracy;
pub mod drums;
pub mod spectra;

use clap::Subcommand;

/// The benchmarks.
#[derive(Subcommand, Debug)]
pub enum Bench {
    /// Error against time step and run time for each integrator and event locator
    /// (writes a Markdown report and log-log charts).
    Accuracy(accuracy::AccuracyArgs),
    /// The drum suite (docs/multidrum.md): columns of 3-20 drums that rock, slide and fly under
    /// the FEMA P695 far-field records; how every run ends, energy residuals, wall time.
    Drums(drums::DrumsBenchArgs),
    /// Wall time of the OAS of records with the thesis's grid (target: 5 s per record).
    Spectra(spectra::SpectraBenchArgs),
}

impl Bench {
    /// Runs the benchmark.
    pub fn run(&self) -> Result<(), String> {
        match self {
            Bench::Accuracy(a) => accuracy::run(a),
            Bench::Drums(a) => drums::run(a),
            Bench::Spectra(a) => spectra::run(a),
        }
    }
}
