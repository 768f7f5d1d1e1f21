//! Overturning spectra (thesis Chapter 5; SPEC §7): overturning curves (OC) of pulses, the
//! overturning acceleration spectrum (OAS) of a record, its transformed form (Eq. 19), the
//! replacement impulse duration `t_1` (Eq. 20), the improved fits `t_1'`, `β` (Eq. 28–30) and a
//! check that the simplified spectra (Eq. 21, 29, 30) are conservative against the computed one.
//!
//! Every point is one time history of the reference driver ([`crate::driver::overturns`]):
//! a column of rigid blocks, at rest and closed, under the scaled motion; *unsafe* means the
//! driver reports overturning (static tipping of the part above some interface, SPEC §5; with
//! `continue_until_fallen`, a block rotated by `π/2`).
//!
//! Axes. A column is described by its *equivalent monolith* ([`Monolith`]): the bottom block's
//! width `B`, the total height `H`, `tan δ = B/H`, `R = ½√(B² + H²)`, `p = √(g/(αR))`,
//! `α = 4/3`, `a_p,min = g tan δ` (Eq. 3, 13). For a single uniform block these are exact; for a
//! stack of equal-width blocks they are the axes of thesis Fig. 40/43 (the column "has the same
//! aspect ratio" as the monolith).
//!
//! Time step ([`TimeStep`]): `dt = min(record_fraction · Δt_record, pulse_fraction · t_p,
//! block_fraction / p)`; convergence in `dt` is shown in `docs/spectra.md` and tested.
//!
//! Sweeps are parallel over levels (OAS) or pulse durations (OC) with the `parallel` feature;
//! every point is computed independently of the others and results are collected in order, so
//! they are bitwise identical whatever the number of threads.

use std::fmt;

use crate::driver::{overturns, DriverError, Recording, SimulationOptions};
use crate::ground::excitation::{ExcitationError, Pulse};
use crate::ground::records::Record;
use crate::ground::GroundMotion;
use crate::model::column::{Block, Column, ColumnError};
use crate::model::single_block::{self, ALPHA_UNIFORM};

/// Why a sweep could not run.
#[derive(Clone, Debug, PartialEq)]
pub enum SpectraError {
    /// An option is invalid.
    InvalidOption {
        /// Field name.
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// A column could not be built.
    Column(ColumnError),
    /// A pulse could not be built.
    Excitation(ExcitationError),
    /// A time history failed.
    Driver(DriverError),
}

impl fmt::Display for SpectraError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpectraError::InvalidOption { field, reason } => write!(f, "{field}: {reason}"),
            SpectraError::Column(e) => write!(f, "column: {e}"),
            SpectraError::Excitation(e) => write!(f, "pulse: {e}"),
            SpectraError::Driver(e) => write!(f, "simulation: {e}"),
        }
    }
}

impl std::error::Error for SpectraError {}

impl From<ColumnError> for SpectraError {
    fn from(e: ColumnError) -> SpectraError {
        SpectraError::Column(e)
    }
}
impl From<ExcitationError> for SpectraError {
    fn from(e: ExcitationError) -> SpectraError {
        SpectraError::Excitation(e)
    }
}
impl From<DriverError> for SpectraError {
    fn from(e: DriverError) -> SpectraError {
        SpectraError::Driver(e)
    }
}

fn invalid(field: &'static str, reason: impl Into<String>) -> SpectraError {
    SpectraError::InvalidOption {
        field,
        reason: reason.into(),
    }
}

// ---------------------------------------------------------------------------------------------
// Geometry.

/// The equivalent monolith of a column: the axes of the OC and OAS (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Monolith {
    /// Width `B` of the bottom block \[m\].
    pub width: f64,
    /// Total height `H` \[m\].
    pub height: f64,
    /// Slenderness angle `δ`, `tan δ = B/H` \[rad\].
    pub delta: f64,
    /// `R = ½√(B² + H²)` \[m\].
    pub r: f64,
    /// Frequency parameter `p = √(g/(αR))`, `α = 4/3` \[1/s\] (Eq. 13).
    pub p: f64,
    /// `a_p,min = g tan δ` \[m/s²\] (Eq. 3).
    pub a_p_min: f64,
    /// `i_cr = √(2/(1 + cos δ))` (Eq. 18).
    pub i_cr: f64,
}

