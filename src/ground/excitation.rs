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

use std::cell::Cell;
use std::f64::consts::PI;
use std::fmt;

use crate::ground::records::{Record, RecordError};
use crate::model::column::GRAVITY;

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
#[derive(Clone, Debug, PartialEq)]
pub enum ExcitationError {
    /// A pulse parameter is out of range.
    InvalidParameter {
        /// Pulse kind (`"half sines"`, `"rectangular"`, …).
        pulse: &'static str,
        /// Field name (`amplitude`, `half_period`, `lobes`, `duration`, `frequency`, `gamma`, `nu`).
        field: &'static str,
        /// The offending value.
        value: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// The record is invalid.
    Record(RecordError),
}

impl fmt::Display for ExcitationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ExcitationError::InvalidParameter {
                pulse,
                field,
                value,
                reason,
            } => write!(f, "{pulse} pulse: {field} = {value}: {reason}"),
            ExcitationError::Record(e) => write!(f, "record: {e}"),
        }
    }
}

impl std::error::Error for ExcitationError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ExcitationError::Record(e) => Some(e),
            ExcitationError::InvalidParameter { .. } => None,
        }
    }
}

impl From<RecordError> for ExcitationError {
    fn from(e: RecordError) -> ExcitationError {
        ExcitationError::Record(e)
    }
}

/// Largest `γ` accepted for the Mavroeidis–Papageorgiou pulse.
pub const MP_GAMMA_MAX: f64 = 100.0;

/// Ricker wavelet: `π f t₀`, half the truncated support in units of `1/(π f)`.
const RICKER_HALF_WIDTH: f64 = 3.0 * std::f64::consts::SQRT_2;

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
        let pulse = self.kind();
        let bad = |field, value, reason| {
            Err(ExcitationError::InvalidParameter {
                pulse,
                field,
                value,
                reason,
            })
        };
        let positive = |field, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                bad(field, value, "must be finite and positive")
            }
        };
        let amplitude = match *self {
            Pulse::HalfSines {
                amplitude,
                half_period,
                lobes,
            } => {
                positive("half_period", half_period)?;
                if lobes == 0 {
                    return bad("lobes", 0.0, "must be at least 1");
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
                if !(gamma.is_finite() && gamma > 1.0) {
                    return bad("gamma", gamma, "must be finite and greater than 1");
                }
                if gamma > MP_GAMMA_MAX {
                    return bad(
                        "gamma",
                        gamma,
                        "must be at most 100 (a pulse, not a harmonic)",
                    );
                }
                if !nu.is_finite() {
                    return bad("nu", nu, "must be finite");
                }
                amplitude
            }
        };
        if !amplitude.is_finite() {
            return bad("amplitude", amplitude, "must be finite");
        }
        if self.end_time().is_infinite() {
            return bad(
                "duration",
                self.end_time(),
                "the pulse is too long to represent",
            );
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

/// Mavroeidis–Papageorgiou acceleration shape in `s = f_p τ ∈ [−γ/2, γ/2]` (M&P 2003 Eq. 2
/// without the factor `−A π f_p / γ`):
/// `h(s) = sin(2πs/γ) cos(2πs + ν) + γ sin(2πs + ν) (1 + cos(2πs/γ))`.
#[inline]
fn mp_shape(s: f64, gamma: f64, nu: f64) -> f64 {
    let (se, ce) = (2.0 * PI * s / gamma).sin_cos();
    let (sc, cc) = (2.0 * PI * s + nu).sin_cos();
    se * cc + gamma * sc * (1.0 + ce)
}

/// `max |h(s)|` over the support: dense sampling (≥ 256 points per cycle) then golden-section
/// refinement around the largest sample.
fn mp_peak(gamma: f64, nu: f64) -> f64 {
    let gamma_c = gamma.clamp(1.0, MP_GAMMA_MAX);
    let n = (256.0 * gamma_c).ceil().max(4096.0) as usize;
    let (lo, hi) = (-0.5 * gamma, 0.5 * gamma);
    let step = (hi - lo) / n as f64;
    let abs_h = |s: f64| mp_shape(s, gamma, nu).abs();
    let (mut best_i, mut best) = (0, 0.0);
    for i in 0..=n {
        let v = abs_h(lo + i as f64 * step);
        if v > best {
            (best_i, best) = (i, v);
        }
    }
    // Golden section on [s_{i−1}, s_{i+1}] (|h| is unimodal there at this sampling density).
    let mut a = lo + best_i.saturating_sub(1) as f64 * step;
    let mut b = (lo + (best_i + 1) as f64 * step).min(hi);
    let r = 0.5 * (5.0_f64.sqrt() - 1.0);
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut fc, mut fd) = (abs_h(c), abs_h(d));
    for _ in 0..80 {
        if fc > fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - r * (b - a);
            fc = abs_h(c);
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + r * (b - a);
            fd = abs_h(d);
        }
    }
    best.max(fc).max(fd)
}

