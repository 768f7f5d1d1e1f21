//! Closed-form facts about a single rigid rocking block (SPEC §6; thesis Chapter 1, section 3.1,
//! Chapter 5 and Appendix A).
//!
//! Two sets of dimensions appear in the thesis and both are kept here as printed:
//! - the design chapter (Fig. 7, Eq. 3, 13–18) uses the FULL width `B` and height `H`, with
//!   `tan δ = B / H` and `R = ½ √(B² + H²)`;
//! - Housner's impact formulas (Eq. 1, Fig. 2) and Appendix A use the HALF dimensions `h` and `b`
//!   (and the half contact width `b₂` for cut corners, pivot positions `x` measured from the middle
//!   of the bottom edge).
//!
//! All functions are plain formulas in SI units (m, s, rad, m/s²). They do not validate their
//! arguments: outside the stated domain they return NaN or a meaningless number. The design
//! functions in [`crate::design`] validate and return errors.

/// `α` of a uniform rectangular block: `θ = α m R²` with `θ` the moment of inertia about a bottom
/// corner (thesis Eq. 13, Fig. 7).
pub const ALPHA_UNIFORM: f64 = 4.0 / 3.0;

/// `α` of a point mass (a pier whose mass is concentrated at its top, its own weight neglected;
/// thesis Eq. 22–23, Fig. 51): `θ = m R²`.
pub const ALPHA_POINT_MASS: f64 = 1.0;

/// Slenderness angle `δ` \[rad\] of a block of full width `B` and full height `H`:
/// `tan δ = B / H` (thesis Fig. 7, `H / B = cot δ`).
pub fn slenderness_angle(width: f64, height: f64) -> f64 {
    (width / height).atan()
}

/// Distance `R` \[m\] from a bottom corner to the centre of a uniform block of full width `B` and
/// full height `H`: `R = ½ √(B² + H²)` (thesis Fig. 7, Fig. 39).
pub fn corner_distance(width: f64, height: f64) -> f64 {
    0.5 * width.hypot(height)
}

/// Moment of inertia about the pivot corner, `θ = α m R²` (thesis Eq. 22; `α = 4/3` for a
/// uniform rectangle, Eq. 13).
pub fn corner_inertia(mass: f64, r: f64, alpha: f64) -> f64 {
    alpha * mass * r * r
}

/// Housner's frequency parameter `p = √(m R g / θ) = √(g / (α R))` \[1/s\] (thesis Eq. 13, with the
/// general `α` of Eq. 22; [`ALPHA_UNIFORM`] for a uniform block).
pub fn frequency_parameter(r: f64, alpha: f64, g: f64) -> f64 {
    (g / (alpha * r)).sqrt()
}

/// The ground acceleration at which the block starts to rock, `a_p,min = g tan δ` \[m/s²\]
/// (thesis Eq. 3). It does not depend on `α` (thesis 5.3.3).
pub fn a_p_min(delta: f64, g: f64) -> f64 {
    g * delta.tan()
}

/// Housner's angular velocity ratio `μ = (2h² − b²) / (2h² + 2b²)` at an impact from one corner
/// to the other (thesis Eq. 1), with `h`, `b` the HALF height and HALF width (Fig. 2a).
///
/// Negative for `h / b < 1/√2`: such a block does not rock back, it lands flat.
pub fn housner_mu(h: f64, b: f64) -> f64 {
    (2.0 * h * h - b * b) / (2.0 * h * h + 2.0 * b * b)
}

/// Relative loss of kinetic energy at an impact with velocity ratio `μ`: `η = 1 − μ²`
/// (thesis Eq. 2).
pub fn energy_loss(mu: f64) -> f64 {
    1.0 - mu * mu
}

/// Velocity ratio for rotation about a pivot at `x1` before the impact and at `x2` after it
/// (thesis Appendix A, Eq. A3):
/// `μ = (2h² + 0.5b² + 1.5 x₁x₂) / (2h² + 0.5b² + 1.5 x₂²)`,
/// `h`, `b` HALF height and HALF width of the uniform block, `x1`, `x2` measured from the middle
/// of the bottom edge (Fig. 59). `x1 = −b`, `x2 = b` gives Housner's Eq. 1.
pub fn mu_pivots(h: f64, b: f64, x1: f64, x2: f64) -> f64 {
    let d = 2.0 * h * h + 0.5 * b * b;
    (d + 1.5 * x1 * x2) / (d + 1.5 * x2 * x2)
}

