//! The overturning acceleration spectrum (OAS) of a record (thesis Fig. 36, 37, 43): for each
//! level `a_p / a_p,min`, the largest column of the size grid that the scaled record overturns.

use super::sweep::map_indexed;
use super::{at_least_one_block, column_of_size, invalid, Progress, SpectraError, SweepOptions};
use crate::driver::{overturns_with, RunOptions};
use crate::ground::records::Record;
use crate::ground::GroundMotion;
use crate::model::single_block::{self, EquivalentBlock};
use crate::validate::{all_positive, positive};

/// `n` levels `a_p / a_p,min` equally spaced from `lo` to `hi` (both included).
pub fn linear_levels(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![lo],
        _ => (0..n)
            .map(|k| lo + (hi - lo) * k as f64 / (n - 1) as f64)
            .collect(),
    }
}

/// `n` sizes `R` log-spaced from `largest` down to `smallest` (both included), descending.
pub fn log_sizes(largest: f64, smallest: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![largest],
        _ => {
            let (a, b) = (largest.ln(), smallest.ln());
            (0..n)
                .map(|k| (a + (b - a) * k as f64 / (n - 1) as f64).exp())
                .collect()
        }
    }
}

/// How the largest unsafe size is searched for at each level.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SizeSearch {
    /// The thesis's search: from the largest size down, stop at the first that overturns.
    /// Exact on the grid (islands of unsafe sizes included).
    #[default]
    Scan,
    /// APPROXIMATE: bisection between the largest size (assumed safe) and the smallest (assumed
    /// unsafe) as if overturning were monotonic in size; ~7 simulations per level instead of up
    /// to 120, but it can miss the largest unsafe size when safe and unsafe sizes alternate
    /// (islands). See `docs/spectra.md` for how often it differs.
    Bisection,
}

/// Options of an OAS. [`OasOptions::default`] is the thesis's grid.
#[derive(Clone, Debug, PartialEq)]
pub struct OasOptions {
    /// `H/B` of the equivalent block (thesis: 12).
    pub slenderness: f64,
    /// Levels `a_p / a_p,min` (thesis: 80 from 1 to 10).
    pub levels: Vec<f64>,
    /// Sizes `R` \[m\], scanned in this order (thesis: 120 log-spaced from 1000 m to 0.1 m).
    pub sizes: Vec<f64>,
    /// Number of equal blocks in the column (1 = single block).
    pub n_blocks: usize,
    /// Search for the largest unsafe size.
    pub search: SizeSearch,
    /// Simulation options.
    pub sweep: SweepOptions,
}

impl Default for OasOptions {
    fn default() -> OasOptions {
        OasOptions {
            slenderness: 12.0,
            levels: linear_levels(1.0, 10.0, 80),
            sizes: log_sizes(1000.0, 0.1, 120),
            n_blocks: 1,
            search: SizeSearch::Scan,
            sweep: SweepOptions::default(),
        }
    }
}

impl OasOptions {
    /// The same options with the time step rule scaled by `factor` (`0.5`: half the step).
    pub fn at_step(&self, factor: f64) -> OasOptions {
        let mut o = self.clone();
        o.sweep.time_step = o.sweep.time_step.scaled(factor);
        o
    }

    pub(super) fn validate(&self) -> Result<(), SpectraError> {
        self.sweep.validate()?;
        positive("slenderness", self.slenderness)?;
        all_positive("levels", &self.levels)?;
        if self.sizes.is_empty() {
            return Err(invalid("sizes", "needs at least one size"));
        }
        all_positive("sizes", &self.sizes)?;
        if self.sizes.windows(2).any(|w| w[1] >= w[0]) {
            return Err(invalid(
                "sizes",
                "must be strictly decreasing (largest first)",
            ));
        }
        at_least_one_block(self.n_blocks)?;
        Ok(())
    }
}

/// Whether the column of size `size` overturns under `record` scaled to `level · a_p,min`.
pub fn record_overturns(
    record: &Record,
    level: f64,
    size: f64,
    options: &OasOptions,
) -> Result<bool, SpectraError> {
    PreparedRecord::new(record)?.overturns(level, size, options)
}

/// A record with what every simulation of a sweep over it reads: its PGA and its tail
/// impulses ([`Record::impulse_table`]), computed once.
pub(super) struct PreparedRecord<'a> {
    record: &'a Record,
    pga: f64,
    impulses: Vec<f64>,
}

