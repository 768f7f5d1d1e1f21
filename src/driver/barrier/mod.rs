//! The potential-energy barrier behind the column's energy-bound stop
//! ([`super::StoppingOptions::stop_when_safe_column`]), certified by branch and bound with
//! interval arithmetic (docs/column-early-stop.md).
//!
//! The stop is exact if, for a column of `n` equal blocks,
//! - (L1) `V ≥ 0` in every configuration where no part has tipped, and
//! - (L2) `V ≥ (1 − ε) E_tip` where a part tips first (or a block reaches 90°),
//!
//! with `(1 − ε) > 0.81`, the square of the stop's safety factor 0.9. Both are statements about
//! the configuration space alone, scale-free: one per `n` and per-block slenderness `λ = h/b`
//! (`h`, `b` half height and half width of a block; the column's H/B is `n λ`). Units here:
//! `b = 1`, every block of mass 1, `g = 1`.
//!
//! Coordinates: `ψ_k` the rotation of block `k` relative to the block below (interface `k`,
//! positive about the left corner, negative about the right: `s_k = sign ψ_k`), `θ_k = Σ_{j≤k} ψ_j`
//! the absolute rotation. With `u_k = ((s_k − s_{k+1}), 2λ)` (block `k`'s bottom pivot to its top
//! pivot) and `w_k = (s_k, λ)` (bottom pivot to its centre), `M_k = n − k` the blocks above
//! interface `k` and `(X_k, Y_k) = M_{k+1} u_k + w_k`:
//! - `V = Σ_k X_k sin θ_k − Y_k (1 − cos θ_k)`, and
//! - the part above interface `k` has not tipped iff its centre is on the inner side of the
//!   pivot in the frame of block `k − 1`: `m_k = s_k Σ_{i≥k} (X_i cos φ_i − Y_i sin φ_i) ≥ 0`,
//!   `φ_i = ψ_k + … + ψ_i`.
//!
//! Where no part above an interface has tipped, `|ψ_k| ≤ atan(2/λ)` (by induction from the top:
//! the centre of the part above `k` lies strictly inside the block's width and at least `λ` above
//! its bottom, so it tips before `tan |ψ_k|` reaches `2/λ`), and a closed interface (`ψ_k = 0`)
//! has its part's centre strictly inside both corners. So, on each orthant `s` of signs, the set
//! of configurations where nothing has tipped lies in `{t = s ψ ∈ [0, atan(2/λ)]ⁿ, m_k ≥ 0 ∀k}`,
//! and a first tipping is where some `m_k = 0`. The branch and bound covers each orthant's box
//! (and the range of `λ`) with boxes, each of which is
//! - outside: some `m_k < 0` on the whole box (`m_k`'s upper bound below zero), or
//! - inside (every `m_k > 0`, no `|θ_k|` reaching π/2): `V ≥ 0` on it, or
//! - on the boundary: `V ≥ (1 − ε) E_tip` on it, `E_tip` the smallest rigid mechanism's energy;
//!
//! and bisects the others. Bounds of `V`: the better of the natural interval extension (each
//! `f_k(θ_k)` separately) and the mean-value form about the box's centre, with the gradient in
//! `t` and `λ` enclosed by intervals; on boxes with a corner at the straight column
//! (`V(0, λ) = 0`) the mean-value form about that corner.

mod interval;

use std::f64::consts::FRAC_PI_2;

use crate::model::column::Column;
use interval::Interval;

/// The columns for which the barrier is certified (n equal blocks, the column's H/B range), by
/// the test `the_barrier_is_certified_for_the_columns_the_stop_is_the_default_for` with
/// [`CERTIFIED_EPSILON`].
pub const CERTIFIED_COLUMNS: [(usize, f64, f64); 2] = [(2, 3.0, 12.0), (3, 3.0, 12.0)];

/// The ε of [`CERTIFIED_COLUMNS`]: `V ≥ (1 − ε) E_tip` at every first tipping.
pub const CERTIFIED_EPSILON: f64 = 1e-3;

/// Whether the column stop is certified exact for `n_blocks` equal blocks with the column's H/B
/// `slenderness` (one of [`CERTIFIED_COLUMNS`]).
pub fn column_stop_is_certified(n_blocks: usize, slenderness: f64) -> bool {
    CERTIFIED_COLUMNS
        .iter()
        .any(|&(n, lo, hi)| n == n_blocks && (lo..=hi).contains(&slenderness))
}

