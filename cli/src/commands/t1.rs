//! `rocking t1`: the replacement impulse duration t₁ (Eq. 20), the fit t₁', β (Eq. 28) and f_min
//! of records, each from its OAS, with the replacement sine duration t_p (Eq. 25) beside it;
//! `--merge` joins the JSON of `--shard` runs; `--svg` draws t₁ against t_p (Fig. 53).

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rocking::spectra::report::{SummaryReport as Summary, T1Row};
use rocking::spectra::{self, statistics};
use serde::{Deserialize, Serialize};

use super::sweep::{OasGridArgs, Procedure, Shard, SimulationArgs};
use crate::output::{check_prefix_writable, print_json, read_report};
use crate::plot::{Chart, Series, Style, COLORS};
use crate::progress;

/// Options of `rocking t1`.
#[derive(Args, Debug)]
pub struct T1Args {
    #[command(flatten)]
    pub record_format: super::sweep::RecordFormatArgs,
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
    /// Add how the run of the governing point (the f_min point) ended: overturning time,
    /// impacts, the last exceedance of the uplift acceleration by the scaled record. With
    /// --merge, one simulation per row (pass the options the rows were computed with: the
    /// row's dt factor, slenderness, blocks and procedure are checked against them).
    #[arg(long)]
    pub explain: bool,
    /// Write PREFIX-tp.svg: t₁ against the replacement sine duration t_p, with the correlation
    /// and the least-squares lines (thesis Fig. 53).
    #[arg(long, value_name = "PREFIX")]
    pub svg: Option<PathBuf>,
    /// With --svg: also write the chart as PNG.
    #[arg(long, requires = "svg")]
    pub png: bool,
    /// Also t₁'s band: the OAS again with half the time step, the level and the size grids
    /// shifted by half a cell and the other event locator, each at the row's step (the
    /// converged one, or the rule's with --single-step); adds `t1_range` [min, max],
    /// `t1_conservative` (f_min of the envelope of those spectra) and each one's t₁ (`band`).
    /// Four OAS more per record.
    #[arg(long, conflicts_with = "merge")]
    pub band: bool,
    /// t₁ converged in the time step (the default): the OAS at the step rule, again at half
    /// the step, and again, until two successive steps give t₁ within TOL (max/min − 1) or
    /// after --converge-halvings halvings; the row is the finest step's, with `t1_steps`
    /// ([dt factor, t₁] of each step) and `step_converged`.
    #[arg(long, value_name = "TOL", default_value_t = spectra::STEP_TOLERANCE,
          conflicts_with = "merge")]
    pub converge_step: f64,
    /// The most halvings of the step when converging.
    #[arg(long, default_value_t = spectra::STEP_HALVINGS)]
    pub converge_halvings: usize,
    /// One OAS at the step rule (× --dt-factor), not converged in the step: 2–5× faster; t₁
    /// within 10 % of the converged one on 95 of the FEMA P695 records (docs/t1-accuracy.md).
    /// The step `rocking oas` and `rocking suite` use.
    #[arg(long, conflicts_with_all = ["merge", "converge_step", "converge_halvings"])]
    pub single_step: bool,
}

impl T1Args {
    /// How t₁ is computed.
    fn method(&self) -> spectra::T1Method {
        spectra::T1Method {
            converge: (!self.single_step).then_some((self.converge_step, self.converge_halvings)),
            band: self.band,
        }
    }
}

/// One record's row of `t1 --json`: the library's row and, with `--explain`, the run of the
/// governing point.
#[derive(Serialize, Deserialize)]
struct Row {
    #[serde(flatten)]
    row: T1Row,
    /// With --explain: the run of the governing point.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    governing: Option<Governing>,
}

impl std::ops::Deref for Row {
    type Target = T1Row;
    fn deref(&self) -> &T1Row {
        &self.row
    }
}

impl std::ops::DerefMut for Row {
    fn deref_mut(&mut self) -> &mut T1Row {
        &mut self.row
    }
}

/// The file of a row (rows of `rocking t1` always have one).
fn file_of(r: &T1Row) -> &str {
    r.file.as_deref().unwrap_or("")
}

/// How the run of the governing point ended (`--explain`); times are record times [s].
#[derive(Serialize, Deserialize)]
struct Governing {
    stop: String,
    start: f64,
    end: f64,
    impacts: usize,
    last_exceedance: f64,
    record_duration: f64,
    /// end − last_exceedance: how long after the strong motion the column overturned.
    after_strong_motion: f64,
}

