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

mod at2;
mod plain;
mod record;
mod synthetic;

use std::path::{Path, PathBuf};

pub use at2::{parse_at2, read_at2, write_at2};
pub use plain::{parse_plain, PlainFormat};
pub use record::Record;
#[cfg(test)]
pub(crate) use synthetic::bundled_record;
pub use synthetic::{
    bundled_synthetic_at2, synthetic_record, SYNTHETIC_DT, SYNTHETIC_DURATION, SYNTHETIC_OMEGA_F,
    SYNTHETIC_OMEGA_G, SYNTHETIC_PGA_G, SYNTHETIC_SEED, SYNTHETIC_ZETA_F, SYNTHETIC_ZETA_G,
};

use crate::model::column::GRAVITY;
use crate::validate::InvalidValue;

/// Why a record could not be read, parsed or built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RecordError {
    /// The file could not be read.
    #[error("{}: {message}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// The text holds no data at all.
    #[error("{record}: empty file, no data")]
    Empty {
        /// Record name (file stem or the name passed to the parser).
        record: String,
    },
    /// A line is malformed: truncated or incomplete header, missing `NPTS` or `DT`, a bad `DT`, a
    /// value that is not a finite number, uneven time spacing...
    #[error("{record}, line {line}: {message}")]
    Parse {
        /// Record name.
        record: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong, quoting the offending text.
        message: String,
    },
    /// The header's `NPTS` disagrees with the number of values that follow it.
    #[error("{record}: header says NPTS = {npts} but the file holds {values} values")]
    CountMismatch {
        /// Record name.
        record: String,
        /// `NPTS` of the header.
        npts: usize,
        /// Number of values in the file.
        values: usize,
    },
    /// A number (an argument or a field of a [`Record`]) is out of its range.
    #[error("{0}")]
    Invalid(#[from] InvalidValue),
    /// An argument is missing or disagrees with the data (a one-column file without a time
    /// step, a given time step that the time column contradicts, a record that cannot be
    /// scaled, ...).
    #[error("{field}: {message}")]
    InvalidArgument {
        /// Argument or field name.
        field: &'static str,
        /// What is wrong with it.
        message: String,
    },
}

fn invalid(field: &'static str, message: String) -> RecordError {
    RecordError::InvalidArgument { field, message }
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

/// The file's text, without the UTF-8 byte-order mark that Windows editors and spreadsheets
/// write first (it was read as part of the first number).
fn read_text(path: &Path) -> Result<String, RecordError> {
    let text = std::fs::read_to_string(path).map_err(|e| RecordError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    Ok(match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_string(),
        None => text,
    })
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

/// Whether [`read_record`] reads `path` as a PEER `.AT2` file (in g, with its own step): by its
/// extension, in any case. Callers that take units or a step for a record refuse them for one.
pub fn is_at2(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case("at2"))
}

/// The factor to m/s² of the units a plain-text record is given in, as scenes and Python's
/// `read_record` name them: `"m/s2"` (or `"m/s^2"`) 1, `"g"` [`GRAVITY`], `"cm/s2"` (`"cm/s^2"`,
/// `"gal"`) 0.01; `None` for any other name.
pub fn units_scale(units: &str) -> Option<f64> {
    match units {
        "m/s2" | "m/s^2" => Some(1.0),
        "g" => Some(GRAVITY),
        "cm/s2" | "cm/s^2" | "gal" => Some(0.01),
        _ => None,
    }
}

/// Reads a record by extension: `.AT2`/`.at2` (any case) as PEER AT2 ([`parse_at2`], `format` is
/// not used), anything else as plain text ([`parse_plain`] with `format`). The record is named
/// after the file stem.
pub fn read_record(path: &Path, format: &PlainFormat) -> Result<Record, RecordError> {
    if is_at2(path) {
        read_at2(path)
    } else {
        let text = read_text(path)?;
        parse_plain(&text, &stem(path), format)
    }
}

#[cfg(test)]
mod tests;
