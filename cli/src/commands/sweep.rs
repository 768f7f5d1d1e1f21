//! What the spectra commands (`oc`, `oas`, `t1`) share: the settings of every simulation of a
//! sweep, the OAS grid, `--shard`, and the value checks of their arguments.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use clap::{Args, ValueEnum};
use rocking::driver::{EventLocator, Integrator};
use rocking::ground::records::{read_record, PlainFormat, Record, RecordError};
use rocking::spectra::{linear_levels, log_sizes, OasOptions, SizeSearch, SweepOptions, TimeStep};

/// A finite number > 0.
pub fn positive(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|_| format!("not a number: {s}"))?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("must be finite and > 0, got {s}"))
    }
}

/// A finite number ≥ 0.
pub fn non_negative(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|_| format!("not a number: {s}"))?;
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(format!("must be finite and >= 0, got {s}"))
    }
}

/// A grid of `n` points from `lo` (`lo_flag`) to `hi` (`hi_flag`) runs upwards: a reversed
/// range ran, silently, on a reversed grid (`oc --ptp-min 5 --ptp-max 1`).
pub fn ascending(lo_flag: &str, lo: f64, hi_flag: &str, hi: f64, n: usize) -> Result<(), String> {
    if n > 1 && lo >= hi {
        return Err(format!("{lo_flag} ({lo}) must be below {hi_flag} ({hi})"));
    }
    Ok(())
}

/// Levels linear from 1 to `--level-max`: it is above 1 (0.5 gave the levels 1 … 0.5, below
/// the level at which a block starts to rock).
pub fn levels_from_one(level_max: f64, n: usize) -> Result<(), String> {
    if n > 1 && level_max <= 1.0 {
        return Err(format!(
            "--level-max ({level_max}) must be above 1 (the levels run linearly from 1)"
        ));
    }
    Ok(())
}

/// A count ≥ 1.
pub fn count(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!("must be a whole number >= 1, got {s}")),
    }
}

/// `--threads N`: a count from 1 to [`rocking::validate::MAX_THREADS`] (`--threads 1000000`
/// had rayon start a million threads, and the process was killed).
pub fn threads(s: &str) -> Result<usize, String> {
    let max = rocking::validate::MAX_THREADS;
    match count(s) {
        Ok(n) if n <= max => Ok(n),
        _ => Err(format!("must be a whole number from 1 to {max}, got {s}")),
    }
}

/// A grid count (levels, sizes, pulse periods, radii): from 1 to
/// [`rocking::validate::MAX_GRID_POINTS`] (`--levels 1000000000` allocated an 8 GB grid and the
/// process aborted under a memory limit).
pub fn grid_count(s: &str) -> Result<usize, String> {
    let max = rocking::validate::MAX_GRID_POINTS;
    match count(s) {
        Ok(n) if n <= max => Ok(n),
        _ => Err(format!(
            "must be a whole number from 1 to {max} (grid points, one simulation or more each), got {s}"
        )),
    }
}

/// `--shard i/n`: keep the items whose index `k` has `k % n == i`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// The whole sweep.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// The items of `items` in this shard, in their order.
    pub fn keep<T: Clone>(&self, items: &[T]) -> Vec<T> {
        items
            .iter()
            .enumerate()
            .filter(|(k, _)| k % self.count == self.index)
            .map(|(_, x)| x.clone())
            .collect()
    }
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Shard, String> {
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("expected i/n, got {s}"))?;
        let index: usize = i.parse().map_err(|_| format!("bad index {i}"))?;
        let count: usize = n.parse().map_err(|_| format!("bad count {n}"))?;
        if count == 0 || index >= count {
            return Err(format!("need 0 <= i < n, got {index}/{count}"));
        }
        Ok(Shard { index, count })
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// Sizes rayon's global pool for the sweeps (`--threads N`). Results do not depend on it; only
/// the first call in a process can set the pool, later ones are ignored.
pub fn set_threads(n: usize) {
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build_global();
}

