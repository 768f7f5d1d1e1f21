//! The frictional contact problem of one time step (or of one impact) at velocity level, joint by
//! joint: Signorini's condition at the ends of every joint and Coulomb's law on the joint.
//!
//! Unknowns per joint `k`: the normal impulses `P_R, P_L ≥ 0` at its two ends and the tangential
//! impulse `T` with `|T| ≤ μ (P_R + P_L)`. Velocities after the impulses:
//! `v = v_free + M⁻¹ Hᵀ P`, relative velocities `U = H v = W P + b`, `W = H M⁻¹ Hᵀ`.
//! Conditions (Moreau's velocity-level laws with zero restitution, Acary & Brogliato 2008 §3.9,
//! §10.1): `0 ≤ U_c ⊥ P_c ≥ 0` at every active end `c`; `T = −μ N sign(U_t)` when the joint
//! slips, `|T| ≤ μ N` with `U_t = 0` when it sticks, `N = P_R + P_L`. The joint's tangential row is
//! that of its active end, the mean of the two when both ends are active: one slip velocity per
//! joint, so that the problem is not degenerate when a joint is closed along a face (the two
//! corners' tangential rows are then equal: both ends are in contact only while the faces are
//! parallel, and a rotation about any point of the face line moves the face line only normally).
//!
//! Per-joint friction equals per-corner friction `|T_c| ≤ μ P_c`: the Minkowski sum of the two
//! corner cones is the joint's cone, and both corners of a closed face slip together.
//!
//! With every end's normal and the joint's tangential status fixed, the conditions are linear and
//! `W` is block tridiagonal (a joint couples with its neighbours through the drums they share):
//! one block LU of 3 × 3 blocks, `O(n)`. The statuses are found by the primal-dual active set
//! method (the semismooth Newton method on the `min` / Alart–Curnier complementarity functions,
//! Hintermüller, Ito & Kunisch 2002; Alart & Curnier 1991), warm-started from the previous step,
//! where they rarely change. It is deterministic and stops after a bounded number of iterations;
//! when it cycles, the problem goes to the fallbacks of [`super::fallback`] (Lemke's algorithm,
//! then the nonsmooth Gauss–Seidel iteration).

use super::drums::ContactRows;
use super::lemke::Lemke;

pub(super) type B3 = [[f64; 3]; 3];

/// Input of one joint.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointContacts {
    /// Whether each end (0: right, 1: left) takes part.
    pub active: [bool; 2],
    /// An equality constraint (`U_c = 0`, impulse of either sign) instead of Signorini's.
    pub bilateral: [bool; 2],
    /// Rows of each end.
    pub rows: [ContactRows; 2],
    /// Coulomb coefficient: `0` frictionless (no tangential impulse), `f64::INFINITY` never slips.
    pub mu: f64,
}

/// Slip status of a joint.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Slip {
    /// No slip (`U_t = 0`).
    #[default]
    Stick,
    /// Slipping with `U_t > 0` (`T = −μN`).
    Positive,
    /// Slipping with `U_t < 0` (`T = +μN`).
    Negative,
}

impl Slip {
    pub(super) fn sign(self) -> f64 {
        match self {
            Slip::Stick => 0.0,
            Slip::Positive => 1.0,
            Slip::Negative => -1.0,
        }
    }
}

/// Contact status of a joint: which ends are closed and how it slips.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct JointStatus {
    /// Closed (velocity held at zero, compressive impulse) at each end.
    pub closed: [bool; 2],
    /// Tangential status (meaningful when an end is closed).
    pub slip: Slip,
}

/// How a problem was solved.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SolveReport {
    /// Active-set iterations (linear solves).
    pub iterations: usize,
    /// Whether Lemke's algorithm had to take over.
    pub fallback: bool,
    /// Whether Lemke's algorithm failed too (round-off on a degenerate problem) and the nonsmooth
    /// Gauss–Seidel iteration gave the answer.
    pub gauss_seidel: bool,
    /// Whether that iteration stopped at its cap of sweeps before its tolerance.
    pub inexact: bool,
}

/// Why the problem could not be solved (none of the methods).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SolveFailure;

/// Maximum active-set iterations before the fallbacks take over.
const MAX_ITERATIONS: usize = 30;

