//! One step of the equations of motion of the open DOFs, in reduced coordinates, without
//! allocation (the buffers live in [`Stepper`]).
//!
//! Wilson θ and Newmark are implicit: the acceleration at the collocation point solves
//! `a = f(t, x(a), v(a))`, found by fixed-point iteration. Its contraction factor is about
//! `(θ dt)² |∂f/∂x| / 6 + θ dt |∂f/∂v| / 2` — of the order of `(p dt)²`, tiny at usual steps —
//! so two evaluations are the rule; the iteration stops when the change of the acceleration is
//! below `1e-6` of its size (the remaining error is then far below the truncation error).
//!
//! RK4 and DOP853 are explicit Runge–Kutta methods on the first-order system `(x, v)' = (v, a)`:
//! stage `i` evaluates `a` at `x0 + h Σ a_ij V_j`, `v0 + h Σ a_ij A_j` and at the ground
//! acceleration of its own time `t0 + c_i h`.

use super::dop853;
use super::dynamics::Dynamics;
use super::Integrator;
use crate::ground::GroundMotion;
use crate::model::configuration::Status;

const MAX_ITERATIONS: usize = 12;
const ITERATION_TOLERANCE: f64 = 1e-6;

/// Buffers of a step; the result is `x1`, `v1`, `a1` (length `k`, the open DOFs).
pub(crate) struct Stepper {
    pub x1: Vec<f64>,
    pub v1: Vec<f64>,
    pub a1: Vec<f64>,
    xs: Vec<f64>,
    vs: Vec<f64>,
    at: Vec<f64>,
    an: Vec<f64>,
    kv: [Vec<f64>; 3],
    kx: [Vec<f64>; 3],
    /// DOP853 stages, `n` per stage: velocities `V_j` and accelerations `A_j` (empty for the
    /// other methods).
    sv: Vec<f64>,
    sa: Vec<f64>,
}

impl Stepper {
    pub fn new(n: usize, method: Integrator) -> Stepper {
        let z = || vec![0.0; n];
        let stages = if method == Integrator::Dop853 {
            dop853::STAGES * n
        } else {
            0
        };
        Stepper {
            x1: z(),
            v1: z(),
            a1: z(),
            xs: z(),
            vs: z(),
            at: z(),
            an: z(),
            kv: [z(), z(), z()],
            kx: [z(), z(), z()],
            sv: vec![0.0; stages],
            sa: vec![0.0; stages],
        }
    }

    /// Writes the result of the last step (`x1`, `v1`, reduced to the `open` DOFs) into the full
    /// DOF vectors `phi`, `rates`; the closed DOFs are left as they are.
    pub fn write_open(&self, open: &[usize], phi: &mut [f64], rates: &mut [f64]) {
        for (i, &d) in open.iter().enumerate() {
            phi[d] = self.x1[i];
            rates[d] = self.v1[i];
        }
    }