fn governing(
    record: &rocking::ground::records::Record,
    summary: &Summary,
    o: &spectra::OasOptions,
) -> Result<Option<Governing>, String> {
    let (Some(level), Some(size)) = (summary.level_at_f_min, summary.size_at_f_min) else {
        return Ok(None);
    };
    let run = spectra::point_run(record, level, size, o).map_err(|e| e.to_string())?;
    Ok(run.map(|r| Governing {
        stop: format!("{:?}", r.stop),
        start: r.start,
        end: r.end,
        impacts: r.impacts,
        last_exceedance: r.last_exceedance,
        record_duration: r.record_duration,
        after_strong_motion: r.end - r.last_exceedance,
    }))
}

/// Runs the command.
pub fn run(a: &T1Args) -> Result<(), String> {
    let rows: Vec<Row> = if a.merge.is_empty() {
        let o = a.grid.options(&a.simulation)?;
        let method = a.method();
        method.check().map_err(|e| e.to_string())?;
        let files = a.shard.keep(&a.records);
        if let Some(prefix) = &a.svg {
            check_prefix_writable("--svg", prefix, "-tp.svg")?;
        }
        let records = super::sweep::read_all(&files, &a.record_format)?;
        // A lower bound of the spectra when converging (more steps may be needed).
        let bar = progress::bar(
            (files.len() * o.levels.len() * method.min_spectra()) as u64,
            "t1",
        );
        let procedure = (a.grid.procedure != Procedure::Converged).then(|| a.grid.procedure.name());
        let mut rows = Vec::new();
        for (f, record) in records {
            bar.set_message(f.display().to_string());
            let t0 = Instant::now();
            let tick = || bar.inc(1);
            let result =
                spectra::t1_of(&record, &o, method, Some(&tick)).map_err(|e| e.to_string())?;
            let t_p = spectra::replacement_sine(&record).map(|s| s.t_p);
            let row = T1Row::of(
                &result,
                t0.elapsed().as_secs_f64(),
                Some(f.display().to_string()),
                &o,
                a.simulation.dt_factor,
                t_p,
                procedure.clone(),
            );
            let governing = if a.explain {
                // The governing point's run at the row's step.
                governing(&record, &row.summary, &o.at_step(result.factor()))?
            } else {
                None
            };
            rows.push(Row { row, governing });
        }
        bar.finish_and_clear();
        rows
    } else {
        let mut rows = Vec::new();
        for p in &a.merge {
            rows.extend(read_report::<Vec<Row>>(
                p,
                "the list of `rocking t1 --json` (whole or --shard)",
            )?);
        }
        // Rows written before t_p was part of the output: t_p from the record, when readable.
        for r in rows.iter_mut().filter(|r| r.t_p.is_none()) {
            if let Ok(record) =
                super::sweep::read(std::path::Path::new(file_of(r)), &a.record_format)
            {
                r.t_p = spectra::replacement_sine(&record).map(|s| s.t_p);
            }
        }
        if a.explain {
            let o = a.grid.options(&a.simulation)?;
            let procedure =
                (a.grid.procedure != Procedure::Converged).then(|| a.grid.procedure.name());
            for r in &mut rows {
                if r.first_dt_factor() != a.simulation.dt_factor
                    || r.slenderness != o.slenderness
                    || r.blocks != o.n_blocks
                    || r.procedure != procedure
                {
                    return Err(format!(
                        "--explain: {} was computed with other options (dt factor {}, \
                         slenderness {}, blocks {}, procedure {}): pass the same",
                        file_of(r),
                        r.first_dt_factor(),
                        r.slenderness,
                        r.blocks,
                        r.procedure.as_deref().unwrap_or("converged")
                    ));
                }
                let record =
                    super::sweep::read(std::path::Path::new(file_of(r)), &a.record_format)?;
                // The governing point's run at the row's own step (the finest when converged).
                let o_row = o.at_step(r.dt_factor / a.simulation.dt_factor);
                r.governing = governing(&record, &r.summary, &o_row)?;
            }
        }
        rows.sort_by(|x, y| file_of(x).cmp(file_of(y)));
        rows
    };
    if a.json {
        print_json(&rows)?;
    } else {
        println!("record                          t1 [s]   t1' [s]  beta [s] f_min [1/s] t_p [s]");
        for r in &rows {
            let s = &r.summary;
            let f = |v: Option<f64>| {
                v.filter(|x| x.is_finite())
                    .map_or("-".to_string(), |x| format!("{x:.3}"))
            };
            println!(
                "{:<30} {:>8} {:>8} {:>8} {:>8} {:>8}",
                s.record,
                f(s.t1),
                f(s.t1_prime),
                f(s.beta),
                f(s.f_min),
                f(r.t_p)
            );
            if let (Some([lo, hi]), Some(c)) = (r.accuracy.t1_range, r.accuracy.t1_conservative) {
                println!("    t1 band: {lo:.3}-{hi:.3} s, conservative {c:.3} s");
            }
            if let (Some(steps), Some(ok)) = (&r.accuracy.t1_steps, r.accuracy.step_converged) {
                let list: Vec<String> = steps
                    .iter()
                    .map(|(f, t)| match t {
                        Some(t) => format!("x{f}: {t:.4}"),
                        None => format!("x{f}: none"),
                    })
                    .collect();
                let verdict = if ok { "converged" } else { "not converged" };
                println!("    t1 by step: {} ({verdict})", list.join(", "));
            }
            if let Some(g) = &r.governing {
                println!(
                    "    governing run: {} at {:.2} s after {} impacts; strong motion {:.2}-{:.2} s \
                     of {:.2} s ({:+.2} s after it)",
                    g.stop,
                    g.end,
                    g.impacts,
                    g.start,
                    g.last_exceedance,
                    g.record_duration,
                    g.after_strong_motion
                );
            }
        }
        let c = Correlation::of(&rows);
        if let Some(r) = c.r {
            println!(
                "t1 against t_p: {} records, Pearson r = {r:.3}, least squares t1 = {:.3} t_p \
                 (through the origin), t1 = {:.3} + {:.3} t_p",
                c.pairs.len(),
                c.slope.unwrap_or(f64::NAN),
                c.line.map_or(f64::NAN, |l| l.0),
                c.line.map_or(f64::NAN, |l| l.1),
            );
        }
    }
    if let Some(prefix) = &a.svg {
        Correlation::of(&rows)
            .chart()
            .write_named(prefix, "tp", a.png)?;
    }
    Ok(())
}

