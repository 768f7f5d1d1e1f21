//! The velocity terms of the exact Lagrangian equations (thesis Eq. 6 leaves them out) and the
//! accelerations of the block centres they come from.

use super::ColumnDynamics;
use crate::model::column::Pose;
use crate::model::configuration::Status;

impl ColumnDynamics<'_> {
    /// The sums behind the velocity terms of the exact equations (uses `pose`, `rates`); the
    /// terms are then [`ColumnDynamics::velocity_entry`].
    pub(super) fn velocity_sums(&mut self, statuses: &[Status]) {
        centre_accelerations(&self.pose, statuses, &self.rates, None, &mut self.cacc);
        self.suffix_moments();
    }

    /// Velocity term of DOF `d` after [`ColumnDynamics::velocity_sums`].
    #[inline]
    pub(super) fn velocity_entry(&self, d: usize) -> f64 {
        let n = self.n;
        let (k, p) = if d < n {
            (d, self.pose.right_pivots[d])
        } else {
            (d - n, self.pose.left_pivots[d - n])
        };
        let b = self.sb[k];
        -(self.sa[k] - (p[0] * b[1] - p[1] * b[0]))
    }

    /// Suffix sums `Σ_{j≥k} m_j c_j × a_j` and `Σ_{j≥k} m_j a_j` of `cacc`.
    fn suffix_moments(&mut self) {
        let n = self.n;
        let (masses, centres) = (&self.masses[..n], &self.pose.centres[..n]);
        let (cacc, sa, sb) = (&self.cacc[..n], &mut self.sa[..n], &mut self.sb[..n]);
        let (mut a, mut b) = (0.0, [0.0, 0.0]);
        for j in (0..n).rev() {
            let m = masses[j];
            let c = centres[j];
            let ac = cacc[j];
            a += m * (c[0] * ac[1] - c[1] * ac[0]);
            b = [b[0] + m * ac[0], b[1] + m * ac[1]];
            sa[j] = a;
            sb[j] = b;
        }
    }
}

/// Accelerations of the block centres relative to the ground for DOF rates `rates` and DOF
/// accelerations `acc` (`None`: zero, the centripetal part only). The active pivot of each
/// interface is a material point of both blocks it joins.
pub(crate) fn centre_accelerations(
    pose: &Pose,
    statuses: &[Status],
    rates: &[f64],
    acc: Option<&[f64]>,
    out: &mut [[f64; 2]],
) {
    let n = statuses.len();
    // Slices of length n up front: no bounds check in the loop.
    let (rates_right, rates_left) = (&rates[..n], &rates[n..2 * n]);
    let (right, left) = (&pose.right_pivots[..n], &pose.left_pivots[..n]);
    let (centres, out) = (&pose.centres[..n], &mut out[..n]);
    let acc = acc.map(|a| (&a[..n], &a[n..2 * n]));
    let (mut omega, mut eps) = (0.0_f64, 0.0_f64);
    let mut hinge = [0.0_f64, 0.0];
    let mut hinge_acc = [0.0_f64, 0.0];
    for j in 0..n {
        let p = if statuses[j] == Status::OpenLeft {
            left[j]
        } else {
            right[j]
        };
        let d = [p[0] - hinge[0], p[1] - hinge[1]];
        let acc_p = [
            hinge_acc[0] - eps * d[1] - omega * omega * d[0],
            hinge_acc[1] + eps * d[0] - omega * omega * d[1],
        ];
        omega += rates_right[j] + rates_left[j];
        if let Some((a_right, a_left)) = acc {
            eps += a_right[j] + a_left[j];
        }
        let c = centres[j];
        let r = [c[0] - p[0], c[1] - p[1]];
        out[j] = [
            acc_p[0] - eps * r[1] - omega * omega * r[0],
            acc_p[1] + eps * r[0] - omega * omega * r[1],
        ];
        hinge = p;
        hinge_acc = acc_p;
    }
}
