//! The projection solver with equality constraints (SPEC §4 and §9).
//!
//! The relaxed problem (both corners of every closed joint allowed) is a convex quadratic
//! programme with equality constraints and bounds: `min ½ŷᵀÂŷ − b̂ᵀŷ` over `Ĉŷ = r`, `ŷ_i ≥ 0`
//! on bounded generators. It is solved by the primal active-set method of Nocedal & Wright
//! (Numerical Optimization, 2nd ed., Algorithm 16.3) in its working-set-of-free-variables form:
//! each iteration solves one face in the null space of its constraint columns, steps towards its
//! optimum until a bound blocks, and when the face is optimal frees the bounded generator of
//! largest gradient `b̂_j − (Âŷ)_j − (Ĉᵀμ)_j`. The working set is kept with constraint columns of
//! full row rank, so that the multipliers `μ` are unique: a loop at rest starts from a vertex
//! with three generators at zero, and the method walks through the degenerate vertices until a
//! four-hinge mechanism (or nothing) is found. Bland's rule takes over after a run of zero steps.
//!
//! Then, as without constraints: if no joint comes out with both corners non-zero the relaxed
//! optimum is admissible and optimal; otherwise branch on such a joint and prune by the relaxed
//! value (branch and bound). Every answer equals the enumeration's.

use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ConeSolution, Solver, TIE_GAP};
use crate::model::constrained::householder::PivotedQr;
use crate::model::constrained::problem::{ConstrainedProblem, ConstrainedWork};

/// Relative column norm under which a candidate column adds no rank.
const RANK_TOLERANCE: f64 = 1e-10;
/// Null-space weight under which a generator of the working set cannot move.
const ESSENTIAL: f64 = 1e-9;

fn not_converged(detail: impl Into<String>) -> RockingError {
    RockingError::new(ErrorKind::SolverDidNotConverge, detail)
}

/// The optimum of one relaxed problem.
struct Relaxed {
    y: Vec<f64>,
    objective: f64,
    condition: f64,
}

/// Buffers of the solver, reused from one relaxed problem (and one constrained problem) to the
/// next.
#[derive(Default)]
pub(crate) struct SolverWork {
    /// The branches' forbidden flags waiting on the stack, and spare ones.
    stack: Vec<Vec<bool>>,
    spare_flags: Vec<Vec<bool>>,
    /// Spare points of relaxed problems (one is the solution, the others come back here).
    spare_points: Vec<Vec<f64>>,
    /// A branch's allowed generators (flags and list), its independent rows, its working set
    /// and flags, the blocked generators, the gradients and their `Ĉᵀ μ`.
    allowed: Vec<bool>,
    allowed_list: Vec<usize>,
    rows: Vec<usize>,
    set: Vec<usize>,
    in_set: Vec<bool>,
    blocked: Vec<bool>,
    gradients: Vec<f64>,
    cm: Vec<f64>,
    /// [`complete_rank`]'s orthonormal basis (`c` entries per vector), the candidate column and
    /// the best candidate's.
    basis: Vec<f64>,
    column: Vec<f64>,
    best: Vec<f64>,
}

impl SolverWork {
    /// Keeps the memory of a point for the next relaxed problems.
    pub fn keep_point(&mut self, y: Vec<f64>) {
        self.spare_points.push(y);
    }
}

/// Rows of `Ĉ` that stay independent on the allowed generators into `keep`, or `false` if the
/// right-hand side cannot be met with them (the branch is empty). `qr`, `u`, `kt`, `rhs` and
/// `rows` are scratch.
#[allow(clippy::too_many_arguments)]
fn allowed_rows(
    problem: &ConstrainedProblem,
    allowed: &[usize],
    keep: &mut Vec<usize>,
    qr: &mut PivotedQr,
    u: &mut Vec<f64>,
    (kt, rhs): (&mut Vec<f64>, &mut Vec<f64>),
    rows: &mut Vec<usize>,
) -> bool {
    rows.clear();
    rows.extend(0..problem.nc);
    u.clear();
    u.resize(allowed.len(), 0.0);
    let residual = problem.particular(allowed, rows, qr, u, (kt, rhs));
    let rmax = problem.r.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    if residual > 1e-9 * (1.0 + rmax) {
        return false;
    }
    keep.clear();
    keep.extend_from_slice(&qr.perm[..qr.rank]);
    keep.sort_unstable();
    true
}

