//! The energy balance of a loop run, as the column driver's (`driver::EnergyBalance`): the work
//! of the ground motion's inertial load, integrated by the trapezoidal rule on the steps (and on
//! the located part of a step that ends at a closing), against the change of kinetic and
//! potential energy and the kinetic energy lost at closings, locks and settlings. The
//! constraint forces of the closure do no work (`G v = 0`); what the balance leaves is the
//! scheme's error: the quadrature of the work, RK4's, and the projections back onto the closure
//! after every step (positions and rates), none of which the driver books.

use super::{LoopState, Runner};
use crate::chain::ChainPose;

/// Energy bookkeeping of a loop run (J).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LoopEnergy {
    /// Work of the inertial load of the ground motion, `∫ −Σ_j m_j a_g ẋ_j dt`.
    pub ground_work: f64,
    /// Kinetic energy lost at closings (the impact model, the locks, the joints kept closed)
    /// and settlings.
    pub dissipated: f64,
    /// Kinetic energy at the start (zero from rest) and at the end.
    pub kinetic_start: f64,
    pub kinetic_end: f64,
    /// Potential energy of the weight at the end minus at the start.
    pub potential_change: f64,
}

impl LoopEnergy {
    /// `ground_work − dissipated − (kinetic_end − kinetic_start) − potential_change`: zero but
    /// for the scheme's error.
    pub fn residual(&self) -> f64 {
        self.ground_work
            - self.dissipated
            - (self.kinetic_end - self.kinetic_start)
            - self.potential_change
    }
}

impl Runner<'_> {
    /// Power of the ground motion's inertial load at time `t` in the pose `pose` with the DOF
    /// rates `rates`: `Σ_a q^{a_g}_a φ̇_a` (the horizontal part of the load).
    pub(super) fn ground_power_posed(&self, pose: &ChainPose, rates: &[f64], t: f64) -> f64 {
        let ag = self.ag(t);
        rates
            .iter()
            .enumerate()
            .filter(|&(_, &r)| r != 0.0)
            .map(|(a, &r)| r * self.chain.load_entry(pose, a, ag, 0.0))
            .sum()
    }

    /// [`Runner::ground_power_posed`] of a state (zero at rest, without a pose), posing its
    /// angles in `pose` (scratch).
    pub(super) fn ground_power(&self, s: &LoopState, pose: &mut ChainPose) -> f64 {
        if s.rates.iter().all(|&r| r == 0.0) {
            return 0.0;
        }
        self.chain.pose_into(&s.phi, pose);
        self.ground_power_posed(pose, &s.rates, s.time)
    }
}
