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
//!
//! [`EquivalentBlock`] gathers these quantities for one block of given width, height and
//! [`MassDistribution`]: the pier of the design method and the axes of the overturning spectra.

use crate::model::column::Column;
use crate::validate::{positive, InvalidValue};

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

/// Mass distribution of a symmetric block (thesis 5.3.3, Eq. 22, Fig. 51; the two cases of the
/// pier example, Eq. 23).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MassDistribution {
    /// A solid block of uniform mass (case "a" of the pier example). Centre of mass at mid-height
    /// (`h_c = H/2`), `α = 4/3` (Eq. 13), `tan δ = B/H`, `R = ½√(B² + H²)`.
    Uniform,
    /// The mass concentrated at the top, the weight of the pier neglected (case "b" of the pier
    /// example). A point mass at `h_c = H`, `α = 1` (`θ = m R²`), `tan δ = B/(2H)`,
    /// `R = √((B/2)² + H²)`.
    Top,
    /// Any other symmetric distribution (Fig. 51): `α` of Eq. 22 and the height of the centre of
    /// mass as a fraction of the block's height. Both are needed: `α` alone fixes `p` only once
    /// `R` (hence the centre of mass) is known, and `δ` also depends on the centre of mass.
    /// `α` is taken as a constant, independent of the width (exact for the two cases above).
    General {
        /// `θ = α m R²` about a bottom corner.
        alpha: f64,
        /// Height of the centre of mass divided by the block's height `H`.
        centre_height_ratio: f64,
    },
}

impl MassDistribution {
    /// `α` of Eq. 22.
    pub fn alpha(self) -> f64 {
        match self {
            MassDistribution::Uniform => ALPHA_UNIFORM,
            MassDistribution::Top => ALPHA_POINT_MASS,
            MassDistribution::General { alpha, .. } => alpha,
        }
    }

    /// Height of the centre of mass over the block's height.
    pub fn centre_height_ratio(self) -> f64 {
        match self {
            MassDistribution::Uniform => 0.5,
            MassDistribution::Top => 1.0,
            MassDistribution::General {
                centre_height_ratio,
                ..
            } => centre_height_ratio,
        }
    }

    /// `α` and the centre height ratio finite and positive.
    pub(crate) fn validate(self) -> Result<(), InvalidValue> {
        positive("alpha", self.alpha())?;
        positive("centre_height_ratio", self.centre_height_ratio())?;
        Ok(())
    }
}

/// The equivalent single block: a symmetric rigid block of full width `B`, full height `H` and a
/// mass distribution, described by the quantities of thesis Chapters 1 and 5 — the centre of
/// mass at height `h_c` on the axis, `tan δ = (B/2) / h_c`, the corner distance
/// `R = √((B/2)² + h_c²)`, `θ = α m R²` about a corner (Eq. 22), `p = √(g / (α R))` (Eq. 13),
/// `a_p,min = g tan δ` (Eq. 3) and `i_cr = √(2 / (1 + cos δ))` (Eq. 18). For a uniform block
/// `tan δ = B/H` and `R = ½√(B² + H²)` (Fig. 7).
///
/// It is the pier of the design method (thesis 5.3.4) and the axes of the overturning spectra:
/// a column is described by the uniform block of its bottom width and total height
/// ([`EquivalentBlock::of_column`]), the column "has the same aspect ratio" (Fig. 40, 43).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EquivalentBlock {
    /// Full width `B` \[m\].
    pub width: f64,
    /// Full height `H` \[m\].
    pub height: f64,
    /// Mass distribution (fixes `α` and the centre of mass).
    pub mass: MassDistribution,
}

impl EquivalentBlock {
    /// A validated block: width, height, `α` and centre height must be finite and positive.
    pub fn new(
        width: f64,
        height: f64,
        mass: MassDistribution,
    ) -> Result<EquivalentBlock, InvalidValue> {
        let block = EquivalentBlock {
            width,
            height,
            mass,
        };
        block.validate()?;
        Ok(block)
    }

    /// A uniform block of full width `B` and height `H` (not validated).
    pub fn uniform(width: f64, height: f64) -> EquivalentBlock {
        EquivalentBlock {
            width,
            height,
            mass: MassDistribution::Uniform,
        }
    }

    /// The uniform block of a column's bottom width and total height: the axes of its
    /// overturning curves and spectra. Exact for a single uniform block.
    pub fn of_column(column: &Column) -> EquivalentBlock {
        EquivalentBlock::uniform(column.blocks()[0].width, column.total_height())
    }

    /// The uniform block of size `R = ½√(B² + H²) = size` \[m\] and slenderness
    /// `H/B = slenderness` (not validated): the blocks of an OAS size grid.
    pub fn of_size(size: f64, slenderness: f64) -> EquivalentBlock {
        let width = 2.0 * size / (1.0 + slenderness * slenderness).sqrt();
        EquivalentBlock::uniform(width, slenderness * width)
    }

    /// Checks width, height, `α` and the centre height: finite and positive.
    pub fn validate(&self) -> Result<(), InvalidValue> {
        positive("width", self.width)?;
        positive("height", self.height)?;
        self.mass.validate()
    }

    /// Height of the centre of mass `h_c` \[m\].
    pub fn centre_height(&self) -> f64 {
        self.mass.centre_height_ratio() * self.height
    }

    /// `tan δ = (B/2) / h_c` (`B/H` for a uniform block, Fig. 7).
    pub fn tan_delta(&self) -> f64 {
        0.5 * self.width / self.centre_height()
    }

    /// Slenderness angle `δ` \[rad\].
    pub fn slenderness_angle(&self) -> f64 {
        self.tan_delta().atan()
    }

    /// Distance `R` from a bottom corner to the centre of mass \[m\].
    pub fn corner_distance(&self) -> f64 {
        (0.5 * self.width).hypot(self.centre_height())
    }

    /// `α` of Eq. 22.
    pub fn alpha(&self) -> f64 {
        self.mass.alpha()
    }

    /// Frequency parameter `p = √(g / (α R))` \[1/s\] (Eq. 13, 22).
    pub fn frequency_parameter(&self, g: f64) -> f64 {
        frequency_parameter(self.corner_distance(), self.alpha(), g)
    }

    /// `a_p,min = g tan δ` \[m/s²\] (Eq. 3).
    pub fn a_p_min(&self, g: f64) -> f64 {
        g * self.tan_delta()
    }

    /// `i_cr = √(2 / (1 + cos δ))` (Eq. 18), `cos δ = h_c / R`.
    pub fn normalised_critical_impulse(&self) -> f64 {
        (2.0 / (1.0 + self.centre_height() / self.corner_distance())).sqrt()
    }
}

#[cfg(test)]
mod tests;
