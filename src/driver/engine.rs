//! The simulation loop: steps, checks, event location and the calls to the models.

use super::dynamics::Dynamics;
use super::events::{hermite, hermite_crossing, hermite_rate, illinois, lock_dof, quintic};
use super::integrator::Stepper;
use super::{
    DriverError, EnergyBalance, Event, EventKind, EventLocator, History, Outcome, Recording,
    SimulationOptions, StopReason,
};
use crate::error::{ErrorKind, RockingError};
use crate::ground::GroundMotion;
use crate::model::column::Column;
use crate::model::cone::ModelReport;
use crate::model::configuration::{open_dofs, Status};
use crate::model::impact::kinetic_energy;
use crate::{impact_model, opening_model};

/// Share of `√E_tip` the energy bound of [`SimulationOptions::stop_when_safe`] may reach.
const SAFETY_FACTOR: f64 = 0.9;
/// Accepted steps between two evaluations of that bound.
const SAFETY_EVERY: usize = 16;

/// Look-ahead ladder of the opening judgement (SPEC §5 trap (a)), in time steps.
const LOOK_AHEAD: [f64; 4] = [1e-3, 1e-2, 1e-1, 1.0];

/// Most re-integrations of one impact time refinement (high-order integrators).
const MAX_REFINE: usize = 8;

enum Found {
    Impact(usize),
    Opening,
}

pub(crate) struct Engine<'a> {
    motion: &'a dyn GroundMotion,
    opts: &'a SimulationOptions,
    rec: Recording,
    n: usize,
    m: usize,
    dynm: Dynamics<'a>,
    stepper: Stepper,
    t: f64,
    /// Kahan compensation of `t` (the part of the summed steps that `t` lost to rounding,
    /// negated): without it the clock drifts by about an ulp per step, 1e-11 s after 3e5 steps.
    t_comp: f64,
    ag: f64,
    statuses: Vec<Status>,
    open: Vec<usize>,
    phi: Vec<f64>,
    rates: Vec<f64>,
    acc: Vec<f64>,
    margin0: Vec<f64>,
    power0: f64,
    // Step buffers.
    x0: Vec<f64>,
    v0: Vec<f64>,
    a0: Vec<f64>,
    phi1: Vec<f64>,
    rates1: Vec<f64>,
    scratch_phi: Vec<f64>,
    scratch_rates: Vec<f64>,
    mass: Vec<f64>,
    load: Vec<f64>,
    // Bookkeeping.
    events: Vec<Event>,
    n_events: usize,
    impacts: usize,
    last_impact: Vec<f64>,
    tipped_recorded: Vec<bool>,
    energy: EnergyBalance,
    potential_start: f64,
    e_tip: f64,
    settle_interval: f64,
    peak: Vec<f64>,
    history: Option<History>,
    steps: usize,
    /// `(m R / √(2 I_P), 0.9 √E_tip)` of [`SimulationOptions::stop_when_safe`] when it applies.
    safety_bound: Option<(f64, f64)>,
}