/// Units of a plain-text record.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum RecordUnits {
    /// m/s² (the default).
    #[value(name = "m/s2")]
    MetresPerSecondSquared,
    /// In g (9.81 m/s²).
    G,
    /// cm/s² (gal).
    #[value(name = "cm/s2", alias = "gal")]
    CentimetresPerSecondSquared,
}

/// How a plain-text record is read: its units and, for one column, its step (a PEER `.AT2`
/// states both: in g, with its own DT).
#[derive(Args, Clone, Debug, Default)]
pub struct RecordFormatArgs {
    /// Units of a plain-text record (an .AT2 is in g)
    #[arg(long, value_enum, value_name = "UNITS")]
    pub units: Option<RecordUnits>,
    /// Time step of a one-column plain-text record [s] (with two columns it must agree with the
    /// time column; an .AT2 states its own)
    #[arg(long, value_parser = positive, value_name = "SECONDS")]
    pub record_dt: Option<f64>,
}

impl RecordFormatArgs {
    /// The plain-text format, or an error naming the option an `.AT2` record does not take.
    fn format(&self, path: &Path) -> Result<PlainFormat, String> {
        if rocking::ground::records::is_at2(path) {
            if self.units.is_some_and(|u| u != RecordUnits::G) {
                return Err(format!(
                    "--units: {} is a PEER .AT2 record, in g; other units are for plain-text records",
                    path.display()
                ));
            }
            if self.record_dt.is_some() {
                return Err(format!(
                    "--record-dt: {} is a PEER .AT2 record, which states its own step",
                    path.display()
                ));
            }
        }
        let format = PlainFormat {
            dt: self.record_dt,
            ..PlainFormat::default()
        };
        Ok(match self.units {
            None | Some(RecordUnits::MetresPerSecondSquared) => format,
            Some(RecordUnits::G) => format.in_g(),
            Some(RecordUnits::CentimetresPerSecondSquared) => PlainFormat {
                scale: 0.01,
                ..format
            },
        })
    }
}

/// Reads a record (PEER `.AT2`, or plain text in m/s² unless `--units` says otherwise). A `.json`
/// file that does not parse as a record is most likely a report given where a record was
/// expected: the error says so.
pub fn read(path: &Path, format: &RecordFormatArgs) -> Result<Record, String> {
    read_record(path, &format.format(path)?).map_err(|e| {
        if let RecordError::InvalidArgument { field: "dt", message } = &e {
            // The step of a plain-text record: the command's option.
            return format!("--record-dt: {message}");
        }
        let json = path
            .extension()
            .is_some_and(|x| x.to_string_lossy().eq_ignore_ascii_case("json"));
        if json {
            format!("{e} (records are .AT2 or plain text in m/s², not JSON reports; `suite`, `t1` and `oas` join reports with --merge)")
        } else {
            e.to_string()
        }
    })
}

/// Reads every record of a `t1` or `suite` run before the first spectrum is computed, each
/// with its file: a missing, malformed or all-zero file among many is refused at once, not
/// after the spectra of the records before it (an hour into a suite of 44).
pub fn read_all(
    paths: &[PathBuf],
    format: &RecordFormatArgs,
) -> Result<Vec<(PathBuf, Record)>, String> {
    paths
        .iter()
        .map(|path| {
            let record = read(path, format)?;
            if record.pga() == 0.0 {
                return Err(format!(
                    "{}: the record is zero everywhere (no peak to scale to the levels)",
                    path.display()
                ));
            }
            Ok((path.clone(), record))
        })
        .collect()
}

