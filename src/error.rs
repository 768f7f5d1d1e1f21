//! One table of status codes (the SUNDIALS / LAPACK convention): zero for success, negative for a
//! bad call, positive when the call is valid but cannot be solved as asked. Each row gives the
//! [`ErrorKind`] variant, its C code and name, its documentation and its static message. From this
//! table come the enum, [`codes`] (the `ROCKING_*` constants of the C ABI), the texts of
//! `rocking_error_message`, and — through `build.rs`, which compiles this file as a module of its
//! own — the status-code block of `include/rocking.h` with the same documentation.
//!
//! Because `build.rs` compiles it, this file uses nothing but `std`: no `crate::` paths, no
//! dependencies.

use std::fmt;

macro_rules! status_table {
    (
        $(#[doc = $ok_doc:literal])* $ok_c:ident = 0, $ok_msg:literal;
        $( $(#[doc = $doc:literal])* $name:ident = $code:literal, $c_name:ident, $msg:literal; )*
    ) => {
        /// Every way a model call can fail. The discriminant is the C status code.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(i32)]
        pub enum ErrorKind {
            $( $(#[doc = $doc])* $name = $code, )*
        }

        /// The status codes of the C ABI (`ROCKING_OK`, `ROCKING_ERR_*`), as the header defines
        /// them.
        pub mod codes {
            $(#[doc = $ok_doc])*
            pub const $ok_c: i32 = 0;
            $( $(#[doc = $doc])* pub const $c_name: i32 = $code; )*
        }

        /// Name, documentation and message of success, the row of code 0 (for the header).
        pub const SUCCESS: (&str, &str, &str) =
            (stringify!($ok_c), concat!($($ok_doc, "\n"),*), $ok_msg);

        impl ErrorKind {
            /// All kinds, in the order of the table.
            pub const ALL: &'static [ErrorKind] = &[$(ErrorKind::$name,)*];

            /// The C status code.
            pub fn code(self) -> i32 {
                self as i32
            }

            /// The name of the code in the C header, e.g. `ROCKING_ERR_NULL_POINTER`.
            pub fn c_name(self) -> &'static str {
                match self { $( ErrorKind::$name => stringify!($c_name), )* }
            }

            /// The documentation of the code (one line per doc-comment line of the table).
            pub fn doc(self) -> &'static str {
                match self { $( ErrorKind::$name => concat!($($doc, "\n"),*), )* }
            }

            /// Static message of the code.
            pub fn message(self) -> &'static str {
                let c = self.c_message();
                &c[..c.len() - 1]
            }

            /// Static message of the code, NUL-terminated for C.
            pub fn c_message(self) -> &'static str {
                match self { $( ErrorKind::$name => concat!($msg, "\0"), )* }
            }

            /// The kind with this code, if any.
            pub fn from_code(code: i32) -> Option<ErrorKind> {
                match code { $( $code => Some(ErrorKind::$name), )* _ => None }
            }
        }

        /// Static message of success, NUL-terminated for C.
        pub const SUCCESS_C_MESSAGE: &str = concat!($ok_msg, "\0");
    };
}

status_table! {
    /// Success: every output was written.
    ROCKING_OK = 0, "success";

    /// A required pointer argument is NULL.
    NullPointer = -1, ROCKING_ERR_NULL_POINTER, "a required pointer argument is NULL";
    /// A size is zero or above its maximum (`ROCKING_MAX_INTERFACES` interfaces), a size computed
    /// from it overflows, or a pointer is not aligned for its type.
    InvalidSize = -2, ROCKING_ERR_INVALID_SIZE, "invalid size: n is zero, above the supported maximum, a size overflows, or a pointer is misaligned";
    /// An input value is NaN or infinite.
    NotFinite = -3, ROCKING_ERR_NOT_FINITE, "an input value is NaN or infinite";
    /// The mass matrix is not symmetric (entry-wise relative 1e-9).
    NotSymmetric = -4, ROCKING_ERR_NOT_SYMMETRIC, "the mass matrix is not symmetric";
    /// A status value is outside -1..1.
    InvalidStatus = -5, ROCKING_ERR_INVALID_STATUS, "a status value is outside -1..1";
    /// The closing interface is out of range or not open.
    InvalidClosingInterface = -6, ROCKING_ERR_INVALID_CLOSING_INTERFACE, "the closing interface is out of range or not open";
    /// A velocity is non-zero on a DOF that is not open.
    VelocityOnClosedDof = -7, ROCKING_ERR_VELOCITY_ON_CLOSED_DOF, "a velocity is non-zero on a DOF that is not open";
    /// Invalid options: n_impacts not in 1..=10000, solver not one of `ROCKING_SOLVER_*`, or
    /// tolerance not a finite value in (0, 0.01].
    InvalidOptions = -8, ROCKING_ERR_INVALID_OPTIONS, "invalid options: n_impacts must be >= 1, solver 0..2, tolerance finite in (0, 0.01]";
    /// Inconsistent state: the closing interface is moving away from closure, or (the
    /// constrained models) the open DOFs cannot satisfy the constraints.
    InconsistentState = -9, ROCKING_ERR_INCONSISTENT_STATE, "inconsistent state: the closing interface is moving away from closure, or the open DOFs cannot satisfy the constraints";
    /// Invalid geometry: a size, mass, inertia, contact width or gravity that is not finite and
    /// positive, or bodies that do not fit together (a contact wider than the blocks it joins,
    /// an arch too thick for its radius, a beam shorter than the span).
    InvalidGeometry = -10, ROCKING_ERR_INVALID_GEOMETRY, "invalid geometry: sizes, masses, inertias and gravity must be finite and positive, and the bodies must fit together";
    /// A DOF angle has the inadmissible sign, or both DOFs of an interface are non-zero.
    InvalidAngles = -11, ROCKING_ERR_INVALID_ANGLES, "invalid angles: a DOF has the inadmissible sign or both DOFs of an interface are non-zero";
    /// The mass matrix (or a sub-matrix the model needs) is not positive definite.
    NotPositiveDefinite = 1, ROCKING_ERR_NOT_POSITIVE_DEFINITE, "the mass matrix (or a sub-matrix the model needs) is not positive definite";
    /// Enumeration refused: more closed interfaces than its limit (12); use the projection solver.
    EnumerationTooLarge = 2, ROCKING_ERR_ENUMERATION_TOO_LARGE, "enumeration refused: more closed interfaces than the enumeration limit (use the projection solver)";
    /// The projection solver did not converge within its iteration limit.
    SolverDidNotConverge = 3, ROCKING_ERR_SOLVER_DID_NOT_CONVERGE, "the projection solver did not converge within its iteration limit";
    /// The inputs are finite but so large that the result overflows.
    Overflow = 4, ROCKING_ERR_OVERFLOW, "the result is not finite: the inputs are too large for double precision";
    /// Internal error: a panic was caught at the library boundary (a bug; please report it).
    Internal = 99, ROCKING_ERR_INTERNAL, "internal error (a panic was caught at the library boundary); please report it";
}

/// A failed model call: the kind (its code) and a detailed message.
#[derive(Clone, Debug, PartialEq)]
pub struct RockingError {
    /// The kind, whose discriminant is the C status code.
    pub kind: ErrorKind,
    /// What exactly was wrong (the field, index and value where that applies).
    pub detail: String,
}

impl RockingError {
    /// A new error with detail text.
    pub fn new(kind: ErrorKind, detail: impl Into<String>) -> RockingError {
        RockingError {
            kind,
            detail: detail.into(),
        }
    }

    /// The C status code.
    pub fn code(&self) -> i32 {
        self.kind.code()
    }
}

impl fmt::Display for RockingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.kind.message(), self.detail)
    }
}

impl std::error::Error for RockingError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_round_trip() {
        let mut seen = std::collections::HashSet::new();
        for k in ErrorKind::ALL {
            assert!(seen.insert(k.code()), "duplicate code {}", k.code());
            assert_eq!(ErrorKind::from_code(k.code()), Some(*k));
            assert!(!k.message().is_empty());
            assert!(!k.doc().is_empty());
        }
        assert_eq!(ErrorKind::from_code(0), None);
        assert_eq!(codes::ROCKING_OK, 0);
        assert_eq!(SUCCESS.0, "ROCKING_OK");
    }

    /// The C name is the variant's name in SCREAMING_SNAKE_CASE after `ROCKING_ERR_`, so a row
    /// cannot pair a variant with another code's name.
    #[test]
    fn c_names_follow_the_variants() {
        for k in ErrorKind::ALL {
            let mut snake = String::new();
            for (i, ch) in format!("{k:?}").chars().enumerate() {
                if ch.is_ascii_uppercase() && i > 0 {
                    snake.push('_');
                }
                snake.push(ch.to_ascii_uppercase());
            }
            assert_eq!(k.c_name(), format!("ROCKING_ERR_{snake}"));
        }
    }

    /// The documentation of `InvalidOptions` states the range that `ModelOptions::validate`
    /// checks, (0, 0.01] (it once said (0, 1)).
    #[test]
    fn invalid_options_documents_the_checked_tolerance_range() {
        assert!(ErrorKind::InvalidOptions.doc().contains("(0, 0.01]"));
        assert!(ErrorKind::InvalidOptions.message().contains("(0, 0.01]"));
        let with = |tolerance| crate::ModelOptions {
            tolerance,
            ..crate::ModelOptions::default()
        };
        assert!(with(0.01).validate().is_ok());
        assert!(with(1e-300).validate().is_ok());
        for bad in [0.0, 0.010000001, 0.5, f64::NAN] {
            assert_eq!(
                with(bad).validate().unwrap_err().kind,
                ErrorKind::InvalidOptions
            );
        }
    }
}
