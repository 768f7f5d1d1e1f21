//! Options of a simulation, by concern: the physics of the column and its contacts, how time is
//! stepped, when a run stops, what it keeps, and where it starts. [`SimulationOptions`] holds one
//! of each; a run reads them through [`RunOptions`], which borrows what it does not copy, so
//! that a sweep shares one physics and one template of the stops and changes only the step and
//! the duration per simulation.

use crate::model::column::{Column, GRAVITY};
use crate::model::cone::ModelOptions;
use crate::validate::{self, InvalidValue};

use super::DriverError;

/// How a run advances in time. Every scheme reports through the same [`super::Outcome`],
/// [`super::Event`] and recorder.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Scheme {
    /// Event-driven (thesis 3.3, SPEC §5): the open DOFs are integrated between events (with
    /// [`SteppingOptions::integrator`]), each event is located inside its step (with
    /// [`SteppingOptions::locator`]) and resolved by the opening or impact model.
    #[default]
    EventDriven,
}

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
    /// At large steps set [`StoppingOptions::settle_interval`] in seconds: its default, four
    /// steps, would settle a block whose impacts are that close.
    Dop853,
}

impl Integrator {
    /// Whether the method's order exceeds the cubic Hermite interpolation's, so that the
    /// Hermite locator refines its events by re-integration.
    pub(crate) fn refines_events(self) -> bool {
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

/// The physics: gravity, contacts and the two models.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhysicsOptions {
    /// Acceleration of gravity (m/s²).
    pub gravity: f64,
    /// Friction coefficient μ (`f64::INFINITY` disables the sliding check).
    pub friction: f64,
    /// Add the velocity terms of the exact Lagrangian equations (`false` = thesis Eq. 6).
    pub exact_velocity_terms: bool,
    /// Options of the opening and impact models (`n_impacts`, solver, tolerance).
    pub model: ModelOptions,
}

impl Default for PhysicsOptions {
    fn default() -> PhysicsOptions {
        PhysicsOptions {
            gravity: GRAVITY,
            friction: 0.7,
            exact_velocity_terms: false,
            model: ModelOptions::default(),
        }
    }
}

/// How time is stepped and events are located.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SteppingOptions {
    /// Time step (s).
    pub dt: f64,
    /// Event-driven (the only scheme so far).
    pub scheme: Scheme,
    /// Integration method between events.
    pub integrator: Integrator,
    /// Event location.
    pub locator: EventLocator,
}

impl Default for SteppingOptions {
    fn default() -> SteppingOptions {
        SteppingOptions {
            dt: 1e-3,
            scheme: Scheme::default(),
            integrator: Integrator::default(),
            locator: EventLocator::default(),
        }
    }
}

