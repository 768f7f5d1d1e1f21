//! `rocking suite`: site design curves from a record suite (thesis 5.3.1–5.3.2, Fig. 44, 47–49)
//! through `rocking::spectra::suite` — the OAS of every record, the characteristic OAS at each
//! fractile with its design t₁, the normalised convex hulls of the transformed OAS, and the check
//! of Eq. 21, 29, 30 against every record; `--merge` joins `--shard` runs (or `rocking oas --json`
//! reports); `--svg`/`--png` draw the charts and `--csv` writes each curve.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rocking::spectra::report::{LevelReport, OasReport, SuiteReport};
use rocking::spectra::suite::Violations;
use rocking::spectra::{self, Oas};
use serde::Deserialize;

use super::suite_charts;
use super::sweep::{OasGridArgs, Shard, SimulationArgs};
use crate::output::{check_prefix_writable, print_json, read_json, with_suffix, write_atomic};
use crate::progress;

/// Options of `rocking suite`.
#[derive(Args, Debug)]
pub struct SuiteArgs {
    #[command(flatten)]
    pub record_format: super::sweep::RecordFormatArgs,
    /// The records of the suite (.AT2 in g, or plain text in m/s²).
    #[arg(required_unless_present = "merge")]
    pub records: Vec<PathBuf>,
    /// Join the JSON of `--shard` runs (or of `rocking oas --json`, one record each) instead of
    /// computing.
    #[arg(long, num_args = 1.., value_name = "FILE.json", conflicts_with = "records")]
    pub merge: Vec<PathBuf>,
    /// The suite's name in the report and the charts' titles.
    #[arg(long, default_value = "suite")]
    pub name: String,
    /// Fractiles of the characteristic OAS, comma separated (each in (0, 1]).
    #[arg(long, value_delimiter = ',', default_value = "0.5,0.84", value_parser = fractile)]
    pub fractile: Vec<f64>,
    #[command(flatten)]
    pub grid: OasGridArgs,
    #[command(flatten)]
    pub simulation: SimulationArgs,
    /// Only the records k with k % n == i (merge the shards with --merge).
    #[arg(long, default_value_t = Shard::WHOLE, value_name = "i/n")]
    pub shard: Shard,
    /// The JSON report (every record's OAS included) instead of a text summary.
    #[arg(long)]
    pub json: bool,
    /// Write the charts PREFIX-oas.svg (Fig. 44, 47a), PREFIX-transformed.svg (Fig. 47b),
    /// PREFIX-hulls.svg (Fig. 49) and PREFIX-size.svg (the design curves against the size R).
    #[arg(long, value_name = "PREFIX")]
    pub svg: Option<PathBuf>,
    /// With --svg: also write the charts as PNG.
    #[arg(long, requires = "svg")]
    pub png: bool,
    /// Write each curve as CSV: PREFIX-records.csv (every record's OAS), PREFIX-characteristic.csv,
    /// PREFIX-hulls.csv, PREFIX-violations.csv.
    #[arg(long, value_name = "PREFIX")]
    pub csv: Option<PathBuf>,
}

/// A fractile in (0, 1].
pub(crate) fn fractile(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|_| format!("not a number: {s}"))?;
    if v > 0.0 && v <= 1.0 {
        Ok(v)
    } else {
        Err(format!("must be in (0, 1], got {s}"))
    }
}

/// What `--merge` reads: a suite report, or one record's OAS report.
#[derive(Deserialize)]
#[serde(untagged)]
enum Part {
    Suite(Box<SuiteReport>),
    Oas(Box<OasReport>),
}

