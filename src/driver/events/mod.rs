//! Events of the event-driven scheme (SPEC §5): finding the first one inside a step
//! ([`detect`]), locating it ([`locate`], and [`refine`]: the state moved to it), and the
//! transitions — the opening judgement ([`opening`]), an impact ([`impact`]) and the settling
//! that may follow it ([`settle`]), the contact-force stops ([`forces`]), overturning
//! ([`overturn`]), and the stops of a column that can no longer move or tip ([`rest`]).

pub(crate) mod detect;
pub(crate) mod forces;
pub(crate) mod impact;
pub(crate) mod locate;
pub(crate) mod monolith;
pub(crate) mod opening;
pub(crate) mod overturn;
pub(crate) mod refine;
pub(crate) mod rest;
pub(crate) mod settle;

use super::chain::{ChainDynamics, Check};
use super::state::State;

/// An event found inside a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Found {
    /// The open DOF `d` back at zero, moving towards it.
    Impact(usize),
    /// A reaction test failing at a closed interface.
    Opening,
}

/// A state probed inside a step or a little past an instant (full `2n` angles and rates).
pub(crate) struct Probe {
    pub phi: Vec<f64>,
    pub rates: Vec<f64>,
}

impl Probe {
    pub fn new(n: usize) -> Probe {
        Probe {
            phi: vec![0.0; 2 * n],
            rates: vec![0.0; 2 * n],
        }
    }

    /// The checks at the probed state in `state`'s configuration under the ground acceleration
    /// `ag` (without the contact forces).
    pub fn check(&self, chain: &mut impl ChainDynamics, state: &State, ag: f64) -> Check {
        chain.check(
            &state.open,
            &state.statuses,
            ag,
            &self.phi,
            &self.rates,
            false,
        )
    }
}
