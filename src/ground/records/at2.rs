//! PEER NGA `.AT2` files: the reader (header variants, units, counts) and the writer.

use std::path::Path;

use super::{bad_value, parse_number, read_text, stem, Record, RecordError};
use crate::model::column::GRAVITY;

/// Number of header lines of an `.AT2` file.
const AT2_HEADER_LINES: usize = 4;

/// The value that follows `key` (case-insensitive, as a whole word) and an optional `=` or `:`,
/// e.g. `NPTS=  4000,` → `"4000"`, `DT= .0050 SEC` → `".0050"`.
fn keyed_value<'a>(upper: &'a str, key: &str) -> Option<&'a str> {
    let bytes = upper.as_bytes();
    let mut from = 0;
    while let Some(pos) = upper[from..].find(key) {
        let start = from + pos;
        let end = start + key.len();
        let word_start = start == 0 || !bytes[start - 1].is_ascii_alphanumeric();
        let word_end = end == bytes.len() || !bytes[end].is_ascii_alphanumeric();
        if word_start && word_end {
            let rest = upper[end..].trim_start();
            let rest = rest
                .strip_prefix('=')
                .or_else(|| rest.strip_prefix(':'))
                .unwrap_or(rest)
                .trim_start();
            let len = rest
                .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '+' | '-' | 'E')))
                .unwrap_or(rest.len());
            // `E` alone would swallow `SEC`; keep it only when followed by digits or a sign.
            let value = &rest[..len];
            let value = value.trim_end_matches('E');
            return (!value.is_empty()).then_some(value);
        }
        from = end;
    }
    None
}

/// `NPTS` and `DT` from line 4 of an `.AT2` file. Accepts the NGA-West2 form
/// `NPTS=  4000, DT=   .0050 SEC` and its variants (no comma, lower case, `:`), and the old PEER
/// form `  4000   .0050   NPTS, DT` (numbers first).
fn parse_at2_counts(record: &str, line_no: usize, line: &str) -> Result<(usize, f64), RecordError> {
    let err = |message: String| RecordError::Parse {
        record: record.to_string(),
        line: line_no,
        message,
    };
    let upper = line.to_ascii_uppercase();
    let (npts_text, dt_text) = match (keyed_value(&upper, "NPTS"), keyed_value(&upper, "DT")) {
        (Some(n), Some(d)) => (n.to_string(), d.to_string()),
        (n, _) => {
            // Old PEER format: `  4000   .0050   NPTS, DT`.
            let tokens: Vec<&str> = upper
                .split(|c: char| c.is_whitespace() || c == ',')
                .filter(|s| !s.is_empty())
                .collect();
            let numbers_first = tokens.len() >= 4
                && tokens[0].parse::<f64>().is_ok()
                && tokens[1].parse::<f64>().is_ok()
                && tokens[2] == "NPTS"
                && tokens[3] == "DT";
            if numbers_first {
                (tokens[0].to_string(), tokens[1].to_string())
            } else if n.is_none() {
                return Err(err(format!("no `NPTS=` in header line: `{}`", line.trim())));
            } else {
                return Err(err(format!("no `DT=` in header line: `{}`", line.trim())));
            }
        }
    };
    let npts = npts_text.parse::<usize>().map_err(|_| {
        err(format!(
            "NPTS = `{npts_text}` is not a non-negative integer"
        ))
    })?;
    let dt = parse_number(&dt_text)
        .ok_or_else(|| err(format!("DT = `{dt_text}` is not a finite number")))?;
    if dt <= 0.0 {
        return Err(err(format!("DT = {dt} must be positive")));
    }
    Ok((npts, dt))
}