impl Monolith {
    /// The equivalent monolith of `column` under gravity `g`.
    pub fn of(column: &Column, g: f64) -> Monolith {
        let width = column.blocks()[0].width;
        let height = column.total_height();
        let delta = single_block::slenderness_angle(width, height);
        let r = single_block::corner_distance(width, height);
        Monolith {
            width,
            height,
            delta,
            r,
            p: single_block::frequency_parameter(r, ALPHA_UNIFORM, g),
            a_p_min: single_block::a_p_min(delta, g),
            i_cr: single_block::normalised_critical_impulse(delta),
        }
    }
}

/// A column of `n_blocks` equal uniform blocks whose equivalent monolith has slenderness
/// `H/B = slenderness` and size `R = ½√(B² + H²) = size` \[m\] (unit total mass: overturning does
/// not depend on it).
pub fn column_of_size(
    size: f64,
    slenderness: f64,
    n_blocks: usize,
) -> Result<Column, SpectraError> {
    if !(size.is_finite() && size > 0.0) {
        return Err(invalid(
            "size",
            format!("must be finite and > 0, got {size}"),
        ));
    }
    if !(slenderness.is_finite() && slenderness > 0.0) {
        return Err(invalid(
            "slenderness",
            format!("must be finite and > 0, got {slenderness}"),
        ));
    }
    if n_blocks == 0 {
        return Err(invalid("n_blocks", "a column needs at least one block"));
    }
    let width = 2.0 * size / (1.0 + slenderness * slenderness).sqrt();
    let height = slenderness * width;
    let n = n_blocks as f64;
    Ok(Column::new(
        (0..n_blocks)
            .map(|_| Block::rectangle(width, height / n, 1.0 / n))
            .collect(),
    )?)
}

/// The smallest ground acceleration that lifts some part of the column off its interface,
/// `min_k g b_k / h_k` with `h_k` the height of the centre of mass of the part above interface
/// `k` over that interface (straight, centred blocks). Below it in absolute value, the column
/// moves with the ground.
pub fn uplift_acceleration(column: &Column, g: f64) -> f64 {
    let blocks = column.blocks();
    let n = blocks.len();
    let mut best = f64::INFINITY;
    for k in 0..n {
        let base: f64 = blocks[..k].iter().map(|b| b.height).sum();
        let mut y = base;
        let (mut m, mut my) = (0.0, 0.0);
        for b in &blocks[k..] {
            m += b.mass;
            my += b.mass * (y + 0.5 * b.height - base);
            y += b.height;
        }
        best = best.min(g * column.half_contact_width(k) / (my / m));
    }
    best
}

// ---------------------------------------------------------------------------------------------
// Options common to the sweeps.

/// How the time step of each simulation is chosen:
/// `dt = min(record_fraction · Δt_record, pulse_fraction · t_p, block_fraction / p)`
/// (the terms that do not apply are left out).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeStep {
    /// Fraction of the record's sample interval.
    pub record_fraction: f64,
    /// Fraction of the pulse's duration parameter `t_p` (OC).
    pub pulse_fraction: f64,
    /// Fraction of the column's `1/p`.
    pub block_fraction: f64,
}

impl Default for TimeStep {
    /// `min(Δt_record / 2, t_p / 100, 1/(50 p))`: converged for `t_1` on the bundled record (see
    /// `docs/spectra.md` and the test `t1_converged_in_dt`).
    fn default() -> TimeStep {
        TimeStep {
            record_fraction: 0.5,
            pulse_fraction: 0.01,
            block_fraction: 0.02,
        }
    }
}

impl TimeStep {
    /// The same rule with every fraction multiplied by `factor` (convergence studies).
    pub fn scaled(&self, factor: f64) -> TimeStep {
        TimeStep {
            record_fraction: self.record_fraction * factor,
            pulse_fraction: self.pulse_fraction * factor,
            block_fraction: self.block_fraction * factor,
        }
    }

    /// The time step for a record of sample interval `record_dt` (or a pulse of duration
    /// parameter `t_p`) and a column of frequency parameter `p`.
    pub fn dt(&self, record_dt: Option<f64>, t_p: Option<f64>, p: f64) -> f64 {
        let mut dt = self.block_fraction / p;
        if let Some(d) = record_dt {
            dt = dt.min(self.record_fraction * d);
        }
        if let Some(t) = t_p {
            dt = dt.min(self.pulse_fraction * t);
        }
        dt
    }

