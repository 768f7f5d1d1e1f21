//! `rocking tp`: the replacement sine duration `t_p` of records (thesis 5.3.5, Eq. 25, Fig. 52)
//! through `rocking::spectra::replacement_sine`: no simulation, a few milliseconds a record.

use std::path::PathBuf;

use clap::Args;
use rocking::spectra::{replacement_sine, SINE_FULLNESS};
use serde::Serialize;

use crate::output::print_json;

/// Options of `rocking tp`.
#[derive(Args, Debug)]
pub struct TpArgs {
    /// The records (.AT2 in g, or plain text in m/s²).
    #[arg(required = true)]
    pub records: Vec<PathBuf>,
    /// A JSON list instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// One record's row of `tp --json`.
#[derive(Serialize)]
struct Row {
    record: String,
    file: String,
    /// Peak absolute ground acceleration [m/s²].
    a_max: f64,
    /// Largest single-lobe impulse ∫|a| dt between two zero crossings [m/s].
    i_max: f64,
    /// Start and end of that lobe [s].
    lobe_start: f64,
    lobe_end: f64,
    /// The fullness used, 2/π.
    fullness: f64,
    /// t_p = I_max / (F a_max) [s].
    t_p: f64,
}

/// Runs the command.
pub fn run(a: &TpArgs) -> Result<(), String> {
    let mut rows = Vec::new();
    for f in &a.records {
        let record = super::sweep::read(f)?;
        let s = replacement_sine(&record)
            .ok_or_else(|| format!("{}: the record is zero everywhere", f.display()))?;
        rows.push(Row {
            record: record.name.clone(),
            file: f.display().to_string(),
            a_max: s.a_max,
            i_max: s.i_max,
            lobe_start: s.lobe_start,
            lobe_end: s.lobe_end,
            fullness: SINE_FULLNESS,
            t_p: s.t_p,
        });
    }
    if a.json {
        print_json(&rows)?;
    } else {
        println!(
            "record                          a_max [m/s2]  I_max [m/s]  lobe [s]          t_p [s]"
        );
        for r in &rows {
            println!(
                "{:<30} {:>12.4} {:>12.4}  {:>7.3}-{:<7.3}  {:>8.4}",
                r.record, r.a_max, r.i_max, r.lobe_start, r.lobe_end, r.t_p
            );
        }
    }
    Ok(())
}
