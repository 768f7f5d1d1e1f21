//! The opening model (thesis 3.2.2; SPEC §3) and the reaction (eccentricity) test.
//!
//! When at a closed interface the eccentricity of the normal force reaches the edge, one or more
//! interfaces open. Among the configurations that open closed interfaces (each stays closed or
//! opens about either corner), keep those whose newly opened DOFs accelerate the admissible way
//! (Eq. 5) and take the one with the highest kinetic energy after the first step: in the limit of
//! a small step, the largest `aᵀMa` with `M_FF a_F = q_F` (Eq. 6). This is Gauss's principle of
//! least constraint, so the current configuration is the answer exactly when its contact
//! reactions are admissible: the eccentricity test, as reaction signs.

use crate::error::RockingError;
use crate::model::cone::{ConeProblem, Generator, ModelOptions, ModelReport};
use crate::model::configuration::{self, Status};
use crate::model::impact::{check_mass, check_positive_definite};

/// Open DOFs are free; each closed joint may open about either corner.
pub(crate) fn generators(statuses: &[Status]) -> Vec<Generator> {
    let n = statuses.len();
    let mut gens = Vec::with_capacity(2 * n);
    for (j, s) in statuses.iter().enumerate() {
        match s.dof(j, n) {
            Some(d) => gens.push(Generator::unit(d, 1.0, false, None)),
            None => {
                // Coefficients >= 0: phĭ = −y (rotation about the right corner, <= 0), phî = +y.
                gens.push(Generator::unit(j, -1.0, true, Some(j)));
                gens.push(Generator::unit(n + j, 1.0, true, Some(j)));
            }
        }
    }
    gens
}

fn check_inputs(mass: &[f64], load: &[f64], statuses: &[Status]) -> Result<(), RockingError> {
    let n = statuses.len();
    check_mass(n, mass)?;
    configuration::check_dof_vector("load", load, 2 * n)?;
    configuration::check_finite("load", load)?;
    check_positive_definite(mass, 2 * n)
}

/// Applies the opening model in place: `statuses` becomes the chosen configuration and
/// `acceleration` (length `2n`) its DOF accelerations (zero outside it). If the current
/// configuration holds (all reactions admissible) it is kept and `report.changed` is false.
/// On error nothing is modified.
pub fn opening_model(
    mass: &[f64],
    load: &[f64],
    statuses: &mut [Status],
    acceleration: &mut [f64],
    options: &ModelOptions,
) -> Result<ModelReport, RockingError> {
    options.validate()?;
    check_inputs(mass, load, statuses)?;
    let n = statuses.len();
    let m = 2 * n;
    configuration::check_dof_vector("acceleration", acceleration, m)?;
    let problem = ConeProblem::new(generators(statuses), mass, m, load, options.tolerance)?;
    let sol = crate::model::solver::solve(&problem, options)?;
    let a = problem.dof_vector(&sol.y_hat, m);
    let mut st = statuses.to_vec();
    let mut changed = false;
    for (g, gen) in problem.gens.iter().enumerate() {
        if let Some(j) = gen.group {
            if sol.y_hat[g] > 0.0 {
                st[j] = Status::of_dof(gen.terms[0].0, n);
                changed = true;
            }
        }
    }
    let report = ModelReport {
        solver: sol.solver,
        configurations_examined: sol.examined,
        admissible: sol.admissible,
        changed,
        tie: sol.tie,
        impacts_applied: 0,
        kinetic_before: 0.0,
        kinetic_after: 0.5 * sol.criterion,
        runner_up: 0.5 * sol.runner_up,
        condition_estimate: sol.condition,
    };
    crate::model::configuration::check_result(&a, &[report.kinetic_after])?;
    statuses.copy_from_slice(&st);
    acceleration.copy_from_slice(&a);
    Ok(report)
}

/// Result of the reaction test on the current configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct ReactionCheck {
    /// DOF accelerations of the current configuration (`M_FF a_F = q_F`, zero elsewhere).
    pub acceleration: Vec<f64>,
    /// Generalised contact reactions `λ = M a − q` (zero on open DOFs). Admissible: `λ >= 0`
    /// on `phî_k`, `λ <= 0` on `phĭ_k` of a closed interface.
    pub reactions: Vec<f64>,
    /// Closed interfaces whose reaction takes the inadmissible sign (beyond the tolerance):
    /// the eccentricity of the normal force has left the contact width.
    pub must_open: Vec<usize>,
}

impl ReactionCheck {
    /// Whether the current configuration holds.
    pub fn holds(&self) -> bool {
        self.must_open.is_empty()
    }
}

