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

pub use super::accounts::{EnergyAccounts, StepCounters};
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
    /// Restitution one at persistent contacts (step 4). `false`: zero everywhere, plain
    /// Moreau–Jean (Siconos' `NewtonImpactFrictionNSL` with e = 0), for comparisons only.
    pub persistent_restitution: bool,
    /// Project positions back onto the contacts after each step (step 6). `false`: no
    /// projection (the drums sink `O(g h²)` into each other), for comparisons only.
    pub project: bool,
    /// Acceleration of gravity (m/s²).
    pub gravity: f64,
    /// Opt-in error control ([`super::refine`]): a step whose own energy error exceeds this
    /// fraction of the run's energy scale is redone as two half steps. `None`: off.
    pub energy_tolerance: Option<f64>,
    /// Opt-in: remove the one-signed energy errors of the located impacts at their source
    /// ([`super::consistent`]): the persistent contacts keep their law through an impact (and
    /// every end on its face and not approaching has it), the trial sub-step of a landing is read
    /// before its projection, the other ends landing in it
    /// are located too, up to [`super::consistent::MAX_SPLITS`] impacts a step, the ends within
    /// [`super::consistent::IMPACT_GAP`]` · g h²` of their face take part in a located impact,
    /// and a slip that stops within a step is booked as friction. `false` (the default): the
    /// scheme as before.
    pub energy_consistent: bool,
    /// Opt-in: condense the drums stuck together into rigid clusters for the step's problem,
    /// checked and otherwise redone in full ([`super::clusters`]). `false`: the scheme as before.
    pub clusters: bool,
}

impl Default for SchemeOptions {
    fn default() -> SchemeOptions {
        SchemeOptions {
            theta: 0.5,
            n_impacts: 1,
            locate_impacts: true,
            persistent_restitution: true,
            project: true,
            gravity: crate::model::column::GRAVITY,
            energy_tolerance: None,
            energy_consistent: false,
            clusters: false,
        }
    }
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
pub(super) const SPLIT_OPEN: f64 = 0.01;
/// Ends touching their face and approaching faster than this fraction of `g h` get the impact
/// law at once.
pub(super) const SPLIT_TOUCHING: f64 = 0.1;

/// Most impacts located in one step.
pub(super) const MAX_SPLITS: usize = 8;

/// State and workspace of the scheme for one column.
#[derive(Clone, Debug)]
pub struct Stepper {
    pub(super) drums: Drums,
    pub(super) mu: Vec<f64>,
    pub(super) options: SchemeOptions,
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
    pub(super) problem: ContactProblem,
    pub(super) projection: ContactProblem,
    pub(super) contacts: Vec<JointContacts>,
    pub(super) proj_statuses: Vec<JointStatus>,
    pub(super) predicted: Vec<JointGeometry>,
    pub(super) v_free: Vec<f64>,
    pub(super) q_next: Vec<f64>,
    pub(super) dq: Vec<f64>,
    pub(super) saved: Option<Box<super::landing::Saved>>,
    /// Contact tolerance on gaps (m).
    pub(super) contact_gap: f64,
    /// Projection tolerance on gaps (m).
    pub(super) projection_gap: f64,
    pub(super) carried: Vec<[bool; 2]>,
    pub(super) flags: Vec<[bool; 2]>,
    pub(super) shifts: Vec<[f64; 3]>,
    /// Rates `(U_R, U_L, U_t)` of the velocities before a sub-step's problem on its rows (the
    /// persistent contacts' law and the contact work read the same numbers).
    pub(super) rates_before: Vec<[f64; 3]>,
    pub(super) landing: Vec<[bool; 2]>,
    /// Gap and normal rate of every end at the start of the sub-step (see `rates_fresh`).
    pub(super) start_rates: Vec<[[f64; 2]; 2]>,
    /// Whether `start_rates` are those of the current state: set at the top of every round of
    /// [`Stepper::step`], cleared when a sub-step begins to change the state. The landing
    /// predictions, the index set and the missed-landing check then share one computation of the
    /// rates (the same function of the same state: the same numbers).
    pub(super) rates_fresh: bool,
    pub(super) missed: Vec<[Option<f64>; 2]>,
    /// With `energy_consistent`: the sub-step leaves its positions unprojected (a landing's
    /// trial, whose gap is read first), and the joints slipping before the sub-step's problem.
    pub(super) skip_projection: bool,
    pub(super) slipping_before: Vec<bool>,
    /// With `energy_consistent`: the persistent ends before an impact (see
    /// [`super::consistent`]).
    pub(super) carried_before_impact: Vec<[bool; 2]>,
    /// With `energy_consistent`: the ends landing first in a landing's trial.
    pub(super) located_first: Vec<[bool; 2]>,
    pub(super) watching: bool,
    pub(super) missed_found: Option<f64>,
    /// Approach speed above which a landing is located (m/s): a tenth of what gravity gives in a
    /// step.
    pub(super) v_split: f64,
    pub(super) v_touch: f64,
    /// Gap (m) within which an end takes part in a located impact: the contact tolerance, and
    /// with `energy_consistent` [`super::consistent::IMPACT_GAP`]` · g h²` if larger.
    pub(super) impact_gap: f64,
    /// Gap (m) within which an end counts as touching in a sub-step (index set, landing
    /// prediction): the contact tolerance, or the projection's in a retry of the error control
    /// ([`super::refine`], `slow_landings`).
    pub(super) touch_gap: f64,
    /// Set by the error control for its retries with `energy_consistent`: every landing located.
    pub(super) slow_landings: bool,
    pub(super) cluster_work: Option<Box<super::clusters::ClusterWork>>,
    /// Condensed steps ([`SchemeOptions::clusters`]).
    pub cluster_counters: super::clusters::ClusterCounters,
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
            rates_before: vec![[0.0; 3]; n],
            landing: vec![[false; 2]; n],
            start_rates: vec![[[0.0; 2]; 2]; n],
            rates_fresh: false,
            missed: vec![[None; 2]; n],
            skip_projection: false,
            slipping_before: vec![false; n],
            carried_before_impact: vec![[false; 2]; n],
            located_first: vec![[false; 2]; n],
            watching: false,
            missed_found: None,
            v_split: 0.0,
            v_touch: 0.0,
            impact_gap: 0.0,
            touch_gap: 1e-9 * size,
            slow_landings: false,
            cluster_work: options
                .clusters
                .then(|| Box::new(super::clusters::ClusterWork::new(&masses, &inertias))),
            cluster_counters: Default::default(),
            q,
            drums,
        };
        s.problem.sweep_fallback = options.energy_consistent;
        s.projection.sweep_fallback = options.energy_consistent;
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
        self.rates_fresh = false;
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

