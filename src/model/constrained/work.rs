//! The memory of the constrained problems (SPEC §9's loops meet one at every impact): the
//! buffers a problem is built and solved in, kept from one problem to the next, and the
//! problem's groups and singles built into them.

use crate::model::cone::{ConeProblem, Generator};
use crate::model::constrained::householder::PivotedQr;
use crate::model::constrained::problem::{ConstrainedProblem, FaceWork};
use crate::model::constrained::projection::SolverWork;

/// Buffers of the constrained problems and their solves, reused from one problem to the next
/// (the loop driver's impacts): a problem built and solved in them allocates nothing once they
/// have grown but its solution.
#[derive(Default)]
pub(crate) struct ConstrainedWork {
    /// The face solves' buffers: the definiteness check's, then the solver's.
    pub face: FaceWork,
    /// Factors of the start point's and a branch's rows.
    pub qr: PivotedQr,
    /// Scratch: a `Kᵀ` or the scaled constraint columns, a particular solution and its
    /// right-hand side, index lists (every generator or the free ones, every row).
    pub kt: Vec<f64>,
    pub u: Vec<f64>,
    pub rhs: Vec<f64>,
    pub all: Vec<usize>,
    pub rows: Vec<usize>,
    /// The projection solver's buffers.
    pub solver: SolverWork,
    /// The storage of the last problem ([`ConstrainedWork::recycle`]), for the next.
    pub(super) spare: Spare,
}

/// A problem's storage between two problems.
#[derive(Default)]
pub(super) struct Spare {
    pub a: Vec<f64>,
    pub b: Vec<f64>,
    pub scale: Vec<f64>,
    pub c: Vec<f64>,
    pub r: Vec<f64>,
    pub start: Vec<f64>,
    pub groups: Vec<[usize; 2]>,
    pub singles: Vec<usize>,
    pub members: Vec<([usize; 2], usize)>,
    pub all_qr: PivotedQr,
}

impl ConstrainedWork {
    /// Keeps the memory of a solution's point (the `y_hat` of a solve in this work) for the
    /// solver's next relaxed problems.
    pub fn keep_point(&mut self, y: Vec<f64>) {
        self.solver.keep_point(y);
    }

    /// Takes back the storage of a problem built by [`ConstrainedProblem::new_in`] (its
    /// generators are the caller's: they are returned).
    pub fn recycle(&mut self, problem: ConstrainedProblem) -> Vec<Generator> {
        let ConstrainedProblem {
            cone,
            c,
            r,
            start,
            all_qr,
            ..
        } = problem;
        let spare = &mut self.spare;
        (spare.c, spare.r, spare.start) = (c, r, start);
        if let Some(qr) = all_qr {
            spare.all_qr = qr;
        }
        let ConeProblem {
            groups,
            singles,
            gens,
            a,
            b,
            scale,
            ..
        } = cone;
        (spare.groups, spare.singles, spare.a, spare.b, spare.scale) =
            (groups, singles, a, b, scale);
        gens
    }
}

/// The two corners of each closed interface (generator index pairs), as [`ConeProblem::new`],
/// into `out`; `members` is scratch.
pub(super) fn groups_into(
    gens: &[Generator],
    members: &mut Vec<([usize; 2], usize)>,
    out: &mut Vec<[usize; 2]>,
) {
    // Per group: its first two members and how many it has (a group of exactly two is kept),
    // in one list rather than one list per group.
    members.clear();
    for (i, g) in gens.iter().enumerate() {
        if let Some(k) = g.group {
            if members.len() <= k {
                members.resize(k + 1, ([0; 2], 0));
            }
            let (first, count) = &mut members[k];
            if *count < 2 {
                first[*count] = i;
            }
            *count += 1;
        }
    }
    out.clear();
    out.extend(
        members
            .iter()
            .filter(|&&(_, count)| count == 2)
            .map(|&(pair, _)| pair),
    );
}

/// Bounded generators outside any group, into `out`.
pub(super) fn singles_into(gens: &[Generator], out: &mut Vec<usize>) {
    out.clear();
    out.extend((0..gens.len()).filter(|&i| gens[i].bounded && gens[i].group.is_none()));
}
