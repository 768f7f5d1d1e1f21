//! What a drum run gives back ([`super::simulation`]): the joints' modes, events and stops,
//! the energy balance with the scheme's own error terms, the kept history, the outcome of a
//! whole run (also of the automatic scheme's, with its switches) and the errors.

use std::fmt;

use super::moreau::{EnergyAccounts, StepCounters};
use super::options::DrumOptionError;

/// Contact mode of a joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointMode {
    /// Both ends in contact.
    Closed,
    /// Only the right end in contact (the thesis's `phĭ`, status −1).
    RockingRight,
    /// Only the left end in contact (`phî`, status +1).
    RockingLeft,
    /// Neither end in contact: the part above flies.
    Flying,
}

impl JointMode {
    /// The thesis's status (−1 right pivot, 0 closed, +1 left pivot); `None` in flight.
    pub fn status(self) -> Option<i8> {
        match self {
            JointMode::Closed => Some(0),
            JointMode::RockingRight => Some(-1),
            JointMode::RockingLeft => Some(1),
            JointMode::Flying => None,
        }
    }
}

/// Kinds of events.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DrumEventKind {
    /// A closed joint opened (rocking starts).
    Opening,
    /// A rocking joint landed on its other end (or closed).
    Impact,
    /// A joint started to slip.
    SlipStart,
    /// A joint stopped slipping.
    SlipStop,
    /// A joint opened at both ends: the part above flies.
    LiftOff,
    /// A flying joint touched down.
    Landing,
    /// The part above a joint tipped beyond its pivot.
    Overturned,
    /// The automatic scheme handed the run from one scheme to the other
    /// ([`DrumOutcome::switches`] says which way and why; `joint`: the joint concerned, else 0).
    /// Not in [`DrumOutcome::event_counts`].
    SchemeSwitch,
}

impl DrumEventKind {
    /// Name used in outputs (`slip_start`, …).
    pub fn name(self) -> &'static str {
        match self {
            DrumEventKind::Opening => "opening",
            DrumEventKind::Impact => "impact",
            DrumEventKind::SlipStart => "slip_start",
            DrumEventKind::SlipStop => "slip_stop",
            DrumEventKind::LiftOff => "lift_off",
            DrumEventKind::Landing => "landing",
            DrumEventKind::Overturned => "overturned",
            DrumEventKind::SchemeSwitch => "scheme_switch",
        }
    }
}

/// One event.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrumEvent {
    /// Time (s): the end of the step in which it was seen (a located impact: its instant).
    pub t: f64,
    /// Kind.
    pub kind: DrumEventKind,
    /// Joint.
    pub joint: usize,
}

/// Why a run stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DrumStop {
    /// The requested duration was simulated.
    Duration,
    /// Static tipping of the part above this joint.
    Overturned {
        /// Joint.
        joint: usize,
    },
    /// A drum rotated by `π/2` (with `continue_until_fallen`).
    Fallen {
        /// The drum.
        drum: usize,
    },
    /// A drum slid off the one below: no overlap left at this joint.
    SlidOff {
        /// Joint.
        joint: usize,
    },
    /// A joint slipped, with [`OnSliding::Stop`](super::options::OnSliding::Stop).
    Sliding {
        /// Joint.
        joint: usize,
    },
    /// A joint lifted off, with [`OnTension::Stop`](super::options::OnTension::Stop).
    Tension {
        /// Joint.
        joint: usize,
    },
}

/// Energy balance of a run (J). Exact identity of the scheme:
/// `ground_work = Δpotential + kinetic_end + impact + friction + persistent_contact + projection`
/// up to round-off; the last two are the scheme's energy errors.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DrumEnergy {
    /// Potential energy at the end minus at the start.
    pub potential_change: f64,
    /// Kinetic energy at the end minus at the start.
    pub kinetic_change: f64,
    /// Accounts of the scheme.
    pub accounts: EnergyAccounts,
}

impl DrumEnergy {
    /// `ground_work − Δpotential − Δkinetic − impact − friction`: the energy error of the run
    /// (the scheme's persistent-contact work and projections plus round-off).
    pub fn residual(&self) -> f64 {
        let a = &self.accounts;
        a.ground_work - self.potential_change - self.kinetic_change - a.impact - a.friction
    }

