//! The column as the driver's chain ([`Equations`], [`ChainDynamics`]): equations of motion of a
//! configuration and the per-step checks, without allocation, and the crate's two models.
//!
//! General path: the pose of the whole column ([`Column::pose_into`]), `M_FF` of the open DOFs
//! ([`Pose::mass_entry`]), `q_F` ([`Pose::load_entry`], plus the exact velocity terms on
//! request) and a small Cholesky solve. Fast paths, exact and not approximations:
//! - one open DOF: the part above rotates rigidly about a pivot fixed to the ground (all other
//!   interfaces are closed, so straight), `M_aa` is its constant moment of inertia about the
//!   pivot and `q_a(θ) = S0 (a_g r_y − g r_x)` with `r = R(θ)(G − P)`; the velocity terms vanish
//!   (the centripetal force passes through the fixed pivot);
//! - everything closed: the column is straight, `q = a_g Qa − g Qg` with constants.
//!
//! Columns of two and three blocks take the general path on fixed-size arrays, fused and
//! monomorphised (`small.rs`), bit for bit the same operations.

mod small;
#[cfg(test)]
mod small_tests;
mod velocity;

use super::chain::{ChainDynamics, Check, Equations, Rigid};
use super::events::settle::lock_dof;
use crate::error::RockingError;
use crate::model::cholesky;
use crate::model::column::{Column, Pose};
use crate::model::cone::{ModelOptions, ModelReport};
use crate::model::configuration::Status;
use crate::model::impact::kinetic_energy;
use crate::model::opening::{reaction_margins, AllClosed, Configuration};
use crate::{impact_model, opening_model};
use small::Small;
use velocity::centre_accelerations;

/// The general path, or the fused one of a column of two or three blocks (`small.rs`).
enum Kernel {
    General,
    Two(Small<2>),
    Three(Small<3>),
}

pub(crate) struct ColumnDynamics<'a> {
    pub col: &'a Column,
    pub n: usize,
    pub g: f64,
    pub exact: bool,
    pub tol: f64,
    pub friction: f64,
    pub pose: Pose,
    pub rigid: Vec<Rigid>,
    straight_qa: Vec<f64>,
    straight_qg: Vec<f64>,
    straight_isq: Vec<f64>,
    centre_y0: Vec<f64>,
    masses: Vec<f64>,
    /// Scratch full DOF vectors for the general path (zero outside the open DOFs).
    phi: Vec<f64>,
    rates: Vec<f64>,
    mk: Vec<f64>,
    rhs: Vec<f64>,
    diag: Vec<f64>,
    cacc: Vec<[f64; 2]>,
    sa: Vec<f64>,
    sb: Vec<[f64; 2]>,
    q: Vec<f64>,
    isq: Vec<f64>,
    /// Accelerations of the last check (full, `2n`).
    pub acc_full: Vec<f64>,
    /// Opening margins of the last check (full, `2n`; `-inf` on DOFs that are no generators).
    pub margin: Vec<f64>,
    /// Block rotations of the last check.
    pub block_angles: Vec<f64>,
    /// The full `2n × 2n` mass matrix and load vector of the last [`ColumnDynamics::assemble`], the
    /// models' input.
    pub system_mass: Vec<f64>,
    pub system_load: Vec<f64>,
    kernel: Kernel,
}

