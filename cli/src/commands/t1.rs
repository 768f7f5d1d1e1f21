//! `rocking t1`: the replacement impulse duration t₁ (Eq. 20), the fit t₁', β (Eq. 28) and f_min
//! of records, each from its OAS; `--merge` joins the JSON of `--shard` runs.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rocking::spectra::{self, SizeSearch};
use serde::{Deserialize, Serialize};

use super::oas::Summary;
use super::sweep::{OasGridArgs, Shard, SimulationArgs};
use crate::output::{print_json, read_json};
use crate::progress;

/// Options of `rocking t1`.
#[derive(Args, Debug)]
pub struct T1Args {
    /// The records (.AT2 in g, or plain text in m/s²).
    #[arg(required_unless_present = "merge")]
    pub records: Vec<PathBuf>,
    /// Join the JSON lists of `--shard` runs (sorted by file) instead of computing.
    #[arg(long, num_args = 1.., value_name = "SHARD.json", conflicts_with = "records")]
    pub merge: Vec<PathBuf>,
    #[command(flatten)]
    pub grid: OasGridArgs,
    #[command(flatten)]
    pub simulation: SimulationArgs,
    /// Only the records k with k % n == i (merge the shards with --merge).
    #[arg(long, default_value_t = Shard::WHOLE, value_name = "i/n")]
    pub shard: Shard,
    /// A JSON list instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// One record's row of `t1 --json`: the summary of its OAS and the settings.
#[derive(Serialize, Deserialize)]
struct Row {
    #[serde(flatten)]
    summary: Summary,
    file: String,
    slenderness: f64,
    blocks: usize,
    dt_factor: f64,
    search: SizeSearch,
}

/// Runs the command.
pub fn run(a: &T1Args) -> Result<(), String> {
    let rows: Vec<Row> = if a.merge.is_empty() {
        let o = a.grid.options(&a.simulation);
        let files = a.shard.keep(&a.records);
        let bar = progress::bar((files.len() * o.levels.len()) as u64, "t1");
        let mut rows = Vec::new();
        for f in files {
            bar.set_message(f.display().to_string());
            let record = super::sweep::read(&f)?;
            let t0 = Instant::now();
            let tick = || bar.inc(1);
            let r = spectra::oas(&record, &o, Some(&tick)).map_err(|e| e.to_string())?;
            rows.push(Row {
                summary: Summary::of(&r, t0.elapsed().as_secs_f64()),
                file: f.display().to_string(),
                slenderness: o.slenderness,
                blocks: o.n_blocks,
                dt_factor: a.simulation.dt_factor,
                search: o.search,
            });
        }
        bar.finish_and_clear();
        rows
    } else {
        let mut rows = Vec::new();
        for p in &a.merge {
            rows.extend(read_json::<Vec<Row>>(p)?);
        }
        rows.sort_by(|x, y| x.file.cmp(&y.file));
        rows
    };
    if a.json {
        print_json(&rows)?;
    } else {
        println!("record                          t1 [s]   t1' [s]  beta     f_min [1/s]");
        for r in &rows {
            let s = &r.summary;
            let f = |v: Option<f64>| {
                v.filter(|x| x.is_finite())
                    .map_or("-".to_string(), |x| format!("{x:.3}"))
            };
            println!(
                "{:<30} {:>8} {:>8} {:>8} {:>8}",
                s.record,
                f(s.t1),
                f(s.t1_prime),
                f(s.beta),
                f(s.f_min)
            );
        }
    }
    Ok(())
}