/// The eccentricity test as reaction signs (SPEC §3): solves the current configuration and
/// reports the closed interfaces that must open (`reaction_margins`, the test the driver makes
/// at every step). Consistent with [`opening_model`]: the configuration holds exactly when the
/// opening model keeps it.
pub fn check_configuration(
    mass: &[f64],
    load: &[f64],
    statuses: &[Status],
    tolerance: f64,
) -> Result<ReactionCheck, RockingError> {
    check_inputs(mass, load, statuses)?;
    let n = statuses.len();
    let m = 2 * n;
    let problem = ConeProblem::new(generators(statuses), mass, m, load, tolerance)?;
    let free: Vec<usize> = (0..problem.p())
        .filter(|&i| !problem.gens[i].bounded)
        .collect();
    let mut y_hat = vec![0.0; problem.p()];
    if !free.is_empty() {
        let (mut work, mut x) = (Vec::new(), Vec::new());
        problem.solve_face(&free, &mut work, &mut x)?;
        for (&i, &v) in free.iter().zip(&x) {
            y_hat[i] = v;
        }
    }
    let a = problem.dof_vector(&y_hat, m);
    let mut reactions = vec![0.0; m];
    for (r, o) in reactions.iter_mut().enumerate() {
        let k = r % n;
        if statuses[k].dof(k, n).is_none() {
            *o = mass[r * m..(r + 1) * m]
                .iter()
                .zip(&a)
                .map(|(x, y)| x * y)
                .sum::<f64>()
                - load[r];
        }
    }
    let inv_sqrt_mass: Vec<f64> = (0..m).map(|d| 1.0 / mass[d * m + d].sqrt()).collect();
    let open = configuration::open_dofs(statuses);
    let mut margin = vec![0.0; m];
    reaction_margins(
        statuses,
        &open,
        load,
        &inv_sqrt_mass,
        &a,
        |d, f| mass[d * m + f],
        tolerance,
        &mut margin,
    );
    let must_open = (0..n)
        .filter(|&k| margin[k] > 0.0 || margin[n + k] > 0.0)
        .collect();
    Ok(ReactionCheck {
        acceleration: a,
        reactions,
        must_open,
    })
}

/// The reaction test (SPEC §3: the eccentricity test as reaction signs), the one function behind
/// [`check_configuration`] and the driver's check at every step.
///
/// With the current configuration's accelerations `acc` (`M_FF a_F = q_F`, zero off the open
/// DOFs), the generalised reaction on a corner DOF `d` of a closed interface is
/// `λ_d = (M a)_d − q_d`, admissible when `λ ≤ 0` on `phĭ` and `λ ≥ 0` on `phî`. Its margin is the
/// inadmissible part in Jacobi-scaled units less the threshold of the cone problem
/// ([`ConeProblem`]: the gradient `b̂ − Â ŷ` of a corner generator against `tolerance` times
/// the largest `|b̂|`):
///
/// `σ_d (q_d − Σ_{f open} M_df a_f) / √M_dd − tolerance · max_g |q_g| / √M_gg`,
///
/// `σ` = −1 on `phĭ`, +1 on `phî`, the maximum over the generators of the configuration (both
/// corners of every closed interface and every open DOF). `> 0`: the interface must open.
///
/// `config` is the configuration (`[Status]`, or [`AllClosed`] for the straight column, which
/// compiles to the loops of that case alone); `load` (`q`) and `inv_sqrt_mass` (`1/√M_dd`) are
/// read on the generators only; `mass(d, f)` is `M_df`. Writes `margin` (`2n`; `−∞` on the DOFs
/// of open interfaces) and returns the largest margin (`−∞` when every interface is open).
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn reaction_margins<C: Configuration + ?Sized>(
    config: &C,
    open: &[usize],
    load: &[f64],
    inv_sqrt_mass: &[f64],
    acc: &[f64],
    mass: impl Fn(usize, usize) -> f64,
    tolerance: f64,
    margin: &mut [f64],
) -> f64 {
    let n = config.interfaces();
    let (load, inv_sqrt_mass, margin) = (
        &load[..2 * n],
        &inv_sqrt_mass[..2 * n],
        &mut margin[..2 * n],
    );
    let mut bmax = 0.0_f64;
    for d in 0..2 * n {
        if config.generator(d) {
            bmax = bmax.max(load[d].abs() * inv_sqrt_mass[d]);
        }
    }
    let threshold = tolerance * bmax;
    let mut largest = f64::NEG_INFINITY;
    for d in 0..2 * n {
        if !config.closed_corner(d) {
            margin[d] = f64::NEG_INFINITY;
            continue;
        }
        let ma: f64 = open.iter().map(|&f| mass(d, f) * acc[f]).sum();
        let sigma = if d < n { -1.0 } else { 1.0 };
        let v = sigma * (load[d] - ma) * inv_sqrt_mass[d] - threshold;
        margin[d] = v;
        largest = largest.max(v);
    }
    largest
}

