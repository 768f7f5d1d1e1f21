//! `rocking oc`: the overturning curve of a pulse (thesis Fig. 8, 33, 40): safe/unsafe on a grid
//! of `p t_p` (log-spaced) × `a_p / a_p,min` (linear, from 1), through
//! `rocking::spectra::overturning_curve`.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use rocking::model::single_block::EquivalentBlock;
use rocking::spectra::report::OcReport;
use rocking::spectra::{self, column_of_size, linear_levels, log_sizes, PulseShape, SweepOptions};

use super::sweep::{count, grid_count, positive, Shard, SimulationArgs};
use crate::output::{check_writable, print_json};
use crate::plot::{Chart, Scale, Series, Style, COLORS};
use crate::progress;

/// The pulse shapes.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Shape {
    HalfSine,
    FullSine,
    ThreeHalfSines,
    Rectangular,
    Triangular,
    Ricker,
}

impl Shape {
    pub fn pulse(self) -> PulseShape {
        match self {
            Shape::HalfSine => PulseShape::half_sine(),
            Shape::FullSine => PulseShape::full_sine(),
            Shape::ThreeHalfSines => PulseShape::three_half_sines(),
            Shape::Rectangular => PulseShape::Rectangular,
            Shape::Triangular => PulseShape::Triangular,
            Shape::Ricker => PulseShape::Ricker,
        }
    }
}

/// Options of `rocking oc`.
#[derive(Args, Debug)]
pub struct OcArgs {
    /// The pulse.
    #[arg(long, value_enum, default_value_t = Shape::HalfSine)]
    pub shape: Shape,
    /// Equal blocks in the column.
    #[arg(long, default_value_t = 1, value_parser = count)]
    pub blocks: usize,
    /// H/B of the whole column (the equivalent monolith, as `rocking oas --slenderness`): each
    /// of the --blocks equal blocks is H/n high and B wide, i.e. of H/B = slenderness / n.
    #[arg(long, default_value_t = 12.0, value_parser = positive)]
    pub slenderness: f64,
    /// Size R of the column (half diagonal of the equivalent monolith) [m].
    #[arg(long, default_value_t = 1.0, value_parser = positive)]
    pub size: f64,
    /// Smallest p t_p.
    #[arg(long = "ptp-min", default_value_t = 0.1, value_parser = positive)]
    pub ptp_min: f64,
    /// Largest p t_p.
    #[arg(long = "ptp-max", default_value_t = 10.0, value_parser = positive)]
    pub ptp_max: f64,
    /// Number of p t_p values (log-spaced).
    #[arg(long = "ptp-n", default_value_t = 40, value_parser = grid_count)]
    pub ptp_n: usize,
    /// Highest level a_p / a_p,min.
    #[arg(long = "level-max", default_value_t = 10.0, value_parser = positive)]
    pub level_max: f64,
    /// Number of levels (linear from 1).
    #[arg(long = "level-n", default_value_t = 40, value_parser = grid_count)]
    pub level_n: usize,
    #[command(flatten)]
    pub simulation: SimulationArgs,
    /// Only the pulse durations k with k % n == i (merge the shards' CSV by hand).
    #[arg(long, default_value_t = Shard::WHOLE, value_name = "i/n")]
    pub shard: Shard,
    /// JSON instead of CSV.
    #[arg(long)]
    pub json: bool,
    /// Draw the curve (.svg or .png).
    #[arg(long, value_name = "FILE", value_parser = crate::plot::plot_path)]
    pub svg: Option<PathBuf>,
}

