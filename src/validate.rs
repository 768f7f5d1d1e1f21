//! One place for the range checks of plain numeric inputs (lengths, masses, time steps, levels
//! …): each returns the value or an [`InvalidValue`] that names the field, so every error type of
//! the crate reports a bad input the same way. The C ABI's own checks (pointers, sizes, NaN in
//! arrays) are in `model::configuration` and `ffi`.

use std::fmt;

/// A numeric input out of its range: the field (as the user wrote it), the value, and the rule.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{field} = {value}: {rule}")]
pub struct InvalidValue {
    /// The field or argument, e.g. `"blocks[2].width"` or `"dt"`.
    pub field: String,
    /// The value, printed.
    pub value: String,
    /// What it must be, e.g. `"must be a finite number greater than zero"`.
    pub rule: &'static str,
}

impl InvalidValue {
    /// An invalid value of any printable type.
    pub fn new(field: impl Into<String>, value: impl fmt::Debug, rule: &'static str) -> Self {
        InvalidValue {
            field: field.into(),
            value: format!("{value:?}"),
            rule,
        }
    }
}

/// The most steps a run may take (`duration / dt`): a step smaller than that would never end
/// the run. The column, drum and loop drivers, the loop scenes and `rocking bench drums` refuse
/// it by the one rule [`too_many_steps`] (their messages say "more than 1e10 steps").
pub const MAX_STEPS: f64 = 1e10;

/// Whether a run of `duration` at steps of `dt` takes more than [`MAX_STEPS`] steps.
pub fn too_many_steps(duration: f64, dt: f64) -> bool {
    duration / dt > MAX_STEPS
}

/// The most threads a sweep starts (the CLI's `--threads`, Python's `threads=`): a count far
/// beyond the machine's cores only costs threads, and a million of them got the process killed
/// while rayon started them.
pub const MAX_THREADS: usize = 1024;

/// The most points a grid count of a sweep asks for (levels, sizes, pulse periods, radii; the
/// thesis's OAS grid is 80 × 120): `levels = 10⁹` allocated an 8 GB grid and the process aborted
/// under a memory limit.
pub const MAX_GRID_POINTS: usize = 100_000;

/// `v` finite and `> 0`.
pub fn positive(field: impl Into<String>, v: f64) -> Result<f64, InvalidValue> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(InvalidValue::new(
            field,
            v,
            "must be a finite number greater than zero",
        ))
    }
}

/// `v` finite and `>= 0`.
pub fn non_negative(field: impl Into<String>, v: f64) -> Result<f64, InvalidValue> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(InvalidValue::new(field, v, "must be a finite number >= 0"))
    }
}

/// `v` finite.
pub fn finite(field: impl Into<String>, v: f64) -> Result<f64, InvalidValue> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(InvalidValue::new(field, v, "must be a finite number"))
    }
}

/// Every value of `values` finite and `> 0` (the field is reported as `field[i]`).
pub fn all_positive(field: &str, values: &[f64]) -> Result<(), InvalidValue> {
    each(field, values, positive)
}

/// Every value of `values` finite (the field is reported as `field[i]`).
pub fn all_finite(field: &str, values: &[f64]) -> Result<(), InvalidValue> {
    each(field, values, finite)
}

/// `check` on every value; the field of an error is `field[i]`, formatted only on failure.
fn each(
    field: &str,
    values: &[f64],
    check: fn(&'static str, f64) -> Result<f64, InvalidValue>,
) -> Result<(), InvalidValue> {
    for (i, &v) in values.iter().enumerate() {
        check("", v).map_err(|e| InvalidValue {
            field: format!("{field}[{i}]"),
            ..e
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_the_field_and_the_rule() {
        assert_eq!(positive("dt", 0.5), Ok(0.5));
        let e = positive("dt", 0.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "dt = 0.0: must be a finite number greater than zero"
        );
        assert!(positive("dt", f64::NAN).is_err());
        assert!(non_negative("duration", 0.0).is_ok());
        assert!(non_negative("duration", -1.0).is_err());
        assert!(finite("x", f64::INFINITY).is_err());
        let e = all_positive("widths", &[1.0, -2.0]).unwrap_err();
        assert_eq!(e.field, "widths[1]");
        assert_eq!(
            e.to_string(),
            "widths[1] = -2.0: must be a finite number greater than zero"
        );
        assert!(all_finite("samples", &[0.0, -1.0]).is_ok());
        assert_eq!(
            all_finite("samples", &[0.0, f64::NAN]).unwrap_err().field,
            "samples[1]"
        );
    }
}
