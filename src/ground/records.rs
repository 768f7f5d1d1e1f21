//! Recorded ground motions: uniformly sampled horizontal ground accelerations in m/s².
//!
//! Readers for the PEER NGA `.AT2` format (values in g, converted with
//! [`GRAVITY`] = 9.81 m/s², as the thesis does) and for plain text
//! (one column of accelerations with a given time step, or two columns `t a`). Every failure is a
//! [`RecordError`] that names the line (1-based) or the field; nothing panics and no record is
//! ever silently shorter than its header says.
//!
//! A record's first sample is at `t = 0`; between samples the acceleration is interpolated
//! linearly, and it is zero before `t = 0` and after the last sample (SPEC §7: the record is the
//! excitation of the overturning acceleration spectra of thesis Ch. 5).
//!
//! [`synthetic_record`] makes a deterministic artificial ground motion (filtered, enveloped white
//! noise) and [`write_at2`] writes a record as `.AT2`; together they produce the bundled
//! `examples/records/synthetic.AT2`.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::model::column::GRAVITY;

/// A uniformly sampled ground-acceleration record. Sample `i` is the acceleration at `t = i·dt`.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// Name for messages and plots (file stem for files read from disk).
    pub name: String,
    /// Time step \[s\], finite and positive.
    pub dt: f64,
    /// Ground accelerations \[m/s²\], positive = ground accelerates to +x.
    pub samples: Vec<f64>,
}

/// Why a record could not be read, parsed or built.
#[derive(Clone, Debug, PartialEq)]
pub enum RecordError {
    /// The file could not be read.
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// The text holds no data at all.
    Empty {
        /// Record name (file stem or the name passed to the parser).
        record: String,
    },
    /// A line is malformed: truncated or incomplete header, missing `NPTS` or `DT`, a bad `DT`, a
    /// value that is not a finite number, uneven time spacing...
    Parse {
        /// Record name.
        record: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong, quoting the offending text.
        message: String,
    },
    /// The header's `NPTS` disagrees with the number of values that follow it.
    CountMismatch {
        /// Record name.
        record: String,
        /// `NPTS` of the header.
        npts: usize,
        /// Number of values in the file.
        values: usize,
    },
    /// An argument (or a field of a [`Record`]) is invalid.
    InvalidArgument {
        /// Argument or field name.
        field: &'static str,
        /// What is wrong with it.
        message: String,
    },
}

impl fmt::Display for RecordError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RecordError::Io { path, message } => write!(f, "{}: {message}", path.display()),
            RecordError::Empty { record } => write!(f, "{record}: empty file, no data"),
            RecordError::Parse {
                record,
                line,
                message,
            } => write!(f, "{record}, line {line}: {message}"),
            RecordError::CountMismatch {
                record,
                npts,
                values,
            } => write!(
                f,
                "{record}: header says NPTS = {npts} but the file holds {values} values"
            ),
            RecordError::InvalidArgument { field, message } => write!(f, "{field}: {message}"),
        }
    }
}

impl std::error::Error for RecordError {}

fn invalid(field: &'static str, message: String) -> RecordError {
    RecordError::InvalidArgument { field, message }
}

impl Record {
    /// A record with validated fields: `dt` finite and positive, every sample finite.
    pub fn new(name: &str, dt: f64, samples: Vec<f64>) -> Result<Record, RecordError> {
        let record = Record {
            name: name.to_string(),
            dt,
            samples,
        };
        record.validate()?;
        Ok(record)
    }

