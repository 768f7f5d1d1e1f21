//! The impact model of a closed chain (SPEC §9): `v⁺ = argmin (v − v⁻)ᵀ M (v − v⁻)` over
//! `G v⁺ = 0` and the cone of SPEC §2, with a *set* of closing joints. A four-hinge loop has one
//! degree of freedom, so when it swings back its four hinges reach zero together; each closing
//! joint stays closed or rotates on about its opposite corner, every other closed joint stays
//! closed or opens either way, open joints keep their DOF.
//!
//! Consecutive impacts (`n_impacts > 1`, thesis 3.1): the pivots of all closing joints walk over
//! the bumps together; a closing joint that stops at a bump stays closed for the rest of the
//! chain (the impact is inelastic: it does not bounce back), the chain ends when none rotates on.
//! With one closing joint this is exactly [`crate::impact_model`].
//!
//! Without constraints the problem is built and solved exactly as [`crate::impact_model`] does
//! (same generators, same scaling, same solvers), so the answers are identical to the last bit.

use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ConeProblem, ConeSolution, Generator, ModelOptions, ModelReport};
use crate::model::configuration::{self, Status};
use crate::model::constrained::problem::{ConstrainedProblem, ConstrainedWork};
use crate::model::constrained::{check_constraints, solve_in};
use crate::model::impact::{
    check_mass, check_mass_size, check_positive_definite, kinetic_energy, row_times_moving,
};

/// Applies the impact model of a closed chain in place.
///
/// - `mass`: the `2n × 2n` mass matrix (row-major, symmetric; only positive semi-definite for a
///   loop, whose cut joint moves no mass);
/// - `constraints`: the row-major `n_c × 2n` closure matrix `G` (`n_c = constraints.len() / 2n`,
///   possibly zero); the velocities after satisfy `G v⁺ = 0`;
/// - `statuses`, `velocity`: the configuration and DOF rates before, updated to those after;
/// - `closing`: one flag per joint, true for every open joint that closes at this instant (each
///   must be open with its DOF at rest or moving towards zero).
///
/// On error nothing is modified.
pub fn impact_model_constrained(
    mass: &[f64],
    constraints: &[f64],
    statuses: &mut [Status],
    velocity: &mut [f64],
    closing: &[bool],
    options: &ModelOptions,
) -> Result<ModelReport, RockingError> {
    options.validate()?;
    check_mass(statuses.len(), mass)?;
    let mut work = ImpactWork::default();
    impact_model_constrained_checked(
        mass,
        constraints,
        statuses,
        velocity,
        closing,
        options,
        &mut work,
    )
}

/// Buffers of the impact model, reused from one impact to the next (the loop driver's): its
/// constrained problems' and solver's, its configurations and rates.
#[derive(Default)]
pub(crate) struct ImpactWork {
    problem: ConstrainedWork,
}

/// [`impact_model_constrained`] for a mass matrix symmetric to the bit by construction
/// ([`crate::chain::Chain::mass_matrix`]: its lower triangle is a copy of the upper): the
/// symmetry sweep of [`check_mass`], whose verdict is then always a pass, is not taken; the
/// size and finiteness checks are. The same answers (and errors) as
/// [`impact_model_constrained`] for such a matrix, in the buffers of `work`.
pub(crate) fn impact_model_constrained_symmetric(
    mass: &[f64],
    constraints: &[f64],
    statuses: &mut [Status],
    velocity: &mut [f64],
    closing: &[bool],
    options: &ModelOptions,
    work: &mut ImpactWork,
) -> Result<ModelReport, RockingError> {
    options.validate()?;
    let n = statuses.len();
    check_mass_size(n, mass)?;
    configuration::check_finite("mass", mass)?;
    debug_assert!(check_mass(n, mass).is_ok());
    impact_model_constrained_checked(
        mass,
        constraints,
        statuses,
        velocity,
        closing,
        options,
        work,
    )
}

