//! The required width of a pier (thesis 5.3.4, Eq. 23 and 24; Eq. 22 for the general `α`).

use super::{Branch, DesignError, EquivalentBlock, ImpulseFactor, MassDistribution};
use crate::validate::positive;

/// Required widths of a pier (thesis 5.3.4, Eq. 23–24).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PierWidth {
    /// Width where the impulse branch of Eq. 31 is exactly met, `a_g = a_p,min / (t_1 p)`
    /// (Eq. 23, `i_cr ≈ 1`, solved exactly) \[m\].
    pub eq23: f64,
    /// The same with the exact `i_cr(δ)` of Eq. 18 (the left form of Eq. 21) \[m\]; slightly
    /// smaller, since `i_cr > 1`.
    pub eq21_exact_icr: f64,
    /// Slender approximation `R ≈ h_c` (`cos δ ≈ 1`), Eq. 24:
    /// `B ≈ 2 t_1 a_g √(h_c / (α g))` — `√H t_1 a_g/√g √(3/2)` (uniform) and `… 2` (top) \[m\].
    pub eq24: f64,
    /// Width where `a_g = a_p,min`, i.e. the pier does not move, `B = 2 h_c a_g / g` \[m\]
    /// (1.68 m and 3.36 m in the thesis example).
    pub at_rest: f64,
    /// The required width by Eq. 31: the smaller of `eq23` and `at_rest` (either inequality
    /// suffices) \[m\].
    pub required: f64,
    /// Which inequality of Eq. 31 gives `required`.
    pub governing: Branch,
}

/// Required width of a pier of height `height` for an earthquake of peak ground acceleration
/// `pga` and replacement impulse duration `t1` (thesis 5.3.4, Eq. 23 and 24; Eq. 22 for the
/// general `α`).
///
/// Eq. 23 is Eq. 31 at equality, `a_g / (g tan δ(B)) = (1/t_1) √(α R(B) / g)`, nonlinear in `B`.
/// Its left side minus its right side, as `g tan δ √(α R / g) / t_1 − a_g`, is strictly
/// increasing in `B` (from `−a_g` at `B = 0`), so the root is unique; it is bracketed by doubling
/// and found by bisection to round-off.
pub fn pier_width(
    height: f64,
    pga: f64,
    t1: f64,
    mass: MassDistribution,
    g: f64,
) -> Result<PierWidth, DesignError> {
    positive("height", height)?;
    positive("pga", pga)?;
    positive("t1", t1)?;
    positive("g", g)?;
    mass.validate()?;
    let h_c = mass.centre_height_ratio() * height;
    let alpha = mass.alpha();
    let at_rest = 2.0 * h_c * pga / g;

    let eq23 = solve_width(height, pga, t1, mass, g, ImpulseFactor::One)?;
    let eq21_exact_icr = solve_width(height, pga, t1, mass, g, ImpulseFactor::Exact)?;
    let eq24 = 2.0 * t1 * pga * (h_c / (alpha * g)).sqrt();
    let (required, governing) = if eq23 <= at_rest {
        (eq23, Branch::Impulse)
    } else {
        (at_rest, Branch::NoRocking)
    };
    Ok(PierWidth {
        eq23,
        eq21_exact_icr,
        eq24,
        at_rest,
        required,
        governing,
    })
}

/// Root in `B` of `a_p,min(B) i / (t_1 p(B)) − a_g` (increasing in `B`).
fn solve_width(
    height: f64,
    pga: f64,
    t1: f64,
    mass: MassDistribution,
    g: f64,
    factor: ImpulseFactor,
) -> Result<f64, DesignError> {
    let residual = |width: f64| {
        let pier = EquivalentBlock {
            width,
            height,
            mass,
        };
        let i = match factor {
            ImpulseFactor::One => 1.0,
            ImpulseFactor::Exact => pier.normalised_critical_impulse(),
        };
        pier.a_p_min(g) * i / (t1 * pier.frequency_parameter(g)) - pga
    };
    let mut lo = 0.0;
    let mut hi = 2.0 * mass.centre_height_ratio() * height * pga / g;
    let mut doublings = 0;
    // `r > 0.0` is false for NaN too: keep searching (and fail) rather than accept it.
    while residual(hi).partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        if !hi.is_finite() || doublings > 2000 {
            return Err(DesignError::NoSolution {
                name: "width",
                detail: format!("no sign change found up to width {hi} (inputs too extreme)"),
            });
        }
        lo = hi;
        hi *= 2.0;
        doublings += 1;
    }
    // Bisection to round-off: stops when the midpoint is one of the ends.
    for _ in 0..2000 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if residual(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}