/// Velocity ratio of a block with cut corners, contact half-width `b2 ≤ b`, one impact from one
/// contact edge to the other (thesis Eq. A4 = Eq. A3 with `x1 = −b2`, `x2 = b2`):
/// `μ = (2h² + 0.5b² − 1.5b₂²) / (2h² + 0.5b² + 1.5b₂²)`.
pub fn mu_cut_corners(h: f64, b: f64, b2: f64) -> f64 {
    mu_pivots(h, b, -b2, b2)
}

/// Velocity ratio of two consecutive impacts, first on a bump in the middle, then on the far
/// contact edge (thesis Eq. A7): `μ = (2h² + 0.5b²) / (2h² + 0.5b² + 1.5b₂²)`; with `b2 = b` this
/// is Eq. A8, `(2h² + 0.5b²) / (2h² + 2b²)`. This is the thesis's recommended model (one bump).
pub fn mu_two_impacts(h: f64, b: f64, b2: f64) -> f64 {
    let d = 2.0 * h * h + 0.5 * b * b;
    d / (d + 1.5 * b2 * b2)
}

/// Velocity ratio of `n_impacts` consecutive impacts (thesis 3.1, Fig. 11–12; SPEC §2): the
/// pivot walks over `n_impacts + 1` equally spaced points from one contact edge (`−b2`) to the
/// other (`+b2`), i.e. over `n_impacts − 1` bumps, and Eq. A3 is applied at every step.
///
/// `n_impacts = 1` is Eq. A4 (Eq. 1 when `b2 = b`), `n_impacts = 2` (one bump in the middle) is
/// Eq. A7 / A8. The ratio increases with `n_impacts` and tends to 1 (rolling, no energy loss);
/// `1 − μ` falls like `1 / n_impacts`. If a step would reverse the rotation (a stocky block,
/// `μ ≤ 0` at that step) the block lands flat there and the result is 0. `n_impacts = 0` is
/// treated as 1.
pub fn mu_consecutive_impacts(h: f64, b: f64, b2: f64, n_impacts: u32) -> f64 {
    let n = n_impacts.max(1);
    let pivot = |k: u32| -b2 + 2.0 * b2 * f64::from(k) / f64::from(n);
    let mut mu = 1.0;
    for k in 0..n {
        let step = mu_pivots(h, b, pivot(k), pivot(k + 1));
        if step <= 0.0 {
            return 0.0;
        }
        mu *= step;
    }
    mu
}

/// Velocity ratio with `n_bumps` equally spaced bumps between the contact edges, i.e.
/// `n_bumps + 1` consecutive impacts (thesis 3.1: "if there are n bumps, rocking occurs in n+1
/// impacts"; Fig. 12 plots `1 − μ²` for 1, 2, … 100 bumps). `n_bumps = 0` is Housner.
pub fn mu_bumps(h: f64, b: f64, b2: f64, n_bumps: u32) -> f64 {
    mu_consecutive_impacts(h, b, b2, n_bumps.saturating_add(1))
}

/// Housner's approximate period of free rocking with amplitude `phi0` (thesis Eq. 14, Housner
/// 1963): `T ≈ 4 √(α R / g) cosh⁻¹(δ / (δ − φ₀))`, for `0 ≤ φ₀ < δ`, `φ₀` the largest rotation
/// from the upright position.
///
/// The thesis prints the argument as `δ / (φ₀ − δ)`, which is negative (no real `cosh⁻¹`) on the
/// whole range `0 < φ₀ < δ` where the block does not overturn; the sign is a misprint. Housner's
/// form `cosh⁻¹(1 / (1 − φ₀/δ))` used here is zero at `φ₀ = 0` and tends to infinity as `φ₀`
/// approaches `δ`, as the thesis says of Eq. 14. Returns NaN outside `0 ≤ φ₀ < δ`.
pub fn housner_period(r: f64, alpha: f64, g: f64, delta: f64, phi0: f64) -> f64 {
    if !(0.0..delta).contains(&phi0) {
        return f64::NAN;
    }
    4.0 / frequency_parameter(r, alpha, g) * (delta / (delta - phi0)).acosh()
}

/// Critical impulse of a single-lobe pulse of vanishing duration that overturns the block
/// (thesis Eq. 17): `I_cr = √(2 α R g (1 − cos δ)) / cos δ` \[m/s\].
pub fn critical_impulse(r: f64, alpha: f64, g: f64, delta: f64) -> f64 {
    (2.0 * alpha * r * g * (1.0 - delta.cos())).sqrt() / delta.cos()
}

