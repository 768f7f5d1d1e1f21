//! `rocking arch oas` / `rocking arch oc`: the spectra of a voussoir arch (issue 15, item 5)
//! through `rocking::spectra::{arch_oas, arch_overturning_curve}`: size = the centre-line radius
//! at fixed `t/R`, embrace angle and voussoirs; level = `a_p / (λ g)`; unsafe = the loop
//! driver's collapse.

use std::path::PathBuf;
use std::time::Instant;

use clap::{Args, Subcommand};
use rocking::spectra::arch_report::{ArchOasReport, ArchOcReport};
use rocking::spectra::{
    self, linear_levels, log_sizes, ArchOas, ArchOasOptions, ArchShape, ArchSweepOptions,
};

use super::oas::level_chart;
use super::oc::Shape;
use super::sweep::{count, grid_count, positive};
use crate::output::{check_prefix_writable, check_writable, print_json};
use crate::plot::{Chart, Scale, Series, Style, COLORS};
use crate::progress;

/// The spectra of an arch.
#[derive(Subcommand, Debug)]
pub enum Arch {
    /// OAS of an arch for a record: for each level a_p / (λ g), the largest radius that
    /// collapses (scanned from the largest); JSON.
    Oas(ArchOasArgs),
    /// Overturning curve of an arch under a pulse: collapse on a grid of p t_p (log) x
    /// a_p / (λ g) (linear); JSON.
    Oc(ArchOcArgs),
    /// The suite procedure on arch OAS (`arch oas` JSON): the characteristic arch OAS at
    /// fractiles, its design t1 (1/f_min) and that t1 checked against every record.
    Suite(super::arch_suite::ArchSuiteArgs),
    /// Candidate arch design rules for t1, fitted on one set of arch OAS and scored on it and,
    /// out of sample, on others.
    Rules(super::arch_suite::ArchRulesArgs),
}

impl Arch {
    pub fn run(&self) -> Result<(), String> {
        match self {
            Arch::Oas(a) => run_oas(a),
            Arch::Oc(a) => run_oc(a),
            Arch::Suite(a) => super::arch_suite::run_suite(a),
            Arch::Rules(a) => super::arch_suite::run_rules(a),
        }
    }
}

/// The arch family and the runs' settings.
#[derive(Args, Debug)]
pub struct ArchFamilyArgs {
    /// Thickness over radius t/R (below 2: the intrados radius R − t/2 is positive).
    #[arg(long = "thickness-ratio", default_value_t = 0.15, value_parser = thickness_ratio)]
    pub thickness_ratio: f64,
    /// Angle of embrace [degrees] (180: semicircular; below 360).
    #[arg(long, default_value_t = 180.0, value_parser = embrace)]
    pub embrace: f64,
    /// Number of voussoirs.
    #[arg(long, default_value_t = 20, value_parser = count)]
    pub voussoirs: usize,
    /// Factor on the time step rule (min(Δt_record/4, t_p/100, 1/(100 p))).
    #[arg(long = "dt-factor", default_value_t = 1.0, value_parser = positive)]
    pub dt_factor: f64,
}

/// `--embrace`: degrees in (0, 360), judged in the degrees given (the arch's own check says
/// `arch.embrace_angle = 6.28…: must be less than 2π`, in radians the user never typed).
fn embrace(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(e) if e > 0.0 && e < 360.0 => Ok(e),
        _ => Err(format!(
            "{s}: the angle of embrace must be greater than 0 and less than 360 degrees (a full \
             ring has no abutments)"
        )),
    }
}

/// `--thickness-ratio`: t/R in (0, 2) (the arch's own check names `arch.thickness`).
fn thickness_ratio(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(r) if r > 0.0 && r < 2.0 => Ok(r),
        _ => Err(format!(
            "{s}: t/R must be greater than 0 and less than 2 (the intrados radius R − t/2 must \
             be positive)"
        )),
    }
}

impl ArchFamilyArgs {
    fn options(&self) -> ArchSweepOptions {
        let mut o = ArchSweepOptions {
            shape: ArchShape {
                thickness_ratio: self.thickness_ratio,
                embrace_angle: self.embrace.to_radians(),
                voussoirs: self.voussoirs,
            },
            ..ArchSweepOptions::default()
        };
        o.time_step = o.time_step.scaled(self.dt_factor);
        o
    }
}

