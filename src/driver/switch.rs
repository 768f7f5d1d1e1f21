//! The event-driven side of the automatic scheme (`crate::contact::auto`,
//! docs/auto-scheme.md): a run of the driver that starts from a state handed
//! over by the Moreau–Jean scheme, and stops, handing the state over, when events crowd or when
//! it meets what only the contact scheme can carry on (a slip, tension, the event cap).

use std::collections::VecDeque;

use super::dynamics::ColumnDynamics;
use super::problem::Problem;
use super::{run, DriverError, Outcome, SimulationOptions, StopReason};
use crate::ground::GroundMotion;
use crate::model::column::Column;
use crate::model::configuration::Status;

/// The driver's state in the thesis's interface coordinates at one instant: what the two
/// schemes hand over to each other.
#[derive(Clone, Debug, PartialEq)]
pub struct InterfaceState {
    /// Time (s).
    pub t: f64,
    /// DOF angles (rad, `2n`: `phĭ_0 … phĭ_{n−1}, phî_0 … phî_{n−1}`).
    pub phi: Vec<f64>,
    /// DOF rates (rad/s, `2n`).
    pub rates: Vec<f64>,
    /// Configuration.
    pub statuses: Vec<Status>,
}

/// When events crowd: more than `max_events` events (openings, impacts, settlings, same-instant
/// chains counted one by one) within the last `window` seconds of simulated time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrowdingRule {
    /// The window (s).
    pub window: f64,
    /// Events allowed within it.
    pub max_events: usize,
}

/// The memory of the crowding rule: the times of the events within the window.
pub(crate) struct Crowding {
    rule: CrowdingRule,
    times: VecDeque<f64>,
    seen: usize,
}

impl Crowding {
    pub fn new(rule: CrowdingRule) -> Crowding {
        Crowding {
            rule,
            times: VecDeque::new(),
            seen: 0,
        }
    }

    /// Before a step at `t`, with `counted` events so far (those since the last call happened
    /// within the last step, and are dated `t`): whether the events crowd.
    pub fn observe(&mut self, t: f64, counted: usize) -> bool {
        while self.seen < counted {
            self.times.push_back(t);
            self.seen += 1;
        }
        while self
            .times
            .front()
            .is_some_and(|&s| s <= t - self.rule.window)
        {
            self.times.pop_front();
        }
        self.times.len() > self.rule.max_events
    }
}

/// Why the driver handed a run over to the contact scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Handover {
    /// The events crowded ([`CrowdingRule`]).
    Crowded,
    /// Friction exceeded at this interface (the driver has no slip DOF).
    Sliding {
        /// Interface.
        interface: usize,
    },
    /// Tension at this interface (the driver has no flight).
    Tension {
        /// Interface.
        interface: usize,
    },
    /// The event cap (`stopping.max_events_per_second`).
    EventCap,
}

impl Handover {
    /// The name in `events.jsonl` (`why` of a `scheme_switch`).
    pub fn name(self) -> &'static str {
        match self {
            Handover::Crowded => "events_crowd",
            Handover::Sliding { .. } => "sliding",
            Handover::Tension { .. } => "tension",
            Handover::EventCap => "event_cap",
        }
    }
}

/// A segment of a run in the driver.
#[derive(Clone, Debug)]
pub struct Segment {
    /// Its outcome: events, history, peaks, the energy balance of the segment (its
    /// `potential_change` from the segment's start). With a handover the stop reason is the one
    /// the driver met, or [`StopReason::TooManyEvents`] when the events crowded.
    pub outcome: Outcome,
    /// Kinetic energy at the segment's start (J).
    pub kinetic_start: f64,
    /// The state it ended at.
    pub end: InterfaceState,
    /// Why it handed the run over (`None`: the run stopped).
    pub handover: Option<Handover>,
}

/// Runs `column` in the driver from `start` (`None`: released as `options.initial` says, at
/// time 0) until a stop, or a handover under `rule`. Without a handover, and from `None`, the
/// outcome is [`super::simulate`]'s bit for bit.
pub fn simulate_segment(
    column: &Column,
    motion: &dyn GroundMotion,
    options: &SimulationOptions,
    start: Option<&InterfaceState>,
    rule: CrowdingRule,
    progress: Option<&mut dyn FnMut(f64)>,
) -> Result<Segment, DriverError> {
    let options = options.run();
    options.validate(column)?;
    let physics = options.physics;
    let mut chain = ColumnDynamics::new(
        column,
        physics.gravity,
        physics.exact_velocity_terms,
        physics.model.tolerance,
        physics.friction,
    );
    let kinetic_start = match start {
        Some(s) => {
            use super::chain::ChainDynamics;
            let open = crate::model::configuration::open_dofs(&s.statuses);
            chain.energy(&open, &s.phi, &s.rates).0
        }
        None => 0.0,
    };
    let problem = Problem::new(chain, motion, options);
    let (outcome, state, crowded) = run::run_segment(problem, progress, start, Some(rule))?;
    let handover = if crowded {
        Some(Handover::Crowded)
    } else {
        match outcome.stop_reason {
            StopReason::Sliding { interface } => Some(Handover::Sliding { interface }),
            StopReason::Tension { interface } => Some(Handover::Tension { interface }),
            StopReason::TooManyEvents => Some(Handover::EventCap),
            _ => None,
        }
    };
    Ok(Segment {
        outcome,
        kinetic_start,
        end: state.interface_state(),
        handover,
    })
}
