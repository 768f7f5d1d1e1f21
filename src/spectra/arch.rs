//! Spectra of voussoir arches (issue 15, item 5; the OC in `arch_oc.rs`): the overturning curve (OC) of an arch under
//! pulses and the overturning acceleration spectrum (OAS) of an arch for a record, through the
//! loop driver ([`crate::driver::simulate_loop`]). *Unsafe* is the loop driver's collapse (the
//! mechanism past its point of no return, `docs/arches.md` 2b).
//!
//! Axes. An arch family is an [`ArchShape`] (`t/R`, embrace angle, voussoirs); its size is the
//! radius `R` of the centre line. The level is `a_p / (λ g)`, `λ` the static collapse multiplier
//! of the discrete arch (the smallest horizontal ground acceleration, in g, at which the opening
//! model moves the closed arch at rest: limit analysis with hinges at joints, `docs/arches.md`
//! §1). `λ` does not depend on `R` (every force scales with the weight).
//!
//! The frequency parameter `p` of an arch is that of its onset mechanism (the four-hinge
//! mechanism of limit analysis, DeJong's one-DOF mechanism): with `u` the mechanism's rate
//! direction at the onset (the opening model's acceleration at `λ (1 + 10⁻⁶)`), the mechanism
//! coordinate `s` (`v = ṡ u`, `u` scaled so that `s` is DeJong's `θ`, the rotation of the
//! first segment about its hinge A, the first open joint in chain order) of the closed arch at
//! rest obeys `s̈ = −(p²/g) (a_g + λ g)` with `p² = g |uᵀ ∂q/∂a_g| / (uᵀ M u)`: the equation of a slender block at rest (`θ̈ = −(p²/g)
//! (a_g + a_p,min)`, `cos α ≈ 1`). It scales as `√(g/R)`: `p = p₁ / √R`, `p₁` its value at
//! `R = 1 m`.
//!
//! Early stops (both exact): a scaled record whose peak stays at or below `λ g` never moves the
//! arch (no run); a run stops once the arch is closed and at rest after the last exceedance
//! ([`LoopOptions::quiet_after`]: the closed arch resists every `|a_g| ≤ λ g` — the
//! resisted accelerations form an interval, each mechanism's power being linear in `a_g` — so it
//! never moves again). No energy bound is used: the collapse of a multi-DOF mechanism has no
//! barrier height computed here.

use super::oas::{exceedance_window, linear_levels, log_sizes, OasLevel, OasPoint};
use super::sweep::map_indexed;
use super::{invalid, Progress, SpectraError, TimeStep};
use crate::chain::arch::VoussoirArch;
use crate::chain::Chain;
use crate::driver::closed::{simulate_loop, LoopOptions, LoopState};
use crate::ground::records::Record;
use crate::ground::GroundMotion;
use crate::model::cone::ModelOptions;
use crate::model::configuration::Status;
use crate::model::constrained::opening_model_constrained;
use crate::validate::{all_positive, non_negative, positive};

/// An arch family: everything but its size (the centre-line radius `R`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ArchShape {
    /// `t/R`.
    pub thickness_ratio: f64,
    /// Angle of embrace `2β` (rad; `π`: semicircular).
    pub embrace_angle: f64,
    /// Number of voussoirs.
    pub voussoirs: usize,
}

impl Default for ArchShape {
    /// The arch of `docs/arches.md`: semicircular, `t/R = 0.15`, 20 voussoirs.
    fn default() -> ArchShape {
        ArchShape {
            thickness_ratio: 0.15,
            embrace_angle: std::f64::consts::PI,
            voussoirs: 20,
        }
    }
}

impl ArchShape {
    /// The arch of radius `radius` (density 2000 kg/m³, unit depth: the verdicts do not depend
    /// on them).
    pub fn arch(&self, radius: f64) -> VoussoirArch {
        VoussoirArch {
            radius,
            thickness: self.thickness_ratio * radius,
            embrace_angle: self.embrace_angle,
            voussoirs: self.voussoirs,
            density: 2000.0,
            depth: 1.0,
        }
    }

    /// The loop of radius `radius`.
    pub fn chain(&self, radius: f64) -> Result<Chain, SpectraError> {
        positive("radius", radius)?;
        Ok(self.arch(radius).chain()?)
    }
}