    /// Checks the fields: `dt` finite and positive, every sample finite.
    pub fn validate(&self) -> Result<(), RecordError> {
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(invalid(
                "dt",
                format!("must be finite and positive, got {}", self.dt),
            ));
        }
        if let Some(i) = self.samples.iter().position(|a| !a.is_finite()) {
            return Err(invalid(
                "samples",
                format!("sample {i} is {}, not a finite number", self.samples[i]),
            ));
        }
        Ok(())
    }

    /// Ground acceleration at time `t` \[m/s²\]: linear interpolation between samples, zero before
    /// `t = 0`, after the last sample and for NaN `t`. O(1) and allocation-free
    /// (`i = floor(t / dt)`).
    #[inline]
    pub fn acceleration(&self, t: f64) -> f64 {
        let n = self.samples.len();
        let x = t / self.dt;
        // `contains` is false for NaN too.
        if n == 0 || !(0.0..=(n - 1) as f64).contains(&x) {
            return 0.0;
        }
        let i = x as usize; // floor, x >= 0
        if i + 1 >= n {
            return self.samples[n - 1];
        }
        let s = x - i as f64;
        let a0 = self.samples[i];
        a0 + s * (self.samples[i + 1] - a0)
    }

    /// Time of the last sample, `(n − 1)·dt` \[s\] (0 for fewer than two samples); the acceleration
    /// is zero after it.
    pub fn duration(&self) -> f64 {
        self.samples.len().saturating_sub(1) as f64 * self.dt
    }

    /// `S[i] = ∫_{t_i}^{end} |a(t)| dt` of the linearly interpolated record (m/s), one entry per
    /// sample (the last is 0): the tail impulses that [`Record::impulse_after`] reads.
    pub fn impulse_table(&self) -> Vec<f64> {
        let n = self.samples.len();
        let mut table = vec![0.0; n];
        for i in (0..n.saturating_sub(1)).rev() {
            table[i] = table[i + 1] + abs_integral(self.samples[i], self.samples[i + 1], self.dt);
        }
        table
    }

    /// `∫_t^end |a(s)| ds` (m/s) of the linearly interpolated record, from the `table` of
    /// [`Record::impulse_table`] (0 after the end, the whole record's before the start).
    pub fn impulse_after(&self, table: &[f64], t: f64) -> f64 {
        let n = self.samples.len().min(table.len());
        if n == 0 {
            return 0.0;
        }
        let x = t / self.dt;
        if x.is_nan() || x <= 0.0 {
            return table[0];
        }
        if x >= (n - 1) as f64 {
            return 0.0;
        }
        let i = x as usize;
        let rest = (i + 1) as f64 - x;
        let b = self.samples[i + 1];
        let a = b + rest * (self.samples[i] - b);
        table[i + 1] + abs_integral(a, b, rest * self.dt)
    }

    /// Peak ground acceleration `max |a|` \[m/s²\] (0 for an empty record). With linear
    /// interpolation this is also the peak of [`Record::acceleration`] over time.
    pub fn pga(&self) -> f64 {
        self.samples.iter().fold(0.0, |m, a| m.max(a.abs()))
    }

    /// The record with every sample multiplied by `factor` (same name, same `dt`).
    pub fn scaled(&self, factor: f64) -> Record {
        Record {
            name: self.name.clone(),
            dt: self.dt,
            samples: self.samples.iter().map(|a| a * factor).collect(),
        }
    }

    /// The record scaled so that its peak ground acceleration is `target` \[m/s²\] (frequency
    /// content unchanged, as the overturning acceleration spectra of SPEC §7 scale records).
    /// Errors: `target` not finite and positive, or a record whose PGA is zero.
    pub fn scaled_to_pga(&self, target: f64) -> Result<Record, RecordError> {
        if !(target.is_finite() && target > 0.0) {
            return Err(invalid(
                "target",
                format!("target PGA must be finite and positive, got {target}"),
            ));
        }
        let pga = self.pga();
        if !(pga > 0.0 && pga.is_finite()) {
            return Err(invalid(
                "samples",
                format!("record `{}` has PGA {pga}, it cannot be scaled", self.name),
            ));
        }
        Ok(self.scaled(target / pga))
    }
}

// ---------------------------------------------------------------------------------------------
// Number parsing shared by the readers.

/// Parses one numeric token; accepts Fortran `D` exponents (`1.0D-03`). Rejects NaN and infinity.
fn parse_number(token: &str) -> Option<f64> {
    let value = match token.parse::<f64>() {
        Ok(v) => v,
        Err(_) if token.contains(['D', 'd']) => token.replace(['D', 'd'], "E").parse().ok()?,
        Err(_) => return None,
    };
    value.is_finite().then_some(value)
}

fn bad_value(record: &str, line: usize, token: &str) -> RecordError {
    RecordError::Parse {
        record: record.to_string(),
        line,
        message: format!("`{token}` is not a finite number"),
    }
}

// ---------------------------------------------------------------------------------------------
// PEER NGA .AT2

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

/// `∫_0^h |a + (b − a) s/h| ds`: a trapezoid, or two triangles when the segment crosses zero.
fn abs_integral(a: f64, b: f64, h: f64) -> f64 {
    if a * b >= 0.0 {
        0.5 * h * (a.abs() + b.abs())
    } else {
        0.5 * h * (a * a + b * b) / (a.abs() + b.abs())
    }
}

/// Reads a PEER NGA `.AT2` file (see [`parse_at2`]); the record is named after the file stem.
pub fn read_at2(path: &Path) -> Result<Record, RecordError> {
    let text = read_text(path)?;
    parse_at2(&text, &stem(path))
}

