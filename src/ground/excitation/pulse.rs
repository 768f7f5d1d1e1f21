//! Pulse-type ground accelerations: the simple signals of thesis Fig. 6, the half-sine family of
//! its overturning curves (Fig. 8), the Ricker wavelet and the Mavroeidis & Papageorgiou (2003)
//! near-fault pulse.

use std::f64::consts::PI;

use super::mavroeidis_papageorgiou::{mp_peak_cached, mp_shape};
use super::{fmt_num, ExcitationError, MP_GAMMA_MAX};
use crate::model::column::GRAVITY;
use crate::validate::{finite, positive, InvalidValue};

/// A pulse-type ground acceleration. Every amplitude is in m/s² and may be negative (the pulse
/// then starts towards −x); durations are in seconds. Build with the checked constructors
/// ([`Pulse::half_sine`], …) or check a literal with [`Pulse::validate`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pulse {
    /// `lobes` consecutive half sines of alternating sign,
    /// `a(t) = A sin(π t / t_p)` for `0 ≤ t ≤ lobes·t_p`, `t_p` = duration of each half sine.
    /// `lobes = 1` is the half sine (thesis Fig. 6a, Fig. 8a; Housner 1963), `2` the full sine
    /// (one period, thesis Fig. 8b), `3` the three half sines (+, −, +) of thesis Fig. 8c.
    HalfSines {
        /// Peak acceleration `a_p` of every lobe \[m/s²\].
        amplitude: f64,
        /// Duration `t_p` of one half sine \[s\].
        half_period: f64,
        /// Number of half sines, ≥ 1.
        lobes: u32,
    },
    /// Single rectangular pulse (thesis Fig. 6; Housner 1963): `a = A` for `0 ≤ t < duration`.
    Rectangular {
        /// Acceleration \[m/s²\].
        amplitude: f64,
        /// Duration \[s\].
        duration: f64,
    },
    /// Symmetric single-lobe triangular pulse (thesis Fig. 6; Voyagaki et al. 2013a):
    /// `a(t) = A (1 − |2t/d − 1|)` for `0 ≤ t ≤ d`, peak `A` at `d/2`.
    Triangular {
        /// Peak acceleration \[m/s²\].
        amplitude: f64,
        /// Duration `d` \[s\].
        duration: f64,
    },
    /// Ricker wavelet ("Mexican hat") of peak frequency `f`:
    /// `a(t) = A (1 − 2π² f² τ²) exp(−π² f² τ²)`, `τ = t − t₀`, `t₀ = 3√2 / (π f)` (≈ 1.35/f),
    /// truncated to `0 ≤ t ≤ 2 t₀`. The peak `A` is at `t₀`, two side lobes of `−0.446 A` at
    /// `t₀ ± √6/(2π f)`; at the ends `π f τ = ±3√2`, so `|a| = 35 e^{−18} |A| ≈ 5·10⁻⁷ |A|`:
    /// the truncation steps are negligible and the velocity returns to ≈ 0.
    Ricker {
        /// Peak acceleration (at `t₀`) \[m/s²\].
        amplitude: f64,
        /// Peak (dominant) frequency `f` \[Hz\].
        frequency: f64,
    },
    /// Mavroeidis & Papageorgiou (2003, BSSA 93(3), Eq. 1–2) near-fault pulse. Velocity
    /// `v(t) = ½ [1 + cos(2π f_p τ / γ)] cos(2π f_p τ + ν)` for `|τ| ≤ γ / (2 f_p)` (up to a
    /// factor); acceleration, differentiated analytically,
    /// `a(t) ∝ −[sin(2π f_p τ/γ) cos(2π f_p τ + ν) + γ sin(2π f_p τ + ν)(1 + cos(2π f_p τ/γ))]`,
    /// scaled so that `max |a| = |amplitude|` and shifted so that the pulse starts at `t = 0`:
    /// `τ = t − γ / (2 f_p)`, support `0 ≤ t ≤ γ / f_p`. `a` is zero at both ends and its
    /// integral is zero (the velocity pulse starts and ends at rest); for `ν = 0` the velocity
    /// peak is positive when `amplitude > 0`.
    ///
    /// The normalisation `max |a|` has no closed form; it is found by dense sampling and a
    /// golden-section refinement (relative accuracy ~1e-12) and cached per thread for the last
    /// `(γ, ν)`, so [`Excitation::acceleration`] stays O(1) in a time-stepping loop.
    ///
    /// [`Excitation::acceleration`]: super::Excitation::acceleration
    MavroeidisPapageorgiou {
        /// Peak `|acceleration|` \[m/s²\] (the sign flips the pulse).
        amplitude: f64,
        /// Pulse frequency `f_p` \[Hz\] (`1 / T_p`).
        frequency: f64,
        /// Oscillatory character `γ`, `1 < γ ≤ 100` (M&P: the pulse is an envelope of `γ`
        /// cycles; typically 1.5–3).
        gamma: f64,
        /// Phase `ν` \[rad\].
        nu: f64,
    },
}