/// The reduced unknowns and equations of a joint for given statuses.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Reduction {
    /// Number of unknowns (= equations).
    pub(super) size: usize,
    /// Rows (0: right normal, 1: left normal, 2: tangent) held at zero velocity.
    pub(super) rows: [usize; 3],
    /// Impulse `(P_R, P_L, T)` of a unit of each unknown.
    pub(super) cols: B3,
}

/// Workspace and solution of the joint-wise contact problem for a column of `n` drums.
#[derive(Clone, Debug, Default)]
pub struct ContactProblem {
    pub(super) n: usize,
    /// Inverse masses, `3n`.
    pub(super) inv_mass: Vec<f64>,
    /// Jacobian rows of each joint for its upper and lower drum: `[nR, nL, t]`, each `[x, y, θ]`.
    pub(super) up: Vec<B3>,
    pub(super) low: Vec<B3>,
    /// Tangent row weights of each joint's two ends.
    pub(super) weights: Vec<[f64; 2]>,
    /// Diagonal blocks of `W`.
    pub(super) wd: Vec<B3>,
    /// Off-diagonal blocks: rows of joint `k`, columns of joint `k + 1`.
    pub(super) wo: Vec<B3>,
    /// Free relative velocities.
    pub(super) b: Vec<[f64; 3]>,
    pub(super) joints: Vec<JointContacts>,
    pub(super) red: Vec<Reduction>,
    pub(super) cp: Vec<B3>,
    pub(super) dinv: Vec<B3>,
    pub(super) dp: Vec<[f64; 3]>,
    pub(super) z: Vec<[f64; 3]>,
    /// Impulses `(P_R, P_L, T)` of every joint.
    pub(super) p: Vec<[f64; 3]>,
    /// Relative velocities on the three rows.
    pub(super) u: Vec<[f64; 3]>,
    pub(super) history: Vec<u64>,
    pub(super) next: Vec<JointStatus>,
    pub(super) viol: Vec<f64>,
    pub(super) lemke: Lemke,
}

/// Inverse of the leading `m × m` block (`m ≤ 3`) by the adjugate; `None` when the block is
/// singular to working precision (|det| below `1e-13` of the product of its rows' norms).
pub(super) fn invert3(a: &B3, m: usize) -> Option<B3> {
    let mut inv = [[0.0; 3]; 3];
    match m {
        0 => Some(inv),
        1 => {
            let d = a[0][0];
            if d.abs() <= 0.0 || !d.is_finite() {
                return None;
            }
            inv[0][0] = 1.0 / d;
            Some(inv)
        }
        2 => {
            let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
            let scale = ((a[0][0] * a[0][0] + a[0][1] * a[0][1])
                * (a[1][0] * a[1][0] + a[1][1] * a[1][1]))
                .sqrt();
            if !(det.abs() > 1e-13 * scale && det.is_finite()) {
                return None;
            }
            let r = 1.0 / det;
            inv[0][0] = a[1][1] * r;
            inv[0][1] = -a[0][1] * r;
            inv[1][0] = -a[1][0] * r;
            inv[1][1] = a[0][0] * r;
            Some(inv)
        }
        _ => {
            let c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
            let c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
            let c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
            let det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
            let norm = |r: &[f64; 3]| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
            let scale = norm(&a[0]) * norm(&a[1]) * norm(&a[2]);
            if !(det.abs() > 1e-13 * scale && det.is_finite()) {
                return None;
            }
            let r = 1.0 / det;
            inv[0][0] = c00 * r;
            inv[1][0] = c01 * r;
            inv[2][0] = c02 * r;
            inv[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) * r;
            inv[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) * r;
            inv[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) * r;
            inv[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) * r;
            inv[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) * r;
            inv[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) * r;
            Some(inv)
        }
    }
}

