//! The driver's state at one instant: a value that a step advances and an event transforms.
//!
//! It holds what the thesis's time history carries from step to step (3.3): the time, the DOF
//! angles and rates, the configuration (statuses and the open DOFs), and what the equations of
//! motion give at that state — the accelerations, the reaction margins of the closed interfaces
//! and the power of the ground motion — so that a step need not evaluate its start twice. The
//! geometry is not state: it is a function of the angles, recomputed by the chain
//! ([`super::chain::ChainDynamics`]) wherever it is needed.

use super::chain::ChainDynamics;
use super::switch::InterfaceState;
use super::DriverError;
use crate::model::configuration::{open_dofs, Status};

/// The simulated time with the compensation of its summation (Kahan): without it the clock
/// drifts by about an ulp per step, 1e-11 s after 3e5 steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Clock {
    /// Time (s).
    pub t: f64,
    /// The part of the summed steps that `t` lost to rounding, negated.
    comp: f64,
}

impl Clock {
    /// The clock at `t`, exactly.
    pub fn at(t: f64) -> Clock {
        Clock { t, comp: 0.0 }
    }

    /// The clock advanced by `d` (compensated summation).
    #[inline]
    pub fn advanced(self, d: f64) -> Clock {
        let y = d - self.comp;
        let t = self.t + y;
        Clock {
            t,
            comp: (t - self.t) - y,
        }
    }
}

/// The state of a chain of `n` interfaces (`2n` DOFs, SPEC §1) at one instant.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct State {
    pub clock: Clock,
    /// Ground acceleration at `clock.t`.
    pub ag: f64,
    /// DOF angles (rad, `2n`: `phĭ_0 … phĭ_{n−1}, phî_0 … phî_{n−1}`).
    pub phi: Vec<f64>,
    /// DOF rates (rad/s, `2n`).
    pub rates: Vec<f64>,
    /// DOF accelerations (rad/s², `2n`, zero off the open DOFs): the integrator's acceleration
    /// state, the equations of motion's at the start of a run and after every event.
    pub acc: Vec<f64>,
    /// Reaction margins of the closed interfaces' corners (`2n`; `> 0`: the reaction test
    /// fails; `−∞` elsewhere), [`crate::model::opening::reaction_margins`].
    pub margin: Vec<f64>,
    /// Power of the ground motion's inertial load, `Σ_f q^{ag}_f φ̇_f`.
    pub power: f64,
    /// Configuration.
    pub statuses: Vec<Status>,
    /// The open DOFs of `statuses`, in interface order ([`open_dofs`]).
    pub open: Vec<usize>,
}

impl State {
    /// Released at rest at time 0 from `angles` (per interface: negative = about the right
    /// corner, positive = about the left corner, zero = closed; `None`: straight and closed).
    pub fn released(n: usize, angles: Option<&[f64]>) -> State {
        let m = 2 * n;
        let mut state = State {
            clock: Clock::at(0.0),
            ag: 0.0,
            phi: vec![0.0; m],
            rates: vec![0.0; m],
            acc: vec![0.0; m],
            margin: vec![f64::NEG_INFINITY; m],
            power: 0.0,
            statuses: vec![Status::Closed; n],
            open: Vec::with_capacity(m),
        };
        for (k, &a) in angles.unwrap_or(&[]).iter().enumerate() {
            if a < 0.0 {
                state.statuses[k] = Status::OpenRight;
                state.phi[k] = a;
            } else if a > 0.0 {
                state.statuses[k] = Status::OpenLeft;
                state.phi[n + k] = a;
            }
        }
        state.open.extend(open_dofs(&state.statuses));
        state
    }

    /// The state `s` handed over by another scheme ([`super::switch`]), its accelerations,
    /// margins and power still to be evaluated ([`State::refresh`]).
    pub fn resumed(s: &InterfaceState) -> State {
        let m = s.phi.len();
        let mut state = State {
            clock: Clock::at(s.t),
            ag: 0.0,
            phi: s.phi.clone(),
            rates: s.rates.clone(),
            acc: vec![0.0; m],
            margin: vec![f64::NEG_INFINITY; m],
            power: 0.0,
            statuses: s.statuses.clone(),
            open: Vec::with_capacity(m),
        };
        state.open.extend(open_dofs(&state.statuses));
        state
    }

    /// The state as another scheme receives it.
    pub fn interface_state(&self) -> InterfaceState {
        InterfaceState {
            t: self.t(),
            phi: self.phi.clone(),
            rates: self.rates.clone(),
            statuses: self.statuses.clone(),
        }
    }

    /// Time (s).
    #[inline]
    pub fn t(&self) -> f64 {
        self.clock.t
    }

    /// Number of interfaces `n`.
    #[inline]
    pub fn n(&self) -> usize {
        self.statuses.len()
    }

    /// Whether every interface is closed (the column moves with the ground).
    #[inline]
    pub fn is_closed(&self) -> bool {
        self.open.is_empty()
    }

    /// The sign `σ` of the admissible angles of DOF `d` (−1 on `phĭ`, +1 on `phî`, 0 when its
    /// interface is closed).
    #[inline]
    pub fn sign(&self, d: usize) -> f64 {
        let n = self.n();
        self.statuses[if d < n { d } else { d - n }].sign()
    }

    /// Largest reaction margin (`> 0`: a reaction test fails at this state).
    pub fn largest_margin(&self) -> f64 {
        self.margin
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Moves the state to `clock`, where the ground acceleration is `ag`.
    #[inline]
    pub fn set_time(&mut self, clock: Clock, ag: f64) {
        self.clock = clock;
        self.ag = ag;
    }

    /// After a change of `statuses`: the open DOFs, and the chain told.
    pub fn reconfigure(&mut self, chain: &mut impl ChainDynamics) {
        self.open.clear();
        self.open.extend(open_dofs(&self.statuses));
        chain.reconfigured();
    }

    /// Evaluates the equations of motion at the state: accelerations, margins and power.
    pub fn refresh(&mut self, chain: &mut impl ChainDynamics) -> Result<(), DriverError> {
        let c = chain.check(
            &self.open,
            &self.statuses,
            self.ag,
            &self.phi,
            &self.rates,
            false,
        );
        if !c.ok {
            return Err(super::chain::not_positive_definite());
        }
        self.acc.copy_from_slice(chain.accelerations());
        self.margin.copy_from_slice(chain.margins());
        self.power = c.power;
        Ok(())
    }

    /// Absolute block rotations: the running sum of the DOF angles (as
    /// [`crate::model::column::Column::pose_into`], without the geometry).
    pub fn block_angles(&self) -> impl Iterator<Item = f64> + '_ {
        let n = self.n();
        (0..n).scan(0.0_f64, move |alpha, k| {
            let theta = if self.phi[k] != 0.0 {
                self.phi[k]
            } else {
                self.phi[n + k]
            };
            *alpha += theta;
            Some(*alpha)
        })
    }
}
