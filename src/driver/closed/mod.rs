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
//!   After every step the open DOFs are projected back onto the closure (positions onto
//!   `G(q) = 0` by Newton steps in the kinetic metric, rates onto `G v = 0`;
//!   [`project_positions`], [`project_rates`]); the closure residual (the last body's gap to its
//!   support, the angle times the chain's reach) is reported before the projection
//!   ([`LoopOutcome::max_step_drift`]) and after it ([`LoopOutcome::max_closure_residual`]);
//! - **closing**: an open DOF whose depth (`|φ|` on the admissible side) reaches zero inside a
//!   step. Each open DOF's first zero is located on the step's cubic Hermite interpolant (its
//!   angles and rates at both ends; `locate.rs`), which also sees a DOF dipping through zero and
//!   back within the step and one that opened at this instant and is back within it; the state
//!   is carried to the earliest zero by RK4 again from the start of the step over the located
//!   fraction; every DOF whose zero lies within `SIMULTANEOUS` (1e-6 dt) of the earliest is
//!   flagged with it (a four-hinge loop closes its four hinges at one instant, SPEC §9: their
//!   located zeros differ by the interpolant's error, below 1e-12 s here), their angles set to
//!   zero (the rest projected back onto the closure), and the constrained impact model chooses
//!   the configuration and rates after; the next step starts at the event. Closings further
//!   apart are separate impacts, in order;
//! - **locking a chattering joint**: a joint flipping between its faces at a vanishing rate
//!   (a Zeno sequence of impacts, each losing almost nothing) cannot be resolved by a fixed step.
//!   When the impact keeps more than `1 − lock_loss` of the kinetic energy and every closing
//!   joint's rate is below `lock_rate` (default `g dt / L`, `L` the chain's reach: the rate
//!   gravity gives in one step at the chain's size, below which a rebound about the other corner
//!   would last about one step), the closing joints are locked instead — closed, their rates
//!   removed by the kinetic-metric projection together with the closure (the limit of such a
//!   Zeno sequence is sustained contact; SPEC §5's settling of a column does the same). The
//!   opening model, asked after the next step, reopens them if the loads call for it;
//! - **no flight slower than the lock rate**: a joint the impact model opens (at zero angle)
//!   with a rate below `lock_rate` is kept closed, for the same reason (and, with
//!   [`LoopOptions::min_flight`], one whose predicted flight is shorter than that many steps):
//!   the rates are the kinetic-metric projection of the model's onto the other open DOFs with
//!   the closure. Without this, a nearly closed arch rattles: each closing opens a fan of
//!   neighbouring joints on the other face at rates of 1e-5 rad/s, which close again one after
//!   another microseconds later, each closing opening the next fan (docs/arches.md §2b);
//! - **opening while moving**: after every accepted step the opening model is asked with the
//!   current configuration; if it prefers another (a new hinge), the new joints open at zero
//!   angle. Where the current mechanism satisfies the model's optimality conditions with a
//!   margin, its answer is the current configuration and it is not called ([`Screen`], exact);
//! - **a step from rest whose opening closes at once** (the mechanism the model opened under
//!   `a_g(t)` is back in closure at the step's start and the loop settles into the state it
//!   started from) is rested through, rather than repeated at the same instant;
//! - **settling**: when the kinetic energy after an impact falls below
//!   [`LoopOptions::settle_ratio`] times the largest kinetic energy of the run, the rates are
//!   set to zero (at rest; the closing joints are then closed, and the loop is closed outright
//!   when no point lies farther than `SNAP_DISTANCE`, 1 nm, from the closed geometry);
//! - **collapse**: the mechanism has passed its point of no return. (a) For any mechanism: the
//!   potential energy of the weight below the closed loop's, `V < V₀` (beyond the slack the
//!   closure residual allows). A loop stable under its self-weight (thicker than the minimum,
//!   the opening model returns zero at `a_g = 0`) has its closed configuration as a strict local
//!   minimum of `V` over the admissible mechanisms: every path from it climbs, so a pose with
//!   `V < V₀` lies beyond the barrier. (b) For a one-DOF mechanism (four open joints), already
//!   at the maximum of `V` along it: gravity's power turns positive while the hinges open
//!   (DeJong's four-hinge criterion, the analogue of a column's centre passing its pivot). With
//!   more DOFs, gravity's power on some of them says nothing about the whole, so (a) alone
//!   decides. (b) also requires `V > V₀` (a path from the closed loop climbs before it can pass
//!   a maximum; a mechanism restarted from rest a hair from closure has gravity's power at
//!   round-off). (c) Safeguard: a hinge angle beyond [`LoopOptions::collapse_angle`].
//!
//! Files: this one holds the run's loop (`simulate_loop`, one step at a time); `opening.rs` the
//! opening model from rest and while moving and the at-rest interval; `closing.rs` the located
//! closings, the impact model, the locks; `collapse.rs` settling and collapse; `locate.rs` the
//! zeros on the step's cubic; `equations.rs` the constrained equations and RK4; `projection.rs`
//! the projections onto the closure; `state.rs` the state, options, events and outcome.
//!
//! `energy.rs` keeps the run's energy balance beside it. This driver has its own loop rather
//! than the column's pipeline (`run.rs` with the `ChainDynamics` traits of `chain.rs`): no
//! reaction test, the closure projected after every step, several joints closing at once
//! (docs/arches.md, "What remains", says why it is kept).

