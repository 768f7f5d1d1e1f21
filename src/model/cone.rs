//! The common shape of the opening and the impact model (SPEC §4): choose, among crack
//! configurations, the admissible one of maximal kinetic energy — equivalently, project a vector
//! in the kinetic metric onto a union of convex cones.
//!
//! A problem is a list of *generators*: directions in the `2n` DOF space that a configuration may
//! use. A generator is either free (the DOF of an interface that is already open and stays so) or
//! bounded (its coefficient must be `>= 0`: a closed interface opening about one corner, or the
//! impacting interface rotating on about its next bump). The two corners of a closed interface
//! form a *group*: at most one of them may be non-zero. With `D` the generator matrix, the problem
//! is `min ½ yᵀAy − bᵀy`, `A = DᵀMD`, over admissible `y`:
//! - impact: `b = Dᵀ M v⁻` (kinetic-metric projection of the pre-impact velocity, thesis Eq. 7);
//! - opening: `b = Dᵀ q` (Gauss's principle; thesis Eq. 6 on each configuration).
//!
//! On a face (a set `S` of non-zero generators) the optimum solves `A_SS y_S = b_S` and its value
//! is `−½ bᵀy`, so the best admissible face is the one with the largest criterion `bᵀy = yᵀAy`
//! (twice the kinetic energy after an impact; `aᵀMa` for an opening). The problem is solved in
//! Jacobi-scaled variables (`Â = D_s A D_s` with unit diagonal) so that thresholds are
//! scale-free and a tiny block on a huge one stays well posed.

use crate::error::{ErrorKind, RockingError};

/// Which algorithm chooses the configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "lowercase")
)]
pub enum Solver {
    /// Enumeration for few closed interfaces (cheap and gives the full report), projection above.
    Auto,
    /// The thesis's exhaustive search over `3^n_closed` (× 2 for impacts) configurations.
    Enumerate,
    /// Relaxed bound-constrained least squares with branching on conflicting corners (SPEC §4).
    Projection,
}

impl Solver {
    /// Decodes the C option value (0 auto, 1 enumerate, 2 projection).
    pub fn from_code(code: u32) -> Option<Solver> {
        match code {
            0 => Some(Solver::Auto),
            1 => Some(Solver::Enumerate),
            2 => Some(Solver::Projection),
            _ => None,
        }
    }

    /// The C option value.
    pub fn code(self) -> u32 {
        match self {
            Solver::Auto => 0,
            Solver::Enumerate => 1,
            Solver::Projection => 2,
        }
    }
}

/// Options of both models.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelOptions {
    /// Consecutive impacts per closing (1 = Housner, 2 = one bump in the middle, …). Ignored by
    /// the opening model.
    pub n_impacts: u32,
    /// Which solver.
    pub solver: Solver,
    /// Relative tolerance of the admissibility tests (a newly opened DOF must move the admissible
    /// way by more than `tolerance` times the problem's scale).
    pub tolerance: f64,
    /// Enumeration refuses problems with more closed interfaces than this.
    pub max_enumerated_closed: usize,
    /// With [`Solver::Auto`], enumerate when there are at most this many closed interfaces.
    pub auto_enumerate_up_to: usize,
}

impl Default for ModelOptions {
    fn default() -> ModelOptions {
        ModelOptions {
            n_impacts: 1,
            solver: Solver::Auto,
            tolerance: 1e-12,
            max_enumerated_closed: 12,
            auto_enumerate_up_to: 2,
        }
    }
}

impl ModelOptions {
    /// Checks the options.
    pub fn validate(&self) -> Result<(), RockingError> {
        if self.n_impacts == 0 || self.n_impacts > 10_000 {
            return Err(RockingError::new(
                ErrorKind::InvalidOptions,
                format!("n_impacts = {}, expected 1..=10000", self.n_impacts),
            ));
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance <= 1e-2) {
            return Err(RockingError::new(
                ErrorKind::InvalidOptions,
                format!(
                    "tolerance = {}, expected a finite value in (0, 0.01]",
                    self.tolerance
                ),
            ));
        }
        Ok(())
    }
}

