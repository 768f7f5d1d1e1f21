//! The rest shortcut of the Moreau–Jean scheme ([`super::moreau`]): a column closed, sticking and
//! at rest takes a step without a contact problem when the impulses that hold it are admissible.

use super::friction::Slip;
use super::moreau::Stepper;

impl Stepper {
    pub(super) fn at_rest(&self) -> bool {
        self.v.iter().all(|&x| x == 0.0)
            && self
                .statuses
                .iter()
                .all(|s| s.closed == [true, true] && s.slip == Slip::Stick)
            && self.geometry.iter().all(|g| {
                g.ends[0].gap.abs() <= self.contact_gap && g.ends[1].gap.abs() <= self.contact_gap
            })
    }

    /// The rest shortcut: a column closed, sticking and at rest stays so if the impulses that
    /// hold it (statics of the part above each joint, top down) are admissible. This is the
    /// solution of the step's contact problem then (the Jacobian of a closed, sticking column is
    /// square and invertible, so the impulses are unique). Returns whether it applied.
    pub(super) fn rest_step(&mut self, h: f64, a_theta: f64) -> bool {
        let n = self.drums.len();
        let g = self.options.gravity;
        // Suffix sums of the loads' impulse on the part above each joint and of its moment.
        let (mut fx, mut fy) = (0.0, 0.0);
        let (mut sx, mut sy) = (0.0, 0.0); // Σ m c
        for k in (0..n).rev() {
            let m = self.drums.mass(k);
            fx += m * a_theta * h; // −h f_x = h m a
            fy += m * g * h;
            sx += m * self.q[3 * k];
            sy += m * self.q[3 * k + 1];
            let geo = &self.geometry[k];
            let (rr, rl) = (geo.ends[0].point, geo.ends[1].point);
            let nrm = geo.ends[0].normal;
            let t = [nrm[1], -nrm[0]];
            // The contact impulse F = (fx, fy) and moment about the left end: the loads' impulse
            // is −h Σ m (a, g) applied at the centres, so the contact's moment about r_L must be
            // −Σ (c − r_L) × (−h m (a, g)) = Σ (c − r_L) × (h m (a, g)).
            let mass_above = fy / (g * h);
            let cx = sx - mass_above * rl[0];
            let cy = sy - mass_above * rl[1];
            // Σ m (c − r_L) × (a, g) h = h (cx g − cy a) with cx, cy mass-weighted.
            let mo = h * (cx * g - cy * a_theta);
            let fn_ = fx * nrm[0] + fy * nrm[1];
            let ft = fx * t[0] + fy * t[1];
            let d = [rr[0] - rl[0], rr[1] - rl[1]];
            let dn = d[0] * nrm[1] - d[1] * nrm[0];
            let dt = d[0] * t[1] - d[1] * t[0];
            if dn.abs() <= 0.0 {
                return false;
            }
            let pr = (mo - 0.5 * ft * dt) / dn;
            let pl = fn_ - pr;
            if pr < 0.0 || pl < 0.0 || ft.abs() > self.mu[k] * fn_ {
                return false;
            }
        }
        self.t += h;
        self.counters.rest_steps += 1;
        true
    }
}
