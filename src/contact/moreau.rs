//! One time step of the Moreau–Jean scheme (Jean 1999; Acary & Brogliato 2008, §10.1) on a column
//! of drums in natural coordinates, with the projection that stops penetration drift (Acary 2013,
//! CMAME 256) and impacts located inside the step.
//!
//! A step of length `h` from `(t, q, v)`:
//! 1. `v_free = v + h M⁻¹ f(t + θh)`: gravity and the inertial load of the ground acceleration at
//!    `t + θh` (the loads do not depend on `q` or `v` in natural coordinates). With `θ = ½` this is
//!    the mean of a record over the step (linear between samples, steps inside sample intervals)
//!    and exact for a rectangular pulse whose ends fall on steps;
//! 2. the contact geometry at the step's midpoint, `q + θ h v`;
//! 3. the index set: the joints' ends in contact (gap below a tolerance) or predicted to close;
//! 4. one frictional contact problem ([`super::friction`]): `v⁺ = v_free + M⁻¹ Hᵀ P`, Moreau's
//!    impact law `0 ≤ U⁺_n + e U⁻_n ⊥ P_n ≥ 0` and Coulomb on each joint. At an arriving end the
//!    restitution is zero (inelastic at the corners). At a persistent contact — an end that
//!    carried an impulse in the last step and is not arriving — it is one: there `U⁻`, taken on
//!    the rows of the new midpoint, is only the turning of the contact with the drums (the
//!    centripetal drift of a pivot, `O(h)`), and the law `U⁺ + U⁻ = 0` is the midpoint rule,
//!    under which the contact does no work and the pivot stays on its face to `O(h³)` per step.
//!    With zero restitution there (plain Moreau–Jean), every step of rocking about a corner
//!    pumps `P h |Ḣ v| / 2` into the column: a first-order energy error (0.6 % of the ground work
//!    on thesis Fig. 14 at dt = 1 ms), which this removes (3e-5 there, second order);
//! 5. `q⁺ = q + h ((1 − θ) v + θ v⁺)`;
//! 6. the projection of `q⁺` in the metric `M` onto the contacts: ends that carried an impulse back
//!    onto the face they touch, penetrating ends out of it (one Newton step of the constraint,
//!    velocities unchanged).
//!
//! **Impacts located.** An end that approaches a face faster than the ground can change a
//! velocity in a step (`g h`) is not left to step 4, whose first-order timing would move the
//! column's potential energy by `m g h |U|` per impact: the step is split at the instant the end
//! reaches the face (a trial sub-step, then the root of the cubic Hermite interpolant of the gap,
//! then the sub-step again to that instant) and the impact is applied there by the impact law
//! below. Slower approaches (chattering, settling, the tail of an accumulation) stay with step 4,
//! whose error is then `O(h²)`: the accumulation is captured, not enumerated.
//!
//! **Impact law.** At an impact instant the velocities jump by the same contact problem with no
//! load (`v_free = v⁻`): the post-impact velocity is the kinetic-metric projection of `v⁻` onto
//! the admissible velocities (ends not approaching, no slip where friction holds) — with friction
//! sticking, the thesis's projection (SPEC §4), and for one block Housner's law. With more than
//! one impact per closing (`n_impacts`), the thesis's consecutive impacts (SPEC §2): a joint
//! rocking about one end and landing on the other first lands on `n_impacts − 1` equally spaced
//! bumps between them, each a projection of the same kind, then on its corner.
//!
//! Energy: with `θ = ½` a step obeys exactly `ΔT + ΔV = W_ground + Σ P·U_mid` (`U_mid` the mean of
//! the relative velocities before and after, on the step's rows), so the contact work splits into
//! the normal impulses' work at approaching ends (impacts), the tangential impulses' work
//! (friction), and the normal impulses' work at ends that were not approaching (zero at the
//! persistent contacts; what is left — an end caught while leaving its face within a step — is
//! the scheme's error); the projections move `q` against the loads (`f·Δq`). The last two are
//! the energy errors of the scheme.

use super::drums::{Drums, JointGeometry, DOF_PER_DRUM};
use super::friction::{ContactProblem, JointContacts, JointStatus, Slip, SolveFailure};
use crate::ground::GroundMotion;
use crate::model::column::Column;