/// t₁ against t_p over the rows that have both (thesis Fig. 53).
struct Correlation {
    /// (t_p, t₁).
    pairs: Vec<(f64, f64)>,
    r: Option<f64>,
    slope: Option<f64>,
    line: Option<(f64, f64)>,
}

impl Correlation {
    fn of(rows: &[Row]) -> Correlation {
        let pairs: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|r| Some((r.t_p?, r.summary.t1?)))
            .collect();
        Correlation {
            r: statistics::pearson(&pairs),
            slope: statistics::slope_through_origin(&pairs),
            line: statistics::least_squares(&pairs),
            pairs,
        }
    }

    /// The scatter of Fig. 53 with the line y = x and the two least-squares lines.
    fn chart(&self) -> Chart {
        let top = self.pairs.iter().fold(0.1_f64, |m, p| m.max(p.0).max(p.1)) * 1.05;
        let mut series = vec![
            Series {
                name: format!("records ({})", self.pairs.len()),
                points: self.pairs.clone(),
                style: Style::Points,
                color: COLORS[0],
            },
            Series {
                name: "t1 = t_p".into(),
                points: vec![(0.0, 0.0), (top, top)],
                style: Style::Line,
                color: COLORS[7],
            },
        ];
        if let Some(b) = self.slope {
            series.push(Series {
                name: format!("least squares through 0: t1 = {b:.3} t_p"),
                points: vec![(0.0, 0.0), (top, b * top)],
                style: Style::Dashed,
                color: COLORS[1],
            });
        }
        if let Some((a, b)) = self.line {
            series.push(Series {
                name: format!("least squares: t1 = {a:.3} + {b:.3} t_p"),
                points: vec![(0.0, a), (top, a + b * top)],
                style: Style::Dashed,
                color: COLORS[2],
            });
        }
        Chart {
            title: format!(
                "t1 against the replacement sine duration t_p (Fig. 53): r = {}",
                self.r.map_or("-".into(), |r| format!("{r:.2}"))
            ),
            x_label: "t_p [s] (Eq. 25)".into(),
            y_label: "t1 [s] (Eq. 20)".into(),
            x_range: Some((0.0, top)),
            y_range: Some((0.0, top)),
            series,
            ..Chart::default()
        }
    }
}
