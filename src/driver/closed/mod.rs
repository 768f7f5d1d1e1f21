//! Time histories of a closed chain (an arch on its abutments, a capped colonnade; SPEC §9).
//!
//! The state is explicit ([`LoopState`]: time, the `2J` DOF angles and rates, the joints'
//! statuses); a run carries it forward with a fixed step, one event at a time:
//!
//! - **at rest** (every rate zero): the opening model is asked at every step under the current
//!   ground acceleration — no reaction test exists in a loop (SPEC §9), the model answers: the loop
//!   starts to move when it returns a non-zero acceleration, in the configuration it chose;
//! - **moving**: the open DOFs are integrated by RK4 with the closure at acceleration level
//!   ([`LoopEquations`]: `[M_FF G_Fᵀ; G_F 0][a; μ] = [q_F + f_F; −Ġ v]`, exact velocity terms).
//!   Positions are not projected: the closure residual (the last body's gap to its support, the
//!   angle times the chain's reach) is measured after every step and reported
//!   ([`LoopOutcome::max_closure_residual`]); with RK4 it stays at the truncation error;
//! - **closing**: an open DOF whose depth (`|φ|` on the admissible side) reaches zero inside a
//!   step. The instant is located by linear interpolation on the first DOF to cross; every open
//!   joint whose DOF crosses zero within the same step is flagged as closing (a four-hinge loop
//!   closes its four hinges together; resolution: one step), the state is moved there by linear
//!   interpolation, the closing angles set to zero, and the constrained impact model chooses the
//!   configuration and rates after;
//! - **opening while moving**: after every accepted step the opening model is asked with the
//!   current configuration; if it prefers another (a new hinge), the new joints open at zero
//!   angle;
//! - **settling**: when the kinetic energy after an impact falls below
//!   [`LoopOptions::settle_ratio`] times the largest kinetic energy of the run, the rates are
//!   set to zero (at rest; the closing joints are then closed);
//! - **collapse**: the mechanism passes its point of no return — the potential energy along the
//!   motion passes its maximum while the hinges keep opening: the power of gravity on the open
//!   DOFs turns positive while the total hinge depth grows (for a one-DOF mechanism exactly the
//!   maximum of `V` along the mechanism, after which gravity alone drives it down); or, as a
//!   safeguard, a hinge angle beyond [`LoopOptions::collapse_angle`].
//!
//! This driver does not yet go through the column's pipeline (`run.rs` with the
//! `ChainDynamics` traits of `chain.rs`); see `docs/arches.md`.

mod equations;

pub use equations::LoopEquations;

use crate::chain::Chain;
use crate::error::RockingError;
use crate::ground::GroundMotion;
use crate::model::cone::ModelOptions;
use crate::model::configuration::Status;
use crate::model::constrained::{impact_model_constrained, opening_model_constrained};

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
    /// Largest `|φ|` of any DOF.
    pub peak_angle: f64,
    /// Largest closure residual after a step (m): `max(|gap|, |rotation| × reach)`.
    pub max_closure_residual: f64,
    /// `(t, φ)` samples every [`LoopOptions::record_every`] steps and at events.
    pub history: Vec<(f64, Vec<f64>)>,
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

fn codes(statuses: &[Status]) -> Vec<i8> {
    statuses.iter().map(|s| s.as_i8()).collect()
}

/// The admissible sign of a DOF's angle (`phĭ ≤ 0`, `phî ≥ 0`).
fn side(dof: usize, n: usize) -> f64 {
    if dof < n {
        -1.0
    } else {
        1.0
    }
}

