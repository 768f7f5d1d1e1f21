//! The explicit state of a loop's run ([`LoopState`]), its options, its events and its outcome.

use crate::chain::Chain;
use crate::error::RockingError;
use crate::model::cone::ModelOptions;
use crate::model::configuration::Status;

/// Options of a loop's time history.
#[derive(Clone, Debug)]
pub struct LoopOptions {
    /// Gravity (m/s², positive).
    pub gravity: f64,
    /// Time step (s).
    pub dt: f64,
    /// End of the run (s).
    pub duration: f64,
    /// The models' options.
    pub model: ModelOptions,
    /// Settled when the kinetic energy after an impact is below this share of the run's largest.
    pub settle_ratio: f64,
    /// Collapse safeguard: a hinge angle beyond this (rad).
    pub collapse_angle: f64,
    /// Ask the opening model every this many steps while moving (1: every step).
    pub check_every: usize,
    /// Record the state every this many steps (0: no history).
    pub record_every: usize,
    /// Project the open DOFs onto the closure after every step (positions onto `G(q) = 0`,
    /// rates onto `G v = 0`, kinetic metric); `false`: only measure the residual.
    pub project: bool,
    /// Locking a chattering joint: a closing whose impact keeps more than `1 − lock_loss` of the
    /// kinetic energy, with every closing joint's rate below [`LoopOptions::lock_rate`], closes
    /// the joints for good (their rates removed by the kinetic-metric projection with the
    /// closure) instead of adopting the impact model's configuration.
    pub lock_loss: f64,
    /// The rate below which a closing joint may be locked (rad/s); `None`: `g dt / L`, the rate
    /// gravity gives in one step at the chain's reach `L` (a rebound slower than this lasts
    /// about one step: the fixed step cannot resolve it).
    pub lock_rate: Option<f64>,
    /// Short flights: a joint an impact opens whose flight, predicted from its rate `ω` and the
    /// acceleration `α` just after the impact (`2ω/|α|`, the flight under constant `α`), is
    /// shorter than this many steps is kept closed, as a joint opened slower than
    /// [`LoopOptions::lock_rate`] always is (0: only the lock rate). Faster than the step, such
    /// a flight's angle (`ω²/2|α|`, below `|α| dt²/8`) is beyond what the fixed step resolves,
    /// and it vanishes as `dt` does.
    pub min_flight: f64,
    /// Stop early at the first step at or after this time (s) at which the loop is closed and
    /// at rest. The caller states that the motion from then on stays inside the accelerations
    /// the closed loop resists (e.g. a record after its last exceedance of `λ g`): the loop can
    /// then never move again, so the rest of the run is known (exact). `None`: run to the end.
    pub quiet_after: Option<f64>,
    /// The exact screen of the opening model while moving ([`Screen`]; default [`Screen::On`]).
    /// Set it explicitly to compare or verify (tests/loop_screen.rs); the library never reads
    /// the environment for it ([`Screen::from_env`] is for harnesses that choose to).
    pub screen: Screen,
}

/// The opening model's screen after a moving step (docs/arch-performance.md). The model is a
/// projection in the kinetic metric (Gauss's principle over the cone of admissible
/// accelerations with the closure, a convex problem whose relaxation has a unique optimum): when
/// the current mechanism's own constrained accelerations satisfy its optimality conditions —
/// every closed DOF's contact multiplier of the admissible sign, by a margin far above
/// round-off — the model's answer is the current configuration, so the model need not be asked.
/// Where the conditions fail or are too close to call, the model answers as before.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Screen {
    /// Ask the opening model after every moving step.
    Off,
    /// Skip the model where the screen proves its answer is the current configuration.
    On,
    /// Ask the model always, and panic if it ever differs from what the screen proved (tests).
    Verify,
}

impl Screen {
    /// From the environment variable `ROCKING_LOOP_SCREEN` (`off`, `on`, `verify`); unset or
    /// anything else: [`Screen::On`]. Only for harnesses that opt in (the `arch_record` example,
    /// the arch bench): [`LoopOptions::default`] does not call it.
    pub fn from_env() -> Screen {
        match std::env::var("ROCKING_LOOP_SCREEN").as_deref() {
            Ok("off") => Screen::Off,
            Ok("verify") => Screen::Verify,
            _ => Screen::On,
        }
    }
}

impl Default for LoopOptions {
    fn default() -> LoopOptions {
        LoopOptions {
            gravity: crate::model::column::GRAVITY,
            dt: 1e-3,
            duration: 10.0,
            model: ModelOptions::default(),
            settle_ratio: 1e-6,
            collapse_angle: std::f64::consts::FRAC_PI_4,
            check_every: 1,
            record_every: 0,
            project: true,
            lock_loss: 1e-6,
            lock_rate: None,
            min_flight: 0.0,
            quiet_after: None,
            screen: Screen::On,
        }
    }
}

