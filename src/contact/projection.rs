//! The projection of the positions after a step (Acary 2013, the projected Moreau–Jean scheme):
//! ends that carried an impulse back onto the face they touch, penetrating ends out of it, in the
//! metric `M`, one linearised step solved by the same contact problem (frictionless, gaps in place
//! of velocities); velocities unchanged. Its work against the loads is booked: it is one of the
//! scheme's energy errors.

use super::friction::{JointContacts, JointStatus};
use super::moreau::{StepError, Stepper};

impl Stepper {
    /// Geometry at `q` (unless `fresh`: already computed), then, if some carried end is off its
    /// face or some end penetrates, the projection of `q` in the metric `M` (one linearised
    /// step). `a_g` is the ground acceleration for the work of the loads on the displacement.
    pub(super) fn project(&mut self, a_g: f64, fresh: bool) -> Result<(), StepError> {
        let n = self.drums.len();
        if !fresh {
            self.update_geometry();
        }
        let mut needed = false;
        for k in 0..n {
            let geo = &self.geometry[k];
            if geo.overlap <= 0.0 {
                return Err(StepError::SlidOff(k));
            }
            for c in 0..2 {
                let g = geo.ends[c].gap;
                if (self.carried[k][c] && g.abs() > self.projection_gap) || g < -self.projection_gap
                {
                    needed = true;
                }
            }
        }
        if !needed {
            return Ok(());
        }
        for k in 0..n {
            let geo = &self.geometry[k];
            let mut jc = JointContacts {
                active: [false; 2],
                bilateral: [false; 2],
                rows: [geo.ends[0].rows, geo.ends[1].rows],
                mu: 0.0,
            };
            for c in 0..2 {
                let g = geo.ends[c].gap;
                if self.carried[k][c] {
                    jc.active[c] = true;
                    jc.bilateral[c] = true;
                } else if g < 0.0 {
                    jc.active[c] = true;
                }
            }
            self.contacts[k] = jc;
            self.proj_statuses[k] = JointStatus {
                closed: jc.active,
                ..JointStatus::default()
            };
        }
        self.dq.iter_mut().for_each(|x| *x = 0.0);
        self.projection.set(&self.contacts, &self.dq);
        for k in 0..n {
            let geo = &self.geometry[k];
            let gaps = [
                if self.contacts[k].active[0] {
                    geo.ends[0].gap
                } else {
                    0.0
                },
                if self.contacts[k].active[1] {
                    geo.ends[1].gap
                } else {
                    0.0
                },
            ];
            self.projection.set_offsets(k, [gaps[0], gaps[1], 0.0]);
        }
        let report = self.projection.solve(&mut self.proj_statuses)?;
        self.counters.iterations += report.iterations as u64;
        self.counters.fallbacks += report.fallback as u64;
        self.counters.inexact += report.inexact as u64;
        self.counters.projections += 1;
        self.projection.apply(&mut self.dq);
        let mut work = 0.0;
        let mut ground = 0.0;
        for j in 0..n {
            let f = self.loads(a_g, j);
            for i in 0..3 {
                self.q[3 * j + i] += self.dq[3 * j + i];
                work += f[i] * self.dq[3 * j + i];
            }
            ground += f[0] * self.dq[3 * j];
        }
        self.energy.ground_work += ground;
        self.energy.projection += work;

        self.update_geometry();
        Ok(())
    }
}