/// A configuration as the reaction test reads it.
pub(crate) trait Configuration {
    /// Number of interfaces `n`.
    fn interfaces(&self) -> usize;
    /// Whether DOF `d < 2n` is a generator: a corner of a closed interface, or the DOF of an
    /// open one.
    fn generator(&self, d: usize) -> bool;
    /// Whether DOF `d < 2n` is a corner of a closed interface.
    fn closed_corner(&self, d: usize) -> bool;
}

impl Configuration for [Status] {
    #[inline]
    fn interfaces(&self) -> usize {
        self.len()
    }

    #[inline]
    fn generator(&self, d: usize) -> bool {
        let n = self.len();
        // The interface of `d` without an integer division: this runs at every step.
        match self[if d < n { d } else { d - n }] {
            Status::Closed => true,
            Status::OpenRight => d < n,
            Status::OpenLeft => d >= n,
        }
    }

    #[inline]
    fn closed_corner(&self, d: usize) -> bool {
        let n = self.len();
        self[if d < n { d } else { d - n }] == Status::Closed
    }
}

/// Every one of `n` interfaces closed: the straight column.
pub(crate) struct AllClosed(pub usize);

impl Configuration for AllClosed {
    #[inline]
    fn interfaces(&self) -> usize {
        self.0
    }

    #[inline]
    fn generator(&self, _: usize) -> bool {
        true
    }

    #[inline]
    fn closed_corner(&self, _: usize) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::cone::Solver;
    use crate::samples;

    /// Thesis Fig. 18–19: two blocks under gravity and a horizontal top impulse. Opening both
    /// interfaces the "obvious" way is inadmissible; the model finds the configuration of Fig. 19e
    /// (bottom and top open about opposite corners).
    #[test]
    fn thesis_fig19_top_push_opens_both_ways() {
        let case = samples::two_block_top_push();
        for solver in [Solver::Enumerate, Solver::Projection] {
            let mut st = vec![Status::Closed; 2];
            let mut a = vec![0.0; 4];
            let opts = ModelOptions {
                solver,
                ..ModelOptions::default()
            };
            let rep = opening_model(&case.mass, &case.load, &mut st, &mut a, &opts).unwrap();
            assert!(rep.changed);
            assert_eq!(st, case.expected, "solver {solver:?}");
            if solver == Solver::Enumerate {
                assert_eq!(rep.configurations_examined, 9);
            }
        }
    }

    #[test]
    fn gravity_alone_keeps_the_column_closed() {
        let case = samples::two_block_impact();
        let col = samples::two_granite_column();
        let pose = col.pose(&[0.0; 4]);
        let q = col.load_vector(&pose, 0.0, crate::model::column::GRAVITY);
        let mut st = vec![Status::Closed; 2];
        let mut a = vec![1.0; 4];
        let rep = opening_model(&case.mass, &q, &mut st, &mut a, &ModelOptions::default()).unwrap();
        assert!(!rep.changed);
        assert_eq!(a, vec![0.0; 4]);
        assert!(check_configuration(&case.mass, &q, &st, 1e-12)
            .unwrap()
            .holds());
    }

    #[test]
    fn reaction_test_agrees_with_the_opening_model() {
        let col = samples::two_granite_column();
        let pose = col.pose(&[0.0; 4]);
        let mass = col.mass_matrix(&pose);
        let amin = col.static_uplift_acceleration(crate::model::column::GRAVITY);
        for factor in [0.5, 0.99, 1.01, 2.0, -1.01, -3.0] {
            let q = col.load_vector(&pose, factor * amin, crate::model::column::GRAVITY);
            let st = vec![Status::Closed; 2];
            let check = check_configuration(&mass, &q, &st, 1e-12).unwrap();
            let mut st2 = st.clone();
            let mut a = vec![0.0; 4];
            let rep = opening_model(&mass, &q, &mut st2, &mut a, &ModelOptions::default()).unwrap();
            assert_eq!(check.holds(), !rep.changed, "factor {factor}");
            assert_eq!(check.holds(), factor.abs() < 1.0, "factor {factor}");
        }
    }
}