/// Options of `rocking arch oas`.
#[derive(Args, Debug)]
pub struct ArchOasArgs {
    #[command(flatten)]
    pub record_format: super::sweep::RecordFormatArgs,
    /// The record (.AT2 in g, or plain text in m/s²).
    pub record: PathBuf,
    #[command(flatten)]
    pub family: ArchFamilyArgs,
    /// Largest radius [m].
    #[arg(long = "radius-max", default_value_t = 100.0, value_parser = positive)]
    pub radius_max: f64,
    /// Smallest radius [m].
    #[arg(long = "radius-min", default_value_t = 1.0, value_parser = positive)]
    pub radius_min: f64,
    /// Number of radii (log-spaced, scanned from the largest).
    #[arg(long = "radius-n", default_value_t = 12, value_parser = grid_count)]
    pub radius_n: usize,
    /// Lowest level a_p / (λ g).
    #[arg(long = "level-min", default_value_t = 1.5, value_parser = positive)]
    pub level_min: f64,
    /// Highest level a_p / (λ g).
    #[arg(long = "level-max", default_value_t = 6.0, value_parser = positive)]
    pub level_max: f64,
    /// Number of levels (linear).
    #[arg(long = "level-n", default_value_t = 10, value_parser = grid_count)]
    pub level_n: usize,
    /// Check the single-block design rule (Eq. 21, i_cr ≈ 1) with this t1 [s] (e.g. the
    /// record's, from `rocking t1`) against the arch OAS, with p of the arch's onset mechanism.
    #[arg(long, value_parser = positive)]
    pub t1: Option<f64>,
    /// Write PREFIX-oas.svg (level against p) and PREFIX-transformed.svg (against f).
    #[arg(long, value_name = "PREFIX")]
    pub svg: Option<PathBuf>,
}

fn run_oas(a: &ArchOasArgs) -> Result<(), String> {
    if let Some(prefix) = &a.svg {
        check_prefix_writable("--svg", prefix, "-oas.svg")?;
    }
    if a.radius_min >= a.radius_max && a.radius_n > 1 {
        return Err(format!(
            "--radius-min ({}) must be below --radius-max ({})",
            a.radius_min, a.radius_max
        ));
    }
    super::sweep::ascending(
        "--level-min",
        a.level_min,
        "--level-max",
        a.level_max,
        a.level_n,
    )?;
    let record = super::sweep::read(&a.record, &a.record_format)?;
    let options = ArchOasOptions {
        levels: linear_levels(a.level_min, a.level_max, a.level_n),
        sizes: log_sizes(a.radius_max, a.radius_min, a.radius_n),
        sweep: a.family.options(),
    };
    let t0 = Instant::now();
    let bar = progress::bar(options.levels.len() as u64, "arch OAS");
    let tick = || bar.inc(1);
    let o = spectra::arch_oas(&record, &options, Some(&tick)).map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    let seconds = t0.elapsed().as_secs_f64();
    eprintln!(
        "arch OAS of {}: {} simulations, {} failed, {seconds:.1} s wall",
        o.record,
        o.simulations(),
        o.runs.failures.len()
    );
    print_json(&ArchOasReport::of(&o, a.t1, seconds))?;
    if let Some(prefix) = &a.svg {
        for (name, chart) in oas_charts(&o, a.t1) {
            chart.write_named(prefix, name, false)?;
        }
    }
    Ok(())
}

/// The arch OAS against `p` and against `f`, with the arch's own `t₁` and the checked one.
fn oas_charts(o: &ArchOas, t1: Option<f64>) -> Vec<(&'static str, Chart)> {
    let b = o.boundary();
    let lmax = o.levels.iter().map(|l| l.level).fold(1.0, f64::max);
    let pmax = b.iter().map(|q| q.p).fold(0.1, f64::max) * 1.2;
    let fmax = b.iter().map(|q| q.f).fold(0.1, f64::max) * 1.2;
    let dots = |points: Vec<(f64, f64)>| Series {
        name: "largest radius that collapses".into(),
        points,
        style: Style::Points,
        color: COLORS[0],
    };
    let mut by_p = vec![dots(b.iter().map(|q| (q.p, q.level)).collect())];
    let mut by_f = vec![dots(b.iter().map(|q| (q.f, q.level)).collect())];
    let ps: Vec<f64> = (1..=400).map(|k| pmax * k as f64 / 400.0).collect();
    let lines = [(o.t1(), "the arch's own"), (t1, "single-block")];
    for (k, (t, what)) in lines.iter().enumerate() {
        let Some(t) = *t else { continue };
        let name = format!("Eq. 21 (i_cr = 1), {what} t1 = {t:.3} s");
        by_p.push(Series {
            name: name.clone(),
            points: ps
                .iter()
                .map(|&p| (p, rocking::design::simplified_oas(p, t, 1.0)))
                .collect(),
            style: Style::Dashed,
            color: COLORS[1 + k],
        });
        by_f.push(Series {
            name,
            points: vec![(1.0 / t, 1.0), (1.0 / t, lmax)],
            style: Style::Dashed,
            color: COLORS[1 + k],
        });
    }
    let title = |what: &str| {
        format!(
            "{what}, arch t/R = {}, {} voussoirs, {}",
            o.shape.thickness_ratio, o.shape.voussoirs, o.record
        )
    };
    arch_level_charts(
        [title("Arch OAS"), title("Transformed arch OAS")],
        (pmax, fmax, lmax),
        by_p,
        by_f,
    )
}

