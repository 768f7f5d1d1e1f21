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
use crate::model::constrained::{check_constraints, check_diagonal, solve_in};
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
    /// The closing joints and their plans, which still rotate, which joints were open.
    closing_joints: Vec<usize>,
    plan: Vec<(usize, f64, f64, f64)>,
    rotating: Vec<bool>,
    open_before: Vec<bool>,
    /// The configuration and rates through the bumps, the next rates, `M v` and its moving DOFs.
    st: Vec<Status>,
    v: Vec<f64>,
    y: Vec<f64>,
    rhs: Vec<f64>,
    moving: Vec<usize>,
    /// The constraints' zero right-hand side, a bump's generators and the closing joints' ones.
    zero_rhs: Vec<f64>,
    gens: Vec<Generator>,
    impacting: Vec<Option<usize>>,
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
    check_diagonal(mass, m)?;
    if closing.len() != n {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!("closing has {} flags, expected n = {n}", closing.len()),
        ));
    }
    let ImpactWork {
        problem: problem_work,
        closing_joints,
        plan,
        rotating,
        open_before,
        st,
        v,
        y,
        rhs,
        moving,
        zero_rhs,
        gens: spare_gens,
        impacting,
    } = work;
    closing_joints.clear();
    closing_joints.extend((0..n).filter(|&k| closing[k]));
    if closing_joints.is_empty() {
        return Err(RockingError::new(
            ErrorKind::InvalidClosingInterface,
            "no joint is flagged as closing",
        ));
    }
    for &k in closing_joints.iter() {
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

    st.clear();
    st.extend_from_slice(statuses);
    v.clear();
    v.extend_from_slice(velocity);
    let mut report = ModelReport::empty(options.solver);
    report.kinetic_before = kinetic_energy(mass, v);
    report.changed = true;
    report.runner_up = f64::NAN;
    // For each closing joint: its direction of rotation (kept through the bumps) and the weight
    // λ of its left-corner DOF at the closing corner and at the opposite one.
    plan.clear();
    plan.extend(closing_joints.iter().map(|&k| {
        let corner = statuses[k];
        let (start, end) = if corner == Status::OpenLeft {
            (1.0, 0.0)
        } else {
            (0.0, 1.0)
        };
        (k, -corner.sign(), start, end)
    }));
    rotating.clear();
    rotating.resize(plan.len(), true);
    open_before.clear();
    open_before.extend(statuses.iter().map(|s| s.is_open()));
    zero_rhs.clear();
    zero_rhs.resize(nc, 0.0);
    let n_imp = options.n_impacts;
    for step in 1..=n_imp {
        let mut gens = std::mem::take(spare_gens);
        gens.clear();
        gens.reserve(2 * n);
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
        impacting.clear();
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
        rhs.clear();
        rhs.extend((0..m).map(|r| row_times_moving(&mass[r * m..(r + 1) * m], v, moving)));
        let (sol, scaled_gens): (ConeSolution, Vec<Generator>) = if nc == 0 {
            let problem = ConeProblem::new(gens, mass, m, rhs, options.tolerance)?;
            let sol = crate::model::solver::solve(&problem, options)?;
            problem.dof_vector_into(&sol.y_hat, m, y);
            (sol, problem.gens)
        } else {
            let problem = ConstrainedProblem::new_in(
                gens,
                mass,
                m,
                rhs,
                constraints,
                nc,
                zero_rhs,
                options.tolerance,
                problem_work,
            )?;
            let sol = solve_in(&problem, options, problem_work)?;
            problem.cone.dof_vector_into(&sol.y_hat, m, y);
            (sol, problem_work.recycle(problem))
        };
        std::mem::swap(v, y);
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
        // The generators' and the solution's memory for the next bump or impact.
        *spare_gens = scaled_gens;
        if nc > 0 {
            problem_work.keep_point(sol.y_hat);
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
    report.kinetic_after = kinetic_energy(mass, v);
    configuration::check_result(v, &[report.kinetic_before, report.kinetic_after])?;
    statuses.copy_from_slice(st);
    velocity.copy_from_slice(v);
    Ok(report)
}
