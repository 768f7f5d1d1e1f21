//! Plain-text records: one column of accelerations with a given time step, or two columns `t a`.

use super::{bad_value, invalid, parse_number, Record, RecordError};
use crate::model::column::GRAVITY;
use crate::validate::{finite, positive, InvalidValue};

/// How to read a plain-text record (see [`parse_plain`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlainFormat {
    /// Time step \[s\]. Required for one column; for two columns, if given, it must agree with the
    /// time column.
    pub dt: Option<f64>,
    /// Factor from the file's units to m/s²: 1 for m/s² (the default), `GRAVITY` for g, 0.01 for
    /// cm/s².
    pub scale: f64,
}

impl Default for PlainFormat {
    fn default() -> PlainFormat {
        PlainFormat {
            dt: None,
            scale: 1.0,
        }
    }
}

impl PlainFormat {
    /// Values in m/s², with the given time step (needed for one column).
    pub fn with_dt(dt: f64) -> PlainFormat {
        PlainFormat {
            dt: Some(dt),
            scale: 1.0,
        }
    }

    /// The same format with values in g (scale = [`GRAVITY`]).
    pub fn in_g(self) -> PlainFormat {
        PlainFormat {
            scale: GRAVITY,
            ..self
        }
    }

    fn validate(&self) -> Result<(), RecordError> {
        if let Some(dt) = self.dt {
            positive("dt", dt)?;
        }
        if finite("scale", self.scale)? == 0.0 {
            return Err(InvalidValue::new("scale", self.scale, "must not be zero").into());
        }
        Ok(())
    }
}

/// Relative tolerance, in time steps, of the time column of a two-column plain file.
const TIME_TOLERANCE: f64 = 0.01;

/// Largest number of zero samples prepended when a time column starts after `t = 0`.
const MAX_LEADING_STEPS: usize = 10_000_000;

/// Parses a plain-text record. Blank lines and lines starting with `#` or `%` are skipped;
/// values are separated by white space, commas or semicolons.
///
/// - One column: accelerations, `format.dt` required.
/// - Two columns: `t a`. The time step is `(t_last − t_first) / (n − 1)` and every time must lie
///   on that grid within 1 % of a step (else the line is reported); if `format.dt` is given it
///   must agree. A time column that starts at `t_first = m·dt > 0` gets `m` zero samples in front,
///   so the record still starts at `t = 0`; any other start is an error.
///
/// Accelerations are multiplied by `format.scale` (their unit in m/s²).
pub fn parse_plain(text: &str, name: &str, format: &PlainFormat) -> Result<Record, RecordError> {
    format.validate()?;
    let err = |line: usize, message: String| RecordError::Parse {
        record: name.to_string(),
        line,
        message,
    };
    // (line number, time or NaN, acceleration)
    let mut columns = 0usize;
    let mut lines_of = Vec::new();
    let mut times = Vec::new();
    let mut values = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line_no = k + 1;
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') || trimmed.starts_with('%') {
            continue;
        }
        let mut row = [0.0; 2];
        let mut count = 0;
        for token in trimmed
            .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .filter(|s| !s.is_empty())
        {
            let v = parse_number(token).ok_or_else(|| {
                if values.is_empty() && token.parse::<f64>().is_err() {
                    // A spreadsheet's CSV starts with its column names.
                    err(
                        line_no,
                        format!(
                            "`{token}` is not a number: a line of column names? Delete it or \
                             start it with # (the units are not read from it: m/s² unless \
                             given)"
                        ),
                    )
                } else {
                    bad_value(name, line_no, token)
                }
            })?;
            if count < 2 {
                row[count] = v;
            }
            count += 1;
        }
        if count > 2 {
            return Err(err(
                line_no,
                format!("{count} columns; a plain record has one (a) or two (t a)"),
            ));
        }
        if columns == 0 {
            columns = count;
        } else if count != columns {
            return Err(err(
                line_no,
                format!("{count} column(s), but the first data line has {columns}"),
            ));
        }
        lines_of.push(line_no);
        if columns == 1 {
            values.push(row[0] * format.scale);
        } else {
            times.push(row[0]);
            values.push(row[1] * format.scale);
        }
    }
    if values.is_empty() {
        return Err(RecordError::Empty {
            record: name.to_string(),
        });
    }
    if columns == 1 {
        let dt = format.dt.ok_or_else(|| {
            invalid(
                "dt",
                format!("`{name}` has one column: the time step must be given"),
            )
        })?;
        return Ok(Record {
            name: name.to_string(),
            dt,
            samples: values,
        });
    }

    let n = times.len();
    let t0 = times[0];
    let dt = if n >= 2 {
        (times[n - 1] - t0) / (n - 1) as f64
    } else {
        format.dt.ok_or_else(|| {
            invalid(
                "dt",
                format!("`{name}` has a single time: the time step must be given"),
            )
        })?
    };
    if positive("dt", dt).is_err() {
        return Err(err(
            lines_of[n - 1],
            format!("times must increase: first {t0}, last {}", times[n - 1]),
        ));
    }
    for i in 1..n {
        let expected = t0 + i as f64 * dt;
        if (times[i] - expected).abs() > TIME_TOLERANCE * dt {
            return Err(err(
                lines_of[i],
                format!(
                    "time {} is off the uniform grid (expected {expected}, dt = {dt})",
                    times[i]
                ),
            ));
        }
    }
    // A given dt must put every time on its grid too; it is then used as is (exact).
    let dt = match format.dt {
        Some(given) if (given - dt).abs() * (n - 1) as f64 > TIME_TOLERANCE * dt => {
            return Err(invalid(
                "dt",
                format!("given dt = {given} but the time column of `{name}` has dt = {dt}"),
            ));
        }
        Some(given) => given,
        None => dt,
    };
    let m = t0 / dt;
    let steps = m.round();
    if m < -TIME_TOLERANCE || (m - steps).abs() > TIME_TOLERANCE {
        return Err(err(
            lines_of[0],
            format!("first time {t0} is not 0 or a whole number of steps dt = {dt}"),
        ));
    }
    if steps > MAX_LEADING_STEPS as f64 {
        return Err(err(
            lines_of[0],
            format!("first time {t0} is more than {MAX_LEADING_STEPS} steps after 0"),
        ));
    }
    let mut samples = vec![0.0; steps as usize];
    samples.extend_from_slice(&values);
    Ok(Record {
        name: name.to_string(),
        dt,
        samples,
    })
}
