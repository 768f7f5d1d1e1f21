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
//! then the nonsmooth Gauss–Seidel iteration). This file sets the problem up; the active set
//! method is [`super::active_set`].

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

/// What the solvers read of a joint's [`JointContacts`] (its rows go into the Delassus blocks):
/// kept apart so that setting a problem up does not copy the rows a second time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct JointLaw {
    pub(super) active: [bool; 2],
    pub(super) bilateral: [bool; 2],
    pub(super) mu: f64,
    /// `0 < μ < ∞`: the joint can slip (classified once per problem, for the status tests).
    pub(super) slips: bool,
    /// `μ = 0` or `μ = ∞`: the joint's tangential status is always stick.
    pub(super) sticks: bool,
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
pub(super) const MAX_ITERATIONS: usize = 30;

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
    /// Inverse masses `[1/m, 1/m, 1/I]` per drum.
    pub(super) inv_mass: Vec<[f64; 3]>,
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
    pub(super) joints: Vec<JointLaw>,
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
    /// Where the active set method cycles, try the nonsmooth Gauss–Seidel sweeps and the active
    /// set method from their statuses before Lemke's algorithm ([`super::fallback`]); set by the
    /// stepper with `energy_consistent`.
    pub(super) sweep_fallback: bool,
    /// The sweeps' impulses while the active set method is tried from them.
    pub(super) gs_saved: Vec<[f64; 3]>,
    /// Whether the joints' rows changed in the last set (see [`ContactProblem::set_again`]).
    pub(super) changed: Vec<bool>,
    /// Whether the blocks were set up once (and `up`, `low`, `wd`, `wo` agree).
    pub(super) blocks_set: bool,
}

/// Inverse of the leading `m × m` block (`m ≤ 3`) by the adjugate; `None` when the block is
/// singular to working precision (|det| below `1e-13` of the product of its rows' norms).
#[inline]
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

/// Drum `k`'s `[x, y, θ]` in a vector of `3n` (one index check per drum instead of three).
#[inline(always)]
pub(super) fn tri(v: &[f64], k: usize) -> &[f64; 3] {
    v[3 * k..3 * k + 3].try_into().expect("three entries")
}

/// [`tri`], mutable.
#[inline(always)]
pub(super) fn tri_mut(v: &mut [f64], k: usize) -> &mut [f64; 3] {
    (&mut v[3 * k..3 * k + 3])
        .try_into()
        .expect("three entries")
}

/// `x` if it is larger than `m`, else `m`: [`f64::max`] for the running maxima of the active
/// set method and the Gauss–Seidel sweeps, whose `m` is never NaN and whose values are never
/// negative zeros (absolute values, positive violations, and the Delassus diagonal, only compared
/// with zero), without its NaN handling (a NaN `x` is skipped by both).
#[inline(always)]
pub(super) fn larger(m: f64, x: f64) -> f64 {
    if x > m {
        x
    } else {
        m
    }
}

/// Whether two blocks have the same bits (not `==`: a negative zero is not a positive one).
#[inline(always)]
fn same_bits(a: &B3, b: &B3) -> bool {
    let mut diff = 0u64;
    for i in 0..3 {
        for j in 0..3 {
            diff |= a[i][j].to_bits() ^ b[i][j].to_bits();
        }
    }
    diff == 0
}

#[inline]
pub(super) fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A joint's rows for its upper drum times that drum's inverse masses, `M⁻¹ Hᵀ` row by row.
#[inline(always)]
fn scaled_rows(up: &B3, mu: &[f64; 3]) -> B3 {
    let mut mup = [[0.0; 3]; 3];
    for a in 0..3 {
        mup[a] = [up[a][0] * mu[0], up[a][1] * mu[1], up[a][2] * mu[2]];
    }
    mup
}

/// Free relative velocities of joint `k`: its rows times `v_free`.
#[inline(always)]
fn free_rates(ups: &[B3], lows: &[B3], v_free: &[f64], k: usize) -> [f64; 3] {
    let up = &ups[k];
    let vu = *tri(v_free, k);
    let mut b = [0.0; 3];
    for a in 0..3 {
        b[a] = dot3(&up[a], &vu);
    }
    if k > 0 {
        let low = &lows[k];
        let vl = *tri(v_free, k - 1);
        for a in 0..3 {
            b[a] += dot3(&low[a], &vl);
        }
    }
    b
}