mod closing;
mod collapse;
mod energy;
mod equations;
mod locate;
mod opening;
mod projection;
mod state;
#[cfg(test)]
mod tests;

pub use energy::LoopEnergy;
pub use equations::LoopEquations;
pub use projection::{project_positions, project_rates};
use projection::{project_positions_posed, project_rates_with, ProjectionWork};
pub use state::{LoopError, LoopEvent, LoopEventKind, LoopOptions, LoopOutcome, LoopState, Screen};

use crate::chain::{Chain, ChainPose, MassDof};
use crate::ground::GroundMotion;
use crate::model::configuration::Status;
use crate::model::constrained::{ConstrainedWork, ImpactWork};
use closing::Located;
use locate::first_crossing;

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
    simulate_loop_with_progress(chain, motion, start, options, None)
}

/// [`simulate_loop`] reporting its progress (the fraction of the duration run, 0–1) to
/// `progress` every 1 % of the duration, as the column drivers do: a progress bar, or a caller
/// that stops the run by unwinding from it (Ctrl-C in the Python package). The same answers.
pub fn simulate_loop_with_progress(
    chain: &Chain,
    motion: &dyn GroundMotion,
    start: LoopState,
    options: &LoopOptions,
    progress: Option<&mut dyn FnMut(f64)>,
) -> Result<LoopOutcome, LoopError> {
    let bad = |name: &str, v: f64| LoopError::Options(format!("{name} = {v}"));
    if !(options.dt > 0.0 && options.dt.is_finite()) {
        return Err(bad("dt", options.dt));
    }
    if !(options.duration >= 0.0 && options.duration.is_finite()) {
        return Err(bad("duration", options.duration));
    }
    // As the column driver (`RunOptions::validate`): a step that would never end the run.
    if crate::validate::too_many_steps(options.duration, options.dt) {
        return Err(LoopError::Options(format!(
            "dt = {:e}: more than 1e10 steps for the duration ({} s)",
            options.dt, options.duration
        )));
    }
    if !(options.gravity > 0.0 && options.gravity.is_finite()) {
        return Err(bad("gravity", options.gravity));
    }
    if options.collapse_angle.is_nan() || options.collapse_angle <= 0.0 {
        return Err(bad("collapse_angle", options.collapse_angle));
    }
    if !(options.min_flight >= 0.0 && options.min_flight.is_finite()) {
        return Err(bad("min_flight", options.min_flight));
    }
    if !(0.0..1.0).contains(&options.lock_loss) {
        return Err(bad("lock_loss", options.lock_loss));
    }
    if let Some(r) = options.lock_rate {
        if !(r >= 0.0 && r.is_finite()) {
            return Err(bad("lock_rate", r));
        }
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
    Runner::new(chain, motion, options).run(start, progress)
}

struct Runner<'a> {
    chain: &'a Chain,
    motion: &'a dyn GroundMotion,
    options: &'a LoopOptions,
    equations: LoopEquations<'a>,
    /// Reach of the chain (m), to express the closure's rotation residual as a length.
    reach: f64,
    /// Rate below which a grazing closing locks (rad/s).
    lock_rate: f64,
    /// The ground accelerations the closed loop at rest has been found to resist (m/s²).
    resisted: Option<(f64, f64)>,
    /// Potential energy of the closed loop (J), and the round-off allowed below it.
    closed_potential: f64,
    potential_tolerance: f64,
    max_kinetic: f64,
    /// The time of the last closing and how many closings in a row happened at it.
    last_event_time: f64,
    stalled: usize,
    /// Power of the ground motion's load at the current state, when known (the end of the last
    /// step; `None` after an event changed the rates).
    power: Option<f64>,
    out: LoopOutcome,
    /// Buffers reused from step to step and event to event.
    work: Work,
}