/// What a model call did, for logs and for the caller's confidence in the answer. (With the
/// `serde` feature, a NaN `runner_up` becomes `null` in JSON, which JSON cannot read back as a
/// number.)
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ModelReport {
    /// The solver that ran (never `Auto`).
    pub solver: Solver,
    /// Configurations (enumeration) or relaxed sub-problems (projection) solved.
    pub configurations_examined: u64,
    /// Admissible configurations found (enumeration; for projection the feasible leaves).
    pub admissible: u64,
    /// Whether the configuration changed (something opened, or the closing interface closed).
    pub changed: bool,
    /// Another admissible configuration has the same criterion to a relative 1e-9: the choice
    /// was made by the fixed search order (deterministic) and may deserve a look.
    pub tie: bool,
    /// Consecutive impacts actually applied (0 for an opening).
    pub impacts_applied: u32,
    /// Impact: kinetic energy `½ v⁻ᵀ M v⁻` before. Opening: 0.
    pub kinetic_before: f64,
    /// Impact: kinetic energy `½ v⁺ᵀ M v⁺` after. Opening: `½ aᵀMa` of the chosen configuration
    /// (the kinetic energy after the first step, divided by `dt²`, thesis 3.2.2).
    pub kinetic_after: f64,
    /// The same measure for the best other admissible configuration examined (NaN if none).
    pub runner_up: f64,
    /// Estimate of the condition number of the (Jacobi-scaled) system of the chosen configuration.
    pub condition_estimate: f64,
}

impl ModelReport {
    pub(crate) fn empty(solver: Solver) -> ModelReport {
        ModelReport {
            solver,
            configurations_examined: 0,
            admissible: 0,
            changed: false,
            tie: false,
            impacts_applied: 0,
            kinetic_before: 0.0,
            kinetic_after: 0.0,
            runner_up: f64::NAN,
            condition_estimate: 1.0,
        }
    }
}

/// A generator: a direction `Σ coef · e_dof` (one or two terms) in the DOF space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Generator {
    pub terms: [(usize, f64); 2],
    pub n_terms: usize,
    pub bounded: bool,
    pub group: Option<usize>,
}

impl Generator {
    pub fn unit(dof: usize, sign: f64, bounded: bool, group: Option<usize>) -> Generator {
        Generator {
            terms: [(dof, sign), (0, 0.0)],
            n_terms: 1,
            bounded,
            group,
        }
    }

    pub fn terms(&self) -> &[(usize, f64)] {
        &self.terms[..self.n_terms]
    }
}

/// A cone problem in Jacobi-scaled variables.
pub(crate) struct ConeProblem {
    pub gens: Vec<Generator>,
    /// Generator index pairs of the groups (the two corners of a closed interface).
    pub groups: Vec<[usize; 2]>,
    /// Bounded generators that belong to no group.
    pub singles: Vec<usize>,
    /// Scaled `Â`, row-major `p × p`, unit diagonal.
    pub a: Vec<f64>,
    /// Scaled `b̂`.
    pub b: Vec<f64>,
    /// `y = scale ⊙ ŷ`.
    pub scale: Vec<f64>,
    /// A bounded scaled coefficient is admissible when above this.
    pub threshold: f64,
    /// Relative tolerance of the options.
    pub tolerance: f64,
}

