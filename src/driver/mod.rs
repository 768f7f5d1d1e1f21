//! The reference rigid-body time-history driver (thesis 3.3, SPEC §5).
//!
//! Between events the open DOFs obey `M_FF φ̈_F = q_F` (thesis Eq. 6; optionally with the exact
//! Lagrangian velocity terms of [`Column::velocity_load_into`]), geometry recomputed at every
//! evaluation. Every step checks, at its end:
//! 1. closed interfaces: the reaction signs (`λ = M a − q` on closed DOFs; inadmissible when
//!    `λ > 0` on `phĭ_k` or `λ < 0` on `phî_k`, with the threshold of
//!    [`crate::check_configuration`]) — an opening;
//! 2. open DOFs: a DOF that crosses zero moving back towards it (`phĭ` rising to 0, `phî` falling
//!    to 0; SPEC §5 trap (b)) — an impact;
//! 3. every interface: compression `N >= 0` and friction `μ N >= |V|`. `N` and `V` are the
//!    components, normal and tangent to the interface (in the frame of the block below), of the
//!    force `F_k = Σ_{j≥k} m_j (c̈_j + (a_g, g))` that the part below exerts on the part above:
//!    Newton's law for the rigid assembly above interface `k` in the ground frame, where the
//!    inertial load `−m_j a_g` and gravity `−m_j g` act on each block and `c̈_j` is the block
//!    centre's acceleration relative to the ground (DOF accelerations and centripetal terms);
//! 4. overturning: the centre of mass of the part above an open interface beyond its pivot
//!    (static tipping), or with `continue_until_fallen` a block rotated by `π/2`.
//!
//! Openings and impacts are located inside the step ([`EventLocator`]); the decision is always
//! made by [`crate::opening_model`] / [`crate::impact_model`]; the integration restarts from the
//! event. Openings are judged a tiny step past the event (SPEC §5 trap (a)). Repeated impacts of
//! shrinking amplitude end in a closed interface ([`EventKind::Settled`]).
//!
//! Energy: the work of the ground motion is `∫ Σ_f q^{ag}_f φ̇_f dt` (the horizontal part of the
//! load times the DOF rates, i.e. `∫ −Σ_j m_j a_g ẋ_j dt`), integrated by the trapezoidal rule on
//! the steps; the energy lost at impacts and settlings is `T⁻ − T⁺`. With the exact velocity
//! terms (and for one open DOF, where they vanish) `ground_work − dissipated = Δ(T + V)` up to
//! the integration and event-location error; thesis Eq. 6 without them is not exactly
//! conservative when several DOFs are open.

mod dop853;
mod dynamics;
mod engine;
mod events;
mod integrator;
pub mod reference;
#[cfg(test)]
mod tests;

use std::fmt;

use crate::error::RockingError;
use crate::ground::GroundMotion;
use crate::model::column::{Column, GRAVITY};
use crate::model::cone::{ModelOptions, ModelReport};
use crate::model::configuration::Status;

/// Time integration method between events.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Integrator {
    /// Wilson's θ method (Chopra), as the thesis; `theta = 1.4` by default. The nonlinear
    /// equation at `t + θ dt` is solved by fixed-point iteration on the acceleration; the ground
    /// acceleration is extrapolated linearly to `t + θ dt` as in the linear method.
    WilsonTheta {
        /// θ ≥ 1 (1.37 or more for unconditional stability of the linear method).
        theta: f64,
    },
    /// Newmark's average acceleration method (γ = 1/2, β = 1/4), fixed-point iteration.
    Newmark,
    /// Classical explicit fourth-order Runge–Kutta.
    Rk4,
    /// The eighth-order explicit Runge–Kutta solution of Dormand and Prince's DOP853 (Hairer,
    /// Nørsett and Wanner), with the driver's fixed step: 12 evaluations of the equations of
    /// motion per step, the ground acceleration at each stage's time. With
    /// [`EventLocator::Hermite`] its events are refined by re-integration to the method's
    /// accuracy (see there). For accurate runs at large steps (e.g. `dt` = 10–50 ms on a
    /// rocking block); its stability bound is `dt ω ≲ 3` on the fastest oscillation. The order
    /// needs a ground motion smooth within each step: a sampled record (linear between samples)
    /// has a kink at every sample, and a step across one is only second-order accurate there.
    /// At large steps set [`SimulationOptions::settle_interval`] in seconds: its default, four
    /// steps, would settle a block whose impacts are that close.
    Dop853,
}

