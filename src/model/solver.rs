//! Dispatch of a cone problem to a solver: the enumeration (the reference) or the projection.

use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ConeProblem, ConeSolution, ModelOptions, Solver};

/// Solves a cone problem with the requested solver.
pub(crate) fn solve(
    problem: &ConeProblem,
    options: &ModelOptions,
) -> Result<ConeSolution, RockingError> {
    let n_closed = problem.groups.len();
    let solver = match options.solver {
        Solver::Auto
            if n_closed
                <= options
                    .auto_enumerate_up_to
                    .min(options.max_enumerated_closed) =>
        {
            Solver::Enumerate
        }
        Solver::Auto => Solver::Projection,
        s => s,
    };
    match solver {
        Solver::Enumerate => {
            if n_closed > options.max_enumerated_closed {
                return Err(RockingError::new(
                    ErrorKind::EnumerationTooLarge,
                    format!(
                        "{n_closed} closed interfaces, enumeration limit {}",
                        options.max_enumerated_closed
                    ),
                ));
            }
            crate::model::enumeration::solve(problem)
        }
        _ => crate::model::projection::solve(problem),
    }
}