/// Whether `column` is one of [`CERTIFIED_COLUMNS`]: equal blocks (width, height, mass) on full
/// contact, whose number and H/B (`n × height / width`) are certified. The moments of inertia
/// do not matter: the lemmas are about the configurations alone.
pub fn column_is_certified(column: &Column) -> bool {
    let blocks = column.blocks();
    let first = blocks[0];
    let equal = blocks.iter().all(|b| {
        b.width == first.width
            && b.height == first.height
            && b.mass == first.mass
            && b.contact_width.map_or(true, |c| c == b.width)
    });
    equal
        && column_stop_is_certified(
            blocks.len(),
            blocks.len() as f64 * first.height / first.width,
        )
}

/// What [`certify_column_barrier`] proved.
#[derive(Clone, Debug, PartialEq)]
pub struct BarrierCertificate {
    pub n_blocks: usize,
    /// The column's H/B range.
    pub slenderness: (f64, f64),
    pub epsilon: f64,
    /// A lower bound of `V / E_tip` over every first tipping (≥ `1 − epsilon`).
    pub min_ratio: f64,
    /// Boxes examined, and those on the tipping boundary.
    pub boxes: usize,
    pub boundary_boxes: usize,
}

/// Where the certificate could not be completed: a box that could be neither discarded nor
/// bounded (the bound may be false there, or the boxes too many).
#[derive(Clone, Debug, PartialEq)]
pub struct BarrierFailure {
    pub reason: String,
    /// Signs of the interface rotations of the box's orthant.
    pub signs: Vec<f64>,
    /// Its interface rotations `ψ` (centre) and per-block slenderness `λ` (centre).
    pub psi: Vec<f64>,
    pub lambda: f64,
    /// `V / E_tip` at the centre (the configuration may be inside, outside or on the boundary).
    pub ratio_at_centre: f64,
}

/// Certifies (L1) and (L2) for `n_blocks` equal blocks and every column H/B in `slenderness`,
/// examining at most `max_boxes` boxes.
pub fn certify_column_barrier(
    n_blocks: usize,
    slenderness: (f64, f64),
    epsilon: f64,
    max_boxes: usize,
) -> Result<BarrierCertificate, BarrierFailure> {
    assert!(epsilon > 0.0 && epsilon < 0.19, "epsilon {epsilon}");
    certify(n_blocks, slenderness, 1.0 - epsilon, max_boxes, 1e-12).map(|mut c| {
        c.epsilon = epsilon;
        c
    })
}

/// [`certify_column_barrier`] with the bound `V ≥ ratio · E_tip` on the boundary, giving up on
/// boxes narrower than `min_width` (relative to the first box).
fn certify(
    n_blocks: usize,
    slenderness: (f64, f64),
    ratio: f64,
    max_boxes: usize,
    min_width: f64,
) -> Result<BarrierCertificate, BarrierFailure> {
    let n = n_blocks;
    assert!(n >= 1 && slenderness.0 > 0.0 && slenderness.0 <= slenderness.1);
    // Per-block λ = (H/B) / n, rounded outwards.
    let lambda = Interval::new(
        interval::next_down(slenderness.0 / n as f64),
        interval::next_up(slenderness.1 / n as f64),
    );
    // The box of each orthant: t_k ∈ [0, atan(2/λ_min)] (rounded up).
    let t_max = (2.0 / lambda.lo).atan() + 1e-9;
    let mut cert = BarrierCertificate {
        n_blocks,
        slenderness,
        epsilon: 1.0 - ratio,
        min_ratio: f64::INFINITY,
        boxes: 0,
        boundary_boxes: 0,
    };
    for orthant in 0..(1usize << n) {
        let signs: Vec<f64> = (0..n)
            .map(|k| if orthant >> k & 1 == 1 { -1.0 } else { 1.0 })
            .collect();
        let column = Pattern::new(&signs);
        let mut stack = vec![Cell {
            t: vec![Interval::new(0.0, t_max); n],
            lambda,
        }];
        while let Some(cell) = stack.pop() {
            cert.boxes += 1;
            if cert.boxes > max_boxes {
                return Err(column.failure(&cell, "too many boxes"));
            }
            match column.classify(&cell, ratio) {
                Verdict::Outside | Verdict::Inside => {}
                Verdict::Boundary(ratio) => {
                    cert.boundary_boxes += 1;
                    cert.min_ratio = cert.min_ratio.min(ratio);
                }
                Verdict::Unknown => {
                    // Bisect the widest side (angles against t_max, λ against its range).
                    let mut widest = (0.0, 0);
                    for (k, t) in cell.t.iter().enumerate() {
                        widest = widest.max_by_width(t.width() / t_max, k);
                    }
                    if lambda.width() > 0.0 {
                        widest = widest.max_by_width(cell.lambda.width() / lambda.width(), n);
                    }
                    if widest.0 < min_width {
                        return Err(column.failure(&cell, "a box too small to bound"));
                    }
                    let (a, b) = cell.split(widest.1);
                    stack.push(a);
                    stack.push(b);
                }
            }
        }
    }
    Ok(cert)
}