    fn validate(&self) -> Result<(), SpectraError> {
        for (field, v) in [
            ("time_step.record_fraction", self.record_fraction),
            ("time_step.pulse_fraction", self.pulse_fraction),
            ("time_step.block_fraction", self.block_fraction),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(field, format!("must be finite and > 0, got {v}")));
            }
        }
        Ok(())
    }
}

/// Options shared by the OC and OAS sweeps.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepOptions {
    /// Template of every simulation: integrator, event locator, impact model (`model.n_impacts`:
    /// 1 = Housner, 2 = the thesis's recommended model, 10 ≈ rolling), friction, gravity,
    /// overturning criterion. `dt` and `duration` are overwritten per simulation and `record`
    /// by [`Recording::NONE`].
    pub simulation: SimulationOptions,
    /// Time step rule.
    pub time_step: TimeStep,
    /// Simulated time after the motion ends, in units of `1/p` (a column still rocking when the
    /// motion ends may yet tip over).
    pub tail: f64,
    /// Records: end each simulation `tail / p` after the last instant at which the scaled record
    /// reaches the uplift acceleration, instead of after the end of the record. After that
    /// instant a column at rest can no longer lift off, and one still rocking is driven only by
    /// accelerations below `a_p,min` for the rest of the record, which it can survive the tail
    /// of but, in principle, not always the whole coda: an approximation that saves the weak
    /// codas of long records. `false` simulates the whole record.
    pub cut_after_last_exceedance: bool,
}

impl Default for SweepOptions {
    /// Driver defaults (Wilson θ = 1.4, linear event location, Housner impacts, static tipping),
    /// except friction: infinite (the thesis does not check sliding), and
    /// [`SimulationOptions::stop_when_safe`]: a single block that the rest of a record provably
    /// cannot tip stops early (same verdicts: `oas_energy_bound_changes_nothing` in the tests).
    fn default() -> SweepOptions {
        SweepOptions {
            simulation: SimulationOptions {
                friction: f64::INFINITY,
                record: Recording::NONE,
                stop_when_safe: true,
                ..SimulationOptions::default()
            },
            time_step: TimeStep::default(),
            tail: 2.0,
            cut_after_last_exceedance: false,
        }
    }
}

impl SweepOptions {
    fn validate(&self) -> Result<(), SpectraError> {
        self.time_step.validate()?;
        if !(self.tail.is_finite() && self.tail >= 0.0) {
            return Err(invalid(
                "tail",
                format!("must be finite and >= 0, got {}", self.tail),
            ));
        }
        Ok(())
    }

    fn simulation(&self, dt: f64, duration: f64) -> SimulationOptions {
        SimulationOptions {
            dt,
            duration,
            record: Recording::NONE,
            ..self.simulation.clone()
        }
    }
}

/// A record scaled by `factor` and started at `t0` (the time before which the column cannot
/// have moved).
struct ScaledRecord<'a> {
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
fn exceedance_window(record: &Record, factor: f64, threshold: f64) -> Option<(f64, f64)> {
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

/// `(0..n).map(f)` collected in order, in parallel with the `parallel` feature.
fn map_indexed<T: Send, F: Fn(usize) -> T + Sync + Send>(n: usize, f: F) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n).into_par_iter().map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        (0..n).map(f).collect()
    }
}

/// Called once per finished unit of work (a level of an OAS, a pulse duration of an OC).
pub type Progress<'a> = &'a (dyn Fn() + Sync);

// ---------------------------------------------------------------------------------------------
// Overturning curves of pulses.

/// The shape of a pulse family for an overturning curve; `t_p` is its duration parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PulseShape {
    /// `lobes` half sines of alternating sign; `t_p` = duration of one half sine (thesis Fig. 8:
    /// 1 = half sine, 2 = full sine, 3 = three half sines).
    HalfSines {
        /// Number of half sines.
        lobes: u32,
    },
    /// Rectangular pulse of duration `t_p`.
    Rectangular,
    /// Symmetric triangular pulse of duration `t_p`.
    Triangular,
    /// Ricker wavelet of peak frequency `1/t_p`.
    Ricker,
    /// Mavroeidis–Papageorgiou pulse of period `t_p` (frequency `1/t_p`).
    MavroeidisPapageorgiou {
        /// Oscillatory character `γ`.
        gamma: f64,
        /// Phase `ν` \[rad\].
        nu: f64,
    },
}