/// One point of a sweep over a record, ready to run: the column, the scaled record started at
/// `t0` and the run's options.
pub(super) struct PointSetup<'a> {
    pub column: crate::model::column::Column,
    pub motion: ScaledRecord<'a>,
    pub run: RunOptions<'a>,
    /// Record time at which the simulation starts (the sample before the first exceedance).
    pub t0: f64,
    /// Record time of the sample after the last exceedance of the uplift acceleration.
    pub t_last: f64,
}

impl<'a> PreparedRecord<'a> {
    pub(super) fn new(record: &'a Record) -> Result<PreparedRecord<'a>, SpectraError> {
        let pga = record.pga();
        if pga.is_nan() || pga <= 0.0 {
            return Err(invalid("record", format!("`{}` has zero PGA", record.name)));
        }
        Ok(PreparedRecord {
            record,
            pga,
            impulses: record.impulse_table(),
        })
    }

    /// The run of the column of size `size` under the record scaled to `level · a_p,min`;
    /// `None` when the scaled record never reaches the uplift acceleration (the column never
    /// moves).
    pub(super) fn setup<'o>(
        &'o self,
        level: f64,
        size: f64,
        options: &'o OasOptions,
    ) -> Result<Option<PointSetup<'o>>, SpectraError> {
        let record = self.record;
        let column = column_of_size(size, options.slenderness, options.n_blocks)?;
        let g = options.sweep.simulation.physics.gravity;
        let block = EquivalentBlock::of_column(&column);
        let factor = level * block.a_p_min(g) / self.pga;
        let p = block.frequency_parameter(g);
        let Some((t0, t_last)) =
            exceedance_window(record, factor, column.static_uplift_acceleration(g))
        else {
            return Ok(None);
        };
        let motion = ScaledRecord {
            record,
            factor,
            t0,
            impulses: &self.impulses,
        };
        let dt = options.sweep.time_step.dt(Some(record.dt), None, p);
        let end = if options.sweep.cut_after_last_exceedance {
            t_last - t0
        } else {
            motion.end_time()
        };
        let tail = options.sweep.tail / p;
        let mut run = options.sweep.simulation(dt, end + tail);
        // After the last exceedance a closed column can never lift off again: stop there
        // (exact).
        run.stopping.quiet_after = Some(t_last - t0);
        Ok(Some(PointSetup {
            column,
            motion,
            run,
            t0,
            t_last,
        }))
    }

    /// [`record_overturns`].
    pub(super) fn overturns(
        &self,
        level: f64,
        size: f64,
        options: &OasOptions,
    ) -> Result<bool, SpectraError> {
        Ok(match self.setup(level, size, options)? {
            None => false,
            Some(s) => overturns_with(&s.column, &s.motion, s.run)?,
        })
    }
}

/// One level of an OAS.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OasLevel {
    /// `a_p / a_p,min`.
    pub level: f64,
    /// Index in [`Oas::sizes`] of the largest unsafe size (`None`: no size of the grid
    /// overturns).
    pub largest_unsafe: Option<usize>,
    /// Simulations run for this level.
    pub simulations: usize,
}

/// A point of the OAS boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OasPoint {
    /// `a_p / a_p,min`.
    pub level: f64,
    /// Largest unsafe size `R` \[m\].
    pub size: f64,
    /// Its `p` \[1/s\].
    pub p: f64,
    /// Transformed coordinate `f = p a_p / a_p,min` \[1/s\] (Eq. 19).
    pub f: f64,
}

/// The overturning acceleration spectrum of a record (thesis Fig. 36, 37, 43).
#[derive(Clone, Debug, PartialEq)]
pub struct Oas {
    /// Record name.
    pub record: String,
    /// `H/B`.
    pub slenderness: f64,
    /// Blocks in the column.
    pub n_blocks: usize,
    /// Consecutive impacts of the impact model.
    pub n_impacts: u32,
    /// Search used.
    pub search: SizeSearch,
    /// Size grid \[m\], descending.
    pub sizes: Vec<f64>,
    /// One entry per level, in the order of the options.
    pub levels: Vec<OasLevel>,
    /// Acceleration of gravity used \[m/s²\].
    pub gravity: f64,
}

impl Oas {
    /// The equivalent block of size `size` (its `p` and `a_p,min` under [`Oas::gravity`]).
    pub fn block(&self, size: f64) -> EquivalentBlock {
        EquivalentBlock::of_size(size, self.slenderness)
    }

    /// `i_cr` of the slenderness (Eq. 18).
    pub fn i_cr(&self) -> f64 {
        single_block::normalised_critical_impulse((1.0 / self.slenderness).atan())
    }