/// The run's buffers: each grows to its largest size once and is then reused (cleared and
/// refilled), so that a step or an event allocates nothing.
#[derive(Default)]
struct Work {
    /// The projections' KKT systems, Jacobians and trial poses.
    projection: ProjectionWork,
    /// The moving DOFs and their joints and pivots (kinetic energy).
    moving: Vec<(usize, (usize, [f64; 2]))>,
    /// A closing's located state, flags, projected DOFs, joints and rates before the impact.
    xe: Vec<f64>,
    ve: Vec<f64>,
    closing: Vec<bool>,
    rest: Vec<usize>,
    statuses_before: Vec<Status>,
    rates_before: Vec<f64>,
    /// The mass matrix at an impact (and its DOFs' shares) and the closure matrix.
    mass: Vec<f64>,
    mass_dofs: Vec<MassDof>,
    g: Vec<f64>,
    /// The impact model's buffers.
    impact: ImpactWork,
    /// The opening model's: a pose, `q + f` (and `f` with its sums), the configuration chosen
    /// and the constrained problem's buffers (its accelerations in `acc`).
    pose: ChainPose,
    load: Vec<f64>,
    velocity_load: Vec<f64>,
    velocity_sums: Vec<[f64; 2]>,
    chosen: Vec<Status>,
    opening_model: ConstrainedWork,
    /// The open DOFs, their angles, rates and accelerations (screen, slow joints; `acc` also
    /// the opening model's accelerations).
    open: Vec<usize>,
    x: Vec<f64>,
    v: Vec<f64>,
    acc: Vec<f64>,
    slow: Vec<usize>,
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
            lock_rate: options
                .lock_rate
                .unwrap_or(options.gravity * options.dt / reach),
            resisted: None,
            closed_potential: 0.0,
            potential_tolerance: 0.0,
            max_kinetic: 0.0,
            last_event_time: f64::NAN,
            stalled: 0,
            power: None,
            out: LoopOutcome {
                events: Vec::new(),
                state: LoopState::at_rest(chain),
                collapsed: false,
                peak_angle: 0.0,
                max_closure_residual: 0.0,
                max_step_drift: 0.0,
                history: Vec::new(),
                moving_checks: 0,
                screened: 0,
                energy: LoopEnergy::default(),
                stands_under_own_weight: None,
            },
            work: Work::default(),
        }
    }

    fn ag(&self, t: f64) -> f64 {
        self.motion.acceleration(t)
    }

    fn kinetic(&mut self, s: &LoopState) -> f64 {
        self.kinetic_posed(&self.chain.pose(&s.phi), &s.rates)
    }

    /// [`Runner::kinetic`] with the pose of the state's angles already built.
    fn kinetic_posed(&mut self, pose: &ChainPose, rates: &[f64]) -> f64 {
        let chain = self.chain;
        let m = chain.n_dofs();
        // Over the moving DOFs only (the others' zero rates add nothing to the sums), each
        // with its joint and pivot.
        let moving = &mut self.work.moving;
        moving.clear();
        moving.extend(
            (0..m)
                .filter(|&a| rates[a] != 0.0)
                .map(|a| (a, chain.dof_pivot(pose, a))),
        );
        if moving.is_empty() {
            // At rest: zero, not the empty sum's −0.0 (which `events.jsonl` printed as `-0.0`).
            return 0.0;
        }
        0.5 * moving
            .iter()
            .map(|&(a, pa)| {
                rates[a]
                    * moving
                        .iter()
                        .map(|&(b, pb)| chain.mass_entry_of(pose, pa, pb) * rates[b])
                        .sum::<f64>()
            })
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
        // The state at an event is one of the run's (the history's row above): an impact that
        // reverses a DOF's rate leaves its largest angle here, between two step ends.
        self.out.peak_angle = s
            .phi
            .iter()
            .fold(self.out.peak_angle, |p, x| p.max(x.abs()));
    }

    fn residual_posed(&self, pose: &ChainPose) -> f64 {
        let r = self.chain.closure_residual(pose);
        r[1].hypot(r[2]).max(r[0].abs() * self.reach)
    }

    /// The run from `start`, reporting to `progress` ([`simulate_loop_with_progress`]).
    fn run(
        mut self,
        start: LoopState,
        mut progress: Option<&mut dyn FnMut(f64)>,
    ) -> Result<LoopOutcome, LoopError> {
        let opts = self.options;
        let n = self.chain.n_joints();
        let mut s = start;
        let t_end = opts.duration;
        self.closed_potential = self.potential(&vec![0.0; self.chain.n_dofs()]);
        self.potential_tolerance = 1e-12 * opts.gravity * self.chain.total_mass() * self.reach;
        let mut steps = 0usize;
        self.max_kinetic = self.kinetic(&s);
        self.out.energy.kinetic_start = self.max_kinetic + 0.0; // `+ 0.0`: no negative zero
        let potential_start = self.potential(&s.phi);
        // The step's buffers (open DOFs, angles and rates at both ends, located zeros, the pose
        // at its end), reused from step to step.
        let (mut open, mut crossings) = (Vec::new(), Vec::new());
        let (mut x, mut v, mut x1, mut v1) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut pose = ChainPose::default();
        // At rest, the angles and statuses the step starts from (below).
        let (mut phi0, mut statuses0) = (Vec::new(), Vec::new());
        if opts.record_every > 0 {
            self.out.history.push((s.time, s.phi.clone()));
        }
        let mut next_report = 0.0;
        while s.time < t_end - 1e-12 * opts.dt {
            if let Some(report) = progress.as_mut() {
                if s.time >= next_report {
                    report(s.time / t_end);
                    next_report = s.time + 0.01 * t_end;
                }
            }
            let dt = opts.dt.min(t_end - s.time);
            let at_rest = s.rates.iter().all(|&r| r == 0.0);
            let ag_now = self.ag(s.time);
            // At rest in the closed geometry, the loop resists every ground acceleration between
            // two it has resisted: each mechanism's power of the loads is linear in `a_g`, so the
            // accelerations no admissible mechanism turns into positive power form an interval.
            // Inside the interval of those the opening model has answered "at rest", it is not
            // asked again (the same answer, without its cost at every step of a record); the
            // interval is found by bisection the first time the loop is at rest closed.
            let reference = at_rest
                && s.phi.iter().all(|&p| p == 0.0)
                && !s.statuses.iter().any(|st| st.is_open());
            // The caller's early stop (`LoopOptions::quiet_after`): closed at rest in a motion
            // that stays inside what the closed loop resists, it never moves again.
            if reference && opts.quiet_after.is_some_and(|tq| s.time >= tq) {
                break;
            }
            if reference && self.resisted.is_none() {
                let resisted = self.resisted_interval(&s)?;
                self.out.stands_under_own_weight = Some(resisted.0 <= 0.0 && 0.0 <= resisted.1);
                self.resisted = Some(resisted);
            }
            if reference
                && self
                    .resisted
                    .is_some_and(|(lo, hi)| lo <= ag_now && ag_now <= hi)
            {
                s.time += dt;
                continue;
            }
            // At rest, the state the step starts from (angles, statuses, events and history
            // recorded so far), to recognise a step the loop rests through (below).
            let rest_start = at_rest.then(|| {
                phi0.clone_from(&s.phi);
                statuses0.clone_from(&s.statuses);
                (
                    s.time,
                    self.out.events.len(),
                    self.out.history.len(),
                    self.out.energy,
                    self.out.peak_angle,
                )
            });
            if at_rest && !self.opening(&mut s, ag_now)? {
                if reference {
                    self.resisted = Some(self.resisted.map_or((ag_now, ag_now), |(lo, hi)| {
                        (lo.min(ag_now), hi.max(ag_now))
                    }));
                }
                s.time += dt;
                continue;
            }
            // The ground's power at the step's start (zero from rest).
            let power_start = match self.power {
                Some(p) => p,
                None => self.ground_power(&s, &mut pose),
            };
            s.open_dofs_into(&mut open);
            s.open_values_into(&open, &mut x, &mut v);
            x1.clear();
            v1.clear();
            x1.resize(open.len(), 0.0);
            v1.resize(open.len(), 0.0);
            let motion = self.motion;
            let ag = |t: f64| motion.acceleration(t);
            let depth = |d: usize, xi: f64| side(d, n) * xi;
            if !self
                .equations
                .rk4_step(&open, &ag, s.time, dt, &x, &v, &mut x1, &mut v1)
            {
                return Err(LoopError::Singular(s.time));
            }
            // Closing: the first zero of each open DOF's depth on the step's cubic Hermite
            // interpolant (ending through zero, dipping through zero and back, or opened at this
            // instant and back within the step).
            crossings.clear();
            crossings.extend((0..open.len()).filter_map(|i| {
                let d = open[i];
                let (g0, g1) = (depth(d, x[i]).max(0.0), depth(d, x1[i]));
                first_crossing(dt, g0, g1, depth(d, v[i]), depth(d, v1[i])).map(|s| (i, s))
            }));
            if let Some(first) = crossings.iter().map(|c| c.1).reduce(f64::min) {
                let step = Located {
                    open: &open,
                    x: &x,
                    v: &v,
                    crossings: &crossings,
                    first,
                    dt,
                    power_start,
                };
                let kinetic_after = self.close(&mut s, &step, &mut pose)?;
                self.settle(&mut s, kinetic_after);
                self.power = None;
                // From rest, the mechanism the opening model chose under `a_g(t)` closed again at
                // the step's start (its depths' cubic never rises: the ground acceleration falls
                // back inside what the loop resists within the step, e.g. a record grazing `λ g`)
                // and the loop is back in the very state the step started from. Repeating it
                // would never advance (`LoopError::Stalled` after 100 events): the loop rests
                // through this step, as its flight, shorter than the step, ends in sustained
                // contact (the lock's argument). Nothing happened: its events are dropped.
                if let Some((t0, events0, history0, energy0, peak0)) = &rest_start {
                    if s.time == *t0
                        && s.rates.iter().all(|&r| r == 0.0)
                        && s.phi == phi0
                        && s.statuses == statuses0
                    {
                        self.out.events.truncate(*events0);
                        self.out.history.truncate(*history0);
                        self.out.energy = *energy0;
                        self.out.peak_angle = *peak0;
                        s.time += dt;
                        continue;
                    }
                }
                continue;
            }
            s.time += dt;
            for i in 0..open.len() {
                s.phi[open[i]] = x1[i];
                s.rates[open[i]] = v1[i];
            }
            steps += 1;
            // One pose of the angles serves the drift, the projection (which leaves the pose
            // of its result), the kinetic energy and the collapse test.
            self.chain.pose_into(&s.phi, &mut pose);
            let drift = self.residual_posed(&pose);
            self.out.max_step_drift = self.out.max_step_drift.max(drift);
            let residual = if opts.project {
                let work = &mut self.work.projection;
                let r = project_positions_posed(
                    self.chain, &open, &mut s.phi, self.reach, 3, &mut pose, work,
                );
                if !project_rates_with(self.chain, &pose, &open, &mut s.rates, work) {
                    return Err(LoopError::Singular(s.time));
                }
                r
            } else {
                drift
            };
            self.out.max_closure_residual = self.out.max_closure_residual.max(residual);
            let power_end = self.ground_power_posed(&pose, &s.rates, s.time);
            self.out.energy.ground_work += 0.5 * dt * (power_start + power_end);
            self.power = Some(power_end);
            self.out.peak_angle = s
                .phi
                .iter()
                .fold(self.out.peak_angle, |p, x| p.max(x.abs()));
            if opts.record_every > 0 && steps % opts.record_every == 0 {
                self.out.history.push((s.time, s.phi.clone()));
            }
            self.max_kinetic = self.max_kinetic.max(self.kinetic_posed(&pose, &s.rates));
            if self.collapsed(&s, &open, residual, &pose) {
                self.out.collapsed = true;
                self.event(&s, LoopEventKind::Collapsed);
                break;
            }
            if opts.check_every > 0 && steps % opts.check_every == 0 {
                let ag_now = self.ag(s.time);
                self.opening(&mut s, ag_now)?;
            }
        }
        self.out.energy.kinetic_end = self.kinetic(&s) + 0.0;
        self.out.energy.potential_change = self.potential(&s.phi) - potential_start;
        self.out.state = s;
        Ok(self.out)
    }
}
