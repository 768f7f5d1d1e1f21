//! Ground accelerations `a_g(t)` \[m/s²\] that drive a column: none, a pulse, or a record.
//!
//! Positive `a_g` = the ground accelerates to +x (to the right); the inertial force on block `j`
//! is then `−m_j a_g` (SPEC §1). Every excitation starts at `t = 0`, is zero before it and after
//! [`Excitation::end_time`].
//!
//! The pulses are the simple signals of thesis Fig. 6 and the shapes of its overturning curves
//! (Fig. 8: half sine, full sine, three half sines), plus the Ricker wavelet and the
//! Mavroeidis & Papageorgiou (2003) near-fault pulse. Records are [`Record`]s (PEER `.AT2` or
//! plain text, see [`crate::ground::records`]).
//!
//! [`Excitation::acceleration`] is called at every time step: it is O(1) and allocation-free for
//! every kind (the Mavroeidis–Papageorgiou normalisation is computed once per `(γ, ν)` and
//! cached, see [`Pulse::MavroeidisPapageorgiou`]).

mod mavroeidis_papageorgiou;
mod pulse;

pub use pulse::Pulse;

use crate::ground::records::{Record, RecordError};
use crate::model::column::GRAVITY;
use crate::validate::InvalidValue;

/// Ground acceleration of a time history.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Excitation {
    /// No ground motion (free rocking from initial conditions).
    #[default]
    None,
    /// A pulse.
    Pulse(Pulse),
    /// A recorded (or synthetic) ground motion.
    Record(Record),
}

/// An invalid pulse or record parameter.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExcitationError {
    /// A pulse parameter (`amplitude`, `half_period`, `lobes`, `duration`, `frequency`, `gamma`,
    /// `nu`) is out of range.
    #[error("{pulse} pulse: {invalid}")]
    InvalidParameter {
        /// Pulse kind (`"half sines"`, `"rectangular"`, …).
        pulse: &'static str,
        /// The field, its value and the rule it breaks.
        invalid: InvalidValue,
    },
    /// The record is invalid.
    #[error("record: {0}")]
    Record(#[from] RecordError),
}

/// Largest `γ` accepted for the Mavroeidis–Papageorgiou pulse.
pub const MP_GAMMA_MAX: f64 = 100.0;

/// Up to 6 significant digits, without trailing zeros.
fn fmt_num(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (5 - x.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{x:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

impl Excitation {
    /// A checked pulse excitation.
    pub fn pulse(pulse: Pulse) -> Result<Excitation, ExcitationError> {
        pulse.validate()?;
        Ok(Excitation::Pulse(pulse))
    }

    /// A checked record excitation (`dt` finite and positive, every sample finite).
    pub fn record(record: Record) -> Result<Excitation, ExcitationError> {
        record.validate()?;
        Ok(Excitation::Record(record))
    }

    /// Checks the pulse or record.
    pub fn validate(&self) -> Result<(), ExcitationError> {
        match self {
            Excitation::None => Ok(()),
            Excitation::Pulse(p) => p.validate(),
            Excitation::Record(r) => Ok(r.validate()?),
        }
    }

    /// Ground acceleration at `t` \[m/s²\]; zero before 0, after [`Excitation::end_time`] and for
    /// NaN `t`. O(1), allocation-free.
    #[inline]
    pub fn acceleration(&self, t: f64) -> f64 {
        match self {
            Excitation::None => 0.0,
            Excitation::Pulse(p) => p.acceleration(t),
            Excitation::Record(r) => r.acceleration(t),
        }
    }

    /// Time after which `a_g` is identically zero \[s\] (0 for `None`; the last sample's time for a
    /// record).
    pub fn end_time(&self) -> f64 {
        match self {
            Excitation::None => 0.0,
            Excitation::Pulse(p) => p.end_time(),
            Excitation::Record(r) => r.duration(),
        }
    }

    /// `max |a_g|` \[m/s²\]: `|amplitude|` for a pulse, the PGA for a record, 0 for `None`.
    pub fn peak(&self) -> f64 {
        match self {
            Excitation::None => 0.0,
            Excitation::Pulse(p) => p.amplitude().abs(),
            Excitation::Record(r) => r.pga(),
        }
    }

    /// The excitation with every acceleration multiplied by `factor` (time axis unchanged).
    pub fn scaled(&self, factor: f64) -> Excitation {
        match self {
            Excitation::None => Excitation::None,
            Excitation::Pulse(p) => Excitation::Pulse(p.scaled(factor)),
            Excitation::Record(r) => Excitation::Record(r.scaled(factor)),
        }
    }

    /// One line for logs and plots.
    pub fn describe(&self) -> String {
        match self {
            Excitation::None => "no ground motion".to_string(),
            Excitation::Pulse(p) => p.describe(),
            Excitation::Record(r) => {
                let pga = r.pga();
                format!(
                    "record {}: {} samples, dt = {} s, duration = {} s, PGA = {} m/s² ({:.3} g)",
                    r.name,
                    r.samples.len(),
                    fmt_num(r.dt),
                    fmt_num(r.duration()),
                    fmt_num(pga),
                    pga / GRAVITY
                )
            }
        }
    }
}

/// The driver's view of an excitation (the same `a_g(t)` and end time).
impl crate::ground::GroundMotion for Excitation {
    fn acceleration(&self, t: f64) -> f64 {
        Excitation::acceleration(self, t)
    }
    fn end_time(&self) -> f64 {
        Excitation::end_time(self)
    }
}

impl From<Pulse> for Excitation {
    fn from(p: Pulse) -> Excitation {
        Excitation::Pulse(p)
    }
}

impl From<Record> for Excitation {
    fn from(r: Record) -> Excitation {
        Excitation::Record(r)
    }
}

#[cfg(test)]
mod tests;