    /// The boundary: for each level with an unsafe size, the largest unsafe size, its `p` and
    /// `f = p · level` (the OAS of Fig. 36 and the transformed OAS of Fig. 37b).
    pub fn boundary(&self) -> Vec<OasPoint> {
        self.levels
            .iter()
            .filter_map(|l| {
                let i = l.largest_unsafe?;
                let size = self.sizes[i];
                let p = self.block(size).frequency_parameter(self.gravity);
                Some(OasPoint {
                    level: l.level,
                    size,
                    p,
                    f: p * l.level,
                })
            })
            .collect()
    }

    /// Total simulations.
    pub fn simulations(&self) -> usize {
        self.levels.iter().map(|l| l.simulations).sum()
    }
}

/// A record scaled by `factor` and started at `t0` (the time before which the column cannot
/// have moved).
pub(super) struct ScaledRecord<'a> {
    record: &'a Record,
    factor: f64,
    t0: f64,
    /// [`Record::impulse_table`] of `record`.
    impulses: &'a [f64],
}

impl GroundMotion for ScaledRecord<'_> {
    fn acceleration(&self, t: f64) -> f64 {
        self.factor * self.record.acceleration(t + self.t0)
    }
    fn end_time(&self) -> f64 {
        (self.record.duration() - self.t0).max(0.0)
    }
    fn remaining_impulse(&self, t: f64) -> Option<f64> {
        Some(self.factor.abs() * self.record.impulse_after(self.impulses, t + self.t0))
    }
}

/// Times of the sample before the first one and of the sample after the last one whose scaled
/// absolute value reaches `threshold` (`None`: the column never lifts off). With linear
/// interpolation `|a| < threshold` outside that window.
pub(super) fn exceedance_window(
    record: &Record,
    factor: f64,
    threshold: f64,
) -> Option<(f64, f64)> {
    let limit = threshold * (1.0 - 1e-9);
    let hit = |a: &f64| (factor * a).abs() >= limit;
    let first = record.samples.iter().position(hit)?;
    let last = record.samples.iter().rposition(hit)?;
    let last = (last + 1).min(record.samples.len() - 1);
    Some((
        first.saturating_sub(1) as f64 * record.dt,
        last as f64 * record.dt,
    ))
}

fn search_level(
    record: &PreparedRecord<'_>,
    level: f64,
    options: &OasOptions,
) -> Result<OasLevel, SpectraError> {
    let sizes = &options.sizes;
    let mut sims = 0;
    let mut test = |i: usize| {
        sims += 1;
        record.overturns(level, sizes[i], options)
    };
    let largest_unsafe = match options.search {
        SizeSearch::Scan => {
            let mut found = None;
            for i in 0..sizes.len() {
                if test(i)? {
                    found = Some(i);
                    break;
                }
            }
            found
        }
        SizeSearch::Bisection => {
            let last = sizes.len() - 1;
            if !test(last)? {
                None
            } else if last == 0 || test(0)? {
                Some(0)
            } else {
                let (mut safe, mut unsafe_) = (0, last);
                while unsafe_ - safe > 1 {
                    let mid = (safe + unsafe_) / 2;
                    if test(mid)? {
                        unsafe_ = mid;
                    } else {
                        safe = mid;
                    }
                }
                Some(unsafe_)
            }
        }
    };
    Ok(OasLevel {
        level,
        largest_unsafe,
        simulations: sims,
    })
}

/// The OAS of `record`, parallel over levels with the `parallel` feature (bitwise identical
/// results with any number of threads). `progress` is called after each level.
pub fn oas(
    record: &Record,
    options: &OasOptions,
    progress: Option<Progress<'_>>,
) -> Result<Oas, SpectraError> {
    options.validate()?;
    record.validate()?;
    let prepared = PreparedRecord::new(record)?;
    let levels = map_indexed(options.levels.len(), |k| {
        let r = search_level(&prepared, options.levels[k], options);
        if let Some(p) = progress {
            p();
        }
        r
    });
    Ok(Oas {
        record: record.name.clone(),
        slenderness: options.slenderness,
        n_blocks: options.n_blocks,
        n_impacts: options.sweep.simulation.physics.model.n_impacts,
        search: options.search,
        sizes: options.sizes.clone(),
        levels: levels.into_iter().collect::<Result<_, _>>()?,
        gravity: options.sweep.simulation.physics.gravity,
    })
}
