//! `rocking oas`: the overturning acceleration spectrum of a record (thesis Fig. 36, 37, 43)
//! through `rocking::spectra::oas`, its summary (t₁ of Eq. 20, the Eq. 28 fit) and charts;
//! `--merge` rebuilds the spectrum from level shards.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rocking::spectra::report::OasReport;
use rocking::spectra::{self, Oas};

use super::sweep::{OasGridArgs, Shard, SimulationArgs};
use crate::output::{check_prefix_writable, print_json, read_report};
use crate::plot::{Chart, Scale, Series, Style, COLORS};
use crate::progress;

/// Options of `rocking oas`.
#[derive(Args, Debug)]
pub struct OasArgs {
    #[command(flatten)]
    pub record_format: super::sweep::RecordFormatArgs,
    /// The record (.AT2 in g, or plain text in m/s²).
    #[arg(required_unless_present_any = ["merge", "overlay"])]
    pub record: Option<PathBuf>,
    /// Rebuild the OAS from the JSON of `--shard` runs instead of computing it.
    #[arg(long, num_args = 1.., value_name = "SHARD.json", conflicts_with = "record")]
    pub merge: Vec<PathBuf>,
    /// Compare stored OAS (the JSON of whole `rocking oas` runs) instead of computing one: a
    /// table of each (unsafe cells, t1), the slenderness check (spectra of a record that differ
    /// in H/B: the levels where the lower H/B has a larger unsafe size than the higher), and
    /// with --svg one chart of all (PREFIX-overlay.svg against p, PREFIX-overlay-size.svg);
    /// thesis Fig. 43 and 45.
    #[arg(long, num_args = 1.., value_name = "OAS.json", conflicts_with_all = ["record", "merge"])]
    pub overlay: Vec<PathBuf>,
    #[command(flatten)]
    pub grid: OasGridArgs,
    #[command(flatten)]
    pub simulation: SimulationArgs,
    /// Only the levels k with k % n == i (merge the shards with --merge).
    #[arg(long, default_value_t = Shard::WHOLE, value_name = "i/n")]
    pub shard: Shard,
    /// JSON (the default).
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// CSV instead of JSON: one row per level.
    #[arg(long)]
    pub csv: bool,
    /// Write charts PREFIX-oas.svg (against p, Fig. 36), PREFIX-transformed.svg (against f,
    /// Fig. 37) and PREFIX-size.svg (against the size R, log axis).
    #[arg(long, value_name = "PREFIX")]
    pub svg: Option<PathBuf>,
    /// With --svg: also write the charts as PNG.
    #[arg(long, requires = "svg")]
    pub png: bool,
    /// Also t₁'s band, as `rocking t1 --band`: the OAS again with half the time step, the
    /// level and the size grids shifted by half a cell and the other event locator; adds
    /// `t1_range`, `t1_conservative` and `band` (four OAS more).
    #[arg(long, conflicts_with_all = ["merge", "overlay", "shard"])]
    pub band: bool,
    /// The OAS converged in the time step, as `rocking t1` computes it: halved until two
    /// successive t₁ agree within TOL (e.g. 0.1); the spectrum is the finest step's, with
    /// `t1_steps` and `step_converged`. Without it, one OAS at the step rule.
    #[arg(long, value_name = "TOL", conflicts_with_all = ["merge", "overlay", "shard"])]
    pub converge_step: Option<f64>,
    /// With --converge-step: the most halvings of the step.
    #[arg(long, default_value_t = spectra::STEP_HALVINGS, requires = "converge_step")]
    pub converge_halvings: usize,
}

/// Runs the command.
pub fn run(a: &OasArgs) -> Result<(), String> {
    if let Some(prefix) = &a.svg {
        check_prefix_writable("--svg", prefix, "-oas.svg")?;
    }
    if !a.overlay.is_empty() {
        return super::overlay::run(&a.overlay, a.svg.as_deref(), a.png);
    }
    let t0 = Instant::now();
    // The spectrum with its band and steps when computed (a merged one has neither).
    let t1 = match &a.record {
        None => {
            let parts: Vec<OasReport> = a
                .merge
                .iter()
                .map(|p| read_report(p, "an OAS report (`rocking oas --json`, whole or --shard)"))
                .collect::<Result<_, _>>()?;
            spectra::T1Result {
                oas: OasReport::merge(parts).ok_or("nothing to merge")?,
                steps: None,
                band: None,
            }
        }
        Some(path) => {
            let record = super::sweep::read(path, &a.record_format)?;
            let mut o = a.grid.options(&a.simulation)?;
            o.levels = a.shard.keep(&o.levels);
            let method = spectra::T1Method {
                converge: a.converge_step.map(|tol| (tol, a.converge_halvings)),
                band: a.band,
            };
            method.check().map_err(|e| e.to_string())?;
            let bar = progress::bar((o.levels.len() * method.min_spectra()) as u64, "OAS");
            let tick = || bar.inc(1);
            let r = spectra::t1_of(&record, &o, method, Some(&tick)).map_err(|e| e.to_string())?;
            bar.finish_and_clear();
            r
        }
    };
    let result = &t1.oas;
    let seconds = t0.elapsed().as_secs_f64();
    if a.csv {
        println!("record,level,size,p,f,simulations");
        for l in &result.levels {
            let (size, p) = match l.largest_unsafe {
                Some(i) => (
                    result.sizes[i],
                    result
                        .block(result.sizes[i])
                        .frequency_parameter(result.gravity),
                ),
                None => (f64::NAN, f64::NAN),
            };
            println!(
                "{},{},{size},{p},{},{}",
                result.record,
                l.level,
                p * l.level,
                l.simulations
            );
        }
    } else {
        print_json(&OasReport::of_t1(&t1, seconds, a.simulation.dt_factor))?;
    }
    if let Some(prefix) = &a.svg {
        for (name, chart) in charts(result) {
            chart.write_named(prefix, name, a.png)?;
        }
    }
    Ok(())
}