impl Integrator {
    /// Whether the method's order exceeds the cubic Hermite interpolation's, so that the
    /// Hermite locator refines its events by re-integration.
    fn refines_events(self) -> bool {
        matches!(self, Integrator::Dop853)
    }
}

impl Default for Integrator {
    fn default() -> Integrator {
        Integrator::WilsonTheta { theta: 1.4 }
    }
}

/// How an event (opening, impact) is located inside a step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EventLocator {
    /// Linear interpolation of the event function and of the state within the step (thesis).
    #[default]
    Linear,
    /// Cubic Hermite interpolation of the angles on the step and Illinois root finding (for an
    /// opening, the reactions evaluated on the interpolated state); the state at the event is
    /// then re-integrated from the start of the step.
    ///
    /// With [`Integrator::Dop853`] (whose error is far below the interpolation's `O(dt⁴)`) the
    /// event time is then refined on the re-integrated solution itself, i.e. on the event
    /// function of one integrator step of length `s dt` from the start of the step. An impact:
    /// the Hermite time improved on the quintic Hermite interpolant of the step (which also uses
    /// the accelerations at both ends), then Newton's method on the angle (its derivative is the
    /// integrated rate) until the correction is below `1e-8` s and its second-order remainder
    /// below `1e-15` s, the last correction applied to the state by a second-order Taylor shift:
    /// one or two extra steps per impact. An opening: Illinois on the largest reaction margin, in
    /// a bracket grown from `1e-7` of the step around the Hermite time, down to `1e-14` s.
    Hermite,
}

/// What a simulation keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Recording {
    /// Keep the state every `k` accepted steps (plus the start and the end); `None`: no history.
    pub history_every: Option<usize>,
    /// Keep the list of events.
    pub events: bool,
}

impl Default for Recording {
    fn default() -> Recording {
        Recording {
            history_every: Some(1),
            events: true,
        }
    }
}

impl Recording {
    /// Nothing kept (the fast path of [`overturns`]).
    pub const NONE: Recording = Recording {
        history_every: None,
        events: false,
    };
}