impl PulseShape {
    /// Half sine (thesis Fig. 8a, 33).
    pub const fn half_sine() -> PulseShape {
        PulseShape::HalfSines { lobes: 1 }
    }
    /// Full sine (thesis Fig. 8b, 39, 40).
    pub const fn full_sine() -> PulseShape {
        PulseShape::HalfSines { lobes: 2 }
    }
    /// Three half sines (thesis Fig. 8c).
    pub const fn three_half_sines() -> PulseShape {
        PulseShape::HalfSines { lobes: 3 }
    }

    /// The pulse of peak `a_p` \[m/s²\] and duration parameter `t_p` \[s\].
    pub fn pulse(&self, a_p: f64, t_p: f64) -> Result<Pulse, SpectraError> {
        Ok(match *self {
            PulseShape::HalfSines { lobes } => Pulse::half_sines(a_p, t_p, lobes)?,
            PulseShape::Rectangular => Pulse::rectangular(a_p, t_p)?,
            PulseShape::Triangular => Pulse::triangular(a_p, t_p)?,
            PulseShape::Ricker => Pulse::ricker(a_p, 1.0 / t_p)?,
            PulseShape::MavroeidisPapageorgiou { gamma, nu } => {
                Pulse::mavroeidis_papageorgiou(a_p, 1.0 / t_p, gamma, nu)?
            }
        })
    }

    /// A short name (`half-sine`, `full-sine`, `3-half-sines`, `rectangular`, …).
    pub fn name(&self) -> String {
        match *self {
            PulseShape::HalfSines { lobes: 1 } => "half-sine".into(),
            PulseShape::HalfSines { lobes: 2 } => "full-sine".into(),
            PulseShape::HalfSines { lobes } => format!("{lobes}-half-sines"),
            PulseShape::Rectangular => "rectangular".into(),
            PulseShape::Triangular => "triangular".into(),
            PulseShape::Ricker => "ricker".into(),
            PulseShape::MavroeidisPapageorgiou { gamma, nu } => format!("mp-g{gamma}-nu{nu}"),
        }
    }
}

/// Whether `column` overturns under the pulse `shape(a_p, t_p)` (one point of an OC).
pub fn pulse_overturns(
    column: &Column,
    shape: PulseShape,
    a_p: f64,
    t_p: f64,
    options: &SweepOptions,
) -> Result<bool, SpectraError> {
    options.validate()?;
    let g = options.simulation.gravity;
    let mono = Monolith::of(column, g);
    let pulse = shape.pulse(a_p, t_p)?;
    // Never lifts off: no simulation needed (the peak of every shape is |a_p|).
    if a_p.abs() < uplift_acceleration(column, g) * (1.0 - 1e-9) {
        return Ok(false);
    }
    let dt = options.time_step.dt(None, Some(t_p), mono.p);
    let sim = options.simulation(dt, pulse.end_time() + options.tail / mono.p);
    Ok(overturns(
        column,
        &crate::ground::excitation::Excitation::Pulse(pulse),
        &sim,
    )?)
}

/// An overturning curve: safe / unsafe on a grid of `(t_p, a_p)` (thesis Fig. 8, 33, 40, 41).
#[derive(Clone, Debug, PartialEq)]
pub struct Oc {
    /// Pulse shape.
    pub shape: PulseShape,
    /// Equivalent monolith of the column (normalisation).
    pub monolith: Monolith,
    /// Number of blocks.
    pub n_blocks: usize,
    /// Pulse durations `t_p` \[s\] (rows).
    pub t_p: Vec<f64>,
    /// Peak accelerations `a_p` \[m/s²\] (columns).
    pub a_p: Vec<f64>,
    /// `overturned[i * a_p.len() + j]`: the column overturns under `(t_p[i], a_p[j])`.
    pub overturned: Vec<bool>,
}

impl Oc {
    /// Whether `(t_p[i], a_p[j])` overturns the column.
    pub fn is_unsafe(&self, i: usize, j: usize) -> bool {
        self.overturned[i * self.a_p.len() + j]
    }