fn read_text(path: &Path) -> Result<String, RecordError> {
    std::fs::read_to_string(path).map_err(|e| RecordError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

// ---------------------------------------------------------------------------------------------
// Plain text

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
            if !(dt.is_finite() && dt > 0.0) {
                return Err(invalid(
                    "dt",
                    format!("must be finite and positive, got {dt}"),
                ));
            }
        }
        if !(self.scale.is_finite() && self.scale != 0.0) {
            return Err(invalid(
                "scale",
                format!("must be finite and non-zero, got {}", self.scale),
            ));
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
            let v = parse_number(token).ok_or_else(|| bad_value(name, line_no, token))?;
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
    if !(dt.is_finite() && dt > 0.0) {
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

/// Reads a record by extension: `.AT2`/`.at2` (any case) as PEER AT2 ([`parse_at2`], `format` is
/// not used), anything else as plain text ([`parse_plain`] with `format`). The record is named
/// after the file stem.
pub fn read_record(path: &Path, format: &PlainFormat) -> Result<Record, RecordError> {
    let is_at2 = path
        .extension()
        .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case("at2"));
    if is_at2 {
        read_at2(path)
    } else {
        let text = read_text(path)?;
        parse_plain(&text, &stem(path), format)
    }
}

// ---------------------------------------------------------------------------------------------
// Writing AT2 and the synthetic example record

/// `x` as a Fortran `E15.7` field (`-1.6078470E-04`), the layout of PEER files.
fn fortran_e(x: f64) -> String {
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

/// 64-bit linear congruential generator (Knuth's MMIX constants).
struct Lcg(u64);

impl Lcg {
    /// Uniform in [0, 1) from the top 53 bits.
    fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Approximately standard normal: sum of 12 uniforms minus 6 (Irwin–Hall), arithmetic only.
    fn normal(&mut self) -> f64 {
        (0..12).map(|_| self.uniform()).sum::<f64>() - 6.0
    }
}

/// Linear single-degree-of-freedom filter `x'' + 2ζω x' + ω² x = −u(t)` integrated with
/// Newmark's average acceleration (trapezoidal) rule; its output is the absolute acceleration
/// `x'' + u = −(2ζω x' + ω² x)`. Used with `u` the input acceleration this is the Kanai–Tajimi
/// filter (low-pass around ω), and `x''` alone is the Clough–Penzien high-pass.
struct Oscillator {
    c: f64,
    k: f64,
    dt: f64,
    x: f64,
    v: f64,
    a: f64,
}

impl Oscillator {
    fn new(omega: f64, zeta: f64, dt: f64) -> Oscillator {
        Oscillator {
            c: 2.0 * zeta * omega,
            k: omega * omega,
            dt,
            x: 0.0,
            v: 0.0,
            a: 0.0,
        }
    }

    /// Advances one step with input `u` at the new time; returns `(x'', x'' + u)`.
    fn step(&mut self, u: f64) -> (f64, f64) {
        let h = self.dt;
        // x1 = x + h v + h²/4 (a + a1), v1 = v + h/2 (a + a1), a1 + c v1 + k x1 = −u.
        let lhs = 1.0 + self.c * h / 2.0 + self.k * h * h / 4.0;
        let rhs = -u
            - self.c * (self.v + h / 2.0 * self.a)
            - self.k * (self.x + h * self.v + h * h / 4.0 * self.a);
        let a1 = rhs / lhs;
        self.x += h * self.v + h * h / 4.0 * (self.a + a1);
        self.v += h / 2.0 * (self.a + a1);
        self.a = a1;
        (a1, a1 + u)
    }
}

/// Kanai–Tajimi ground frequency ω_g \[rad/s\] of [`synthetic_record`] (2.5 Hz, firm soil).
pub const SYNTHETIC_OMEGA_G: f64 = 5.0 * std::f64::consts::PI;
/// Kanai–Tajimi ground damping ratio ζ_g of [`synthetic_record`].
pub const SYNTHETIC_ZETA_G: f64 = 0.6;
/// Clough–Penzien high-pass frequency ω_f \[rad/s\] of [`synthetic_record`] (0.25 Hz).
pub const SYNTHETIC_OMEGA_F: f64 = 0.5 * std::f64::consts::PI;
/// Clough–Penzien damping ratio ζ_f of [`synthetic_record`].
pub const SYNTHETIC_ZETA_F: f64 = 0.6;

/// A deterministic artificial ground motion, `n = round(duration / dt) + 1` samples:
///
/// 1. white noise: a 64-bit LCG seeded with `seed`, each sample the sum of 12 uniforms − 6;
/// 2. a Jennings-type envelope: `(t/t₁)²` up to `t₁ = 0.1·duration`, 1 up to `t₂ = 0.5·duration`,
///    then `((T − t)/(T − t₂))²` down to zero at `T = duration` (polynomial rather than
///    exponential decay, so that only `+ − × /` are used and the result is bit-identical on every
///    platform);
/// 3. a Kanai–Tajimi filter (ω_g = 5π rad/s, ζ_g = 0.6) followed by a Clough–Penzien high-pass
///    (ω_f = 0.5π rad/s, ζ_f = 0.6), both integrated with Newmark's average acceleration rule;
/// 4. scaled so that the PGA is exactly `pga` \[m/s²\].
///
/// This is the kind of white-noise-based artificial record the thesis cites (Housner 1963,
/// Aslam et al. 1980, DeJong 2012) — a test input, not a model of any real earthquake.
pub fn synthetic_record(
    seed: u64,
    duration: f64,
    dt: f64,
    pga: f64,
) -> Result<Record, RecordError> {
    for (field, value) in [("duration", duration), ("dt", dt), ("pga", pga)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(invalid(
                field,
                format!("must be finite and positive, got {value}"),
            ));
        }
    }
    let steps = (duration / dt).round();
    if !(1.0..=1e8).contains(&steps) {
        return Err(invalid(
            "dt",
            format!(
                "duration / dt = {} must be between 1 and 1e8",
                duration / dt
            ),
        ));
    }
    let n = steps as usize + 1;
    let (t1, t2) = (0.1 * duration, 0.5 * duration);
    let envelope = |t: f64| {
        if t < t1 {
            (t / t1) * (t / t1)
        } else if t <= t2 {
            1.0
        } else {
            let r = ((duration - t) / (duration - t2)).max(0.0);
            r * r
        }
    };
    let mut rng = Lcg(seed);
    let mut kanai_tajimi = Oscillator::new(SYNTHETIC_OMEGA_G, SYNTHETIC_ZETA_G, dt);
    let mut clough_penzien = Oscillator::new(SYNTHETIC_OMEGA_F, SYNTHETIC_ZETA_F, dt);
    let mut samples = Vec::with_capacity(n);
    samples.push(0.0);
    for i in 1..n {
        let t = i as f64 * dt;
        let w = envelope(t) * rng.normal();
        let (_, a_kt) = kanai_tajimi.step(w);
        let (a_cp, _) = clough_penzien.step(a_kt);
        samples.push(a_cp);
    }
    Record {
        name: format!("synthetic-seed{seed}"),
        dt,
        samples,
    }
    .scaled_to_pga(pga)
}

/// Seed of the bundled `examples/records/synthetic.AT2`.
pub const SYNTHETIC_SEED: u64 = 20_170_101;
/// Duration of the bundled synthetic record \[s\].
pub const SYNTHETIC_DURATION: f64 = 20.0;
/// Time step of the bundled synthetic record \[s\].
pub const SYNTHETIC_DT: f64 = 0.01;
/// PGA of the bundled synthetic record, in g.
pub const SYNTHETIC_PGA_G: f64 = 0.3;

/// The text of the bundled `examples/records/synthetic.AT2`: [`synthetic_record`] with the
/// `SYNTHETIC_*` parameters, written by [`write_at2`] with a header that says how it was made.
pub fn bundled_synthetic_at2() -> Result<String, RecordError> {
    let record = synthetic_record(
        SYNTHETIC_SEED,
        SYNTHETIC_DURATION,
        SYNTHETIC_DT,
        SYNTHETIC_PGA_G * GRAVITY,
    )?;
    Ok(write_at2(
        &record,
        [
            "SYNTHETIC GROUND MOTION, NOT A RECORDED EARTHQUAKE (rocking crate, records::synthetic_record)",
            &format!(
                "seed {SYNTHETIC_SEED}: LCG white noise, Jennings-type envelope 0.1T/0.5T/T, Kanai-Tajimi wg=5pi zg=0.6, Clough-Penzien wf=0.5pi zf=0.6, PGA {SYNTHETIC_PGA_G} g"
            ),
        ],
    ))
}

/// The bundled `examples/records/synthetic.AT2`, for the crate's tests (spectra, driver).
#[cfg(test)]
pub(crate) fn bundled_record() -> Record {
    parse_at2(
        include_str!("../../examples/records/synthetic.AT2"),
        "synthetic",
    )
    .unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "PEER NGA STRONG MOTION DATABASE RECORD
Test 1999, STATION, 000
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=     7, DT=   .0100 SEC
  1.0000000E-01  -2.0000000E-01  3.0000000E-01  0.0000000E+00  -5.0000000E-02
  2.5000000E-02   0.0
";

    /// The tail impulse of the interpolated record against a fine midpoint quadrature of
    /// `|a(t)|` (segments that cross zero included), at sample times and between them.
    #[test]
    fn impulse_after_is_the_integral_of_the_absolute_acceleration() {
        let r = Record {
            name: "r".into(),
            dt: 0.01,
            samples: vec![1.0, -2.0, 3.0, 0.0, -0.5, 0.25, 0.0],
        };
        let table = r.impulse_table();
        let quadrature = |t: f64| {
            let n = 200_000;
            let h = (r.duration() - t) / n as f64;
            (0..n)
                .map(|i| r.acceleration(t + (i as f64 + 0.5) * h).abs() * h)
                .sum::<f64>()
        };
        for t in [0.0, 0.003, 0.01, 0.0149, 0.027, 0.04, 0.0555] {
            let got = r.impulse_after(&table, t);
            assert!((got - quadrature(t)).abs() < 1e-8, "t = {t}: {got}");
        }
        assert_eq!(r.impulse_after(&table, -1.0), table[0]);
        assert_eq!(r.impulse_after(&table, 0.06), 0.0);
        assert_eq!(r.impulse_after(&table, 1.0), 0.0);
    }

    fn parse_err(text: &str) -> RecordError {
        parse_at2(text, "t").expect_err("must fail")
    }

    fn with_line4(line4: &str, body: &str) -> String {
        format!("title\nevent\nACCELERATION TIME SERIES IN UNITS OF G\n{line4}\n{body}")
    }

    #[test]
    fn parses_inline_at2() {
        let r = parse_at2(SAMPLE, "sample").unwrap();
        assert_eq!(r.name, "sample");
        assert_eq!(r.dt, 0.01);
        assert_eq!(r.samples.len(), 7);
        assert!((r.samples[2] - 0.3 * GRAVITY).abs() < 1e-12);
        assert!((r.pga() - 0.3 * GRAVITY).abs() < 1e-12);
        assert!((r.duration() - 0.06).abs() < 1e-12);
    }

    #[test]
    fn header_variants() {
        for line4 in [
            "NPTS=  3, DT=   .0050 SEC",
            "NPTS= 3 DT= 0.005 SEC",
            "npts=3, dt=0.005 sec",
            "NPTS=3,DT=5.0E-03SEC",
            "NPTS: 3, DT: 0.005 SEC",
            "   3   .0050   NPTS, DT",
        ] {
            let r = parse_at2(&with_line4(line4, "0.1 0.2 0.3\n"), "v")
                .unwrap_or_else(|e| panic!("`{line4}`: {e}"));
            assert_eq!(r.samples.len(), 3, "{line4}");
            assert_eq!(r.dt, 0.005, "{line4}");
        }
    }

    #[test]
    fn fortran_d_exponent_and_commas() {
        let r = parse_at2(&with_line4("NPTS=2, DT=0.01", "1.0D-01, -2.0d-01\n"), "d").unwrap();
        assert!((r.samples[1] + 0.2 * GRAVITY).abs() < 1e-12);
    }

    #[test]
    fn error_empty() {
        assert!(matches!(parse_err(""), RecordError::Empty { .. }));
        assert!(matches!(parse_err("  \n\n"), RecordError::Empty { .. }));
    }

    #[test]
    fn error_truncated_header() {
        let e = parse_err("title\nevent\n");
        assert!(matches!(e, RecordError::Parse { line: 3, .. }), "{e}");
        assert!(e.to_string().contains("truncated header"), "{e}");
    }

    #[test]
    fn error_missing_npts_or_dt() {
        let e = parse_err(&with_line4("DT= 0.01 SEC", "0.1\n"));
        assert!(matches!(e, RecordError::Parse { line: 4, .. }), "{e}");
        assert!(e.to_string().contains("NPTS"), "{e}");
        let e = parse_err(&with_line4("NPTS= 1", "0.1\n"));
        assert!(matches!(e, RecordError::Parse { line: 4, .. }), "{e}");
        assert!(e.to_string().contains("DT"), "{e}");
        let e = parse_err(&with_line4("NPTS= -1, DT= 0.01", "0.1\n"));
        assert!(e.to_string().contains("NPTS"), "{e}");
    }

    #[test]
    fn error_bad_dt() {
        for dt in ["0", "-0.01", "0.0000", "abc", "nan"] {
            let e = parse_err(&with_line4(&format!("NPTS= 1, DT= {dt} SEC"), "0.1\n"));
            assert!(matches!(e, RecordError::Parse { line: 4, .. }), "{dt}: {e}");
            assert!(e.to_string().contains("DT"), "{e}");
        }
    }

    #[test]
    fn error_non_numeric_value_names_line() {
        let e = parse_err(&with_line4("NPTS= 4, DT= 0.01", "0.1 0.2\n0.3 x7\n"));
        assert_eq!(
            e,
            RecordError::Parse {
                record: "t".into(),
                line: 6,
                message: "`x7` is not a finite number".into()
            }
        );
        let e = parse_err(&with_line4("NPTS= 2, DT= 0.01", "0.1 NaN\n"));
        assert!(matches!(e, RecordError::Parse { line: 5, .. }), "{e}");
    }

    #[test]
    fn error_count_mismatch_reports_both() {
        let e = parse_err(&with_line4("NPTS= 5, DT= 0.01", "0.1 0.2\n0.3\n"));
        assert_eq!(
            e,
            RecordError::CountMismatch {
                record: "t".into(),
                npts: 5,
                values: 3
            }
        );
        let msg = e.to_string();
        assert!(msg.contains('5') && msg.contains('3'), "{msg}");
        let e = parse_err(&with_line4("NPTS= 1, DT= 0.01", "0.1 0.2\n"));
        assert!(matches!(
            e,
            RecordError::CountMismatch {
                npts: 1,
                values: 2,
                ..
            }
        ));
    }

    #[test]
    fn error_units() {
        let text = "t\ne\nVELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 1, DT= 0.01\n0.1\n";
        assert!(matches!(
            parse_err(text),
            RecordError::Parse { line: 3, .. }
        ));
        let text = "t\ne\nACCELERATION TIME SERIES IN UNITS OF CM/S/S\nNPTS= 1, DT= 0.01\n0.1\n";
        assert!(matches!(
            parse_err(text),
            RecordError::Parse { line: 3, .. }
        ));
    }

    #[test]
    fn read_errors_name_the_path() {
        let path = Path::new("/nonexistent/dir/x.AT2");
        let e = read_at2(path).unwrap_err();
        assert!(matches!(e, RecordError::Io { .. }));
        assert!(e.to_string().contains("/nonexistent/dir/x.AT2"), "{e}");
        assert!(read_record(path, &PlainFormat::default()).is_err());
    }

    #[test]
    fn interpolation_and_zero_outside() {
        let r = Record::new("r", 0.5, vec![0.0, 2.0, -2.0]).unwrap();
        assert_eq!(r.acceleration(-1e-9), 0.0);
        assert_eq!(r.acceleration(0.0), 0.0);
        assert!((r.acceleration(0.25) - 1.0).abs() < 1e-15);
        assert_eq!(r.acceleration(0.5), 2.0);
        assert!((r.acceleration(0.75) - 0.0).abs() < 1e-15);
        assert_eq!(r.acceleration(1.0), -2.0);
        assert_eq!(r.acceleration(1.0 + 1e-9), 0.0);
        assert_eq!(r.acceleration(f64::NAN), 0.0);
        assert_eq!(r.acceleration(f64::INFINITY), 0.0);
        assert_eq!(r.duration(), 1.0);
        let empty = Record {
            name: "e".into(),
            dt: 0.1,
            samples: vec![],
        };
        assert_eq!(empty.acceleration(0.0), 0.0);
        assert_eq!(empty.pga(), 0.0);
    }

    #[test]
    fn record_validation() {
        assert!(matches!(
            Record::new("r", 0.0, vec![1.0]),
            Err(RecordError::InvalidArgument { field: "dt", .. })
        ));
        assert!(matches!(
            Record::new("r", 0.1, vec![1.0, f64::NAN]),
            Err(RecordError::InvalidArgument {
                field: "samples",
                ..
            })
        ));
    }

    #[test]
    fn scaling_to_pga() {
        let r = parse_at2(SAMPLE, "sample").unwrap();
        let s = r.scaled_to_pga(1.5).unwrap();
        assert!((s.pga() - 1.5).abs() < 1e-12);
        assert!((s.samples[0] / r.samples[0] - 1.5 / r.pga()).abs() < 1e-12);
        assert_eq!(s.dt, r.dt);
        assert!((r.scaled(-2.0).pga() - 2.0 * r.pga()).abs() < 1e-12);
        assert!(matches!(
            r.scaled_to_pga(0.0),
            Err(RecordError::InvalidArgument {
                field: "target",
                ..
            })
        ));
        assert!(r.scaled_to_pga(f64::NAN).is_err());
        let zero = Record::new("z", 0.1, vec![0.0; 3]).unwrap();
        assert!(zero.scaled_to_pga(1.0).is_err());
    }

    #[test]
    fn plain_one_column() {
        let text = "# accelerations in g\n0.1\n-0.2\n\n0.05\n";
        let r = parse_plain(text, "p", &PlainFormat::with_dt(0.02).in_g()).unwrap();
        assert_eq!(r.dt, 0.02);
        assert_eq!(r.samples.len(), 3);
        assert!((r.samples[1] + 0.2 * GRAVITY).abs() < 1e-12);
        let e = parse_plain(text, "p", &PlainFormat::default()).unwrap_err();
        assert!(matches!(
            e,
            RecordError::InvalidArgument { field: "dt", .. }
        ));
        let e = parse_plain("0.1\nabc\n", "p", &PlainFormat::with_dt(0.1)).unwrap_err();
        assert!(matches!(e, RecordError::Parse { line: 2, .. }), "{e}");
        let e = parse_plain("0.1\n0.2 0.3\n", "p", &PlainFormat::with_dt(0.1)).unwrap_err();
        assert!(matches!(e, RecordError::Parse { line: 2, .. }), "{e}");
        let e = parse_plain("# only a comment\n", "p", &PlainFormat::with_dt(0.1)).unwrap_err();
        assert!(matches!(e, RecordError::Empty { .. }));
        let e = parse_plain("0.1\n", "p", &PlainFormat::with_dt(-1.0)).unwrap_err();
        assert!(matches!(
            e,
            RecordError::InvalidArgument { field: "dt", .. }
        ));
    }

    #[test]
    fn plain_two_columns() {
        let text = "0.00, 0.0\n0.01, 1.0\n0.02, -1.0\n0.03, 0.5\n";
        let r = parse_plain(text, "p", &PlainFormat::default()).unwrap();
        assert!((r.dt - 0.01).abs() < 1e-15);
        assert_eq!(r.samples, vec![0.0, 1.0, -1.0, 0.5]);
        // Given dt must agree.
        assert!(parse_plain(text, "p", &PlainFormat::with_dt(0.01)).is_ok());
        let e = parse_plain(text, "p", &PlainFormat::with_dt(0.02)).unwrap_err();
        assert!(matches!(
            e,
            RecordError::InvalidArgument { field: "dt", .. }
        ));
        // Uneven spacing: the line is reported.
        let e = parse_plain(
            "0 0\n0.01 1\n0.025 2\n0.03 3\n",
            "p",
            &PlainFormat::default(),
        )
        .unwrap_err();
        assert!(matches!(e, RecordError::Parse { line: 3, .. }), "{e}");
        // Starting at dt: a zero sample in front.
        let r = parse_plain("0.01 1\n0.02 2\n0.03 3\n", "p", &PlainFormat::default()).unwrap();
        assert_eq!(r.samples, vec![0.0, 1.0, 2.0, 3.0]);
        // Starting off the grid or before 0.
        assert!(parse_plain("0.005 1\n0.015 2\n", "p", &PlainFormat::default()).is_err());
        assert!(parse_plain("-0.01 1\n0.0 2\n", "p", &PlainFormat::default()).is_err());
        // Decreasing times.
        assert!(parse_plain("0.02 1\n0.01 2\n", "p", &PlainFormat::default()).is_err());
        // Three columns.
        let e = parse_plain("0 1 2\n", "p", &PlainFormat::default()).unwrap_err();
        assert!(matches!(e, RecordError::Parse { line: 1, .. }), "{e}");
    }

    #[test]
    fn read_record_by_extension() {
        let dir = std::env::temp_dir().join(format!("rocking-records-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let at2 = dir.join("sample.at2");
        std::fs::write(&at2, SAMPLE).unwrap();
        let r = read_record(&at2, &PlainFormat::default()).unwrap();
        assert_eq!((r.name.as_str(), r.samples.len()), ("sample", 7));
        let txt = dir.join("plain.txt");
        std::fs::write(&txt, "0 1\n0.1 2\n").unwrap();
        let r = read_record(&txt, &PlainFormat::default()).unwrap();
        assert_eq!((r.name.as_str(), r.samples.len()), ("plain", 2));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn fortran_format() {
        assert_eq!(fortran_e(-1.607847e-4), "-1.6078470E-04");
        assert_eq!(fortran_e(0.0), "0.0000000E+00");
        assert_eq!(fortran_e(12.5), "1.2500000E+01");
        assert_eq!(fortran_e(1e-100), "1.0000000E-100");
    }

    #[test]
    fn write_then_parse_round_trips() {
        let r = Record::new("w", 0.0024, vec![0.1, -2.0, 0.0, 3.3e-5, 1.0, 0.7]).unwrap();
        let text = write_at2(&r, ["title", "two\nlines"]);
        assert_eq!(text.lines().count(), 4 + 2);
        let back = parse_at2(&text, "w").unwrap();
        assert_eq!(back.dt, r.dt);
        for (a, b) in r.samples.iter().zip(&back.samples) {
            assert!((a - b).abs() <= 1e-7 * a.abs().max(1e-12), "{a} {b}");
        }
        let odd = Record::new("o", 0.001234567891, vec![1.0]).unwrap();
        assert_eq!(
            parse_at2(&write_at2(&odd, ["", ""]), "o").unwrap().dt,
            odd.dt
        );
    }

    #[test]
    fn synthetic_record_properties() {
        let r = synthetic_record(1, 20.0, 0.01, 0.3 * GRAVITY).unwrap();
        assert_eq!(r.samples.len(), 2001);
        assert!((r.pga() - 0.3 * GRAVITY).abs() < 1e-12);
        assert_eq!(r, synthetic_record(1, 20.0, 0.01, 0.3 * GRAVITY).unwrap());
        assert_ne!(
            r.samples,
            synthetic_record(2, 20.0, 0.01, 0.3 * GRAVITY)
                .unwrap()
                .samples
        );
        // Strong phase in the middle, quiet ends.
        let rms = |s: &[f64]| (s.iter().map(|a| a * a).sum::<f64>() / s.len() as f64).sqrt();
        assert!(rms(&r.samples[500..1000]) > 3.0 * rms(&r.samples[1900..]));
        assert!(synthetic_record(1, 0.0, 0.01, 1.0).is_err());
        assert!(synthetic_record(1, 1.0, f64::NAN, 1.0).is_err());
        assert!(synthetic_record(1, 1.0, 0.01, -1.0).is_err());
    }

    fn bundled_path() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/records/synthetic.AT2")
    }

    #[test]
    fn bundled_record_is_what_the_generator_writes() {
        let text = std::fs::read_to_string(bundled_path()).unwrap();
        assert!(
            text == bundled_synthetic_at2().unwrap(),
            "examples/records/synthetic.AT2 differs from records::bundled_synthetic_at2(); \
             regenerate with `cargo test --lib -- --ignored regenerate_synthetic_record`"
        );
        assert!(text.len() < 60_000);
        let r = read_record(&bundled_path(), &PlainFormat::default()).unwrap();
        assert_eq!(r.samples.len(), 2001);
        assert_eq!(r.dt, SYNTHETIC_DT);
        assert!((r.pga() / GRAVITY - SYNTHETIC_PGA_G).abs() < 1e-7);
        assert!(text.lines().next().unwrap().contains("SYNTHETIC"));
    }

    /// Rewrites `examples/records/synthetic.AT2` (run with `--ignored`).
    #[test]
    #[ignore]
    fn regenerate_synthetic_record() {
        let path = bundled_path();
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, bundled_synthetic_at2().unwrap()).unwrap();
    }

    /// The 100 FEMA P695 records of the shared data directory (skipped when it is absent). Each
    /// must parse and agree with `index.csv` (dt, npts, PGA to the printed 4 decimals).
    #[test]
    fn shared_fema_p695_records_parse() {
        // `../shared` beside the checkout (as on the developers' machines and in CI), or
        // $ROCKING_SHARED.
        let shared = std::env::var_os("ROCKING_SHARED")
            .map(std::path::PathBuf::from)
            .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared"));
        let root = shared.join("records/fema-p695");
        let root = root.as_path();
        let index = match std::fs::read_to_string(root.join("index.csv")) {
            Ok(text) => text,
            Err(_) => {
                println!("skipped: {} is absent", root.display());
                return;
            }
        };
        let mut parsed = 0;
        for (k, row) in index.lines().enumerate().skip(1) {
            let fields: Vec<&str> = row.split(',').collect();
            let n = fields.len();
            assert!(n >= 12, "index.csv line {}: {row}", k + 1);
            let (file, dt, npts, pga) =
                (fields[n - 4], fields[n - 3], fields[n - 2], fields[n - 1]);
            let r = read_record(&root.join(file), &PlainFormat::default())
                .unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(r.dt, dt.parse::<f64>().unwrap(), "{file}");
            assert_eq!(r.samples.len(), npts.parse::<usize>().unwrap(), "{file}");
            let pga_g = r.pga() / GRAVITY;
            assert!(
                (pga_g - pga.parse::<f64>().unwrap()).abs() <= 0.5e-4 + 1e-9,
                "{file}: PGA {pga_g} g, index says {pga}"
            );
            parsed += 1;
        }
        assert_eq!(parsed, 100);
        println!("{parsed} FEMA P695 records parsed");
    }
}