/// Options of a simulation. See [`SimulationOptions::default`].
#[derive(Clone, Debug, PartialEq)]
pub struct SimulationOptions {
    /// Time step (s).
    pub dt: f64,
    /// Simulated duration (s).
    pub duration: f64,
    /// Integration method.
    pub integrator: Integrator,
    /// Event location.
    pub locator: EventLocator,
    /// Options of the opening and impact models (`n_impacts`, solver, tolerance).
    pub model: ModelOptions,
    /// Friction coefficient μ (`f64::INFINITY` disables the sliding check).
    pub friction: f64,
    /// Acceleration of gravity (m/s²).
    pub gravity: f64,
    /// Add the velocity terms of the exact Lagrangian equations (`false` = thesis Eq. 6).
    pub exact_velocity_terms: bool,
    /// Do not stop at static tipping; stop when a block has rotated by `π/2`.
    pub continue_until_fallen: bool,
    /// Stop with [`StopReason::TooManyEvents`] when the events exceed this many per simulated
    /// second (counted over `max(t, 1 s)`).
    pub max_events_per_second: f64,
    /// What to keep.
    pub record: Recording,
    /// Initial angles per interface (rad), released at rest: negative = about the right corner
    /// (`phĭ`), positive = about the left corner (`phî`), zero = closed. `None`: straight.
    pub initial_angles: Option<Vec<f64>>,
    /// Settling: after an impact, the closing interface is closed for good (its DOF removed by a
    /// kinetic-metric projection) when the kinetic energy left is below this fraction of the
    /// smallest potential energy that tips a part of the column statically.
    pub settle_energy_fraction: f64,
    /// Settling: ... or when the time since the previous impact at the same interface is below
    /// this (s). `None`: four time steps.
    pub settle_interval: Option<f64>,
    /// After this time the ground acceleration stays below the column's static uplift
    /// acceleration for good (e.g. the last exceedance of a record). A column that is closed
    /// then — straight and moving with the ground — can never open again, so the run stops
    /// there with [`StopReason::AtRest`]: exact, and it saves the weak codas of long records in
    /// spectra sweeps. `None`: run the whole duration.
    pub quiet_after: Option<f64>,
    /// Single block: stop with [`StopReason::CannotTip`] as soon as an energy bound proves that
    /// the rest of the ground motion cannot tip the block. Rocking about a pivot `P`, the ground
    /// acceleration's inertial load does the power `−m a_g ẋ_G` with `|ẋ_G| ≤ R |θ̇|` and
    /// `½ I_P θ̇² ≤ E` (kinetic plus potential energy above rest, which is `≥ 0` while the
    /// centre of mass is above its rest height), so `d√E/dt ≤ m R |a_g| / √(2 I_P)`; impacts and
    /// settling only take energy away. Hence if
    /// `√E(t) + m R / √(2 I_P) · ∫_t^∞ |a_g| ≤ 0.9 √E_tip` (`E_tip`: the energy that lifts the
    /// centre of mass over the pivot, which static tipping needs), the block can never tip; the
    /// factor 0.9 leaves room for the integration error, so the verdict is the one the full run
    /// would give. Needs [`GroundMotion::remaining_impulse`]; ignored for columns of more than
    /// one block (thesis Eq. 6 does not conserve energy there) and with
    /// `continue_until_fallen`. Checked every 16 steps. It proves only that the block will not
    /// tip: a sliding or tension stop that the rest of the run would have met is not reported
    /// (sweeps use infinite friction).
    pub stop_when_safe: bool,
}

impl Default for SimulationOptions {
    fn default() -> SimulationOptions {
        SimulationOptions {
            dt: 1e-3,
            duration: 10.0,
            integrator: Integrator::default(),
            locator: EventLocator::default(),
            model: ModelOptions::default(),
            friction: 0.7,
            gravity: GRAVITY,
            exact_velocity_terms: false,
            continue_until_fallen: false,
            max_events_per_second: 2000.0,
            record: Recording::default(),
            initial_angles: None,
            settle_energy_fraction: 1e-6,
            settle_interval: None,
            quiet_after: None,
            stop_when_safe: false,
        }
    }
}

/// What happened at an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "snake_case")
)]
pub enum EventKind {
    /// One or more closed interfaces opened (opening model).
    Opening,
    /// An open interface closed (impact model).
    Impact,
    /// An interface closed for good after impacts of shrinking amplitude.
    Settled,
    /// The part above an interface tipped statically beyond its pivot.
    Overturned,
    /// Friction exceeded at an interface (`μ N < |V|`).
    Sliding,
    /// Tension at an interface (`N < 0`).
    Tension,
}

/// One event of a simulation.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Event {
    /// Time (s).
    pub t: f64,
    /// Kind.
    pub kind: EventKind,
    /// The interface concerned (impact: the closing one; opening: the lowest newly opened one).
    pub interface: Option<usize>,
    /// Kinetic energy before (J).
    pub kinetic_before: f64,
    /// Kinetic energy after (J).
    pub kinetic_after: f64,
    /// Configuration before.
    pub statuses_before: Vec<Status>,
    /// Configuration after.
    pub statuses_after: Vec<Status>,
    /// The model's report (openings and impacts).
    pub report: Option<ModelReport>,
}