/// Parses a PEER NGA `.AT2` acceleration file: 4 header lines (title, event and station,
/// `ACCELERATION TIME SERIES IN UNITS OF G`, `NPTS= n, DT= dt SEC`), then `n` values in g, any
/// number per line, first sample at `t = 0`. Values are converted to m/s² with
/// [`GRAVITY`].
///
/// Errors: empty text, fewer than 4 header lines, line 3 naming a velocity or displacement series
/// or units other than g, missing or invalid `NPTS` or `DT` (`DT <= 0`), a value that is not a
/// finite number (its line), `NPTS` different from the number of values (both numbers).
pub fn parse_at2(text: &str, name: &str) -> Result<Record, RecordError> {
    if text.trim().is_empty() {
        return Err(RecordError::Empty {
            record: name.to_string(),
        });
    }
    let mut lines = text.lines();
    let mut header = Vec::with_capacity(AT2_HEADER_LINES);
    for _ in 0..AT2_HEADER_LINES {
        match lines.next() {
            Some(line) => header.push(line),
            None => {
                return Err(RecordError::Parse {
                    record: name.to_string(),
                    line: header.len() + 1,
                    message: format!(
                        "truncated header: the file ends after {} line(s), an AT2 header has {}",
                        header.len(),
                        AT2_HEADER_LINES
                    ),
                })
            }
        }
    }
    check_at2_units(name, header[2])?;
    let (npts, dt) = parse_at2_counts(name, AT2_HEADER_LINES, header[3])?;

    let mut samples = Vec::with_capacity(npts.min(10_000_000));
    for (k, line) in lines.enumerate() {
        let line_no = AT2_HEADER_LINES + 1 + k;
        for token in line.split(|c: char| c.is_whitespace() || c == ',') {
            if token.is_empty() {
                continue;
            }
            let g = parse_number(token).ok_or_else(|| bad_value(name, line_no, token))?;
            samples.push(g * GRAVITY);
        }
    }
    if samples.len() != npts {
        return Err(RecordError::CountMismatch {
            record: name.to_string(),
            npts,
            values: samples.len(),
        });
    }
    Ok(Record {
        name: name.to_string(),
        dt,
        samples,
    })
}

/// Line 3 of an AT2 file: refuses velocity and displacement series (`.VT2`, `.DT2`) and units
/// other than g, which would otherwise be read as accelerations in g without a word.
fn check_at2_units(record: &str, line: &str) -> Result<(), RecordError> {
    let upper = line.to_ascii_uppercase();
    let err = |message: String| RecordError::Parse {
        record: record.to_string(),
        line: 3,
        message,
    };
    if upper.contains("VELOCITY") || upper.contains("DISPLACEMENT") {
        return Err(err(format!(
            "not an acceleration series: `{}`",
            line.trim()
        )));
    }
    if let Some(pos) = upper.find("UNITS OF") {
        let unit = upper[pos + "UNITS OF".len()..]
            .split_whitespace()
            .next()
            .map(|u| u.trim_matches(|c: char| !c.is_ascii_alphanumeric()));
        if unit != Some("G") {
            return Err(err(format!(
                "units must be g, the header says `{}`",
                line.trim()
            )));
        }
    }
    Ok(())
}

/// Reads a PEER NGA `.AT2` file (see [`parse_at2`]); the record is named after the file stem.
pub fn read_at2(path: &Path) -> Result<Record, RecordError> {
    let text = read_text(path)?;
    parse_at2(&text, &stem(path))
}

/// `x` as a Fortran `E15.7` field (`-1.6078470E-04`), the layout of PEER files.
pub(super) fn fortran_e(x: f64) -> String {
    if x == 0.0 {
        return "0.0000000E+00".to_string();
    }
    let s = format!("{x:.7e}");
    let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    format!("{mantissa}E{exponent:+03}")
}

/// Writes `record` as a PEER `.AT2` text: `header[0]` and `header[1]` as lines 1 and 2 (line
/// breaks replaced by spaces), `ACCELERATION TIME SERIES IN UNITS OF G`, `NPTS= n, DT= dt SEC`,
/// then the samples in g (divided by [`GRAVITY`]), 5 per line, 8
/// significant digits. `dt` is written so that it reads back exactly.
pub fn write_at2(record: &Record, header: [&str; 2]) -> String {
    let one_line = |s: &str| s.replace(['\r', '\n'], " ");
    let dt5 = format!("{:.5}", record.dt);
    let dt_text = if dt5.parse::<f64>() == Ok(record.dt) {
        dt5
    } else {
        format!("{}", record.dt)
    };
    let mut out = String::with_capacity(64 * 4 + record.samples.len() * 16 + 200);
    out.push_str(&one_line(header[0]));
    out.push('\n');
    out.push_str(&one_line(header[1]));
    out.push('\n');
    out.push_str("ACCELERATION TIME SERIES IN UNITS OF G\n");
    out.push_str(&format!(
        "NPTS= {:>6}, DT= {dt_text} SEC\n",
        record.samples.len()
    ));
    for chunk in record.samples.chunks(5) {
        for a in chunk {
            out.push_str(&format!("{:>16}", fortran_e(a / GRAVITY)));
        }
        out.push('\n');
    }
    out
}