/// Ricker wavelet: `π f t₀`, half the truncated support in units of `1/(π f)`.
pub(super) const RICKER_HALF_WIDTH: f64 = 3.0 * std::f64::consts::SQRT_2;

impl Pulse {
    /// Checked [`Pulse::HalfSines`].
    pub fn half_sines(
        amplitude: f64,
        half_period: f64,
        lobes: u32,
    ) -> Result<Pulse, ExcitationError> {
        Pulse::HalfSines {
            amplitude,
            half_period,
            lobes,
        }
        .checked()
    }

    /// Half sine (thesis Fig. 8a): `A sin(π t / t_p)` on `[0, t_p]`.
    pub fn half_sine(amplitude: f64, half_period: f64) -> Result<Pulse, ExcitationError> {
        Pulse::half_sines(amplitude, half_period, 1)
    }

    /// Full sine (thesis Fig. 8b): one period, `t_p` = duration of each half.
    pub fn full_sine(amplitude: f64, half_period: f64) -> Result<Pulse, ExcitationError> {
        Pulse::half_sines(amplitude, half_period, 2)
    }

    /// Checked [`Pulse::Rectangular`].
    pub fn rectangular(amplitude: f64, duration: f64) -> Result<Pulse, ExcitationError> {
        Pulse::Rectangular {
            amplitude,
            duration,
        }
        .checked()
    }

    /// Checked [`Pulse::Triangular`].
    pub fn triangular(amplitude: f64, duration: f64) -> Result<Pulse, ExcitationError> {
        Pulse::Triangular {
            amplitude,
            duration,
        }
        .checked()
    }

    /// Checked [`Pulse::Ricker`].
    pub fn ricker(amplitude: f64, frequency: f64) -> Result<Pulse, ExcitationError> {
        Pulse::Ricker {
            amplitude,
            frequency,
        }
        .checked()
    }

    /// Checked [`Pulse::MavroeidisPapageorgiou`].
    pub fn mavroeidis_papageorgiou(
        amplitude: f64,
        frequency: f64,
        gamma: f64,
        nu: f64,
    ) -> Result<Pulse, ExcitationError> {
        Pulse::MavroeidisPapageorgiou {
            amplitude,
            frequency,
            gamma,
            nu,
        }
        .checked()
    }

    fn checked(self) -> Result<Pulse, ExcitationError> {
        self.validate().map(|()| self)
    }