/// `v ← v − (q · v) q` for each vector `q` (length `v.len()`) of the orthonormal `basis`, in
/// order (modified Gram–Schmidt).
fn reduce(basis: &[f64], v: &mut [f64]) {
    for q in basis.chunks_exact(v.len()) {
        let d: f64 = q.iter().zip(v.iter()).map(|(a, b)| a * b).sum();
        v.iter_mut().zip(q).for_each(|(x, qi)| *x -= d * qi);
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Adds bounded allowed generators (at zero) to `set` until its constraint columns reach the
/// rank of the rows, choosing each time the column least explained by those already in.
/// `basis`, `column` and `best_v` are scratch.
#[allow(clippy::too_many_arguments)]
fn complete_rank(
    problem: &ConstrainedProblem,
    set: &mut Vec<usize>,
    in_set: &mut [bool],
    allowed: &[bool],
    rows: &[usize],
    basis: &mut Vec<f64>,
    column: &mut Vec<f64>,
    best_v: &mut Vec<f64>,
) {
    let p = problem.p();
    let c = rows.len();
    let column_of = |j: usize, out: &mut Vec<f64>| {
        out.clear();
        out.extend(rows.iter().map(|&r| problem.c[r * p + j]));
    };
    // Orthonormal basis of the span of the set's columns (modified Gram–Schmidt), `c` entries
    // per vector.
    basis.clear();
    let size = |basis: &Vec<f64>| basis.len().checked_div(c).unwrap_or(0);
    for &j in set.iter() {
        if size(basis) == c {
            break;
        }
        column_of(j, column);
        let full = norm(column);
        reduce(basis, column);
        let n = norm(column);
        if n > RANK_TOLERANCE * full.max(1e-300) {
            basis.extend(column.iter().map(|x| x / n));
        }
    }
    while size(basis) < c {
        let mut best: Option<(usize, f64)> = None;
        for j in 0..p {
            if in_set[j] || !allowed[j] || !problem.cone.gens[j].bounded {
                continue;
            }
            column_of(j, column);
            let full = norm(column);
            reduce(basis, column);
            let n = norm(column);
            if n > RANK_TOLERANCE * full && best.as_ref().map_or(true, |b| n > b.1) {
                best = Some((j, n));
                std::mem::swap(best_v, column);
            }
        }
        let Some((j, n)) = best else { break };
        basis.extend(best_v.iter().map(|x| x / n));
        set.push(j);
        in_set[j] = true;
    }
}

/// Solves the relaxed problem with the generators in `forbidden` fixed at zero. `None` when the
/// branch cannot satisfy the constraints.
fn relaxed(
    problem: &ConstrainedProblem,
    forbidden: &[bool],
    work: &mut ConstrainedWork,
) -> Result<Option<Relaxed>, RockingError> {
    let cone = &problem.cone;
    let p = problem.p();
    let SolverWork {
        spare_points,
        allowed,
        allowed_list,
        rows,
        set,
        in_set,
        blocked,
        gradients,
        cm,
        basis,
        column,
        best,
        ..
    } = &mut work.solver;
    allowed.clear();
    allowed.extend(forbidden.iter().map(|f| !f));
    allowed_list.clear();
    allowed_list.extend((0..p).filter(|&i| allowed[i]));
    let scratch = (&mut work.kt, &mut work.rhs);
    if !allowed_rows(
        problem,
        allowed_list,
        rows,
        &mut work.qr,
        &mut work.u,
        scratch,
        &mut work.all,
    ) {
        return Ok(None);
    }
    let rows = &rows[..];
    let ws = &mut work.face;
    // Start: the free generators at the feasible start point, bounded ones at zero.
    let mut y = spare_points.pop().unwrap_or_default();
    y.clone_from(&problem.start);
    set.clear();
    set.extend((0..p).filter(|&i| !cone.gens[i].bounded));
    in_set.clear();
    in_set.resize(p, false);
    set.iter().for_each(|&i| in_set[i] = true);
    complete_rank(problem, set, in_set, allowed, rows, basis, column, best);
    blocked.clear();
    blocked.resize(p, false);
    let mut last_entered: Option<usize> = None;
    let max_iterations = 20 * p + 200;
    let mut zero_steps = 0usize;
    let mut iterations = 0usize;
    let mut info;
    loop {
        iterations += 1;
        if iterations > max_iterations {
            return Err(not_converged(format!(
                "constrained active-set iterations exceeded {max_iterations}"
            )));
        }
        info = problem
            .solve_face(set, rows, ws)?
            .ok_or_else(|| not_converged("the working set lost feasibility (round-off)"))?;
        if info.rank < rows.len() {
            return Err(not_converged(
                "the working set lost the rank of the constraints (round-off)",
            ));
        }
        let bland = zero_steps > p;
        // A generator whose constraint column no other of the face can replace cannot move (its
        // exact step is zero): keep it where it is rather than let round-off make it block, which
        // would drop the rank of the working set.
        for (idx, &i) in set.iter().enumerate() {
            if cone.gens[i].bounded && ws.null_weight(idx) < ESSENTIAL {
                ws.y[idx] = y[i];
            }
        }
        // Ratio test towards the face optimum.
        let mut alpha = 1.0_f64;
        let mut blocking: Option<usize> = None;
        for (idx, &i) in set.iter().enumerate() {
            if !cone.gens[i].bounded {
                continue;
            }
            let step = ws.y[idx] - y[i];
            if step < 0.0 {
                let t = (y[i] / -step).max(0.0);
                let better = match blocking {
                    None => t < alpha,
                    Some(b) => t < alpha || (bland && t == alpha && i < set[b]),
                };
                if better {
                    alpha = t;
                    blocking = Some(idx);
                }
            }
        }
        match blocking {
            Some(idx) => {
                let i = set[idx];
                if alpha > 0.0 {
                    for (k, &s) in set.iter().enumerate() {
                        y[s] += alpha * (ws.y[k] - y[s]);
                    }
                    zero_steps = 0;
                    blocked.iter_mut().for_each(|b| *b = false);
                } else {
                    zero_steps += 1;
                    if last_entered == Some(i) {
                        // Round-off: the gradient said "enter" but the face disagrees.
                        blocked[i] = true;
                    }
                }
                y[i] = 0.0;
                in_set[i] = false;
                set.remove(idx);
                last_entered = None;
            }
            None => {
                let moved = set
                    .iter()
                    .enumerate()
                    .any(|(k, &s)| (ws.y[k] - y[s]).abs() > 1e-14 * (1.0 + y[s].abs()));
                for (k, &s) in set.iter().enumerate() {
                    y[s] = ws.y[k];
                }
                if moved {
                    zero_steps = 0;
                    blocked.iter_mut().for_each(|b| *b = false);
                } else {
                    zero_steps += 1;
                }
                // The face is optimal: free the bounded generator of largest gradient.
                let mut entering = None;
                let mut best = cone.threshold;
                problem.gradients(set, &y, &ws.mu, gradients, cm);
                for j in 0..p {
                    if in_set[j] || !allowed[j] || !cone.gens[j].bounded || blocked[j] {
                        continue;
                    }
                    let w = gradients[j];
                    if w > best {
                        entering = Some(j);
                        if bland {
                            break;
                        }
                        best = w;
                    }
                }
                let Some(j) = entering else { break };
                set.push(j);
                in_set[j] = true;
                last_entered = Some(j);
            }
        }
    }
    // Generators of the final set that sit at zero are dropped from the report's face.
    Ok(Some(Relaxed {
        objective: info.objective,
        condition: info.condition,
        y,
    }))
}

/// Projection with branch and bound on joints where both corners come out non-zero, in the
/// buffers of `work`.
pub(crate) fn solve_in(
    problem: &ConstrainedProblem,
    work: &mut ConstrainedWork,
) -> Result<ConeSolution, RockingError> {
    let cone = &problem.cone;
    let p = problem.p();
    let fresh = |spare: &mut Vec<Vec<bool>>| spare.pop().unwrap_or_default();
    // Flags left on the stack by a branch that failed go back to the spares.
    let mut stack = std::mem::take(&mut work.solver.stack);
    while let Some(flags) = stack.pop() {
        work.solver.spare_flags.push(flags);
    }
    let mut root = fresh(&mut work.solver.spare_flags);
    root.clear();
    root.resize(p, false);
    stack.push(root);
    let mut best: Option<Relaxed> = None;
    let mut runner_up = f64::NAN;
    let (mut examined, mut admissible) = (0u64, 0u64);
    while let Some(forbidden) = stack.pop() {
        examined += 1;
        let relaxed = match relaxed(problem, &forbidden, work) {
            Ok(r) => r,
            Err(e) => {
                work.solver.stack = stack;
                return Err(e);
            }
        };
        let Some(relaxed) = relaxed else {
            work.solver.spare_flags.push(forbidden);
            continue;
        };
        let f = relaxed.objective;
        if let Some(b) = &best {
            if f > b.objective + TIE_GAP * b.objective.abs() {
                work.solver.spare_points.push(relaxed.y);
                work.solver.spare_flags.push(forbidden);
                continue;
            }
        }
        let y = &relaxed.y;
        let conflict = cone
            .groups
            .iter()
            .find(|g| y[g[0]] > 0.0 && y[g[1]] > 0.0)
            .copied();
        match conflict {
            None => {
                admissible += 1;
                match &best {
                    Some(b) if f >= b.objective - 1e-14 * b.objective.abs() => {
                        if runner_up.is_nan() || -2.0 * f > runner_up {
                            runner_up = -2.0 * f;
                        }
                        work.solver.spare_points.push(relaxed.y);
                    }
                    _ => {
                        if let Some(b) = &best {
                            runner_up = -2.0 * b.objective;
                        }
                        if let Some(old) = best.replace(relaxed) {
                            work.solver.spare_points.push(old.y);
                        }
                    }
                }
                work.solver.spare_flags.push(forbidden);
            }
            Some([g0, g1]) => {
                let (keep, drop) = if y[g0] >= y[g1] { (g0, g1) } else { (g1, g0) };
                work.solver.spare_points.push(relaxed.y);
                let mut other = fresh(&mut work.solver.spare_flags);
                other.clone_from(&forbidden);
                other[keep] = true;
                let mut first = forbidden;
                first[drop] = true;
                stack.push(other);
                stack.push(first);
            }
        }
    }
    work.solver.stack = stack;
    let best = best.ok_or_else(|| {
        not_converged("no branch satisfies the constraints (the start point should have)")
    })?;
    let (y_hat, objective, condition) = polish(problem, best, work)?;
    let criterion = -2.0 * objective;
    let tie = !runner_up.is_nan() && runner_up >= criterion - TIE_GAP * criterion.abs();
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

/// Applies the enumeration's admissibility rule to the optimum: bounded coefficients that fail it
/// (openings at round-off rates) are removed and the face is solved again, until every remaining
/// one passes.
fn polish(
    problem: &ConstrainedProblem,
    best: Relaxed,
    work: &mut ConstrainedWork,
) -> Result<(Vec<f64>, f64, f64), RockingError> {
    let cone = &problem.cone;
    let p = problem.p();
    let (rows, all, set) = (&mut work.rows, &mut work.all, &mut work.solver.set);
    rows.clear();
    rows.extend(0..problem.nc);
    let ws = &mut work.face;
    let Relaxed {
        mut y,
        mut objective,
        mut condition,
    } = best;
    loop {
        all.clear();
        all.extend(0..p);
        let largest = cone.largest_rate(all, &y);
        let weak =
            |i: usize| cone.gens[i].bounded && y[i] != 0.0 && !cone.admissible(i, y[i], largest);
        if !(0..p).any(weak) {
            return Ok((y, objective, condition));
        }
        set.clear();
        set.extend((0..p).filter(|&i| !cone.gens[i].bounded || (y[i] != 0.0 && !weak(i))));
        let Some(info) = problem.solve_face(set, rows, ws)? else {
            // Dropping round-off openings cannot be done without breaking the closure: keep them.
            return Ok((y, objective, condition));
        };
        y.iter_mut().for_each(|v| *v = 0.0);
        for (&i, &v) in set.iter().zip(&ws.y) {
            y[i] = v;
        }
        objective = info.objective;
        condition = info.condition;
    }
}