/// Runs a time history of the loop `chain` under `motion` from `start` (e.g.
/// [`LoopState::at_rest`], or the closed loop moving in a mechanism).
pub fn simulate_loop(
    chain: &Chain,
    motion: &dyn GroundMotion,
    start: LoopState,
    options: &LoopOptions,
) -> Result<LoopOutcome, LoopError> {
    let bad = |name: &str, v: f64| LoopError::Options(format!("{name} = {v}"));
    if !(options.dt > 0.0 && options.dt.is_finite()) {
        return Err(bad("dt", options.dt));
    }
    if !(options.duration >= 0.0 && options.duration.is_finite()) {
        return Err(bad("duration", options.duration));
    }
    if !(options.gravity > 0.0 && options.gravity.is_finite()) {
        return Err(bad("gravity", options.gravity));
    }
    if options.collapse_angle.is_nan() || options.collapse_angle <= 0.0 {
        return Err(bad("collapse_angle", options.collapse_angle));
    }
    if !chain.is_loop() {
        return Err(LoopError::Options("chain: not a loop".into()));
    }
    let (m, n) = (chain.n_dofs(), chain.n_joints());
    if start.phi.len() != m || start.rates.len() != m || start.statuses.len() != n {
        return Err(LoopError::Options(format!(
            "start: {} angles, {} rates, {} statuses; the chain has {m} DOFs and {n} joints",
            start.phi.len(),
            start.rates.len(),
            start.statuses.len()
        )));
    }
    Runner::new(chain, motion, options).run(start)
}

struct Runner<'a> {
    chain: &'a Chain,
    motion: &'a dyn GroundMotion,
    options: &'a LoopOptions,
    equations: LoopEquations<'a>,
    /// Reach of the chain (m), to express the closure's rotation residual as a length.
    reach: f64,
    max_kinetic: f64,
    out: LoopOutcome,
}

impl<'a> Runner<'a> {
    fn new(chain: &'a Chain, motion: &'a dyn GroundMotion, options: &'a LoopOptions) -> Self {
        let joints = chain.joints();
        let reach = joints
            .iter()
            .map(|j| {
                let (a, b) = (joints[0].centre, j.centre);
                (a[0] - b[0]).hypot(a[1] - b[1])
            })
            .fold(0.0, f64::max);
        Runner {
            chain,
            motion,
            options,
            equations: LoopEquations::new(chain, options.gravity),
            reach,
            max_kinetic: 0.0,
            out: LoopOutcome {
                events: Vec::new(),
                state: LoopState::at_rest(chain),
                collapsed: false,
                peak_angle: 0.0,
                max_closure_residual: 0.0,
                history: Vec::new(),
            },
        }
    }

    fn ag(&self, t: f64) -> f64 {
        self.motion.acceleration(t)
    }

    fn kinetic(&self, s: &LoopState) -> f64 {
        let pose = self.chain.pose(&s.phi);
        let mass = self.chain.mass_matrix(&pose);
        let m = self.chain.n_dofs();
        0.5 * (0..m)
            .map(|a| s.rates[a] * (0..m).map(|b| mass[a * m + b] * s.rates[b]).sum::<f64>())
            .sum::<f64>()
    }

    fn event(&mut self, s: &LoopState, kind: LoopEventKind) {
        self.out.events.push(LoopEvent {
            time: s.time,
            kind,
            statuses: codes(&s.statuses),
        });
        if self.options.record_every > 0 {
            self.out.history.push((s.time, s.phi.clone()));
        }
    }

    /// The opening model at `s` under `ag`: adopts its configuration if it differs (new joints at
    /// zero angle) and, from rest, only if it moves something. Returns whether it changed.
    fn opening(&mut self, s: &mut LoopState, ag: f64) -> Result<bool, LoopError> {
        let pose = self.chain.pose(&s.phi);
        let mass = self.chain.mass_matrix(&pose);
        let q = self.chain.load_vector(&pose, ag, self.options.gravity);
        let f = self.chain.velocity_load(&pose, &s.phi, &s.rates);
        let load: Vec<f64> = q.iter().zip(&f).map(|(a, b)| a + b).collect();
        let g = self.chain.closure_matrix(&pose);
        let rhs: Vec<f64> = self
            .chain
            .closure_rate(&pose, &s.rates)
            .iter()
            .map(|x| -x)
            .collect();
        let mut statuses = s.statuses.clone();
        let mut acc = vec![0.0; self.chain.n_dofs()];
        opening_model_constrained(
            &mass,
            &load,
            &g,
            Some(&rhs),
            &mut statuses,
            &mut acc,
            &self.options.model,
        )?;
        // A joint the model opens with zero acceleration (to round-off) at zero angle and rate
        // does not move: it stays closed (else it chatters back through zero at once).
        let scale = acc.iter().fold(0.0, |m: f64, a| m.max(a.abs()));
        let n = statuses.len();
        for k in 0..n {
            if let Some(d) = statuses[k].dof(k, n) {
                let at_zero = s.phi[d] == 0.0 && s.rates[d] == 0.0 && !s.statuses[k].is_open();
                if at_zero && acc[d].abs() <= 1e-12 * scale {
                    statuses[k] = Status::Closed;
                    acc[d] = 0.0;
                }
            }
        }
        let moving = s.rates.iter().any(|&r| r != 0.0);
        let moves = acc.iter().any(|&a| a != 0.0);
        // From rest: adopt what the model chose when it moves something; while moving: adopt a
        // different configuration.
        if (!moving && moves) || (moving && statuses != s.statuses) {
            s.statuses = statuses;
            self.event(s, LoopEventKind::Opening);
            return Ok(true);
        }
        Ok(false)
    }