/// When a run stops, and when rocking settles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StoppingOptions {
    /// Simulated duration (s).
    pub duration: f64,
    /// Do not stop at static tipping; stop when a block has rotated by `π/2`.
    pub continue_until_fallen: bool,
    /// Stop with [`super::StopReason::TooManyEvents`] when the events exceed this many per
    /// simulated second (counted over `max(t, 1 s)`).
    pub max_events_per_second: f64,
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
    /// there with [`super::StopReason::AtRest`]: exact, and it saves the weak codas of long
    /// records in spectra sweeps. `None`: run the whole duration.
    pub quiet_after: Option<f64>,
    /// Single block: stop with [`super::StopReason::CannotTip`] as soon as an energy bound
    /// proves that the rest of the ground motion cannot tip the block. Rocking about a pivot
    /// `P`, the ground acceleration's inertial load does the power `−m a_g ẋ_G` with
    /// `|ẋ_G| ≤ R |θ̇|` and `½ I_P θ̇² ≤ E` (kinetic plus potential energy above rest, which is
    /// `≥ 0` while the centre of mass is above its rest height), so
    /// `d√E/dt ≤ m R |a_g| / √(2 I_P)`; impacts and settling only take energy away. Hence if
    /// `√E(t) + m R / √(2 I_P) · ∫_t^∞ |a_g| ≤ 0.9 √E_tip` (`E_tip`: the energy that lifts the
    /// centre of mass over the pivot, which static tipping needs), the block can never tip; the
    /// factor 0.9 leaves room for the integration error, so the verdict is the one the full run
    /// would give. Needs [`crate::ground::GroundMotion::remaining_impulse`]; ignored with
    /// `continue_until_fallen`. Columns of more than one block: the stop of
    /// `stop_when_safe_column`, with [`PhysicsOptions::exact_velocity_terms`] only (thesis Eq. 6
    /// does not conserve energy there) and only where its barrier is certified
    /// ([`crate::driver::column_is_certified`]: 2 or 3 equal blocks, H/B 3–12); otherwise
    /// ignored. Columns under thesis Eq. 6, with `quiet_after`: the monolith stop
    /// (`driver/events/monolith.rs`) — after `quiet_after`, a column rocking as one body about
    /// a base corner whose energy bound, reaction margins and impact model prove that it goes on
    /// so without tipping. Checked every 16 steps. It proves only that the block will not
    /// tip: a sliding or tension stop that the rest of the run would have met is not reported
    /// (sweeps use infinite friction).
    pub stop_when_safe: bool,
    /// Columns of more than one block, with [`PhysicsOptions::exact_velocity_terms`] (whose
    /// equations conserve `E = T + V` between events; impacts and settling only take energy
    /// away): stop with [`super::StopReason::CannotTip`] when
    /// `√E(t) + √(M/2) · ∫_t^∞ |a_g| ≤ 0.9 √E_tip`, `M` the total mass and `E_tip` the smallest
    /// potential energy of a rigid tipping mechanism of the straight column. The growth is
    /// proven (`|Σ m_j ẋ_j| ≤ √(2 M T)`); that no path tips the column with less than
    /// `0.999 E_tip` of potential energy, and that `V ≥ 0` before tipping, is certified by
    /// [`crate::driver::certify_column_barrier`] for [`crate::driver::CERTIFIED_COLUMNS`] only
    /// (see docs/column-early-stop.md); there `stop_when_safe` already implies
    /// it. This flag forces it on any column, where it is **not proven** (check it against full
    /// runs with `rocking bench spectra --compare`). Ignored without the exact velocity terms
    /// (thesis Eq. 6 does not conserve energy when several interfaces are open) and with
    /// `continue_until_fallen`.
    pub stop_when_safe_column: bool,
}

impl Default for StoppingOptions {
    fn default() -> StoppingOptions {
        StoppingOptions {
            duration: 10.0,
            continue_until_fallen: false,
            max_events_per_second: 2000.0,
            settle_energy_fraction: 1e-6,
            settle_interval: None,
            quiet_after: None,
            stop_when_safe: false,
            stop_when_safe_column: false,
        }
    }
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
    /// Nothing kept (the fast path of [`super::overturns`]).
    pub const NONE: Recording = Recording {
        history_every: None,
        events: false,
    };
}

/// Where a run starts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct InitialState {
    /// Initial angles per interface (rad), released at rest: negative = about the right corner
    /// (`phĭ`), positive = about the left corner (`phî`), zero = closed. `None`: straight.
    pub angles: Option<Vec<f64>>,
}

/// Options of a simulation, by concern. See the defaults of each part.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SimulationOptions {
    /// Gravity, friction, the equations of motion and the models.
    pub physics: PhysicsOptions,
    /// Time step, scheme, integrator and event locator.
    pub stepping: SteppingOptions,
    /// Duration and the other stops; settling.
    pub stopping: StoppingOptions,
    /// What to keep.
    pub recording: Recording,
    /// Initial angles.
    pub initial: InitialState,
}

impl SimulationOptions {
    /// Checks every field; the error names the field by its path (e.g. `stepping.dt`).
    pub fn validate(&self, column: &Column) -> Result<(), DriverError> {
        self.run().validate(column)
    }

