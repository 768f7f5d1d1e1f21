//! Orders of convergence of the integrators and event locators; DOP853 against RK4.

use super::thesis::{full_sine, thesis_two_block};
use super::*;

/// Order of convergence on free rocking: error of the first impact time against the exact
/// quarter period, for dt halving.
#[test]
fn integrator_convergence_order() {
    let (b, h) = (0.25, 1.0);
    let exact = SingleBlockExact::new(b, h, G);
    let theta0 = 0.6 * exact.delta;
    let t_exact = exact.quarter(theta0);
    for (method, locator, lo, hi) in [
        (
            Integrator::WilsonTheta { theta: 1.4 },
            EventLocator::Hermite,
            1.7,
            2.3,
        ),
        (Integrator::Newmark, EventLocator::Hermite, 1.7, 2.3),
        (Integrator::Rk4, EventLocator::Hermite, 3.5, 4.6),
        (Integrator::Rk4, EventLocator::Linear, 1.7, 2.3),
    ] {
        let mut errors = Vec::new();
        for dt in [0.04, 0.02, 0.01, 0.005] {
            let mut opts = free(-theta0, 1.0);
            opts.stepping.dt = dt;
            opts.stepping.integrator = method;
            opts.stepping.locator = locator;
            let out = simulate(&block(b, h), &NoMotion, &opts, None).unwrap();
            errors.push((impacts(&out)[0].t - t_exact).abs());
        }
        let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        eprintln!("{method:?} {locator:?}: errors {errors:?}, orders {orders:.2?}");
        // Mean observed order (RK4 reaches ~3e-10 s at dt = 5 ms, where the last ratio drops).
        let mean = orders.iter().sum::<f64>() / orders.len() as f64;
        assert!(
            mean > lo && mean < hi,
            "{method:?} {locator:?}: mean order {mean}"
        );
    }
}

/// DOP853 with the refined Hermite location converges at about its order (8) on free rocking:
/// the largest error of the first five impact times against the exact solution, at steps from
/// 0.2 s (three steps per quarter period) down to 0.1 s, where it reaches ~1e-11 s; at 0.05 s it
/// is at the exact reference's own accuracy, where RK4 with the same locator is at 1e-5 s.
#[test]
fn dop853_converges_at_high_order_on_free_rocking() {
    let (b, h) = (0.25, 1.0);
    let exact = SingleBlockExact::new(b, h, G);
    let theta0 = 0.6 * exact.delta;
    let expected = exact.impact_times(theta0, housner(b, h), 5);
    let worst = |method: Integrator, dt: f64| -> f64 {
        let mut opts = free(-theta0, 3.6);
        opts.stepping.dt = dt;
        opts.stepping.integrator = method;
        opts.stepping.locator = EventLocator::Hermite;
        // Not four steps (the default): at these steps that would settle the block.
        opts.stopping.settle_interval = Some(0.05);
        let out = simulate(&block(b, h), &NoMotion, &opts, None).unwrap();
        let imps = impacts(&out);
        assert!(
            imps.len() >= 5,
            "{method:?} dt = {dt}: {} impacts",
            imps.len()
        );
        imps.iter()
            .zip(&expected)
            .map(|(e, t)| (e.t - t).abs())
            .fold(0.0, f64::max)
    };
    let dts = [0.2, 0.16, 0.12, 0.1];
    let errors: Vec<f64> = dts
        .iter()
        .map(|&dt| worst(Integrator::Dop853, dt))
        .collect();
    let orders: Vec<f64> = errors
        .windows(2)
        .zip(dts.windows(2))
        .map(|(e, d)| (e[0] / e[1]).ln() / (d[0] / d[1]).ln())
        .collect();
    // Least-squares slope of log(error) against log(dt).
    let (lx, ly): (Vec<f64>, Vec<f64>) = dts
        .iter()
        .zip(&errors)
        .map(|(d, e)| (d.ln(), e.ln()))
        .unzip();
    let mx = lx.iter().sum::<f64>() / 4.0;
    let my = ly.iter().sum::<f64>() / 4.0;
    let slope = lx
        .iter()
        .zip(&ly)
        .map(|(x, y)| (x - mx) * (y - my))
        .sum::<f64>()
        / lx.iter().map(|x| (x - mx) * (x - mx)).sum::<f64>();
    let fine = worst(Integrator::Dop853, 0.05);
    let rk4 = worst(Integrator::Rk4, 0.05);
    eprintln!(
        "DOP853 + Hermite: errors {:?} at dt {dts:?}, local orders {orders:.2?}, slope {slope:.2}; dt = 0.05: {fine:.2e} (RK4 {rk4:.2e})",
        errors.iter().map(|e| format!("{e:.2e}")).collect::<Vec<_>>()
    );
    assert!(slope > 6.5 && slope < 10.5, "observed order {slope}");
    assert!(errors[3] < 1e-10, "dt = 0.1: {}", errors[3]);
    assert!(fine < 1e-12, "dt = 0.05: {fine}");
    assert!(rk4 > 1e-7, "RK4 at dt = 0.05: {rk4}");
}

