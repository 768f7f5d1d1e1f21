//! Columns of two and three blocks ([`Small`]): the general path of `dynamics.rs` — the pose,
//! `M_FF` and `q_F` of the open DOFs with the exact velocity terms, the Cholesky solve and the
//! end-of-step check — fused on fixed-size arrays, without the bounds checks, the branches on a
//! DOF's side, the `Vec` indirections and the copies of the general path. Every value is computed
//! by the same operations on the same operands in the same order as there
//! ([`crate::model::column::Column::pose_into`], `Pose::mass_entry`, `Pose::load_entry`,
//! [`super::velocity::centre_accelerations`], `suffix_moments`,
//! [`crate::model::opening::reaction_margins`]), so every answer is the same bits (test
//! `small_columns_are_the_general_path_bit_for_bit`); the constants of the column (the suffix
//! sums of the masses and inertias, the centres' heights) are those sums, computed once.

use crate::driver::chain::Check;
use crate::model::cholesky;
use crate::model::column::{BlockMap, Column};
use crate::model::configuration::Status;

/// Most DOFs of a small column (`2N`, `N ≤ 4`).
const DOFS: usize = 8;
/// Most entries of its `M_FF` (at most one open DOF per interface: `N²`).
const OPEN_SQ: usize = 16;

/// The constants of a column of `N` blocks.
#[derive(Clone, Copy, Debug)]
pub(super) struct Small<const N: usize> {
    /// Half contact width and height of each interface in the straight column.
    b: [f64; N],
    y: [f64; N],
    /// Height of each block's centre in the straight column, `y + h / 2`.
    yc: [f64; N],
    mass: [f64; N],
    /// Mass and own moments of inertia of the part above each interface (suffix sums).
    s0: [f64; N],
    si: [f64; N],
    /// `1e-9 S0 g` of each interface (the contact-force tests).
    scale: [f64; N],
    /// Height of each block's centre in the straight column as the general pose gives it.
    centre_y0: [f64; N],
    g: f64,
    exact: bool,
    tol: f64,
    friction: f64,
}

/// The pose of a small column ([`crate::model::column::Pose`] with the sums above each
/// interface).
#[derive(Clone, Copy)]
struct Pose<const N: usize> {
    right: [[f64; 2]; N],
    left: [[f64; 2]; N],
    centres: [[f64; 2]; N],
    angles: [f64; N],
    sin_cos: [(f64, f64); N],
    moment: [[f64; 2]; N],
    centre: [[f64; 2]; N],
    spread: [f64; N],
}

impl<const N: usize> Pose<N> {
    /// Interface and pivot of DOF `a`.
    #[inline(always)]
    fn side(&self, a: usize) -> (usize, [f64; 2]) {
        if a < N {
            (a, self.right[a])
        } else {
            (a - N, self.left[a - N])
        }
    }

    /// `sin_cos` of the rotation of the block below interface `k` (the ground: 0).
    #[inline(always)]
    fn below_sin_cos(&self, k: usize) -> (f64, f64) {
        if k == 0 {
            (0.0, 1.0)
        } else {
            self.sin_cos[k - 1]
        }
    }
}

/// The sums behind the velocity terms (`ColumnDynamics::velocity_sums`).
type Velocity<const N: usize> = ([f64; N], [[f64; 2]; N]);

/// The arguments of [`Small::accel`].
type AccelArgs<'a> = (
    &'a [usize],
    &'a [Status],
    f64,
    &'a [f64],
    &'a [f64],
    &'a mut [f64],
);

/// The arguments of [`Small::check`].
type CheckArgs<'a> = (
    &'a [usize],
    &'a [Status],
    f64,
    &'a [f64],
    &'a [f64],
    bool,
    (&'a mut [f64], &'a mut [f64]),
    &'a mut [f64],
    &'a mut [f64],
    &'a mut [f64],
    &'a mut Check,
);

