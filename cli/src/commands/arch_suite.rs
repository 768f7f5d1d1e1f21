//! `rocking arch suite` / `rocking arch rules`: an arch design rule from arch OAS already
//! computed (`rocking arch oas` JSON), through `rocking::spectra::{arch_suite, candidate_rules}`
//! — the suite procedure of thesis 5.3.1 on arches (characteristic arch OAS, its design t₁, the
//! check against every record) and candidate rules fitted on one set and scored on others.

use std::collections::HashMap;
use std::path::PathBuf;

use clap::Args;
use rocking::spectra::arch_report::{ArchOasReport, ArchRulesReport, ArchSuiteReport};
use rocking::spectra::{characteristic_arch_oas, same_arch, ArchOas, ArchRecord, RuleScore};
use serde::Deserialize;

use crate::output::print_json;
use crate::plot::{Chart, Series, Style, COLORS};

/// Options of `rocking arch suite`.
#[derive(Args, Debug)]
pub struct ArchSuiteArgs {
    /// The arch OAS of the records (`rocking arch oas` JSON, one record each, one arch and grid).
    #[arg(required = true, value_name = "OAS.json")]
    pub spectra: Vec<PathBuf>,
    /// The suite's name in the report and the charts' titles.
    #[arg(long, default_value = "arch suite")]
    pub name: String,
    /// Fractiles of the characteristic arch OAS, comma separated (each in (0, 1]).
    #[arg(long, value_delimiter = ',', default_value = "0.5,0.84",
          value_parser = super::suite::fractile)]
    pub fractile: Vec<f64>,
    /// The JSON report instead of a text summary.
    #[arg(long)]
    pub json: bool,
    /// Write PREFIX-oas.svg (level against p, the records behind the characteristic arch OAS and
    /// the design rule) and PREFIX-transformed.svg (against f).
    #[arg(long, value_name = "PREFIX")]
    pub svg: Option<PathBuf>,
    /// With --svg: also write the charts as PNG.
    #[arg(long, requires = "svg")]
    pub png: bool,
}

/// Options of `rocking arch rules`.
#[derive(Args, Debug)]
pub struct ArchRulesArgs {
    /// The arch OAS the rules are fitted on (`rocking arch oas` JSON).
    #[arg(long, required = true, num_args = 1.., value_name = "OAS.json")]
    pub fit: Vec<PathBuf>,
    /// The arch OAS the rules are tested on, out of sample: one set per folder, in the order of
    /// their first file.
    #[arg(long, num_args = 1.., value_name = "OAS.json")]
    pub test: Vec<PathBuf>,
    /// Names of the sets, comma separated: the fit set, then each test set (default: their
    /// folders).
    #[arg(long, value_delimiter = ',')]
    pub names: Vec<String>,
    /// The records' replacement sine durations t_p: a JSON list of rows with `record` and `t_p`
    /// (`rocking t1 --json` or `rocking tp --json`); repeat for several files.
    #[arg(long, value_name = "FILE.json")]
    pub tp: Vec<PathBuf>,
    /// The JSON report instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Draw every record's arch t1 against its single-block t1, with the rules of that form
    /// (.svg or .png).
    #[arg(long, value_name = "FILE", value_parser = crate::plot::plot_path)]
    pub svg: Option<PathBuf>,
}

/// A row of a `t_p` file.
#[derive(Deserialize)]
struct TpRow {
    record: String,
    #[serde(default)]
    t_p: Option<f64>,
}

