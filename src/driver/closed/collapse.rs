//! Settling and collapse of a loop (docs/arches.md 2b): at rest after an impact, the loop
//! closed outright a hair from closure; the point of no return of its mechanism.

use super::{side, LoopEventKind, LoopState, Runner};
use crate::chain::ChainPose;
use crate::model::configuration::Status;

/// A loop settled with no point displaced farther than this from the closed geometry (m) is
/// closed: a nanometre, a thousand times the closure projection's round-off on the arches of
/// docs/arches.md and far below any displacement that matters to a structure.
const SNAP_DISTANCE: f64 = 1e-9;

impl Runner<'_> {
    /// After an impact that left `kinetic_after`: settled (at rest) below the settle ratio of the
    /// run's largest kinetic energy or with fewer than four open joints (SPEC §9).
    pub(super) fn settle(&mut self, s: &mut LoopState, kinetic_after: f64) {
        let opts = self.options;
        let n = self.chain.n_joints();
        let open_after = s.statuses.iter().filter(|st| st.is_open()).count();
        if kinetic_after <= opts.settle_ratio * self.max_kinetic || open_after < 4 {
            // At rest: what kinetic energy was left is lost.
            self.out.energy.dissipated += kinetic_after;
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
            self.event(s, LoopEventKind::Settled);
        }
    }

    /// Potential energy of the bodies' weight (J) in the pose of `phi`.
    pub(super) fn potential(&self, phi: &[f64]) -> f64 {
        self.potential_posed(&self.chain.pose(phi))
    }

    /// [`Runner::potential`] in a pose already built.
    fn potential_posed(&self, pose: &ChainPose) -> f64 {
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
    pub(super) fn collapsed(
        &self,
        s: &LoopState,
        open: &[usize],
        residual: f64,
        pose: &ChainPose,
    ) -> bool {
        let n = self.chain.n_joints();
        if s.phi.iter().any(|p| p.abs() > self.options.collapse_angle) {
            return true;
        }
        // A pose off the closure by `residual` misplaces the weight by about that much.
        let slack =
            self.potential_tolerance + self.options.gravity * self.chain.total_mass() * residual;
        let potential = self.potential_posed(pose);
        if potential < self.closed_potential - slack {
            return true;
        }
        // Past the maximum of `V` along a one-DOF path from the closed loop, a strict local
        // minimum: `V` has climbed above `V₀` first. (A mechanism at rest a hair from closure,
        // angles of 1e-12 rad, has gravity's power at round-off, of either sign.)
        if open.len() != 4 || potential <= self.closed_potential + slack {
            return false;
        }
        // Gravity's load on the open DOFs (`Chain::load_entry`, the entries of
        // `Chain::load_vector`: the same arithmetic).
        let g = self.options.gravity;
        let power: f64 = open
            .iter()
            .map(|&d| self.chain.load_entry(pose, d, 0.0, g) * s.rates[d])
            .sum();
        let opening: f64 = open.iter().map(|&d| side(d, n) * s.rates[d]).sum();
        power > 0.0 && opening > 0.0
    }
}