/// The spectra of the files of `--merge`, each with its wall time; a record given twice is an
/// error.
fn merged(files: &[PathBuf]) -> Result<Vec<(Oas, f64)>, String> {
    let mut out: Vec<(Oas, f64)> = Vec::new();
    for f in files {
        let part = match read_json::<Part>(f) {
            Ok(p) => p,
            Err(_) => {
                return Err(format!(
                    "{}: neither a `rocking suite --json` nor a `rocking oas --json` report",
                    f.display()
                ))
            }
        };
        let spectra = match part {
            Part::Suite(s) => s.spectra(),
            Part::Oas(r) => {
                let seconds = r.summary.seconds;
                OasReport::merge(vec![*r])
                    .map(|o| vec![(o, seconds)])
                    .unwrap_or_default()
            }
        };
        for (o, s) in spectra {
            if out.iter().any(|(p, _)| p.record == o.record) {
                return Err(format!(
                    "{}: record `{}` is already in the suite",
                    f.display(),
                    o.record
                ));
            }
            out.push((o, s));
        }
    }
    Ok(out)
}

/// Runs the command.
pub fn run(a: &SuiteArgs) -> Result<(), String> {
    // Before the spectra: the report refuses them after.
    spectra::suite::distinct_fractiles(&a.fractile).map_err(|e| format!("--{e}"))?;
    if let Some(prefix) = &a.csv {
        check_prefix_writable("--csv", prefix, "-records.csv")?;
    }
    if let Some(prefix) = &a.svg {
        check_prefix_writable("--svg", prefix, "-oas.svg")?;
    }
    let spectra = if a.merge.is_empty() {
        let o = a.grid.options(&a.simulation)?;
        let files = a.shard.keep(&a.records);
        let records = super::sweep::read_all(&files, &a.record_format)?;
        for (k, (f, record)) in records.iter().enumerate() {
            if records[..k].iter().any(|(_, r)| r.name == record.name) {
                return Err(format!(
                    "{}: record `{}` is already in the suite",
                    f.display(),
                    record.name
                ));
            }
        }
        let bar = progress::bar((files.len() * o.levels.len()) as u64, "suite");
        let mut out = Vec::new();
        for (f, record) in records {
            bar.set_message(f.display().to_string());
            let t0 = Instant::now();
            let tick = || bar.inc(1);
            let r = spectra::oas(&record, &o, Some(&tick))
                .map_err(|e| format!("{}: {e}", f.display()))?;
            out.push((r, t0.elapsed().as_secs_f64()));
        }
        bar.finish_and_clear();
        out
    } else {
        merged(&a.merge)?
    };
    let report = SuiteReport::of(&a.name, &spectra, &a.fractile).map_err(|e| e.to_string())?;
    if a.json {
        print_json(&report)?;
    } else {
        print!("{}", summary(&report));
    }
    if let Some(prefix) = &a.csv {
        for (name, text) in csv(&report) {
            write_atomic(
                &with_suffix(prefix, &format!("-{name}.csv")),
                text.as_bytes(),
            )?;
        }
    }
    if let Some(prefix) = &a.svg {
        for (name, chart) in suite_charts::charts(&report) {
            chart.write_named(prefix, name, a.png)?;
        }
    }
    Ok(())
}

/// `x` with three decimals, `-` when absent or not finite.
fn num(x: Option<f64>) -> String {
    x.filter(|v| v.is_finite())
        .map_or("-".into(), |v| format!("{v:.3}"))
}

fn range(v: &Violations) -> String {
    v.level_below
        .map_or("all levels".into(), |b| format!("a_p/a_p,min < {b}"))
}