/// The static onset of an arch family: `λ`, the onset mechanism and its `p` at `R = 1 m`.
#[derive(Clone, Debug, PartialEq)]
pub struct ArchOnset {
    /// `λ`: the largest `|a_g| / g` found resisted by the closed arch at rest in either
    /// direction (bisection to 1e-12 relative; the arch opens at `λ (1 + 10⁻¹²)`).
    pub lambda: f64,
    /// The joints' statuses of the onset mechanism under `a_g = −λ (1 + 10⁻⁶) g` (pushing +x).
    pub hinges: Vec<Status>,
    /// `p` of the onset mechanism at `R = 1 m` (1/s); `p = p₁ / √R`.
    pub p_unit: f64,
}

impl ArchOnset {
    /// `p` of the arch of radius `radius` (1/s).
    pub fn p(&self, radius: f64) -> f64 {
        self.p_unit / radius.sqrt()
    }
}

/// The opening model on the closed `chain` at rest under `ag`: its statuses and accelerations.
fn onset_answer(
    chain: &Chain,
    ag: f64,
    gravity: f64,
    model: &ModelOptions,
) -> Result<(Vec<Status>, Vec<f64>), SpectraError> {
    let phi = vec![0.0; chain.n_dofs()];
    let pose = chain.pose(&phi);
    let mass = chain.mass_matrix(&pose);
    let load = chain.load_vector(&pose, ag, gravity);
    let g = chain.closure_matrix(&pose);
    let mut statuses = vec![Status::Closed; chain.n_joints()];
    let mut acc = vec![0.0; chain.n_dofs()];
    opening_model_constrained(&mass, &load, &g, None, &mut statuses, &mut acc, model)
        .map_err(|e| SpectraError::Loop(e.to_string()))?;
    Ok((statuses, acc))
}

/// `λ`, the onset mechanism and its `p` (see the module's documentation) of `shape`.
pub fn arch_onset(
    shape: &ArchShape,
    gravity: f64,
    model: &ModelOptions,
) -> Result<ArchOnset, SpectraError> {
    positive("gravity", gravity)?;
    shape.arch(1.0).runnable()?;
    onset_of(&shape.chain(1.0)?, gravity, model)
}

