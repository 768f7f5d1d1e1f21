//! The projection solver (SPEC §4): the search scheme for many closed interfaces that the thesis
//! left open (end of 3.2.3).
//!
//! For one choice of corner per interface the admissible set is a convex cone, and the
//! kinetic-metric projection onto it is the admissible configuration of maximal kinetic energy.
//! Allowing both corners of every closed interface at once gives a convex relaxation: a
//! bound-constrained least-squares problem, solved here by a primal active-set method
//! (Lawson–Hanson, with free variables). If no interface comes out with both corners non-zero,
//! the relaxed optimum is admissible and therefore optimal. Otherwise branch on such an interface
//! (forbid one corner, then the other) and prune branches whose relaxed value cannot beat the
//! best admissible one found (branch and bound). Every result equals the enumeration's.

use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ConeProblem, ConeSolution, Solver, TIE_GAP};

/// Work buffers of one relaxed solve.
struct Workspace {
    set: Vec<usize>,
    in_set: Vec<bool>,
    blocked: Vec<bool>,
    factor: Vec<f64>,
    z: Vec<f64>,
}

/// Solves the relaxed problem with the generators in `forbidden` fixed at zero. Returns the
/// scaled coefficients and the objective `−½ b̂ᵀŷ`.
fn relaxed(
    problem: &ConeProblem,
    forbidden: &[bool],
    ws: &mut Workspace,
) -> Result<(Vec<f64>, f64, f64), RockingError> {
    let p = problem.p();
    ws.set.clear();
    ws.in_set.clear();
    ws.in_set.resize(p, false);
    ws.blocked.clear();
    ws.blocked.resize(p, false);
    let mut y = vec![0.0; p];
    for (i, g) in problem.gens.iter().enumerate() {
        if !g.bounded {
            ws.set.push(i);
            ws.in_set[i] = true;
        }
    }
    if !ws.set.is_empty() {
        problem.solve_face(&ws.set, &mut ws.factor, &mut ws.z)?;
        for (&i, &v) in ws.set.iter().zip(&ws.z) {
            y[i] = v;
        }
    }
    let max_iterations = 10 * p + 100;
    let mut iterations = 0;
    loop {
        // Most violated bound: largest gradient b̂ − Âŷ among bounded generators at zero.
        let mut entering = None;
        let mut best = problem.threshold;
        for j in 0..p {
            if ws.in_set[j] || !problem.gens[j].bounded || forbidden[j] || ws.blocked[j] {
                continue;
            }
            let row = &problem.a[j * p..(j + 1) * p];
            let w = problem.b[j] - ws.set.iter().map(|&s| row[s] * y[s]).sum::<f64>();
            if w > best {
                best = w;
                entering = Some(j);
            }
        }
        let Some(j) = entering else { break };
        ws.set.push(j);
        ws.in_set[j] = true;
        let mut first = true;
        loop {
            iterations += 1;
            if iterations > max_iterations {
                return Err(RockingError::new(
                    ErrorKind::SolverDidNotConverge,
                    format!("active-set iterations exceeded {max_iterations}"),
                ));
            }
            problem.solve_face(&ws.set, &mut ws.factor, &mut ws.z)?;
            let feasible = ws
                .set
                .iter()
                .zip(&ws.z)
                .all(|(&i, &v)| !problem.gens[i].bounded || v > 0.0);
            if feasible {
                for (&i, &v) in ws.set.iter().zip(&ws.z) {
                    y[i] = v;
                }
                break;
            }
            let entering_is_negative = ws.set.last() == Some(&j) && *ws.z.last().unwrap() <= 0.0;
            if first && entering_is_negative {
                // Round-off: the gradient said "enter" but the face disagrees. Keep it out.
                ws.set.pop();
                ws.in_set[j] = false;
                ws.blocked[j] = true;
                break;
            }
            first = false;
            // Step from y towards z until the first bounded coefficient reaches zero.
            let mut alpha = 1.0_f64;
            for (&i, &v) in ws.set.iter().zip(&ws.z) {
                if problem.gens[i].bounded && v <= 0.0 {
                    let yi = y[i];
                    let t = if yi - v > 0.0 { yi / (yi - v) } else { 0.0 };
                    alpha = alpha.min(t);
                }
            }
            for (&i, &v) in ws.set.iter().zip(&ws.z) {
                y[i] += alpha * (v - y[i]);
            }
            // Drop the bounded coefficients that reached zero.
            let tiny = 1e-14 * (1.0 + y.iter().fold(0.0_f64, |a, v| a.max(v.abs())));
            let mut k = 0;
            while k < ws.set.len() {
                let i = ws.set[k];
                if problem.gens[i].bounded && y[i] <= tiny {
                    y[i] = 0.0;
                    ws.in_set[i] = false;
                    ws.set.remove(k);
                } else {
                    k += 1;
                }
            }
        }
    }
    // Final face solve for an exact face optimum and its condition.
    let mut condition = 1.0;
    if !ws.set.is_empty() {
        problem.solve_face(&ws.set, &mut ws.factor, &mut ws.z)?;
        condition = crate::model::cholesky::condition_estimate(&ws.factor, ws.set.len());
        y.iter_mut().for_each(|v| *v = 0.0);
        for (&i, &v) in ws.set.iter().zip(&ws.z) {
            y[i] = v;
        }
    }
    let criterion: f64 = problem.b.iter().zip(&y).map(|(b, v)| b * v).sum();
    Ok((y, -0.5 * criterion, condition))
}

