//! A step of the event-driven scheme: its length, and the state at its end, integrated from the
//! state at its start by the chosen [`super::Integrator`] (the open DOFs only; closed DOFs stay
//! at zero). The start is kept, so that an event inside the step can be reached by integrating
//! again over part of it.

use super::chain::{not_positive_definite, ChainDynamics};
use super::integrator::Stepper;
use super::problem::Problem;
use super::state::{Clock, State};
use super::{DriverError, Integrator};

pub(crate) struct Step {
    /// The integrator's buffers; after [`Step::advance`] or [`Step::advance_to`] the open DOFs'
    /// angles, rates and accelerations at the end (`x1`, `v1`, `a1`).
    pub stepper: Stepper,
    /// Start: time, ground acceleration, and the open DOFs' angles, rates and accelerations.
    pub t0: f64,
    ag0: f64,
    pub x0: Vec<f64>,
    pub v0: Vec<f64>,
    pub a0: Vec<f64>,
    /// Length (s).
    pub h: f64,
    /// End: clock and ground acceleration.
    pub end: Clock,
    pub ag1: f64,
    /// The angles and rates at the end (full `2n`).
    pub phi1: Vec<f64>,
    pub rates1: Vec<f64>,
}

impl Step {
    pub fn new(n: usize, integrator: Integrator) -> Step {
        let m = 2 * n;
        Step {
            stepper: Stepper::new(n, integrator),
            t0: 0.0,
            ag0: 0.0,
            x0: vec![0.0; n],
            v0: vec![0.0; n],
            a0: vec![0.0; n],
            h: 0.0,
            end: Clock::at(0.0),
            ag1: 0.0,
            phi1: vec![0.0; m],
            rates1: vec![0.0; m],
        }
    }

    /// The next step from `state`: `dt`, the last two halved rather than leaving a sliver
    /// before `duration`, and ended exactly where the ground motion ends (its acceleration has a
    /// kink or a jump there, which a straddling step would integrate at first order only).
    #[inline]
    pub fn plan<C: ChainDynamics>(&mut self, problem: &Problem<C>, state: &State) {
        let dt = problem.opts.stepping.dt;
        let t = state.t();
        let remaining = problem.opts.stopping.duration - t;
        let mut h = if remaining < 1.5 * dt && remaining > dt {
            0.5 * remaining
        } else {
            dt.min(remaining)
        };
        let mut end = state.clock.advanced(h);
        let motion_end = problem.motion_end;
        if t < motion_end && t + h > motion_end && motion_end - t > 1e-9 * dt {
            h = motion_end - t;
            end = Clock::at(motion_end);
        }
        self.t0 = t;
        self.ag0 = state.ag;
        self.h = h;
        self.end = end;
        self.ag1 = problem.ag(end.t);
    }

    /// Integrates the open DOFs of `state` over the step: the end in `phi1`, `rates1`.
    #[inline]
    pub fn advance<C: ChainDynamics>(
        &mut self,
        problem: &mut Problem<C>,
        state: &State,
    ) -> Result<(), DriverError> {
        for (i, &d) in state.open.iter().enumerate() {
            self.x0[i] = state.phi[d];
            self.v0[i] = state.rates[d];
            self.a0[i] = state.acc[d];
        }
        self.integrate(problem, state, self.h, self.ag1)?;
        self.phi1.copy_from_slice(&state.phi);
        self.rates1.copy_from_slice(&state.rates);
        self.stepper
            .write_open(&state.open, &mut self.phi1, &mut self.rates1);
        Ok(())
    }

    /// One integrator step over the fraction `s` of the step from its start; the result is in
    /// the stepper.
    pub fn advance_to<C: ChainDynamics>(
        &mut self,
        problem: &mut Problem<C>,
        state: &State,
        s: f64,
    ) -> Result<(), DriverError> {
        let ag = problem.ag(self.t0 + s * self.h);
        self.integrate(problem, state, s * self.h, ag)
    }

    #[inline]
    fn integrate<C: ChainDynamics>(
        &mut self,
        problem: &mut Problem<C>,
        state: &State,
        h: f64,
        ag1: f64,
    ) -> Result<(), DriverError> {
        let k = state.open.len();
        let ok = self.stepper.step(
            problem.opts.stepping.integrator,
            &mut problem.chain,
            &state.open,
            &state.statuses,
            problem.motion,
            self.t0,
            h,
            self.ag0,
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

    /// Accepts the step: `state` moves to its end, where the chain's last check was made
    /// (margins, power `power`).
    #[inline]
    pub fn accept(&mut self, state: &mut State, chain: &impl ChainDynamics, power: f64) {
        state.power = power;
        std::mem::swap(&mut state.phi, &mut self.phi1);
        std::mem::swap(&mut state.rates, &mut self.rates1);
        for (i, &d) in state.open.iter().enumerate() {
            state.acc[d] = self.stepper.a1[i];
        }
        state.margin.copy_from_slice(chain.margins());
        state.set_time(self.end, self.ag1);
    }
}
