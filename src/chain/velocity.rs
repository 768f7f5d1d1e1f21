//! The velocity-dependent generalised forces of a chain (the exact equations' centripetal terms).

use super::{cross, Chain, ChainPose};

impl Chain {
    /// Velocity-dependent generalised forces that thesis Eq. 6 leaves out (centripetal terms of
    /// the exact Lagrangian equations), as [`crate::model::column::Column::velocity_load_into`]:
    /// with `φ̈ = 0` every body still accelerates, `a(x) = a(P) − ω² (x − P)` for two points of
    /// the same body, and the generalised force is `−Σ_{j after joint} m_j (c_j − P_a) × a(c_j)`.
    /// The exact equations of the cut chain are `M φ̈ = q + this (+ Gᵀ λ in a loop)`.
    pub fn velocity_load(&self, pose: &ChainPose, phi: &[f64], rates: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n_dofs()];
        self.velocity_load_into(pose, phi, rates, &mut out, &mut Vec::new());
        out
    }

    /// [`Chain::velocity_load`] into `out` (length `2J`), with the suffix sums
    /// `Σ_{j after joint} m_j c_j × a_j` and `Σ m_j a_j` kept in `scratch` (reused memory):
    /// `f_a = −(Σ m_j c_j × a_j − P_a × Σ m_j a_j)`, linear in the number of bodies.
    pub fn velocity_load_into(
        &self,
        pose: &ChainPose,
        phi: &[f64],
        rates: &[f64],
        out: &mut [f64],
        scratch: &mut Vec<[f64; 2]>,
    ) {
        assert_eq!(out.len(), 2 * self.n_joints());
        self.velocity_load_sums(pose, phi, rates, scratch);
        for (d, o) in out.iter_mut().enumerate() {
            *o = self.velocity_load_entry(pose, scratch, d);
        }
    }

    /// Entry `d` of [`Chain::velocity_load_into`] from the sums [`Chain::velocity_load_sums`]
    /// left in `scratch` (the same arithmetic): for the DOFs a caller reads, not all `2J`.
    #[inline]
    pub fn velocity_load_entry(&self, pose: &ChainPose, scratch: &[[f64; 2]], d: usize) -> f64 {
        let (nj, nb) = (self.n_joints(), self.n_bodies());
        let (centre_acc, sums) = scratch.split_at(nb + 1);
        let k = (if d < nj { d } else { d - nj }).min(nb);
        let p = self.pivot(pose, d);
        -(centre_acc[k][0] - cross(p, sums[k]))
    }

    /// The suffix sums of [`Chain::velocity_load_into`] into `scratch` (length `2 (bodies + 1)`).
    pub fn velocity_load_sums(
        &self,
        pose: &ChainPose,
        phi: &[f64],
        rates: &[f64],
        scratch: &mut Vec<[f64; 2]>,
    ) {
        let (nj, nb) = (self.n_joints(), self.n_bodies());
        assert_eq!(rates.len(), 2 * nj);
        assert_eq!(phi.len(), 2 * nj);
        scratch.clear();
        scratch.resize(2 * (nb + 1), [0.0; 2]);
        let (centre_acc, sums) = scratch.split_at_mut(nb + 1);
        centre_accelerations(
            phi,
            rates,
            [&pose.right_pivots, &pose.left_pivots],
            &pose.centres,
            nj,
            &mut centre_acc[..nb],
        );
        // Backwards: sums[k] = Σ_{j>=k} m_j a_j, and centre_acc[k], once read, becomes
        // (Σ_{j>=k} m_j c_j × a_j, 0).
        let (mut moment, mut force) = (0.0_f64, [0.0_f64; 2]);
        centre_acc[nb] = [0.0, 0.0];
        sums[nb] = [0.0, 0.0];
        for j in (0..nb).rev() {
            let m = self.bodies[j].mass;
            let (c, a) = (pose.centres[j], centre_acc[j]);
            moment += m * cross(c, a);
            force = [force[0] + m * a[0], force[1] + m * a[1]];
            centre_acc[j] = [moment, 0.0];
            sums[j] = force;
        }
    }
}

/// The centripetal accelerations of the body centres of an open chain with every DOF
/// acceleration zero, into `out` (one per body): `a(r on body j) = a(P_j) − ω_j² (r − P_j)`,
/// where `P_j` is the active pivot of joint `j` (a material point of both bodies it joins; the
/// right corner `pivots[0][j]` when `phĭ_j` is displaced or alone moving, else the left
/// `pivots[1][j]`) and `ω_j` the angular velocity of body `j`. `n_joints` is the offset of the
/// `phî` DOFs in `phi` and `rates` (SPEC §1 order). The column's and the chain's velocity loads
/// share it.
pub(crate) fn centre_accelerations(
    phi: &[f64],
    rates: &[f64],
    pivots: [&[[f64; 2]]; 2],
    centres: &[[f64; 2]],
    n_joints: usize,
    out: &mut [[f64; 2]],
) {
    let mut omega = 0.0_f64;
    // Hinge point of the previous joint and its acceleration (ground: at rest).
    let mut hinge = [0.0_f64, 0.0];
    let mut hinge_acc = [0.0_f64, 0.0];
    for (j, acc) in out.iter_mut().enumerate() {
        let use_right = phi[j] != 0.0 || (phi[n_joints + j] == 0.0 && rates[j] != 0.0);
        let p = if use_right {
            pivots[0][j]
        } else {
            pivots[1][j]
        };
        // Acceleration of the new hinge as a point of the body before it.
        let acc_p = [
            hinge_acc[0] - omega * omega * (p[0] - hinge[0]),
            hinge_acc[1] - omega * omega * (p[1] - hinge[1]),
        ];
        omega += rates[j] + rates[n_joints + j];
        let c = centres[j];
        *acc = [
            acc_p[0] - omega * omega * (c[0] - p[0]),
            acc_p[1] - omega * omega * (c[1] - p[1]),
        ];
        hinge = p;
        hinge_acc = acc_p;
    }
}