/// The arch OAS of `files` with their single-block t₁ (the one each was checked against) and
/// `t_p` from `tp`; a record given twice is an error.
fn read_set(files: &[PathBuf], tp: &HashMap<String, f64>) -> Result<Vec<ArchRecord>, String> {
    let mut out: Vec<ArchRecord> = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(f).map_err(|e| format!("{}: {e}", f.display()))?;
        let report: ArchOasReport = serde_json::from_str(&text)
            .map_err(|e| format!("{}: not a `rocking arch oas` JSON report: {e}", f.display()))?;
        let oas = report
            .to_oas()
            .map_err(|e| format!("{}: {e}", f.display()))?;
        if let Some(earlier) = out.iter().find(|r| r.oas.record == oas.record) {
            // The same record for another arch or grid is a mix of sets, not a file given twice.
            let pair = [earlier.oas.clone(), oas.clone()];
            let other = characteristic_arch_oas(&pair, 1.0, "check").is_err();
            return Err(format!(
                "{}: record `{}` is already in the set{}",
                f.display(),
                oas.record,
                if other {
                    ", for another arch or grid: an arch suite needs one grid and one arch"
                } else {
                    ""
                }
            ));
        }
        out.push(ArchRecord {
            t_p: tp.get(&oas.record).copied(),
            block_t1: report.check.as_ref().map(|c| c.t1),
            oas,
        });
    }
    Ok(out)
}

/// Errors unless every record of a set is on the first one's grid and arch, naming the file.
fn one_arch(files: &[PathBuf], records: &[ArchRecord]) -> Result<(), String> {
    let Some(first) = records.first() else {
        return Ok(());
    };
    for (f, r) in files.iter().zip(records).skip(1) {
        characteristic_arch_oas(&[first.oas.clone(), r.oas.clone()], 1.0, "check")
            .map_err(|e| format!("{}: {e}", f.display()))?;
    }
    Ok(())
}

/// Errors when a test set on the fit set's arch holds a record of the fit set (it would be
/// scored in sample), naming its file.
fn out_of_sample(fit: &[ArchRecord], files: &[PathBuf], set: &[ArchRecord]) -> Result<(), String> {
    let (Some(first), Some(test)) = (fit.first(), set.first()) else {
        return Ok(());
    };
    if !same_arch(&first.oas, &test.oas) {
        return Ok(());
    }
    for (f, r) in files.iter().zip(set) {
        if fit.iter().any(|x| x.oas.record == r.oas.record) {
            return Err(format!(
                "{}: record `{}` is in the fit set, on the same arch: a test set must be out of \
                 sample (other records or another arch)",
                f.display(),
                r.oas.record
            ));
        }
    }
    Ok(())
}

/// `record → t_p` of the `--tp` files.
fn read_tp(files: &[PathBuf]) -> Result<HashMap<String, f64>, String> {
    let mut out = HashMap::new();
    for f in files {
        let text = std::fs::read_to_string(f).map_err(|e| format!("{}: {e}", f.display()))?;
        let rows: Vec<TpRow> = serde_json::from_str(&text).map_err(|e| {
            format!(
                "{}: not a JSON list of rows with `record` and `t_p`: {e}",
                f.display()
            )
        })?;
        for r in rows {
            if let Some(t) = r.t_p {
                if !(t > 0.0 && t.is_finite()) {
                    return Err(format!(
                        "{}: record `{}`: t_p must be positive, got {t}",
                        f.display(),
                        r.record
                    ));
                }
                out.insert(r.record, t);
            }
        }
    }
    Ok(out)
}

/// The folder of a file.
fn folder(file: &std::path::Path) -> String {
    file.parent()
        .map_or_else(|| ".".into(), |p| p.display().to_string())
}

/// `files` grouped by folder, in the order of each folder's first file.
fn by_folder(files: &[PathBuf]) -> Vec<(String, Vec<PathBuf>)> {
    let mut out: Vec<(String, Vec<PathBuf>)> = Vec::new();
    for f in files {
        let d = folder(f);
        match out.iter_mut().find(|(n, _)| *n == d) {
            Some((_, v)) => v.push(f.clone()),
            None => out.push((d, vec![f.clone()])),
        }
    }
    out
}

/// `x` with three decimals, `-` when absent.
fn num(x: Option<f64>) -> String {
    x.map_or("-".into(), |v| format!("{v:.3}"))
}

