//! Physics acceptance tests of the driver (thesis 3.3, 4.2, 4.3, Fig. 40; SPEC §5).

use super::dynamics::Dynamics;
use super::*;
use crate::column::Block;
use crate::configuration::Status;
use crate::opening::check_configuration;

const G: f64 = GRAVITY;

/// A uniform block `2b × 2h` (half dimensions, as Housner and Appendix A).
fn block(b: f64, h: f64) -> Column {
    Column::new(vec![Block::rectangle(2.0 * b, 2.0 * h, 100.0)]).unwrap()
}

fn free(angle: f64, duration: f64) -> SimulationOptions {
    SimulationOptions {
        duration,
        initial_angles: Some(vec![angle]),
        ..SimulationOptions::default()
    }
}

/// Exact single-block quantities: `I_P θ̈ = −m g R sin(δ − θ)` for `0 < θ < δ` (θ = |φ|).
struct Exact {
    delta: f64,
    /// `m g R / I_P` (= p²).
    p2: f64,
}

impl Exact {
    fn new(b: f64, h: f64) -> Exact {
        let r = (b * b + h * h).sqrt();
        // I_P = m R² + m ((2b)² + (2h)²) / 12 = 4/3 m R².
        Exact {
            delta: (b / h).atan(),
            p2: G * r / (4.0 / 3.0 * r * r),
        }
    }

    /// Time to fall from rest at `theta0` to `θ = 0` (a quarter of the rocking period):
    /// `∫ dθ / ω`, `ω² = 2 p² (cos(δ − θ0) − cos(δ − θ))`, by the midpoint rule after
    /// `θ = θ0 (1 − s²)` (which removes the square-root singularity at θ0).
    fn quarter(&self, theta0: f64) -> f64 {
        let n = 20_000;
        let mut sum = 0.0;
        for i in 0..n {
            let s = (i as f64 + 0.5) / n as f64;
            let theta = theta0 * (1.0 - s * s);
            let w2 = 2.0 * self.p2 * ((self.delta - theta0).cos() - (self.delta - theta).cos());
            sum += 2.0 * theta0 * s / w2.sqrt();
        }
        sum / n as f64
    }

    /// Amplitude reached from `θ = 0` with rate `omega`.
    fn amplitude(&self, omega: f64) -> f64 {
        let c = self.delta.cos() + 0.5 * omega * omega / self.p2;
        self.delta - c.acos()
    }

    /// Rate at `θ = 0` after falling from `theta0`.
    fn rate_at_zero(&self, theta0: f64) -> f64 {
        (2.0 * self.p2 * ((self.delta - theta0).cos() - self.delta.cos())).sqrt()
    }

    /// Impact times with a constant velocity ratio `mu`.
    fn impact_times(&self, theta0: f64, mu: f64, count: usize) -> Vec<f64> {
        let mut t = self.quarter(theta0);
        let mut out = vec![t];
        let mut omega = self.rate_at_zero(theta0);
        for _ in 1..count {
            omega *= mu;
            let a = self.amplitude(omega);
            t += 2.0 * self.quarter(a);
            out.push(t);
        }
        out
    }
}

/// Housner's velocity ratio (thesis Eq. 1, half dimensions h, b).
fn housner(b: f64, h: f64) -> f64 {
    (2.0 * h * h - b * b) / (2.0 * h * h + 2.0 * b * b)
}

/// Two consecutive impacts (thesis Eq. A8).
fn two_impacts(b: f64, h: f64) -> f64 {
    (2.0 * h * h + 0.5 * b * b) / (2.0 * h * h + 2.0 * b * b)
}

fn impacts(out: &Outcome) -> Vec<&Event> {
    out.events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .collect()
}

#[test]
fn single_block_free_rocking_matches_the_exact_solution() {
    let (b, h) = (0.25, 1.0);
    let exact = Exact::new(b, h);
    let theta0 = 0.6 * exact.delta;
    for (n_imp, mu) in [(1, housner(b, h)), (2, two_impacts(b, h))] {
        for locator in [EventLocator::Linear, EventLocator::Hermite] {
            let mut opts = free(-theta0, 6.0);
            opts.locator = locator;
            opts.model.n_impacts = n_imp;
            let out = simulate(&block(b, h), &NoMotion, &opts, None).unwrap();
            let imps = impacts(&out);
            let expected = exact.impact_times(theta0, mu, 6);
            let mut worst = 0.0_f64;
            for (e, t) in imps.iter().zip(&expected) {
                worst = worst.max((e.t - t).abs());
                let ratio = e.kinetic_after / e.kinetic_before;
                assert!(
                    (ratio - mu * mu).abs() < 1e-9,
                    "energy ratio {ratio} vs μ² = {}",
                    mu * mu
                );
            }
            eprintln!(
                "single block n_imp={n_imp} {locator:?}: first impacts {:?} exact {:?}, worst |Δt| = {worst:.2e} s",
                imps.iter().take(6).map(|e| e.t).collect::<Vec<_>>(),
                expected
            );
            // Wilson θ (period error O(dt²)) and the event location at dt = 1 ms.
            assert!(worst < 2e-4, "worst impact-time error {worst}");
        }
    }
}