    fn residual(&self, phi: &[f64]) -> f64 {
        let r = self.chain.closure_residual(&self.chain.pose(phi));
        r[1].hypot(r[2]).max(r[0].abs() * self.reach)
    }

    /// Collapse: gravity's power on the open DOFs positive while the total hinge depth grows; or
    /// a hinge angle beyond the safeguard.
    fn collapsed(&self, s: &LoopState, open: &[usize]) -> bool {
        let n = self.chain.n_joints();
        if s.phi.iter().any(|p| p.abs() > self.options.collapse_angle) {
            return true;
        }
        let pose = self.chain.pose(&s.phi);
        let gravity = self.chain.load_vector(&pose, 0.0, self.options.gravity);
        let power: f64 = open.iter().map(|&d| gravity[d] * s.rates[d]).sum();
        let opening: f64 = open.iter().map(|&d| side(d, n) * s.rates[d]).sum();
        power > 0.0 && opening > 0.0
    }

    fn run(mut self, start: LoopState) -> Result<LoopOutcome, LoopError> {
        let opts = self.options;
        let n = self.chain.n_joints();
        let mut s = start;
        let t_end = opts.duration;
        let mut steps = 0usize;
        let (mut last_event_time, mut stalled) = (f64::NAN, 0usize);
        self.max_kinetic = self.kinetic(&s);
        if opts.record_every > 0 {
            self.out.history.push((s.time, s.phi.clone()));
        }
        while s.time < t_end - 1e-12 * opts.dt {
            let dt = opts.dt.min(t_end - s.time);
            let at_rest = s.rates.iter().all(|&r| r == 0.0);
            let ag_now = self.ag(s.time);
            if at_rest && !self.opening(&mut s, ag_now)? {
                s.time += dt;
                continue;
            }
            let open = s.open_dofs();
            let x: Vec<f64> = open.iter().map(|&d| s.phi[d]).collect();
            let v: Vec<f64> = open.iter().map(|&d| s.rates[d]).collect();
            let (mut x1, mut v1) = (vec![0.0; open.len()], vec![0.0; open.len()]);
            let motion = self.motion;
            let ag = |t: f64| motion.acceleration(t);
            let depth = |d: usize, xi: f64| side(d, n) * xi;
            // A joint that opened at this instant (depth 0) and is back through zero within the
            // step, or one that dips through zero and comes back, cannot be located by linear
            // interpolation: the step is halved until none does (down to 1e-9 dt).
            let mut h = dt;
            let crossings = loop {
                if !self
                    .equations
                    .rk4_step(&open, &ag, s.time, h, &x, &v, &mut x1, &mut v1)
                {
                    return Err(LoopError::Singular(s.time));
                }
                // Closing: open DOFs whose depth reaches zero in the step.
                let mut fresh = false;
                let crossings: Vec<(usize, f64)> = (0..open.len())
                    .filter_map(|i| {
                        let (d0, d1) = (depth(open[i], x[i]), depth(open[i], x1[i]));
                        if d1 > 0.0 || (d0 == 0.0 && d1 == 0.0) {
                            return None;
                        }
                        let frac = if d0 > 0.0 { d0 / (d0 - d1) } else { 0.0 };
                        // Moving away from closure at the located instant: it dipped through
                        // zero and came back within the step.
                        let rate = v[i] + frac * (v1[i] - v[i]);
                        fresh |= d0 == 0.0 || depth(open[i], rate) > 0.0;
                        Some((i, frac))
                    })
                    .collect();
                if fresh && h > 1e-9 * dt {
                    h *= 0.5;
                    continue;
                }
                break crossings;
            };
            let dt = h;
            if let Some(frac) = crossings.iter().map(|c| c.1).reduce(f64::min) {
                s.time += frac * dt;
                for i in 0..open.len() {
                    s.phi[open[i]] = x[i] + frac * (x1[i] - x[i]);
                    s.rates[open[i]] = v[i] + frac * (v1[i] - v[i]);
                }
                // Flagged: the crossing DOFs moving towards closure at the instant.
                let mut closing = vec![false; n];
                for &(i, _) in &crossings {
                    // At the refinement's floor, a rate at round-off moving away (a joint
                    // that opened with zero acceleration) is taken as zero.
                    let d = open[i];
                    let scale = v.iter().fold(0.0, |m: f64, r| m.max(r.abs()));
                    if h <= 1e-9 * opts.dt && s.rates[d].abs() <= 1e-8 * scale {
                        s.rates[d] = 0.0;
                    }
                    if depth(d, s.rates[d]) <= 0.0 {
                        s.phi[open[i]] = 0.0;
                        closing[open[i] % n] = true;
                    }
                }
                self.out.max_closure_residual =
                    self.out.max_closure_residual.max(self.residual(&s.phi));
                if s.time == last_event_time {
                    stalled += 1;
                    if stalled >= 100 {
                        return Err(LoopError::Stalled(s.time));
                    }
                } else {
                    (last_event_time, stalled) = (s.time, 0);
                }
                let before = self.kinetic(&s);
                self.max_kinetic = self.max_kinetic.max(before);
                let pose = self.chain.pose(&s.phi);
                let mass = self.chain.mass_matrix(&pose);
                let g = self.chain.closure_matrix(&pose);
                let report = impact_model_constrained(
                    &mass,
                    &g,
                    &mut s.statuses,
                    &mut s.rates,
                    &closing,
                    &opts.model,
                )?;
                let joints = (0..n).filter(|&k| closing[k]).collect();
                self.event(
                    &s,
                    LoopEventKind::Closing {
                        joints,
                        kinetic_before: report.kinetic_before,
                        kinetic_after: report.kinetic_after,
                    },
                );
                let open_after = s.statuses.iter().filter(|st| st.is_open()).count();
                if report.kinetic_after <= opts.settle_ratio * self.max_kinetic || open_after < 4 {
                    s.rates.iter_mut().for_each(|r| *r = 0.0);
                    for k in 0..n {
                        if s.phi[k] == 0.0 && s.phi[n + k] == 0.0 {
                            s.statuses[k] = Status::Closed;
                        }
                    }
                    self.event(&s, LoopEventKind::Settled);
                }
                continue;
            }
            s.time += dt;
            for i in 0..open.len() {
                s.phi[open[i]] = x1[i];
                s.rates[open[i]] = v1[i];
            }
            steps += 1;
            self.out.max_closure_residual =
                self.out.max_closure_residual.max(self.residual(&s.phi));
            self.out.peak_angle = s
                .phi
                .iter()
                .fold(self.out.peak_angle, |p, x| p.max(x.abs()));
            if opts.record_every > 0 && steps % opts.record_every == 0 {
                self.out.history.push((s.time, s.phi.clone()));
            }
            self.max_kinetic = self.max_kinetic.max(self.kinetic(&s));
            if self.collapsed(&s, &open) {
                self.out.collapsed = true;
                self.event(&s, LoopEventKind::Collapsed);
                break;
            }
            if opts.check_every > 0 && steps % opts.check_every == 0 {
                let ag_now = self.ag(s.time);
                self.opening(&mut s, ag_now)?;
            }
        }
        self.out.state = s;
        Ok(self.out)
    }
}
