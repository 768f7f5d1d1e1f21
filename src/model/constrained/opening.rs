//! The opening model of a closed chain (SPEC §9): `a = argmin ½ aᵀMa − aᵀq` over `G a = r`
//! (`r = −Ġ v`, the pivots move with the bodies) and the cone of SPEC §3 — Gauss's principle of
//! least constraint. A closed loop is statically indeterminate, so there is no reaction test: the
//! model itself answers. From rest (`r = 0`) it returns `a ≠ 0` exactly when some admissible
//! mechanism has positive power of the loads (the kinematic theorem of limit analysis). With
//! joints already open, "nothing new opens" is one of the candidates: the model then returns the
//! current mechanism's accelerations. With a non-zero `r` the minimisation, not the largest
//! `aᵀMa`, decides.
//!
//! Without constraints the problem is built and solved exactly as [`crate::opening_model`] does.

use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ConeProblem, ModelOptions, ModelReport};
use crate::model::configuration::{self, Status};
use crate::model::constrained::problem::{ConstrainedProblem, ConstrainedWork};
use crate::model::constrained::{check_constraints, check_diagonal, solve_in};
use crate::model::impact::{check_mass, check_positive_definite};
use crate::model::opening::generators;

/// Applies the opening model of a closed chain in place: `statuses` becomes the chosen
/// configuration and `acceleration` (length `2n`) its DOF accelerations.
///
/// - `mass`, `load`: `M` (row-major `2n × 2n`) and `q` (length `2n`) of the current geometry;
/// - `constraints`: the row-major `n_c × 2n` closure matrix `G` (possibly empty);
/// - `constraint_rhs`: `r` (length `n_c`), `None` for zeros (a chain at rest).
///
/// `report.changed` is true when a closed joint opened; `report.kinetic_after` is `½ aᵀMa` of
/// the answer and `report.runner_up` is `−f` of the best other admissible configuration
/// (`f = ½ aᵀMa − aᵀq`, which is `½ aᵀMa` at a face optimum when `r = 0`). On error nothing is
/// modified.
pub fn opening_model_constrained(
    mass: &[f64],
    load: &[f64],
    constraints: &[f64],
    constraint_rhs: Option<&[f64]>,
    statuses: &mut [Status],
    acceleration: &mut [f64],
    options: &ModelOptions,
) -> Result<ModelReport, RockingError> {
    let mut work = ConstrainedWork::default();
    opening_model_constrained_in(
        mass,
        load,
        constraints,
        constraint_rhs,
        statuses,
        acceleration,
        options,
        &mut work,
    )
}

/// [`opening_model_constrained`] with its constrained problem built and solved in the buffers
/// of `work` (the loop driver's openings): the same answers.
#[allow(clippy::too_many_arguments)]
pub(crate) fn opening_model_constrained_in(
    mass: &[f64],
    load: &[f64],
    constraints: &[f64],
    constraint_rhs: Option<&[f64]>,
    statuses: &mut [Status],
    acceleration: &mut [f64],
    options: &ModelOptions,
    work: &mut ConstrainedWork,
) -> Result<ModelReport, RockingError> {
    options.validate()?;
    let n = statuses.len();
    check_mass(n, mass)?;
    let m = 2 * n;
    configuration::check_dof_vector("load", load, m)?;
    configuration::check_finite("load", load)?;
    configuration::check_dof_vector("acceleration", acceleration, m)?;
    let nc = check_constraints(constraints, m)?;
    check_diagonal(mass, m)?;
    let zeros;
    let rhs = match constraint_rhs {
        Some(r) if r.len() != nc => {
            return Err(RockingError::new(
                ErrorKind::InvalidSize,
                format!(
                    "constraint_rhs has {} entries, expected one per constraint row ({nc})",
                    r.len()
                ),
            ))
        }
        Some(r) => {
            configuration::check_finite("constraint_rhs", r)?;
            r
        }
        None => {
            zeros = vec![0.0; nc];
            &zeros
        }
    };
    let (sol, a, gens) = if nc == 0 {
        check_positive_definite(mass, m)?;
        let problem = ConeProblem::new(generators(statuses), mass, m, load, options.tolerance)?;
        let sol = crate::model::solver::solve(&problem, options)?;
        let a = problem.dof_vector(&sol.y_hat, m);
        (sol, a, problem.gens)
    } else {
        let problem = ConstrainedProblem::new_in(
            generators(statuses),
            mass,
            m,
            load,
            constraints,
            nc,
            rhs,
            options.tolerance,
            work,
        )?;
        let sol = solve_in(&problem, options, work)?;
        let a = problem.cone.dof_vector(&sol.y_hat, m);
        (sol, a, work.recycle(problem))
    };
    let mut st = statuses.to_vec();
    let mut changed = false;
    for (g, gen) in gens.iter().enumerate() {
        if let Some(j) = gen.group {
            if sol.y_hat[g] > 0.0 {
                st[j] = Status::of_dof(gen.terms[0].0, n);
                changed = true;
            }
        }
    }
    let kinetic_after = if nc == 0 {
        0.5 * sol.criterion
    } else {
        crate::model::impact::kinetic_energy(mass, &a)
    };
    let report = ModelReport {
        solver: sol.solver,
        configurations_examined: sol.examined,
        admissible: sol.admissible,
        changed,
        tie: sol.tie,
        impacts_applied: 0,
        kinetic_before: 0.0,
        kinetic_after,
        runner_up: 0.5 * sol.runner_up,
        condition_estimate: sol.condition,
    };
    configuration::check_result(&a, &[report.kinetic_after])?;
    statuses.copy_from_slice(&st);
    acceleration.copy_from_slice(&a);
    Ok(report)
}