    /// Number of unsafe grid points.
    pub fn unsafe_count(&self) -> usize {
        self.overturned.iter().filter(|&&u| u).count()
    }

    /// The envelope: for each `t_p`, the smallest unsafe `a_p` of the grid (`None`: none
    /// overturns). Safe bays above it are ignored (thesis 1: "a single envelope can be used for
    /// design purposes").
    pub fn envelope(&self) -> Vec<Option<f64>> {
        (0..self.t_p.len())
            .map(|i| {
                (0..self.a_p.len())
                    .filter(|&j| self.is_unsafe(i, j))
                    .map(|j| self.a_p[j])
                    .reduce(f64::min)
            })
            .collect()
    }

    /// Normalised coordinates of every grid point: `(p t_p, a_p / a_p,min, unsafe)` (Fig. 33a).
    pub fn normalised(&self) -> Vec<(f64, f64, bool)> {
        let m = &self.monolith;
        let mut out = Vec::with_capacity(self.overturned.len());
        for (i, &t) in self.t_p.iter().enumerate() {
            for (j, &a) in self.a_p.iter().enumerate() {
                out.push((m.p * t, a / m.a_p_min, self.is_unsafe(i, j)));
            }
        }
        out
    }

    /// The envelope in normalised coordinates `(p t_p, a_p / a_p,min)`.
    pub fn normalised_envelope(&self) -> Vec<(f64, Option<f64>)> {
        let m = &self.monolith;
        self.t_p
            .iter()
            .zip(self.envelope())
            .map(|(&t, e)| (m.p * t, e.map(|a| a / m.a_p_min)))
            .collect()
    }
}

/// The overturning curve of `column` for `shape` on the grid `t_p × a_p`, parallel over `t_p`.
pub fn overturning_curve(
    column: &Column,
    shape: PulseShape,
    t_p: &[f64],
    a_p: &[f64],
    options: &SweepOptions,
    progress: Option<Progress<'_>>,
) -> Result<Oc, SpectraError> {
    options.validate()?;
    for &t in t_p {
        if !(t.is_finite() && t > 0.0) {
            return Err(invalid(
                "t_p",
                format!("durations must be finite and > 0, got {t}"),
            ));
        }
    }
    for &a in a_p {
        if !(a.is_finite() && a > 0.0) {
            return Err(invalid(
                "a_p",
                format!("amplitudes must be finite and > 0, got {a}"),
            ));
        }
    }
    let rows = map_indexed(t_p.len(), |i| {
        let row: Result<Vec<bool>, SpectraError> = a_p
            .iter()
            .map(|&a| pulse_overturns(column, shape, a, t_p[i], options))
            .collect();
        if let Some(p) = progress {
            p();
        }
        row
    });
    let mut overturned = Vec::with_capacity(t_p.len() * a_p.len());
    for row in rows {
        overturned.extend(row?);
    }
    Ok(Oc {
        shape,
        monolith: Monolith::of(column, options.simulation.gravity),
        n_blocks: column.n_interfaces(),
        t_p: t_p.to_vec(),
        a_p: a_p.to_vec(),
        overturned,
    })
}

// ---------------------------------------------------------------------------------------------
// Overturning acceleration spectra of records.

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
    /// `H/B` of the equivalent monolith (thesis: 12).
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
    fn validate(&self) -> Result<(), SpectraError> {
        self.sweep.validate()?;
        if !(self.slenderness.is_finite() && self.slenderness > 0.0) {
            return Err(invalid("slenderness", "must be finite and > 0"));
        }
        if self.levels.iter().any(|l| !(l.is_finite() && *l > 0.0)) {
            return Err(invalid("levels", "every level must be finite and > 0"));
        }
        if self.sizes.is_empty() || self.sizes.iter().any(|r| !(r.is_finite() && *r > 0.0)) {
            return Err(invalid(
                "sizes",
                "needs at least one size, each finite and > 0",
            ));
        }
        if self.sizes.windows(2).any(|w| w[1] >= w[0]) {
            return Err(invalid(
                "sizes",
                "must be strictly decreasing (largest first)",
            ));
        }
        if self.n_blocks == 0 {
            return Err(invalid("n_blocks", "must be >= 1"));
        }
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
struct PreparedRecord<'a> {
    record: &'a Record,
    pga: f64,
    impulses: Vec<f64>,
}

