//! Where an open DOF of a loop closes inside a step: the first zero of its depth on the step's
//! cubic Hermite interpolant (angles and rates at both ends of the RK4 step), the column
//! driver's interpolant (`driver::events::locate`), with every way back to zero a step can hide:
//! a DOF ending the step through zero, one dipping through zero and back within it, and one that
//! opened at this instant (depth 0) and is back within the step.

use crate::driver::events::locate::{hermite, illinois};

/// The first fraction `s ∈ [0, 1]` of a step of length `h` at which the cubic Hermite
/// interpolant of the depth `g` (`g0 >= 0` at the start, `g1` at the end, rates `r0`, `r1`)
/// comes down to zero, or `None` if it stays positive over the step. With `g0 == 0` (a DOF
/// that opened at this instant) the cubic must first rise: if it does not rise above zero before
/// its first turning point, the DOF closes at once (`Some(0.0)`).
pub(super) fn first_crossing(h: f64, g0: f64, g1: f64, r0: f64, r1: f64) -> Option<f64> {
    let cubic = |s: f64| hermite(s, h, g0, g1, r0, r1);
    // Turning points: roots of the derivative A s² + B s + C inside (0, 1).
    let a = 6.0 * g0 + 3.0 * h * r0 - 6.0 * g1 + 3.0 * h * r1;
    let b = -6.0 * g0 - 4.0 * h * r0 + 6.0 * g1 - 2.0 * h * r1;
    let c = h * r0;
    // At most two turning points and the step's end, in a fixed array.
    let mut roots = [0.0; 2];
    let n_roots = if a.abs() > 1e-300 {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let r = disc.sqrt();
            roots = [(-b - r) / (2.0 * a), (-b + r) / (2.0 * a)];
            2
        } else {
            0
        }
    } else if b.abs() > 1e-300 {
        roots[0] = -c / b;
        1
    } else {
        0
    };
    let mut points = [0.0; 3];
    let mut len = 0;
    for &s in &roots[..n_roots] {
        if s > 0.0 && s < 1.0 {
            points[len] = s;
            len += 1;
        }
    }
    if len == 2 && points[1].total_cmp(&points[0]).is_lt() {
        points.swap(0, 1);
    }
    points[len] = 1.0;
    let points = &points[..=len];
    let (mut lo, mut glo) = (0.0, g0);
    let mut rest = points.iter().copied();
    if g0 <= 0.0 {
        let first = rest.next()?;
        let g = if first == 1.0 { g1 } else { cubic(first) };
        if g <= 0.0 {
            return Some(0.0);
        }
        (lo, glo) = (first, g);
    }
    for hi in rest {
        let ghi = if hi == 1.0 { g1 } else { cubic(hi) };
        if ghi <= 0.0 {
            // f = −g: from < 0 (before) to >= 0 (after).
            return Some(illinois(|s| -cubic(s), lo, -glo, hi, -ghi, 1e-13));
        }
        (lo, glo) = (hi, ghi);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic's own Hermite interpolant is itself: the zeros are found to round-off.
    #[test]
    fn crossings_of_cubics() {
        // Ends through zero: g(s) = 1 − 2 s + 0.5 s³ has its zero at s = 0.5392…
        let g = |s: f64| 1.0 - 2.0 * s + 0.5 * s * s * s;
        let dg = |s: f64| -2.0 + 1.5 * s * s;
        let s = first_crossing(1.0, g(0.0), g(1.0), dg(0.0), dg(1.0)).unwrap();
        assert!(g(s).abs() < 1e-12 && s > 0.5 && s < 0.6, "{s}");
        // Dips through zero and back within the step: the first zero, before the minimum.
        let g = |s: f64| 0.01 - s * (1.0 - s) + 0.0 * s;
        let dg = |s: f64| -1.0 + 2.0 * s;
        let s = first_crossing(1.0, g(0.0), g(1.0), dg(0.0), dg(1.0)).unwrap();
        assert!(g(s).abs() < 1e-12 && s < 0.5, "{s}");
        // Stays positive.
        assert_eq!(first_crossing(1.0, 1.0, 0.5, -0.1, -0.2), None);
        // Opened at zero, rises and comes back: the zero after the maximum.
        let g = |s: f64| s * (0.7 - s);
        let dg = |s: f64| 0.7 - 2.0 * s;
        let s = first_crossing(1.0, 0.0, g(1.0), dg(0.0), dg(1.0)).unwrap();
        assert!((s - 0.7).abs() < 1e-12, "{s}");
        // Opened at zero and never rises: at once.
        assert_eq!(first_crossing(1.0, 0.0, -1.0, -0.5, -1.5), Some(0.0));
        // Opened at zero and rises over the whole step: no closing.
        assert_eq!(first_crossing(1.0, 0.0, 1.0, 1.0, 1.0), None);
    }
}
