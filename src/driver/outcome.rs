//! What a run reports: its events, why it stopped, the kept history, the energy balance, and
//! why it could not run. Shared by every scheme.

use crate::error::RockingError;
use crate::model::cone::ModelReport;
use crate::model::configuration::Status;
use crate::validate::InvalidValue;

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

impl EventKind {
    /// The name in `events.jsonl` and `summary.json` (`"opening"`, `"impact"`, …; the serde name).
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Opening => "opening",
            EventKind::Impact => "impact",
            EventKind::Settled => "settled",
            EventKind::Overturned => "overturned",
            EventKind::Sliding => "sliding",
            EventKind::Tension => "tension",
        }
    }
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
    /// Closed after [`super::StoppingOptions::quiet_after`]: the ground can no longer open it.
    AtRest,
    /// The energy bound of [`super::StoppingOptions::stop_when_safe`] proved that the rest of the
    /// ground motion cannot tip the block.
    CannotTip,
}

impl StopReason {
    /// The name in `summary.json` (`stop_reason`: `"duration"`, `"overturned"`, …).
    pub fn name(&self) -> &'static str {
        match self {
            StopReason::Duration => "duration",
            StopReason::Overturned { .. } => "overturned",
            StopReason::Fallen { .. } => "fallen",
            StopReason::Sliding { .. } => "sliding",
            StopReason::Tension { .. } => "tension",
            StopReason::TooManyEvents => "too_many_events",
            StopReason::AtRest => "at_rest",
            StopReason::CannotTip => "cannot_tip",
        }
    }

    /// The interface the reason concerns, if any (`stop_interface`).
    pub fn interface(&self) -> Option<usize> {
        match *self {
            StopReason::Overturned { interface }
            | StopReason::Fallen { interface }
            | StopReason::Sliding { interface }
            | StopReason::Tension { interface } => Some(interface),
            StopReason::Duration
            | StopReason::TooManyEvents
            | StopReason::AtRest
            | StopReason::CannotTip => None,
        }
    }
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
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DriverError {
    /// An option is invalid; the field is its path in [`super::SimulationOptions`] (e.g.
    /// `stepping.dt`).
    #[error("invalid simulation option {0}")]
    InvalidOption(#[from] InvalidValue),
    /// The opening or impact model failed.
    #[error("model error: {0}")]
    Model(#[from] RockingError),
}
