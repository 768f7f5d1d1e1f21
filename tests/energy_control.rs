//! The opt-in error control of the drum scheme (`rocking::contact::refine`,
//! docs/energy-control.md): off it changes nothing, a tolerance never reached gives the default
//! scheme's run to the bit, and on a run whose energy residual is well above 0.1 % it brings the
//! residual under it with the identity still closing at round-off and the events in order.

use rocking::contact::simulation::{simulate, DrumEventKind, DrumOptions, DrumOutcome};
use rocking::ground::excitation::Excitation;
use rocking::ground::records::read_at2;
use rocking::model::column::{Block, Column};

fn run(tol: Option<f64>) -> DrumOutcome {
    // Ten 1 × 2 m drums under the bundled synthetic record at 3 m/s², 10 s, μ 0.5, two impacts:
    // the kind of column whose residual is largest at dt = 1 ms (docs/multidrum.md, "Energy");
    // here 1.0e-2 without the control.
    let col = Column::new(
        (0..10)
            .map(|_| Block::rectangle(1.0, 2.0, 5000.0))
            .collect(),
    )
    .unwrap();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/records/synthetic.AT2"
    );
    let record = read_at2(std::path::Path::new(path)).unwrap();
    let motion = Excitation::record(record.scaled_to_pga(3.0).unwrap()).unwrap();
    let mut opts = DrumOptions::quiet(10.0, 0.5, 2);
    opts.record.events = true;
    opts.scheme.energy_tolerance = tol;
    simulate(&col, &motion, &opts, None).unwrap()
}

#[test]
fn a_tolerance_never_reached_is_the_default_scheme_to_the_bit() {
    let a = run(None);
    let b = run(Some(1e300));
    assert_eq!(b.counters.refined, 0);
    assert_eq!(format!("{a:?}"), format!("{b:?}"));
}

#[test]
fn the_control_brings_the_residual_under_a_thousandth() {
    let a = run(None);
    let b = run(Some(1e-6));
    let rel = |o: &DrumOutcome| o.energy.residual() / o.energy.scale();
    println!(
        "default: {:?}, residual {:.2e}, {:?}\ncontrolled: {:?}, residual {:.2e}, {:?}",
        a.stop,
        rel(&a),
        a.counters,
        b.stop,
        rel(&b),
        b.counters
    );
    assert!(
        rel(&a).abs() > 1e-3,
        "the default run is no test: {}",
        rel(&a)
    );
    assert!(rel(&b).abs() < 1e-3, "controlled residual {}", rel(&b));
    assert!(b.counters.refined > 0);
    // The identity with the scheme's own terms still closes: nothing double-counted or lost
    // when a step is rolled back.
    assert!(b.energy.closure().abs() < 1e-9 * b.energy.scale());
    // Events: in time order, each counted once.
    assert!(b.events.windows(2).all(|w| w[0].t <= w[1].t));
    let counted: usize = b.event_counts.iter().sum();
    let kept = b
        .events
        .iter()
        .filter(|e| e.kind != DrumEventKind::SchemeSwitch)
        .count();
    assert_eq!(counted, kept);
    assert!(b.event_counts[1] > 0);
}
