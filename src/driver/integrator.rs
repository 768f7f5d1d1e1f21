//! One step of the equations of motion of the open DOFs, in reduced coordinates, without
//! allocation (the buffers live in [`Stepper`]).
//!
//! Wilson θ and Newmark are implicit: the acceleration at the collocation point solves
//! `a = f(t, x(a), v(a))`, found by fixed-point iteration. Its contraction factor is about
//! `(θ dt)² |∂f/∂x| / 6 + θ dt |∂f/∂v| / 2` — of the order of `(p dt)²`, tiny at usual steps —
//! so two evaluations are the rule; the iteration stops when the change of the acceleration is
//! below `1e-6` of its size (the remaining error is then far below the truncation error).
//!
//! RK4 and DOP853 are explicit Runge–Kutta methods on the first-order system `(x, v)' = (v, a)`,
//! one loop over a Butcher [`Tableau`]: stage `i` evaluates `a` at `x0 + h Σ a_ij V_j`,
//! `v0 + h Σ a_ij A_j` and at the ground acceleration of its own time `t0 + c_i h`.
//!
//! The equations come through [`Equations`], so any chain the driver runs (SPEC §9) is integrated
//! by the same code.

use super::chain::Equations;
use super::dop853;
use super::Integrator;
use crate::ground::GroundMotion;
use crate::model::configuration::Status;

/// An explicit Runge–Kutta method: nodes `c`, the nonzero `a_ij` of each stage (pairs
/// `(j, a_ij)`, `j < i`), the weights `b_j` over a common `divisor` (the step's increment is
/// `h / divisor · Σ b_j k_j`; RK4's integer weights over 6 give the classical formula's
/// rounding exactly), stage 0 the start of the step.
pub(crate) struct Tableau {
    pub c: &'static [f64],
    pub a: &'static [&'static [(usize, f64)]],
    pub b: &'static [(usize, f64)],
    pub divisor: f64,
}

impl Tableau {
    pub const fn stages(&self) -> usize {
        self.c.len()
    }
}

/// The classical fourth-order Runge–Kutta method.
pub(crate) const RK4: Tableau = Tableau {
    c: &[0.0, 0.5, 0.5, 1.0],
    a: &[&[], &[(0, 0.5)], &[(1, 0.5)], &[(2, 1.0)]],
    b: &[(0, 1.0), (1, 2.0), (2, 2.0), (3, 1.0)],
    divisor: 6.0,
};

/// The eighth-order solution of DOP853 ([`dop853`]).
pub(crate) const DOP853: Tableau = Tableau {
    c: &dop853::C,
    a: &dop853::A,
    b: &dop853::B,
    divisor: 1.0,
};

impl Integrator {
    /// The Butcher tableau of an explicit method.
    fn tableau(self) -> Option<&'static Tableau> {
        match self {
            Integrator::Rk4 => Some(&RK4),
            Integrator::Dop853 => Some(&DOP853),
            Integrator::WilsonTheta { .. } | Integrator::Newmark => None,
        }
    }
}

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
    /// Runge–Kutta stages, `n` per stage: velocities `V_j` and accelerations `A_j` (empty for
    /// the implicit methods).
    sv: Vec<f64>,
    sa: Vec<f64>,
}

impl Stepper {
    pub fn new(n: usize, method: Integrator) -> Stepper {
        let z = || vec![0.0; n];
        let stages = method.tableau().map_or(0, |t| t.stages() * n);
        Stepper {
            x1: z(),
            v1: z(),
            a1: z(),
            xs: z(),
            vs: z(),
            at: z(),
            an: z(),
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
        dynm: &mut impl Equations,
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
                self.explicit(&RK4, dynm, open, statuses, motion, t0, h, ag1, x0, v0, a0)
            }
            Integrator::Dop853 => self.explicit(
                &DOP853, dynm, open, statuses, motion, t0, h, ag1, x0, v0, a0,
            ),
        }
    }

    /// One step of an explicit Runge–Kutta method. Stage 0 is the state at the step start
    /// (FSAL: its derivative is the acceleration the driver keeps); a stage at `c = 1` takes
    /// `ag1`, one at the previous stage's node reuses its ground acceleration.
    #[allow(clippy::too_many_arguments)]
    fn explicit(
        &mut self,
        tableau: &Tableau,
        dynm: &mut impl Equations,
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
        let mut previous = (f64::NAN, f64::NAN);
        for i in 1..tableau.stages() {
            let row = tableau.a[i];
            for r in 0..k {
                let (mut dx, mut dv) = (0.0, 0.0);
                for &(j, a) in row {
                    dx += a * sv[j * k + r];
                    dv += a * sa[j * k + r];
                }
                self.xs[r] = x0[r] + h * dx;
                sv[i * k + r] = v0[r] + h * dv;
            }
            let c = tableau.c[i];
            let ag = if c == 1.0 {
                ag1
            } else if c == previous.0 {
                previous.1
            } else {
                motion.acceleration(t0 + c * h)
            };
            previous = (c, ag);
            ok &= dynm.accel(
                open,
                statuses,
                ag,
                &self.xs[..k],
                &sv[i * k..(i + 1) * k],
                &mut sa[i * k..(i + 1) * k],
            );
        }
        let hb = h / tableau.divisor;
        for r in 0..k {
            let (mut dx, mut dv) = (0.0, 0.0);
            for &(j, b) in tableau.b {
                dx += b * sv[j * k + r];
                dv += b * sa[j * k + r];
            }
            self.x1[r] = x0[r] + hb * dx;
            self.v1[r] = v0[r] + hb * dv;
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
        dynm: &mut impl Equations,
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
        let rigid = if k == 1 {
            dynm.rigid_rotation(open[0])
        } else {
            None
        };
        if let Some((rigid, g)) = rigid {
            // One open DOF turning a rigid part (every single block, and most of the time of a
            // column): the same iteration on scalars, with the rigid rotation's acceleration.
            let (x0, v0, a0) = (x0[0], v0[0], a0[0]);
            let mut at = a0;
            for it in 0..MAX_ITERATIONS {
                let xs = x0 + tau * v0 + tau * tau * (c_old * a0 + c_new * at);
                let an = rigid.accel(xs, ag, g);
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
