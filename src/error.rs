//! One table of status codes and their messages (the SUNDIALS / LAPACK convention): negative for a
//! bad call, positive when the call is valid but cannot be solved as asked, zero for success.

use std::fmt;

macro_rules! codes {
    ($( $(#[$doc:meta])* $name:ident = $code:expr, $msg:expr; )*) => {
        /// Every way a model call can fail. The discriminant is the C status code.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(i32)]
        pub enum ErrorKind {
            $( $(#[$doc])* $name = $code, )*
        }

        impl ErrorKind {
            /// All kinds, for tests and documentation.
            pub const ALL: &'static [ErrorKind] = &[$(ErrorKind::$name,)*];

            /// The C status code.
            pub fn code(self) -> i32 {
                self as i32
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
    };
}

codes! {
    /// A required pointer argument was NULL.
    NullPointer = -1, "a required pointer argument is NULL";
    /// `n_interfaces` is zero, too large, or a size computed from it overflows.
    InvalidSize = -2, "invalid size: n is zero, above the supported maximum, a size overflows, or a pointer is misaligned";
    /// An input holds NaN or infinity.
    NotFinite = -3, "an input value is NaN or infinite";
    /// The mass matrix is not symmetric.
    NotSymmetric = -4, "the mass matrix is not symmetric";
    /// A status value is outside −1..1.
    InvalidStatus = -5, "a status value is outside -1..1";
    /// The closing interface is out of range or not open.
    InvalidClosingInterface = -6, "the closing interface is out of range or not open";
    /// A velocity is non-zero on a DOF that is not open.
    VelocityOnClosedDof = -7, "a velocity is non-zero on a DOF that is not open";
    /// The options are invalid (n_impacts = 0, unknown solver, tolerance not in (0, 1)).
    InvalidOptions = -8, "invalid options: n_impacts must be >= 1, solver 0..2, tolerance finite in (0, 0.01]";
    /// The state is inconsistent (the closing interface moves away from closure).
    InconsistentState = -9, "inconsistent state: the closing interface is not moving towards closure";
    /// Geometry or mass data of a column is invalid (non-positive width, height or mass...).
    InvalidGeometry = -10, "invalid column geometry: sizes, masses and inertias must be finite and positive";
    /// A DOF angle is on the inadmissible side or both DOFs of an interface are non-zero.
    InvalidAngles = -11, "invalid angles: a DOF has the inadmissible sign or both DOFs of an interface are non-zero";
    /// The mass matrix (or a sub-matrix the model needs) is not positive definite.
    NotPositiveDefinite = 1, "the mass matrix (or a sub-matrix the model needs) is not positive definite";
    /// Exhaustive enumeration was asked for more closed interfaces than the limit allows.
    EnumerationTooLarge = 2, "enumeration refused: more closed interfaces than the enumeration limit (use the projection solver)";
    /// The projection solver did not converge within its iteration limit.
    SolverDidNotConverge = 3, "the projection solver did not converge within its iteration limit";
    /// The inputs are finite but so large that the result overflows.
    Overflow = 4, "the result is not finite: the inputs are too large for double precision";
    /// An internal error (a bug): a panic was caught at the boundary.
    Internal = 99, "internal error (a panic was caught at the library boundary); please report it";
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
        }
        assert_eq!(ErrorKind::from_code(0), None);
    }
}