/// `score_columns`, or why a rule is not scored on a set.
fn score_or_na(s: Option<&RuleScore>) -> String {
    s.map_or_else(
        || format!("{:>9} not scored: a fixed t1 of another arch", "n/a"),
        score_columns,
    )
}

/// `unsafe records / scored records`, `unsafe points / checked`, and the ratios.
fn score_columns(s: &RuleScore) -> String {
    format!(
        "{:>9} {:>11} {:>6} {:>6} {:>6}",
        format!("{}/{}", s.unsafe_points.records, s.records - s.unscored),
        format!("{}/{}", s.unsafe_points.points, s.checked),
        num(s.ratio_min),
        num(s.ratio_median),
        num(s.ratio_max)
    )
}

const SCORE_HEADER: &str = "  records    points    ratio: min median    max";

/// Runs `rocking arch suite`.
pub fn run_suite(a: &ArchSuiteArgs) -> Result<(), String> {
    let records = read_set(&a.spectra, &HashMap::new())?;
    one_arch(&a.spectra, &records)?;
    let report = ArchSuiteReport::of(&a.name, &records, &a.fractile).map_err(|e| e.to_string())?;
    if a.json {
        print_json(&report)?;
    } else {
        print!("{}", suite_summary(&report));
    }
    if let Some(prefix) = &a.svg {
        let spectra: Vec<ArchOas> = records.into_iter().map(|r| r.oas).collect();
        for (name, chart) in suite_charts(&report, &spectra) {
            chart.write_named(prefix, name, a.png)?;
        }
    }
    Ok(())
}

fn suite_summary(r: &ArchSuiteReport) -> String {
    let t1s: Vec<f64> = r.records.iter().filter_map(|o| o.t1).collect();
    let mut s = format!(
        "arch suite {}: {} records, {} voussoirs, t/R = {}, λ = {:.6}, p = {:.4}/√R; arch t1 of \
         the records {}…{} s\n",
        r.name,
        r.records.len(),
        r.shape.voussoirs,
        r.shape.thickness_ratio,
        r.onset.lambda,
        r.onset.p_at_1m,
        num(t1s.iter().copied().reduce(f64::min)),
        num(t1s.iter().copied().reduce(f64::max)),
    );
    s += "rule t1 against each record's arch OAS: unsafe records / scored, unsafe boundary \
          points / checked, rule t1 / arch t1\n";
    s += &format!("{:<32} {SCORE_HEADER}\n", "t1 [s]");
    s += &format!(
        "{:<32} {}\n",
        "each record's single-block t1",
        score_columns(&r.block_rule)
    );
    for c in &r.characteristic {
        s += &format!(
            "{:<32} {}\n",
            format!("design t1 of fractile {}: {}", c.fractile, num(c.design_t1)),
            score_columns(&c.check)
        );
    }
    s += "fractile  design t1 [s]  f_min [1/s]  level  R [m]  fractile of record arch t1 [s]\n";
    for c in &r.characteristic {
        s += &format!(
            "{:<9} {:>13} {:>12} {:>6} {:>6} {:>30}\n",
            c.fractile,
            num(c.design_t1),
            num(c.f_min),
            c.level_at_f_min.map_or("-".into(), |l| l.to_string()),
            c.size_at_f_min.map_or("-".into(), |x| format!("{x:.2}")),
            num(c.record_t1_fractile)
        );
    }
    s
}