impl<const N: usize> Small<N> {
    /// The constants of `col`; `s0r` the masses above the interfaces and `centre_y0` the
    /// centres' heights of the straight column, as `ColumnDynamics` has them.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        col: &Column,
        g: f64,
        exact: bool,
        tol: f64,
        friction: f64,
        s0r: &[f64],
        centre_y0: &[f64],
    ) -> Self {
        assert!(col.n_interfaces() == N && 2 * N <= DOFS);
        let blocks = col.blocks();
        let mut small = Small {
            b: [0.0; N],
            y: [0.0; N],
            yc: [0.0; N],
            mass: [0.0; N],
            s0: [0.0; N],
            si: [0.0; N],
            scale: [0.0; N],
            centre_y0: [0.0; N],
            g,
            exact,
            tol,
            friction,
        };
        for k in 0..N {
            small.b[k] = col.half_contact_width(k);
            small.y[k] = col.base_height(k);
            small.yc[k] = small.y[k] + 0.5 * blocks[k].height;
            small.mass[k] = blocks[k].mass;
            small.scale[k] = 1e-9 * s0r[k] * g;
            small.centre_y0[k] = centre_y0[k];
        }
        let (mut s0, mut si) = (0.0, 0.0);
        for j in (0..N).rev() {
            s0 += blocks[j].mass;
            si += col.inertia(j);
            small.s0[j] = s0;
            small.si[j] = si;
        }
        small
    }

    /// [`Column::pose_into`] and `Pose::update_sums`.
    #[inline(always)]
    fn pose(&self, phi: &[f64]) -> Pose<N> {
        let phi = &phi[..2 * N];
        let mut p = Pose {
            right: [[0.0; 2]; N],
            left: [[0.0; 2]; N],
            centres: [[0.0; 2]; N],
            angles: [0.0; N],
            sin_cos: [(0.0, 1.0); N],
            moment: [[0.0; 2]; N],
            centre: [[0.0; 2]; N],
            spread: [0.0; N],
        };
        let mut map = BlockMap::GROUND;
        for k in 0..N {
            let (b, y) = (self.b[k], self.y[k]);
            let right = map.apply([b, y]);
            let left = map.apply([-b, y]);
            map.turn(phi[k], phi[N + k], b, y);
            p.right[k] = right;
            p.left[k] = left;
            p.centres[k] = map.apply([0.0, self.yc[k]]);
            p.angles[k] = map.alpha;
            p.sin_cos[k] = map.sin_cos;
        }
        let (mut s1, mut s2) = ([0.0, 0.0], 0.0);
        for j in (0..N).rev() {
            let m = self.mass[j];
            let c = p.centres[j];
            let s0 = self.s0[j];
            s1 = [s1[0] + m * c[0], s1[1] + m * c[1]];
            s2 += m * (c[0] * c[0] + c[1] * c[1]);
            let g = [s1[0] / s0, s1[1] / s0];
            p.moment[j] = s1;
            p.centre[j] = g;
            p.spread[j] = (s2 - s0 * (g[0] * g[0] + g[1] * g[1])).max(0.0);
        }
        p
    }

    /// `Pose::mass_entry`.
    #[inline(always)]
    fn mass_entry(&self, p: &Pose<N>, a: usize, b: usize) -> f64 {
        let (ka, pa) = p.side(a);
        let (kb, pb) = p.side(b);
        let k = ka.max(kb);
        let (s0, g) = (self.s0[k], p.centre[k]);
        s0 * ((g[0] - pa[0]) * (g[0] - pb[0]) + (g[1] - pa[1]) * (g[1] - pb[1]))
            + p.spread[k]
            + self.si[k]
    }

    /// `Pose::load_entry` (plus the velocity term when `vel` is given).
    #[inline(always)]
    fn load_entry(
        &self,
        p: &Pose<N>,
        vel: Option<&Velocity<N>>,
        a: usize,
        ground_acc: f64,
        gravity: f64,
    ) -> f64 {
        let (k, pv) = p.side(a);
        let (s0, s1) = (self.s0[k], p.moment[k]);
        let q = ground_acc * (s1[1] - s0 * pv[1]) - gravity * (s1[0] - s0 * pv[0]);
        match vel {
            Some((sa, sb)) => {
                let b = sb[k];
                q + -(sa[k] - (pv[0] * b[1] - pv[1] * b[0]))
            }
            None => q,
        }
    }

    /// [`super::velocity::centre_accelerations`].
    #[inline(always)]
    fn centre_accelerations(
        pose: &Pose<N>,
        statuses: &[Status],
        rates: &[f64],
        acc: Option<&[f64]>,
    ) -> [[f64; 2]; N] {
        let (statuses, rates) = (&statuses[..N], &rates[..2 * N]);
        let acc = acc.map(|a| &a[..2 * N]);
        let mut out = [[0.0; 2]; N];
        let (mut omega, mut eps) = (0.0_f64, 0.0_f64);
        let mut hinge = [0.0_f64, 0.0];
        let mut hinge_acc = [0.0_f64, 0.0];
        for j in 0..N {
            let p = if statuses[j] == Status::OpenLeft {
                pose.left[j]
            } else {
                pose.right[j]
            };
            let d = [p[0] - hinge[0], p[1] - hinge[1]];
            let acc_p = [
                hinge_acc[0] - eps * d[1] - omega * omega * d[0],
                hinge_acc[1] + eps * d[0] - omega * omega * d[1],
            ];
            omega += rates[j] + rates[N + j];
            if let Some(a) = acc {
                eps += a[j] + a[N + j];
            }
            let c = pose.centres[j];
            let r = [c[0] - p[0], c[1] - p[1]];
            out[j] = [
                acc_p[0] - eps * r[1] - omega * omega * r[0],
                acc_p[1] + eps * r[0] - omega * omega * r[1],
            ];
            hinge = p;
            hinge_acc = acc_p;
        }
        out
    }

    /// `ColumnDynamics::velocity_sums`: the suffix sums `Σ_{j≥k} m_j c_j × a_j`, `Σ_{j≥k} m_j a_j`
    /// of the centripetal accelerations.
    #[inline(always)]
    fn velocity(&self, pose: &Pose<N>, statuses: &[Status], rates: &[f64]) -> Velocity<N> {
        let cacc = Self::centre_accelerations(pose, statuses, rates, None);
        let (mut sa, mut sb) = ([0.0; N], [[0.0; 2]; N]);
        let (mut a, mut b) = (0.0, [0.0, 0.0]);
        for j in (0..N).rev() {
            let m = self.mass[j];
            let c = pose.centres[j];
            let ac = cacc[j];
            a += m * (c[0] * ac[1] - c[1] * ac[0]);
            b = [b[0] + m * ac[0], b[1] + m * ac[1]];
            sa[j] = a;
            sb[j] = b;
        }
        (sa, sb)
    }

    /// `ColumnDynamics::solve_open`: `M_FF a_F = q_F` at `pose`, the result in `rhs[..k]`
    /// (the loads if `M_FF` is not positive definite), `q_F` and the diagonal of `M_FF` in `q`,
    /// `diag` (DOF vectors).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn solve(
        &self,
        pose: &Pose<N>,
        vel: Option<&Velocity<N>>,
        open: &[usize],
        ag: f64,
        rhs: &mut [f64; DOFS],
        q: &mut [f64; DOFS],
        diag: &mut [f64; DOFS],
    ) -> bool {
        let k = open.len();
        let mut mk = [0.0; OPEN_SQ];
        for (r, &a) in open.iter().enumerate() {
            for (c, &b) in open.iter().enumerate().skip(r) {
                let v = self.mass_entry(pose, a, b);
                mk[r * k + c] = v;
                mk[c * k + r] = v;
            }
            diag[a] = mk[r * k + r];
        }
        for (r, &a) in open.iter().enumerate() {
            let v = self.load_entry(pose, vel, a, ag, self.g);
            rhs[r] = v;
            q[a] = v;
        }
        let mk = &mut mk[..k * k];
        if !cholesky::factor(mk, k) {
            return false;
        }
        cholesky::solve(mk, k, &mut rhs[..k]);
        true
    }

    /// `ChainDynamics::energy`: kinetic and potential energy at `phi`, `rates`.
    pub fn energy(&self, open: &[usize], phi: &[f64], rates: &[f64]) -> (f64, f64) {
        let pose = self.pose(phi);
        let mut t = 0.0;
        for &a in open {
            for &b in open {
                t += rates[a] * self.mass_entry(&pose, a, b) * rates[b];
            }
        }
        let v: f64 = (0..N)
            .map(|j| self.mass[j] * self.g * (pose.centres[j][1] - self.centre_y0[j]))
            .sum();
        (0.5 * t, v)
    }

    /// `Equations::accel` with two or more open DOFs; `phi`, `rates` are the full DOF vectors.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub fn accel(
        &self,
        open: &[usize],
        statuses: &[Status],
        ag: f64,
        phi: &[f64],
        rates: &[f64],
        out: &mut [f64],
    ) -> bool {
        let args = (open, statuses, ag, phi, rates, out);
        match (open.len(), self.exact) {
            (2, false) => self.accel_of::<2, false>(args),
            (2, true) => self.accel_of::<2, true>(args),
            (3, false) => self.accel_of::<3, false>(args),
            (3, true) => self.accel_of::<3, true>(args),
            (_, exact) => {
                if exact {
                    self.accel_of::<0, true>(args)
                } else {
                    self.accel_of::<0, false>(args)
                }
            }
        }
    }

    /// [`Small::accel`] with `K` open DOFs (0: any) and the velocity terms if `EXACT`; the same
    /// operations, with the loops' lengths known to the compiler.
    #[inline(always)]
    fn accel_of<const K: usize, const EXACT: bool>(
        &self,
        (open, statuses, ag, phi, rates, out): AccelArgs,
    ) -> bool {
        let open = if K > 0 { &open[..K] } else { open };
        let pose = self.pose(phi);
        let vel = EXACT.then(|| self.velocity(&pose, statuses, rates));
        let (mut rhs, mut q, mut diag) = ([0.0; DOFS], [0.0; DOFS], [0.0; DOFS]);
        let ok = self.solve(&pose, vel.as_ref(), open, ag, &mut rhs, &mut q, &mut diag);
        let k = open.len();
        out[..k].copy_from_slice(&rhs[..k]);
        ok
    }

    /// `ColumnDynamics::general_check`: the accelerations, margins and block rotations into
    /// `acc_full`, `margin`, `block_angles`; `scratch_phi`, `scratch_rates` become `phi`, `rates`.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub fn check(
        &self,
        open: &[usize],
        statuses: &[Status],
        ag: f64,
        phi: &[f64],
        rates: &[f64],
        forces: bool,
        scratch: (&mut [f64], &mut [f64]),
        acc_full: &mut [f64],
        margin: &mut [f64],
        block_angles: &mut [f64],
        out: &mut Check,
    ) {
        let args = (
            open,
            statuses,
            ag,
            phi,
            rates,
            forces,
            scratch,
            acc_full,
            margin,
            block_angles,
            out,
        );
        // One open DOF is most steps of a column (the part above one interface rocks).
        match (open.len(), self.exact) {
            (1, false) => self.check_of::<1, false>(args),
            (1, true) => self.check_of::<1, true>(args),
            (_, false) => self.check_of::<0, false>(args),
            (_, true) => self.check_of::<0, true>(args),
        }
    }

    /// [`Small::check`] with `K` open DOFs (0: any) and the velocity terms if `EXACT`.
    #[inline(always)]
    fn check_of<const K: usize, const EXACT: bool>(
        &self,
        (open, statuses, ag, phi, rates, forces, scratch, acc_full, margin, block_angles, out): CheckArgs,
    ) {
        let open = if K > 0 { &open[..K] } else { open };
        let (phi, rates, statuses) = (&phi[..2 * N], &rates[..2 * N], &statuses[..N]);
        let (acc_full, margin) = (&mut acc_full[..2 * N], &mut margin[..2 * N]);
        let g = self.g;
        scratch.0[..2 * N].copy_from_slice(phi);
        scratch.1[..2 * N].copy_from_slice(rates);
        let pose = self.pose(phi);
        let vel = EXACT.then(|| self.velocity(&pose, statuses, rates));
        let (mut rhs, mut q, mut diag) = ([0.0; DOFS], [0.0; DOFS], [0.0; DOFS]);
        out.ok = self.solve(&pose, vel.as_ref(), open, ag, &mut rhs, &mut q, &mut diag);
        acc_full.iter_mut().for_each(|v| *v = 0.0);
        for (i, &d) in open.iter().enumerate() {
            acc_full[d] = rhs[i];
        }
        // Loads and Jacobi scales of the generators, then the reaction test.
        let generator = |d: usize| match statuses[if d < N { d } else { d - N }] {
            Status::Closed => true,
            Status::OpenRight => d < N,
            Status::OpenLeft => d >= N,
        };
        let closed = |d: usize| statuses[if d < N { d } else { d - N }] == Status::Closed;
        let mut isq = [0.0; DOFS];
        for d in 0..2 * N {
            if !generator(d) {
                continue;
            }
            if closed(d) {
                q[d] = self.load_entry(&pose, vel.as_ref(), d, ag, g);
                diag[d] = self.mass_entry(&pose, d, d);
            }
            isq[d] = 1.0 / diag[d].sqrt();
        }
        let mut bmax = 0.0_f64;
        for d in 0..2 * N {
            if generator(d) {
                bmax = bmax.max(q[d].abs() * isq[d]);
            }
        }
        let threshold = self.tol * bmax;
        let mut largest = f64::NEG_INFINITY;
        for d in 0..2 * N {
            if !closed(d) {
                margin[d] = f64::NEG_INFINITY;
                continue;
            }
            let ma: f64 = open
                .iter()
                .map(|&f| self.mass_entry(&pose, d, f) * acc_full[f])
                .sum();
            let sigma = if d < N { -1.0 } else { 1.0 };
            let v = sigma * (q[d] - ma) * isq[d] - threshold;
            margin[d] = v;
            largest = largest.max(v);
        }
        out.max_margin = largest;
        let mut power = 0.0;
        for &f in open {
            power += self.load_entry(&pose, None, f, ag, 0.0) * rates[f];
        }
        out.power = power;
        block_angles[..N].copy_from_slice(&pose.angles);
        // Tipping of the part above each open interface, in the frame of the block below.
        for k in 0..N {
            let sigma = statuses[k].sign();
            if sigma == 0.0 {
                continue;
            }
            let p = if sigma < 0.0 {
                pose.right[k]
            } else {
                pose.left[k]
            };
            let c = pose.centre[k];
            let (s, co) = pose.below_sin_cos(k);
            let along = (c[0] - p[0]) * co + (c[1] - p[1]) * s;
            if -sigma * along > 0.0 {
                out.tipped = Some(k);
                break;
            }
        }
        if let Some(j) = pose
            .angles
            .iter()
            .position(|a| a.abs() >= 0.5 * std::f64::consts::PI)
        {
            let k = (0..=j)
                .max_by(|&a, &b| {
                    let ra = (phi[a] + phi[N + a]).abs();
                    let rb = (phi[b] + phi[N + b]).abs();
                    ra.total_cmp(&rb)
                })
                .unwrap_or(0);
            out.fallen = Some(k);
        }
        if forces {
            let cacc = Self::centre_accelerations(&pose, statuses, rates, Some(acc_full));
            let (mut fx, mut fy) = (0.0, 0.0);
            for k in (0..N).rev() {
                let m = self.mass[k];
                fx += m * (cacc[k][0] + ag);
                fy += m * (cacc[k][1] + g);
                let (s, c) = pose.below_sin_cos(k);
                let v = fx * c + fy * s;
                let nn = -fx * s + fy * c;
                let scale = self.scale[k];
                if nn < -scale {
                    out.tension = Some(k);
                } else if v.abs() > self.friction * nn.max(0.0) + scale {
                    out.sliding = Some(k);
                }
            }
        }
    }
}