/// Why a simulation stopped (a reason, not an error).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StopReason {
    /// The requested duration was simulated.
    Duration,
    /// Static tipping at this interface (without `continue_until_fallen`).
    Overturned {
        /// Interface whose part above tipped.
        interface: usize,
    },
    /// A block rotated by `π/2` (with `continue_until_fallen`); the interface with the largest
    /// rotation at or below that block.
    Fallen {
        /// Interface.
        interface: usize,
    },
    /// Friction exceeded at this interface.
    Sliding {
        /// Interface.
        interface: usize,
    },
    /// Tension at this interface.
    Tension {
        /// Interface.
        interface: usize,
    },
    /// More events than `max_events_per_second` allows.
    TooManyEvents,
    /// Closed after [`SimulationOptions::quiet_after`]: the ground can no longer open it.
    AtRest,
    /// The energy bound of [`SimulationOptions::stop_when_safe`] proved that the rest of the
    /// ground motion cannot tip the block.
    CannotTip,
}

/// Kept states, struct of arrays (`n` interfaces, `2n` DOFs per sample).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct History {
    /// Number of interfaces `n`.
    pub n_interfaces: usize,
    /// Times (s).
    pub t: Vec<f64>,
    /// DOF angles, `2n` per sample (rad).
    pub phi: Vec<f64>,
    /// DOF rates, `2n` per sample (rad/s).
    pub rates: Vec<f64>,
    /// Absolute block rotations, `n` per sample (rad).
    pub block_angles: Vec<f64>,
    /// Interface statuses, `n` per sample.
    pub statuses: Vec<Status>,
}

impl History {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether nothing was kept.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// DOF angles of sample `i`.
    pub fn phi_at(&self, i: usize) -> &[f64] {
        let m = 2 * self.n_interfaces;
        &self.phi[i * m..(i + 1) * m]
    }

    /// Block rotations of sample `i`.
    pub fn block_angles_at(&self, i: usize) -> &[f64] {
        let n = self.n_interfaces;
        &self.block_angles[i * n..(i + 1) * n]
    }
}

/// Energy bookkeeping (J). Invariant: `ground_work − dissipated ≈ kinetic_end + potential_change`
/// (kinetic energy at the start is zero: the column starts at rest).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EnergyBalance {
    /// Work of the inertial load of the ground motion, `∫ −Σ_j m_j a_g ẋ_j dt`.
    pub ground_work: f64,
    /// Kinetic energy lost at impacts and settlings.
    pub dissipated: f64,
    /// Kinetic energy at the end.
    pub kinetic_end: f64,
    /// Potential energy at the end minus at the start.
    pub potential_change: f64,
}

impl EnergyBalance {
    /// `ground_work − dissipated − kinetic_end − potential_change`.
    pub fn residual(&self) -> f64 {
        self.ground_work - self.dissipated - self.kinetic_end - self.potential_change
    }
}

/// The result of a simulation.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// Why it stopped.
    pub stop_reason: StopReason,
    /// Time reached (s).
    pub t_end: f64,
    /// Overturned: stopped by static tipping, or fallen with `continue_until_fallen` — or, with
    /// that option, tipped beyond a pivot before the run ended for another reason (a falling
    /// block whose corner lifts off ends in `Tension`).
    pub overturned: bool,
    /// Number of impacts.
    pub impacts: usize,
    /// Events (empty unless `record.events`).
    pub events: Vec<Event>,
    /// Kept states.
    pub history: Option<History>,
    /// Largest absolute rotation of each block (rad).
    pub peak_block_rotation: Vec<f64>,
    /// Energy bookkeeping.
    pub energy: EnergyBalance,
    /// Configuration at the end.
    pub statuses_end: Vec<Status>,
}

/// Why a simulation could not run.
#[derive(Clone, Debug, PartialEq)]
pub enum DriverError {
    /// An option is invalid.
    InvalidOption {
        /// Field of [`SimulationOptions`].
        field: &'static str,
        /// The value, printed.
        value: String,
        /// What is wrong.
        reason: &'static str,
    },
    /// The opening or impact model failed.
    Model(RockingError),
}

