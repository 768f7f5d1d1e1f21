//! The checks at a state (the reaction test, the velocity terms), determinism, and the
//! validation of the options.

use super::*;

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
        stopping: StoppingOptions {
            duration: 6.0,
            ..StoppingOptions::default()
        },
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
    let mut rnd = crate::test_support::uniform(12345u64);
    for exact in [false, true] {
        let mut dynm = ColumnDynamics::new(&col, G, exact, 1e-12, 0.7);
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
            let open = crate::model::configuration::open_dofs(&statuses);
            dynm.reconfigured();
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

fn dynm_margin(d: &ColumnDynamics, dof: usize) -> f64 {
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
    let mut dynm = ColumnDynamics::new(&col, G, true, 1e-12, 0.7);
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
    bad(&|o| o.stepping.dt = 0.0, "stepping.dt");
    bad(&|o| o.stepping.dt = f64::NAN, "stepping.dt");
    bad(&|o| o.stopping.duration = -1.0, "stopping.duration");
    bad(&|o| o.physics.friction = 0.0, "physics.friction");
    bad(
        &|o| o.initial.angles = Some(vec![0.1, 0.2]),
        "initial.angles",
    );
    bad(
        &|o| o.initial.angles = Some(vec![f64::NAN]),
        "initial.angles",
    );
    bad(
        &|o| o.stepping.integrator = Integrator::WilsonTheta { theta: 0.5 },
        "stepping.integrator.theta",
    );
    bad(
        &|o| o.recording.history_every = Some(0),
        "recording.history_every",
    );
    bad(&|o| o.physics.model.n_impacts = 0, "n_impacts");
}