/// Options of the scheme.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SchemeOptions {
    /// θ of the θ-method on velocities (½: no numerical dissipation of the free motion).
    pub theta: f64,
    /// Consecutive impacts per landing of a rocking joint (1 = Housner; 2 = one bump in the
    /// middle, the thesis's recommendation).
    pub n_impacts: u32,
    /// Locate fast impacts inside the step (see the module documentation).
    pub locate_impacts: bool,
    /// Acceleration of gravity (m/s²).
    pub gravity: f64,
}

impl Default for SchemeOptions {
    fn default() -> SchemeOptions {
        SchemeOptions {
            theta: 0.5,
            n_impacts: 1,
            locate_impacts: true,
            gravity: crate::model::column::GRAVITY,
        }
    }
}

/// Energy accounts of the scheme (J), accumulated over the steps.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct EnergyAccounts {
    /// Work of the inertial load of the ground motion along the path, `∫ −Σ m a_g dx`.
    pub ground_work: f64,
    /// Energy dissipated by the normal impulses at approaching ends (impacts).
    pub impact: f64,
    /// Energy dissipated by friction (tangential impulses).
    pub friction: f64,
    /// Work of the normal impulses at ends that were not approaching, with the sign of a
    /// dissipation: the scheme's error at persistent contacts (`O(h)` in total).
    pub persistent_contact: f64,
    /// Work of the loads on the projections' displacements (`Σ f·Δq`).
    pub projection: f64,
}

/// One impact located and applied inside a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocatedImpact {
    /// Time (s).
    pub t: f64,
    /// Joint.
    pub joint: usize,
    /// End (0 right, 1 left) that landed.
    pub end: usize,
    /// Kinetic energy before and after (J).
    pub kinetic_before: f64,
    /// Kinetic energy after (J).
    pub kinetic_after: f64,
}

/// Counters of the work done.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepCounters {
    /// Sub-steps integrated (accepted).
    pub substeps: u64,
    /// Steps taken by the rest shortcut (column closed, sticking and at rest).
    pub rest_steps: u64,
    /// Contact problems solved.
    pub solves: u64,
    /// Active-set iterations in total.
    pub iterations: u64,
    /// Problems that went to Lemke's algorithm.
    pub fallbacks: u64,
    /// Projections of the positions.
    pub projections: u64,
    /// Impacts located inside steps.
    pub located_impacts: u64,
    /// Active-set iterations of the impact problems.
    pub impact_iterations: u64,
    /// Problems whose last fallback (nonsmooth Gauss–Seidel) stopped at its cap of sweeps.
    pub inexact: u64,
}

/// Why a step failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StepError {
    /// The contact problem could not be solved.
    Contact,
    /// A drum slid off the one below (joint index): the joint has no overlap left.
    SlidOff(usize),
}

impl From<SolveFailure> for StepError {
    fn from(_: SolveFailure) -> StepError {
        StepError::Contact
    }
}

/// Landings of open ends faster than this fraction of `g h` are located inside the step.
const SPLIT_OPEN: f64 = 0.01;
/// Ends touching their face and approaching faster than this fraction of `g h` get the impact
/// law at once.
const SPLIT_TOUCHING: f64 = 0.1;

/// Most impacts located in one step.
const MAX_SPLITS: usize = 8;

/// State and workspace of the scheme for one column.
#[derive(Clone, Debug)]
pub struct Stepper {
    drums: Drums,
    mu: Vec<f64>,
    options: SchemeOptions,
    /// Time (s).
    pub t: f64,
    /// Positions `x, y, θ` per drum.
    pub q: Vec<f64>,
    /// Velocities.
    pub v: Vec<f64>,
    /// Contact statuses of the joints (warm start and the last solution).
    pub statuses: Vec<JointStatus>,
    /// Contact geometry at `q`.
    pub geometry: Vec<JointGeometry>,
    /// Normal impulses (sum of both ends) and tangential impulse of each joint in the last step.
    pub joint_impulses: Vec<[f64; 2]>,
    /// Energy accounts.
    pub energy: EnergyAccounts,
    /// Counters.
    pub counters: StepCounters,
    /// Impacts located in the last step.
    pub impacts: Vec<LocatedImpact>,
    problem: ContactProblem,
    projection: ContactProblem,
    contacts: Vec<JointContacts>,
    proj_statuses: Vec<JointStatus>,
    predicted: Vec<JointGeometry>,
    v_free: Vec<f64>,
    q_next: Vec<f64>,
    dq: Vec<f64>,
    saved: Option<Box<Saved>>,
    /// Contact tolerance on gaps (m).
    contact_gap: f64,
    /// Projection tolerance on gaps (m).
    projection_gap: f64,
    carried: Vec<[bool; 2]>,
    flags: Vec<[bool; 2]>,
    shifts: Vec<[f64; 3]>,
    landing: Vec<[bool; 2]>,
    start_rates: Vec<[[f64; 2]; 2]>,
    missed: Vec<[Option<f64>; 2]>,
    watching: bool,
    missed_found: Option<f64>,
    /// Approach speed above which a landing is located (m/s): a tenth of what gravity gives in a
    /// step.
    v_split: f64,
    v_touch: f64,
}

