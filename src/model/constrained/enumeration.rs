//! The reference for closed chains: the thesis's exhaustive search with the closure added. Every
//! closed joint stays closed or opens about either corner (3 choices), every closing joint stays
//! closed or rotates on about its opposite corner (2 choices); each configuration is an
//! equality-constrained projection (SPEC §9), kept when feasible and kinematically admissible,
//! and the one of least `f = ½ yᵀAy − bᵀy` is taken (for an impact or an opening from rest this
//! is the highest kinetic energy; with a non-zero right-hand side only the minimisation is right).
//!
//! Unlike the column's enumeration there is no preference for faces that are stationary in
//! their own cone: with constraints a face's multipliers are not unique when its closure columns
//! lose rank (a loop at rest is statically indeterminate: three redundants), so first-order
//! stationarity is a linear programme, not a sign test. Where the two best faces differ only at
//! round-off the report's `tie` flag says so.

use crate::error::RockingError;
use crate::model::cone::{scatter, ConeSolution, Faces, Solver, TIE_GAP};
use crate::model::constrained::problem::{ConstrainedProblem, FaceWork};

/// Enumerates every configuration of the problem.
pub(crate) fn solve(problem: &ConstrainedProblem) -> Result<ConeSolution, RockingError> {
    let cone = &problem.cone;
    let p = problem.p();
    let rows: Vec<usize> = (0..problem.nc).collect();
    let mut faces = Faces::new(cone);
    let mut set: Vec<usize> = Vec::with_capacity(p);
    let mut ws = FaceWork::default();
    let mut best: Option<(f64, Vec<usize>, Vec<f64>, f64)> = None;
    let mut runner_up = f64::NAN;
    let (mut examined, mut admissible) = (0u64, 0u64);
    while faces.next_into(&mut set) {
        examined += 1;
        if let Some(info) = problem.solve_face(&set, &rows, &mut ws)? {
            let largest = cone.largest_rate(&set, &ws.y);
            let ok = set
                .iter()
                .zip(&ws.y)
                .all(|(&i, &v)| !cone.gens[i].bounded || cone.admissible(i, v, largest));
            if ok {
                admissible += 1;
                // Criterion −2f: for a zero right-hand side this is bᵀy = yᵀAy, as in the
                // unconstrained enumeration; the first face found wins ties.
                let c = -2.0 * info.objective;
                match &best {
                    Some((bc, ..)) if c <= *bc + 1e-14 * bc.abs() => {
                        if runner_up.is_nan() || c > runner_up {
                            runner_up = c;
                        }
                    }
                    _ => {
                        runner_up = best.as_ref().map_or(f64::NAN, |b| b.0);
                        best = Some((c, set.clone(), ws.y.clone(), info.condition));
                    }
                }
            }
        }
    }
    let (criterion, set, x, condition) =
        best.expect("the configuration that opens nothing satisfies the constraints (checked)");
    let tie = !runner_up.is_nan() && runner_up >= criterion - TIE_GAP * criterion.abs().max(1e-300);
    Ok(ConeSolution {
        y_hat: scatter(&set, &x, p),
        criterion,
        runner_up,
        examined,
        admissible,
        tie,
        condition,
        solver: Solver::Enumerate,
    })
}