/// The charts of an OAS: against `p` (Fig. 36), against `f` (Fig. 37) and against the size.
fn charts(o: &Oas) -> Vec<(&'static str, Chart)> {
    let s = o.summary();
    let b = o.boundary();
    let i_cr = o.i_cr();
    let lmax = o.levels.iter().map(|l| l.level).fold(1.0, f64::max);
    let pmax = b.iter().map(|q| q.p).fold(1.0, f64::max) * 1.1;
    let fmax = b.iter().map(|q| q.f).fold(1.0, f64::max) * 1.1;
    let (rmin, rmax) = o
        .sizes
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &r| {
            (lo.min(r), hi.max(r))
        });
    let ps: Vec<f64> = (1..=400).map(|k| pmax * k as f64 / 400.0).collect();
    let rs: Vec<f64> = (0..=400)
        .map(|k| rmin * (rmax / rmin).powf(k as f64 / 400.0))
        .collect();
    let dots = |points: Vec<(f64, f64)>| Series {
        name: "largest unsafe size".into(),
        points,
        style: Style::Points,
        color: COLORS[0],
    };
    let mut by_p = vec![dots(b.iter().map(|q| (q.p, q.level)).collect())];
    let mut by_f = vec![dots(b.iter().map(|q| (q.f, q.level)).collect())];
    let mut by_r = vec![dots(b.iter().map(|q| (q.size, q.level)).collect())];
    if let Some(t1) = s.t1 {
        let eq21 = |p: f64| rocking::design::simplified_oas(p, t1, i_cr);
        let name = format!("Eq. 21, t1 = {t1:.3} s");
        let curve = |points: Vec<(f64, f64)>| Series {
            name: name.clone(),
            points,
            style: Style::Dashed,
            color: COLORS[1],
        };
        by_p.push(curve(ps.iter().map(|&p| (p, eq21(p))).collect()));
        by_r.push(curve(
            rs.iter()
                .map(|&r| (r, eq21(o.block(r).frequency_parameter(o.gravity))))
                .collect(),
        ));
        by_f.push(Series {
            name: format!("f_min = i_cr / t1 (Eq. 20), t1 = {t1:.3} s"),
            points: vec![(i_cr / t1, 1.0), (i_cr / t1, lmax)],
            style: Style::Dashed,
            color: COLORS[1],
        });
        if let Some(fit) = s.fit {
            let eq30 = |p: f64| rocking::design::improved_oas_eq30(p, t1, fit.t1_prime, fit.beta);
            let name = format!(
                "Eq. 30, t1' = {:.3} s, beta = {:.2} s",
                fit.t1_prime, fit.beta
            );
            let curve = |points: Vec<(f64, f64)>| Series {
                name: name.clone(),
                points,
                style: Style::Dashed,
                color: COLORS[2],
            };
            by_p.push(curve(ps.iter().map(|&p| (p, eq30(p))).collect()));
            by_r.push(curve(
                rs.iter()
                    .map(|&r| (r, eq30(o.block(r).frequency_parameter(o.gravity))))
                    .collect(),
            ));
            by_f.push(Series {
                name: format!(
                    "Eq. 28, t1' = {:.3} s, beta = {:.2} s",
                    fit.t1_prime, fit.beta
                ),
                points: vec![
                    (1.0 / fit.beta + 1.0 / fit.t1_prime, 1.0),
                    (lmax / fit.beta + 1.0 / fit.t1_prime, lmax),
                ],
                style: Style::Dashed,
                color: COLORS[2],
            });
        }
    }
    let chart = |title, x_label, x_scale, x_range, series| {
        level_chart(title, x_label, x_scale, Some(x_range), lmax, series)
    };
    vec![
        (
            "oas",
            chart(
                format!("OAS, {}", o.record),
                "p [1/s]",
                Scale::Linear,
                (0.0, pmax),
                by_p,
            ),
        ),
        (
            "transformed",
            chart(
                format!("Transformed OAS, {}", o.record),
                "f = p a_p / a_p,min [1/s]",
                Scale::Linear,
                (0.0, fmax),
                by_f,
            ),
        ),
        (
            "size",
            chart(
                format!("OAS against the block size, {}", o.record),
                "size R [m] (half diagonal)",
                Scale::Log,
                (rmin, rmax),
                by_r,
            ),
        ),
    ]
}

/// A chart of OAS curves: the level `a_p / a_p,min` (0 to `level_max`) against `p`, `f` or `R`.
pub(crate) fn level_chart(
    title: String,
    x_label: &str,
    x_scale: Scale,
    x_range: Option<(f64, f64)>,
    level_max: f64,
    series: Vec<Series>,
) -> Chart {
    Chart {
        title,
        x_label: x_label.into(),
        y_label: "a_p / a_p,min".into(),
        x_scale,
        x_range,
        y_range: Some((0.0, level_max)),
        series,
        ..Chart::default()
    }
}