impl<'a> ColumnDynamics<'a> {
    pub fn new(
        col: &'a Column,
        gravity: f64,
        exact: bool,
        tol: f64,
        friction: f64,
    ) -> ColumnDynamics<'a> {
        let n = col.n_interfaces();
        let m = 2 * n;
        let pose = col.pose(&vec![0.0; m]);
        let mut rigid = Vec::with_capacity(m);
        let mut qa = Vec::with_capacity(m);
        let mut qg = Vec::with_capacity(m);
        let mut isq = Vec::with_capacity(m);
        for a in 0..m {
            let k = a % n;
            let p = if a < n {
                pose.right_pivots[k]
            } else {
                pose.left_pivots[k]
            };
            let (s0, gc) = pose.mass_above(k);
            let ip = pose.mass_entry(a, a);
            rigid.push(Rigid {
                s0,
                dx: gc[0] - p[0],
                dy: gc[1] - p[1],
                inv_ip: 1.0 / ip,
            });
            qa.push(pose.load_entry(a, 1.0, 0.0));
            qg.push(-pose.load_entry(a, 0.0, 1.0));
            isq.push(1.0 / ip.sqrt());
        }
        let centre_y0: Vec<f64> = pose.centres.iter().map(|c| c[1]).collect();
        let s0: Vec<f64> = rigid[..n].iter().map(|r| r.s0).collect();
        let y0 = &centre_y0;
        let kernel = match n {
            2 => Kernel::Two(Small::new(col, gravity, exact, tol, friction, &s0, y0)),
            3 => Kernel::Three(Small::new(col, gravity, exact, tol, friction, &s0, y0)),
            _ => Kernel::General,
        };
        ColumnDynamics {
            col,
            n,
            g: gravity,
            exact,
            tol,
            friction,
            masses: col.blocks().iter().map(|b| b.mass).collect(),
            pose,
            rigid,
            straight_qa: qa,
            straight_qg: qg,
            straight_isq: isq,
            centre_y0,
            phi: vec![0.0; m],
            rates: vec![0.0; m],
            mk: vec![0.0; n * n],
            rhs: vec![0.0; n],
            diag: vec![0.0; m],
            cacc: vec![[0.0; 2]; n],
            sa: vec![0.0; n],
            sb: vec![[0.0; 2]; n],
            q: vec![0.0; m],
            isq: vec![0.0; m],
            acc_full: vec![0.0; m],
            margin: vec![f64::NEG_INFINITY; m],
            block_angles: vec![0.0; n],
            system_mass: vec![0.0; m * m],
            system_load: vec![0.0; m],
            kernel,
        }
    }

    /// Solves `M_FF a_F = q_F` on the current `pose`; the result is in `rhs[..k]`, and `q_F`
    /// and the diagonal of `M_FF` are left in `q`, `diag` (full DOF vectors) for the check.
    fn solve_open(&mut self, open: &[usize], statuses: &[Status], ag: f64) -> bool {
        let k = open.len();
        if self.exact {
            self.velocity_sums(statuses);
        }
        let (pose, mk, diag) = (&self.pose, &mut self.mk[..k * k], &mut self.diag);
        for (r, &a) in open.iter().enumerate() {
            for (c, &b) in open.iter().enumerate().skip(r) {
                let v = pose.mass_entry(a, b);
                mk[r * k + c] = v;
                mk[c * k + r] = v;
            }
            diag[a] = mk[r * k + r];
        }
        for (r, &a) in open.iter().enumerate() {
            let mut q = self.pose.load_entry(a, ag, self.g);
            if self.exact {
                q += self.velocity_entry(a);
            }
            self.rhs[r] = q;
            self.q[a] = q;
        }
        let mk = &mut self.mk[..k * k];
        if !cholesky::factor(mk, k) {
            return false;
        }
        cholesky::solve(mk, k, &mut self.rhs[..k]);
        true
    }

    /// Tension and friction tests on interface `k` with shear `v` and normal force `nn`.
    fn classify_force(&self, k: usize, v: f64, nn: f64, out: &mut Check) {
        let scale = 1e-9 * self.rigid[k].s0 * self.g;
        if nn < -scale {
            out.tension.get_or_insert(k);
        } else if v.abs() > self.friction * nn.max(0.0) + scale {
            out.sliding.get_or_insert(k);
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn general_check(
        &mut self,
        open: &[usize],
        statuses: &[Status],
        ag: f64,
        phi: &[f64],
        rates: &[f64],
        forces: bool,
        out: &mut Check,
    ) {
        let n = self.n;
        let g = self.g;
        self.phi.copy_from_slice(phi);
        self.rates.copy_from_slice(rates);
        self.col.pose_into(&self.phi, &mut self.pose);
        out.ok = self.solve_open(open, statuses, ag);
        self.acc_full.iter_mut().for_each(|v| *v = 0.0);
        for (i, &d) in open.iter().enumerate() {
            self.acc_full[d] = self.rhs[i];
        }
        // Loads and Jacobi scales of every generator (closed: both corners; open: its DOF, whose
        // load and `M_dd` `solve_open` computed), then the reaction test.
        for d in 0..2 * n {
            if !statuses.generator(d) {
                continue;
            }
            if statuses[if d < n { d } else { d - n }] == Status::Closed {
                let mut q = self.pose.load_entry(d, ag, g);
                if self.exact {
                    q += self.velocity_entry(d);
                }
                self.q[d] = q;
                self.diag[d] = self.pose.mass_entry(d, d);
            }
            self.isq[d] = 1.0 / self.diag[d].sqrt();
        }
        let pose = &self.pose;
        out.max_margin = reaction_margins(
            statuses,
            open,
            &self.q,
            &self.isq,
            &self.acc_full,
            |d, f| pose.mass_entry(d, f),
            self.tol,
            &mut self.margin,
        );
        let mut power = 0.0;
        for &f in open {
            power += self.pose.load_entry(f, ag, 0.0) * rates[f];
        }
        out.power = power;
        self.block_angles.copy_from_slice(&self.pose.block_angles);
        // Tipping of the part above each open interface, in the frame of the block below.
        for k in 0..n {
            let sigma = statuses[k].sign();
            if sigma == 0.0 {
                continue;
            }
            let p = if sigma < 0.0 {
                self.pose.right_pivots[k]
            } else {
                self.pose.left_pivots[k]
            };
            let (_, c) = self.pose.mass_above(k);
            let (s, co) = self.below_sin_cos(k);
            let along = (c[0] - p[0]) * co + (c[1] - p[1]) * s;
            if -sigma * along > 0.0 {
                out.tipped = Some(k);
                break;
            }
        }
        if let Some(j) = self
            .pose
            .block_angles
            .iter()
            .position(|a| a.abs() >= 0.5 * std::f64::consts::PI)
        {
            let k = (0..=j)
                .max_by(|&a, &b| {
                    let ra = (phi[a] + phi[n + a]).abs();
                    let rb = (phi[b] + phi[n + b]).abs();
                    ra.total_cmp(&rb)
                })
                .unwrap_or(0);
            out.fallen = Some(k);
        }
        if forces {
            centre_accelerations(
                &self.pose,
                statuses,
                rates,
                Some(&self.acc_full),
                &mut self.cacc,
            );
            let (mut fx, mut fy) = (0.0, 0.0);
            for k in (0..n).rev() {
                let m = self.masses[k];
                fx += m * (self.cacc[k][0] + ag);
                fy += m * (self.cacc[k][1] + g);
                let (s, c) = self.below_sin_cos(k);
                let v = fx * c + fy * s;
                let nn = -fx * s + fy * c;
                let scale = 1e-9 * self.rigid[k].s0 * g;
                if nn < -scale {
                    out.tension = Some(k);
                } else if v.abs() > self.friction * nn.max(0.0) + scale {
                    out.sliding = Some(k);
                }
            }
        }
    }

    /// Full `2n × 2n` mass matrix and load vector (with the velocity terms when exact) at a
    /// state, for the models.
    pub fn full_system(
        &mut self,
        statuses: &[Status],
        ag: f64,
        phi: &[f64],
        rates: &[f64],
        mass: &mut [f64],
        load: &mut [f64],
    ) {
        self.col.pose_into(phi, &mut self.pose);
        self.col.mass_matrix_into(&self.pose, mass);
        self.col.load_vector_into(&self.pose, ag, self.g, load);
        if self.exact {
            self.rates.copy_from_slice(rates);
            self.velocity_sums(statuses);
            for (d, l) in load.iter_mut().enumerate() {
                *l += self.velocity_entry(d);
            }
        }
    }

    /// `sin_cos` of the rotation of the block below interface `k` (the ground: 0), bit for bit.
    #[inline]
    fn below_sin_cos(&self, k: usize) -> (f64, f64) {
        if k == 0 {
            (0.0, 1.0)
        } else {
            self.pose.block_sin_cos[k - 1]
        }
    }
}

impl Equations for ColumnDynamics<'_> {
    #[inline]
    fn accel(
        &mut self,
        open: &[usize],
        statuses: &[Status],
        ag: f64,
        x: &[f64],
        v: &[f64],
        out: &mut [f64],
    ) -> bool {
        match open.len() {
            0 => true,
            1 => {
                out[0] = self.rigid[open[0]].accel(x[0], ag, self.g);
                true
            }
            k => {
                for i in 0..k {
                    self.phi[open[i]] = x[i];
                    self.rates[open[i]] = v[i];
                }
                let (phi, rates) = (&self.phi, &self.rates);
                match &self.kernel {
                    Kernel::Two(s) => s.accel(open, statuses, ag, phi, rates, out),
                    Kernel::Three(s) => s.accel(open, statuses, ag, phi, rates, out),
                    Kernel::General => {
                        self.col.pose_into(&self.phi, &mut self.pose);
                        let ok = self.solve_open(open, statuses, ag);
                        out[..k].copy_from_slice(&self.rhs[..k]);
                        ok
                    }
                }
            }
        }
    }

    /// Every single open DOF of a column turns the part above about a pivot fixed to the ground.
    #[inline]
    fn rigid_rotation(&self, dof: usize) -> Option<(Rigid, f64)> {
        Some((self.rigid[dof], self.g))
    }
}