impl<'a> PreparedRecord<'a> {
    fn new(record: &'a Record) -> Result<PreparedRecord<'a>, SpectraError> {
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

    /// [`record_overturns`].
    fn overturns(&self, level: f64, size: f64, options: &OasOptions) -> Result<bool, SpectraError> {
        let record = self.record;
        let column = column_of_size(size, options.slenderness, options.n_blocks)?;
        let g = options.sweep.simulation.gravity;
        let mono = Monolith::of(&column, g);
        let factor = level * mono.a_p_min / self.pga;
        let Some((t0, t_last)) = exceedance_window(record, factor, uplift_acceleration(&column, g))
        else {
            return Ok(false);
        };
        let motion = ScaledRecord {
            record,
            factor,
            t0,
            impulses: &self.impulses,
        };
        let dt = options.sweep.time_step.dt(Some(record.dt), None, mono.p);
        let end = if options.sweep.cut_after_last_exceedance {
            t_last - t0
        } else {
            motion.end_time()
        };
        let tail = options.sweep.tail / mono.p;
        let mut sim = options.sweep.simulation(dt, end + tail);
        // After the last exceedance a closed column can never lift off again: stop there
        // (exact).
        sim.quiet_after = Some(t_last - t0);
        Ok(overturns(&column, &motion, &sim)?)
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

/// The improved fit of the transformed OAS (Eq. 28): `f = L/β + 1/t_1'`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InclinedFit {
    /// `t_1'` \[s\]; `f64::INFINITY` for a line through the origin (the thesis's "~∞").
    pub t1_prime: f64,
    /// `β` \[s\]: the slope of `f` against the level is `1/β`; `f64::INFINITY` for a vertical
    /// line.
    pub beta: f64,
}

/// The numbers of an OAS that the design method uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OasSummary {
    /// The most vulnerable boundary point: smallest `f` (Eq. 19). `None` when nothing overturns.
    pub f_min: Option<OasPoint>,
    /// `t_1 = i_cr / f_min` \[s\] (Eq. 20, exact `i_cr` of the slenderness).
    pub t1: Option<f64>,
    /// The inclined line (Eq. 28).
    pub fit: Option<InclinedFit>,
    /// Total simulations.
    pub simulations: usize,
}

/// Which of the simplified spectra a check is about, and what it found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConservativeCheck {
    /// Boundary points predicted safe by Eq. 21 (exact `i_cr`) although they overturn.
    pub eq21: Vec<OasPoint>,
    /// ... by Eq. 21 / 31 with `i_cr ≈ 1`.
    pub eq21_approx: Vec<OasPoint>,
    /// ... by Eq. 29 (inclined line, as solved from Eq. 28).
    pub eq29: Vec<OasPoint>,
    /// ... by Eq. 30 (vertical and inclined line).
    pub eq30: Vec<OasPoint>,
}

impl ConservativeCheck {
    /// No violation at all.
    pub fn all_conservative(&self) -> bool {
        self.eq21.is_empty()
            && self.eq21_approx.is_empty()
            && self.eq29.is_empty()
            && self.eq30.is_empty()
    }
}

impl Oas {
    /// The equivalent monolith of size `size`.
    pub fn monolith(&self, size: f64) -> Monolith {
        let width = 2.0 * size / (1.0 + self.slenderness * self.slenderness).sqrt();
        let height = self.slenderness * width;
        let delta = single_block::slenderness_angle(width, height);
        let r = single_block::corner_distance(width, height);
        Monolith {
            width,
            height,
            delta,
            r,
            p: single_block::frequency_parameter(r, ALPHA_UNIFORM, self.gravity),
            a_p_min: single_block::a_p_min(delta, self.gravity),
            i_cr: single_block::normalised_critical_impulse(delta),
        }
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
                let p = self.monolith(size).p;
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

    /// The leftmost boundary point of the transformed OAS (smallest `f`; the lowest level on a
    /// tie). Its `f` is `f_min` of Eq. 20.
    pub fn f_min(&self) -> Option<OasPoint> {
        self.boundary()
            .into_iter()
            .reduce(|a, b| if b.f < a.f { b } else { a })
    }

    /// `t_1 = i_cr / f_min` (Eq. 20).
    pub fn t1(&self) -> Option<f64> {
        self.f_min().map(|m| self.i_cr() / m.f)
    }

    /// The inclined line of Eq. 28, `f = L/β + 1/t_1'`, fitted as the line that stays left of
    /// every boundary point of the transformed OAS (so that Eq. 29 and 30 are conservative on
    /// the grid), with intercept and slope `≥ 0`, and is highest at the middle of the level
    /// range (the supporting line of the boundary's convex hull there). The thesis does not say
    /// how it fitted its lines; this is one reproducible reading.
    pub fn fit(&self) -> Option<InclinedFit> {
        let pts = self.boundary();
        if pts.is_empty() {
            return None;
        }
        let (lo, hi) = self
            .levels
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), l| {
                (lo.min(l.level), hi.max(l.level))
            });
        let mid = 0.5 * (lo + hi);
        // Candidate lines (a = intercept, b = slope): through two points, through the origin and
        // one point, horizontal through one point. Feasible: a, b >= 0 and a + b L_i <= f_i.
        let feasible = |a: f64, b: f64| {
            a >= 0.0
                && b >= 0.0
                && pts
                    .iter()
                    .all(|q| a + b * q.level <= q.f * (1.0 + 1e-12) + 1e-12)
        };
        let mut best: Option<(f64, f64, f64)> = None;
        let mut consider = |a: f64, b: f64| {
            if a.is_finite() && b.is_finite() && feasible(a, b) {
                let v = a + b * mid;
                if best.map_or(true, |(bv, _, _)| v > bv) {
                    best = Some((v, a, b));
                }
            }
        };
        for (i, p) in pts.iter().enumerate() {
            consider(0.0, p.f / p.level);
            consider(p.f, 0.0);
            for q in &pts[i + 1..] {
                if q.level != p.level {
                    let b = (q.f - p.f) / (q.level - p.level);
                    consider(p.f - b * p.level, b);
                }
            }
        }
        let (_, a, b) = best?;
        Some(InclinedFit {
            t1_prime: if a > 0.0 { 1.0 / a } else { f64::INFINITY },
            beta: if b > 0.0 { 1.0 / b } else { f64::INFINITY },
        })
    }