/// The model once the options and the mass matrix have passed their checks.
fn impact_model_constrained_checked(
    mass: &[f64],
    constraints: &[f64],
    statuses: &mut [Status],
    velocity: &mut [f64],
    closing: &[bool],
    options: &ModelOptions,
    work: &mut ImpactWork,
) -> Result<ModelReport, RockingError> {
    let n = statuses.len();
    let m = 2 * n;
    configuration::check_dof_vector("velocity", velocity, m)?;
    configuration::check_finite("velocity", velocity)?;
    let nc = check_constraints(constraints, m)?;
    if closing.len() != n {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!("closing has {} flags, expected n = {n}", closing.len()),
        ));
    }
    let closing_joints: Vec<usize> = (0..n).filter(|&k| closing[k]).collect();
    if closing_joints.is_empty() {
        return Err(RockingError::new(
            ErrorKind::InvalidClosingInterface,
            "no joint is flagged as closing",
        ));
    }
    for &k in &closing_joints {
        let corner = statuses[k];
        let Some(dof) = corner.dof(k, n) else {
            return Err(RockingError::new(
                ErrorKind::InvalidClosingInterface,
                format!("closing[{k}] is set but interface {k} is closed; only an open interface can close"),
            ));
        };
        if velocity[dof] * corner.sign() > 0.0 {
            return Err(RockingError::new(
                ErrorKind::InconsistentState,
                format!(
                    "interface {k} (status {}) has rate {} on its DOF, moving away from closure",
                    corner.as_i8(),
                    velocity[dof]
                ),
            ));
        }
    }
    configuration::check_zero_off_configuration(
        "velocity",
        statuses,
        velocity,
        ErrorKind::VelocityOnClosedDof,
    )?;
    if nc == 0 {
        check_positive_definite(mass, m)?;
    }

    let mut st = statuses.to_vec();
    let mut v = velocity.to_vec();
    let mut report = ModelReport::empty(options.solver);
    report.kinetic_before = kinetic_energy(mass, &v);
    report.changed = true;
    report.runner_up = f64::NAN;
    // For each closing joint: its direction of rotation (kept through the bumps) and the weight
    // λ of its left-corner DOF at the closing corner and at the opposite one.
    let plan: Vec<(usize, f64, f64, f64)> = closing_joints
        .iter()
        .map(|&k| {
            let corner = statuses[k];
            let (start, end) = if corner == Status::OpenLeft {
                (1.0, 0.0)
            } else {
                (0.0, 1.0)
            };
            (k, -corner.sign(), start, end)
        })
        .collect();
    let mut rotating = vec![true; plan.len()];
    let open_before: Vec<bool> = statuses.iter().map(|s| s.is_open()).collect();
    let zero_rhs = vec![0.0; nc];
    let n_imp = options.n_impacts;
    let mut moving: Vec<usize> = Vec::with_capacity(m);
    for step in 1..=n_imp {
        let mut gens = Vec::with_capacity(2 * n);
        for (j, s) in st.iter().enumerate() {
            if closing[j] {
                continue;
            }
            match s.dof(j, n).filter(|_| open_before[j]) {
                Some(d) => gens.push(Generator::unit(d, 1.0, false, None)),
                None => {
                    gens.push(Generator::unit(j, -1.0, true, Some(j)));
                    gens.push(Generator::unit(n + j, 1.0, true, Some(j)));
                }
            }
        }
        let mut impacting = Vec::with_capacity(plan.len());
        for (u, &(k, direction, start, end)) in plan.iter().enumerate() {
            if !rotating[u] {
                impacting.push(None);
                continue;
            }
            let lambda = start + (end - start) * f64::from(step) / f64::from(n_imp);
            impacting.push(Some(gens.len()));
            gens.push(if lambda == 1.0 {
                Generator::unit(n + k, direction, true, None)
            } else if lambda == 0.0 {
                Generator::unit(k, direction, true, None)
            } else {
                Generator {
                    terms: [(n + k, direction * lambda), (k, direction * (1.0 - lambda))],
                    n_terms: 2,
                    bounded: true,
                    group: None,
                }
            });
        }
        // `M v`, each row's sum over the moving DOFs only (`row_times_moving`).
        moving.clear();
        moving.extend((0..m).filter(|&d| v[d] != 0.0));
        let mut rhs = vec![0.0; m];
        for (r, o) in rhs.iter_mut().enumerate() {
            *o = row_times_moving(&mass[r * m..(r + 1) * m], &v, &moving);
        }
        let (sol, y, scaled_gens): (ConeSolution, Vec<f64>, Vec<Generator>) = if nc == 0 {
            let problem = ConeProblem::new(gens, mass, m, &rhs, options.tolerance)?;
            let sol = crate::model::solver::solve(&problem, options)?;
            let y = problem.dof_vector(&sol.y_hat, m);
            (sol, y, problem.gens)
        } else {
            let work = &mut work.problem;
            let problem = ConstrainedProblem::new_in(
                gens,
                mass,
                m,
                &rhs,
                constraints,
                nc,
                &zero_rhs,
                options.tolerance,
                work,
            )?;
            let sol = solve_in(&problem, options, work)?;
            let y = problem.cone.dof_vector(&sol.y_hat, m);
            (sol, y, work.recycle(problem))
        };
        v = y;
        for j in (0..n).filter(|&j| !closing[j] && !open_before[j]) {
            st[j] = Status::Closed;
        }
        for (g, gen) in scaled_gens.iter().enumerate() {
            if let Some(j) = gen.group {
                if sol.y_hat[g] > 0.0 {
                    st[j] = Status::of_dof(gen.terms[0].0, n);
                }
            }
        }
        report.solver = sol.solver;
        report.configurations_examined += sol.examined;
        report.admissible += sol.admissible;
        report.tie |= sol.tie;
        report.condition_estimate = report.condition_estimate.max(sol.condition);
        report.runner_up = 0.5 * sol.runner_up;
        report.impacts_applied = step;
        for (u, slot) in impacting.iter().enumerate() {
            if let Some(g) = *slot {
                rotating[u] = sol.y_hat[g] > 0.0;
            }
        }
        if !rotating.iter().any(|&r| r) {
            break;
        }
    }
    for (u, &(k, _, _, end)) in plan.iter().enumerate() {
        if rotating[u] {
            st[k] = if end == 1.0 {
                Status::OpenLeft
            } else {
                Status::OpenRight
            };
        } else {
            st[k] = Status::Closed;
            v[k] = 0.0;
            v[n + k] = 0.0;
        }
    }
    report.kinetic_after = kinetic_energy(mass, &v);
    configuration::check_result(&v, &[report.kinetic_before, report.kinetic_after])?;
    statuses.copy_from_slice(&st);
    velocity.copy_from_slice(&v);
    Ok(report)
}