impl ChainDynamics for ColumnDynamics<'_> {
    fn n_joints(&self) -> usize {
        self.n
    }

    /// Sets the scratch vectors to zero.
    fn reconfigured(&mut self) {
        self.phi.iter_mut().for_each(|v| *v = 0.0);
        self.rates.iter_mut().for_each(|v| *v = 0.0);
    }

    #[inline]
    fn check(
        &mut self,
        open: &[usize],
        statuses: &[Status],
        ag: f64,
        phi: &[f64],
        rates: &[f64],
        forces: bool,
    ) -> Check {
        let n = self.n;
        let g = self.g;
        let mut out = Check {
            max_margin: f64::NEG_INFINITY,
            ok: true,
            ..Check::default()
        };
        match open.len() {
            0 => {
                // Straight column moving with the ground: constant `M`, `q = a_g Qa − g Qg`.
                for d in 0..2 * n {
                    self.q[d] = ag * self.straight_qa[d] - g * self.straight_qg[d];
                    self.acc_full[d] = 0.0;
                }
                out.max_margin = reaction_margins(
                    &AllClosed(n),
                    &[],
                    &self.q,
                    &self.straight_isq,
                    &self.acc_full,
                    |_, _| 0.0,
                    self.tol,
                    &mut self.margin,
                );
                self.block_angles.iter_mut().for_each(|v| *v = 0.0);
                // N = S0 g, V = S0 a_g on every interface: the lowest decides.
                if forces && ag.abs() > self.friction * g {
                    out.sliding = Some(0);
                }
                out
            }
            1 if n == 1 => {
                let d = open[0];
                let r = self.rigid[d];
                let theta = phi[d];
                let omega = rates[d];
                let (rx, ry) = r.arm(theta);
                let eps = r.s0 * (ag * ry - g * rx) * r.inv_ip;
                self.acc_full[d] = eps;
                self.margin[0] = f64::NEG_INFINITY;
                self.margin[1] = f64::NEG_INFINITY;
                self.block_angles[0] = theta;
                out.power = ag * r.s0 * ry * omega;
                let sigma = statuses[0].sign();
                if -sigma * rx > 0.0 {
                    out.tipped = Some(0);
                }
                if theta.abs() >= 0.5 * std::f64::consts::PI {
                    out.fallen = Some(0);
                }
                if forces {
                    // c̈ = ε ẑ × r − ω² r; F = S0 (c̈ + (a_g, g)).
                    let fx = r.s0 * (-eps * ry - omega * omega * rx + ag);
                    let fy = r.s0 * (eps * rx - omega * omega * ry + g);
                    self.classify_force(0, fx, fy, &mut out);
                }
                out
            }
            _ => {
                let scratch = (&mut self.phi[..], &mut self.rates[..]);
                let (acc, margin, angles) =
                    (&mut self.acc_full, &mut self.margin, &mut self.block_angles);
                match &self.kernel {
                    Kernel::Two(s) => s.check(
                        open, statuses, ag, phi, rates, forces, scratch, acc, margin, angles,
                        &mut out,
                    ),
                    Kernel::Three(s) => s.check(
                        open, statuses, ag, phi, rates, forces, scratch, acc, margin, angles,
                        &mut out,
                    ),
                    Kernel::General => {
                        self.general_check(open, statuses, ag, phi, rates, forces, &mut out)
                    }
                }
                out
            }
        }
    }

    fn accelerations(&self) -> &[f64] {
        &self.acc_full
    }

    fn margins(&self) -> &[f64] {
        &self.margin
    }

    fn block_angles(&self) -> &[f64] {
        &self.block_angles
    }

    fn energy(&mut self, open: &[usize], phi: &[f64], rates: &[f64]) -> (f64, f64) {
        match &self.kernel {
            Kernel::Two(s) => return s.energy(open, phi, rates),
            Kernel::Three(s) => return s.energy(open, phi, rates),
            Kernel::General => {}
        }
        self.col.pose_into(phi, &mut self.pose);
        let mut t = 0.0;
        for &a in open {
            for &b in open {
                t += rates[a] * self.pose.mass_entry(a, b) * rates[b];
            }
        }
        let v: f64 = (0..self.n)
            .map(|j| self.masses[j] * self.g * (self.pose.centres[j][1] - self.centre_y0[j]))
            .sum();
        (0.5 * t, v)
    }

    fn power(&mut self, open: &[usize], ag: f64, phi: &[f64], rates: &[f64]) -> f64 {
        if open.is_empty() || ag == 0.0 {
            return 0.0;
        }
        self.col.pose_into(phi, &mut self.pose);
        open.iter()
            .map(|&f| self.pose.load_entry(f, ag, 0.0) * rates[f])
            .sum()
    }

    /// Over the rigid rotations of the straight column.
    fn tipping_energy(&self) -> f64 {
        self.rigid
            .iter()
            .map(|r| r.s0 * self.g * ((r.dx * r.dx + r.dy * r.dy).sqrt() - r.dy))
            .fold(f64::INFINITY, f64::min)
    }

    /// The largest `m R / √(2 I_P)` over the rigid rotations of the straight column.
    fn energy_growth_bound(&self) -> f64 {
        self.rigid
            .iter()
            .map(|r| r.s0 * (r.dx * r.dx + r.dy * r.dy).sqrt() * (0.5 * r.inv_ip).sqrt())
            .fold(0.0, f64::max)
    }

    fn column_growth_bound(&self) -> f64 {
        (0.5 * self.masses.iter().sum::<f64>()).sqrt()
    }

    fn barrier_certified(&self) -> bool {
        super::barrier::column_is_certified(self.col)
    }

    fn monolith(&self) -> Option<super::events::monolith::Monolith> {
        (self.n >= 2 && !self.exact)
            .then(|| super::events::monolith::Monolith::of_column(self.col, self.g))
    }

    fn assemble(&mut self, statuses: &[Status], ag: f64, phi: &[f64], rates: &[f64]) {
        let mut mass = std::mem::take(&mut self.system_mass);
        let mut load = std::mem::take(&mut self.system_load);
        self.full_system(statuses, ag, phi, rates, &mut mass, &mut load);
        self.system_mass = mass;
        self.system_load = load;
    }

    fn kinetic_energy(&self, rates: &[f64]) -> f64 {
        kinetic_energy(&self.system_mass, rates)
    }

    fn opening(
        &self,
        statuses: &mut [Status],
        options: &ModelOptions,
    ) -> Result<ModelReport, RockingError> {
        let mut acceleration = vec![0.0; self.system_load.len()];
        opening_model(
            &self.system_mass,
            &self.system_load,
            statuses,
            &mut acceleration,
            options,
        )
    }

    fn impact(
        &self,
        statuses: &mut [Status],
        rates: &mut [f64],
        closing: &[usize],
        options: &ModelOptions,
    ) -> Result<ModelReport, RockingError> {
        debug_assert_eq!(closing.len(), 1, "a column closes one interface at a time");
        impact_model(&self.system_mass, statuses, rates, closing[0], options)
    }

    fn lock(&self, open: &[usize], dof: usize, rates: &mut [f64]) {
        lock_dof(&self.system_mass, 2 * self.n, open, dof, rates);
    }
}
