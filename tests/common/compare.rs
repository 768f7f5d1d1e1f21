//! Comparisons shared by the integration tests: with the thesis's printed numbers
//! ([`rocking::samples::Printed`]) and absolute closeness.

use rocking::samples::Printed;

/// `value` reproduces the printed number (within half a unit of its last digit).
#[track_caller]
pub fn assert_printed(value: f64, printed: Printed) {
    assert!(
        printed.matches(value),
        "{value} does not print as {printed}"
    );
}

/// `|a − b| ≤ tol`.
pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}
