//! The thesis's exhaustive search (3.2.2 and 3.2.3): every closed interface stays closed or
//! opens about either corner (3 choices), the impacting interface stays closed or rotates on
//! (2 choices, Eq. 9); solve each configuration (Eq. 7 / Eq. 6), keep the kinematically
//! admissible ones (Eq. 5) and take the one with the highest kinetic energy. This is the reference
//! that the projection solver is tested against.

use crate::error::RockingError;
use crate::model::cone::{scatter, ConeProblem, ConeSolution, Faces, Solver, TIE_GAP};

/// Enumerates every configuration of the problem.
pub(crate) fn solve(problem: &ConeProblem) -> Result<ConeSolution, RockingError> {
    let p = problem.p();
    let mut faces = Faces::new(problem);
    let mut set: Vec<usize> = Vec::with_capacity(p);
    let mut work = Vec::with_capacity(p * p);
    let mut x = Vec::with_capacity(p);
    // Two rankings: faces that are also stationary in their cone (the KKT condition), and all
    // sign-admissible faces (the thesis's rule). In exact arithmetic the best of both is the same
    // face; near an event, where criteria differ below round-off, the stationary one is right.
    let mut best = [Best::default(), Best::default()];
    let mut examined = 0u64;
    let mut admissible = 0u64;
    while faces.next_into(&mut set) {
        examined += 1;
        problem.solve_face(&set, &mut work, &mut x)?;
        let largest = problem.largest_rate(&set, &x);
        let ok = set
            .iter()
            .zip(&x)
            .all(|(&i, &v)| !problem.gens[i].bounded || problem.admissible(i, v, largest));
        if ok {
            admissible += 1;
            let c = problem.criterion(&set, &x);
            let cond = crate::model::cholesky::condition_estimate(&work, set.len());
            best[1].offer(c, &set, &x, cond);
            if problem.stationary(&set, &x) {
                best[0].offer(c, &set, &x, cond);
            }
        }
    }
    let [stationary, any] = best;
    let chosen = if stationary.face.is_some() {
        stationary
    } else {
        any
    };
    let runner_up = chosen.runner_up;
    let (criterion, set, x, condition) = chosen
        .face
        .expect("the all-closed configuration is always admissible");
    let tie = !runner_up.is_nan() && runner_up >= criterion * (1.0 - TIE_GAP);
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

/// The best face seen so far and the runner-up's criterion.
#[derive(Default)]
struct Best {
    face: Option<(f64, Vec<usize>, Vec<f64>, f64)>,
    runner_up: f64,
}

impl Best {
    /// Keeps the face if its criterion is higher (first found wins ties, by a relative 1e-14).
    fn offer(&mut self, c: f64, set: &[usize], x: &[f64], cond: f64) {
        match &self.face {
            Some((bc, ..)) if c <= *bc * (1.0 + 1e-14) => {
                if self.runner_up.is_nan() || c > self.runner_up {
                    self.runner_up = c;
                }
            }
            _ => {
                self.runner_up = self.face.as_ref().map_or(f64::NAN, |f| f.0);
                self.face = Some((c, set.to_vec(), x.to_vec(), cond));
            }
        }
    }
}