/// [`arch_onset`] of the arch `chain` (its `p_unit` is then its own `p`).
pub(super) fn onset_of(
    chain: &Chain,
    gravity: f64,
    model: &ModelOptions,
) -> Result<ArchOnset, SpectraError> {
    let opens = |ag: f64| -> Result<bool, SpectraError> {
        Ok(onset_answer(chain, ag, gravity, model)?
            .1
            .iter()
            .any(|&a| a != 0.0))
    };
    if opens(0.0)? {
        return Err(invalid(
            "arch",
            "the arch does not stand under its own weight (thinner than the minimum)",
        ));
    }
    let mut lambda = f64::INFINITY;
    for sign in [-1.0, 1.0] {
        let (mut lo, mut hi) = (0.0, 0.01);
        while !opens(sign * hi * gravity)? {
            lo = hi;
            hi *= 2.0;
            if hi > 1e3 {
                return Err(invalid(
                    "arch",
                    "does not open under any horizontal ground acceleration up to 1000 g: no \
                     collapse multiplier λ, no spectrum (a shallow arch thick enough to hold a \
                     thrust line under any load; the embrace angle is in degrees)",
                ));
            }
        }
        while hi - lo > 1e-12 * hi {
            let mid = 0.5 * (lo + hi);
            if opens(sign * mid * gravity)? {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lambda = lambda.min(lo);
    }
    let ag = -lambda * (1.0 + 1e-6) * gravity;
    let (hinges, mut u) = onset_answer(chain, ag, gravity, model)?;
    // DeJong's coordinate: the rotation of the first segment about its hinge A (the first open
    // joint in chain order), whose rate is that joint's DOF rate (the abutment is fixed).
    let n = chain.n_joints();
    let a = (0..n)
        .find_map(|k| hinges[k].dof(k, n))
        .ok_or_else(|| invalid("arch", "no onset mechanism"))?;
    let scale = u[a];
    u.iter_mut().for_each(|x| *x /= scale);
    let pose = chain.pose(&vec![0.0; chain.n_dofs()]);
    let mass = chain.mass_matrix(&pose);
    let m = chain.n_dofs();
    let q1 = chain.load_vector(&pose, 1.0, gravity);
    let q0 = chain.load_vector(&pose, 0.0, gravity);
    let kinetic: f64 = (0..m)
        .map(|a| u[a] * (0..m).map(|b| mass[a * m + b] * u[b]).sum::<f64>())
        .sum();
    let coupling: f64 = (0..m).map(|a| u[a] * (q1[a] - q0[a])).sum();
    Ok(ArchOnset {
        lambda,
        hinges,
        p_unit: (gravity * coupling.abs() / kinetic).sqrt(),
    })
}

/// Options of the arch sweeps (OC and OAS).
#[derive(Clone, Debug)]
pub struct ArchSweepOptions {
    /// The arch family.
    pub shape: ArchShape,
    /// Template of every run (gravity, models, settling, locking); `dt`, `duration` and
    /// `quiet_after` are set per run, `record_every` is 0.
    pub simulation: LoopOptions,
    /// Time step rule, with the arch's `p` for the block's.
    pub time_step: TimeStep,
    /// Simulated time after the motion ends, in units of `1/p`.
    pub tail: f64,
}

impl Default for ArchSweepOptions {
    fn default() -> ArchSweepOptions {
        ArchSweepOptions {
            shape: ArchShape::default(),
            simulation: LoopOptions::default(),
            time_step: TimeStep::default(),
            tail: 2.0,
        }
    }
}

impl ArchSweepOptions {
    pub(super) fn validate(&self) -> Result<(), SpectraError> {
        self.time_step.validate()?;
        non_negative("tail", self.tail)?;
        positive("shape.thickness_ratio", self.shape.thickness_ratio)?;
        self.shape.arch(1.0).validate()?;
        Ok(())
    }

    /// The loop options of one run.
    pub(super) fn run(&self, dt: f64, duration: f64, quiet_after: Option<f64>) -> LoopOptions {
        LoopOptions {
            dt,
            duration,
            quiet_after,
            record_every: 0,
            ..self.simulation.clone()
        }
    }
}

/// What one run of a sweep found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArchRun {
    /// The loop driver reported a collapse.
    pub collapsed: bool,
    /// A simulation was run (`false`: the motion never reaches `λ g`, the arch never moves).
    pub simulated: bool,
    /// Events of the run.
    pub events: usize,
    /// Simulated time (s).
    pub simulated_time: f64,
    /// Largest joint angle of the run (rad).
    pub peak_angle: f64,
}

impl ArchRun {
    pub(super) const NEVER_MOVES: ArchRun = ArchRun {
        collapsed: false,
        simulated: false,
        events: 0,
        simulated_time: 0.0,
        peak_angle: 0.0,
    };
}

/// A record scaled by `factor`.
struct ScaledRecord<'a> {
    record: &'a Record,
    factor: f64,
}

impl GroundMotion for ScaledRecord<'_> {
    fn acceleration(&self, t: f64) -> f64 {
        self.factor * self.record.acceleration(t)
    }
    fn end_time(&self) -> f64 {
        self.record.duration()
    }
}

/// The arch of radius `radius` under `record` scaled to peak `level · λ g`, from rest.
pub fn arch_record_run(
    record: &Record,
    onset: &ArchOnset,
    level: f64,
    radius: f64,
    options: &ArchSweepOptions,
) -> Result<ArchRun, SpectraError> {
    let pga = record.pga();
    if pga.is_nan() || pga <= 0.0 {
        return Err(invalid("record", format!("`{}` has zero PGA", record.name)));
    }
    let g = options.simulation.gravity;
    let factor = level * onset.lambda * g / pga;
    // The peak at or below λ g: resisted throughout (exact).
    if level <= 1.0 {
        return Ok(ArchRun::NEVER_MOVES);
    }
    let Some((_, t_last)) = exceedance_window(record, factor, onset.lambda * g) else {
        return Ok(ArchRun::NEVER_MOVES);
    };
    let p = onset.p(radius);
    // From t = 0, not from the first exceedance: the driver skips the quiet start at no cost
    // (its resisted interval), and the motion is then bit for bit the record's. Started at the
    // sample before the first exceedance (the same motion up to the rounding of `t + t0`), the
    // verdict of a run that rattles can differ: the bundled record at level 2 on the 8-voussoir
    // arch of 5 m collapses that way and survives from t = 0.
    let motion = ScaledRecord { record, factor };
    let dt = options.time_step.dt(Some(record.dt), None, p);
    let run = options.run(dt, motion.end_time() + options.tail / p, Some(t_last));
    let chain = options.shape.chain(radius)?;
    run_loop(&chain, &motion, &run)
}