/// The records' arch OAS (grey) behind the characteristic ones and their design rule, against
/// `p` and against `f`.
fn suite_charts(r: &ArchSuiteReport, spectra: &[ArchOas]) -> Vec<(&'static str, Chart)> {
    let grey = (0xbb, 0xbb, 0xbb);
    let lmax = spectra
        .iter()
        .flat_map(|o| o.levels.iter().map(|l| l.level))
        .fold(1.0, f64::max);
    let boundaries: Vec<_> = spectra.iter().map(ArchOas::boundary).collect();
    let pmax = boundaries.iter().flatten().map(|q| q.p).fold(0.1, f64::max) * 1.1;
    let fmax = boundaries.iter().flatten().map(|q| q.f).fold(0.1, f64::max) * 1.1;
    let records = |pick: fn(&rocking::spectra::OasPoint) -> f64| -> Vec<Series> {
        boundaries
            .iter()
            .enumerate()
            .map(|(k, b)| Series {
                name: if k == 0 {
                    format!("arch OAS of the {} records", spectra.len())
                } else {
                    String::new()
                },
                points: b.iter().map(|q| (pick(q), q.level)).collect(),
                style: Style::Points,
                color: grey,
            })
            .collect()
    };
    let mut by_p = records(|q| q.p);
    let mut by_f = records(|q| q.f);
    for (k, c) in r.characteristic.iter().enumerate() {
        let color = COLORS[k % 6];
        let name = format!("characteristic arch OAS, fractile {}", c.fractile);
        let pts = |pick: fn(&rocking::spectra::report::LevelReport) -> Option<f64>| {
            c.oas
                .levels
                .iter()
                .filter_map(|l| Some((pick(l)?, l.level.level)))
                .collect::<Vec<_>>()
        };
        by_p.push(Series {
            name: name.clone(),
            points: pts(|l| l.p),
            style: Style::Line,
            color,
        });
        by_f.push(Series {
            name,
            points: pts(|l| l.f),
            style: Style::Line,
            color,
        });
        let Some(t1) = c.design_t1 else { continue };
        let rule = format!("rule: level ≥ 1/(p t1), design t1 = {t1:.3} s");
        by_p.push(Series {
            name: rule.clone(),
            points: (1..=400)
                .map(|j| pmax * j as f64 / 400.0)
                .map(|p| (p, rocking::design::simplified_oas(p, t1, 1.0)))
                .collect(),
            style: Style::Dashed,
            color,
        });
        by_f.push(Series {
            name: format!("{rule}: f = 1/t1"),
            points: vec![(1.0 / t1, 1.0), (1.0 / t1, lmax)],
            style: Style::Dashed,
            color,
        });
    }
    let title = |what: &str| {
        format!(
            "{what}, {}: arch t/R = {}, {} voussoirs",
            r.name, r.shape.thickness_ratio, r.shape.voussoirs
        )
    };
    super::arch::arch_level_charts(
        [
            title("Characteristic arch OAS"),
            title("Transformed characteristic arch OAS"),
        ],
        (pmax, fmax, lmax),
        by_p,
        by_f,
    )
}