/// The two charts of an arch OAS (or of a suite's): against the onset mechanism's `p` up to
/// `pmax` and against `f` up to `fmax`, levels `a_p / (λ g)` up to `lmax`; `titles` in that order.
pub(crate) fn arch_level_charts(
    titles: [String; 2],
    (pmax, fmax, lmax): (f64, f64, f64),
    by_p: Vec<Series>,
    by_f: Vec<Series>,
) -> Vec<(&'static str, Chart)> {
    let [by_p_title, by_f_title] = titles;
    let relabel = |mut c: Chart| {
        c.y_label = "a_p / (λ g)".into();
        c
    };
    vec![
        (
            "oas",
            relabel(level_chart(
                by_p_title,
                "p of the onset mechanism [1/s]",
                Scale::Linear,
                Some((0.0, pmax)),
                lmax,
                by_p,
            )),
        ),
        (
            "transformed",
            relabel(level_chart(
                by_f_title,
                "f = p a_p / (λ g) [1/s]",
                Scale::Linear,
                Some((0.0, fmax)),
                lmax,
                by_f,
            )),
        ),
    ]
}

/// Options of `rocking arch oc`.
#[derive(Args, Debug)]
pub struct ArchOcArgs {
    /// The pulse.
    #[arg(long, value_enum, default_value_t = Shape::HalfSine)]
    pub shape: Shape,
    #[command(flatten)]
    pub family: ArchFamilyArgs,
    /// Radius of the arch's centre line [m].
    #[arg(long, default_value_t = 5.0, value_parser = positive)]
    pub radius: f64,
    /// Smallest p t_p.
    #[arg(long = "ptp-min", default_value_t = 0.5, value_parser = positive)]
    pub ptp_min: f64,
    /// Largest p t_p.
    #[arg(long = "ptp-max", default_value_t = 10.0, value_parser = positive)]
    pub ptp_max: f64,
    /// Number of p t_p values (log-spaced).
    #[arg(long = "ptp-n", default_value_t = 8, value_parser = grid_count)]
    pub ptp_n: usize,
    /// Highest level a_p / (λ g).
    #[arg(long = "level-max", default_value_t = 6.0, value_parser = positive)]
    pub level_max: f64,
    /// Number of levels (linear from 1).
    #[arg(long = "level-n", default_value_t = 11, value_parser = grid_count)]
    pub level_n: usize,
    /// Draw the curve (.svg or .png).
    #[arg(long, value_name = "FILE", value_parser = crate::plot::plot_path)]
    pub svg: Option<PathBuf>,
}

fn run_oc(a: &ArchOcArgs) -> Result<(), String> {
    if let Some(path) = &a.svg {
        check_writable("--svg", path)?;
    }
    super::sweep::ascending("--ptp-min", a.ptp_min, "--ptp-max", a.ptp_max, a.ptp_n)?;
    super::sweep::levels_from_one(a.level_max, a.level_n)?;
    let options = a.family.options();
    let sim = &options.simulation;
    let onset =
        spectra::arch_onset(&options.shape, sim.gravity, &sim.model).map_err(|e| e.to_string())?;
    let p = onset.p(a.radius);
    let t_p: Vec<f64> = log_sizes(a.ptp_max, a.ptp_min, a.ptp_n)
        .into_iter()
        .rev()
        .map(|x| x / p)
        .collect();
    let levels = linear_levels(1.0, a.level_max, a.level_n);
    let t0 = Instant::now();
    let bar = progress::bar(t_p.len() as u64, "arch OC");
    let tick = || bar.inc(1);
    let oc = spectra::arch_overturning_curve(
        a.shape.pulse(),
        a.radius,
        &t_p,
        &levels,
        &options,
        Some(&tick),
    )
    .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    let report = ArchOcReport::of(&oc, t0.elapsed().as_secs_f64());
    print_json(&report)?;
    if let Some(path) = &a.svg {
        let env: Vec<(f64, f64)> = report
            .envelope
            .iter()
            .filter_map(|e| e.level.map(|l| (e.p_tp, l)))
            .collect();
        super::oc::oc_chart(
            format!(
                "Arch OC, {}, R = {} m, t/R = {}, {} voussoirs",
                oc.pulse.name(),
                a.radius,
                a.family.thickness_ratio,
                a.family.voussoirs
            ),
            "p t_p (p of the onset mechanism)",
            "a_p / (λ g)",
            (
                "collapses",
                report
                    .points
                    .iter()
                    .filter(|q| q.collapses)
                    .map(|q| (q.p_tp, q.level))
                    .collect(),
            ),
            env,
            super::oc::grid_extent(
                &report
                    .points
                    .iter()
                    .map(|q| (q.p_tp, q.level, ()))
                    .collect::<Vec<_>>(),
            ),
        )
        .write(path)?;
    }
    Ok(())
}