    /// Short name of the pulse kind, as used in messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Pulse::HalfSines { .. } => "half sines",
            Pulse::Rectangular { .. } => "rectangular",
            Pulse::Triangular { .. } => "triangular",
            Pulse::Ricker { .. } => "Ricker",
            Pulse::MavroeidisPapageorgiou { .. } => "Mavroeidis-Papageorgiou",
        }
    }

    /// Checks every field: amplitude finite; durations and frequencies finite and positive;
    /// `lobes ≥ 1`; for Mavroeidis–Papageorgiou `1 < γ ≤ 100` and `ν` finite. The error names
    /// the field.
    pub fn validate(&self) -> Result<(), ExcitationError> {
        self.check()
            .map_err(|invalid| ExcitationError::InvalidParameter {
                pulse: self.kind(),
                invalid,
            })
    }

    /// [`Pulse::validate`] without the pulse's name.
    fn check(&self) -> Result<(), InvalidValue> {
        let amplitude = match *self {
            Pulse::HalfSines {
                amplitude,
                half_period,
                lobes,
            } => {
                positive("half_period", half_period)?;
                if lobes == 0 {
                    return Err(InvalidValue::new("lobes", lobes, "must be at least 1"));
                }
                amplitude
            }
            Pulse::Rectangular {
                amplitude,
                duration,
            }
            | Pulse::Triangular {
                amplitude,
                duration,
            } => {
                positive("duration", duration)?;
                amplitude
            }
            Pulse::Ricker {
                amplitude,
                frequency,
            } => {
                positive("frequency", frequency)?;
                amplitude
            }
            Pulse::MavroeidisPapageorgiou {
                amplitude,
                frequency,
                gamma,
                nu,
            } => {
                positive("frequency", frequency)?;
                if !(gamma > 1.0 && gamma <= MP_GAMMA_MAX) {
                    return Err(InvalidValue::new(
                        "gamma",
                        gamma,
                        "must be greater than 1 and at most 100 (a pulse, not a harmonic)",
                    ));
                }
                finite("nu", nu)?;
                amplitude
            }
        };
        finite("amplitude", amplitude)?;
        if self.end_time().is_infinite() {
            return Err(InvalidValue::new(
                "duration",
                self.end_time(),
                "the pulse is too long to represent",
            ));
        }
        Ok(())
    }

    /// The signed amplitude (peak `|a|` is its absolute value).
    pub fn amplitude(&self) -> f64 {
        match *self {
            Pulse::HalfSines { amplitude, .. }
            | Pulse::Rectangular { amplitude, .. }
            | Pulse::Triangular { amplitude, .. }
            | Pulse::Ricker { amplitude, .. }
            | Pulse::MavroeidisPapageorgiou { amplitude, .. } => amplitude,
        }
    }

    /// The same pulse with its amplitude multiplied by `factor`.
    pub fn scaled(&self, factor: f64) -> Pulse {
        let mut p = *self;
        match &mut p {
            Pulse::HalfSines { amplitude, .. }
            | Pulse::Rectangular { amplitude, .. }
            | Pulse::Triangular { amplitude, .. }
            | Pulse::Ricker { amplitude, .. }
            | Pulse::MavroeidisPapageorgiou { amplitude, .. } => *amplitude *= factor,
        }
        p
    }

    /// Time after which the pulse is identically zero \[s\].
    pub fn end_time(&self) -> f64 {
        match *self {
            Pulse::HalfSines {
                half_period, lobes, ..
            } => f64::from(lobes) * half_period,
            Pulse::Rectangular { duration, .. } | Pulse::Triangular { duration, .. } => duration,
            Pulse::Ricker { frequency, .. } => 2.0 * RICKER_HALF_WIDTH / (PI * frequency),
            Pulse::MavroeidisPapageorgiou {
                frequency, gamma, ..
            } => gamma / frequency,
        }
    }

    /// Ground acceleration at `t` \[m/s²\]; zero before 0, after [`Pulse::end_time`] and for NaN.
    /// The parameters are assumed valid ([`Pulse::validate`]); invalid ones give meaningless
    /// numbers but never panic.
    #[inline]
    pub fn acceleration(&self, t: f64) -> f64 {
        if !(0.0..=self.end_time()).contains(&t) {
            return 0.0;
        }
        match *self {
            Pulse::HalfSines {
                amplitude,
                half_period,
                ..
            } => amplitude * (PI * t / half_period).sin(),
            Pulse::Rectangular {
                amplitude,
                duration,
            } => {
                if t < duration {
                    amplitude
                } else {
                    0.0
                }
            }
            Pulse::Triangular {
                amplitude,
                duration,
            } => amplitude * (1.0 - (2.0 * t / duration - 1.0).abs()),
            Pulse::Ricker {
                amplitude,
                frequency,
            } => {
                let x = PI * frequency * t - RICKER_HALF_WIDTH;
                let x2 = x * x;
                amplitude * (1.0 - 2.0 * x2) * (-x2).exp()
            }
            Pulse::MavroeidisPapageorgiou {
                amplitude,
                frequency,
                gamma,
                nu,
            } => {
                let s = frequency * t - 0.5 * gamma;
                -amplitude * mp_shape(s, gamma, nu) / mp_peak_cached(gamma, nu)
            }
        }
    }

    /// One line for logs and plots, e.g. `full sine: a_p = 2.5 m/s² (0.255 g), t_p = 0.5 s`.
    pub fn describe(&self) -> String {
        let a = self.amplitude();
        let amp = format!("{} m/s² ({:.3} g)", fmt_num(a), a / GRAVITY);
        match *self {
            Pulse::HalfSines {
                half_period, lobes, ..
            } => {
                let name = match lobes {
                    1 => "half sine".to_string(),
                    2 => "full sine".to_string(),
                    n => format!("{n} half sines"),
                };
                format!("{name}: a_p = {amp}, t_p = {} s", fmt_num(half_period))
            }
            Pulse::Rectangular { duration, .. } => {
                format!(
                    "rectangular pulse: a_p = {amp}, duration = {} s",
                    fmt_num(duration)
                )
            }
            Pulse::Triangular { duration, .. } => {
                format!(
                    "triangular pulse: a_p = {amp}, duration = {} s",
                    fmt_num(duration)
                )
            }
            Pulse::Ricker { frequency, .. } => {
                format!("Ricker wavelet: a_p = {amp}, f = {} Hz", fmt_num(frequency))
            }
            Pulse::MavroeidisPapageorgiou {
                frequency,
                gamma,
                nu,
                ..
            } => format!(
                "Mavroeidis-Papageorgiou pulse: a_p = {amp}, f_p = {} Hz, gamma = {}, nu = {} rad",
                fmt_num(frequency),
                fmt_num(gamma),
                fmt_num(nu)
            ),
        }
    }
}
