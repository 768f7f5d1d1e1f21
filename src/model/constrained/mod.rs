//! The opening and impact models of closed chains (SPEC §9): the same projections as for a
//! column, with the loop's closure as linear equality constraints on the interface DOFs
//! (`G v = 0` for impacts, `G a = r` for openings) and a set of closing joints. Without
//! constraints and with one closing joint they are exactly [`crate::impact_model`] and
//! [`crate::opening_model`].
//!
//! - `problem`: the constrained cone problem, its scaling (a loop's `M` is singular on the full
//!   DOF set) and the null-space solve of one face;
//! - `enumeration`: the reference (every configuration);
//! - `projection`: primal active set with constraints, branch and bound;
//! - `impact`, `opening`: the two models;
//! - `work`: the buffers a problem is built and solved in, reused from one to the next.

mod enumeration;
mod householder;
mod impact;
mod opening;
mod problem;
mod projection;
mod work;

pub use impact::impact_model_constrained;
pub(crate) use impact::{impact_model_constrained_symmetric, ImpactWork};
pub use opening::opening_model_constrained;
pub(crate) use opening::opening_model_constrained_in;
pub(crate) use problem::ConstrainedWork;

use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ConeSolution, ModelOptions, Solver};
use crate::model::configuration;
use problem::ConstrainedProblem;

/// Checks the constraint matrix (row-major `n_c × m`, finite) and returns `n_c`.
fn check_constraints(constraints: &[f64], m: usize) -> Result<usize, RockingError> {
    if constraints.len() % m != 0 {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!(
                "constraints has {} entries, not a multiple of 2n = {m} (one row per constraint)",
                constraints.len()
            ),
        ));
    }
    configuration::check_finite("constraints", constraints)?;
    Ok(constraints.len() / m)
}

/// A loop's mass matrix is only positive semi-definite (its cut joint moves no mass), but none of
/// its diagonal entries can be negative: `e_iᵀ M e_i` is twice the kinetic energy of DOF `i`
/// moving alone. A negative one (an input error) made the kinetic energy before an impact
/// negative and the one after larger (found by the fuzzer of the C ABI).
fn check_diagonal(mass: &[f64], m: usize) -> Result<(), RockingError> {
    match (0..m).find(|&i| mass[i * m + i] < 0.0) {
        None => Ok(()),
        Some(i) => Err(RockingError::new(
            ErrorKind::NotPositiveDefinite,
            format!(
                "mass[{i}][{i}] = {}: a diagonal entry of a mass matrix cannot be negative (twice \
                 the kinetic energy of DOF {i} moving alone)",
                mass[i * m + i]
            ),
        )),
    }
}

/// Dispatches a constrained problem to a solver, with the rule of [`crate::model::solver`]: with
/// [`Solver::Auto`] enumerate for few closed joints, project above. The enumeration limit counts
/// the closed joints and every closing joint but the first (`3^closed × 2^closing`
/// configurations; one closing joint is free, as for a column).
/// The projection solver's buffers are `work`'s.
fn solve_in(
    problem: &ConstrainedProblem,
    options: &ModelOptions,
    work: &mut ConstrainedWork,
) -> Result<ConeSolution, RockingError> {
    let n_closed = problem.cone.groups.len();
    let n_choices = n_closed + problem.cone.singles.len().saturating_sub(1);
    let solver = match options.solver {
        Solver::Auto
            if n_closed
                <= options
                    .auto_enumerate_up_to
                    .min(options.max_enumerated_closed)
                && n_choices <= options.max_enumerated_closed =>
        {
            Solver::Enumerate
        }
        Solver::Auto => Solver::Projection,
        s => s,
    };
    match solver {
        Solver::Enumerate => {
            if n_choices > options.max_enumerated_closed {
                return Err(RockingError::new(
                    ErrorKind::EnumerationTooLarge,
                    format!(
                        "{n_closed} closed and {} closing joints, enumeration limit {}",
                        problem.cone.singles.len(),
                        options.max_enumerated_closed
                    ),
                ));
            }
            enumeration::solve(problem)
        }
        _ => projection::solve_in(problem, work),
    }
}