#[test]
fn housner_ratio_for_table1_slenderness() {
    // Table 1 rows h/b = 2, 3, 4: 51.0 %, 27.8 %, 16.9 % energy loss at the first impact.
    for (hb, loss) in [(2.0, 51.0), (3.0, 27.8), (4.0, 16.9)] {
        let (b, h) = (0.2, 0.2 * hb);
        let exact = Exact::new(b, h);
        let out = simulate(&block(b, h), &NoMotion, &free(0.5 * exact.delta, 3.0), None).unwrap();
        let e = impacts(&out)[0];
        // 27.75 % prints as 27.8 in the table; compare to the printed half-digit.
        let pct = 100.0 * (1.0 - e.kinetic_after / e.kinetic_before);
        assert!((pct - loss).abs() <= 0.05 + 1e-9, "h/b = {hb}: {pct} %");
    }
}

#[test]
fn free_rocking_settles_in_finite_time() {
    let (b, h) = (0.25, 1.0);
    let exact = Exact::new(b, h);
    let out = simulate(
        &block(b, h),
        &NoMotion,
        &free(-0.6 * exact.delta, 20.0),
        None,
    )
    .unwrap();
    assert_eq!(out.stop_reason, StopReason::Duration);
    assert_eq!(out.statuses_end, vec![Status::Closed]);
    let settled = out
        .events
        .iter()
        .find(|e| e.kind == EventKind::Settled)
        .expect("a Settled event");
    assert!(settled.t < 10.0, "settled at {}", settled.t);
    assert!(out.impacts < 200, "{} impacts", out.impacts);
    assert_eq!(out.events.last().unwrap().kind, EventKind::Settled);
    let hist = out.history.as_ref().unwrap();
    assert!(hist.phi.iter().chain(&hist.rates).all(|v| v.is_finite()));
    eprintln!(
        "settled at {:.3} s after {} impacts",
        settled.t, out.impacts
    );
}

#[test]
fn event_cap_stops_a_zeno_sequence() {
    let (b, h) = (0.25, 1.0);
    let exact = Exact::new(b, h);
    let mut opts = free(-0.6 * exact.delta, 20.0);
    opts.settle_energy_fraction = 0.0;
    opts.settle_interval = Some(0.0);
    let out = simulate(&block(b, h), &NoMotion, &opts, None).unwrap();
    eprintln!(
        "without settling: {} impacts, stop {:?} at {}",
        out.impacts, out.stop_reason, out.t_end
    );
    opts.max_events_per_second = 1.0;
    let out = simulate(&block(b, h), &NoMotion, &opts, None).unwrap();
    assert_eq!(out.stop_reason, StopReason::TooManyEvents);
    assert!(out.t_end < 20.0);
}

