//! The transformed OAS (`f = p a_p / a_p,min`, thesis Eq. 19) of a computed spectrum: its
//! leftmost point `f_min` and `t_1 = i_cr / f_min` (Eq. 20), the inclined line of Eq. 28
//! (`t_1'`, `β`), and the check that the simplified spectra (Eq. 21, 29, 30) are conservative.

use super::{Oas, OasPoint};

/// The improved fit of the transformed OAS (Eq. 28): `f = L/β + 1/t_1'`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InclinedFit {
    /// `t_1'` \[s\]; `f64::INFINITY` for a line through the origin (the thesis's "~∞").
    pub t1_prime: f64,
    /// `β` \[s\]: the slope of `f` against the level is `1/β`; `f64::INFINITY` for a vertical
    /// line.
    pub beta: f64,
}

/// The numbers of an OAS that the design method uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OasSummary {
    /// The most vulnerable boundary point: smallest `f` (Eq. 19). `None` when nothing overturns.
    pub f_min: Option<OasPoint>,
    /// `t_1 = i_cr / f_min` \[s\] (Eq. 20, exact `i_cr` of the slenderness).
    pub t1: Option<f64>,
    /// The inclined line (Eq. 28).
    pub fit: Option<InclinedFit>,
    /// Total simulations.
    pub simulations: usize,
}

/// Which of the simplified spectra a check is about, and what it found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConservativeCheck {
    /// Boundary points predicted safe by Eq. 21 (exact `i_cr`) although they overturn.
    pub eq21: Vec<OasPoint>,
    /// ... by Eq. 21 / 31 with `i_cr ≈ 1`.
    pub eq21_approx: Vec<OasPoint>,
    /// ... by Eq. 29 (inclined line, as solved from Eq. 28).
    pub eq29: Vec<OasPoint>,
    /// ... by Eq. 30 (vertical and inclined line).
    pub eq30: Vec<OasPoint>,
}

impl ConservativeCheck {
    /// No violation at all.
    pub fn all_conservative(&self) -> bool {
        self.eq21.is_empty()
            && self.eq21_approx.is_empty()
            && self.eq29.is_empty()
            && self.eq30.is_empty()
    }
}

impl Oas {
    /// The leftmost boundary point of the transformed OAS (smallest `f`; the lowest level on a
    /// tie). Its `f` is `f_min` of Eq. 20.
    pub fn f_min(&self) -> Option<OasPoint> {
        self.boundary()
            .into_iter()
            .reduce(|a, b| if b.f < a.f { b } else { a })
    }

    /// `t_1 = i_cr / f_min` (Eq. 20).
    pub fn t1(&self) -> Option<f64> {
        self.f_min().map(|m| self.i_cr() / m.f)
    }

    /// The inclined line of Eq. 28, `f = L/β + 1/t_1'`, fitted as the line that stays left of
    /// every boundary point of the transformed OAS (so that Eq. 29 and 30 are conservative on
    /// the grid), with intercept and slope `≥ 0`, and is highest at the middle of the level
    /// range (the supporting line of the boundary's convex hull there). The thesis does not say
    /// how it fitted its lines; this is one reproducible reading.
    pub fn fit(&self) -> Option<InclinedFit> {
        let pts = self.boundary();
        if pts.is_empty() {
            return None;
        }
        let (lo, hi) = self
            .levels
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), l| {
                (lo.min(l.level), hi.max(l.level))
            });
        let mid = 0.5 * (lo + hi);
        // Candidate lines (a = intercept, b = slope): through two points, through the origin and
        // one point, horizontal through one point. Feasible: a, b >= 0 and a + b L_i <= f_i.
        let feasible = |a: f64, b: f64| {
            a >= 0.0
                && b >= 0.0
                && pts
                    .iter()
                    .all(|q| a + b * q.level <= q.f * (1.0 + 1e-12) + 1e-12)
        };
        let mut best: Option<(f64, f64, f64)> = None;
        let mut consider = |a: f64, b: f64| {
            if a.is_finite() && b.is_finite() && feasible(a, b) {
                let v = a + b * mid;
                if best.map_or(true, |(bv, _, _)| v > bv) {
                    best = Some((v, a, b));
                }
            }
        };
        for (i, p) in pts.iter().enumerate() {
            consider(0.0, p.f / p.level);
            consider(p.f, 0.0);
            for q in &pts[i + 1..] {
                if q.level != p.level {
                    let b = (q.f - p.f) / (q.level - p.level);
                    // Two points on a line through the origin leave a rounding residue as the
                    // intercept (1/a would then print t1' ~ 1e14 s): within the feasibility
                    // tolerance it is the origin line.
                    let a = p.f - b * p.level;
                    let a = if a.abs() <= 1e-12 * p.f.abs() { 0.0 } else { a };
                    consider(a, b);
                }
            }
        }
        let (_, a, b) = best?;
        Some(InclinedFit {
            t1_prime: if a > 0.0 { 1.0 / a } else { f64::INFINITY },
            beta: if b > 0.0 { 1.0 / b } else { f64::INFINITY },
        })
    }

    /// `f_min`, `t_1`, the inclined fit and the count of simulations.
    pub fn summary(&self) -> OasSummary {
        OasSummary {
            f_min: self.f_min(),
            t1: self.t1(),
            fit: self.fit(),
            simulations: self.simulations(),
        }
    }

    /// The boundary points that a simplified OAS with these parameters predicts safe although
    /// they overturn (a point exactly on the simplified line, within a relative 1e-9, counts as
    /// predicted unsafe: the line through the most vulnerable point is the definition of `t_1`).
    /// Checking the boundary suffices for [`SizeSearch::Scan`]: every unsafe size of a level is
    /// at least as small (`p` at least as large) as the boundary's and the simplified limits
    /// decrease with `p`.
    ///
    /// [`SizeSearch::Scan`]: super::SizeSearch::Scan
    pub fn check(&self, t1: f64, fit: Option<InclinedFit>) -> ConservativeCheck {
        let i_cr = self.i_cr();
        let mut out = ConservativeCheck::default();
        let violates = |limit: f64, level: f64| level < limit * (1.0 - 1e-9);
        for q in self.boundary() {
            if violates(crate::design::simplified_oas(q.p, t1, i_cr), q.level) {
                out.eq21.push(q);
            }
            if violates(crate::design::simplified_oas(q.p, t1, 1.0), q.level) {
                out.eq21_approx.push(q);
            }
            if let Some(fit) = fit {
                // Eq. 29 predicts the point safe iff it is left of the inclined line of Eq. 28
                // (the same as `level < improved_oas_eq29(p, ..)`, which solves the line for the
                // level); compared in the transformed plane so that a point on a line through
                // the origin, where `p − 1/β` is zero up to rounding, counts as on the line.
                let left_of_line = q.f
                    < crate::design::inclined_line(q.level, fit.t1_prime, fit.beta) * (1.0 - 1e-9);
                if left_of_line {
                    out.eq29.push(q);
                }
                // Eq. 30: the larger of the vertical line (i_cr ≈ 1) and Eq. 29.
                if left_of_line || violates(crate::design::simplified_oas(q.p, t1, 1.0), q.level) {
                    out.eq30.push(q);
                }
            }
        }
        out
    }
}
