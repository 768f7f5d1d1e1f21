//! The closure of a loop (SPEC §9): the matrix `G` of the constraint `G v = 0`, its rate `Ġ v`
//! and the position-level residual.

use super::{Chain, ChainPose};

impl Chain {
    /// Closure matrix `G` (row-major `3 × 2J`; empty for an open chain): the column of DOF `a`
    /// is the planar twist `(1, P_y, −P_x)` of a unit rotation about its pivot (rotation rate;
    /// velocity of the material point at the origin). Around a loop `G v = 0`.
    pub fn closure_matrix(&self, pose: &ChainPose) -> Vec<f64> {
        let mut g = Vec::new();
        self.closure_matrix_into(pose, &mut g);
        g
    }

    /// [`Chain::closure_matrix`] into `out` (cleared first), reusing its memory.
    pub fn closure_matrix_into(&self, pose: &ChainPose, out: &mut Vec<f64>) {
        out.clear();
        if !self.is_loop() {
            return;
        }
        let m = self.n_dofs();
        out.reserve(3 * m);
        out.extend((0..m).map(|_| 1.0));
        out.extend((0..m).map(|a| self.pivot(pose, a)[1]));
        out.extend((0..m).map(|a| -self.pivot(pose, a)[0]));
    }

    /// `Ġ v` (length 3; empty for an open chain) for the DOF rates `rates`: the pivots move with
    /// the bodies, `Ġ v = Σ_a v_a (0, Ṗ_a,y, −Ṗ_a,x)` with `Ṗ_a` the velocity of DOF `a`'s pivot
    /// as a material point of the body before its joint. The accelerations of a loop obey
    /// `G a = −Ġ v`.
    pub fn closure_rate(&self, pose: &ChainPose, rates: &[f64]) -> Vec<f64> {
        if !self.is_loop() {
            return Vec::new();
        }
        self.closure_rate_of(pose, rates).to_vec()
    }

    /// [`Chain::closure_rate`] of a loop, without allocation.
    pub fn closure_rate_of(&self, pose: &ChainPose, rates: &[f64]) -> [f64; 3] {
        let nj = self.n_joints();
        assert_eq!(rates.len(), 2 * nj);
        // Twist of the body before joint k: rotation rate and velocity at the origin.
        let mut omega = 0.0;
        let mut v0 = [0.0_f64; 2];
        let mut out = [0.0; 3];
        for k in 0..nj {
            for (a, p) in [(k, pose.right_pivots[k]), (nj + k, pose.left_pivots[k])] {
                let va = rates[a];
                if va != 0.0 {
                    let pdot = [v0[0] - omega * p[1], v0[1] + omega * p[0]];
                    out[1] += va * pdot[1];
                    out[2] -= va * pdot[0];
                }
            }
            for (a, p) in [(k, pose.right_pivots[k]), (nj + k, pose.left_pivots[k])] {
                let va = rates[a];
                omega += va;
                v0 = [v0[0] + va * p[1], v0[1] - va * p[0]];
            }
        }
        out
    }

    /// Position-level closure residual of a loop (zeros for an open chain): the rotation of the
    /// right support implied by the angles and the displacement of the last joint's centre,
    /// `(angle, dx, dy)`. Zero when the last body sits back on its support.
    pub fn closure_residual(&self, pose: &ChainPose) -> [f64; 3] {
        if !self.is_loop() {
            return [0.0; 3];
        }
        let o = self.joints[self.n_joints() - 1].centre;
        let moved = pose.support.apply(o);
        [pose.support.angle, moved[0] - o[0], moved[1] - o[1]]
    }
}