thread_local! {
    /// Last `(γ bits, ν bits, max |h|)` computed on this thread.
    static MP_PEAK_CACHE: Cell<(u64, u64, f64)> = const { Cell::new((u64::MAX, u64::MAX, f64::NAN)) };
}

/// [`mp_peak`] with a one-entry per-thread cache: a time history evaluates the same pulse at
/// every step, so after the first call this is two comparisons.
#[inline]
fn mp_peak_cached(gamma: f64, nu: f64) -> f64 {
    let key = (gamma.to_bits(), nu.to_bits());
    MP_PEAK_CACHE.with(|cache| {
        let (g, n, peak) = cache.get();
        if (g, n) == key {
            peak
        } else {
            let peak = mp_peak(gamma, nu);
            cache.set((key.0, key.1, peak));
            peak
        }
    })
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
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    /// Max |a| over a dense grid of the support.
    fn sampled_peak(e: &Excitation, n: usize) -> f64 {
        let end = e.end_time();
        (0..=n)
            .map(|i| e.acceleration(end * i as f64 / n as f64).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn half_sine_formula() {
        let e = Excitation::pulse(Pulse::half_sine(2.0, 0.4).unwrap()).unwrap();
        assert_eq!(e.end_time(), 0.4);
        assert!(close(e.acceleration(0.2), 2.0, 1e-15));
        assert!(close(e.acceleration(0.1), 2.0 * (PI / 4.0).sin(), 1e-15));
        assert_eq!(e.acceleration(0.0), 0.0);
        assert!(close(e.acceleration(0.4), 0.0, 1e-15));
        assert_eq!(e.acceleration(-0.01), 0.0);
        assert_eq!(e.acceleration(0.4 + 1e-12), 0.0);
        assert_eq!(e.acceleration(100.0), 0.0);
        assert_eq!(e.acceleration(f64::NAN), 0.0);
        assert_eq!(e.peak(), 2.0);
        assert!(close(sampled_peak(&e, 1000), 2.0, 1e-12));
    }

    #[test]
    fn full_sine_is_antisymmetric() {
        let (a, tp) = (1.5, 0.3);
        let p = Pulse::full_sine(a, tp).unwrap();
        assert_eq!(p.end_time(), 2.0 * tp);
        for i in 0..=50 {
            let x = tp * i as f64 / 50.0;
            // Second half = −first half, and point symmetry about t_p.
            assert!(
                close(p.acceleration(tp + x), -p.acceleration(x), 1e-12),
                "{x}"
            );
            assert!(
                close(p.acceleration(tp - x), -p.acceleration(tp + x), 1e-12),
                "{x}"
            );
        }
        assert!(close(p.acceleration(0.5 * tp), a, 1e-14));
        assert!(close(p.acceleration(1.5 * tp), -a, 1e-14));
    }

    #[test]
    fn three_half_sines_alternate() {
        let p = Pulse::half_sines(1.0, 0.2, 3).unwrap();
        assert!(close(p.end_time(), 0.6, 1e-15));
        assert!(close(p.acceleration(0.1), 1.0, 1e-14));
        assert!(close(p.acceleration(0.3), -1.0, 1e-14));
        assert!(close(p.acceleration(0.5), 1.0, 1e-14));
        assert_eq!(p.acceleration(0.61), 0.0);
    }

    #[test]
    fn rectangular_and_triangular() {
        let r = Pulse::rectangular(-3.0, 0.5).unwrap();
        assert_eq!(r.acceleration(0.0), -3.0);
        assert_eq!(r.acceleration(0.499), -3.0);
        assert_eq!(r.acceleration(0.5), 0.0);
        assert_eq!(r.acceleration(-0.1), 0.0);
        assert_eq!(Excitation::Pulse(r).peak(), 3.0);
        let t = Pulse::triangular(2.0, 1.0).unwrap();
        assert_eq!(t.acceleration(0.0), 0.0);
        assert!(close(t.acceleration(0.25), 1.0, 1e-15));
        assert_eq!(t.acceleration(0.5), 2.0);
        assert!(close(t.acceleration(0.75), 1.0, 1e-15));
        assert!(close(t.acceleration(1.0), 0.0, 1e-15));
        assert_eq!(t.acceleration(1.01), 0.0);
    }

    #[test]
    fn ricker_wavelet() {
        let (a, f) = (4.0, 2.0);
        let p = Pulse::ricker(a, f).unwrap();
        let t0 = RICKER_HALF_WIDTH / (PI * f);
        assert!(close(p.end_time(), 2.0 * t0, 1e-15));
        assert!(close(p.acceleration(t0), a, 1e-14));
        // Side lobes at t0 ± √6/(2πf) of −0.446 A; zero crossings at t0 ± 1/(√2 π f).
        let side = 6.0_f64.sqrt() / (2.0 * PI * f);
        assert!(close(
            p.acceleration(t0 + side),
            -2.0 * (-1.5_f64).exp() * a,
            1e-12
        ));
        assert!(close(
            p.acceleration(t0 - 1.0 / (2.0_f64.sqrt() * PI * f)),
            0.0,
            1e-12
        ));
        // Starts and ends near zero; zero mean.
        assert!(p.acceleration(0.0).abs() < 1e-6 * a);
        assert!(p.acceleration(2.0 * t0).abs() < 1e-6 * a);
        let n = 20_000;
        let h = 2.0 * t0 / n as f64;
        let integral: f64 = (0..n)
            .map(|i| p.acceleration((i as f64 + 0.5) * h) * h)
            .sum();
        assert!(integral.abs() < 1e-6 * a, "{integral}");
        let e = Excitation::Pulse(p);
        assert!(close(sampled_peak(&e, 10_000), a, 1e-6));
    }

    /// M&P 2003 Eq. 1, the velocity whose derivative the pulse is (unnormalised).
    fn mp_velocity(s: f64, gamma: f64, nu: f64) -> f64 {
        0.5 * (1.0 + (2.0 * PI * s / gamma).cos()) * (2.0 * PI * s + nu).cos()
    }

    #[test]
    fn mavroeidis_papageorgiou_peak_and_shape() {
        for &(gamma, nu) in &[
            (2.0, 0.0),
            (1.5, PI / 2.0),
            (3.0, 1.0),
            (1.01, -2.0),
            (8.0, 0.3),
        ] {
            let (a, fp) = (3.0, 0.8);
            let p = Pulse::mavroeidis_papageorgiou(a, fp, gamma, nu).unwrap();
            let e = Excitation::pulse(p).unwrap();
            assert!(close(e.end_time(), gamma / fp, 1e-15));
            assert_eq!(e.peak(), a);
            // Peak of the sampled signal equals the amplitude (and never exceeds it).
            let sampled = sampled_peak(&e, 200_000);
            assert!(sampled <= a * (1.0 + 1e-12), "{gamma} {nu}: {sampled}");
            assert!(close(sampled, a, 1e-6 * a), "{gamma} {nu}: {sampled}");
            // Zero at both ends and outside.
            assert!(e.acceleration(0.0).abs() < 1e-12);
            assert!(e.acceleration(gamma / fp).abs() < 1e-12);
            assert_eq!(e.acceleration(gamma / fp + 1e-9), 0.0);
            assert_eq!(e.acceleration(-1e-9), 0.0);
            // The integral of a is the M&P velocity (analytic derivative is right): compare the
            // shapes normalised by their value at the pulse centre's neighbourhood maximum.
            let n = 40_000;
            let h = e.end_time() / n as f64;
            let mut v = 0.0;
            let mut prev = e.acceleration(0.0);
            let mut ratio = None;
            for i in 1..=n {
                let t = i as f64 * h;
                let cur = e.acceleration(t);
                v += 0.5 * h * (prev + cur);
                prev = cur;
                let reference = mp_velocity(fp * t - 0.5 * gamma, gamma, nu);
                if ratio.is_none() && reference.abs() > 0.5 {
                    ratio = Some(v / reference);
                }
                if let Some(k) = ratio {
                    assert!(
                        close(v, k * reference, 1e-5 * k.abs()),
                        "{gamma} {nu} t={t}"
                    );
                }
            }
            assert!(
                ratio.unwrap() > 0.0,
                "velocity has the sign of the amplitude"
            );
            assert!(v.abs() < 1e-6, "ends at rest: {v}");
        }
    }

    #[test]
    fn mp_cache_follows_parameter_changes() {
        let p1 = Pulse::mavroeidis_papageorgiou(1.0, 1.0, 2.0, 0.0).unwrap();
        let p2 = Pulse::mavroeidis_papageorgiou(1.0, 1.0, 3.0, 0.5).unwrap();
        let t = 0.9;
        let (a1, a2) = (p1.acceleration(t), p2.acceleration(t));
        for _ in 0..3 {
            assert_eq!(p1.acceleration(t), a1);
            assert_eq!(p2.acceleration(t), a2);
        }
        assert_eq!(mp_peak_cached(2.0, 0.0), mp_peak(2.0, 0.0));
    }

    #[test]
    fn validation_names_the_field() {
        let field = |r: Result<Pulse, ExcitationError>| match r {
            Err(ExcitationError::InvalidParameter { field, .. }) => field,
            other => panic!("expected an error, got {other:?}"),
        };
        assert_eq!(field(Pulse::half_sines(1.0, 0.5, 0)), "lobes");
        assert_eq!(field(Pulse::half_sine(1.0, 0.0)), "half_period");
        assert_eq!(field(Pulse::half_sine(1.0, -1.0)), "half_period");
        assert_eq!(field(Pulse::half_sine(1.0, f64::INFINITY)), "half_period");
        assert_eq!(field(Pulse::half_sine(f64::NAN, 0.5)), "amplitude");
        assert_eq!(field(Pulse::rectangular(1.0, f64::NAN)), "duration");
        assert_eq!(field(Pulse::triangular(1.0, 0.0)), "duration");
        assert_eq!(field(Pulse::ricker(1.0, 0.0)), "frequency");
        assert_eq!(field(Pulse::ricker(f64::INFINITY, 1.0)), "amplitude");
        assert_eq!(
            field(Pulse::mavroeidis_papageorgiou(1.0, 1.0, 1.0, 0.0)),
            "gamma"
        );
        assert_eq!(
            field(Pulse::mavroeidis_papageorgiou(1.0, 1.0, 0.5, 0.0)),
            "gamma"
        );
        assert_eq!(
            field(Pulse::mavroeidis_papageorgiou(1.0, 1.0, 500.0, 0.0)),
            "gamma"
        );
        assert_eq!(
            field(Pulse::mavroeidis_papageorgiou(1.0, 1.0, f64::NAN, 0.0)),
            "gamma"
        );
        assert_eq!(
            field(Pulse::mavroeidis_papageorgiou(1.0, 1.0, 2.0, f64::NAN)),
            "nu"
        );
        assert_eq!(
            field(Pulse::mavroeidis_papageorgiou(1.0, -1.0, 2.0, 0.0)),
            "frequency"
        );
        assert_eq!(field(Pulse::half_sines(1.0, 1e308, u32::MAX)), "duration");
        let msg = Pulse::half_sines(1.0, 0.5, 0).unwrap_err().to_string();
        assert!(msg.contains("lobes") && msg.contains("half sines"), "{msg}");
        // Zero and negative amplitudes are valid (no motion, reversed pulse).
        assert!(Pulse::half_sine(0.0, 0.5).is_ok());
        assert!(Pulse::half_sine(-1.0, 0.5).is_ok());
        // Records are checked too.
        let bad = Record {
            name: "r".into(),
            dt: 0.0,
            samples: vec![1.0],
        };
        assert!(matches!(
            Excitation::record(bad),
            Err(ExcitationError::Record(_))
        ));
    }

    #[test]
    fn none_and_record() {
        let none = Excitation::default();
        assert_eq!(none.acceleration(1.0), 0.0);
        assert_eq!(none.end_time(), 0.0);
        assert_eq!(none.peak(), 0.0);
        assert_eq!(none.scaled(2.0), Excitation::None);
        assert_eq!(none.describe(), "no ground motion");
        let r = Record::new("rec", 0.1, vec![0.0, 1.0, -3.0, 0.5]).unwrap();
        let e = Excitation::record(r.clone()).unwrap();
        for i in 0..40 {
            let t = -0.05 + i as f64 * 0.0123;
            assert_eq!(e.acceleration(t), r.acceleration(t));
        }
        assert!(close(e.acceleration(0.15), -1.0, 1e-12));
        assert!(close(e.end_time(), 0.3, 1e-15));
        assert_eq!(e.peak(), 3.0);
        assert_eq!(e.scaled(2.0).peak(), 6.0);
        let d = e.describe();
        assert!(
            d.contains("rec") && d.contains("4 samples") && d.contains("dt = 0.1 s"),
            "{d}"
        );
    }

    #[test]
    fn scaling_and_description_of_pulses() {
        let e = Excitation::from(Pulse::full_sine(2.0, 0.5).unwrap());
        let s = e.scaled(-1.5);
        assert_eq!(s.peak(), 3.0);
        assert!(close(s.acceleration(0.25), -3.0, 1e-14));
        assert_eq!(s.end_time(), e.end_time());
        assert_eq!(
            e.describe(),
            "full sine: a_p = 2 m/s² (0.204 g), t_p = 0.5 s"
        );
        for p in [
            Pulse::half_sine(1.0, 0.1).unwrap(),
            Pulse::half_sines(1.0, 0.1, 3).unwrap(),
            Pulse::rectangular(1.0, 0.1).unwrap(),
            Pulse::triangular(1.0, 0.1).unwrap(),
            Pulse::ricker(1.0, 2.0).unwrap(),
            Pulse::mavroeidis_papageorgiou(1.0, 0.5, 2.0, 0.1).unwrap(),
        ] {
            let d = Excitation::Pulse(p).describe();
            assert!(d.contains("a_p = 1 m/s²"), "{d}");
        }
        assert_eq!(fmt_num(0.30000000000000004), "0.3");
        assert_eq!(fmt_num(1234.5678), "1234.57");
    }
}
