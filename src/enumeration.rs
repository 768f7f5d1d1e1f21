//! The thesis's exhaustive search (3.2.2 and 3.2.3): every closed interface stays closed or
//! opens about either corner (3 choices), the impacting interface stays closed or rotates on
//! (2 choices, Eq. 9); solve each configuration (Eq. 7 / Eq. 6), keep the kinematically
//! admissible ones (Eq. 5) and take the one with the highest kinetic energy. This is the reference
//! that the projection solver is tested against.

use crate::cone::{ConeProblem, ConeSolution, Solver, TIE_GAP};
use crate::error::{ErrorKind, RockingError};

/// Enumerates every configuration of the problem.
pub(crate) fn solve(problem: &ConeProblem) -> Result<ConeSolution, RockingError> {
    let p = problem.p();
    let free: Vec<usize> = (0..p).filter(|&i| !problem.gens[i].bounded).collect();
    // Mixed-radix counter: groups have 3 choices (closed, first corner, second corner), singles 2.
    let radices: Vec<u8> = problem
        .groups
        .iter()
        .map(|_| 3u8)
        .chain(problem.singles.iter().map(|_| 2u8))
        .collect();
    let mut digits = vec![0u8; radices.len()];
    let mut set: Vec<usize> = Vec::with_capacity(p);
    let mut work = Vec::with_capacity(p * p);
    let mut x = Vec::with_capacity(p);
    let mut best: Option<(f64, Vec<usize>, Vec<f64>, f64)> = None;
    let mut runner_up = f64::NAN;
    let mut examined = 0u64;
    let mut admissible = 0u64;
    loop {
        set.clear();
        set.extend_from_slice(&free);
        for (u, &d) in digits.iter().enumerate() {
            if u < problem.groups.len() {
                if d > 0 {
                    set.push(problem.groups[u][d as usize - 1]);
                }
            } else if d > 0 {
                set.push(problem.singles[u - problem.groups.len()]);
            }
        }
        examined += 1;
        if !problem.solve_face(&set, &mut work, &mut x) {
            return Err(RockingError::new(
                ErrorKind::NotPositiveDefinite,
                "the mass matrix of a configuration is not positive definite",
            ));
        }
        let largest = problem.largest_rate(&set, &x);
        let ok = set
            .iter()
            .zip(&x)
            .all(|(&i, &v)| !problem.gens[i].bounded || problem.admissible(i, v, largest));
        if ok {
            admissible += 1;
            let c = problem.criterion(&set, &x);
            match &best {
                Some((bc, ..)) if c <= *bc * (1.0 + 1e-14) => {
                    if runner_up.is_nan() || c > runner_up {
                        runner_up = c;
                    }
                }
                _ => {
                    if let Some((bc, ..)) = &best {
                        runner_up = *bc;
                    }
                    let cond = crate::cholesky::condition_estimate(&work, set.len());
                    best = Some((c, set.clone(), x.clone(), cond));
                }
            }
        }
        // Next configuration.
        let mut u = 0;
        loop {
            if u == digits.len() {
                let (criterion, set, x, condition) =
                    best.expect("the all-closed configuration is always admissible");
                let mut y_hat = vec![0.0; p];
                for (&i, &v) in set.iter().zip(&x) {
                    y_hat[i] = v;
                }
                let tie = !runner_up.is_nan() && runner_up >= criterion * (1.0 - TIE_GAP);
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
