use std::f64::consts::PI;

use super::mavroeidis_papageorgiou::{mp_peak, mp_peak_cached};
use super::pulse::RICKER_HALF_WIDTH;
use super::*;
use crate::test_support::close;

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
        Err(ExcitationError::InvalidParameter { invalid, .. }) => invalid.field,
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