/// DOP853 (refined Hermite location) at a coarse step against RK4 + Hermite at a fine one on two
/// multi-block cases: the three-block column of `rocking bench accuracy` scene (c) (openings of
/// an upper interface while the lower one is open: the refined opening location) and the thesis
/// 4.2 two-block free rocking (20 impacts, with a settling interval fixed in seconds so that it
/// does not depend on the step). Same events, interface by interface, times within 1e-9 s.
#[test]
fn dop853_event_sequences_agree_with_rk4() {
    let col_c = Column::new(vec![
        Block::rectangle(0.5, 1.0, 600.0),
        Block::rectangle(0.4, 0.8, 300.0),
        Block::rectangle(0.3, 0.6, 130.0),
    ])
    .unwrap();
    let motion_c = full_sine(4.0, 0.6);
    let col_42 = thesis_two_block();
    type Case<'a> = (
        &'a str,
        &'a Column,
        &'a dyn GroundMotion,
        f64,
        Option<Vec<f64>>,
    );
    let cases: [Case; 2] = [
        ("scene (c)", &col_c, &motion_c, 0.5, None),
        (
            "thesis 4.2",
            &col_42,
            &NoMotion,
            1.0,
            Some(vec![0.0, -0.153]),
        ),
    ];
    for (name, col, motion, duration, initial_angles) in cases {
        let run = |integrator, dt| {
            let mut opts = SimulationOptions {
                stopping: StoppingOptions {
                    duration,
                    settle_interval: Some(1e-3),
                    ..StoppingOptions::default()
                },
                stepping: SteppingOptions {
                    dt,
                    integrator,
                    locator: EventLocator::Hermite,
                    ..SteppingOptions::default()
                },
                physics: PhysicsOptions {
                    friction: f64::INFINITY,
                    ..PhysicsOptions::default()
                },
                initial: InitialState {
                    angles: initial_angles.clone(),
                },
                ..SimulationOptions::default()
            };
            opts.physics.model.n_impacts = 2;
            simulate(col, motion, &opts, None).unwrap()
        };
        let reference = run(Integrator::Rk4, 1e-4);
        let coarse = run(Integrator::Dop853, 1e-2);
        let key = |e: &Event| (e.kind, e.interface, e.statuses_after.clone());
        assert!(reference.events.len() >= 4);
        assert_eq!(
            coarse.events.iter().map(key).collect::<Vec<_>>(),
            reference.events.iter().map(key).collect::<Vec<_>>(),
            "{name}"
        );
        let dt_max = coarse
            .events
            .iter()
            .zip(&reference.events)
            .map(|(a, b)| (a.t - b.t).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "{name}: {} events, DOP853 at 10 ms against RK4 at 0.1 ms: max |Δt| = {dt_max:.2e} s",
            coarse.events.len()
        );
        assert!(dt_max < 1e-9, "{name}: {dt_max}");
    }
}
