//! Event location inside a step: the interpolants of a step (cubic and quintic Hermite) and the
//! root finding on them (Illinois), free of the driver's state.

/// Cubic Hermite interpolation of `y` on a step of length `h` at `s ∈ [0, 1]` from the values
/// and derivatives at both ends.
#[inline]
pub(crate) fn hermite(s: f64, h: f64, y0: f64, y1: f64, v0: f64, v1: f64) -> f64 {
    let s2 = s * s;
    let s3 = s2 * s;
    (2.0 * s3 - 3.0 * s2 + 1.0) * y0
        + (s3 - 2.0 * s2 + s) * h * v0
        + (-2.0 * s3 + 3.0 * s2) * y1
        + (s3 - s2) * h * v1
}

/// Time derivative of [`hermite`].
#[inline]
pub(crate) fn hermite_rate(s: f64, h: f64, y0: f64, y1: f64, v0: f64, v1: f64) -> f64 {
    let s2 = s * s;
    ((6.0 * s2 - 6.0 * s) * y0
        + (3.0 * s2 - 4.0 * s + 1.0) * h * v0
        + (-6.0 * s2 + 6.0 * s) * y1
        + (3.0 * s2 - 2.0 * s) * h * v1)
        / h
}

/// Quintic Hermite interpolation of `y` on a step of length `h` at `s ∈ [0, 1]` from the values,
/// first and second derivatives at both ends: the value and the time derivative.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn quintic(
    s: f64,
    h: f64,
    y0: f64,
    y1: f64,
    v0: f64,
    v1: f64,
    a0: f64,
    a1: f64,
) -> (f64, f64) {
    let s2 = s * s;
    let s3 = s2 * s;
    let s4 = s3 * s;
    let s5 = s4 * s;
    let (hv0, hv1, ha0, ha1) = (h * v0, h * v1, h * h * a0, h * h * a1);
    let y = (1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5) * y0
        + (s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5) * hv0
        + 0.5 * (s2 - 3.0 * s3 + 3.0 * s4 - s5) * ha0
        + 0.5 * (s3 - 2.0 * s4 + s5) * ha1
        + (-4.0 * s3 + 7.0 * s4 - 3.0 * s5) * hv1
        + (10.0 * s3 - 15.0 * s4 + 6.0 * s5) * y1;
    let dy = 30.0 * (s2 - 2.0 * s3 + s4) * (y1 - y0)
        + (1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4) * hv0
        + (s - 4.5 * s2 + 6.0 * s3 - 2.5 * s4) * ha0
        + (1.5 * s2 - 4.0 * s3 + 2.5 * s4) * ha1
        + (-12.0 * s2 + 28.0 * s3 - 15.0 * s4) * hv1;
    (y, dy / h)
}

/// Root of `f` on `[a, b]` with `f(a) <= 0 < f(b)` by the Illinois variant of regula falsi.
/// Returns a point of the final bracket's violated side (`f > 0`, or `b`), so that the event has
/// happened at the returned time; stops when the bracket is below `tol`.
pub(crate) fn illinois(
    mut f: impl FnMut(f64) -> f64,
    mut a: f64,
    mut fa: f64,
    mut b: f64,
    mut fb: f64,
    tol: f64,
) -> f64 {
    let mut side = 0i8;
    for _ in 0..100 {
        if b - a <= tol {
            break;
        }
        let mut c = (a * fb - b * fa) / (fb - fa);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let fc = f(c);
        if fc > 0.0 {
            b = c;
            fb = fc;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        } else {
            a = c;
            fa = fc;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        }
    }
    b
}