    /// The options of a run.
    pub(crate) fn run(&self) -> RunOptions<'_> {
        RunOptions {
            physics: &self.physics,
            stepping: self.stepping,
            stopping: self.stopping,
            recording: self.recording,
            initial_angles: self.initial.angles.as_deref(),
        }
    }

    /// The options of one run of a sweep: these physics and stops (and initial state) with the
    /// step `dt` and the duration `duration`, nothing recorded.
    pub(crate) fn sweep_run(&self, dt: f64, duration: f64) -> RunOptions<'_> {
        RunOptions {
            stepping: SteppingOptions {
                dt,
                ..self.stepping
            },
            stopping: StoppingOptions {
                duration,
                ..self.stopping
            },
            recording: Recording::NONE,
            ..self.run()
        }
    }
}

/// What one run reads: the options by concern, the physics and the initial angles borrowed.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RunOptions<'a> {
    pub physics: &'a PhysicsOptions,
    pub stepping: SteppingOptions,
    pub stopping: StoppingOptions,
    pub recording: Recording,
    pub initial_angles: Option<&'a [f64]>,
}

impl RunOptions<'_> {
    /// Checks every field; the error names the field by its path in [`SimulationOptions`].
    pub fn validate(&self, column: &Column) -> Result<(), DriverError> {
        let (physics, stepping, stopping) = (self.physics, &self.stepping, &self.stopping);
        validate::positive("stepping.dt", stepping.dt)?;
        validate::non_negative("stopping.duration", stopping.duration)?;
        if validate::too_many_steps(stopping.duration, stepping.dt) {
            return Err(invalid(
                "stepping.dt",
                stepping.dt,
                "more than 1e10 steps for the duration",
            ));
        }
        if let Integrator::WilsonTheta { theta } = stepping.integrator {
            if !(theta.is_finite() && (1.0..=3.0).contains(&theta)) {
                return Err(invalid(
                    "stepping.integrator.theta",
                    theta,
                    "must be in [1, 3]",
                ));
            }
        }
        physics.model.validate()?;
        if physics.friction.is_nan() || physics.friction <= 0.0 {
            return Err(invalid(
                "physics.friction",
                physics.friction,
                "must be > 0 (infinity disables sliding)",
            ));
        }
        validate::positive("physics.gravity", physics.gravity)?;
        if stopping.max_events_per_second.is_nan() || stopping.max_events_per_second <= 0.0 {
            return Err(invalid(
                "stopping.max_events_per_second",
                stopping.max_events_per_second,
                "must be > 0",
            ));
        }
        if self.recording.history_every == Some(0) {
            return Err(invalid(
                "recording.history_every",
                0,
                "must be >= 1 (None keeps no history)",
            ));
        }
        let fraction = stopping.settle_energy_fraction;
        if !(fraction.is_finite() && (0.0..1.0).contains(&fraction)) {
            return Err(invalid(
                "stopping.settle_energy_fraction",
                fraction,
                "must be in [0, 1)",
            ));
        }
        if let Some(s) = stopping.settle_interval {
            validate::non_negative("stopping.settle_interval", s)?;
        }
        if let Some(a) = self.initial_angles {
            if a.len() != column.n_interfaces() {
                return Err(invalid(
                    "initial.angles",
                    a,
                    "needs one angle per interface",
                ));
            }
            if a.iter()
                .any(|v| !(v.is_finite() && v.abs() < 0.5 * std::f64::consts::PI))
            {
                return Err(invalid(
                    "initial.angles",
                    a,
                    "angles must be finite with |angle| < π/2",
                ));
            }
        }
        Ok(())
    }
}

fn invalid(field: &'static str, value: impl std::fmt::Debug, rule: &'static str) -> DriverError {
    DriverError::InvalidOption(InvalidValue::new(field, value, rule))
}
