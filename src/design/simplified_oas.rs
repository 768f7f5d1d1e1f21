//! The simplified overturning acceleration spectrum (thesis Eq. 20, 21) and the improved ones
//! with an inclined line (Eq. 28–30), as functions of the frequency parameter `p`.

use crate::model::single_block;

/// Vertical line of the simplified transformed OAS, `f_min = i_cr / t_1` \[1/s\] (thesis Eq. 20),
/// `i_cr = √(2 / (1 + cos δ))`; `δ → 0` gives the approximation `1 / t_1`.
pub fn f_min(t1: f64, delta: f64) -> f64 {
    single_block::normalised_critical_impulse(delta) / t1
}

/// Simplified OAS, `a_p / a_p,min = max{ i_cr / (t_1 p), 1 }` as a function of `p` (thesis
/// Eq. 21; pass `i_cr = 1` for the approximate right-hand form used in Eq. 31).
///
/// The thesis prints the factor as `t_cr`; it is `i_cr`, the only reading consistent with
/// Eq. 19 and 20 (`f = p a_p / a_p,min = f_min`).
pub fn simplified_oas(p: f64, t1: f64, i_cr: f64) -> f64 {
    (i_cr / (t1 * p)).max(1.0)
}

/// Inclined line of the improved transformed OAS (thesis Eq. 28):
/// `f = p a_p / a_p,min = (a_p / a_p,min) / β + 1 / t_1'`, returned as `f` for a given level
/// `a_p / a_p,min`. `t_1' = ∞` (printed "~∞" in Tables 4, 5) is allowed: the line passes through
/// the origin.
pub fn inclined_line(level: f64, t1_prime: f64, beta: f64) -> f64 {
    level / beta + 1.0 / t1_prime
}

/// Improved OAS with the inclined line only, `a_p / a_p,min` as a function of `p`
/// (thesis Eq. 29, solved from Eq. 28):
/// `a_p / a_p,min = max{ 1 / (t_1' (p − 1/β)), 1 }` for `p > 1/β`, and `+∞` for `p ≤ 1/β`
/// (the line never reaches such a large block: no level overturns it).
///
/// The thesis prints the right-hand side as `max{ 1/(t_1' p) − 1/β; 1 }`, which is not the
/// solution of its Eq. 28 (`p y = y/β + 1/t_1'` gives `y = 1/(t_1'(p − 1/β))`). The Eq. 28
/// reading is used here because it is the line the text describes ("an inclined line defined by
/// t_1' and its slope β"), because it is what makes the table entries `t_1' = ~∞` meaningful
/// (a line through the origin; with the printed form `β` would then drop out and every block would
/// overturn at `a_p,min`), and because with it Eq. 30 (vertical plus inclined line) is the better
/// fit the thesis says it is. The printed form is kept in [`improved_oas_eq29_as_printed`].
pub fn improved_oas_eq29(p: f64, t1_prime: f64, beta: f64) -> f64 {
    let denominator = p - 1.0 / beta;
    if denominator <= 0.0 {
        return f64::INFINITY;
    }
    (1.0 / (t1_prime * denominator)).max(1.0)
}

/// Thesis Eq. 29 exactly as printed, `max{ 1/(t_1' p) − 1/β; 1 }`, for comparison only; see
/// [`improved_oas_eq29`] for why it is not the solution of Eq. 28.
pub fn improved_oas_eq29_as_printed(p: f64, t1_prime: f64, beta: f64) -> f64 {
    (1.0 / (t1_prime * p) - 1.0 / beta).max(1.0)
}

/// Improved OAS with a vertical and an inclined line (thesis Eq. 30), as a function of `p`:
/// `a_p / a_p,min = max{ 1/(t_1 p); 1/(t_1'(p − 1/β)); 1 }` (approximate form, `i_cr ≈ 1`).
///
/// The thesis prints `max{ 1/(t_1' p); 1/(t_1' p) − 1/β; 1 }`, whose second term can never
/// govern (it is the first minus `1/β`) and whose first term would be Eq. 21 with `t_1'` instead
/// of `t_1`, more conservative than Eq. 21 everywhere because `t_1' > t_1` in the tables; that
/// contradicts "Eq. (30) is always very accurate". "A vertical and an inclined line" is the
/// vertical line of Eq. 20/21 (`t_1`) with the inclined line of Eq. 28 (`t_1'`, `β`), which is
/// what is computed here.
pub fn improved_oas_eq30(p: f64, t1: f64, t1_prime: f64, beta: f64) -> f64 {
    (1.0 / (t1 * p)).max(improved_oas_eq29(p, t1_prime, beta))
}