/// The text summary: the design t₁ per fractile and the violations.
fn summary(r: &SuiteReport) -> String {
    let mut s = String::new();
    let t1s: Vec<f64> = r.records.iter().filter_map(|o| o.summary.t1).collect();
    // Records that overturn no size at any level have no t1: said, not left out of the range
    // unmentioned (the range of the others read as the suite's).
    let none = r.records.len() - t1s.len();
    let without = match none {
        0 => String::new(),
        1 => " (1 record overturns no size on the grid: no t1)".into(),
        n => format!(" ({n} records overturn no size on the grid: no t1)"),
    };
    s += &format!(
        "suite {}: {} records, t1 of the records {}…{} s{without}, {:.1} s of OAS\n",
        r.name,
        r.records.len(),
        num(t1s.iter().copied().reduce(f64::min)),
        num(t1s.iter().copied().reduce(f64::max)),
        r.seconds
    );
    s += "fractile  design t1 [s]  f_min [1/s]  t1' [s]  beta [s]  fractile of record t1 [s]\n";
    for c in &r.characteristic {
        s += &format!(
            "{:<9} {:>13} {:>12} {:>8} {:>9} {:>26}\n",
            c.fractile,
            num(c.design_t1),
            num(c.f_min),
            num(c.oas.summary.t1_prime),
            num(c.oas.summary.beta),
            num(c.record_t1_fractile)
        );
    }
    let table = |title: &str, vs: &[Violations]| {
        let mut s = format!(
            "{title}: boundary points (records) predicted safe that overturn\n\
             {:<22} {:>8} {:>12} {:>12} {:>12} {:>12}\n",
            "range", "points", "Eq. 21", "Eq. 21 i≈1", "Eq. 29", "Eq. 30"
        );
        for v in vs {
            let t = |t: spectra::suite::Tally| format!("{} ({})", t.points, t.records);
            s += &format!(
                "{:<22} {:>8} {:>12} {:>12} {:>12} {:>12}\n",
                range(v),
                v.checked,
                t(v.eq21),
                t(v.eq21_approx),
                t(v.eq29),
                t(v.eq30)
            );
        }
        s
    };
    for c in &r.characteristic {
        s += &table(
            &format!(
                "design parameters of fractile {} (t1 = {} s)",
                c.fractile,
                num(c.design_t1)
            ),
            &c.violations,
        );
    }
    s += &table("each record's own t1, t1', beta", &r.own_parameters);
    s
}

/// The CSV files: (name, text).
fn csv(r: &SuiteReport) -> Vec<(&'static str, String)> {
    let opt = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
    // One row per level of an OAS, after the key of its curve (record name or fractile).
    let level_rows = |key: &str, levels: &[LevelReport]| -> String {
        levels
            .iter()
            .map(|l| {
                format!(
                    "{key},{},{},{},{}\n",
                    l.level.level,
                    opt(l.size),
                    opt(l.p),
                    opt(l.f)
                )
            })
            .collect()
    };
    let mut records = String::from("record,level,size,p,f\n");
    for o in &r.records {
        records += &level_rows(&o.record, &o.levels);
    }
    let mut characteristic = String::from("fractile,level,size,p,f\n");
    for c in &r.characteristic {
        characteristic += &level_rows(&c.fractile.to_string(), &c.oas.levels);
    }
    let mut hulls = String::from("record,level,f,f_normalised\n");
    for h in &r.hulls {
        for v in &h.vertices {
            hulls += &format!("{},{},{},{}\n", h.record, v.level, v.f, v.f_normalised);
        }
    }
    let mut violations = String::from(
        "parameters,level_below,checked,eq21_points,eq21_records,eq21_approx_points,\
         eq21_approx_records,eq29_points,eq29_records,eq30_points,eq30_records\n",
    );
    let rows = r
        .characteristic
        .iter()
        .flat_map(|c| {
            c.violations
                .iter()
                .map(move |v| (format!("design {}", c.fractile), v))
        })
        .chain(r.own_parameters.iter().map(|v| ("own".to_string(), v)));
    for (who, v) in rows {
        violations += &format!(
            "{who},{},{},{},{},{},{},{},{},{},{}\n",
            opt(v.level_below),
            v.checked,
            v.eq21.points,
            v.eq21.records,
            v.eq21_approx.points,
            v.eq21_approx.records,
            v.eq29.points,
            v.eq29.records,
            v.eq30.points,
            v.eq30.records
        );
    }
    vec![
        ("records", records),
        ("characteristic", characteristic),
        ("hulls", hulls),
        ("violations", violations),
    ]
}