#[test]
fn determinism_bitwise() {
    let col = Column::uniform(3, 1.0, 12.0, 3000.0).unwrap();
    let motion = FnMotion(
        |t: f64| {
            if t < 2.0 {
                3.0 * (std::f64::consts::PI * t).sin()
            } else {
                0.0
            }
        },
        2.0,
    );
    let opts = SimulationOptions {
        duration: 6.0,
        ..SimulationOptions::default()
    };
    let a = simulate(&col, &motion, &opts, None).unwrap();
    let b = simulate(&col, &motion, &opts, None).unwrap();
    assert_eq!(format!("{a:?}"), format!("{b:?}"));
    let bits = |o: &Outcome| {
        o.history
            .as_ref()
            .unwrap()
            .phi
            .iter()
            .map(|v| v.to_bits())
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(overturns(&col, &motion, &opts).unwrap(), a.overturned);
}

/// The driver's own reaction test agrees with `check_configuration` (same margins, same
/// threshold) on random states of a three-block column, and the one-DOF fast path agrees with
/// the general assembly.
#[test]
fn reaction_test_agrees_with_check_configuration() {
    let col = Column::new(vec![
        Block::rectangle(0.5, 1.5, 200.0),
        Block::rectangle(0.4, 1.0, 120.0),
        Block::rectangle(0.3, 0.8, 60.0),
    ])
    .unwrap();
    let n = 3;
    let mut seed = 12345u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for exact in [false, true] {
        let mut dynm = Dynamics::new(&col, G, exact, 1e-12, 0.7);
        for _ in 0..300 {
            let statuses: Vec<Status> = (0..n)
                .map(|_| match (rnd() * 3.0) as i32 {
                    0 => Status::OpenRight,
                    1 => Status::Closed,
                    _ => Status::OpenLeft,
                })
                .collect();
            let mut phi = vec![0.0; 2 * n];
            let mut rates = vec![0.0; 2 * n];
            for k in 0..n {
                if let Some(d) = statuses[k].dof(k, n) {
                    phi[d] = statuses[k].sign() * 0.2 * rnd();
                    rates[d] = (rnd() - 0.5) * 2.0;
                }
            }
            let ag = (rnd() - 0.5) * 12.0;
            let open = crate::configuration::open_dofs(&statuses);
            dynm.reset_scratch();
            let c = dynm.check(&open, &statuses, ag, &phi, &rates, false);
            let mut mass = vec![0.0; 36];
            let mut load = vec![0.0; 6];
            dynm.full_system(&statuses, ag, &phi, &rates, &mut mass, &mut load);
            let reference = check_configuration(&mass, &load, &statuses, 1e-12).unwrap();
            let mut mine: Vec<usize> = (0..2 * n)
                .filter(|&d| dynm_margin(&dynm, d) > 0.0)
                .map(|d| d % n)
                .collect();
            mine.sort_unstable();
            mine.dedup();
            assert_eq!(mine, reference.must_open, "statuses {statuses:?} ag {ag}");
            assert_eq!(c.max_margin > 0.0, !reference.holds());
            for (a, b) in dynm.acc_full.clone().iter().zip(&reference.acceleration) {
                assert!((a - b).abs() <= 1e-9 * (1.0 + b.abs()), "{a} vs {b}");
            }
            if open.len() == 1 {
                let x = [phi[open[0]]];
                let v = [rates[open[0]]];
                let mut out = [0.0];
                dynm.accel(&open, &statuses, ag, &x, &v, &mut out);
                let b = reference.acceleration[open[0]];
                assert!(
                    (out[0] - b).abs() <= 1e-9 * (1.0 + b.abs()),
                    "fast path {} vs {b}",
                    out[0]
                );
            }
        }
    }
}

fn dynm_margin(d: &Dynamics, dof: usize) -> f64 {
    d.margin[dof]
}

#[test]
fn velocity_terms_match_the_column() {
    let col = Column::new(vec![
        Block::rectangle(0.4, 1.2, 3.0),
        Block::rectangle(0.3, 0.9, 2.0),
    ])
    .unwrap();
    let statuses = [Status::OpenRight, Status::OpenLeft];
    let phi = [-0.1, 0.0, 0.0, 0.05];
    let rates = [-0.7, 0.0, 0.0, 0.4];
    let mut dynm = Dynamics::new(&col, G, true, 1e-12, 0.7);
    let mut mass = vec![0.0; 16];
    let mut load = vec![0.0; 4];
    dynm.full_system(&statuses, 0.3, &phi, &rates, &mut mass, &mut load);
    let pose = col.pose(&phi);
    let mut vl = [0.0; 4];
    col.velocity_load_into(&pose, &phi, &rates, &mut vl);
    let q = col.load_vector(&pose, 0.3, G);
    for a in 0..4 {
        assert!(
            (load[a] - q[a] - vl[a]).abs() < 1e-12,
            "{a}: {} vs {}",
            load[a] - q[a],
            vl[a]
        );
    }
}

#[test]
fn invalid_options_name_the_field() {
    let col = block(0.25, 1.0);
    let bad = |f: &dyn Fn(&mut SimulationOptions), field: &str| {
        let mut o = SimulationOptions::default();
        f(&mut o);
        let e = simulate(&col, &NoMotion, &o, None).unwrap_err();
        assert!(e.to_string().contains(field), "{e}");
    };
    bad(&|o| o.dt = 0.0, "dt");
    bad(&|o| o.dt = f64::NAN, "dt");
    bad(&|o| o.duration = -1.0, "duration");
    bad(&|o| o.friction = 0.0, "friction");
    bad(
        &|o| o.initial_angles = Some(vec![0.1, 0.2]),
        "initial_angles",
    );
    bad(
        &|o| o.initial_angles = Some(vec![f64::NAN]),
        "initial_angles",
    );
    bad(
        &|o| o.integrator = Integrator::WilsonTheta { theta: 0.5 },
        "theta",
    );
    bad(&|o| o.record.history_every = Some(0), "history_every");
    bad(&|o| o.model.n_impacts = 0, "n_impacts");
}
