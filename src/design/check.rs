//! The design check of thesis Eq. 31 (with the exact `i_cr`, the left form of Eq. 21).

use super::{DesignError, EquivalentBlock};
use crate::validate::positive;

/// Which factor multiplies `1 / (t_1 p)` in the simplified OAS.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ImpulseFactor {
    /// `i_cr ≈ 1`: Eq. 31 (the recommended check) and the pier example Eq. 23, 24.
    One,
    /// `i_cr = √(2 / (1 + cos δ))` of the block: Eq. 20 and the left form of Eq. 21.
    Exact,
}

/// Which inequality of Eq. 31 gives the (larger) admissible acceleration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum Branch {
    /// `a_p ≤ a_p,min`: the block does not even start to rock.
    NoRocking,
    /// `a_p ≤ a_p,min i_cr / (t_1 p)`: the block rocks but the impulse is too short to overturn it.
    Impulse,
}

/// The verdict of the design check Eq. 31 (Eq. 21) and the numbers behind it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DesignCheck {
    /// `true` when `a_p ≤ limit`.
    pub safe: bool,
    /// Peak ground acceleration `a_p` \[m/s²\].
    pub a_p: f64,
    /// `a_p,min = g tan δ` \[m/s²\] (Eq. 3).
    pub a_p_min: f64,
    /// Frequency parameter `p` \[1/s\] (Eq. 13).
    pub p: f64,
    /// The factor used: 1 (Eq. 31) or `i_cr` (Eq. 18, 21).
    pub i_cr: f64,
    /// `a_p,min i_cr / (t_1 p)` \[m/s²\], the impulse branch of Eq. 31.
    pub impulse_limit: f64,
    /// `max(impulse_limit, a_p_min)` \[m/s²\]: the largest safe peak acceleration.
    pub limit: f64,
    /// The branch that gives `limit`.
    pub governing: Branch,
    /// `a_p / limit` (≤ 1 when safe).
    pub utilisation: f64,
}

/// Design check of a pier for an earthquake `(a_p, t_1)` (thesis Eq. 31; with
/// [`ImpulseFactor::Exact`], the left form of Eq. 21):
/// safe if `a_p ≤ a_p,min i_cr / (t_1 p)` or `a_p ≤ a_p,min`, with `1/p = √(α R / g)`.
pub fn design_check(
    pier: &EquivalentBlock,
    a_p: f64,
    t1: f64,
    g: f64,
    factor: ImpulseFactor,
) -> Result<DesignCheck, DesignError> {
    pier.validate()?;
    positive("a_p", a_p)?;
    positive("t1", t1)?;
    positive("g", g)?;
    let a_p_min = pier.a_p_min(g);
    let p = pier.frequency_parameter(g);
    let i_cr = match factor {
        ImpulseFactor::One => 1.0,
        ImpulseFactor::Exact => pier.normalised_critical_impulse(),
    };
    let impulse_limit = a_p_min * i_cr / (t1 * p);
    let (limit, governing) = if impulse_limit >= a_p_min {
        (impulse_limit, Branch::Impulse)
    } else {
        (a_p_min, Branch::NoRocking)
    };
    Ok(DesignCheck {
        safe: a_p <= limit,
        a_p,
        a_p_min,
        p,
        i_cr,
        impulse_limit,
        limit,
        governing,
        utilisation: a_p / limit,
    })
}