    /// Advances `(x0, v0, a0)` at `t0` by `h`. `ag0`, `ag1` are the ground accelerations at `t0`
    /// and `t0 + h`. `a0` must be the method's acceleration state (for RK4, DOP853 and Newmark
    /// the acceleration of the state; Wilson θ carries its own). Returns `false` if a mass matrix
    /// was not positive definite.
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        method: Integrator,
        dynm: &mut Dynamics,
        open: &[usize],
        statuses: &[Status],
        motion: &dyn GroundMotion,
        t0: f64,
        h: f64,
        ag0: f64,
        ag1: f64,
        x0: &[f64],
        v0: &[f64],
        a0: &[f64],
    ) -> bool {
        let k = open.len();
        match method {
            Integrator::WilsonTheta { theta } => {
                let tau = theta * h;
                let agt = ag0 + theta * (ag1 - ag0);
                let ok = self.collocate(dynm, open, statuses, agt, tau, 1.0 / 6.0, x0, v0, a0);
                for i in 0..k {
                    let a1 = a0[i] + (self.at[i] - a0[i]) / theta;
                    self.a1[i] = a1;
                    self.v1[i] = v0[i] + 0.5 * h * (a0[i] + a1);
                    self.x1[i] = x0[i] + h * v0[i] + h * h / 6.0 * (2.0 * a0[i] + a1);
                }
                ok
            }
            Integrator::Newmark => {
                let ok = self.collocate(dynm, open, statuses, ag1, h, 0.25, x0, v0, a0);
                for i in 0..k {
                    let a1 = self.at[i];
                    self.a1[i] = a1;
                    self.v1[i] = v0[i] + 0.5 * h * (a0[i] + a1);
                    self.x1[i] = x0[i] + h * v0[i] + h * h * 0.25 * (a0[i] + a1);
                }
                ok
            }
            Integrator::Rk4 => {
                let agm = motion.acceleration(t0 + 0.5 * h);
                let mut ok = true;
                // Stage 2 and 3 at the midpoint, stage 4 at the end; stage 1 is (v0, a0).
                for i in 0..k {
                    self.xs[i] = x0[i] + 0.5 * h * v0[i];
                    self.vs[i] = v0[i] + 0.5 * h * a0[i];
                }
                ok &= dynm.accel(
                    open,
                    statuses,
                    agm,
                    &self.xs[..k],
                    &self.vs[..k],
                    &mut self.kv[0][..k],
                );
                self.kx[0][..k].copy_from_slice(&self.vs[..k]);
                for i in 0..k {
                    self.xs[i] = x0[i] + 0.5 * h * self.kx[0][i];
                    self.vs[i] = v0[i] + 0.5 * h * self.kv[0][i];
                }
                ok &= dynm.accel(
                    open,
                    statuses,
                    agm,
                    &self.xs[..k],
                    &self.vs[..k],
                    &mut self.kv[1][..k],
                );
                self.kx[1][..k].copy_from_slice(&self.vs[..k]);
                for i in 0..k {
                    self.xs[i] = x0[i] + h * self.kx[1][i];
                    self.vs[i] = v0[i] + h * self.kv[1][i];
                }
                ok &= dynm.accel(
                    open,
                    statuses,
                    ag1,
                    &self.xs[..k],
                    &self.vs[..k],
                    &mut self.kv[2][..k],
                );
                self.kx[2][..k].copy_from_slice(&self.vs[..k]);
                for i in 0..k {
                    self.x1[i] = x0[i]
                        + h / 6.0
                            * (v0[i] + 2.0 * self.kx[0][i] + 2.0 * self.kx[1][i] + self.kx[2][i]);
                    self.v1[i] = v0[i]
                        + h / 6.0
                            * (a0[i] + 2.0 * self.kv[0][i] + 2.0 * self.kv[1][i] + self.kv[2][i]);
                }
                ok &= dynm.accel(
                    open,
                    statuses,
                    ag1,
                    &self.x1[..k],
                    &self.v1[..k],
                    &mut self.a1[..k],
                );
                ok
            }
            Integrator::Dop853 => self.dop853(dynm, open, statuses, motion, t0, h, ag1, x0, v0, a0),
        }
    }

    /// One step of the eighth-order Dormand–Prince method ([`dop853`]).
    #[allow(clippy::too_many_arguments)]
    fn dop853(
        &mut self,
        dynm: &mut Dynamics,
        open: &[usize],
        statuses: &[Status],
        motion: &dyn GroundMotion,
        t0: f64,
        h: f64,
        ag1: f64,
        x0: &[f64],
        v0: &[f64],
        a0: &[f64],
    ) -> bool {
        let k = open.len();
        let (sv, sa) = (&mut self.sv, &mut self.sa);
        sv[..k].copy_from_slice(v0);
        sa[..k].copy_from_slice(a0);
        let mut ok = true;
        for i in 1..dop853::STAGES {
            let row = dop853::A[i];
            for r in 0..k {
                let (mut dx, mut dv) = (0.0, 0.0);
                for &(j, a) in row {
                    dx += a * sv[j * k + r];
                    dv += a * sa[j * k + r];
                }
                self.xs[r] = x0[r] + h * dx;
                sv[i * k + r] = v0[r] + h * dv;
            }
            let c = dop853::C[i];
            let ag = if c == 1.0 {
                ag1
            } else {
                motion.acceleration(t0 + c * h)
            };
            ok &= dynm.accel(
                open,
                statuses,
                ag,
                &self.xs[..k],
                &sv[i * k..(i + 1) * k],
                &mut sa[i * k..(i + 1) * k],
            );
        }
        for r in 0..k {
            let (mut dx, mut dv) = (0.0, 0.0);
            for &(j, b) in &dop853::B {
                dx += b * sv[j * k + r];
                dv += b * sa[j * k + r];
            }
            self.x1[r] = x0[r] + h * dx;
            self.v1[r] = v0[r] + h * dv;
        }
        ok &= dynm.accel(
            open,
            statuses,
            ag1,
            &self.x1[..k],
            &self.v1[..k],
            &mut self.a1[..k],
        );
        ok
    }

    /// Solves `a = f(ag, x0 + τ v0 + τ² ((1 − 2β') a0 ... ))` at the collocation point `τ`:
    /// `x = x0 + τ v0 + τ² (c a0 + c' a)` with `(c, c') = (2/6, 1/6)` (Wilson, linear
    /// acceleration) or `(1/4, 1/4)` (Newmark), `v = v0 + τ/2 (a0 + a)`. Result in `at`.
    #[allow(clippy::too_many_arguments)]
    fn collocate(
        &mut self,
        dynm: &mut Dynamics,
        open: &[usize],
        statuses: &[Status],
        ag: f64,
        tau: f64,
        c_new: f64,
        x0: &[f64],
        v0: &[f64],
        a0: &[f64],
    ) -> bool {
        let k = open.len();
        let c_old = if c_new == 0.25 { 0.25 } else { 2.0 / 6.0 };
        if k == 1 {
            // One open DOF (every single block, and most of the time of a column): the same
            // iteration on scalars, with the rigid-rotation acceleration of `Dynamics::accel`.
            let rigid = dynm.rigid[open[0]];
            let (x0, v0, a0) = (x0[0], v0[0], a0[0]);
            let mut at = a0;
            for it in 0..MAX_ITERATIONS {
                let xs = x0 + tau * v0 + tau * tau * (c_old * a0 + c_new * at);
                let an = rigid.accel(xs, ag, dynm.g);
                let diff = 0.0_f64.max((an - at).abs());
                let scale = 0.0_f64.max(an.abs());
                at = an;
                if it >= 1 && diff <= ITERATION_TOLERANCE * scale {
                    break;
                }
            }
            self.at[0] = at;
            return true;
        }
        self.at[..k].copy_from_slice(&a0[..k]);
        let mut ok = true;
        for it in 0..MAX_ITERATIONS {
            for i in 0..k {
                self.xs[i] = x0[i] + tau * v0[i] + tau * tau * (c_old * a0[i] + c_new * self.at[i]);
                self.vs[i] = v0[i] + 0.5 * tau * (a0[i] + self.at[i]);
            }
            ok &= dynm.accel(
                open,
                statuses,
                ag,
                &self.xs[..k],
                &self.vs[..k],
                &mut self.an[..k],
            );
            let (mut diff, mut scale) = (0.0_f64, 0.0_f64);
            for i in 0..k {
                diff = diff.max((self.an[i] - self.at[i]).abs());
                scale = scale.max(self.an[i].abs());
            }
            self.at[..k].copy_from_slice(&self.an[..k]);
            if it >= 1 && diff <= ITERATION_TOLERANCE * scale {
                break;
            }
        }
        ok
    }
}