/// The settings of every simulation of a sweep.
#[derive(Args, Debug)]
pub struct SimulationArgs {
    /// Consecutive impacts per closing (1: Housner; 2: the thesis's recommended model).
    #[arg(long, default_value_t = 1, value_parser = count)]
    pub impacts: usize,
    /// Factor on the time step rule.
    #[arg(long = "dt-factor", default_value_t = 1.0, value_parser = positive)]
    pub dt_factor: f64,
    /// Simulated time after the motion ends, in units of 1/p [default: the library's].
    #[arg(long, value_parser = non_negative)]
    pub tail: Option<f64>,
    /// Hermite event location (events refined by re-integration).
    #[arg(long)]
    pub hermite: bool,
    /// RK4 with Hermite event location.
    #[arg(long)]
    pub rk4: bool,
    /// Run every simulation to its end (by default a single block stops as soon as an energy
    /// bound proves that the rest of the motion cannot tip it: the same verdicts, faster; with
    /// --lagrangian so do columns of 2 or 3 equal blocks with H/B 3–12, whose bound is
    /// certified, see docs/column-early-stop.md).
    #[arg(long = "full-runs")]
    pub full_runs: bool,
    /// The exact Lagrangian equations of motion (thesis Eq. 6 plus the velocity terms), which
    /// conserve energy between events.
    #[arg(long)]
    pub lagrangian: bool,
    /// With --lagrangian, any column of several blocks: stop a run as soon as an energy bound
    /// says the rest of the record cannot tip the column. Already the default where the bound
    /// is certified (2 or 3 equal blocks, H/B 3–12); elsewhere UNPROVEN
    /// (docs/column-early-stop.md; check with `rocking bench spectra --compare`).
    #[arg(long = "column-bound", requires = "lagrangian")]
    pub column_bound: bool,
    /// Threads [default: every core]; the results do not depend on it.
    #[arg(long, value_parser = threads)]
    pub threads: Option<usize>,
}

impl SimulationArgs {
    /// Writes these settings into `s` (and sizes the thread pool).
    pub fn apply(&self, s: &mut SweepOptions) {
        if let Some(n) = self.threads {
            set_threads(n);
        }
        s.simulation.physics.model.n_impacts = self.impacts as u32;
        s.time_step = s.time_step.scaled(self.dt_factor);
        if let Some(tail) = self.tail {
            s.tail = tail;
        }
        if self.hermite || self.rk4 {
            s.simulation.stepping.locator = EventLocator::Hermite;
        }
        if self.rk4 {
            s.simulation.stepping.integrator = Integrator::Rk4;
        }
        // Same verdicts either way (tested); only for checking that claim, or timing it.
        s.simulation.stopping.stop_when_safe = !self.full_runs;
        s.simulation.physics.exact_velocity_terms = self.lagrangian;
        s.simulation.stopping.stop_when_safe_column = self.column_bound && !self.full_runs;
    }
}

/// The grid of an OAS: levels, sizes, column.
#[derive(Args, Debug)]
pub struct OasGridArgs {
    /// H/B of the equivalent monolith (thesis: 12).
    #[arg(long, default_value_t = 12.0, value_parser = positive)]
    pub slenderness: f64,
    /// Number of levels a_p / a_p,min, linear from 1 to --level-max (thesis: 80).
    #[arg(long, default_value_t = 80, value_parser = grid_count)]
    pub levels: usize,
    /// Highest level a_p / a_p,min.
    #[arg(long = "level-max", default_value_t = 10.0, value_parser = positive)]
    pub level_max: f64,
    /// Number of sizes R, log-spaced from --size-max down to --size-min (thesis: 120).
    #[arg(long, default_value_t = 120, value_parser = grid_count)]
    pub sizes: usize,
    /// Smallest size R [m].
    #[arg(long = "size-min", default_value_t = 0.1, value_parser = positive)]
    pub size_min: f64,
    /// Largest size R [m].
    #[arg(long = "size-max", default_value_t = 1000.0, value_parser = positive)]
    pub size_max: f64,
    /// Equal blocks in the column (1: a single block).
    #[arg(long, default_value_t = 1, value_parser = count)]
    pub blocks: usize,
    /// Bisection on the size instead of the thesis's scan from the largest size.
    #[arg(long)]
    pub bisection: bool,
    /// How each OAS is computed where the thesis does not say (docs/t1-table.md, "Procedure
    /// variants"); --tail and --dt-factor still apply on top.
    #[arg(long, value_enum, default_value_t = Procedure::Converged)]
    pub procedure: Procedure,
}

