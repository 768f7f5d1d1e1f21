//! Interval arithmetic with outward rounding, as much as the barrier certificate needs: sums,
//! products, `sin`, `cos`, `sqrt`, division by a positive interval.
//!
//! Every result contains the exact real result for every pair of reals in the operands. Sums,
//! differences and products are rounded outwards by one ulp (`next_down`/`next_up`; IEEE
//! round-to-nearest is within half an ulp). `sqrt` and division are correctly rounded by IEEE,
//! so one ulp outwards is enough too. `sin` and `cos` come from the platform's libm, whose error
//! is below one ulp (glibc documents ≤ 1 ulp for both); their values are widened by
//! [`ELEMENTARY_MARGIN`] = 2⁻⁴⁸ ≈ 3.6e-15 (32 ulps of 1) and clamped to [-1, 1]. Extremes
//! (±1) are added when a critical point lies within 1e-9 rad of the interval, so that the
//! rounding of `lo / 2π` cannot drop one.

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::ops::{Add, Mul, Neg, Sub};

/// Absolute widening of every value of `sin` and `cos`.
pub const ELEMENTARY_MARGIN: f64 = 1.0 / (1u64 << 48) as f64;

/// A closed interval `[lo, hi]` of reals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

impl Interval {
    pub fn new(lo: f64, hi: f64) -> Interval {
        debug_assert!(lo <= hi, "[{lo}, {hi}]");
        Interval { lo, hi }
    }

    /// The exact number `x` (a thin interval).
    pub fn point(x: f64) -> Interval {
        Interval { lo: x, hi: x }
    }

    pub fn width(self) -> f64 {
        self.hi - self.lo
    }

    /// The midpoint (rounded; any point of the interval will do where it is used).
    pub fn mid(self) -> f64 {
        0.5 * (self.lo + self.hi)
    }

    /// `sin` over the interval.
    pub fn sin(self) -> Interval {
        // sin has its maxima at π/2 + 2πk and its minima at -π/2 + 2πk.
        self.periodic(self.lo.sin(), self.hi.sin(), FRAC_PI_2, -FRAC_PI_2)
    }

    /// `cos` over the interval.
    pub fn cos(self) -> Interval {
        self.periodic(self.lo.cos(), self.hi.cos(), 0.0, PI)
    }

    /// Range of a 2π-periodic function with values `a`, `b` at the ends, its maxima (+1) at
    /// `max_at + 2πk` and minima (-1) at `min_at + 2πk`, monotone in between.
    fn periodic(self, a: f64, b: f64, max_at: f64, min_at: f64) -> Interval {
        if !(self.lo.is_finite() && self.hi.is_finite()) || self.width() >= TAU {
            return Interval::new(-1.0, 1.0);
        }
        let reaches = |at: f64| {
            let k = ((self.lo - at - 1e-9) / TAU).ceil();
            at + k * TAU <= self.hi + 1e-9
        };
        let lo = if reaches(min_at) {
            -1.0
        } else {
            (a.min(b) - ELEMENTARY_MARGIN).max(-1.0)
        };
        let hi = if reaches(max_at) {
            1.0
        } else {
            (a.max(b) + ELEMENTARY_MARGIN).min(1.0)
        };
        Interval::new(lo, hi)
    }

    /// `√x` of a non-negative interval.
    pub fn sqrt(self) -> Interval {
        debug_assert!(self.lo >= 0.0);
        Interval::new(next_down(self.lo.sqrt()).max(0.0), next_up(self.hi.sqrt()))
    }

    /// `self / d` for `d > 0`.
    pub fn div_positive(self, d: Interval) -> Interval {
        debug_assert!(d.lo > 0.0);
        let q = [
            self.lo / d.lo,
            self.lo / d.hi,
            self.hi / d.lo,
            self.hi / d.hi,
        ];
        Interval::new(
            next_down(q.iter().copied().fold(f64::INFINITY, f64::min)),
            next_up(q.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
        )
    }
}

/// The next float above `x` (`f64::next_up`, which is newer than the crate's MSRV).
pub fn next_up(x: f64) -> f64 {
    if x.is_nan() || x == f64::INFINITY {
        return x;
    }
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits + 1 } else { bits - 1 })
}

