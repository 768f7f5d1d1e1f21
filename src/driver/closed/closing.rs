//! Closings of a loop's step: the located earliest zero, the joints closing with it, the
//! constrained impact model, the lock of a chattering joint and of joints opened slower than the
//! step resolves (docs/arches.md 2b).

use super::{
    project_positions_posed, project_rates_with, side, LoopError, LoopEventKind, LoopState, Runner,
    Work,
};
use crate::chain::ChainPose;
use crate::model::configuration::Status;
use crate::model::constrained::impact_model_constrained_symmetric;

/// Closings located within this share of the step of the earliest are one event (the closing
/// set of one impact): far above the located zeros' error (the cubic interpolant's `O(dt⁴)` on
/// the angles divided by the closing rate, below 1e-12 s on the arches of docs/arches.md), far
/// below any physical interval between two impacts the step could resolve.
const SIMULTANEOUS: f64 = 1e-6;

/// A step of the open DOFs `open` from `(x, v)` whose depths reach zero: `crossings` are the
/// located zeros (index into `open`, fraction of the step `dt`), `first` the earliest.
pub(super) struct Located<'s> {
    pub open: &'s [usize],
    pub x: &'s [f64],
    pub v: &'s [f64],
    pub crossings: &'s [(usize, f64)],
    pub first: f64,
    pub dt: f64,
    /// The ground's power at the step's start (for the work up to the closing).
    pub power_start: f64,
}

