//! The interface mass matrix `M`, the load vector `q` and the velocity terms that thesis Eq. 6
//! leaves out, in the current geometry (thesis Eq. 4–6; SPEC §1):
//! `M[a][b] = Σ_{j ≥ max(k_a, k_b)} ( m_j (c_j − P_a)·(c_j − P_b) + I_j )`,
//! `q[a] = Σ_{j ≥ k_a} ( −(c_j − P_a)_y F_jx + (c_j − P_a)_x F_jy )`, `F_j = (−m_j a_g, −m_j g)`.

use super::{Column, Pose};

impl Pose {
    /// Entry `M[a][b]` of the mass matrix:
    /// `Σ_{j≥K} m_j |c_j|² − (P_a + P_b)·Σ m_j c_j + P_a·P_b Σ m_j + Σ I_j`, `K = max(k_a, k_b)`.
    ///
    /// The expanded form loses digits when the column is far from the pivots compared with its
    /// size, so the entry is evaluated as `Σ m_j (c_j − P_a)·(c_j − P_b)` about the centre of mass
    /// of the part above: `S0 (g − P_a)·(g − P_b) + (S2 − S0 |g|²) + ΣI`.
    ///
    /// `g` and the spread (clamped at 0) come with the pose (`Above`), computed there by the same
    /// operations.
    #[inline]
    pub(crate) fn mass_entry(&self, a: usize, b: usize) -> f64 {
        let k = self.interface(a).max(self.interface(b));
        let pa = self.pivot(a);
        let pb = self.pivot(b);
        let above = &self.above[k];
        let (s0, g) = (above.mass, above.centre);
        s0 * ((g[0] - pa[0]) * (g[0] - pb[0]) + (g[1] - pa[1]) * (g[1] - pb[1]))
            + above.spread
            + above.inertia
    }

    /// Entry `q[a]` of the load vector: `a_g (S1y − S0 P_ay) − g (S1x − S0 P_ax)` over `j ≥ k_a`.
    #[inline]
    pub(crate) fn load_entry(&self, a: usize, ground_acc: f64, gravity: f64) -> f64 {
        let k = self.interface(a);
        let p = self.pivot(a);
        let above = &self.above[k];
        let (s0, s1) = (above.mass, above.moment);
        ground_acc * (s1[1] - s0 * p[1]) - gravity * (s1[0] - s0 * p[0])
    }
}

impl Column {
    /// Full `2n × 2n` mass matrix of the current geometry, row-major (it is symmetric).
    pub fn mass_matrix(&self, pose: &Pose) -> Vec<f64> {
        let m = self.n_dofs();
        let mut out = vec![0.0; m * m];
        self.mass_matrix_into(pose, &mut out);
        out
    }

    /// [`Column::mass_matrix`] into `out` (length `4n²`).
    pub fn mass_matrix_into(&self, pose: &Pose, out: &mut [f64]) {
        let m = self.n_dofs();
        assert_eq!(out.len(), m * m);
        for a in 0..m {
            for b in a..m {
                let v = pose.mass_entry(a, b);
                out[a * m + b] = v;
                out[b * m + a] = v;
            }
        }
    }

    /// Load vector `q` (length `2n`) for horizontal ground acceleration `ground_acc` and gravity
    /// `gravity` (both m/s², gravity positive downwards), in the current geometry.
    pub fn load_vector(&self, pose: &Pose, ground_acc: f64, gravity: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.n_dofs()];
        self.load_vector_into(pose, ground_acc, gravity, &mut out);
        out
    }

    /// [`Column::load_vector`] into `out` (length `2n`).
    pub fn load_vector_into(&self, pose: &Pose, ground_acc: f64, gravity: f64, out: &mut [f64]) {
        assert_eq!(out.len(), self.n_dofs());
        for (a, o) in out.iter_mut().enumerate() {
            *o = pose.load_entry(a, ground_acc, gravity);
        }
    }

    /// Velocity-dependent generalised forces that the thesis's Eq. 6 leaves out (centripetal
    /// terms of the exact Lagrangian equations), for DOF rates `rates` (length `2n`), written to
    /// `out` (length `2n`). The exact equations are `M φ̈ = q + out`.
    ///
    /// With `φ̈ = 0` every block still accelerates centripetally:
    /// `a(r on block j) = a(P_j) − ω_j² (r − P_j)`, where `P_j` is the active pivot of interface
    /// `j` (a material point of both blocks it joins) and `ω_j` the angular velocity of block `j`.
    /// The generalised force is `−Σ_{j ≥ k_a} m_j (c_j − P_a) × a_c(c_j)`.
    pub fn velocity_load_into(&self, pose: &Pose, phi: &[f64], rates: &[f64], out: &mut [f64]) {
        let n = self.n_interfaces();
        assert_eq!(rates.len(), 2 * n);
        assert_eq!(phi.len(), 2 * n);
        assert_eq!(out.len(), 2 * n);
        // Accelerations of the block centres with zero DOF accelerations.
        let mut centre_acc = vec![[0.0_f64; 2]; n];
        crate::chain::velocity::centre_accelerations(
            phi,
            rates,
            [&pose.right_pivots, &pose.left_pivots],
            &pose.centres,
            n,
            &mut centre_acc,
        );
        for (a, o) in out.iter_mut().enumerate() {
            let k = a % n;
            let p = if a < n {
                pose.right_pivots[k]
            } else {
                pose.left_pivots[k]
            };
            let mut s = 0.0;
            for j in k..n {
                let r = [pose.centres[j][0] - p[0], pose.centres[j][1] - p[1]];
                let ac = centre_acc[j];
                s -= self.blocks[j].mass * (r[0] * ac[1] - r[1] * ac[0]);
            }
            *o = s;
        }
    }
}
