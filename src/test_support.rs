//! Helpers shared by the library's unit tests: rounding and comparing with the thesis's printed
//! numbers ([`crate::samples::Printed`]), and absolute closeness.

use crate::samples::Printed;

/// `x` rounded to `decimals` places (half away from zero), for statements about how a number
/// prints (double rounding, ties).
pub(crate) fn round_to(x: f64, decimals: i32) -> f64 {
    let s = 10f64.powi(decimals);
    (x * s).round() / s
}

/// `value` reproduces the printed number (within half a unit of its last digit).
#[track_caller]
pub(crate) fn assert_printed(value: f64, printed: Printed) {
    assert!(
        printed.matches(value),
        "{value} does not print as {printed}"
    );
}

/// `|a − b| ≤ tol`.
pub(crate) fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

/// A xorshift64 generator from `seed`: each call gives the next value in `[0, 1)` (53 bits). The
/// bit-for-bit tests of the exact fast paths draw their random inputs from it.
pub(crate) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}
