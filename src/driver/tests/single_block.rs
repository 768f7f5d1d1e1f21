//! One block: free rocking against the exact solution, Housner's ratio, settling, the event
//! cap, and the energy bound of `stop_when_safe`.

use super::*;

#[test]
fn single_block_free_rocking_matches_the_exact_solution() {
    let (b, h) = (0.25, 1.0);
    let exact = SingleBlockExact::new(b, h, G);
    let theta0 = 0.6 * exact.delta;
    for (n_imp, mu) in [(1, housner(b, h)), (2, two_impacts(b, h))] {
        for locator in [EventLocator::Linear, EventLocator::Hermite] {
            let mut opts = free(-theta0, 6.0);
            opts.stepping.locator = locator;
            opts.physics.model.n_impacts = n_imp;
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
        let exact = SingleBlockExact::new(b, h, G);
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
    let exact = SingleBlockExact::new(b, h, G);
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
    let exact = SingleBlockExact::new(b, h, G);
    let mut opts = free(-0.6 * exact.delta, 20.0);
    opts.stopping.settle_energy_fraction = 0.0;
    opts.stopping.settle_interval = Some(0.0);
    let out = simulate(&block(b, h), &NoMotion, &opts, None).unwrap();
    eprintln!(
        "without settling: {} impacts, stop {:?} at {}",
        out.impacts, out.stop_reason, out.t_end
    );
    opts.stopping.max_events_per_second = 1.0;
    let out = simulate(&block(b, h), &NoMotion, &opts, None).unwrap();
    assert_eq!(out.stop_reason, StopReason::TooManyEvents);
    assert!(out.t_end < 20.0);
}

/// The bundled record scaled by `factor`, with the tail impulses of
/// [`SimulationOptions::stop_when_safe`].
struct BundledRecord {
    record: crate::ground::records::Record,
    table: Vec<f64>,
}

impl BundledRecord {
    fn new(pga: f64) -> BundledRecord {
        let raw = crate::ground::records::bundled_record();
        let record = raw.scaled(pga / raw.pga());
        let table = record.impulse_table();
        BundledRecord { record, table }
    }
}

impl GroundMotion for BundledRecord {
    fn acceleration(&self, t: f64) -> f64 {
        self.record.acceleration(t)
    }
    fn end_time(&self) -> f64 {
        self.record.duration()
    }
    fn remaining_impulse(&self, t: f64) -> Option<f64> {
        Some(self.record.impulse_after(&self.table, t))
    }
}

/// The energy bound behind `stop_when_safe`: `√E` grows by at most `m R / √(2 I_P) ∫|a_g|`
/// between any two states of a whole run (RK4, fine steps), and the bound is not loose by a
/// factor of two (half the rate is exceeded somewhere).
#[test]
fn energy_grows_no_faster_than_the_bound_of_stop_when_safe() {
    let (b, h, m) = (0.1, 1.0, 100.0);
    let col = block(b, h);
    let motion = BundledRecord::new(1.5 * G * b / h);
    let opts = SimulationOptions {
        stopping: StoppingOptions {
            duration: 20.0,
            ..StoppingOptions::default()
        },
        stepping: SteppingOptions {
            dt: 2e-4,
            integrator: Integrator::Rk4,
            ..SteppingOptions::default()
        },
        physics: PhysicsOptions {
            friction: f64::INFINITY,
            ..PhysicsOptions::default()
        },
        ..SimulationOptions::default()
    };
    let out = simulate(&col, &motion, &opts, None).unwrap();
    assert!(!out.overturned && out.impacts > 10, "{:?}", out.stop_reason);
    let r = (b * b + h * h).sqrt();
    let alpha = (b / h).atan();
    let i_p = 4.0 / 3.0 * m * r * r;
    let k = m * r / (2.0 * i_p).sqrt();
    let hist = out.history.unwrap();
    let root_energy = |j: usize| {
        let (theta, omega) = (
            hist.phi[2 * j] + hist.phi[2 * j + 1],
            hist.rates[2 * j] + hist.rates[2 * j + 1],
        );
        let potential = m * G * (r * (alpha - theta.abs()).cos() - h);
        (0.5 * i_p * omega * omega + potential).max(0.0).sqrt()
    };
    let e_tip = m * G * (r - h);
    let (mut worst, mut half_exceeded) = (f64::NEG_INFINITY, false);
    for j in 0..hist.t.len() - 1 {
        let impulse = motion.record.impulse_after(&motion.table, hist.t[j])
            - motion.record.impulse_after(&motion.table, hist.t[j + 1]);
        let rise = root_energy(j + 1) - root_energy(j);
        worst = worst.max((rise - k * impulse) / e_tip.sqrt());
        half_exceeded |= rise > 0.5 * k * impulse;
    }
    eprintln!("largest excess of the bound over a step: {worst:e} √E_tip");
    assert!(worst < 1e-6, "bound exceeded by {worst:e} √E_tip");
    assert!(half_exceeded);

    // With the stop on, the run ends early with the same verdict.
    let stopped = simulate(
        &col,
        &motion,
        &SimulationOptions {
            stopping: StoppingOptions {
                stop_when_safe: true,
                ..opts.stopping
            },
            ..opts.clone()
        },
        None,
    )
    .unwrap();
    assert_eq!(stopped.stop_reason, StopReason::CannotTip);
    assert!(!stopped.overturned && stopped.t_end < 0.9 * out.t_end);
    // A block that the record tips is never stopped by the bound.
    let tipped = |stop_when_safe| {
        let o = SimulationOptions {
            stopping: StoppingOptions {
                stop_when_safe,
                ..opts.stopping
            },
            ..opts.clone()
        };
        simulate(
            &block(0.02, 0.2),
            &BundledRecord::new(4.0 * G * 0.1),
            &o,
            None,
        )
        .unwrap()
    };
    let (a, b2) = (tipped(true), tipped(false));
    assert!(a.overturned && b2.overturned);
    assert_eq!(a.t_end, b2.t_end);
}