#[inline]
fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl ContactProblem {
    /// A workspace for `n` drums with the given masses and moments of inertia.
    pub fn new(masses: &[f64], inertias: &[f64]) -> ContactProblem {
        let n = masses.len();
        let mut inv_mass = Vec::with_capacity(3 * n);
        for j in 0..n {
            inv_mass.extend_from_slice(&[1.0 / masses[j], 1.0 / masses[j], 1.0 / inertias[j]]);
        }
        let zero = [[0.0; 3]; 3];
        ContactProblem {
            n,
            inv_mass,
            up: vec![zero; n],
            low: vec![zero; n],
            weights: vec![[0.0; 2]; n],
            wd: vec![zero; n],
            wo: vec![zero; n],
            b: vec![[0.0; 3]; n],
            joints: vec![JointContacts::default(); n],
            red: vec![Reduction::default(); n],
            cp: vec![zero; n],
            dinv: vec![zero; n],
            dp: vec![[0.0; 3]; n],
            z: vec![[0.0; 3]; n],
            p: vec![[0.0; 3]; n],
            u: vec![[0.0; 3]; n],
            history: Vec::with_capacity(MAX_ITERATIONS),
            next: vec![JointStatus::default(); n],
            viol: vec![0.0; n],
            lemke: Lemke::default(),
        }
    }

    /// Number of joints.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Whether the column is empty.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Weights of the two ends' tangent rows in the joint's tangential row.
    pub fn tangent_weights(active: [bool; 2]) -> [f64; 2] {
        match active {
            [true, true] => [0.5, 0.5],
            [true, false] => [1.0, 0.0],
            [false, true] => [0.0, 1.0],
            [false, false] => [0.0, 0.0],
        }
    }

    /// Sets up the problem: the joints' contacts and the free velocities `v_free` (`3n`).
    pub fn set(&mut self, joints: &[JointContacts], v_free: &[f64]) {
        let n = self.n;
        for k in 0..n {
            let jc = joints[k];
            self.joints[k] = jc;
            let w = Self::tangent_weights(jc.active);
            self.weights[k] = w;
            let r = &jc.rows;
            let t = |a: [f64; 3], b: [f64; 3]| {
                [
                    w[0] * a[0] + w[1] * b[0],
                    w[0] * a[1] + w[1] * b[1],
                    w[0] * a[2] + w[1] * b[2],
                ]
            };
            self.up[k] = [r[0].n_up, r[1].n_up, t(r[0].t_up, r[1].t_up)];
            self.low[k] = [r[0].n_low, r[1].n_low, t(r[0].t_low, r[1].t_low)];
        }
        for k in 0..n {
            let up = self.up[k];
            let mu = [
                self.inv_mass[3 * k],
                self.inv_mass[3 * k + 1],
                self.inv_mass[3 * k + 2],
            ];
            let vu = [v_free[3 * k], v_free[3 * k + 1], v_free[3 * k + 2]];
            let mut w = [[0.0; 3]; 3];
            let mut b = [0.0; 3];
            let mut mup = [[0.0; 3]; 3];
            for a in 0..3 {
                mup[a] = [up[a][0] * mu[0], up[a][1] * mu[1], up[a][2] * mu[2]];
                b[a] = dot3(&up[a], &vu);
            }
            for a in 0..3 {
                for c in a..3 {
                    w[a][c] = dot3(&mup[a], &up[c]);
                }
            }
            if k > 0 {
                let low = self.low[k];
                let ml = [
                    self.inv_mass[3 * k - 3],
                    self.inv_mass[3 * k - 2],
                    self.inv_mass[3 * k - 1],
                ];
                let vl = [v_free[3 * k - 3], v_free[3 * k - 2], v_free[3 * k - 1]];
                for a in 0..3 {
                    b[a] += dot3(&low[a], &vl);
                    let ml_a = [low[a][0] * ml[0], low[a][1] * ml[1], low[a][2] * ml[2]];
                    for c in a..3 {
                        w[a][c] += dot3(&ml_a, &low[c]);
                    }
                }
            }
            for a in 0..3 {
                for c in 0..a {
                    w[a][c] = w[c][a];
                }
            }
            self.wd[k] = w;
            self.b[k] = b;
            // Coupling with joint k+1 through drum k.
            if k + 1 < n {
                let ln = self.low[k + 1];
                let mut o = [[0.0; 3]; 3];
                for a in 0..3 {
                    for c in 0..3 {
                        o[a][c] = dot3(&mup[a], &ln[c]);
                    }
                }
                self.wo[k] = o;
            }
        }
    }

    /// Replaces the free relative velocities of joint `k` (e.g. by gaps, for a projection of
    /// positions: then `U = W P + b` is the gap after the displacement `M⁻¹ Hᵀ P`).
    pub fn set_offsets(&mut self, k: usize, b: [f64; 3]) {
        self.b[k] = b;
    }

    /// The reduction of joint `k` for status `st`.
    pub(super) fn reduce(&self, k: usize, st: &JointStatus) -> Reduction {
        let jc = &self.joints[k];
        let mut red = Reduction::default();
        let mut r = 0;
        for c in 0..2 {
            if jc.active[c] && st.closed[c] {
                red.rows[r] = c;
                red.cols[r][c] = 1.0;
                r += 1;
            }
        }
        let nclosed = r;
        if nclosed > 0 && jc.mu > 0.0 {
            match st.slip {
                Slip::Stick => {
                    red.rows[r] = 2;
                    red.cols[r][2] = 1.0;
                    r += 1;
                }
                slip => {
                    let f = -slip.sign() * jc.mu;
                    for i in 0..nclosed {
                        red.cols[i][2] = f;
                    }
                }
            }
        }
        red.size = r;
        red
    }

    /// `S_k X E_l`: rows of joint `k`'s reduction, columns of joint `l`'s.
    #[inline]
    pub(super) fn reduced_block(rk: &Reduction, x: &B3, rl: &Reduction) -> B3 {
        let mut out = [[0.0; 3]; 3];
        for i in 0..rk.size {
            let row = &x[rk.rows[i]];
            for j in 0..rl.size {
                out[i][j] = dot3(row, &rl.cols[j]);
            }
        }
        out
    }

    #[inline]
    pub(super) fn reduced_block_t(rk: &Reduction, x: &B3, rl: &Reduction) -> B3 {
        // Uses Xᵀ: rows of X's columns.
        let mut out = [[0.0; 3]; 3];
        for i in 0..rk.size {
            let r = rk.rows[i];
            let row = [x[0][r], x[1][r], x[2][r]];
            for j in 0..rl.size {
                out[i][j] = dot3(&row, &rl.cols[j]);
            }
        }
        out
    }

    /// One linear solve for the statuses; fills `p` and `u`. `false` if singular. Joints below
    /// `from` have the statuses of the previous solve: their reductions and eliminated blocks are
    /// kept (the coupling of joint `from − 1` with joint `from` is redone).
    fn linear_solve(&mut self, statuses: &[JointStatus], from: usize) -> bool {
        let n = self.n;
        for k in from..n {
            self.red[k] = self.reduce(k, &statuses[k]);
        }
        if from > 0 {
            let k = from - 1;
            let rk = self.red[k];
            let rn = self.red[from];
            let a_up = Self::reduced_block(&rk, &self.wo[k], &rn);
            let dinv = self.dinv[k];
            let mut c = [[0.0; 3]; 3];
            for i in 0..rk.size {
                for j in 0..rn.size {
                    let mut acc = 0.0;
                    for l in 0..rk.size {
                        acc += dinv[i][l] * a_up[l][j];
                    }
                    c[i][j] = acc;
                }
            }
            self.cp[k] = c;
        }
        // Forward elimination.
        for k in from..n {
            let rk = self.red[k];
            let m = rk.size;
            if m == 0 {
                self.dp[k] = [0.0; 3];
                self.cp[k] = [[0.0; 3]; 3];
                continue;
            }
            let mut d = Self::reduced_block(&rk, &self.wd[k], &rk);
            let mut rhs = [0.0; 3];
            for i in 0..m {
                rhs[i] = -self.b[k][rk.rows[i]];
            }
            if k > 0 && self.red[k - 1].size > 0 {
                let rp = self.red[k - 1];
                let a_lo = Self::reduced_block_t(&rk, &self.wo[k - 1], &rp);
                let cprev = &self.cp[k - 1];
                let dprev = &self.dp[k - 1];
                for i in 0..m {
                    for j in 0..m {
                        let mut acc = 0.0;
                        for l in 0..rp.size {
                            acc += a_lo[i][l] * cprev[l][j];
                        }
                        d[i][j] -= acc;
                    }
                    let mut acc = 0.0;
                    for l in 0..rp.size {
                        acc += a_lo[i][l] * dprev[l];
                    }
                    rhs[i] -= acc;
                }
            }
            let Some(dinv) = invert3(&d, m) else {
                return false;
            };
            self.dinv[k] = dinv;
            let mut y = [0.0; 3];
            for i in 0..m {
                for j in 0..m {
                    y[i] += dinv[i][j] * rhs[j];
                }
            }
            self.dp[k] = y;
            if k + 1 < n {
                let rn = self.red[k + 1];
                let a_up = Self::reduced_block(&rk, &self.wo[k], &rn);
                let mut c = [[0.0; 3]; 3];
                for i in 0..m {
                    for j in 0..rn.size {
                        let mut acc = 0.0;
                        for l in 0..m {
                            acc += dinv[i][l] * a_up[l][j];
                        }
                        c[i][j] = acc;
                    }
                }
                self.cp[k] = c;
            }
        }
        // Back substitution.
        for k in (0..n).rev() {
            let m = self.red[k].size;
            let mut z = self.dp[k];
            if k + 1 < n {
                let rn = self.red[k + 1].size;
                let zn = self.z[k + 1];
                for i in 0..m {
                    let mut acc = 0.0;
                    for j in 0..rn {
                        acc += self.cp[k][i][j] * zn[j];
                    }
                    z[i] -= acc;
                }
            }
            self.z[k] = z;
        }
        let mut finite = true;
        for k in 0..n {
            let red = &self.red[k];
            let mut p = [0.0; 3];
            for j in 0..red.size {
                let zj = self.z[k][j];
                for a in 0..3 {
                    p[a] += red.cols[j][a] * zj;
                }
            }
            finite &= p.iter().all(|x| x.is_finite());
            self.p[k] = p;
        }
        self.update_rates();
        finite
    }

    /// `u = W p + b`.
    pub(super) fn update_rates(&mut self) {
        let n = self.n;
        for k in 0..n {
            let mut u = self.b[k];
            let p = self.p[k];
            for a in 0..3 {
                u[a] += dot3(&self.wd[k][a], &p);
            }
            if k + 1 < n {
                let pn = self.p[k + 1];
                for a in 0..3 {
                    u[a] += dot3(&self.wo[k][a], &pn);
                }
            }
            if k > 0 {
                let pp = self.p[k - 1];
                let o = &self.wo[k - 1];
                for a in 0..3 {
                    u[a] += o[0][a] * pp[0] + o[1][a] * pp[1] + o[2][a] * pp[2];
                }
            }
            self.u[k] = u;
        }
    }

    /// Status update of the active set method; returns the lowest joint whose status changed.
    /// Each joint's next status and the size of the violation that calls for it (relative to the
    /// problem's velocity or impulse scale) are found first; then the violated joints change
    /// whose violation is at least half the largest, the lowest of each run of neighbours calling
    /// for the same change (a damped primal-dual active set step: in a stack, a wrong status at
    /// one joint puts spurious tension on the joints around it, and opening them all makes the
    /// closures come back one joint per iteration); with `single`, only the lowest violated
    /// joint. On the 20-drum suite columns this takes a third fewer iterations and half the
    /// fallbacks of changing every violated joint at once.
    fn update_statuses(
        &mut self,
        statuses: &mut [JointStatus],
        tol_u: f64,
        tol_p: f64,
        single: bool,
    ) -> Option<usize> {
        let (u_ref, p_ref) = (tol_u * 1e10, tol_p * 1e10);
        let mut worst = 0.0_f64;
        for k in 0..self.n {
            let jc = &self.joints[k];
            let st = statuses[k];
            let p = self.p[k];
            let u = self.u[k];
            let mut next = st;
            let mut viol = 0.0_f64;
            for c in 0..2 {
                if !jc.active[c] {
                    next.closed[c] = false;
                } else if jc.bilateral[c] {
                    next.closed[c] = true;
                } else if st.closed[c] {
                    if p[c] < -tol_p {
                        next.closed[c] = false;
                        viol = viol.max(-p[c] / p_ref);
                    }
                } else if u[c] < -tol_u {
                    next.closed[c] = true;
                    viol = viol.max(-u[c] / u_ref);
                }
            }
            let any_closed = (jc.active[0] && st.closed[0]) || (jc.active[1] && st.closed[1]);
            if any_closed && jc.mu > 0.0 && jc.mu.is_finite() {
                let bound = jc.mu * (p[0] + p[1]).max(0.0);
                match st.slip {
                    Slip::Stick => {
                        if p[2].abs() > bound + tol_p {
                            next.slip = if p[2] > 0.0 {
                                Slip::Negative
                            } else {
                                Slip::Positive
                            };
                            viol = viol.max((p[2].abs() - bound) / p_ref);
                        }
                    }
                    slip => {
                        let s = slip.sign();
                        if s * u[2] < -tol_u {
                            // Reversed: stick, or slip the other way if it reverses strongly
                            // (Alart–Curnier's augmented test with ρ = 1 / W_tt).
                            let wtt = self.wd[k][2][2];
                            let rho = if wtt > 0.0 { 1.0 / wtt } else { 0.0 };
                            next.slip = if -s * u[2] * rho > 2.0 * bound {
                                if s > 0.0 {
                                    Slip::Negative
                                } else {
                                    Slip::Positive
                                }
                            } else {
                                Slip::Stick
                            };
                            viol = viol.max(-s * u[2] / u_ref);
                        }
                    }
                }
            }
            let any_next = (jc.active[0] && next.closed[0]) || (jc.active[1] && next.closed[1]);
            if !any_next || jc.mu == 0.0 || jc.mu.is_infinite() {
                next.slip = Slip::Stick;
            }
            if next == st {
                viol = 0.0;
            } else {
                // A change with no measured violation (bookkeeping of inactive ends) is taken.
                viol = viol.max(f64::MIN_POSITIVE);
            }
            self.next[k] = next;
            self.viol[k] = viol;
            worst = worst.max(viol);
        }
        if worst == 0.0 {
            return None;
        }
        let mut changed: Option<usize> = None;
        // Of a run of neighbouring joints calling for the same change (same status before and
        // after), only the lowest changes: the others' violations are usually the echo of its
        // wrong status (in a stack, a joint that should open puts tension on its neighbours).
        let mut run: Option<(JointStatus, JointStatus)> = None;
        for k in 0..self.n {
            let v = self.viol[k];
            if v == 0.0 {
                run = None;
                continue;
            }
            let kind = (statuses[k], self.next[k]);
            let echo = run == Some(kind);
            run = Some(kind);
            if !single && (v < 0.5 * worst || echo) {
                continue;
            }
            statuses[k] = self.next[k];
            if changed.is_none() {
                changed = Some(k);
                if single {
                    break;
                }
            }
        }
        if changed.is_none() {
            // Every violation was held back: take the largest.
            let mut k_max = 0;
            for k in 0..self.n {
                if self.viol[k] > self.viol[k_max] {
                    k_max = k;
                }
            }
            statuses[k_max] = self.next[k_max];
            changed = Some(k_max);
        }
        changed
    }

    fn signature(statuses: &[JointStatus]) -> u64 {
        // FNV-1a over the status codes: deterministic, no allocation.
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for s in statuses {
            let code = (s.closed[0] as u64) | (s.closed[1] as u64) << 1 | (s.slip as u64) << 2;
            h ^= code;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
        h
    }

    /// Solves the problem set by [`ContactProblem::set`], starting from `statuses` (the previous
    /// step's: a warm start) and leaving the solution's statuses there. The impulses are then
    /// read with [`ContactProblem::impulses`], the velocities with [`ContactProblem::apply`].
    pub fn solve(&mut self, statuses: &mut [JointStatus]) -> Result<SolveReport, SolveFailure> {
        let n = self.n;
        // Statuses of inactive ends are open; bilateral ends closed.
        for k in 0..n {
            let jc = self.joints[k];
            for c in 0..2 {
                if !jc.active[c] {
                    statuses[k].closed[c] = false;
                } else if jc.bilateral[c] {
                    statuses[k].closed[c] = true;
                }
            }
            if jc.mu == 0.0 || jc.mu.is_infinite() {
                statuses[k].slip = Slip::Stick;
            }
        }
        let mut scale_u = 0.0_f64;
        for k in 0..n {
            for a in 0..3 {
                scale_u = scale_u.max(self.b[k][a].abs());
            }
        }
        let tol_u = 1e-10 * scale_u.max(1e-300);
        // The impulse that changes a velocity by `scale_u`: the floor of the impulse tolerance
        // (when every impulse is nearly zero, their own size is round-off).
        let mut wmax = 0.0_f64;
        for k in 0..n {
            for a in 0..3 {
                wmax = wmax.max(self.wd[k][a][a]);
            }
        }
        let p_floor = if wmax > 0.0 { scale_u / wmax } else { 0.0 };
        self.history.clear();
        let mut report = SolveReport::default();
        let mut from = 0;
        // All violated statuses change at once (primal-dual active set); after a cycle, one joint
        // at a time (the lowest: a least-index rule, Murty 1974); then the fallbacks.
        let mut single = false;
        let mut single_iterations = 0;
        loop {
            report.iterations += 1;
            if single {
                single_iterations += 1;
            }
            if !self.linear_solve(statuses, from) {
                break;
            }
            let mut scale_p = 0.0_f64;
            for p in &self.p {
                for x in p {
                    scale_p = scale_p.max(x.abs());
                }
            }
            let tol_p = 1e-10 * scale_p.max(p_floor).max(1e-300);
            match self.update_statuses(statuses, tol_u, tol_p, single) {
                None => return Ok(report),
                Some(k) => from = k,
            }
            let sig = Self::signature(statuses);
            let seen = self.history.iter().position(|&h| h == sig);
            if !single {
                if seen.is_some() || report.iterations >= MAX_ITERATIONS {
                    single = true;
                    self.history.clear();
                }
            } else if seen.is_some() || single_iterations >= 4 * n + 8 {
                break;
            }
            self.history.push(sig);
        }
        report.fallback = true;
        if self.solve_lemke(statuses).is_ok() {
            return Ok(report);
        }
        report.gauss_seidel = true;
        report.inexact = !self.solve_gauss_seidel(statuses)?;
        Ok(report)
    }

    /// Impulses `(P_R, P_L, T)` of joint `k`.
    pub fn impulses(&self, k: usize) -> [f64; 3] {
        self.p[k]
    }

    /// Relative velocities after the impulses, `(U_R, U_L, U_t)`, of joint `k`.
    pub fn rates(&self, k: usize) -> [f64; 3] {
        self.u[k]
    }

    /// Free relative velocities `(U_R, U_L, U_t)` of joint `k`.
    pub fn free_rates(&self, k: usize) -> [f64; 3] {
        self.b[k]
    }

    /// Weights of the right and left tangent rows in joint `k`'s tangential row.
    pub fn weights(&self, k: usize) -> [f64; 2] {
        self.weights[k]
    }

    /// Relative velocities `(U_R, U_L, U_t)` of joint `k` on the problem's rows for velocities `v`.
    pub fn rows_rates(&self, k: usize, v: &[f64]) -> [f64; 3] {
        let vu = [v[3 * k], v[3 * k + 1], v[3 * k + 2]];
        let mut u = [0.0; 3];
        for a in 0..3 {
            u[a] = dot3(&self.up[k][a], &vu);
        }
        if k > 0 {
            let vl = [v[3 * k - 3], v[3 * k - 2], v[3 * k - 1]];
            for a in 0..3 {
                u[a] += dot3(&self.low[k][a], &vl);
            }
        }
        u
    }

    /// `v = v_free + M⁻¹ Hᵀ P` (`v` holds `v_free` on entry).
    pub fn apply(&self, v: &mut [f64]) {
        let n = self.n;
        for k in 0..n {
            let p = self.p[k];
            if p == [0.0; 3] {
                continue;
            }
            let up = &self.up[k];
            for i in 0..3 {
                let acc = up[0][i] * p[0] + up[1][i] * p[1] + up[2][i] * p[2];
                v[3 * k + i] += self.inv_mass[3 * k + i] * acc;
            }
            if k > 0 {
                let low = &self.low[k];
                for i in 0..3 {
                    let acc = low[0][i] * p[0] + low[1][i] * p[1] + low[2][i] * p[2];
                    v[3 * k - 3 + i] += self.inv_mass[3 * k - 3 + i] * acc;
                }
            }
        }
    }
}