/// Runs `rocking arch rules`.
pub fn run_rules(a: &ArchRulesArgs) -> Result<(), String> {
    let tp = read_tp(&a.tp)?;
    let test_sets = by_folder(&a.test);
    let n_sets = 1 + test_sets.len();
    if !a.names.is_empty() && a.names.len() != n_sets {
        return Err(format!(
            "--names has {} names for {n_sets} sets (the fit set and {} test folders)",
            a.names.len(),
            test_sets.len()
        ));
    }
    let name = |k: usize, dir: String| a.names.get(k).cloned().unwrap_or(dir);
    let fit = read_set(&a.fit, &tp)?;
    one_arch(&a.fit, &fit)?;
    let tests = test_sets
        .into_iter()
        .enumerate()
        .map(|(k, (dir, files))| {
            let set = read_set(&files, &tp)?;
            one_arch(&files, &set)?;
            out_of_sample(&fit, &files, &set)?;
            Ok((name(k + 1, dir), set))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let fit_name = name(0, a.fit.first().map_or_else(|| ".".into(), |f| folder(f)));
    let report = ArchRulesReport::of(&fit_name, &fit, &tests);
    if a.json {
        print_json(&report)?;
    } else {
        print!("{}", rules_table(&report));
    }
    if let Some(path) = &a.svg {
        let sets: Vec<(&str, &[ArchRecord])> = std::iter::once((fit_name.as_str(), &fit[..]))
            .chain(tests.iter().map(|(n, r)| (n.as_str(), &r[..])))
            .collect();
        rules_chart(&report, &sets).write(path)?;
    }
    Ok(())
}

fn rules_table(r: &ArchRulesReport) -> String {
    let mut s = format!(
        "rules fitted on {}; scored on {} (in sample), {} (out of sample)\n",
        r.fit,
        r.sets[0],
        if r.sets.len() > 1 {
            r.sets[1..].join(", ")
        } else {
            "none".into()
        }
    );
    for (set, arch) in r.sets.iter().zip(&r.arches) {
        let Some(a) = arch else { continue };
        s += &format!(
            "set {set}: {} voussoirs, t/R = {}, embrace {:.0}°, λ = {:.6}, p = {:.4}/√R{}\n",
            a.shape.voussoirs,
            a.shape.thickness_ratio,
            a.shape.embrace_angle.to_degrees(),
            a.onset.lambda,
            a.onset.p_at_1m,
            if a.fit_arch {
                " (the fit set's arch)"
            } else {
                " (another arch than the fit set's: a fixed t1 is not scored)"
            }
        );
    }
    for row in &r.rules {
        s += &format!("({}) {}\n", row.rule.key, row.rule.statement);
    }
    s += &format!("{:<6} {:<28} {SCORE_HEADER}\n", "rule", "set");
    for row in &r.rules {
        for (set, score) in r.sets.iter().zip(&row.scores) {
            s += &format!(
                "{:<6} {:<28} {}\n",
                row.rule.key,
                set,
                score_or_na(score.as_ref())
            );
        }
    }
    s
}

/// The sets' colours in the rules chart: the palette's first six (its last two draw the rules),
/// then matplotlib's pink and olive and an indigo, so that nine sets stay apart.
const SET_COLORS: [crate::plot::Rgb; 9] = [
    COLORS[0],
    COLORS[1],
    COLORS[2],
    COLORS[3],
    COLORS[4],
    COLORS[5],
    (0xe3, 0x77, 0xc2),
    (0xbc, 0xbd, 0x22),
    (0x33, 0x33, 0x99),
];

/// Each record's arch t₁ against its single-block t₁, one colour a set, with the rules
/// `t₁,arch = c t₁,block` (c = 1 and the fitted ones).
fn rules_chart(r: &ArchRulesReport, sets: &[(&str, &[ArchRecord])]) -> Chart {
    let mut series: Vec<Series> = sets
        .iter()
        .enumerate()
        .map(|(k, (name, records))| Series {
            name: format!("{name} ({} records)", records.len()),
            points: records
                .iter()
                .filter_map(|x| Some((x.block_t1?, x.oas.t1()?)))
                .collect(),
            style: Style::Points,
            color: SET_COLORS[k % SET_COLORS.len()],
        })
        .collect();
    let xmax = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .fold(0.1, f64::max)
        * 1.05;
    let mut k = 0;
    for row in &r.rules {
        if let rocking::spectra::ArchRule::BlockT1(c) = row.rule.rule {
            k += 1;
            series.push(Series {
                name: format!("({}) arch t1 = {c:.3} × single-block t1", row.rule.key),
                points: vec![(0.0, 0.0), (xmax, c * xmax)],
                style: Style::Dashed,
                // Black, then the last two colours: the sets take the first six.
                color: [(0, 0, 0), COLORS[6], COLORS[7]][(k - 1) % 3],
            });
        }
    }
    Chart {
        title: format!(
            "Arch t1 = 1/f_min against the single-block t1 (rules fitted on {})",
            r.fit
        ),
        x_label: "single-block t1 of the record [s]".into(),
        y_label: "arch t1 [s]".into(),
        x_range: Some((0.0, xmax)),
        series,
        ..Chart::default()
    }
}