    /// `f_min`, `t_1`, the inclined fit and the count of simulations.
    pub fn summary(&self) -> OasSummary {
        OasSummary {
            f_min: self.f_min(),
            t1: self.t1(),
            fit: self.fit(),
            simulations: self.simulations(),
        }
    }

    /// The boundary points that a simplified OAS with these parameters predicts safe although
    /// they overturn (a point exactly on the simplified line, within a relative 1e-9, counts as
    /// predicted unsafe: the line through the most vulnerable point is the definition of `t_1`).
    /// Checking the boundary suffices for [`SizeSearch::Scan`]: every unsafe size of a level is
    /// at least as small (`p` at least as large) as the boundary's and the simplified limits
    /// decrease with `p`.
    pub fn check(&self, t1: f64, fit: Option<InclinedFit>) -> ConservativeCheck {
        let i_cr = self.i_cr();
        let mut out = ConservativeCheck::default();
        let violates = |limit: f64, level: f64| level < limit * (1.0 - 1e-9);
        for q in self.boundary() {
            if violates(crate::design::simplified_oas(q.p, t1, i_cr), q.level) {
                out.eq21.push(q);
            }
            if violates(crate::design::simplified_oas(q.p, t1, 1.0), q.level) {
                out.eq21_approx.push(q);
            }
            if let Some(fit) = fit {
                if violates(
                    crate::design::improved_oas_eq29(q.p, fit.t1_prime, fit.beta),
                    q.level,
                ) {
                    out.eq29.push(q);
                }
                if violates(
                    crate::design::improved_oas_eq30(q.p, t1, fit.t1_prime, fit.beta),
                    q.level,
                ) {
                    out.eq30.push(q);
                }
            }
        }
        out
    }
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
    record
        .validate()
        .map_err(|e| invalid("record", e.to_string()))?;
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
        n_impacts: options.sweep.simulation.model.n_impacts,
        search: options.search,
        sizes: options.sizes.clone(),
        levels: levels.into_iter().collect::<Result<_, _>>()?,
        gravity: options.sweep.simulation.gravity,
    })
}

#[cfg(test)]
mod tests;