trait Widest {
    fn max_by_width(self, w: f64, k: usize) -> Self;
}

impl Widest for (f64, usize) {
    fn max_by_width(self, w: f64, k: usize) -> Self {
        if w > self.0 {
            (w, k)
        } else {
            self
        }
    }
}

/// A box: `t = s ψ` per interface and `λ`.
#[derive(Clone, Debug)]
struct Cell {
    t: Vec<Interval>,
    lambda: Interval,
}

impl Cell {
    fn split(&self, side: usize) -> (Cell, Cell) {
        let (mut a, mut b) = (self.clone(), self.clone());
        let iv = if side < self.t.len() {
            self.t[side]
        } else {
            self.lambda
        };
        let mid = iv.mid();
        let (lo, hi) = (Interval::new(iv.lo, mid), Interval::new(mid, iv.hi));
        if side < self.t.len() {
            a.t[side] = lo;
            b.t[side] = hi;
        } else {
            a.lambda = lo;
            b.lambda = hi;
        }
        (a, b)
    }
}

enum Verdict {
    /// Some part has certainly tipped on the whole box.
    Outside,
    /// Nothing tipped or fallen on the box, and `V ≥ 0` on it.
    Inside,
    /// The box may hold a first tipping or a fallen block, and `V ≥ (1 − ε) E_tip` on it: the
    /// lower bound of `V / E_tip`.
    Boundary(f64),
    Unknown,
}

/// The column of one orthant of signs: `X_k`, `c_k` (`Y_k = c_k λ`).
struct Pattern {
    s: Vec<f64>,
    x: Vec<f64>,
    c: Vec<f64>,
}

impl Pattern {
    fn new(signs: &[f64]) -> Pattern {
        let n = signs.len();
        let above = |k: usize| (n - k - 1) as f64;
        let x = (0..n)
            .map(|k| {
                let next = if k + 1 < n { signs[k + 1] } else { 0.0 };
                above(k) * (signs[k] - next) + signs[k]
            })
            .collect();
        let c = (0..n).map(|k| 2.0 * above(k) + 1.0).collect();
        Pattern {
            s: signs.to_vec(),
            x,
            c,
        }
    }

    fn psi(&self, t: &[Interval]) -> Vec<Interval> {
        t.iter()
            .zip(&self.s)
            .map(|(&t, &s)| if s < 0.0 { -t } else { t })
            .collect()
    }

    fn thetas(psi: &[Interval]) -> Vec<Interval> {
        let mut acc = Interval::point(0.0);
        psi.iter()
            .map(|&p| {
                acc = acc + p;
                acc
            })
            .collect()
    }

    /// `V` (natural extension).
    fn potential(&self, theta: &[Interval], lambda: Interval) -> Interval {
        let mut v = Interval::point(0.0);
        for (k, &th) in theta.iter().enumerate() {
            let drop = Interval::point(1.0) - th.cos();
            v = v + th.sin() * self.x[k] - lambda * self.c[k] * drop;
        }
        v
    }

    /// The non-tipping margins `m_k`.
    fn margins(&self, psi: &[Interval], lambda: Interval) -> Vec<Interval> {
        let n = psi.len();
        (0..n)
            .map(|k| {
                let (mut phi, mut m) = (Interval::point(0.0), Interval::point(0.0));
                for i in k..n {
                    phi = phi + psi[i];
                    m = m + phi.cos() * self.x[i] - lambda * self.c[i] * phi.sin();
                }
                m * self.s[k]
            })
            .collect()
    }

    /// `E_tip(λ) = min_k M_k / (λ M_k + √(1 + (λ M_k)²))`.
    fn tipping_energy(n: usize, lambda: Interval) -> Interval {
        let mut e = Interval::point(f64::INFINITY);
        for k in 0..n {
            let m = (n - k) as f64;
            let y = lambda * m;
            let den = y + (Interval::point(1.0) + y * y).sqrt();
            let ek = Interval::point(m).div_positive(den);
            e = Interval::new(e.lo.min(ek.lo), e.hi.min(ek.hi));
        }
        e
    }