/// Diagonal Delassus block of joint `k` (`mup`: its [`scaled_rows`]).
#[inline(always)]
fn diagonal_block(ups: &[B3], lows: &[B3], inv_mass: &[[f64; 3]], mup: &B3, k: usize) -> B3 {
    let up = &ups[k];
    let mut w = [[0.0; 3]; 3];
    for a in 0..3 {
        for c in a..3 {
            w[a][c] = dot3(&mup[a], &up[c]);
        }
    }
    if k > 0 {
        let low = &lows[k];
        let ml = inv_mass[k - 1];
        for a in 0..3 {
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
    w
}

/// Off-diagonal block: joint `k`'s rows (`mup`: its [`scaled_rows`]) against joint `k + 1`'s
/// rows for drum `k` (`ln`).
#[inline(always)]
fn coupling_block(mup: &B3, ln: &B3) -> B3 {
    let mut o = [[0.0; 3]; 3];
    for a in 0..3 {
        for c in 0..3 {
            o[a][c] = dot3(&mup[a], &ln[c]);
        }
    }
    o
}

impl ContactProblem {
    /// A workspace for `n` drums with the given masses and moments of inertia.
    pub fn new(masses: &[f64], inertias: &[f64]) -> ContactProblem {
        let n = masses.len();
        let mut inv_mass = Vec::with_capacity(n);
        for j in 0..n {
            inv_mass.push([1.0 / masses[j], 1.0 / masses[j], 1.0 / inertias[j]]);
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
            joints: vec![JointLaw::default(); n],
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
            sweep_fallback: false,
            gs_saved: Vec::with_capacity(n),
            changed: vec![true; n],
            blocks_set: false,
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
        self.blocks_set = true;
        // Slices of length `n`: the indices below need no checks.
        let joints = &joints[..n];
        let inv_mass = &self.inv_mass[..n];
        let (ups, lows) = (&mut self.up[..n], &mut self.low[..n]);
        let (laws, weights) = (&mut self.joints[..n], &mut self.weights[..n]);
        for k in 0..n {
            let jc = &joints[k];
            laws[k] = JointLaw {
                active: jc.active,
                bilateral: jc.bilateral,
                mu: jc.mu,
                // Classified by `solve`.
                slips: false,
                sticks: false,
            };
            let w = Self::tangent_weights(jc.active);
            weights[k] = w;
            let r = &jc.rows;
            let t = |a: [f64; 3], b: [f64; 3]| {
                [
                    w[0] * a[0] + w[1] * b[0],
                    w[0] * a[1] + w[1] * b[1],
                    w[0] * a[2] + w[1] * b[2],
                ]
            };
            ups[k] = [r[0].n_up, r[1].n_up, t(r[0].t_up, r[1].t_up)];
            lows[k] = [r[0].n_low, r[1].n_low, t(r[0].t_low, r[1].t_low)];
        }
        let (ups, lows) = (&self.up[..n], &self.low[..n]);
        let (wds, wos, bs) = (&mut self.wd[..n], &mut self.wo[..n], &mut self.b[..n]);
        for k in 0..n {
            let up = ups[k];
            let mu = inv_mass[k];
            let vu = *tri(v_free, k);
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
                let low = lows[k];
                let ml = inv_mass[k - 1];
                let vl = *tri(v_free, k - 1);
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
            wds[k] = w;
            bs[k] = b;
            // Coupling with joint k+1 through drum k.
            if k + 1 < n {
                let ln = &lows[k + 1];
                let mut o = [[0.0; 3]; 3];
                for a in 0..3 {
                    for c in 0..3 {
                        o[a][c] = dot3(&mup[a], &ln[c]);
                    }
                }
                wos[k] = o;
            }
        }
    }

    /// [`Self::set`] for a problem set up before on this workspace whose rows may have changed
    /// only in part (the stages of an impact, where only the bumps' rows move): the Delassus
    /// blocks of the joints whose rows (and, for a coupling block, the next joint's) have the
    /// same bits as at the last set are kept — the numbers the same operations would give again.
    pub(super) fn set_again(&mut self, joints: &[JointContacts], v_free: &[f64]) {
        if !self.blocks_set {
            self.set(joints, v_free);
            return;
        }
        let n = self.n;
        // Slices of length `n`: the indices below need no checks.
        let joints = &joints[..n];
        let (ups, lows) = (&mut self.up[..n], &mut self.low[..n]);
        let (laws, weights) = (&mut self.joints[..n], &mut self.weights[..n]);
        let changed = &mut self.changed[..n];
        for k in 0..n {
            let jc = &joints[k];
            laws[k] = JointLaw {
                active: jc.active,
                bilateral: jc.bilateral,
                mu: jc.mu,
                slips: false,
                sticks: false,
            };
            let w = Self::tangent_weights(jc.active);
            weights[k] = w;
            let r = &jc.rows;
            let t = |a: [f64; 3], b: [f64; 3]| {
                [
                    w[0] * a[0] + w[1] * b[0],
                    w[0] * a[1] + w[1] * b[1],
                    w[0] * a[2] + w[1] * b[2],
                ]
            };
            let up = [r[0].n_up, r[1].n_up, t(r[0].t_up, r[1].t_up)];
            let low = [r[0].n_low, r[1].n_low, t(r[0].t_low, r[1].t_low)];
            changed[k] = !(same_bits(&ups[k], &up) && same_bits(&lows[k], &low));
            ups[k] = up;
            lows[k] = low;
        }
        self.set_changed_blocks(v_free);
    }

    /// The free rates of every joint from `v_free`, and the Delassus blocks of the joints whose
    /// rows changed ([`Self::set_again`]).
    fn set_changed_blocks(&mut self, v_free: &[f64]) {
        let n = self.n;
        let inv_mass = &self.inv_mass[..n];
        let (ups, lows, changed) = (&self.up[..n], &self.low[..n], &self.changed[..n]);
        let (wds, wos, bs) = (&mut self.wd[..n], &mut self.wo[..n], &mut self.b[..n]);
        for k in 0..n {
            bs[k] = free_rates(ups, lows, v_free, k);
            let coupling = k + 1 < n && (changed[k] || changed[k + 1]);
            if !changed[k] && !coupling {
                continue;
            }
            let mup = scaled_rows(&ups[k], &inv_mass[k]);
            if changed[k] {
                wds[k] = diagonal_block(ups, lows, inv_mass, &mup, k);
            }
            if coupling {
                wos[k] = coupling_block(&mup, &lows[k + 1]);
            }
        }
    }

    /// Replaces the free relative velocities of joint `k` (e.g. by gaps, for a projection of
    /// positions: then `U = W P + b` is the gap after the displacement `M⁻¹ Hᵀ P`).
    pub fn set_offsets(&mut self, k: usize, b: [f64; 3]) {
        self.b[k] = b;
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
        let vu = *tri(v, k);
        let mut u = [0.0; 3];
        let up = &self.up[k];
        for a in 0..3 {
            u[a] = dot3(&up[a], &vu);
        }
        if k > 0 {
            let vl = *tri(v, k - 1);
            let low = &self.low[k];
            for a in 0..3 {
                u[a] += dot3(&low[a], &vl);
            }
        }
        u
    }

    /// `v = v_free + M⁻¹ Hᵀ P` (`v` holds `v_free` on entry).
    pub fn apply(&self, v: &mut [f64]) {
        let n = self.n;
        let (ps, ups, lows) = (&self.p[..n], &self.up[..n], &self.low[..n]);
        let inv_mass = &self.inv_mass[..n];
        for k in 0..n {
            let p = ps[k];
            if p == [0.0; 3] {
                continue;
            }
            let up = &ups[k];
            for i in 0..3 {
                let acc = up[0][i] * p[0] + up[1][i] * p[1] + up[2][i] * p[2];
                tri_mut(v, k)[i] += inv_mass[k][i] * acc;
            }
            if k > 0 {
                let low = &lows[k];
                for i in 0..3 {
                    let acc = low[0][i] * p[0] + low[1][i] * p[1] + low[2][i] * p[2];
                    tri_mut(v, k - 1)[i] += inv_mass[k - 1][i] * acc;
                }
            }
        }
    }
}
