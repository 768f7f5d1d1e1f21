//! The Mavroeidis & Papageorgiou (2003) pulse shape and its normalisation `max |a|`, which has no
//! closed form: dense sampling, golden-section refinement, and a per-thread cache so that the
//! pulse stays O(1) in a time-stepping loop.

use std::cell::Cell;
use std::f64::consts::PI;

use super::MP_GAMMA_MAX;

/// Mavroeidis–Papageorgiou acceleration shape in `s = f_p τ ∈ [−γ/2, γ/2]` (M&P 2003 Eq. 2
/// without the factor `−A π f_p / γ`):
/// `h(s) = sin(2πs/γ) cos(2πs + ν) + γ sin(2πs + ν) (1 + cos(2πs/γ))`.
#[inline]
pub(super) fn mp_shape(s: f64, gamma: f64, nu: f64) -> f64 {
    let (se, ce) = (2.0 * PI * s / gamma).sin_cos();
    let (sc, cc) = (2.0 * PI * s + nu).sin_cos();
    se * cc + gamma * sc * (1.0 + ce)
}

/// `max |h(s)|` over the support: dense sampling (≥ 256 points per cycle) then golden-section
/// refinement around the largest sample.
pub(super) fn mp_peak(gamma: f64, nu: f64) -> f64 {
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
pub(super) fn mp_peak_cached(gamma: f64, nu: f64) -> f64 {
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