pub(super) fn run_loop(
    chain: &Chain,
    motion: &dyn GroundMotion,
    run: &LoopOptions,
) -> Result<ArchRun, SpectraError> {
    let out = simulate_loop(chain, motion, LoopState::at_rest(chain), run)
        .map_err(|e| SpectraError::Loop(e.to_string()))?;
    Ok(ArchRun {
        collapsed: out.collapsed,
        simulated: true,
        events: out.events.len(),
        simulated_time: out.state.time,
        peak_angle: out.peak_angle,
    })
}

/// Options of an arch OAS.
#[derive(Clone, Debug)]
pub struct ArchOasOptions {
    /// Levels `a_p / (λ g)`.
    pub levels: Vec<f64>,
    /// Radii `R` (m), strictly decreasing: each level is scanned from the largest down and
    /// stops at the first that collapses (the thesis's scan).
    pub sizes: Vec<f64>,
    /// The family and the runs.
    pub sweep: ArchSweepOptions,
}

impl Default for ArchOasOptions {
    /// 10 levels from 1.5 to 6, 12 radii log-spaced from 100 m to 1 m.
    fn default() -> ArchOasOptions {
        ArchOasOptions {
            levels: linear_levels(1.5, 6.0, 10),
            sizes: log_sizes(100.0, 1.0, 12),
            sweep: ArchSweepOptions::default(),
        }
    }
}

/// The OAS of an arch family for a record.
#[derive(Clone, Debug, PartialEq)]
pub struct ArchOas {
    pub record: String,
    pub shape: ArchShape,
    pub onset: ArchOnset,
    /// Radii (m), descending. A level's scan goes past a radius whose run failed (recorded in
    /// `runs.failures`), so `largest_unsafe` is the largest radius found to collapse.
    pub sizes: Vec<f64>,
    pub levels: Vec<OasLevel>,
    pub gravity: f64,
    /// Runs that collapsed / survived / were skipped (the record never reaches `λ g`), and the
    /// simulated time of all runs (s).
    pub runs: ArchRunCounts,
}

/// How many runs an arch sweep took, and the runs the loop driver failed on (no verdict).
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ArchRunCounts {
    pub collapsed: usize,
    pub survived: usize,
    pub never_moved: usize,
    pub events: usize,
    pub simulated_time: f64,
    /// Every collapse: level, radius (OC: `t_p`), the time and the run's peak joint angle
    /// (a collapse at a peak of micro-radians is the loop driver's criterion firing while the
    /// arch rattles nearly closed; see `docs/arches.md`).
    pub collapses: Vec<ArchCollapse>,
    pub failures: Vec<ArchFailure>,
}

/// A run that collapsed.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ArchCollapse {
    pub level: f64,
    pub radius: f64,
    pub time: f64,
    pub peak_angle: f64,
}

/// A run the loop driver failed on: its level, radius (for an OC: the pulse's `t_p`) and error.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ArchFailure {
    pub level: f64,
    pub radius: f64,
    pub message: String,
}

impl ArchRunCounts {
    pub(super) fn add(&mut self, r: &ArchRun, level: f64, radius: f64) {
        if r.collapsed {
            self.collapses.push(ArchCollapse {
                level,
                radius,
                time: r.simulated_time,
                peak_angle: r.peak_angle,
            });
        }
        match (r.simulated, r.collapsed) {
            (false, _) => self.never_moved += 1,
            (true, true) => self.collapsed += 1,
            (true, false) => self.survived += 1,
        }
        self.events += r.events;
        self.simulated_time += r.simulated_time;
    }

    /// Adds the counts of `o` (the next level of an OAS: [`arch_oas`] merges its levels'
    /// counts in level order).
    pub fn merge(&mut self, o: &ArchRunCounts) {
        self.collapsed += o.collapsed;
        self.survived += o.survived;
        self.never_moved += o.never_moved;
        self.events += o.events;
        self.simulated_time += o.simulated_time;
        self.collapses.extend(o.collapses.iter().cloned());
        self.failures.extend(o.failures.iter().cloned());
    }
}

