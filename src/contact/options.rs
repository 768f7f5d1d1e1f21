//! Options of a drum-column run ([`super::simulation`]): the time step and duration, friction
//! (one μ or one per joint), what sliding and tensile joints do, the scheme's options, what a run
//! keeps, initial angles; and their validation, whose errors name the field.

use std::fmt;

use super::moreau::SchemeOptions;
use crate::model::column::Column;

/// What a sliding joint does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum OnSliding {
    /// Stop the run at the first slip (the thesis's driver; its default).
    #[default]
    Stop,
    /// Let the joint slide (Coulomb).
    Slide,
}

/// What a joint whose normal force would turn tensile does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum OnTension {
    /// Stop the run at the first lift-off (the thesis's driver; its default).
    #[default]
    Stop,
    /// The part above lifts off and flies until it lands.
    Fly,
}

/// What a run keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DrumRecording {
    /// Keep the state every `k` steps (plus the start and the end); `None`: no history.
    pub history_every: Option<usize>,
    /// Keep the events.
    pub events: bool,
}

impl Default for DrumRecording {
    fn default() -> DrumRecording {
        DrumRecording {
            history_every: None,
            events: true,
        }
    }
}

/// Options of a drum-column run.
#[derive(Clone, Debug, PartialEq)]
pub struct DrumOptions {
    /// Time step (s).
    pub dt: f64,
    /// Simulated duration (s).
    pub duration: f64,
    /// Coulomb coefficient μ of every joint (`f64::INFINITY`: no sliding).
    pub friction: f64,
    /// μ per joint, overriding `friction` (length `n`).
    pub joint_friction: Option<Vec<f64>>,
    /// Sliding joints: stop or slide.
    pub on_sliding: OnSliding,
    /// Tensile joints: stop or fly.
    pub on_tension: OnTension,
    /// The scheme (θ, consecutive impacts, impact location, gravity).
    pub scheme: SchemeOptions,
    /// Do not stop at static tipping; stop when a drum has rotated by `π/2`.
    pub continue_until_fallen: bool,
    /// What to keep.
    pub record: DrumRecording,
    /// Initial interface angles (thesis convention: negative about the right corner), at rest.
    pub initial_angles: Option<Vec<f64>>,
}

impl Default for DrumOptions {
    fn default() -> DrumOptions {
        DrumOptions {
            dt: 1e-3,
            duration: 10.0,
            friction: 0.7,
            joint_friction: None,
            on_sliding: OnSliding::Slide,
            on_tension: OnTension::Fly,
            scheme: SchemeOptions::default(),
            continue_until_fallen: false,
            record: DrumRecording::default(),
            initial_angles: None,
        }
    }
}

/// Why options were refused.
#[derive(Clone, Debug, PartialEq)]
pub struct DrumOptionError {
    /// The field.
    pub field: &'static str,
    /// The value, printed.
    pub value: String,
    /// The rule it breaks.
    pub rule: &'static str,
}

impl fmt::Display for DrumOptionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {}: {}", self.field, self.value, self.rule)
    }
}

impl std::error::Error for DrumOptionError {}

fn bad(field: &'static str, value: impl fmt::Debug, rule: &'static str) -> DrumOptionError {
    DrumOptionError {
        field,
        value: format!("{value:?}"),
        rule,
    }
}

impl DrumOptions {
    /// The options of a quiet run (nothing kept: no history, no events) of `duration` seconds at
    /// `dt` = 1 ms, friction `mu` at every joint, sliding and flight allowed, `n_impacts`
    /// consecutive impacts: what the drum benchmarks and tests run.
    pub fn quiet(duration: f64, mu: f64, n_impacts: u32) -> DrumOptions {
        let mut options = DrumOptions {
            dt: 1e-3,
            duration,
            friction: mu,
            record: DrumRecording {
                history_every: None,
                events: false,
            },
            ..DrumOptions::default()
        };
        options.scheme.n_impacts = n_impacts;
        options
    }

    /// Checks every field; the error names it.
    pub fn validate(&self, column: &Column) -> Result<(), DrumOptionError> {
        let n = column.n_interfaces();
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(bad("dt", self.dt, "must be finite and > 0"));
        }
        if !(self.duration.is_finite() && self.duration >= 0.0) {
            return Err(bad("duration", self.duration, "must be finite and >= 0"));
        }
        if crate::validate::too_many_steps(self.duration, self.dt) {
            return Err(bad("dt", self.dt, "more than 1e10 steps for the duration"));
        }
        if self.friction.is_nan() || self.friction <= 0.0 {
            return Err(bad(
                "friction",
                self.friction,
                "must be > 0 (infinity: no sliding)",
            ));
        }
        if let Some(mu) = &self.joint_friction {
            if mu.len() != n {
                return Err(bad("joint_friction", mu, "needs one value per joint"));
            }
            if mu.iter().any(|m| m.is_nan() || *m <= 0.0) {
                return Err(bad("joint_friction", mu, "every value must be > 0"));
            }
        }
        let s = &self.scheme;
        if !(s.theta.is_finite() && (0.5..=1.0).contains(&s.theta)) {
            return Err(bad("scheme.theta", s.theta, "must be in [0.5, 1]"));
        }
        if s.n_impacts == 0 || s.n_impacts > 100 {
            return Err(bad("scheme.n_impacts", s.n_impacts, "must be in 1..=100"));
        }
        if !(s.gravity.is_finite() && s.gravity > 0.0) {
            return Err(bad("scheme.gravity", s.gravity, "must be finite and > 0"));
        }
        if let Some(tol) = s.energy_tolerance {
            if !(tol.is_finite() && tol > 0.0) {
                return Err(bad(
                    "scheme.energy_tolerance",
                    tol,
                    "must be finite and > 0",
                ));
            }
        }
        if self.record.history_every == Some(0) {
            return Err(bad("record.history_every", 0, "must be >= 1"));
        }
        if let Some(a) = &self.initial_angles {
            if a.len() != n {
                return Err(bad("initial_angles", a, "needs one angle per interface"));
            }
            if a.iter()
                .any(|x| !(x.is_finite() && x.abs() < 0.5 * std::f64::consts::PI))
            {
                return Err(bad(
                    "initial_angles",
                    a,
                    "angles must be finite, |angle| < π/2",
                ));
            }
        }
        Ok(())
    }

    pub(super) fn mu(&self, n: usize) -> Vec<f64> {
        match &self.joint_friction {
            Some(m) => m.clone(),
            None => vec![self.friction; n],
        }
    }
}