/// The next float below `x`.
pub fn next_down(x: f64) -> f64 {
    -next_up(-x)
}

/// One ulp down, except an exact zero: a rounded sum that is zero is exact (IEEE with gradual
/// underflow), so `0` needs no widening.
fn down(x: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        next_down(x)
    }
}

/// One ulp up, except an exact zero.
fn up(x: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        next_up(x)
    }
}

impl Add for Interval {
    type Output = Interval;
    fn add(self, o: Interval) -> Interval {
        Interval::new(down(self.lo + o.lo), up(self.hi + o.hi))
    }
}

impl Sub for Interval {
    type Output = Interval;
    fn sub(self, o: Interval) -> Interval {
        Interval::new(down(self.lo - o.hi), up(self.hi - o.lo))
    }
}

impl Neg for Interval {
    type Output = Interval;
    fn neg(self) -> Interval {
        Interval::new(-self.hi, -self.lo)
    }
}

impl Mul for Interval {
    type Output = Interval;
    fn mul(self, o: Interval) -> Interval {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for a in [self.lo, self.hi] {
            for b in [o.lo, o.hi] {
                // A product with a zero factor is exact; any other is widened by one ulp (a
                // product that underflows to zero included).
                let p = a * b;
                if a == 0.0 || b == 0.0 {
                    lo = lo.min(0.0);
                    hi = hi.max(0.0);
                } else {
                    lo = lo.min(next_down(p));
                    hi = hi.max(next_up(p));
                }
            }
        }
        Interval::new(lo, hi)
    }
}

impl Mul<f64> for Interval {
    type Output = Interval;
    fn mul(self, x: f64) -> Interval {
        self * Interval::point(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dense sampling stays inside the enclosures, and they are tight for small intervals.
    #[test]
    fn enclosures_contain_the_sampled_values() {
        let mut x = 0.123_f64;
        for i in 0..2000 {
            x = (x * 7.31 + 0.77).fract();
            let lo = -7.0 + 14.0 * x;
            let w = [1e-9, 1e-3, 0.1, 1.0, 3.0, 7.0][i % 6];
            let iv = Interval::new(lo, lo + w);
            let (s, c) = (iv.sin(), iv.cos());
            for j in 0..=100 {
                let t = lo + w * j as f64 / 100.0;
                assert!(s.lo <= t.sin() && t.sin() <= s.hi, "sin {iv:?} at {t}");
                assert!(c.lo <= t.cos() && t.cos() <= c.hi, "cos {iv:?} at {t}");
            }
            if w <= 1e-3 {
                assert!(s.width() <= 2e-3 && c.width() <= 2e-3);
            }
        }
        // The extremes are found.
        assert_eq!(Interval::new(1.5, 1.6).sin().hi, 1.0);
        assert_eq!(Interval::new(3.1, 3.2).cos().lo, -1.0);
        assert_eq!(Interval::new(-0.1, 0.1).cos().hi, 1.0);
        let p = Interval::new(-2.0, 3.0) * Interval::new(-5.0, 1.0);
        assert!(p.lo <= -15.0 && p.hi >= 10.0 && p.lo > -15.001 && p.hi < 10.001);
        assert_eq!(
            Interval::point(0.0) * Interval::new(-1.0, 2.0),
            Interval::point(0.0)
        );
        assert_eq!(next_up(1.0), 1.0 + f64::EPSILON);
        assert_eq!(next_down(1.0), 1.0 - 0.5 * f64::EPSILON);
        assert_eq!(next_up(-1.0), -1.0 + 0.5 * f64::EPSILON);
        assert!(next_down(0.0) < 0.0 && next_up(0.0) > 0.0);
    }
}