/// The OAS of the arch family of `options` for `record`, parallel over levels with the
/// `parallel` feature.
pub fn arch_oas(
    record: &Record,
    options: &ArchOasOptions,
    progress: Option<Progress<'_>>,
) -> Result<ArchOas, SpectraError> {
    options.sweep.validate()?;
    record.validate()?;
    all_positive("levels", &options.levels)?;
    if options.sizes.is_empty() {
        return Err(invalid("sizes", "needs at least one size"));
    }
    all_positive("sizes", &options.sizes)?;
    if options.sizes.windows(2).any(|w| w[1] >= w[0]) {
        return Err(invalid(
            "sizes",
            "must be strictly decreasing (largest first)",
        ));
    }
    let sim = &options.sweep.simulation;
    let onset = arch_onset(&options.sweep.shape, sim.gravity, &sim.model)?;
    let per_level = map_indexed(options.levels.len(), |k| {
        let level = options.levels[k];
        let mut counts = ArchRunCounts::default();
        let mut found = None;
        for (i, &r) in options.sizes.iter().enumerate() {
            let run = match arch_record_run(record, &onset, level, r, &options.sweep) {
                Ok(run) => run,
                // The loop driver failed on this run: no verdict; recorded, the scan goes on.
                Err(SpectraError::Loop(message)) => {
                    counts.failures.push(ArchFailure {
                        level,
                        radius: r,
                        message,
                    });
                    continue;
                }
                Err(e) => return Err(e),
            };
            counts.add(&run, level, r);
            if run.collapsed {
                found = Some(i);
                break;
            }
            if !run.simulated {
                break; // no radius moves at this level
            }
        }
        if let Some(p) = progress {
            p();
        }
        Ok::<_, SpectraError>((
            OasLevel {
                level,
                largest_unsafe: found,
                simulations: counts.collapsed + counts.survived + counts.failures.len(),
            },
            counts,
        ))
    });
    let mut runs = ArchRunCounts::default();
    let mut levels = Vec::with_capacity(per_level.len());
    for r in per_level {
        let (l, c) = r?;
        runs.merge(&c);
        levels.push(l);
    }
    Ok(ArchOas {
        record: record.name.clone(),
        shape: options.sweep.shape,
        onset,
        sizes: options.sizes.clone(),
        levels,
        gravity: sim.gravity,
        runs,
    })
}

/// The single-block design rule (thesis Eq. 21/31, `i_cr ≈ 1`: `a_p/a_p,min ≥ max(1, 1/(p t₁))`
/// is unsafe) applied to an arch with `a_p,min → λ g` and the onset mechanism's `p`: the
/// boundary points of the arch OAS it predicts safe although they collapse.
#[derive(Clone, Debug, PartialEq)]
pub struct ArchT1Check {
    /// The `t₁` checked (s), e.g. the record's single-block `t₁`.
    pub t1: f64,
    /// The arch's own `t₁ = 1/f_min` (s): the rule with any `t₁ ≥` this is conservative.
    pub arch_t1: Option<f64>,
    /// Boundary points the rule predicts safe although they collapse.
    pub violations: Vec<OasPoint>,
}

impl ArchOas {
    /// The boundary: for each level with a collapsing radius, the largest, its `p` and
    /// `f = p · level`.
    pub fn boundary(&self) -> Vec<OasPoint> {
        self.levels
            .iter()
            .filter_map(|l| {
                let size = self.sizes[l.largest_unsafe?];
                let p = self.onset.p(size);
                Some(OasPoint {
                    level: l.level,
                    size,
                    p,
                    f: p * l.level,
                })
            })
            .collect()
    }

    /// The leftmost point of the transformed OAS (smallest `f`, the lowest level on a tie).
    pub fn f_min(&self) -> Option<OasPoint> {
        self.boundary()
            .into_iter()
            .reduce(|a, b| if b.f < a.f { b } else { a })
    }

    /// The arch's `t₁ = 1/f_min` (`i_cr ≈ 1`, Eq. 20/31).
    pub fn t1(&self) -> Option<f64> {
        self.f_min().map(|m| 1.0 / m.f)
    }

    /// Simulations run.
    pub fn simulations(&self) -> usize {
        self.levels.iter().map(|l| l.simulations).sum()
    }

    /// The single-block rule with `t1` against this OAS (a point on the line, within a relative
    /// 1e-9, counts as predicted unsafe).
    pub fn check(&self, t1: f64) -> ArchT1Check {
        let violations = self
            .boundary()
            .into_iter()
            .filter(|q| q.level < crate::design::simplified_oas(q.p, t1, 1.0) * (1.0 - 1e-9))
            .collect();
        ArchT1Check {
            t1,
            arch_t1: self.t1(),
            violations,
        }
    }
}