/// Runs the command.
pub fn run(a: &OcArgs) -> Result<(), String> {
    super::sweep::ascending("--ptp-min", a.ptp_min, "--ptp-max", a.ptp_max, a.ptp_n)?;
    super::sweep::levels_from_one(a.level_max, a.level_n)?;
    let shape = a.shape.pulse();
    let column = column_of_size(a.size, a.slenderness, a.blocks).map_err(|e| e.to_string())?;
    let mut sweep = SweepOptions::default();
    a.simulation.apply(&mut sweep);
    let block = EquivalentBlock::of_column(&column);
    let g = sweep.simulation.physics.gravity;
    let (mono_p, mono_a_p_min) = (block.frequency_parameter(g), block.a_p_min(g));
    let ptp: Vec<f64> = log_sizes(a.ptp_max, a.ptp_min, a.ptp_n)
        .into_iter()
        .rev()
        .collect();
    let t_p: Vec<f64> = a.shard.keep(&ptp).iter().map(|x| x / mono_p).collect();
    let levels = linear_levels(1.0, a.level_max, a.level_n);
    let a_p: Vec<f64> = levels.iter().map(|l| l * mono_a_p_min).collect();
    if let Some(path) = &a.svg {
        check_writable("--svg", path)?;
    }
    let bar = progress::bar(t_p.len() as u64, "OC");
    let tick = || bar.inc(1);
    let res = spectra::overturning_curve(&column, shape, &t_p, &a_p, &sweep, Some(&tick))
        .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    if a.json {
        print_json(&OcReport::of(&res, &a_p, a.blocks, mono_p, mono_a_p_min))?;
    } else {
        println!("shape,blocks,t_p,a_p,p_tp,level,unsafe");
        for (i, &t) in res.t_p.iter().enumerate() {
            for (j, &ap) in res.a_p.iter().enumerate() {
                println!(
                    "{},{},{t},{ap},{},{},{}",
                    shape.name(),
                    a.blocks,
                    mono_p * t,
                    ap / mono_a_p_min,
                    u8::from(res.is_unsafe(i, j))
                );
            }
        }
    }
    if let Some(path) = &a.svg {
        let pts = res.normalised();
        let env: Vec<(f64, f64)> = res
            .normalised_envelope()
            .iter()
            .filter_map(|(x, e)| e.map(|y| (*x, y)))
            .collect();
        oc_chart(
            format!(
                "Overturning curve, {}, {} block{}",
                shape.name(),
                a.blocks,
                if a.blocks == 1 { "" } else { "s" }
            ),
            "p t_p",
            "a_p / a_p,min",
            (
                "overturns",
                pts.iter().filter(|p| p.2).map(|p| (p.0, p.1)).collect(),
            ),
            env,
            grid_extent(&pts),
        )
        .write(path)?;
    }
    Ok(())
}

/// The extent `((x_lo, x_hi), (y_lo, y_hi))` of a grid's points `(x, y, …)`.
pub(super) fn grid_extent<T>(points: &[(f64, f64, T)]) -> ((f64, f64), (f64, f64)) {
    let range = |values: &mut dyn Iterator<Item = f64>| {
        values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
    };
    (
        range(&mut points.iter().map(|p| p.0)),
        range(&mut points.iter().map(|p| p.1)),
    )
}

/// The chart of an overturning curve: the grid points that overturn (or collapse), `(name,
/// points)`, and their lower envelope, against `p t_p` on a log axis. The axes span the whole
/// computed grid (`extent`, [`grid_extent`]), not only the points that overturn: a grid from
/// p t_p = 0.1 whose shortest pulses overturned nothing was drawn from 0.2, as if it started
/// there.
pub(super) fn oc_chart(
    title: String,
    x_label: &str,
    y_label: &str,
    (name, points): (&str, Vec<(f64, f64)>),
    envelope: Vec<(f64, f64)>,
    (x_extent, y_extent): ((f64, f64), (f64, f64)),
) -> Chart {
    Chart {
        title,
        x_label: x_label.into(),
        y_label: y_label.into(),
        x_scale: Scale::Log,
        x_range: Some(x_extent),
        y_range: Some((y_extent.0.min(0.0), y_extent.1)),
        series: vec![
            Series {
                name: name.into(),
                points,
                style: Style::Points,
                color: COLORS[0],
            },
            Series {
                name: "envelope".into(),
                points: envelope,
                style: Style::Line,
                color: COLORS[1],
            },
        ],
        ..Chart::default()
    }
}
