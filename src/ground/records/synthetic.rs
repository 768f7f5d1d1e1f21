//! A deterministic artificial ground motion (filtered, enveloped white noise) and the bundled
//! `examples/records/synthetic.AT2` made from it.

#[cfg(test)]
use super::parse_at2;
use super::{invalid, write_at2, Record, RecordError};
use crate::model::column::GRAVITY;
use crate::validate::positive;

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
    positive("duration", duration)?;
    positive("dt", dt)?;
    positive("pga", pga)?;
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
        include_str!("../../../examples/records/synthetic.AT2"),
        "synthetic",
    )
    .unwrap()
}