impl Runner<'_> {
    /// Carries `s` to the earliest located zero of the step, flags the joints closing there and
    /// applies the impact model (or the lock); returns the kinetic energy after. `pose` is
    /// scratch (left the pose of the state at the impact).
    pub(super) fn close(
        &mut self,
        s: &mut LoopState,
        step: &Located,
        pose: &mut ChainPose,
    ) -> Result<f64, LoopError> {
        let opts = self.options;
        let n = self.chain.n_joints();
        let Located {
            open,
            x,
            v,
            crossings,
            first,
            dt,
            power_start,
        } = *step;
        let motion = self.motion;
        let ag = |t: f64| motion.acceleration(t);
        let depth = |d: usize, xi: f64| side(d, n) * xi;
        // The state at the earliest zero: RK4 again from the start of the step over the
        // located fraction (no interpolation error in the state the impact sees).
        let (xe, ve) = (&mut self.work.xe, &mut self.work.ve);
        xe.clear();
        ve.clear();
        xe.extend_from_slice(x);
        ve.extend_from_slice(v);
        if first > 0.0
            && !self
                .equations
                .rk4_step(open, &ag, s.time, first * dt, x, v, xe, ve)
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
        // The work's buffers taken for the event (given back at its end).
        let mut closing = std::mem::take(&mut self.work.closing);
        closing.clear();
        closing.resize(n, false);
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
        // One pose of the angles at the impact serves the projection (which leaves the pose of
        // its result), the kinetic energies, the model's matrices and the slow joints' rates.
        self.chain.pose_into(&s.phi, pose);
        let residual = if opts.project {
            let rest = &mut self.work.rest;
            rest.clear();
            rest.extend(open.iter().copied().filter(|&d| !closing[d % n]));
            let work = &mut self.work.projection;
            project_positions_posed(self.chain, rest, &mut s.phi, self.reach, 3, pose, work)
        } else {
            self.residual_posed(pose)
        };
        self.out.max_closure_residual = self.out.max_closure_residual.max(residual);
        if s.time == self.last_event_time {
            self.stalled += 1;
            if self.stalled >= 100 {
                return Err(LoopError::Stalled(s.time));
            }
        } else {
            (self.last_event_time, self.stalled) = (s.time, 0);
        }
        // The ground's work up to the closing, on the located part of the step.
        let power_event = self.ground_power_posed(pose, &s.rates, s.time);
        self.out.energy.ground_work += 0.5 * first * dt * (power_start + power_event);
        let before = self.kinetic_posed(pose, &s.rates);
        self.max_kinetic = self.max_kinetic.max(before);
        let mut statuses_before = std::mem::take(&mut self.work.statuses_before);
        let mut rates_before = std::mem::take(&mut self.work.rates_before);
        statuses_before.clone_from(&s.statuses);
        rates_before.clone_from(&s.rates);
        let closing_rate = (0..n)
            .filter(|&k| closing[k])
            .map(|k| (s.rates[k] + s.rates[n + k]).abs())
            .fold(0.0, f64::max);
        let Work {
            mass,
            mass_dofs,
            g,
            impact,
            ..
        } = &mut self.work;
        self.chain.mass_matrix_with(pose, mass, mass_dofs);
        self.chain.closure_matrix_into(pose, g);
        // The chain's mass matrix is symmetric to the bit (its lower triangle copied).
        let report = impact_model_constrained_symmetric(
            mass,
            g,
            &mut s.statuses,
            &mut s.rates,
            &closing,
            &opts.model,
            impact,
        )?;
        let joints: Vec<usize> = (0..n).filter(|&k| closing[k]).collect();
        let loss = report.kinetic_before - report.kinetic_after;
        let mut kinetic_after = report.kinetic_after;
        if loss <= opts.lock_loss * report.kinetic_before && closing_rate <= self.lock_rate {
            // A chatter: lock the closing joints instead.
            s.statuses.copy_from_slice(&statuses_before);
            s.rates.copy_from_slice(&rates_before);
            for &k in &joints {
                s.statuses[k] = Status::Closed;
            }
            let Work {
                open, projection, ..
            } = &mut self.work;
            s.open_dofs_into(open);
            // Fewer than four open joints: at rest (SPEC §9), settled below.
            if open.len() < 4 {
                s.rates.iter_mut().for_each(|r| *r = 0.0);
            } else if !project_rates_with(self.chain, pose, open, &mut s.rates, projection) {
                return Err(LoopError::Singular(s.time));
            }
            kinetic_after = self.kinetic_posed(pose, &s.rates);
            self.event(
                s,
                LoopEventKind::Locked {
                    joints,
                    kinetic_before: report.kinetic_before,
                    kinetic_after,
                },
            );
        } else {
            if self.keep_slow_closed(s, pose)? {
                kinetic_after = self.kinetic_posed(pose, &s.rates);
            }
            self.event(
                s,
                LoopEventKind::Closing {
                    joints,
                    kinetic_before: report.kinetic_before,
                    kinetic_after,
                },
            );
        }
        self.out.energy.dissipated += report.kinetic_before - kinetic_after;
        self.work.closing = closing;
        self.work.statuses_before = statuses_before;
        self.work.rates_before = rates_before;
        Ok(kinetic_after)
    }

    /// Joints the impact model opens at zero angle with a rate below the lock rate are kept
    /// closed: such a flight lasts about one step or less (the rate gravity gives in one step at
    /// the chain's size, as the lock of a chattering joint), the fixed step cannot resolve it, and
    /// the limit of the Zeno sequence of impacts it starts is sustained contact. The rates are
    /// then the kinetic-metric projection of the model's onto the remaining open DOFs with the
    /// closure (kinetic energy not above the model's); a DOF at zero angle that the projection
    /// turns inadmissible (closing) is kept closed too, until none is. Fewer than four open
    /// joints: at rest (SPEC §9). Returns whether anything changed.
    /// `pose` is the pose of `s.phi` (which this does not change).
    pub(super) fn keep_slow_closed(
        &mut self,
        s: &mut LoopState,
        pose: &ChainPose,
    ) -> Result<bool, LoopError> {
        let n = self.chain.n_joints();
        let mut changed = false;
        let flight = self.options.min_flight;
        let Work {
            open,
            x,
            v,
            acc,
            slow,
            projection,
            ..
        } = &mut self.work;
        loop {
            s.open_dofs_into(open);
            acc.clear();
            acc.resize(open.len(), 0.0);
            if flight > 0.0 {
                s.open_values_into(open, x, v);
                let ag = self.motion.acceleration(s.time);
                if !self.equations.accelerations(open, ag, x, v, acc) {
                    return Err(LoopError::Singular(s.time));
                }
            }
            slow.clear();
            slow.extend(
                open.iter()
                    .zip(acc.iter())
                    .filter(|&(&d, &a)| {
                        let (r, a) = (side(d, n) * s.rates[d], side(d, n) * a);
                        let short = a < 0.0 && 2.0 * r <= -a * flight * self.options.dt;
                        s.phi[d] == 0.0 && (r <= self.lock_rate || short)
                    })
                    .map(|(&d, _)| d % n),
            );
            if slow.is_empty() {
                return Ok(changed);
            }
            changed = true;
            for &k in slow.iter() {
                s.statuses[k] = Status::Closed;
            }
            s.open_dofs_into(open);
            if open.len() < 4 {
                s.rates.iter_mut().for_each(|r| *r = 0.0);
                return Ok(true);
            }
            if !project_rates_with(self.chain, pose, open, &mut s.rates, projection) {
                return Err(LoopError::Singular(s.time));
            }
        }
    }
}