    pub(super) fn update_geometry(&mut self) {
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
        let max_splits = if self.options.energy_consistent {
            let g = self.options.gravity;
            self.impact_gap = self
                .contact_gap
                .max(super::consistent::IMPACT_GAP * g * h * h);
            super::consistent::MAX_SPLITS
        } else {
            self.impact_gap = self.contact_gap;
            MAX_SPLITS
        };
        self.locate_slow_landings(h);
        loop {
            let remaining = t_end - self.t;
            if remaining <= 1e-12 * h {
                self.t = t_end;
                return Ok(());
            }
            self.record_start_rates();
            if self.options.locate_impacts && splits < max_splits {
                if let Some((tau, _)) = self.next_landing(remaining) {
                    splits += 1;
                    self.locate_and_impact(tau, remaining, motion)?;
                    continue;
                }
            }
            let watch = self.options.locate_impacts && splits < max_splits;
            if watch {
                self.save();
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

    pub(super) fn loads(&self, a_g: f64, j: usize) -> [f64; 3] {
        let m = self.drums.mass(j);
        [-m * a_g, -m * self.options.gravity, 0.0]
    }

    /// Fills `contacts` for the ends flagged in `self.flags` with the rows of the predicted
    /// geometry.
    pub(super) fn fill_contacts(&mut self) {
        for k in 0..self.drums.len() {
            // Field by field: the rows move in place instead of through a temporary.
            let geo = &self.predicted[k];
            let c = &mut self.contacts[k];
            c.active = self.flags[k];
            c.bilateral = [false; 2];
            c.rows[0] = geo.ends[0].rows;
            c.rows[1] = geo.ends[1].rows;
            c.mu = self.mu[k];
        }
    }

    /// Whether end `c` of joint `k` enters the index set of a sub-step of length `h`: touching
    /// its face (gap within the touch gap) or predicted, linearly from its normal rate at the
    /// start of the sub-step, to close within it; never an `excluded` end. The full and the
    /// condensed sub-steps (`clusters.rs`) take the same set.
    pub(super) fn in_index_set(
        &self,
        k: usize,
        c: usize,
        h: f64,
        excluded: Option<&[[bool; 2]]>,
    ) -> bool {
        let e = &self.geometry[k].ends[c];
        let un = || {
            if self.rates_fresh {
                self.start_rates[k][c][1]
            } else {
                self.drums.rates(&e.rows, &self.v, k).0
            }
        };
        !excluded.is_some_and(|e| e[k][c]) && (e.gap <= self.touch_gap || e.gap + h * un() <= 0.0)
    }

    /// One Moreau–Jean sub-step of length `h`; `excluded` ends are kept out of the index set (the
    /// landing ends before their located impact).
    pub(super) fn substep(
        &mut self,
        h: f64,
        motion: &dyn GroundMotion,
        excluded: Option<&[[bool; 2]]>,
    ) -> Result<(), StepError> {
        if self.options.clusters && self.condensed_substep(h, motion, excluded)? {
            return Ok(());
        }
        let n = self.drums.len();
        let theta = self.options.theta;
        let a = motion.acceleration(self.t + theta * h);
        let a1 = motion.acceleration(self.t + h);
        // Free velocities and the geometry of the step's midpoint (θ).
        {
            // Per drum `[x, y, θ]`; the inverse masses are the problem's (the same quotients).
            let inv_mass = &self.problem.inv_mass[..n];
            let drums = self
                .v
                .chunks_exact(3)
                .zip(self.q.chunks_exact(3))
                .zip(self.v_free.chunks_exact_mut(3))
                .zip(self.q_next.chunks_exact_mut(3));
            for (j, (((v, q), v_free), q_next)) in drums.enumerate().take(n) {
                let m = self.drums.mass(j);
                let f = [-m * a, -m * self.options.gravity, 0.0];
                let inv = inv_mass[j];
                for i in 0..3 {
                    v_free[i] = v[i] + h * inv[i] * f[i];
                    q_next[i] = q[i] + theta * h * v[i];
                }
            }
        }
        // Only its rows are read (`fill_contacts`).
        self.drums
            .joints_rows_into(&self.q_next, &mut self.predicted);
        // The index set: ends touching their face and ends predicted (linearly) to close.
        for k in 0..n {
            for c in 0..2 {
                self.flags[k][c] = self.in_index_set(k, c, h, excluded);
            }
        }
        self.rates_fresh = false;
        self.fill_contacts();
        self.problem.set(&self.contacts, &self.v_free);
        // Persistent contacts: an end that carried an impulse in the last step and is not
        // arriving (faster than `v_touch`) — with `energy_consistent`, also an end on its face
        // and not approaching, whether it carried an impulse or not — obeys Moreau's law with
        // restitution one,
        // `0 ≤ U⁺ + U⁻ ⊥ P ≥ 0`: its relative velocity before the step, on the rows of the
        // step's midpoint, is only the turning of the contact with the drums, and the midpoint
        // rule makes the contact do no work (Acary 2016, the energy of the θ = ½ scheme). A
        // joint that stuck likewise keeps its mean slip rate at zero. Arrivals are impacts
        // (restitution zero).
        for k in 0..n {
            let ub = self.problem.rows_rates(k, &self.v);
            self.rates_before[k] = ub;
            let mut shift = [0.0; 3];
            for c in 0..2 {
                if self.options.persistent_restitution
                    && self.contacts[k].active[c]
                    && ((self.carried[k][c] && ub[c] >= -self.v_touch)
                        || (self.options.energy_consistent
                            && ub[c] >= 0.0
                            && self.geometry[k].ends[c].gap <= self.touch_gap))
                {
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
        if self.options.energy_consistent {
            for (was, st) in self.slipping_before.iter_mut().zip(&self.statuses) {
                *was = st.slip != Slip::Stick;
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
        // With `energy_consistent` the step is finished with the solved velocities and they are
        // removed at its end (a velocity jump at fixed positions, whose energy is exactly the
        // kinetic energy booked): the persistent law keeps through impacts velocities that are
        // not round-off, and removing them before the positions are advanced would leave the
        // identity short of `f·h v/2` (see `super::consistent`).
        let snap_at_end = all_stuck && self.options.energy_consistent;
        if all_stuck && !snap_at_end {
            self.energy.impact += self.drums.kinetic_energy(&v_new);
            v_new.iter_mut().for_each(|x| *x = 0.0);
        }
        // Positions, ground work, contact work.
        let mut work = 0.0;
        {
            let drums = self
                .v
                .chunks_exact(3)
                .zip(v_new.chunks_exact(3))
                .zip(self.q.chunks_exact(3))
                .zip(self.q_next.chunks_exact_mut(3));
            for (j, (((v, v_new), q), q_next)) in drums.enumerate().take(n) {
                for i in 0..3 {
                    let vt = (1.0 - theta) * v[i] + theta * v_new[i];
                    q_next[i] = q[i] + h * vt;
                }
                let dx = q_next[0] - q[0];
                work += -self.drums.mass(j) * a * dx;
            }
        }
        self.energy.ground_work += work;
        let before = std::mem::replace(&mut self.v, v_new);
        self.account_contact_work(None, false);
        self.v_free = before;
        if snap_at_end {
            self.energy.impact += self.drums.kinetic_energy(&self.v);
            self.v.iter_mut().for_each(|x| *x = 0.0);
        }
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
        if self.options.project && !self.skip_projection {
            self.project(a1, true)?;
        }
        self.counters.substeps += 1;
        Ok(())
    }
}