/// Fraction `s ∈ [0, 1]` of the step where the Hermite cubic of `g = σ φ` (`g0 >= 0`, `g1 < 0`)
/// first reaches zero coming down: with `g0 > 0` the root in `(0, 1)`; with `g0 == 0` (a DOF
/// that has just opened) the root after the cubic's interior maximum, or 0 if the cubic never
/// rises above zero.
pub(crate) fn hermite_crossing(h: f64, g0: f64, g1: f64, r0: f64, r1: f64) -> f64 {
    let cubic = |s: f64| hermite(s, h, g0, g1, r0, r1);
    let mut lo = 0.0;
    let mut flo = -g0;
    if g0 <= 0.0 {
        // Interior maxima: roots of the derivative (a quadratic A s² + B s + C).
        let a = 6.0 * g0 + 3.0 * h * r0 - 6.0 * g1 + 3.0 * h * r1;
        let b = -6.0 * g0 - 4.0 * h * r0 + 6.0 * g1 - 2.0 * h * r1;
        let c = h * r0;
        let mut best = (0.0, 0.0);
        let mut consider = |s: f64| {
            if s > 0.0 && s < 1.0 {
                let v = cubic(s);
                if v > best.1 {
                    best = (s, v);
                }
            }
        };
        if a.abs() > 1e-300 {
            let disc = b * b - 4.0 * a * c;
            if disc >= 0.0 {
                let r = disc.sqrt();
                consider((-b + r) / (2.0 * a));
                consider((-b - r) / (2.0 * a));
            }
        } else if b.abs() > 1e-300 {
            consider(-c / b);
        }
        if best.1 <= 0.0 {
            return 0.0;
        }
        lo = best.0;
        flo = -best.1;
    }
    // f = −g: from <= 0 (before) to > 0 (after).
    illinois(|s| -cubic(s), lo, flo, 1.0, -g1, 1e-13)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_reproduces_cubics() {
        let y = |t: f64| 1.0 - 2.0 * t + 0.5 * t * t - 3.0 * t * t * t;
        let dy = |t: f64| -2.0 + t - 9.0 * t * t;
        let (t0, h) = (0.3, 0.2);
        for s in [0.0, 0.25, 0.7, 1.0] {
            let t = t0 + s * h;
            assert!((hermite(s, h, y(t0), y(t0 + h), dy(t0), dy(t0 + h)) - y(t)).abs() < 1e-14);
            assert!(
                (hermite_rate(s, h, y(t0), y(t0 + h), dy(t0), dy(t0 + h)) - dy(t)).abs() < 1e-13
            );
        }
    }

    #[test]
    fn quintic_reproduces_quintics() {
        let y = |t: f64| {
            0.3 - t + 2.0 * t.powi(2) - 0.7 * t.powi(3) + 1.1 * t.powi(4) - 2.0 * t.powi(5)
        };
        let dy = |t: f64| -1.0 + 4.0 * t - 2.1 * t.powi(2) + 4.4 * t.powi(3) - 10.0 * t.powi(4);
        let ddy = |t: f64| 4.0 - 4.2 * t + 13.2 * t.powi(2) - 40.0 * t.powi(3);
        let (t0, h) = (0.4, 0.3);
        let t1 = t0 + h;
        for s in [0.0, 0.2, 0.55, 0.9, 1.0] {
            let t = t0 + s * h;
            let (v, d) = quintic(s, h, y(t0), y(t1), dy(t0), dy(t1), ddy(t0), ddy(t1));
            assert!((v - y(t)).abs() < 1e-14, "{v} vs {}", y(t));
            assert!((d - dy(t)).abs() < 1e-13, "{d} vs {}", dy(t));
        }
    }

    #[test]
    fn illinois_finds_roots() {
        let r = illinois(|t| t * t - 2.0, 0.0, -2.0, 2.0, 2.0, 1e-14);
        assert!((r - 2f64.sqrt()).abs() < 1e-13);
    }

    #[test]
    fn crossing_after_just_opened() {
        // g(t) = t (1 − t) · 4 − 0.5 t: rises from 0 and comes back.
        let g = |t: f64| 4.0 * t * (1.0 - t) - 2.0 * t * t * t;
        let dg = |t: f64| 4.0 - 8.0 * t - 6.0 * t * t;
        let s = hermite_crossing(1.0, g(0.0), g(1.0), dg(0.0), dg(1.0));
        assert!(s > 0.5 && s < 1.0 && g(s).abs() < 1e-10, "s = {s}");
        // Never rises: the crossing is at the start.
        assert_eq!(hermite_crossing(1.0, 0.0, -1.0, -0.5, -1.5), 0.0);
    }
}