impl<'a> Engine<'a> {
    pub fn new(
        column: &'a Column,
        motion: &'a dyn GroundMotion,
        opts: &'a SimulationOptions,
        rec: Recording,
    ) -> Engine<'a> {
        let n = column.n_interfaces();
        let m = 2 * n;
        let dynm = Dynamics::new(
            column,
            opts.gravity,
            opts.exact_velocity_terms,
            opts.model.tolerance,
            opts.friction,
        );
        let e_tip = dynm.tipping_energy();
        let safety_bound =
            (opts.stop_when_safe && n == 1 && !opts.continue_until_fallen).then(|| {
                let k = dynm
                    .rigid
                    .iter()
                    .map(|r| r.s0 * (r.dx * r.dx + r.dy * r.dy).sqrt() * (0.5 * r.inv_ip).sqrt())
                    .fold(0.0, f64::max);
                (k, SAFETY_FACTOR * e_tip.sqrt())
            });
        Engine {
            motion,
            opts,
            rec,
            n,
            m,
            dynm,
            stepper: Stepper::new(n, opts.integrator),
            t: 0.0,
            t_comp: 0.0,
            ag: 0.0,
            statuses: vec![Status::Closed; n],
            open: Vec::with_capacity(n),
            phi: vec![0.0; m],
            rates: vec![0.0; m],
            acc: vec![0.0; m],
            margin0: vec![f64::NEG_INFINITY; m],
            power0: 0.0,
            x0: vec![0.0; n],
            v0: vec![0.0; n],
            a0: vec![0.0; n],
            phi1: vec![0.0; m],
            rates1: vec![0.0; m],
            scratch_phi: vec![0.0; m],
            scratch_rates: vec![0.0; m],
            mass: vec![0.0; m * m],
            load: vec![0.0; m],
            events: Vec::new(),
            n_events: 0,
            impacts: 0,
            last_impact: vec![f64::NEG_INFINITY; n],
            tipped_recorded: vec![false; n],
            energy: EnergyBalance::default(),
            potential_start: 0.0,
            e_tip,
            settle_interval: opts.settle_interval.unwrap_or(4.0 * opts.dt),
            peak: vec![0.0; n],
            history: rec.history_every.map(|every| {
                // Room for the samples of the whole duration (capped), so that the history does
                // not grow by reallocation and copying while it runs.
                let samples = (opts.duration / (opts.dt * every as f64)).min(1e6) as usize + 16;
                History {
                    n_interfaces: n,
                    t: Vec::with_capacity(samples),
                    phi: Vec::with_capacity(samples * m),
                    rates: Vec::with_capacity(samples * m),
                    block_angles: Vec::with_capacity(samples * n),
                    statuses: Vec::with_capacity(samples * n),
                }
            }),
            steps: 0,
            safety_bound,
        }
    }

    /// The clock advanced by `d` (compensated summation) and its new compensation.
    fn clock(&self, d: f64) -> (f64, f64) {
        let y = d - self.t_comp;
        let t = self.t + y;
        (t, (t - self.t) - y)
    }

    fn set_clock(&mut self, (t, comp): (f64, f64)) {
        self.t = t;
        self.t_comp = comp;
    }

    fn set_open(&mut self) {
        self.open.clear();
        self.open.extend(open_dofs(&self.statuses));
        self.dynm.reset_scratch();
    }

    /// Recomputes the accelerations, margins and power at the current state.
    fn refresh(&mut self) -> Result<(), DriverError> {
        let c = self.dynm.check(
            &self.open,
            &self.statuses,
            self.ag,
            &self.phi,
            &self.rates,
            false,
        );
        if !c.ok {
            return Err(not_positive_definite());
        }
        self.acc.copy_from_slice(&self.dynm.acc_full);
        self.margin0.copy_from_slice(&self.dynm.margin);
        self.power0 = c.power;
        Ok(())
    }

    fn record_sample(&mut self) {
        if let Some(h) = &mut self.history {
            h.t.push(self.t);
            h.phi.extend_from_slice(&self.phi);
            h.rates.extend_from_slice(&self.rates);
            h.statuses.extend_from_slice(&self.statuses);
            // Block rotations: the running sum of the DOF angles (as `Column::pose_into`, without
            // the geometry).
            let n = self.n;
            let mut alpha = 0.0_f64;
            for k in 0..n {
                let theta = if self.phi[k] != 0.0 {
                    self.phi[k]
                } else {
                    self.phi[n + k]
                };
                alpha += theta;
                h.block_angles.push(alpha);
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn push_event(
        &mut self,
        kind: EventKind,
        interface: Option<usize>,
        kinetic_before: f64,
        kinetic_after: f64,
        before: Option<&[Status]>,
        report: Option<ModelReport>,
    ) {
        self.n_events += 1;
        if self.rec.events {
            self.events.push(Event {
                t: self.t,
                kind,
                interface,
                kinetic_before,
                kinetic_after,
                statuses_before: before.unwrap_or(&self.statuses).to_vec(),
                statuses_after: self.statuses.clone(),
                report,
            });
        }
    }

    /// The opening judgement a little past the current instant (trap (a)): returns whether
    /// something opened. `escalate`: widen the look-ahead up to one step.
    fn try_opening(&mut self, escalate: bool) -> Result<bool, DriverError> {
        let ladder = if escalate {
            &LOOK_AHEAD[..]
        } else {
            &LOOK_AHEAD[..1]
        };
        for &f in ladder {
            let eps = f * self.opts.dt;
            for d in 0..self.m {
                self.scratch_phi[d] =
                    self.phi[d] + eps * self.rates[d] + 0.5 * eps * eps * self.acc[d];
                self.scratch_rates[d] = self.rates[d] + eps * self.acc[d];
            }
            let ag = self.motion.acceleration(self.t + eps);
            let c = self.dynm.check(
                &self.open,
                &self.statuses,
                ag,
                &self.scratch_phi,
                &self.scratch_rates,
                false,
            );
            if c.max_margin <= 0.0 {
                continue;
            }
            self.dynm.full_system(
                &self.statuses,
                ag,
                &self.scratch_phi,
                &self.scratch_rates,
                &mut self.mass,
                &mut self.load,
            );
            let mut st = self.statuses.clone();
            let mut a = vec![0.0; self.m];
            let report = opening_model(&self.mass, &self.load, &mut st, &mut a, &self.opts.model)?;
            if !report.changed {
                continue;
            }
            let before = std::mem::replace(&mut self.statuses, st);
            let first = (0..self.n).find(|&k| before[k] != self.statuses[k]);
            self.set_open();
            let kin = kinetic_energy(&self.mass, &self.rates);
            self.push_event(
                EventKind::Opening,
                first,
                kin,
                kin,
                Some(&before),
                Some(report),
            );
            self.refresh()?;
            return Ok(true);
        }
        Ok(false)
    }

    /// Impact of DOF `d` at the current instant (its angle is set to zero).
    fn impact(&mut self, d: usize) -> Result<(), DriverError> {
        let n = self.n;
        let k = d % n;
        self.phi[d] = 0.0;
        self.dynm.full_system(
            &self.statuses,
            self.ag,
            &self.phi,
            &self.rates,
            &mut self.mass,
            &mut self.load,
        );
        let sigma = self.statuses[k].sign();
        if sigma * self.rates[d] > 0.0 {
            // Touching zero without moving towards it (a grazing DOF, located at zero with a
            // rate of round-off size the wrong way): the rate is set to zero, and whatever that
            // changes in kinetic energy is booked as dissipated, so the event reports the energy
            // the impact model actually received.
            let grazing = kinetic_energy(&self.mass, &self.rates);
            self.rates[d] = 0.0;
            self.energy.dissipated += grazing - kinetic_energy(&self.mass, &self.rates);
        }
        let kin_before = kinetic_energy(&self.mass, &self.rates);
        let mut st = self.statuses.clone();
        let mut v = self.rates.clone();
        let report = impact_model(&self.mass, &mut st, &mut v, k, &self.opts.model)?;
        let before = std::mem::replace(&mut self.statuses, st);
        self.rates.copy_from_slice(&v);
        self.set_open();
        let kin_after = report.kinetic_after;
        self.energy.dissipated += kin_before - kin_after;
        self.impacts += 1;
        self.push_event(
            EventKind::Impact,
            Some(k),
            kin_before,
            kin_after,
            Some(&before),
            Some(report),
        );
        // Settling: shrinking impacts end in a closed interface.
        let interval = self.t - self.last_impact[k];
        self.last_impact[k] = self.t;
        if let Some(dof) = self.statuses[k].dof(k, n) {
            if kin_after < self.opts.settle_energy_fraction * self.e_tip
                || interval < self.settle_interval
            {
                let before = self.statuses.clone();
                lock_dof(&self.mass, self.m, &self.open, dof, &mut self.rates);
                self.statuses[k] = Status::Closed;
                self.set_open();
                let kin = kinetic_energy(&self.mass, &self.rates);
                self.energy.dissipated += kin_after - kin;
                self.push_event(
                    EventKind::Settled,
                    Some(k),
                    kin_after,
                    kin,
                    Some(&before),
                    None,
                );
            }
        }
        self.refresh()
    }

    fn stop(&mut self, reason: StopReason) -> Result<Outcome, DriverError> {
        let (kin, pot) = self.dynm.energy(&self.open, &self.phi, &self.rates);
        self.energy.kinetic_end = kin;
        self.energy.potential_change = pot - self.potential_start;
        if let Some(h) = &self.history {
            if h.t.last() != Some(&self.t) {
                self.record_sample();
            }
        }
        Ok(Outcome {
            stop_reason: reason,
            t_end: self.t,
            // With `continue_until_fallen` a column that has tipped beyond a pivot may still end
            // in tension or sliding while it falls (its corner lifts off): it has overturned.
            overturned: matches!(
                reason,
                StopReason::Overturned { .. } | StopReason::Fallen { .. }
            ) || self.tipped_recorded.iter().any(|&t| t),
            impacts: self.impacts,
            events: std::mem::take(&mut self.events),
            history: self.history.take(),
            peak_block_rotation: std::mem::take(&mut self.peak),
            energy: self.energy,
            statuses_end: self.statuses.clone(),
        })
    }

    pub fn run(
        mut self,
        mut progress: Option<&mut dyn FnMut(f64)>,
    ) -> Result<Outcome, DriverError> {
        let n = self.n;
        let opts = self.opts;
        if let Some(angles) = &opts.initial_angles {
            for (k, &a) in angles.iter().enumerate() {
                if a < 0.0 {
                    self.statuses[k] = Status::OpenRight;
                    self.phi[k] = a;
                } else if a > 0.0 {
                    self.statuses[k] = Status::OpenLeft;
                    self.phi[n + k] = a;
                }
            }
        }
        self.set_open();
        self.ag = self.motion.acceleration(0.0);
        let (_, pot) = self.dynm.energy(&self.open, &self.phi, &self.rates);
        self.potential_start = pot;
        self.refresh()?;
        let pose = self.dynm.col.pose(&self.phi);
        for (p, a) in self.peak.iter_mut().zip(&pose.block_angles) {
            *p = a.abs();
        }
        self.record_sample();
        if self.margin0.iter().any(|&v| v > 0.0) {
            self.try_opening(true)?;
        }
        let duration = opts.duration;
        let dt = opts.dt;
        let motion_end = self.motion.end_time();
        let mut next_progress = 0.0;
        loop {
            if let Some(cb) = progress.as_mut() {
                if self.t >= next_progress {
                    cb((self.t / duration).min(1.0));
                    next_progress += 0.01 * duration;
                }
            }
            let remaining = duration - self.t;
            if remaining <= 1e-9 * dt {
                if let Some(cb) = progress.as_mut() {
                    cb(1.0);
                }
                return self.stop(StopReason::Duration);
            }
            if self.n_events as f64 > opts.max_events_per_second * self.t.max(1.0) {
                return self.stop(StopReason::TooManyEvents);
            }
            if self.open.is_empty() && opts.quiet_after.is_some_and(|q| self.t >= q) {
                return self.stop(StopReason::AtRest);
            }
            if self.steps % SAFETY_EVERY == 0 && self.cannot_tip() {
                return self.stop(StopReason::CannotTip);
            }
            let mut h = if remaining < 1.5 * dt && remaining > dt {
                0.5 * remaining
            } else {
                dt.min(remaining)
            };
            // End a step exactly where the ground motion ends: its acceleration has a kink or a
            // jump there, which a straddling step would integrate at first order only.
            let mut clock1 = self.clock(h);
            if self.t < motion_end && self.t + h > motion_end && motion_end - self.t > 1e-9 * dt {
                h = motion_end - self.t;
                clock1 = (motion_end, 0.0);
            }
            let t0 = self.t;
            let t1 = clock1.0;
            let ag1 = self.motion.acceleration(t1);
            let k = self.open.len();
            if k == 0 {
                let c = self
                    .dynm
                    .check(&[], &self.statuses, ag1, &self.phi, &self.rates, true);
                if c.max_margin > 0.0 {
                    let s = match opts.locator {
                        EventLocator::Linear => linear_opening(&self.margin0, &self.dynm.margin),
                        EventLocator::Hermite => {
                            let g0 = self.largest_margin0();
                            if g0 > 0.0 {
                                0.0
                            } else {
                                let (dynm, statuses, phi, rates, motion) = (
                                    &mut self.dynm,
                                    &self.statuses,
                                    &self.phi,
                                    &self.rates,
                                    self.motion,
                                );
                                illinois(
                                    |s| {
                                        dynm.check(
                                            &[],
                                            statuses,
                                            motion.acceleration(t0 + s * h),
                                            phi,
                                            rates,
                                            false,
                                        )
                                        .max_margin
                                    },
                                    0.0,
                                    g0,
                                    1.0,
                                    c.max_margin,
                                    1e-13,
                                )
                            }
                        }
                    };
                    self.set_clock(self.clock(s * h));
                    self.ag = self.motion.acceleration(self.t);
                    self.refresh()?;
                    if !self.try_opening(true)? {
                        // The model keeps the column closed: accept the step (counted as an event
                        // so that a disagreement can never loop).
                        self.n_events += 1;
                        self.set_clock(clock1);
                        self.ag = ag1;
                        self.refresh()?;
                    }
                    continue;
                }
                if let Some(k) = c.sliding {
                    self.set_clock(clock1);
                    self.ag = ag1;
                    self.push_event(EventKind::Sliding, Some(k), 0.0, 0.0, None, None);
                    return self.stop(StopReason::Sliding { interface: k });
                }
                self.set_clock(clock1);
                self.ag = ag1;
                self.margin0.copy_from_slice(&self.dynm.margin);
                self.power0 = 0.0;
                self.accepted_step();
                continue;
            }
            // Integrate the open DOFs.
            for (i, &d) in self.open.iter().enumerate() {
                self.x0[i] = self.phi[d];
                self.v0[i] = self.rates[d];
                self.a0[i] = self.acc[d];
            }
            self.advance(t0, h, ag1, k)?;
            self.phi1.copy_from_slice(&self.phi);
            self.rates1.copy_from_slice(&self.rates);
            self.stepper
                .write_open(&self.open, &mut self.phi1, &mut self.rates1);
            let c = self.dynm.check(
                &self.open,
                &self.statuses,
                ag1,
                &self.phi1,
                &self.rates1,
                true,
            );
            if !c.ok {
                return Err(not_positive_definite());
            }
            // (2) impacts: a DOF crossing zero coming back; (1) openings: reaction signs.
            let mut found: Option<(f64, Found)> = None;
            for &d in &self.open {
                let sigma = self.statuses[d % n].sign();
                let (g0, g1) = (sigma * self.phi[d], sigma * self.phi1[d]);
                if g1 < 0.0 && g0 >= 0.0 {
                    let s = match opts.locator {
                        EventLocator::Linear => g0 / (g0 - g1),
                        EventLocator::Hermite => hermite_crossing(
                            h,
                            g0,
                            g1,
                            sigma * self.rates[d],
                            sigma * self.rates1[d],
                        ),
                    };
                    if found.as_ref().map_or(true, |f| s < f.0) {
                        found = Some((s, Found::Impact(d)));
                    }
                }
            }
            if c.max_margin > 0.0 {
                let s = match opts.locator {
                    EventLocator::Linear => linear_opening(&self.margin0, &self.dynm.margin),
                    EventLocator::Hermite => self.hermite_opening(t0, h, c.max_margin),
                };
                if found.as_ref().map_or(true, |f| s < f.0) {
                    found = Some((s, Found::Opening));
                }
            }
            if let Some((s, what)) = found {
                self.n_events += 1;
                self.move_to_event(t0, h, s, &what, c.max_margin)?;
                match what {
                    Found::Impact(d) => {
                        self.impact(d)?;
                        self.try_opening(false)?;
                    }
                    Found::Opening => {
                        if !self.try_opening(true)? {
                            self.refresh()?;
                        }
                    }
                }
                continue;
            }
            // Accept the step.
            self.energy.ground_work += 0.5 * h * (self.power0 + c.power);
            self.power0 = c.power;
            self.phi.copy_from_slice(&self.phi1);
            self.rates.copy_from_slice(&self.rates1);
            for (i, &d) in self.open.iter().enumerate() {
                self.acc[d] = self.stepper.a1[i];
            }
            self.margin0.copy_from_slice(&self.dynm.margin);
            self.set_clock(clock1);
            self.ag = ag1;
            for (p, a) in self.peak.iter_mut().zip(&self.dynm.block_angles) {
                *p = p.max(a.abs());
            }
            if let Some(k) = c.tension {
                self.push_event(EventKind::Tension, Some(k), 0.0, 0.0, None, None);
                return self.stop(StopReason::Tension { interface: k });
            }
            if let Some(k) = c.sliding {
                self.push_event(EventKind::Sliding, Some(k), 0.0, 0.0, None, None);
                return self.stop(StopReason::Sliding { interface: k });
            }
            if let Some(k) = c.tipped {
                if !opts.continue_until_fallen {
                    self.push_event(EventKind::Overturned, Some(k), 0.0, 0.0, None, None);
                    return self.stop(StopReason::Overturned { interface: k });
                }
                if !self.tipped_recorded[k] {
                    self.tipped_recorded[k] = true;
                    self.push_event(EventKind::Overturned, Some(k), 0.0, 0.0, None, None);
                }
            }
            if let Some(k) = c.fallen {
                if opts.continue_until_fallen {
                    return self.stop(StopReason::Fallen { interface: k });
                }
            }
            self.accepted_step();
        }
    }

    /// Largest opening margin at the start of the step (`> 0`: a reaction test already fails).
    fn largest_margin0(&self) -> f64 {
        self.margin0
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The energy bound of [`SimulationOptions::stop_when_safe`] at the current state.
    fn cannot_tip(&mut self) -> bool {
        let Some((k, limit)) = self.safety_bound else {
            return false;
        };
        let Some(impulse) = self.motion.remaining_impulse(self.t) else {
            return false;
        };
        let energy = if self.open.is_empty() {
            0.0
        } else {
            let (kin, pot) = self.dynm.energy(&self.open, &self.phi, &self.rates);
            kin + pot
        };
        energy.max(0.0).sqrt() + k * impulse <= limit
    }

    fn accepted_step(&mut self) {
        self.steps += 1;
        if let Some(every) = self.rec.history_every {
            if self.steps % every == 0 {
                self.record_sample();
            }
        }
    }

    /// Fraction of the step where the opening test first fails, by Illinois on the largest
    /// margin evaluated on the Hermite-interpolated state.
    fn hermite_opening(&mut self, t0: f64, h: f64, g1: f64) -> f64 {
        let g0 = self.largest_margin0();
        if g0 > 0.0 {
            return 0.0;
        }
        let Engine {
            dynm,
            open,
            statuses,
            phi,
            rates,
            phi1,
            rates1,
            scratch_phi,
            scratch_rates,
            motion,
            ..
        } = self;
        let f = |s: f64| {
            scratch_phi.copy_from_slice(phi);
            scratch_rates.copy_from_slice(rates);
            for &d in open.iter() {
                scratch_phi[d] = hermite(s, h, phi[d], phi1[d], rates[d], rates1[d]);
                scratch_rates[d] = hermite_rate(s, h, phi[d], phi1[d], rates[d], rates1[d]);
            }
            dynm.check(
                open,
                statuses,
                motion.acceleration(t0 + s * h),
                scratch_phi,
                scratch_rates,
                false,
            )
            .max_margin
        };
        illinois(f, 0.0, g0, 1.0, g1, 1e-13)
    }

    /// One step of the integrator from the start-of-step state `x0, v0, a0` (`k` open DOFs)
    /// over `h`, the ground acceleration going from the current one to `ag1`; the result is in
    /// the stepper's `x1, v1, a1`.
    fn advance(&mut self, t0: f64, h: f64, ag1: f64, k: usize) -> Result<(), DriverError> {
        let ok = self.stepper.step(
            self.opts.integrator,
            &mut self.dynm,
            &self.open,
            &self.statuses,
            self.motion,
            t0,
            h,
            self.ag,
            ag1,
            &self.x0[..k],
            &self.v0[..k],
            &self.a0[..k],
        );
        if ok {
            Ok(())
        } else {
            Err(not_positive_definite())
        }
    }

    /// [`Engine::advance`] over the fraction `s` of the step `h`.
    fn advance_to(&mut self, t0: f64, h: f64, s: f64) -> Result<(), DriverError> {
        let ag = self.motion.acceleration(t0 + s * h);
        self.advance(t0, s * h, ag, self.open.len())
    }

    /// Moves the state to the fraction `s` of the step just taken (which starts at the current
    /// state): linear interpolation (thesis) or re-integration over `s h` (Hermite; refined
    /// first for a high-order integrator). `margin1`: the largest opening margin at the step
    /// end.
    fn move_to_event(
        &mut self,
        t0: f64,
        h: f64,
        s: f64,
        what: &Found,
        margin1: f64,
    ) -> Result<(), DriverError> {
        let mut s = s;
        match self.opts.locator {
            EventLocator::Linear => {
                for &d in &self.open {
                    self.phi[d] += s * (self.phi1[d] - self.phi[d]);
                    self.rates[d] += s * (self.rates1[d] - self.rates[d]);
                }
            }
            EventLocator::Hermite => {
                if s > 0.0 {
                    if self.opts.integrator.refines_events() {
                        s = match *what {
                            Found::Impact(d) => self.refine_impact(t0, h, s, d)?,
                            Found::Opening => self.refine_opening(t0, h, s, margin1)?,
                        };
                    } else {
                        self.advance_to(t0, h, s)?;
                    }
                    self.stepper
                        .write_open(&self.open, &mut self.phi, &mut self.rates);
                }
            }
        }
        let clock_e = self.clock(s * h);
        let te = clock_e.0;
        let ag_e = self.motion.acceleration(te);
        // An open DOF may not pass zero at the event (the located one is set to zero by the
        // impact; others, crossing in the same step a hair later, are held at zero).
        for &d in &self.open {
            let sigma = self.statuses[d % self.n].sign();
            if sigma * self.phi[d] < 0.0 {
                self.phi[d] = 0.0;
            }
        }
        self.set_clock(clock_e);
        self.ag = ag_e;
        let power = self.dynm.power(&self.open, ag_e, &self.phi, &self.rates);
        self.energy.ground_work += 0.5 * s * h * (self.power0 + power);
        // Every method (Wilson's acceleration state included) restarts from the equations of
        // motion at the event.
        self.refresh()
    }

    /// The impact time of DOF `d` on the re-integrated solution, from the Hermite estimate
    /// `s_est`, first improved on the quintic Hermite interpolant of the step (angles, rates and
    /// accelerations at both ends: error `O(h⁶)`): Newton's method on `σ φ_d(s)`, each iterate
    /// one integrator step of `s h` from the start of the step, the derivative the integrated
    /// rate. Once the correction `Δt` is below `1e-8` s and its own error (`|φ̈ Δt² / φ̇|`, twice
    /// the remainder of the Newton step) below `1e-15` s, it is applied to the state by a
    /// second-order Taylor shift instead of a further step (the shift's error in the rates,
    /// `Δt²/2` times the jerk, is then of round-off size). Falls back to the Hermite time (the
    /// plain locator) for a DOF not moving towards zero there or after `MAX_REFINE` iterates.
    /// Leaves the state at the returned fraction in the stepper.
    fn refine_impact(&mut self, t0: f64, h: f64, s_est: f64, d: usize) -> Result<f64, DriverError> {
        let i = self.open.iter().position(|&f| f == d).unwrap_or(0);
        let sigma = self.statuses[d % self.n].sign();
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        let mut s = s_est;
        {
            // The stepper still holds the whole step.
            let (y0, v0, a0) = (self.x0[i], self.v0[i], self.a0[i]);
            let (y1, v1, a1) = (self.phi1[d], self.rates1[d], self.stepper.a1[i]);
            let mut q = s_est;
            for _ in 0..4 {
                let (y, r) = quintic(q, h, y0, y1, v0, v1, a0, a1);
                if sigma * r >= 0.0 {
                    q = f64::NAN;
                    break;
                }
                let dq = -y / (r * h);
                q += dq;
                if dq.abs() < 1e-15 {
                    break;
                }
            }
            if q > 0.0 && q <= 1.0 {
                s = q;
            }
        }
        for _ in 0..MAX_REFINE {
            self.advance_to(t0, h, s)?;
            let st = &mut self.stepper;
            let g = sigma * st.x1[i];
            let rate = sigma * st.v1[i];
            if g >= 0.0 {
                lo = lo.max(s);
            } else {
                hi = hi.min(s);
            }
            if rate.is_nan() || rate >= 0.0 {
                break;
            }
            let dt = -g / rate;
            let remainder = (sigma * st.a1[i] * dt * dt / rate).abs();
            if dt.abs() <= 1e-8 && remainder <= 1e-15 {
                for r in 0..self.open.len() {
                    let (v, a) = (st.v1[r], st.a1[r]);
                    st.x1[r] += dt * (v + 0.5 * dt * a);
                    st.v1[r] += dt * a;
                }
                return Ok(s + dt / h);
            }
            let next = s + dt / h;
            s = if next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
        }
        self.advance_to(t0, h, s_est)?;
        Ok(s_est)
    }

    /// Largest opening margin after one integrator step of `s h` from the start of the step.
    fn margin_at(&mut self, t0: f64, h: f64, s: f64) -> Result<f64, DriverError> {
        self.advance_to(t0, h, s)?;
        self.scratch_phi.copy_from_slice(&self.phi);
        self.scratch_rates.copy_from_slice(&self.rates);
        self.stepper
            .write_open(&self.open, &mut self.scratch_phi, &mut self.scratch_rates);
        let c = self.dynm.check(
            &self.open,
            &self.statuses,
            self.motion.acceleration(t0 + s * h),
            &self.scratch_phi,
            &self.scratch_rates,
            false,
        );
        if c.ok {
            Ok(c.max_margin)
        } else {
            Err(not_positive_definite())
        }
    }

    /// The opening time on the re-integrated solution, from the Hermite estimate `s_est`:
    /// a bracket of the largest margin grown from `1e-7` of the step on the side of the root
    /// (factor 100; the step's ends bracket it in any case: `margin1 > 0` at the end), then
    /// Illinois down to `1e-14` s. Leaves the state at the returned fraction in the stepper.
    fn refine_opening(
        &mut self,
        t0: f64,
        h: f64,
        s_est: f64,
        margin1: f64,
    ) -> Result<f64, DriverError> {
        let g0 = self.largest_margin0();
        let fe = self.margin_at(t0, h, s_est)?;
        let after = fe > 0.0;
        let (mut a, mut fa, mut b, mut fb) = if after {
            (0.0, g0, s_est, fe)
        } else {
            (s_est, fe, 1.0, margin1)
        };
        let mut w = 1e-7;
        loop {
            let p = if after { s_est - w } else { s_est + w };
            if !(p > a && p < b) {
                break;
            }
            let fp = self.margin_at(t0, h, p)?;
            if fp > 0.0 {
                (b, fb) = (p, fp);
            } else {
                (a, fa) = (p, fp);
            }
            if (fp > 0.0) != after {
                break;
            }
            w *= 100.0;
        }
        let mut failed = None;
        let s = illinois(
            |s| match self.margin_at(t0, h, s) {
                Ok(v) => v,
                Err(e) => {
                    failed = Some(e);
                    f64::NAN
                }
            },
            a,
            fa,
            b,
            fb,
            1e-14 / h,
        );
        if let Some(e) = failed {
            return Err(e);
        }
        self.advance_to(t0, h, s)?;
        Ok(s)
    }
}

/// Linear interpolation of the margins (thesis): earliest crossing over the violated DOFs.
fn linear_opening(m0: &[f64], m1: &[f64]) -> f64 {
    let mut s = 1.0_f64;
    for (&a, &b) in m0.iter().zip(m1) {
        if b > 0.0 {
            let si = if a > 0.0 || !a.is_finite() {
                0.0
            } else {
                a / (a - b)
            };
            s = s.min(si);
        }
    }
    s
}

fn not_positive_definite() -> DriverError {
    DriverError::Model(RockingError::new(
        ErrorKind::NotPositiveDefinite,
        "the mass matrix of the open DOFs is not positive definite",
    ))
}