#[derive(Clone, Debug)]
struct Saved {
    t: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    statuses: Vec<JointStatus>,
    energy: EnergyAccounts,
    counters: StepCounters,
    joint_impulses: Vec<[f64; 2]>,
    carried: Vec<[bool; 2]>,
}

impl Stepper {
    /// A stepper for `column` with friction `mu` per joint, starting straight and at rest.
    pub fn new(column: &Column, mu: Vec<f64>, options: SchemeOptions) -> Stepper {
        let drums = Drums::new(column);
        let n = drums.len();
        assert_eq!(mu.len(), n, "one friction coefficient per joint");
        let masses: Vec<f64> = (0..n).map(|j| drums.mass(j)).collect();
        let inertias: Vec<f64> = (0..n).map(|j| drums.inertia(j)).collect();
        let mut size = f64::INFINITY;
        for j in 0..n {
            size = size.min(drums.half_height(j)).min(drums.upper_extent(j));
        }
        let q = drums.rest_positions();
        let mut s = Stepper {
            mu,
            options,
            t: 0.0,
            v: vec![0.0; DOF_PER_DRUM * n],
            statuses: vec![
                JointStatus {
                    closed: [true, true],
                    ..JointStatus::default()
                };
                n
            ],
            geometry: vec![JointGeometry::default(); n],
            joint_impulses: vec![[0.0; 2]; n],
            energy: EnergyAccounts::default(),
            counters: StepCounters::default(),
            impacts: Vec::with_capacity(MAX_SPLITS),
            problem: ContactProblem::new(&masses, &inertias),
            projection: ContactProblem::new(&masses, &inertias),
            contacts: vec![JointContacts::default(); n],
            proj_statuses: vec![JointStatus::default(); n],
            predicted: vec![JointGeometry::default(); n],
            v_free: vec![0.0; DOF_PER_DRUM * n],
            q_next: vec![0.0; DOF_PER_DRUM * n],
            dq: vec![0.0; DOF_PER_DRUM * n],
            saved: None,
            contact_gap: 1e-9 * size,
            projection_gap: 1e-10 * size,
            carried: vec![[false; 2]; n],
            flags: vec![[false; 2]; n],
            shifts: vec![[0.0; 3]; n],
            landing: vec![[false; 2]; n],
            start_rates: vec![[[0.0; 2]; 2]; n],
            missed: vec![[None; 2]; n],
            watching: false,
            missed_found: None,
            v_split: 0.0,
            v_touch: 0.0,
            q,
            drums,
        };
        s.update_geometry();
        s
    }

    /// The drums.
    pub fn drums(&self) -> &Drums {
        &self.drums
    }

    /// Friction coefficient of each joint.
    pub fn friction(&self) -> &[f64] {
        &self.mu
    }

    /// Options.
    pub fn options(&self) -> &SchemeOptions {
        &self.options
    }

    /// Gap below which an end is in contact (m).
    pub fn contact_gap(&self) -> f64 {
        self.contact_gap
    }

    /// Sets positions and velocities (e.g. from a thesis state); statuses from the gaps.
    pub fn set_state(&mut self, t: f64, q: &[f64], v: &[f64]) {
        self.t = t;
        self.q.copy_from_slice(q);
        self.v.copy_from_slice(v);
        self.update_geometry();
        for k in 0..self.drums.len() {
            let g = &self.geometry[k];
            self.statuses[k] = JointStatus {
                closed: [
                    g.ends[0].gap <= self.contact_gap,
                    g.ends[1].gap <= self.contact_gap,
                ],
                ..JointStatus::default()
            };
        }
    }