    /// Lower bound of `V` on the box: the better of the natural extension and the mean-value
    /// form (about the corner at the straight column when the box has it, else the centre).
    fn potential_lower_bound(&self, cell: &Cell, theta: &[Interval]) -> f64 {
        let n = cell.t.len();
        let natural = self.potential(theta, cell.lambda).lo;
        // Gradient: ∂V/∂t_j = s_j Σ_{k≥j} f_k'(θ_k), ∂V/∂λ = −Σ c_k (1 − cos θ_k).
        let fprime: Vec<Interval> = (0..n)
            .map(|k| theta[k].cos() * self.x[k] - cell.lambda * self.c[k] * theta[k].sin())
            .collect();
        let mut dt = vec![Interval::point(0.0); n];
        let mut acc = Interval::point(0.0);
        for j in (0..n).rev() {
            acc = acc + fprime[j];
            dt[j] = acc * self.s[j];
        }
        let at_straight = cell.t.iter().all(|t| t.lo == 0.0);
        let form = if at_straight {
            // V(0, λ) = 0 for every λ: expand along t only.
            let mut v = Interval::point(0.0);
            for j in 0..n {
                v = v + dt[j] * cell.t[j];
            }
            v
        } else {
            let mut dl = Interval::point(0.0);
            for k in 0..n {
                dl = dl - (Interval::point(1.0) - theta[k].cos()) * self.c[k];
            }
            let tc: Vec<Interval> = cell.t.iter().map(|t| Interval::point(t.mid())).collect();
            let lc = Interval::point(cell.lambda.mid());
            let mut v = self.potential(&Pattern::thetas(&self.psi(&tc)), lc);
            for j in 0..n {
                v = v + dt[j] * (cell.t[j] - tc[j]);
            }
            v + dl * (cell.lambda - lc)
        };
        natural.max(form.lo)
    }

    fn classify(&self, cell: &Cell, ratio: f64) -> Verdict {
        let psi = self.psi(&cell.t);
        let theta = Pattern::thetas(&psi);
        let margins = self.margins(&psi, cell.lambda);
        if margins.iter().any(|m| m.hi < 0.0) {
            return Verdict::Outside;
        }
        let boundary = margins.iter().any(|m| m.lo <= 0.0)
            || theta
                .iter()
                .any(|th| th.hi >= FRAC_PI_2 - 1e-9 || th.lo <= -FRAC_PI_2 + 1e-9);
        let v = self.potential_lower_bound(cell, &theta);
        if !boundary {
            return if v >= 0.0 {
                Verdict::Inside
            } else {
                Verdict::Unknown
            };
        }
        let e_tip = Pattern::tipping_energy(cell.t.len(), cell.lambda).hi;
        if v >= (Interval::point(ratio) * e_tip).hi {
            Verdict::Boundary(interval::next_down(v / e_tip))
        } else {
            Verdict::Unknown
        }
    }

    fn failure(&self, cell: &Cell, reason: &str) -> BarrierFailure {
        let tc: Vec<Interval> = cell.t.iter().map(|t| Interval::point(t.mid())).collect();
        let lambda = cell.lambda.mid();
        let psi = self.psi(&tc);
        let v = self.potential(&Pattern::thetas(&psi), Interval::point(lambda));
        let e = Pattern::tipping_energy(tc.len(), Interval::point(lambda));
        BarrierFailure {
            reason: reason.to_string(),
            signs: self.s.clone(),
            psi: psi.iter().map(|p| p.mid()).collect(),
            lambda,
            ratio_at_centre: v.mid() / e.mid(),
        }
    }
}

/// `(V, margins m_k)` of the configuration `psi` (interface rotations, signed) of `n` equal
/// blocks of per-block slenderness `lambda`, in the units of this module (`b = 1`, masses 1,
/// `g = 1`): the formulas the certificate bounds, for checking them against the driver.
#[cfg(test)]
pub(crate) fn configuration(psi: &[f64], lambda: f64) -> (f64, Vec<f64>) {
    let signs: Vec<f64> = psi
        .iter()
        .map(|&p| if p < 0.0 { -1.0 } else { 1.0 })
        .collect();
    let col = Pattern::new(&signs);
    let p: Vec<Interval> = psi.iter().map(|&x| Interval::point(x)).collect();
    let th = Pattern::thetas(&p);
    let l = Interval::point(lambda);
    (
        col.potential(&th, l).mid(),
        col.margins(&p, l).iter().map(|m| m.mid()).collect(),
    )
}

#[cfg(test)]
mod tests;