/// A way of computing an OAS that the thesis could have used: it states neither its time step,
/// nor whether a run ends with the record, nor how its 80 levels are spaced. Each variant changes
/// one of these choices of the default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Procedure {
    /// The default, converged for accuracy: the whole record and 2/p of free rocking after it,
    /// dt = min(record dt / 4, 1/(100 p)), 80 linear levels 1…10 with both ends.
    #[default]
    Converged,
    /// The run ends with the record: no free rocking after the last sample.
    RecordEnd,
    /// The run ends 2/p after the last instant at which the scaled record reaches the uplift
    /// acceleration (the end of the strong motion for that column), not with the record.
    StrongMotion,
    /// Wilson θ at the record's own sample interval: dt = record dt, whatever the block.
    RecordDt,
    /// 80 linear levels without the lower end: 1 + 9k/80, k = 1…80 (a_p = a_p,min left out).
    LevelsOpen,
    /// 80 levels log-spaced from 1 to 10.
    LevelsLog,
}

impl Procedure {
    /// The name on the command line.
    pub fn name(self) -> String {
        self.to_possible_value()
            .map_or_else(String::new, |v| v.get_name().to_string())
    }

    /// Writes this procedure's choices into `o` (built from the default's), for `n` levels up
    /// to `level_max`.
    fn apply(self, o: &mut OasOptions, n: usize, level_max: f64) {
        match self {
            Procedure::Converged => {}
            Procedure::RecordEnd => o.sweep.tail = 0.0,
            Procedure::StrongMotion => o.sweep.cut_after_last_exceedance = true,
            Procedure::RecordDt => {
                o.sweep.time_step = TimeStep {
                    record_fraction: 1.0,
                    // 1e6 / p exceeds any record's dt: only the record's dt is left.
                    block_fraction: 1e6,
                    ..o.sweep.time_step
                }
            }
            Procedure::LevelsOpen => {
                o.levels = (1..=n)
                    .map(|k| 1.0 + (level_max - 1.0) * k as f64 / n as f64)
                    .collect();
            }
            Procedure::LevelsLog => {
                o.levels = log_sizes(level_max, 1.0, n);
                o.levels.reverse();
            }
        }
    }
}

impl OasGridArgs {
    /// The OAS options of this grid with `simulation`'s settings; a reversed range of sizes
    /// or levels is refused naming its arguments (the library's check said `sizes: must be
    /// strictly decreasing`, and levels 1 … 0.5 ran).
    pub fn options(&self, simulation: &SimulationArgs) -> Result<OasOptions, String> {
        ascending(
            "--size-min",
            self.size_min,
            "--size-max",
            self.size_max,
            self.sizes,
        )?;
        levels_from_one(self.level_max, self.levels)?;
        let mut o = OasOptions {
            slenderness: self.slenderness,
            levels: linear_levels(1.0, self.level_max, self.levels),
            sizes: log_sizes(self.size_max, self.size_min, self.sizes),
            n_blocks: self.blocks,
            search: if self.bisection {
                SizeSearch::Bisection
            } else {
                SizeSearch::Scan
            },
            ..OasOptions::default()
        };
        self.procedure.apply(&mut o, self.levels, self.level_max);
        simulation.apply(&mut o.sweep);
        Ok(o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_items() {
        let items: Vec<usize> = (0..7).collect();
        let s: Shard = "1/3".parse().unwrap();
        assert_eq!(s.keep(&items), vec![1, 4]);
        assert_eq!(Shard::WHOLE.keep(&items), items);
        for bad in ["3/3", "1", "a/2", "0/0", "-1/2"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }
}