/// Projection with branch and bound on interfaces where both corners come out non-zero.
pub(crate) fn solve(problem: &ConeProblem) -> Result<ConeSolution, RockingError> {
    let p = problem.p();
    let mut ws = Workspace {
        set: Vec::with_capacity(p),
        in_set: Vec::with_capacity(p),
        blocked: Vec::with_capacity(p),
        factor: Vec::with_capacity(p * p),
        z: Vec::with_capacity(p),
    };
    let mut stack: Vec<Vec<bool>> = vec![vec![false; p]];
    let mut best: Option<(f64, Vec<f64>, f64)> = None;
    let mut runner_up = f64::NAN;
    let mut examined = 0u64;
    let mut admissible = 0u64;
    while let Some(forbidden) = stack.pop() {
        let (y, f, condition) = relaxed(problem, &forbidden, &mut ws)?;
        examined += 1;
        let criterion = -2.0 * f;
        if let Some((best_f, ..)) = &best {
            // The relaxed value bounds every admissible face of this branch; branches within the
            // tie gap are still explored so that ties are found and reported.
            if f > *best_f + TIE_GAP * best_f.abs() {
                continue;
            }
        }
        let conflict = problem
            .groups
            .iter()
            .find(|g| y[g[0]] > 0.0 && y[g[1]] > 0.0)
            .copied();
        match conflict {
            None => {
                admissible += 1;
                match &best {
                    Some((best_f, ..)) if f >= *best_f - 1e-14 * best_f.abs() => {
                        if runner_up.is_nan() || criterion > runner_up {
                            runner_up = criterion;
                        }
                    }
                    _ => {
                        if let Some((best_f, ..)) = &best {
                            runner_up = -2.0 * best_f;
                        }
                        best = Some((f, y, condition));
                    }
                }
            }
            Some([g0, g1]) => {
                // Depth first, exploring first the branch that keeps the larger corner.
                let (keep, drop) = if y[g0] >= y[g1] { (g0, g1) } else { (g1, g0) };
                let mut other = forbidden.clone();
                other[keep] = true;
                let mut first = forbidden;
                first[drop] = true;
                stack.push(other);
                stack.push(first);
            }
        }
    }
    let (_, y_hat, condition) =
        best.expect("the branch that keeps every group closed is admissible");
    let (y_hat, condition) = polish(problem, y_hat, condition, &mut ws)?;
    let criterion: f64 = problem.b.iter().zip(&y_hat).map(|(b, v)| b * v).sum();
    let tie = !runner_up.is_nan() && runner_up >= criterion * (1.0 - TIE_GAP);
    Ok(ConeSolution {
        y_hat,
        criterion,
        runner_up,
        examined,
        admissible,
        tie,
        condition,
        solver: Solver::Projection,
    })
}

/// Applies the enumeration's admissibility rule ([`ConeProblem::admissible`]) to the optimum: a
/// bounded coefficient must pass it, not merely be positive. Coefficients that fail (openings at
/// round-off rates, which the enumeration rejects) are set to zero and the face is solved again,
/// until every remaining one passes. The kinetic energy changes only at round-off level.
fn polish(
    problem: &ConeProblem,
    mut y: Vec<f64>,
    mut condition: f64,
    ws: &mut Workspace,
) -> Result<(Vec<f64>, f64), RockingError> {
    loop {
        let all: Vec<usize> = (0..problem.p()).collect();
        let largest = problem.largest_rate(&all, &y);
        let weak = |i: usize| {
            problem.gens[i].bounded && y[i] != 0.0 && !problem.admissible(i, y[i], largest)
        };
        if !(0..problem.p()).any(weak) {
            return Ok((y, condition));
        }
        ws.set.clear();
        ws.set
            .extend((0..problem.p()).filter(|&i| y[i] != 0.0 && !weak(i)));
        y.iter_mut().for_each(|v| *v = 0.0);
        if ws.set.is_empty() {
            return Ok((y, 1.0));
        }
        problem.solve_face(&ws.set, &mut ws.factor, &mut ws.z)?;
        condition = crate::model::cholesky::condition_estimate(&ws.factor, ws.set.len());
        for (&i, &v) in ws.set.iter().zip(&ws.z) {
            y[i] = if problem.gens[i].bounded {
                v.max(0.0)
            } else {
                v
            };
        }
    }
}
