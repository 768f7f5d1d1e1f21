//! The opening model in the loop driver: from rest and after every moving step (a loop has no
//! reaction test, SPEC §9), and the interval of ground accelerations the closed loop at rest
//! resists.

use super::{codes, LoopError, LoopEventKind, LoopState, Runner, Screen, Work};
use crate::model::configuration::Status;
use crate::model::constrained::opening_model_constrained_in;

/// The screen's margin: every closed DOF's multiplier must exceed this share of the largest
/// generalised force in its optimality condition (`|(M a)_d|`, `|q_d + f_d|`, `|(Gᵀμ)_d|`), far
/// above the round-off of both the screen and the model (about 1e-15 of it), so that the
/// model's answer cannot differ; closer calls go to the model.
const SCREEN_MARGIN: f64 = 1e-9;

impl Runner<'_> {
    /// The opening model at `s` under `ag`: adopts its configuration if it differs (new joints at
    /// zero angle) and, from rest, only if it moves something. Returns whether it changed.
    pub(super) fn opening(&mut self, s: &mut LoopState, ag: f64) -> Result<bool, LoopError> {
        let moving = s.rates.iter().any(|&r| r != 0.0);
        // While moving, the screen proves where the answer is the current configuration.
        self.out.moving_checks += usize::from(moving);
        let screened = moving && self.options.screen != Screen::Off && {
            let Work { open, x, v, .. } = &mut self.work;
            s.open_dofs_into(open);
            s.open_values_into(open, x, v);
            let holds = self
                .equations
                .current_holds(&s.statuses, open, ag, x, v, SCREEN_MARGIN);
            self.out.screened += usize::from(holds);
            holds
        };
        if screened && self.options.screen == Screen::On {
            return Ok(false);
        }
        let moves = match self.choice(s, ag) {
            Ok(moves) => moves,
            Err(e) if screened => panic!("loop screen (verify) at t = {}: {e}", s.time),
            Err(e) => return Err(e),
        };
        let statuses = &self.work.chosen;
        if screened && *statuses != s.statuses {
            panic!(
                "loop screen (verify) at t = {}: the screen kept {:?}, the opening model chose {:?}",
                s.time,
                codes(&s.statuses),
                codes(statuses)
            );
        }
        // From rest: adopt what the model chose when it moves something; while moving: adopt a
        // different configuration.
        if (!moving && moves) || (moving && *statuses != s.statuses) {
            s.statuses.copy_from_slice(statuses);
            self.event(s, LoopEventKind::Opening);
            return Ok(true);
        }
        Ok(false)
    }

    /// The opening model's configuration at `s` under `ag` (left in `self.work.chosen`), and
    /// whether it moves anything.
    pub(super) fn choice(&mut self, s: &LoopState, ag: f64) -> Result<bool, LoopError> {
        let chain = self.chain;
        let m = chain.n_dofs();
        let Work {
            pose,
            mass,
            mass_dofs,
            load,
            velocity_load,
            velocity_sums,
            g,
            chosen: statuses,
            acc,
            opening_model,
            ..
        } = &mut self.work;
        chain.pose_into(&s.phi, pose);
        chain.mass_matrix_with(pose, mass, mass_dofs);
        // `q + f`: `Chain::load_entry` is `Chain::load_vector`'s entry (the same arithmetic).
        velocity_load.clear();
        velocity_load.resize(m, 0.0);
        chain.velocity_load_into(pose, &s.phi, &s.rates, velocity_load, velocity_sums);
        let gravity = self.options.gravity;
        load.clear();
        load.extend((0..m).map(|a| chain.load_entry(pose, a, ag, gravity) + velocity_load[a]));
        chain.closure_matrix_into(pose, g);
        // A loop's `Ġ v` (`Chain::closure_rate`), negated.
        let rhs = chain.closure_rate_of(pose, &s.rates).map(|x| -x);
        statuses.clone_from(&s.statuses);
        acc.clear();
        acc.resize(m, 0.0);
        opening_model_constrained_in(
            mass,
            load,
            g,
            Some(&rhs),
            statuses,
            acc,
            &self.options.model,
            opening_model,
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
        Ok(moves)
    }

    /// The interval of ground accelerations the closed loop at rest `s` resists, by bisection on
    /// each side with the opening model (to 1e-9 relative; its ends are accelerations the model
    /// answered "at rest" to). Empty (`(+∞, −∞)`) if it does not resist `a_g = 0`: a loop that
    /// does not stand under its own weight (an arch thinner than its minimum thickness) must be
    /// asked at every step, `a_g = 0` included (`(0, 0)` here kept it at rest under no motion).
    pub(super) fn resisted_interval(&mut self, s: &LoopState) -> Result<(f64, f64), LoopError> {
        let gravity = self.options.gravity;
        let mut opens = |ag: f64| self.choice(s, ag);
        if opens(0.0)? {
            return Ok((f64::INFINITY, f64::NEG_INFINITY));
        }
        let mut ends = [0.0; 2];
        for (end, sign) in ends.iter_mut().zip([-1.0, 1.0]) {
            let (mut lo, mut hi) = (0.0, 0.01 * gravity);
            while !opens(sign * hi)? {
                lo = hi;
                hi *= 2.0;
                if hi > 1e3 * gravity {
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
}
