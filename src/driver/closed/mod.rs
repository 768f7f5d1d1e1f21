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
//!   angle;
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
//! This driver does not yet go through the column's pipeline (`run.rs` with the
//! `ChainDynamics` traits of `chain.rs`); see `docs/arches.md`.

mod equations;
mod locate;
mod projection;
mod state;

pub use equations::LoopEquations;
pub use projection::{project_positions, project_rates};
pub use state::{LoopError, LoopEvent, LoopEventKind, LoopOptions, LoopOutcome, LoopState};

use crate::chain::Chain;
use crate::ground::GroundMotion;
use crate::model::configuration::Status;
use crate::model::constrained::{impact_model_constrained, opening_model_constrained};
use locate::first_crossing;

/// Closings located within this share of the step of the earliest are one event (the closing
/// set of one impact): far above the located zeros' error (the cubic interpolant's `O(dt⁴)` on
/// the angles divided by the closing rate, below 1e-12 s on the arches of docs/arches.md), far
/// below any physical interval between two impacts the step could resolve.
const SIMULTANEOUS: f64 = 1e-6;

/// A loop settled with no point displaced farther than this from the closed geometry (m) is
/// closed: a nanometre, a thousand times the closure projection's round-off on the arches of
/// docs/arches.md and far below any displacement that matters to a structure.
const SNAP_DISTANCE: f64 = 1e-9;

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
    Runner::new(chain, motion, options).run(start)
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
            lock_rate: options
                .lock_rate
                .unwrap_or(options.gravity * options.dt / reach),
            resisted: None,
            closed_potential: 0.0,
            potential_tolerance: 0.0,
            max_kinetic: 0.0,
            out: LoopOutcome {
                events: Vec::new(),
                state: LoopState::at_rest(chain),
                collapsed: false,
                peak_angle: 0.0,
                max_closure_residual: 0.0,
                max_step_drift: 0.0,
                history: Vec::new(),
            },
        }
    }

    fn ag(&self, t: f64) -> f64 {
        self.motion.acceleration(t)
    }

    fn kinetic(&self, s: &LoopState) -> f64 {
        let pose = self.chain.pose(&s.phi);
        let m = self.chain.n_dofs();
        // Over the moving DOFs only (the others' zero rates add nothing to the sums).
        let moving: Vec<usize> = (0..m).filter(|&a| s.rates[a] != 0.0).collect();
        0.5 * moving
            .iter()
            .map(|&a| {
                s.rates[a]
                    * moving
                        .iter()
                        .map(|&b| self.chain.mass_entry(&pose, a, b) * s.rates[b])
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
    }

    /// The opening model at `s` under `ag`: adopts its configuration if it differs (new joints at
    /// zero angle) and, from rest, only if it moves something. Returns whether it changed.
    fn opening(&mut self, s: &mut LoopState, ag: f64) -> Result<bool, LoopError> {
        let (statuses, moves) = self.choice(s, ag)?;
        let moving = s.rates.iter().any(|&r| r != 0.0);
        // From rest: adopt what the model chose when it moves something; while moving: adopt a
        // different configuration.
        if (!moving && moves) || (moving && statuses != s.statuses) {
            s.statuses = statuses;
            self.event(s, LoopEventKind::Opening);
            return Ok(true);
        }
        Ok(false)
    }

    /// The opening model's configuration at `s` under `ag`, and whether it moves anything.
    fn choice(&self, s: &LoopState, ag: f64) -> Result<(Vec<Status>, bool), LoopError> {
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
        let moves = acc.iter().any(|&a| a != 0.0);
        Ok((statuses, moves))
    }

    /// The interval of ground accelerations the closed loop at rest `s` resists, by bisection on
    /// each side with the opening model (to 1e-9 relative; its ends are accelerations the model
    /// answered "at rest" to). `(0, 0)` if it does not resist `a_g = 0`.
    fn resisted_interval(&self, s: &LoopState) -> Result<(f64, f64), LoopError> {
        let opens = |ag: f64| self.choice(s, ag).map(|c| c.1);
        if opens(0.0)? {
            return Ok((0.0, 0.0));
        }
        let mut ends = [0.0; 2];
        for (end, sign) in ends.iter_mut().zip([-1.0, 1.0]) {
            let (mut lo, mut hi) = (0.0, 0.01 * self.options.gravity);
            while !opens(sign * hi)? {
                lo = hi;
                hi *= 2.0;
                if hi > 1e3 * self.options.gravity {
                    break;
                }
            }
            while hi - lo > 1e-9 * hi {
                let mid = 0.5 * (lo + hi);
                if opens(sign * mid)? {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            *end = sign * lo;
        }
        Ok((ends[0], ends[1]))
    }

    /// Joints the impact model opens at zero angle with a rate below the lock rate are kept
    /// closed: such a flight lasts about one step or less (the rate gravity gives in one step at
    /// the chain's size, as the lock of a chattering joint), the fixed step cannot resolve it, and
    /// the limit of the Zeno sequence of impacts it starts is sustained contact. The rates are
    /// then the kinetic-metric projection of the model's onto the remaining open DOFs with the
    /// closure (kinetic energy not above the model's); a DOF at zero angle that the projection
    /// turns inadmissible (closing) is kept closed too, until none is. Fewer than four open
    /// joints: at rest (SPEC §9). Returns whether anything changed.
    fn keep_slow_closed(&mut self, s: &mut LoopState) -> Result<bool, LoopError> {
        let n = self.chain.n_joints();
        let mut changed = false;
        let flight = self.options.min_flight;
        loop {
            let open = s.open_dofs();
            let mut acc = vec![0.0; open.len()];
            if flight > 0.0 {
                let x: Vec<f64> = open.iter().map(|&d| s.phi[d]).collect();
                let v: Vec<f64> = open.iter().map(|&d| s.rates[d]).collect();
                let ag = self.motion.acceleration(s.time);
                if !self.equations.accelerations(&open, ag, &x, &v, &mut acc) {
                    return Err(LoopError::Singular(s.time));
                }
            }
            let slow: Vec<usize> = open
                .iter()
                .zip(&acc)
                .filter(|&(&d, &a)| {
                    let (r, a) = (side(d, n) * s.rates[d], side(d, n) * a);
                    let short = a < 0.0 && 2.0 * r <= -a * flight * self.options.dt;
                    s.phi[d] == 0.0 && (r <= self.lock_rate || short)
                })
                .map(|(&d, _)| d % n)
                .collect();
            if slow.is_empty() {
                return Ok(changed);
            }
            changed = true;
            for &k in &slow {
                s.statuses[k] = Status::Closed;
            }
            let open = s.open_dofs();
            if open.len() < 4 {
                s.rates.iter_mut().for_each(|r| *r = 0.0);
                return Ok(true);
            }
            let pose = self.chain.pose(&s.phi);
            if !project_rates(self.chain, &pose, &open, &mut s.rates) {
                return Err(LoopError::Singular(s.time));
            }
        }
    }

    fn residual(&self, phi: &[f64]) -> f64 {
        let r = self.chain.closure_residual(&self.chain.pose(phi));
        r[1].hypot(r[2]).max(r[0].abs() * self.reach)
    }

    /// Potential energy of the bodies' weight (J) in the pose of `phi`.
    fn potential(&self, phi: &[f64]) -> f64 {
        let pose = self.chain.pose(phi);
        let bodies = self.chain.bodies();
        self.options.gravity
            * bodies
                .iter()
                .zip(&pose.centres)
                .map(|(b, c)| b.mass * c[1])
                .sum::<f64>()
    }

    /// Collapse (see the module's documentation): the potential energy below the closed loop's
    /// (over the barrier, any mechanism); for a one-DOF mechanism (four open joints) already
    /// past the maximum of `V` along it (gravity's power positive while the hinges open); or a
    /// hinge angle beyond the safeguard.
    fn collapsed(&self, s: &LoopState, open: &[usize], residual: f64) -> bool {
        let n = self.chain.n_joints();
        if s.phi.iter().any(|p| p.abs() > self.options.collapse_angle) {
            return true;
        }
        // A pose off the closure by `residual` misplaces the weight by about that much.
        let slack =
            self.potential_tolerance + self.options.gravity * self.chain.total_mass() * residual;
        let potential = self.potential(&s.phi);
        if potential < self.closed_potential - slack {
            return true;
        }
        // Past the maximum of `V` along a one-DOF path from the closed loop, a strict local
        // minimum: `V` has climbed above `V₀` first. (A mechanism at rest a hair from closure,
        // angles of 1e-12 rad, has gravity's power at round-off, of either sign.)
        if open.len() != 4 || potential <= self.closed_potential + slack {
            return false;
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
        self.closed_potential = self.potential(&vec![0.0; self.chain.n_dofs()]);
        self.potential_tolerance = 1e-12 * opts.gravity * self.chain.total_mass() * self.reach;
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
                self.resisted = Some(self.resisted_interval(&s)?);
            }
            if reference
                && self
                    .resisted
                    .is_some_and(|(lo, hi)| lo <= ag_now && ag_now <= hi)
            {
                s.time += dt;
                continue;
            }
            if at_rest && !self.opening(&mut s, ag_now)? {
                if reference {
                    self.resisted = Some(self.resisted.map_or((ag_now, ag_now), |(lo, hi)| {
                        (lo.min(ag_now), hi.max(ag_now))
                    }));
                }
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
            if !self
                .equations
                .rk4_step(&open, &ag, s.time, dt, &x, &v, &mut x1, &mut v1)
            {
                return Err(LoopError::Singular(s.time));
            }
            // Closing: the first zero of each open DOF's depth on the step's cubic Hermite
            // interpolant (ending through zero, dipping through zero and back, or opened at this
            // instant and back within the step).
            let crossings: Vec<(usize, f64)> = (0..open.len())
                .filter_map(|i| {
                    let d = open[i];
                    let (g0, g1) = (depth(d, x[i]).max(0.0), depth(d, x1[i]));
                    first_crossing(dt, g0, g1, depth(d, v[i]), depth(d, v1[i])).map(|s| (i, s))
                })
                .collect();
            if let Some(first) = crossings.iter().map(|c| c.1).reduce(f64::min) {
                // The state at the earliest zero: RK4 again from the start of the step over the
                // located fraction (no interpolation error in the state the impact sees).
                let (mut xe, mut ve) = (x.clone(), v.clone());
                if first > 0.0
                    && !self.equations.rk4_step(
                        &open,
                        &ag,
                        s.time,
                        first * dt,
                        &x,
                        &v,
                        &mut xe,
                        &mut ve,
                    )
                {
                    return Err(LoopError::Singular(s.time));
                }
                s.time += first * dt;
                for i in 0..open.len() {
                    s.phi[open[i]] = xe[i];
                    s.rates[open[i]] = ve[i];
                }
                // Flagged: every DOF whose zero lies within `SIMULTANEOUS` of the earliest (a
                // one-DOF mechanism's hinges reach zero at the same instant, SPEC §9; their
                // located zeros differ by the interpolant's error only), and any DOF the
                // integration to the instant left at or through zero.
                let tolerance = SIMULTANEOUS * opts.dt;
                let mut closing = vec![false; n];
                for i in 0..open.len() {
                    let d = open[i];
                    let located = crossings
                        .iter()
                        .any(|&(j, sj)| j == i && (sj - first) * dt <= tolerance);
                    if located || depth(d, s.phi[d]) <= 0.0 {
                        s.phi[d] = 0.0;
                        // At its zero a DOF moves towards closure; a rate moving away there is
                        // the interpolant's round-off (a joint that opened with zero rate).
                        if depth(d, s.rates[d]) > 0.0 {
                            s.rates[d] = 0.0;
                        }
                        closing[d % n] = true;
                    }
                }
                // The closing angles set to zero leave the state off the closure by their
                // located zeros' error: back onto it with the rest.
                let residual = if opts.project {
                    let rest: Vec<usize> =
                        open.iter().copied().filter(|&d| !closing[d % n]).collect();
                    project_positions(self.chain, &rest, &mut s.phi, self.reach, 3)
                } else {
                    self.residual(&s.phi)
                };
                self.out.max_closure_residual = self.out.max_closure_residual.max(residual);
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
                let (statuses_before, rates_before) = (s.statuses.clone(), s.rates.clone());
                let closing_rate = (0..n)
                    .filter(|&k| closing[k])
                    .map(|k| (s.rates[k] + s.rates[n + k]).abs())
                    .fold(0.0, f64::max);
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
                let joints: Vec<usize> = (0..n).filter(|&k| closing[k]).collect();
                let loss = report.kinetic_before - report.kinetic_after;
                let mut kinetic_after = report.kinetic_after;
                if loss <= opts.lock_loss * report.kinetic_before && closing_rate <= self.lock_rate
                {
                    // A chatter: lock the closing joints instead.
                    s.statuses = statuses_before;
                    s.rates = rates_before;
                    for &k in &joints {
                        s.statuses[k] = Status::Closed;
                    }
                    let open = s.open_dofs();
                    // Fewer than four open joints: at rest (SPEC §9), settled below.
                    if open.len() < 4 {
                        s.rates.iter_mut().for_each(|r| *r = 0.0);
                    } else if !project_rates(self.chain, &pose, &open, &mut s.rates) {
                        return Err(LoopError::Singular(s.time));
                    }
                    kinetic_after = self.kinetic(&s);
                    self.event(
                        &s,
                        LoopEventKind::Locked {
                            joints,
                            kinetic_before: report.kinetic_before,
                            kinetic_after,
                        },
                    );
                } else {
                    if self.keep_slow_closed(&mut s)? {
                        kinetic_after = self.kinetic(&s);
                    }
                    self.event(
                        &s,
                        LoopEventKind::Closing {
                            joints,
                            kinetic_before: report.kinetic_before,
                            kinetic_after,
                        },
                    );
                }
                let open_after = s.statuses.iter().filter(|st| st.is_open()).count();
                if kinetic_after <= opts.settle_ratio * self.max_kinetic || open_after < 4 {
                    s.rates.iter_mut().for_each(|r| *r = 0.0);
                    // At rest a hair from closure (no point displaced by more than
                    // `SNAP_DISTANCE`: the round-off of the closure projection), the loop is
                    // closed: the angles are set to zero.
                    let largest = s.phi.iter().fold(0.0, |m: f64, p| m.max(p.abs()));
                    if largest * self.reach <= SNAP_DISTANCE {
                        s.phi.iter_mut().for_each(|p| *p = 0.0);
                    }
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
            let drift = self.residual(&s.phi);
            self.out.max_step_drift = self.out.max_step_drift.max(drift);
            let residual = if opts.project {
                let r = project_positions(self.chain, &open, &mut s.phi, self.reach, 3);
                let pose = self.chain.pose(&s.phi);
                if !project_rates(self.chain, &pose, &open, &mut s.rates) {
                    return Err(LoopError::Singular(s.time));
                }
                r
            } else {
                drift
            };
            self.out.max_closure_residual = self.out.max_closure_residual.max(residual);
            self.out.peak_angle = s
                .phi
                .iter()
                .fold(self.out.peak_angle, |p, x| p.max(x.abs()));
            if opts.record_every > 0 && steps % opts.record_every == 0 {
                self.out.history.push((s.time, s.phi.clone()));
            }
            self.max_kinetic = self.max_kinetic.max(self.kinetic(&s));
            if self.collapsed(&s, &open, residual) {
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