    /// The residual left once the scheme's own error terms are counted: round-off.
    pub fn closure(&self) -> f64 {
        self.residual() - self.accounts.persistent_contact - self.accounts.projection
    }

    /// The scale the residual is measured against: the largest of the energies involved.
    pub fn scale(&self) -> f64 {
        let a = &self.accounts;
        a.ground_work
            .abs()
            .max(a.impact.abs() + a.friction.abs())
            .max(self.potential_change.abs())
            .max(self.kinetic_change.abs())
            .max(1e-300)
    }
}

/// Kept states.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DrumHistory {
    /// Number of drums.
    pub n: usize,
    /// Times (s).
    pub t: Vec<f64>,
    /// `x, y, θ` per drum per sample.
    pub q: Vec<f64>,
    /// Slip per joint per sample (m).
    pub slip: Vec<f64>,
}

/// Result of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct DrumOutcome {
    /// Why it stopped.
    pub stop: DrumStop,
    /// Time reached (s).
    pub t_end: f64,
    /// Overturned: static tipping, fallen, or slid off.
    pub overturned: bool,
    /// Largest absolute rotation of each drum (rad).
    pub peak_rotation: Vec<f64>,
    /// Largest absolute slip of each joint (m).
    pub peak_slip: Vec<f64>,
    /// Slip of each joint at the end (m, signed: + when the upper face moved to +x).
    pub residual_slip: Vec<f64>,
    /// Largest absolute horizontal displacement of the top drum's centre (m).
    pub peak_top_displacement: f64,
    /// Energy balance.
    pub energy: DrumEnergy,
    /// Number of events of each kind (opening, impact, slip_start, slip_stop, lift_off, landing,
    /// overturned), counted even when the events are not kept.
    pub event_counts: [usize; 7],
    /// Events (when kept).
    pub events: Vec<DrumEvent>,
    /// History (when kept).
    pub history: Option<DrumHistory>,
    /// Modes of the joints at the end.
    pub modes_end: Vec<JointMode>,
    /// Work counters.
    pub counters: StepCounters,
    /// Counters of the condensed steps (`SchemeOptions::clusters`; zero otherwise).
    pub clusters: super::clusters::ClusterCounters,
    /// The scheme switches of the automatic scheme ([`super::auto`]; empty otherwise).
    pub switches: Vec<SchemeSwitch>,
    /// Simulated time spent in the event-driven driver (s; 0 unless [`super::auto`]).
    pub time_event_driven: f64,
}

/// The two schemes of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SchemePart {
    /// The thesis's event-driven driver ([`crate::driver`]).
    EventDriven,
    /// Moreau–Jean time stepping ([`super::moreau`]).
    Moreau,
}

impl SchemePart {
    /// The name in outputs.
    pub fn name(self) -> &'static str {
        match self {
            SchemePart::EventDriven => "event_driven",
            SchemePart::Moreau => "moreau",
        }
    }
}

/// A hand-over of the automatic scheme ([`super::auto`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SchemeSwitch {
    /// Time (s).
    pub t: f64,
    /// The scheme that ran before.
    pub from: SchemePart,
    /// The scheme that runs after.
    pub to: SchemePart,
    /// Why: `events_crowd`, `sliding`, `tension`, `event_cap` (to Moreau–Jean), `calm` (back).
    pub why: &'static str,
    /// Kinetic energy before and after the state was mapped (J; equal to round-off to Moreau–Jean;
    /// back, the closed joints' relative rates are dropped).
    pub kinetic_before: f64,
    /// See `kinetic_before`.
    pub kinetic_after: f64,
    /// Handed back: the largest joint slip (m), within the tolerance, that the driver's
    /// kinematics (faces aligned) drops; the slips restart from zero.
    pub slip_dropped: f64,
}

/// Why a run failed.
#[derive(Clone, Debug, PartialEq)]
pub enum DrumError {
    /// Bad options.
    Option(DrumOptionError),
    /// The contact problem could not be solved at this time (s).
    Contact {
        /// Time.
        t: f64,
    },
}

impl fmt::Display for DrumError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DrumError::Option(e) => write!(f, "invalid drum option {e}"),
            DrumError::Contact { t } => write!(f, "contact problem unsolvable at t = {t} s"),
        }
    }
}

impl std::error::Error for DrumError {}
