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
use crate::model::cone::{ConeSolution, Solver, TIE_GAP};
use crate::model::constrained::problem::{ConstrainedProblem, FaceWork};

/// Enumerates every configuration of the problem.
pub(crate) fn solve(problem: &ConstrainedProblem) -> Result<ConeSolution, RockingError> {
    let cone = &problem.cone;
    let p = problem.p();
    let free: Vec<usize> = (0..p).filter(|&i| !cone.gens[i].bounded).collect();
    let rows: Vec<usize> = (0..problem.nc).collect();
    let radices: Vec<u8> = cone
        .groups
        .iter()
        .map(|_| 3u8)
        .chain(cone.singles.iter().map(|_| 2u8))
        .collect();
    let mut digits = vec![0u8; radices.len()];
    let mut set: Vec<usize> = Vec::with_capacity(p);
    let mut ws = FaceWork::default();
    let mut best: Option<(f64, Vec<usize>, Vec<f64>, f64)> = None;
    let mut runner_up = f64::NAN;
    let (mut examined, mut admissible) = (0u64, 0u64);
    loop {
        set.clear();
        set.extend_from_slice(&free);
        for (u, &d) in digits.iter().enumerate() {
            if d == 0 {
                continue;
            }
            if u < cone.groups.len() {
                set.push(cone.groups[u][d as usize - 1]);
            } else {
                set.push(cone.singles[u - cone.groups.len()]);
            }
        }
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
        let mut u = 0;
        loop {
            if u == digits.len() {
                let (criterion, set, x, condition) = best.expect(
                    "the configuration that opens nothing satisfies the constraints (checked)",
                );
                let mut y_hat = vec![0.0; p];
                for (&i, &v) in set.iter().zip(&x) {
                    y_hat[i] = v;
                }
                let tie = !runner_up.is_nan()
                    && runner_up >= criterion - TIE_GAP * criterion.abs().max(1e-300);
                return Ok(ConeSolution {
                    y_hat,
                    criterion,
                    runner_up,
                    examined,
                    admissible,
                    tie,
                    condition,
                    solver: Solver::Enumerate,
                });
            }
            digits[u] += 1;
            if digits[u] < radices[u] {
                break;
            }
            digits[u] = 0;
            u += 1;
        }
    }
}