impl ConeProblem {
    /// Builds `Â`, `b̂` from the row-major `m × m` mass matrix and the right-hand side `rhs`
    /// (`b = Dᵀ rhs`).
    pub fn new(
        gens: Vec<Generator>,
        mass: &[f64],
        m: usize,
        rhs: &[f64],
        tolerance: f64,
    ) -> Result<ConeProblem, RockingError> {
        let p = gens.len();
        let mut a = vec![0.0; p * p];
        let mut b = vec![0.0; p];
        for i in 0..p {
            for j in i..p {
                let mut s = 0.0;
                for &(di, ci) in gens[i].terms() {
                    for &(dj, cj) in gens[j].terms() {
                        s += ci * cj * mass[di * m + dj];
                    }
                }
                a[i * p + j] = s;
                a[j * p + i] = s;
            }
            b[i] = gens[i].terms().iter().map(|&(d, c)| c * rhs[d]).sum();
        }
        let mut scale = vec![0.0; p];
        for i in 0..p {
            let d = a[i * p + i];
            if d.is_nan() || d <= 0.0 {
                return Err(RockingError::new(
                    ErrorKind::NotPositiveDefinite,
                    format!("diagonal entry of a configuration's mass matrix is {d}"),
                ));
            }
            scale[i] = 1.0 / d.sqrt();
        }
        for i in 0..p {
            for j in 0..p {
                a[i * p + j] *= scale[i] * scale[j];
            }
            a[i * p + i] = 1.0;
            b[i] *= scale[i];
        }
        let bmax = b.iter().fold(0.0_f64, |acc, v| acc.max(v.abs()));
        let mut groups = Vec::new();
        let mut singles = Vec::new();
        let mut group_members: Vec<Vec<usize>> = Vec::new();
        for (i, g) in gens.iter().enumerate() {
            match g.group {
                Some(k) => {
                    if group_members.len() <= k {
                        group_members.resize(k + 1, Vec::new());
                    }
                    group_members[k].push(i);
                }
                None if g.bounded => singles.push(i),
                None => {}
            }
        }
        for members in group_members {
            if members.len() == 2 {
                groups.push([members[0], members[1]]);
            }
        }
        Ok(ConeProblem {
            gens,
            groups,
            singles,
            a,
            b,
            scale,
            threshold: tolerance * bmax,
            tolerance,
        })
    }

    pub fn p(&self) -> usize {
        self.gens.len()
    }

    /// Gathers `Â_SS` (row-major) into `work` and `b̂_S` into `x`, factors and solves in place.
    /// Fails with [`ErrorKind::NotPositiveDefinite`] if `Â_SS` is not positive definite.
    pub fn solve_face(
        &self,
        set: &[usize],
        work: &mut Vec<f64>,
        x: &mut Vec<f64>,
    ) -> Result<(), RockingError> {
        let k = set.len();
        let p = self.p();
        work.clear();
        x.clear();
        for &r in set {
            for &c in set {
                work.push(self.a[r * p + c]);
            }
            x.push(self.b[r]);
        }
        if !crate::model::cholesky::factor(work, k) {
            return Err(RockingError::new(
                ErrorKind::NotPositiveDefinite,
                "the mass matrix of a configuration is not positive definite",
            ));
        }
        crate::model::cholesky::solve(work, k, x);
        Ok(())
    }

    /// Whether the bounded generator `i` with scaled coefficient `v` opens admissibly (SPEC §2–3:
    /// strictly the admissible way). Two tests, both relative: `ŷ` above the threshold (its
    /// kinetic-energy weight is not round-off), and its rate `y = s ŷ` above `tolerance` times
    /// the largest rate `largest_rate` of the same solution (all DOFs are rotations, so rates
    /// compare directly; a tiny block on a huge one must not open the huge one at 1e-16 rad/s).
    pub fn admissible(&self, i: usize, v: f64, largest_rate: f64) -> bool {
        v > self.threshold && v * self.scale[i] > self.tolerance * largest_rate
    }

    /// Whether a face solution is stationary in its own cone (the KKT condition): no bounded
    /// generator at zero whose group is not already used by the face has a gradient
    /// `b̂_j − (Âŷ)_j` above the threshold. This is the first-order form of "nothing more
    /// opens": just past an opening event the reaction is tiny and the kinetic-energy criterion
    /// of the faces differs only in the square of it (below round-off), while this test still
    /// sees it — the same test as [`crate::check_configuration`] and the projection solver.
    pub fn stationary(&self, set: &[usize], x: &[f64]) -> bool {
        let p = self.p();
        let in_set = |j: usize| set.contains(&j);
        (0..p).all(|j| {
            let g = &self.gens[j];
            if !g.bounded || in_set(j) {
                return true;
            }
            if let Some(k) = g.group {
                if set.iter().any(|&s| self.gens[s].group == Some(k)) {
                    return true;
                }
            }
            let row = &self.a[j * p..(j + 1) * p];
            let grad = self.b[j] - set.iter().zip(x).map(|(&s, v)| row[s] * v).sum::<f64>();
            grad <= self.threshold
        })
    }