impl fmt::Display for DriverError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DriverError::InvalidOption {
                field,
                value,
                reason,
            } => {
                write!(f, "invalid simulation option {field} = {value}: {reason}")
            }
            DriverError::Model(e) => write!(f, "model error: {e}"),
        }
    }
}

impl std::error::Error for DriverError {}

impl From<RockingError> for DriverError {
    fn from(e: RockingError) -> DriverError {
        DriverError::Model(e)
    }
}

fn invalid(field: &'static str, value: impl fmt::Debug, reason: &'static str) -> DriverError {
    DriverError::InvalidOption {
        field,
        value: format!("{value:?}"),
        reason,
    }
}

impl SimulationOptions {
    /// Checks every field; the error names the field.
    pub fn validate(&self, column: &Column) -> Result<(), DriverError> {
        let positive = |field, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(invalid(
                    field,
                    v,
                    "must be a finite number greater than zero",
                ))
            }
        };
        positive("dt", self.dt)?;
        if !(self.duration.is_finite() && self.duration >= 0.0) {
            return Err(invalid(
                "duration",
                self.duration,
                "must be finite and >= 0",
            ));
        }
        if self.duration / self.dt > 1e10 {
            return Err(invalid(
                "dt",
                self.dt,
                "more than 1e10 steps for the duration",
            ));
        }
        if let Integrator::WilsonTheta { theta } = self.integrator {
            if !(theta.is_finite() && (1.0..=3.0).contains(&theta)) {
                return Err(invalid("integrator.theta", theta, "must be in [1, 3]"));
            }
        }
        self.model.validate()?;
        if self.friction.is_nan() || self.friction <= 0.0 {
            return Err(invalid(
                "friction",
                self.friction,
                "must be > 0 (infinity disables sliding)",
            ));
        }
        positive("gravity", self.gravity)?;
        if self.max_events_per_second.is_nan() || self.max_events_per_second <= 0.0 {
            return Err(invalid(
                "max_events_per_second",
                self.max_events_per_second,
                "must be > 0",
            ));
        }
        if self.record.history_every == Some(0) {
            return Err(invalid(
                "record.history_every",
                0,
                "must be >= 1 (None keeps no history)",
            ));
        }
        if !(self.settle_energy_fraction.is_finite()
            && (0.0..1.0).contains(&self.settle_energy_fraction))
        {
            return Err(invalid(
                "settle_energy_fraction",
                self.settle_energy_fraction,
                "must be in [0, 1)",
            ));
        }
        if let Some(s) = self.settle_interval {
            if !(s.is_finite() && s >= 0.0) {
                return Err(invalid("settle_interval", s, "must be finite and >= 0"));
            }
        }
        if let Some(a) = &self.initial_angles {
            if a.len() != column.n_interfaces() {
                return Err(invalid(
                    "initial_angles",
                    a,
                    "needs one angle per interface",
                ));
            }
            if a.iter()
                .any(|v| !(v.is_finite() && v.abs() < 0.5 * std::f64::consts::PI))
            {
                return Err(invalid(
                    "initial_angles",
                    a,
                    "angles must be finite with |angle| < π/2",
                ));
            }
        }
        Ok(())
    }
}

/// Runs a time history of `column` under `motion`. `progress` is called with the fraction of the
/// duration done (about every 1 %).
pub fn simulate(
    column: &Column,
    motion: &dyn GroundMotion,
    options: &SimulationOptions,
    progress: Option<&mut dyn FnMut(f64)>,
) -> Result<Outcome, DriverError> {
    options.validate(column)?;
    engine::Engine::new(column, motion, options, options.record).run(progress)
}

/// Whether `column` overturns under `motion` (static tipping, or fallen with
/// `continue_until_fallen`): the lean path of the spectra sweeps. Records nothing and stops at
/// the first overturning. Same physics as [`simulate`].
pub fn overturns(
    column: &Column,
    motion: &dyn GroundMotion,
    options: &SimulationOptions,
) -> Result<bool, DriverError> {
    options.validate(column)?;
    let out = engine::Engine::new(column, motion, options, Recording::NONE).run(None)?;
    Ok(out.overturned)
}
