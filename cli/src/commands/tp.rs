//! `rocking tp`: the replacement sine duration `t_p` of records (thesis 5.3.5, Eq. 25, Fig. 52)
//! through `rocking::spectra::replacement_sine`: no simulation, a few milliseconds a record.

use std::path::PathBuf;

use clap::Args;
use rocking::spectra::replacement_sine;
use rocking::spectra::report::TpRow;

use crate::output::print_json;

/// Options of `rocking tp`.
#[derive(Args, Debug)]
pub struct TpArgs {
    #[command(flatten)]
    pub record_format: super::sweep::RecordFormatArgs,
    /// The records (.AT2 in g, or plain text in m/s²).
    #[arg(required = true)]
    pub records: Vec<PathBuf>,
    /// A JSON list instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// Runs the command.
pub fn run(a: &TpArgs) -> Result<(), String> {
    let mut rows = Vec::new();
    for f in &a.records {
        let record = super::sweep::read(f, &a.record_format)?;
        let s = replacement_sine(&record)
            .ok_or_else(|| format!("{}: the record is zero everywhere", f.display()))?;
        rows.push(TpRow::of(&record.name, Some(f.display().to_string()), &s));
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