/// Normalised critical impulse `i_cr = p I_cr / a_p,min = √(2 / (1 + cos δ)) ≥ 1` (thesis
/// Eq. 18); independent of the size, of `g` and of `α`.
pub fn normalised_critical_impulse(delta: f64) -> f64 {
    (2.0 / (1.0 + delta.cos())).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Round to `decimals` places (half away from zero), for comparisons with printed values.
    fn round_to(x: f64, decimals: i32) -> f64 {
        let s = 10f64.powi(decimals);
        (x * s).round() / s
    }

    /// Housner energy loss in percent from the printed full dimensions `2h`, `2b`.
    fn eta_percent(two_h: f64, two_b: f64) -> f64 {
        100.0 * energy_loss(housner_mu(two_h / 2.0, two_b / 2.0))
    }

    #[test]
    fn table_1_housner_rows() {
        // (2h, 2b, printed η_Hous in %), thesis Table 1, Eq. 1 and 2.
        let rows = [
            (200.0, 100.0, 51.0),
            (400.0, 100.0, 16.9),
            (771.5, 152.0, 10.9),
            (950.0, 190.0, 11.2),
            (1000.0, 250.0, 16.9),
            (1000.0, 170.0, 8.2),
            (1000.0, 120.0, 4.2),
        ];
        for (two_h, two_b, printed) in rows {
            assert_eq!(
                round_to(eta_percent(two_h, two_b), 1),
                printed,
                "{two_h} x {two_b}"
            );
        }
    }

    /// h/b = 3: μ = 17/20 exactly and η = 27.75 % exactly, a tie at one decimal. The thesis
    /// prints 27.8 % (round half up). The f64 value is 27.750000000000007, so rounding it gives
    /// the printed 27.8; because that depends on the last ulp, the test also checks that the value
    /// is the tie and that the printed number is its half-up rounding.
    #[test]
    fn table_1_h_over_b_3_is_an_exact_tie() {
        let eta = eta_percent(300.0, 100.0);
        assert_eq!(round_to(eta, 1), 27.8);
        assert!((eta - 27.75).abs() <= 8.0 * f64::EPSILON * 27.75, "{eta}");
        assert_eq!(round_to(27.75, 1), 27.8);
        assert_eq!(housner_mu(3.0, 1.0), 0.85);
    }

    #[test]
    fn table_1_prieto_cut_corners_eq_a3() {
        // 2h = 500, 2b = 246, 2b₂ = 160: η = 25.2 %.
        let mu = mu_pivots(250.0, 123.0, -80.0, 80.0);
        assert_eq!(mu, mu_cut_corners(250.0, 123.0, 80.0));
        assert_eq!(round_to(100.0 * energy_loss(mu), 1), 25.2);
    }

    #[test]
    fn eq_a3_at_the_corners_is_housner() {
        for (h, b) in [(1.0, 0.5), (1.5, 0.5), (2.0, 0.5), (3.7, 0.4), (0.6, 1.0)] {
            let a3 = mu_pivots(h, b, -b, b);
            let eq1 = housner_mu(h, b);
            assert!(
                (a3 - eq1).abs() <= 4.0 * f64::EPSILON,
                "{h} {b}: {a3} vs {eq1}"
            );
        }
    }

    #[test]
    fn a5_a6_a7_a8() {
        let (h, b, b2) = (1.2, 0.4, 0.3);
        // A5: corner to middle keeps the angular velocity.
        assert_eq!(mu_pivots(h, b, -b2, 0.0), 1.0);
        // A6 then A7.
        let a7 = mu_pivots(h, b, -b2, 0.0) * mu_pivots(h, b, 0.0, b2);
        assert!((a7 - mu_two_impacts(h, b, b2)).abs() < 1e-15);
        // A8: b2 = b.
        let a8 = (2.0 * h * h + 0.5 * b * b) / (2.0 * h * h + 2.0 * b * b);
        assert!((mu_two_impacts(h, b, b) - a8).abs() < 1e-15);
    }

    #[test]
    fn consecutive_impacts_chain() {
        for hb in [1.0, 2.0, 3.0, 5.0, 10.0] {
            let (h, b) = (hb, 1.0);
            // One impact is Housner, two impacts (one bump) are Eq. A8.
            assert!((mu_consecutive_impacts(h, b, b, 1) - housner_mu(h, b)).abs() < 1e-15);
            assert!((mu_consecutive_impacts(h, b, b, 2) - mu_two_impacts(h, b, b)).abs() < 1e-15);
            assert_eq!(mu_bumps(h, b, b, 1), mu_consecutive_impacts(h, b, b, 2));
            assert_eq!(mu_bumps(h, b, b, 0), mu_consecutive_impacts(h, b, b, 1));
            // Increases with the number of impacts and tends to 1 (Fig. 12): 1 − μ ~ c / n.
            let mut previous = 0.0;
            for n in 1..=200 {
                let mu = mu_consecutive_impacts(h, b, b, n);
                assert!(mu > previous && mu < 1.0, "h/b = {hb}, n = {n}: {mu}");
                previous = mu;
            }
            let gap_100 = 1.0 - mu_consecutive_impacts(h, b, b, 100);
            let gap_1000 = 1.0 - mu_consecutive_impacts(h, b, b, 1000);
            assert!(gap_100 < 0.01, "{gap_100}");
            assert!(gap_1000 < 0.2 * gap_100, "{gap_1000} vs {gap_100}");
        }
    }

    #[test]
    fn stocky_block_lands_flat() {
        // h/b < 1/√2: Eq. 1 is negative; the chained model stops the block.
        assert!(housner_mu(0.5, 1.0) < 0.0);
        assert_eq!(mu_consecutive_impacts(0.5, 1.0, 1.0, 1), 0.0);
    }

    #[test]
    fn normalised_critical_impulse_printed_values() {
        // Thesis after Eq. 18: H/B = 3 → 1.013, H/B = 8 → 1.002.
        for (h_over_b, printed) in [(3.0, 1.013), (8.0, 1.002)] {
            let delta = slenderness_angle(1.0, h_over_b);
            assert_eq!(round_to(normalised_critical_impulse(delta), 3), printed);
        }
    }

    #[test]
    fn eq_18_follows_from_eq_3_13_17() {
        let g = 9.81;
        for (b, h, alpha) in [(1.0, 3.0, ALPHA_UNIFORM), (0.5, 4.0, 1.0), (2.0, 12.0, 1.2)] {
            let delta = slenderness_angle(b, h);
            let r = corner_distance(b, h);
            let p = frequency_parameter(r, alpha, g);
            let i = p * critical_impulse(r, alpha, g, delta) / a_p_min(delta, g);
            assert!((i - normalised_critical_impulse(delta)).abs() < 1e-13);
        }
    }

    #[test]
    fn frequency_parameter_matches_inertia_definition() {
        // p = √(m R g / θ) with θ = α m R² (Eq. 13, 22), and the uniform block's α is 4/3:
        // θ_corner = m (B² + H²)/12 + m R² = (4/3) m R².
        let (b, h, m, g) = (1.0, 12.0, 7.0, 9.81);
        let r = corner_distance(b, h);
        let theta = m * (b * b + h * h) / 12.0 + m * r * r;
        assert!((theta - corner_inertia(m, r, ALPHA_UNIFORM)).abs() < 1e-12 * theta);
        let p = (m * r * g / theta).sqrt();
        assert!((p - frequency_parameter(r, ALPHA_UNIFORM, g)).abs() < 1e-14);
        assert!((a_p_min(slenderness_angle(b, h), g) - g / 12.0).abs() < 1e-15);
    }

    #[test]
    fn housner_period_limits() {
        let (r, alpha, g, delta) = (2.0, ALPHA_UNIFORM, 9.81, 0.2);
        assert_eq!(housner_period(r, alpha, g, delta, 0.0), 0.0);
        let mut previous = 0.0;
        for k in 1..100 {
            let t = housner_period(r, alpha, g, delta, delta * f64::from(k) / 100.0);
            assert!(t > previous);
            previous = t;
        }
        assert!(housner_period(r, alpha, g, delta, delta * (1.0 - 1e-12)) > 4.0 * previous);
        assert!(housner_period(r, alpha, g, delta, delta).is_nan());
        assert!(housner_period(r, alpha, g, delta, -0.1).is_nan());
        // T ∝ 1/p for a given amplitude (Eq. 15).
        let ratio =
            housner_period(4.0 * r, alpha, g, delta, 0.1) / housner_period(r, alpha, g, delta, 0.1);
        assert!((ratio - 2.0).abs() < 1e-14);
    }
}
