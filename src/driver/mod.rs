//! The reference rigid-body time-history driver (thesis 3.3, SPEC §5).
//!
//! Between events the open DOFs obey `M_FF φ̈_F = q_F` (thesis Eq. 6; optionally with the exact
//! Lagrangian velocity terms of [`Column::velocity_load_into`]), geometry recomputed at every
//! evaluation. Every step checks, at its end:
//! 1. closed interfaces: the reaction signs (`λ = M a − q` on closed DOFs; inadmissible when
//!    `λ > 0` on `phĭ_k` or `λ < 0` on `phî_k`, with the threshold of
//!    [`crate::check_configuration`], one function for both) — an opening;
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
//!
//! # The pipeline
//!
//! A run is a state (`state.rs`: time, DOF angles, rates and accelerations, statuses, the open
//! DOFs — a value) carried forward by a short loop (`run.rs`) that reads as the list above:
//!
//! - **options** (`options.rs`): by concern — [`PhysicsOptions`], [`SteppingOptions`],
//!   [`StoppingOptions`], [`Recording`], [`InitialState`]; a run borrows them as one
//!   `RunOptions`, so that a sweep shares its physics and stops across simulations;
//! - **chain** (`chain.rs`): what the driver asks of the bodies — the equations of motion, the
//!   checks at a state (reaction margins, contact forces, tipping), energies and the two models —
//!   as two traits; the column's implementation is `dynamics.rs` with the crate's models;
//! - **step** (`step.rs`, `integrator.rs`, `dop853.rs`): the next step's length and the state at
//!   its end, integrated from its start (Wilson θ, Newmark, or RK4 and DOP853 through one
//!   Runge–Kutta tableau loop);
//! - **events** (`events/`): `detect` finds the first event in the step, `locate` and `refine`
//!   place it (linear or Hermite, the DOP853 refinement) and move the state there; then the
//!   transition, each in its own module — `opening`, `impact`, `settle`, the stops of `forces`
//!   (tension, sliding), `overturn` (tipped, fallen) and `rest` (at rest, cannot tip);
//! - **recorder** (`recorder.rs`): what is kept — history samples, events, peaks, the energy
//!   balance — and the [`Outcome`] (`outcome.rs`).
//!
//! Room for what comes next: another scheme (an event-capturing, Moreau–Jean time stepping with
//! sliding and flight) is a variant of [`Scheme`] with its own loop beside `run.rs`, reporting
//! through the same recorder, [`Outcome`] and [`Event`]; another chain (a closed loop, SPEC §9:
//! the closure `G v = 0`, several joints closing at once, no reaction test) implements the two
//! traits of `chain.rs`; neither touches the integrators.

mod barrier;
mod chain;
pub mod closed;
mod dop853;
mod dynamics;
mod events;
mod integrator;
mod options;
mod outcome;
mod problem;
mod recorder;
pub mod reference;
mod run;
mod state;
mod step;
pub mod switch;
#[cfg(test)]
mod tests;

pub use barrier::{
    certify_column_barrier, column_is_certified, column_stop_is_certified, BarrierCertificate,
    BarrierFailure, CERTIFIED_COLUMNS, CERTIFIED_EPSILON,
};
pub use closed::{simulate_loop, simulate_loop_with_progress, LoopOptions, LoopOutcome, LoopState};
pub(crate) use options::RunOptions;
pub use options::{
    EventLocator, InitialState, Integrator, PhysicsOptions, Recording, Scheme, SimulationOptions,
    SteppingOptions, StoppingOptions,
};
pub use outcome::{DriverError, EnergyBalance, Event, EventKind, History, Outcome, StopReason};

use crate::ground::GroundMotion;
use crate::model::column::Column;
use problem::Problem;

/// Runs a time history of `column` under `motion`. `progress` is called with the fraction of the
/// duration done (about every 1 %).
pub fn simulate(
    column: &Column,
    motion: &dyn GroundMotion,
    options: &SimulationOptions,
    progress: Option<&mut dyn FnMut(f64)>,
) -> Result<Outcome, DriverError> {
    simulate_with(column, motion, options.run(), progress)
}

/// Whether `column` overturns under `motion` (static tipping, or fallen with
/// `continue_until_fallen`): the lean path of the spectra sweeps. Records nothing and stops at
/// the first overturning. Same physics as [`simulate`].
pub fn overturns(
    column: &Column,
    motion: &dyn GroundMotion,
    options: &SimulationOptions,
) -> Result<bool, DriverError> {
    overturns_with(column, motion, options.run())
}

/// [`overturns`] with the options of one run (e.g. [`SimulationOptions::sweep_run`]).
pub(crate) fn overturns_with(
    column: &Column,
    motion: &dyn GroundMotion,
    options: RunOptions,
) -> Result<bool, DriverError> {
    Ok(outcome_with(column, motion, options)?.overturned)
}

/// The [`Outcome`] of the lean path of [`overturns_with`] (nothing recorded, the stop, its time
/// and the count of impacts kept): how a sweep's point ended.
pub(crate) fn outcome_with(
    column: &Column,
    motion: &dyn GroundMotion,
    options: RunOptions,
) -> Result<Outcome, DriverError> {
    let options = RunOptions {
        recording: Recording::NONE,
        ..options
    };
    simulate_with(column, motion, options, None)
}

fn simulate_with(
    column: &Column,
    motion: &dyn GroundMotion,
    options: RunOptions,
    progress: Option<&mut dyn FnMut(f64)>,
) -> Result<Outcome, DriverError> {
    options.validate(column)?;
    match options.stepping.scheme {
        Scheme::EventDriven => {
            let physics = options.physics;
            let chain = dynamics::ColumnDynamics::new(
                column,
                physics.gravity,
                physics.exact_velocity_terms,
                physics.model.tolerance,
                physics.friction,
            );
            run::run(Problem::new(chain, motion, options), progress)
        }
    }
}