    /// Largest unscaled coefficient `max |s_i ŷ_i|` over a face.
    pub fn largest_rate(&self, set: &[usize], x: &[f64]) -> f64 {
        set.iter()
            .zip(x)
            .fold(0.0_f64, |a, (&i, v)| a.max((v * self.scale[i]).abs()))
    }

    /// Criterion `b̂ᵀŷ` of a face solution.
    pub fn criterion(&self, set: &[usize], x: &[f64]) -> f64 {
        set.iter().zip(x).map(|(&i, v)| self.b[i] * v).sum()
    }

    /// Unscaled DOF vector `D y` (length `m`) from scaled coefficients `ŷ` (length `p`).
    pub fn dof_vector(&self, y_hat: &[f64], m: usize) -> Vec<f64> {
        let mut v = Vec::new();
        self.dof_vector_into(y_hat, m, &mut v);
        v
    }

    /// [`ConeProblem::dof_vector`] into `v` (cleared first), reusing its memory.
    pub fn dof_vector_into(&self, y_hat: &[f64], m: usize, v: &mut Vec<f64>) {
        v.clear();
        v.resize(m, 0.0);
        for (i, g) in self.gens.iter().enumerate() {
            let yi = y_hat[i] * self.scale[i];
            if yi != 0.0 {
                for &(d, c) in g.terms() {
                    v[d] += c * yi;
                }
            }
        }
    }
}

/// Every face of a cone problem in the enumeration's order (thesis 3.2.2–3.2.3): a mixed-radix
/// counter over the groups (closed, first corner, second corner: 3 choices) and the singles
/// (closed or on: 2), the free generators always in the face.
pub(crate) struct Faces<'a> {
    cone: &'a ConeProblem,
    free: Vec<usize>,
    digits: Vec<u8>,
    radices: Vec<u8>,
    done: bool,
}

impl<'a> Faces<'a> {
    pub(crate) fn new(cone: &'a ConeProblem) -> Self {
        Faces {
            cone,
            free: (0..cone.p()).filter(|&i| !cone.gens[i].bounded).collect(),
            digits: vec![0; cone.groups.len() + cone.singles.len()],
            radices: (cone.groups.iter().map(|_| 3))
                .chain(cone.singles.iter().map(|_| 2))
                .collect(),
            done: false,
        }
    }

    /// Writes the next face into `set` (cleared first); false when every face has been given.
    #[inline(always)]
    pub(crate) fn next_into(&mut self, set: &mut Vec<usize>) -> bool {
        if self.done {
            return false;
        }
        let groups = self.cone.groups.len();
        set.clear();
        set.extend_from_slice(&self.free);
        for (u, &d) in self.digits.iter().enumerate() {
            if d > 0 {
                set.push(if u < groups {
                    self.cone.groups[u][d as usize - 1]
                } else {
                    self.cone.singles[u - groups]
                });
            }
        }
        // Advance the counter; past the last face, stop.
        self.done = true;
        for (d, &radix) in self.digits.iter_mut().zip(&self.radices) {
            *d += 1;
            if *d < radix {
                self.done = false;
                break;
            }
            *d = 0;
        }
        true
    }
}

/// `ŷ` of length `p` from the coefficients `x` of the face `set` (zero elsewhere).
pub(crate) fn scatter(set: &[usize], x: &[f64], p: usize) -> Vec<f64> {
    let mut y_hat = vec![0.0; p];
    for (&i, &v) in set.iter().zip(x) {
        y_hat[i] = v;
    }
    y_hat
}

/// The chosen face of a cone problem.
pub(crate) struct ConeSolution {
    /// Scaled coefficients `ŷ` (length `p`, zero outside the face).
    pub y_hat: Vec<f64>,
    /// Criterion `bᵀy` of the chosen face.
    pub criterion: f64,
    /// Criterion of the best other admissible face examined (NaN if none).
    pub runner_up: f64,
    pub examined: u64,
    pub admissible: u64,
    pub tie: bool,
    pub condition: f64,
    pub solver: Solver,
}

/// Relative gap under which two admissible faces are reported as a tie.
pub(crate) const TIE_GAP: f64 = 1e-9;