    fn update_geometry(&mut self) {
        self.drums.joints_into(&self.q, &mut self.geometry);
    }

    /// Kinetic energy (J).
    pub fn kinetic_energy(&self) -> f64 {
        self.drums.kinetic_energy(&self.v)
    }

    /// Potential energy above the straight column (J).
    pub fn potential_energy(&self) -> f64 {
        self.drums.potential_energy(&self.q, self.options.gravity)
    }

    fn at_rest(&self) -> bool {
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
    fn rest_step(&mut self, h: f64, a_theta: f64) -> bool {
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

    /// Advances by one step of length `h`.
    pub fn step(&mut self, h: f64, motion: &dyn GroundMotion) -> Result<(), StepError> {
        self.impacts.clear();
        let theta = self.options.theta;
        if self.at_rest() {
            let a = motion.acceleration(self.t + theta * h);
            if self.rest_step(h, a) {
                return Ok(());
            }
        }
        let t_end = self.t + h;
        self.v_split = SPLIT_OPEN * self.options.gravity * h;
        self.v_touch = SPLIT_TOUCHING * self.options.gravity * h;
        let mut splits = 0;
        loop {
            let remaining = t_end - self.t;
            if remaining <= 1e-12 * h {
                self.t = t_end;
                return Ok(());
            }
            if self.options.locate_impacts && splits < MAX_SPLITS {
                if let Some((tau, _)) = self.next_landing(remaining) {
                    splits += 1;
                    self.locate_and_impact(tau, remaining, motion)?;
                    continue;
                }
            }
            let watch = self.options.locate_impacts && splits < MAX_SPLITS;
            if watch {
                self.save();
                self.record_start_rates();
            }
            self.watching = watch;
            let result = self.substep(remaining, motion, None);
            self.watching = false;
            result?;
            if let Some(tau) = self.missed_found.take() {
                // A landing the linear prediction missed (the end accelerated onto its face):
                // back to the start of the sub-step, and locate it.
                self.restore();
                splits += 1;
                let mut landing = std::mem::take(&mut self.landing);
                self.missed_set(tau, remaining, &mut landing);
                let result = self.integrate_and_impact(tau, &landing, motion);
                self.landing = landing;
                result?;
                continue;
            }
            self.t = t_end;
            return Ok(());
        }
    }

    /// Gaps and normal rates of every end at the start of a sub-step (for [`Self::missed_landing`]).
    fn record_start_rates(&mut self) {
        for k in 0..self.drums.len() {
            for c in 0..2 {
                let e = &self.geometry[k].ends[c];
                let (un, _) = self.drums.rates(&e.rows, &self.v, k);
                self.start_rates[k][c] = [e.gap, un];
            }
        }
    }

    /// Root in `(0, h]` of the cubic Hermite interpolant of a gap going from `g0` (rate `u0`) to
    /// `g1 ≤ 0` (rate `u1`) over `h`.
    fn hermite_root(g0: f64, u0: f64, g1: f64, u1: f64, h: f64) -> f64 {
        let p = |s: f64| {
            let x = s / h;
            let (x2, x3) = (x * x, x * x * x);
            (2.0 * x3 - 3.0 * x2 + 1.0) * g0
                + (x3 - 2.0 * x2 + x) * h * u0
                + (-2.0 * x3 + 3.0 * x2) * g1
                + (x3 - x2) * h * u1
        };
        let (mut lo, mut hi) = (0.0, h);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if p(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    /// Ends open at the start of the last sub-step of length `h` that ended inside their face
    /// (deeper than a tenth of what the split speed covers in the step), arriving faster than the
    /// split speed: their landing instants (Hermite) into `self.missed`, the first one returned.
    fn missed_landing(&mut self, h: f64) -> Option<f64> {
        let deep = 0.1 * self.v_split * h;
        let mut best: Option<f64> = None;
        for k in 0..self.drums.len() {
            for c in 0..2 {
                let tau = self.missed_time(k, c, h, deep);
                self.missed[k][c] = tau;
                if let Some(tau) = tau {
                    if best.map_or(true, |b| tau < b) {
                        best = Some(tau);
                    }
                }
            }
        }
        best
    }

    fn missed_time(&self, k: usize, c: usize, h: f64, deep: f64) -> Option<f64> {
        let [g0, u0] = self.start_rates[k][c];
        // Only ends that the sub-step left free (its index set is still in `flags`).
        if self.flags[k][c] {
            return None;
        }
        let e = &self.geometry[k].ends[c];
        if e.gap >= -deep {
            return None;
        }
        let (u1, _) = self.drums.rates(&e.rows, &self.v, k);
        if u1 >= -self.v_split {
            return None;
        }
        Some(Self::hermite_root(g0, u0, e.gap, u1, h))
    }

    /// The missed landings within `1e-9` of the step of the first (recorded by
    /// [`Self::missed_landing`] before the restore).
    fn missed_set(&self, tau: f64, h: f64, out: &mut [[bool; 2]]) {
        for k in 0..self.drums.len() {
            for c in 0..2 {
                out[k][c] = self.missed[k][c].is_some_and(|t| t <= tau + 1e-9 * h);
            }
        }
    }

    /// Linear landing time of end `c` of joint `k` if it approaches its face faster than
    /// `v_split`: `gap / |U|`, or zero for an end already touching (its impact is due now).
    fn landing_time(&self, k: usize, c: usize, v_split: f64) -> Option<f64> {
        let e = &self.geometry[k].ends[c];
        let (un, _) = self.drums.rates(&e.rows, &self.v, k);
        if e.gap <= self.contact_gap {
            (un < -self.v_touch).then_some(0.0)
        } else {
            (un < -v_split).then(|| e.gap / -un)
        }
    }

    /// The first fast landing within `remaining`: `(τ, (joint, end))` by the linear prediction.
    fn next_landing(&self, remaining: f64) -> Option<(f64, (usize, usize))> {
        let mut best: Option<(f64, (usize, usize))> = None;
        for k in 0..self.drums.len() {
            for c in 0..2 {
                if let Some(tau) = self.landing_time(k, c, self.v_split) {
                    if tau < remaining && best.map_or(true, |(b, _)| tau < b) {
                        best = Some((tau, (k, c)));
                    }
                }
            }
        }
        best
    }

    /// Ends landing at (nearly) the time `tau`: all with linear landing time within `1e-9` of
    /// the step of the first.
    fn landing_set(&self, tau: f64, remaining: f64, out: &mut [[bool; 2]]) {
        for k in 0..self.drums.len() {
            out[k] = [false; 2];
            for c in 0..2 {
                if let Some(t) = self.landing_time(k, c, self.v_split) {
                    out[k][c] = t <= tau + 1e-9 * remaining;
                }
            }
        }
    }

    fn save(&mut self) {
        let saved = self.saved.get_or_insert_with(|| {
            Box::new(Saved {
                t: 0.0,
                q: vec![0.0; self.q.len()],
                v: vec![0.0; self.v.len()],
                statuses: vec![JointStatus::default(); self.statuses.len()],
                energy: EnergyAccounts::default(),
                counters: StepCounters::default(),
                joint_impulses: vec![[0.0; 2]; self.joint_impulses.len()],
                carried: vec![[false; 2]; self.carried.len()],
            })
        });
        saved.t = self.t;
        saved.q.copy_from_slice(&self.q);
        saved.v.copy_from_slice(&self.v);
        saved.statuses.copy_from_slice(&self.statuses);
        saved.energy = self.energy;
        saved.counters = self.counters;
        saved.joint_impulses.copy_from_slice(&self.joint_impulses);
        saved.carried.copy_from_slice(&self.carried);
    }

    fn restore(&mut self) {
        let s = self.saved.as_ref().expect("saved state");
        self.t = s.t;
        self.q.copy_from_slice(&s.q);
        self.v.copy_from_slice(&s.v);
        self.statuses.copy_from_slice(&s.statuses);
        self.energy = s.energy;
        self.counters = s.counters;
        self.joint_impulses.copy_from_slice(&s.joint_impulses);
        self.carried.copy_from_slice(&s.carried);
        self.update_geometry();
    }

    /// Integrates up to the first landing (trial, Hermite root, redo) and applies the impact.
    fn locate_and_impact(
        &mut self,
        tau: f64,
        remaining: f64,
        motion: &dyn GroundMotion,
    ) -> Result<(), StepError> {
        let mut landing = std::mem::take(&mut self.landing);
        self.landing_set(tau, remaining, &mut landing);
        let result = self.locate_and_impact_set(tau, &landing, motion);
        self.landing = landing;
        result
    }

    fn locate_and_impact_set(
        &mut self,
        tau: f64,
        landing: &[[bool; 2]],
        motion: &dyn GroundMotion,
    ) -> Result<(), StepError> {
        let n = self.drums.len();
        // The end that decides the instant: the first one.
        let (k0, c0) = (0..n)
            .flat_map(|k| (0..2).map(move |c| (k, c)))
            .find(|&(k, c)| landing[k][c])
            .expect("a landing end");
        if tau <= 0.0 {
            return self.impact(landing, motion.acceleration(self.t));
        }
        let g0 = self.geometry[k0].ends[c0].gap;
        let (u0, _) = self
            .drums
            .rates(&self.geometry[k0].ends[c0].rows, &self.v, k0);
        self.save();
        let t0 = self.t;
        self.substep(tau, motion, Some(landing))?;
        let g1 = self.geometry[k0].ends[c0].gap;
        let (u1, _) = self
            .drums
            .rates(&self.geometry[k0].ends[c0].rows, &self.v, k0);
        self.t = t0 + tau;
        if g1 > self.contact_gap {
            // Not there yet (it slowed down): keep the sub-step; the next round looks again.
            return Ok(());
        }
        let tau_star = Self::hermite_root(g0, u0, g1, u1, tau);
        // Redo the sub-step to the root unless the trial already ended on the face (to the
        // contact tolerance).
        if g1 < -self.contact_gap && (tau_star - tau).abs() > 1e-12 * tau {
            self.restore();
            self.substep(tau_star, motion, Some(landing))?;
            self.t = t0 + tau_star;
        }
        self.impact(landing, motion.acceleration(self.t))
    }

    /// From the start of a sub-step: integrate to `tau` without the landing ends, then the impact.
    fn integrate_and_impact(
        &mut self,
        tau: f64,
        landing: &[[bool; 2]],
        motion: &dyn GroundMotion,
    ) -> Result<(), StepError> {
        if tau > 0.0 {
            let t0 = self.t;
            self.substep(tau, motion, Some(landing))?;
            self.t = t0 + tau;
        }
        self.impact(landing, motion.acceleration(self.t))
    }

    fn loads(&self, a_g: f64, j: usize) -> [f64; 3] {
        let m = self.drums.mass(j);
        [-m * a_g, -m * self.options.gravity, 0.0]
    }

    /// Fills `contacts` for the ends flagged in `self.flags` with the rows of the predicted
    /// geometry.
    fn fill_contacts(&mut self) {
        for k in 0..self.drums.len() {
            let geo = &self.predicted[k];
            self.contacts[k] = JointContacts {
                active: self.flags[k],
                bilateral: [false; 2],
                rows: [geo.ends[0].rows, geo.ends[1].rows],
                mu: self.mu[k],
            };
        }
    }

    /// Adds the contact work of the solved problem to the accounts: `−P·U_mid` per row, with
    /// `U_before` the rows' rates of the velocities before. In an impact (`impact`) all of it is
    /// impact dissipation; in a step, the normal work at approaching ends and the tangential work
    /// of a sticking joint with an approaching end is, the tangential work of a slipping joint is
    /// friction, the rest is the scheme's work at persistent contacts.
    fn account_contact_work(&mut self, v_before: &[f64], impact: bool) {
        let n = self.drums.len();
        for k in 0..n {
            let p = self.problem.impulses(k);
            self.joint_impulses[k] = [p[0] + p[1], p[2]];
            if p == [0.0; 3] {
                continue;
            }
            let ua = self.problem.rates(k);
            let sh = self.shifts[k];
            let ua = [ua[0] - sh[0], ua[1] - sh[1], ua[2] - sh[2]];
            let ub = self.problem.rows_rates(k, v_before);
            let mut approaching = false;
            for c in 0..2 {
                if p[c] != 0.0 {
                    let w = -p[c] * 0.5 * (ub[c] + ua[c]);
                    if impact || ub[c] < 0.0 {
                        approaching = true;
                        self.energy.impact += w;
                    } else {
                        self.energy.persistent_contact += w;
                    }
                }
            }
            if p[2] != 0.0 {
                let w = -p[2] * 0.5 * (ub[2] + ua[2]);
                if self.statuses[k].slip != Slip::Stick {
                    self.energy.friction += w;
                } else if approaching {
                    self.energy.impact += w;
                } else {
                    self.energy.persistent_contact += w;
                }
            }
        }
    }

    /// The impact law at the current instant: the ends in contact and the `landing` ones (per
    /// joint, right and left), with the bump stages of the thesis's consecutive impacts for
    /// rocking joints; `a_g` is the ground acceleration now (for the work of the loads on the
    /// projection that follows). Used by the steps; public for the models' comparisons.
    pub fn impact(&mut self, landing: &[[bool; 2]], a_g: f64) -> Result<(), StepError> {
        let n = self.drums.len();
        let kinetic_before = self.kinetic_energy();
        let stages = self.options.n_impacts.max(1);
        self.shifts.iter_mut().for_each(|s| *s = [0.0; 3]);
        // Warm start: the landing ends close.
        for k in 0..n {
            for c in 0..2 {
                if landing[k][c] {
                    self.statuses[k].closed[c] = true;
                }
            }
        }
        let eps = self.contact_gap;
        for stage in 1..=stages {
            for k in 0..n {
                let geo = self.geometry[k];
                let mut jc = JointContacts {
                    active: [false; 2],
                    bilateral: [false; 2],
                    rows: [geo.ends[0].rows, geo.ends[1].rows],
                    mu: self.mu[k],
                };
                for c in 0..2 {
                    jc.active[c] = landing[k][c] || geo.ends[c].gap <= eps;
                }
                for c in 0..2 {
                    let p = 1 - c;
                    let rocking = landing[k][c] && !landing[k][p] && geo.ends[p].gap <= eps;
                    if rocking && stage < stages {
                        // A bump at the fraction stage/stages from the pivot towards the corner.
                        let lam = stage as f64 / stages as f64;
                        let (a, b) = (geo.ends[p].point, geo.ends[c].point);
                        let r = [a[0] + lam * (b[0] - a[0]), a[1] + lam * (b[1] - a[1])];
                        jc.rows[c] = self.drums.rows_at(&self.q, k, r, geo.ends[c].normal);
                    }
                }
                self.contacts[k] = jc;
            }
            self.v_free.copy_from_slice(&self.v);
            self.problem.set(&self.contacts, &self.v_free);
            let report = self.problem.solve(&mut self.statuses)?;
            self.counters.impact_iterations += report.iterations as u64;
            self.counters.inexact += report.inexact as u64;
            self.counters.solves += 1;
            self.counters.iterations += report.iterations as u64;
            self.counters.fallbacks += report.fallback as u64;
            let mut v = std::mem::take(&mut self.v_free);
            self.problem.apply(&mut v);
            let before = std::mem::replace(&mut self.v, v);
            self.account_contact_work(&before, true);
            self.v_free = before;
        }
        // Landed ends that hold an impulse are put back onto their faces.
        for k in 0..n {
            let p = self.problem.impulses(k);
            self.carried[k] = [p[0] > 0.0, p[1] > 0.0];
        }
        self.project(a_g, true)?;
        self.counters.located_impacts += 1;
        for k in 0..n {
            for c in 0..2 {
                if landing[k][c] {
                    self.impacts.push(LocatedImpact {
                        t: self.t,
                        joint: k,
                        end: c,
                        kinetic_before,
                        kinetic_after: self.kinetic_energy(),
                    });
                }
            }
        }
        Ok(())
    }

    /// One Moreau–Jean sub-step of length `h`; `excluded` ends are kept out of the index set (the
    /// landing ends before their located impact).
    fn substep(
        &mut self,
        h: f64,
        motion: &dyn GroundMotion,
        excluded: Option<&[[bool; 2]]>,
    ) -> Result<(), StepError> {
        let n = self.drums.len();
        let theta = self.options.theta;
        let a = motion.acceleration(self.t + theta * h);
        let a1 = motion.acceleration(self.t + h);
        // Free velocities and the geometry of the step's midpoint (θ).
        for j in 0..n {
            let f = self.loads(a, j);
            let inv = [
                1.0 / self.drums.mass(j),
                1.0 / self.drums.mass(j),
                1.0 / self.drums.inertia(j),
            ];
            for i in 0..3 {
                self.v_free[3 * j + i] = self.v[3 * j + i] + h * inv[i] * f[i];
                self.q_next[3 * j + i] = self.q[3 * j + i] + theta * h * self.v[3 * j + i];
            }
        }
        self.drums.joints_into(&self.q_next, &mut self.predicted);
        // The index set: ends touching their face and ends predicted (linearly) to close.
        let eps = self.contact_gap;
        for k in 0..n {
            for c in 0..2 {
                let e = &self.geometry[k].ends[c];
                let closing = || e.gap + h * self.drums.rates(&e.rows, &self.v, k).0 <= 0.0;
                self.flags[k][c] =
                    !excluded.is_some_and(|e| e[k][c]) && (e.gap <= eps || closing());
            }
        }
        self.fill_contacts();
        self.problem.set(&self.contacts, &self.v_free);
        // Persistent contacts: an end that carried an impulse in the last step and is not
        // arriving (faster than `v_touch`) obeys Moreau's law with restitution one,
        // `0 ≤ U⁺ + U⁻ ⊥ P ≥ 0`: its relative velocity before the step, on the rows of the
        // step's midpoint, is only the turning of the contact with the drums, and the midpoint
        // rule makes the contact do no work (Acary 2016, the energy of the θ = ½ scheme). A
        // joint that stuck likewise keeps its mean slip rate at zero. Arrivals are impacts
        // (restitution zero).
        for k in 0..n {
            let ub = self.problem.rows_rates(k, &self.v);
            let mut shift = [0.0; 3];
            for c in 0..2 {
                if self.contacts[k].active[c] && self.carried[k][c] && ub[c] >= -self.v_touch {
                    shift[c] = ub[c];
                }
            }
            if (shift[0] != 0.0 || shift[1] != 0.0) && self.statuses[k].slip == Slip::Stick {
                shift[2] = ub[2];
            }
            self.shifts[k] = shift;
            if shift != [0.0; 3] {
                let b = self.problem.free_rates(k);
                self.problem
                    .set_offsets(k, [b[0] + shift[0], b[1] + shift[1], b[2] + shift[2]]);
            }
        }
        let report = self.problem.solve(&mut self.statuses)?;
        self.counters.solves += 1;
        self.counters.iterations += report.iterations as u64;
        self.counters.fallbacks += report.fallback as u64;
        self.counters.inexact += report.inexact as u64;
        let mut v_new = std::mem::take(&mut self.v_free);
        self.problem.apply(&mut v_new);
        // A column closed and sticking everywhere comes to rest (H v = 0 with H invertible):
        // the velocities left by the persistent contacts' law are removed, their energy booked
        // as impact dissipation.
        let all_stuck = (0..n).all(|k| {
            self.contacts[k].active == [true, true]
                && self.statuses[k].closed == [true, true]
                && self.statuses[k].slip == Slip::Stick
        });
        if all_stuck {
            self.energy.impact += self.drums.kinetic_energy(&v_new);
            v_new.iter_mut().for_each(|x| *x = 0.0);
        }
        // Positions, ground work, contact work.
        let mut work = 0.0;
        for j in 0..n {
            for i in 0..3 {
                let vt = (1.0 - theta) * self.v[3 * j + i] + theta * v_new[3 * j + i];
                self.q_next[3 * j + i] = self.q[3 * j + i] + h * vt;
            }
            let dx = self.q_next[3 * j] - self.q[3 * j];
            work += -self.drums.mass(j) * a * dx;
        }
        self.energy.ground_work += work;
        let before = std::mem::replace(&mut self.v, v_new);
        self.account_contact_work(&before, false);
        self.v_free = before;
        std::mem::swap(&mut self.q, &mut self.q_next);
        // Ends that carried an impulse go back onto their faces.
        for k in 0..n {
            let st = self.statuses[k];
            let p = self.problem.impulses(k);
            self.carried[k] = [
                self.contacts[k].active[0] && st.closed[0] && p[0] > 0.0,
                self.contacts[k].active[1] && st.closed[1] && p[1] > 0.0,
            ];
        }
        self.t += h;
        self.update_geometry();
        if self.watching {
            if let Some(tau) = self.missed_landing(h) {
                self.missed_found = Some(tau);
                return Ok(());
            }
        }
        self.project(a1, true)?;
        self.counters.substeps += 1;
        Ok(())
    }

    /// Geometry at `q` (unless `fresh`: already computed), then, if some carried end is off its
    /// face or some end penetrates, the projection of `q` in the metric `M` (one linearised
    /// step). `a_g` is the ground acceleration for the work of the loads on the displacement.
    fn project(&mut self, a_g: f64, fresh: bool) -> Result<(), StepError> {
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