/// The state of a loop: time, DOF angles and rates (`2J`, SPEC §1 order), statuses (`J`).
#[derive(Clone, Debug, PartialEq)]
pub struct LoopState {
    pub time: f64,
    pub phi: Vec<f64>,
    pub rates: Vec<f64>,
    pub statuses: Vec<Status>,
}

impl LoopState {
    /// The closed loop at rest at time 0.
    pub fn at_rest(chain: &Chain) -> LoopState {
        LoopState {
            time: 0.0,
            phi: vec![0.0; chain.n_dofs()],
            rates: vec![0.0; chain.n_dofs()],
            statuses: vec![Status::Closed; chain.n_joints()],
        }
    }

    /// The open DOFs.
    pub fn open_dofs(&self) -> Vec<usize> {
        crate::model::configuration::open_dofs(&self.statuses)
    }

    /// The angles and rates of the DOFs `open` (the reduced vectors of the integrators) into
    /// `x` and `v` (cleared first), reusing their memory.
    pub(crate) fn open_values_into(&self, open: &[usize], x: &mut Vec<f64>, v: &mut Vec<f64>) {
        x.clear();
        x.extend(open.iter().map(|&d| self.phi[d]));
        v.clear();
        v.extend(open.iter().map(|&d| self.rates[d]));
    }

    /// [`LoopState::open_dofs`] into `out` (cleared first), reusing its memory.
    pub fn open_dofs_into(&self, out: &mut Vec<usize>) {
        let n = self.statuses.len();
        out.clear();
        out.extend(
            self.statuses
                .iter()
                .enumerate()
                .filter_map(|(k, s)| s.dof(k, n)),
        );
    }
}

/// What happened.
#[derive(Clone, Debug, PartialEq)]
pub enum LoopEventKind {
    /// The opening model chose a new configuration (from rest, or a new hinge while moving).
    Opening,
    /// The flagged joints closed; the impact model chose the configuration after.
    Closing {
        joints: Vec<usize>,
        kinetic_before: f64,
        kinetic_after: f64,
    },
    /// The flagged joints closed at a rate too small to resolve (a chatter): locked, their rates
    /// removed by the kinetic-metric projection with the closure.
    Locked {
        joints: Vec<usize>,
        kinetic_before: f64,
        kinetic_after: f64,
    },
    /// The kinetic energy vanished: at rest.
    Settled,
    /// The mechanism passed its point of no return.
    Collapsed,
}

/// An event, with the statuses after it (`-1`, `0`, `+1` per joint).
#[derive(Clone, Debug, PartialEq)]
pub struct LoopEvent {
    pub time: f64,
    pub kind: LoopEventKind,
    pub statuses: Vec<i8>,
}

/// The result of a run.
#[derive(Clone, Debug)]
pub struct LoopOutcome {
    pub events: Vec<LoopEvent>,
    /// The state at the end (the collapse, or the duration).
    pub state: LoopState,
    pub collapsed: bool,
    /// Largest `|φ|` of any DOF, over the step ends and the events (every state the history
    /// can hold).
    pub peak_angle: f64,
    /// Largest closure residual of the state after a step (m): `max(|gap|, |rotation| × reach)`
    /// (after the projection when [`LoopOptions::project`]).
    pub max_closure_residual: f64,
    /// Largest closure residual one integration step leaves before the projection (m).
    pub max_step_drift: f64,
    /// `(t, φ)` samples every [`LoopOptions::record_every`] steps and at events.
    pub history: Vec<(f64, Vec<f64>)>,
    /// Questions to the opening model after a moving step, and how many of them the screen
    /// answered ([`LoopOptions::screen`]; with [`Screen::Verify`], would have answered).
    pub moving_checks: usize,
    pub screened: usize,
    /// The energy balance of the run (its residual is the scheme's error).
    pub energy: super::LoopEnergy,
    /// Whether the closed loop at rest resists its own weight (`a_g = 0`, the opening model's
    /// answer), once the run has been closed at rest (`None` if it never was): `false` for an
    /// arch thinner than its minimum thickness, which collapses whatever the ground does.
    pub stands_under_own_weight: Option<bool>,
}

/// Errors of a loop run.
#[derive(Clone, Debug)]
pub enum LoopError {
    /// Bad options (the field named).
    Options(String),
    /// A model failed.
    Model(RockingError),
    /// The constrained equations were singular at time `t`.
    Singular(f64),
    /// Events without time advancing (100 in a row) at time `t`: the located closures and the
    /// models' choices chatter (a joint the impact or opening model opens recloses at once).
    Stalled(f64),
}

impl std::fmt::Display for LoopError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LoopError::Options(s) => write!(f, "invalid option: {s}"),
            LoopError::Model(e) => write!(f, "{e}"),
            LoopError::Singular(t) => {
                write!(f, "the constrained equations are singular at t = {t} s")
            }
            LoopError::Stalled(t) => write!(f, "events without progress at t = {t} s"),
        }
    }
}

impl std::error::Error for LoopError {}

impl From<RockingError> for LoopError {
    fn from(e: RockingError) -> LoopError {
        LoopError::Model(e)
    }
}
