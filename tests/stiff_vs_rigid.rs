//! `c_examples/stiff_blocks.c` (axially elastic blocks, axial frequency 100, 1000 and 10 000
//! times the rocking frequency) against the rigid Rust driver (`rocking::driver::simulate`, set
//! up as in `tests/harness_vs_driver.rs` but with the program's dt = 1e-4 s).
//!
//! Asserted for the recipe (docs/opensees.md section 6) at every stiffness ratio and scene:
//! - the same event sequence as the driver (kind, interface, configuration after), complete, and
//!   the same stop;
//! - event times and peak rotations converge to the driver's as the stiffness grows: the
//!   largest event-time difference falls with the ratio, and at 10 000x it is within dt/10 and
//!   the peaks within 1 %.
//!
//! And, as the evidence the recipe is needed, that the naive coupling (decisions on the total,
//! vibrating interface forces) does NOT reproduce the rigid sequence in the half-sine (b) and
//! two-block (c) scenes at any ratio.
//!
//! `cargo test --release --test stiff_vs_rigid -- --nocapture` prints the measured figures.

mod common;

use std::collections::BTreeMap;

use rocking::column::{Block, Column};
use rocking::driver::{
    simulate, EventKind, EventLocator, FnMotion, GroundMotion, Integrator, NoMotion,
    SimulationOptions, StopReason,
};
use rocking::Status;

/// One event as the harness prints it (`EVENT scene=… kind=… t=… interface=… after=…`).
#[derive(Debug, Clone, PartialEq)]
struct Ev {
    kind: String,
    t: f64,
    interface: usize,
    after: Vec<i8>,
}

#[derive(Debug, Default)]
struct SceneResult {
    events: Vec<Ev>,
    stop: String,
    t_end: f64,
    peak: Vec<f64>,
}

fn field<'a>(line: &'a str, key: &str) -> &'a str {
    line.split_whitespace()
        .find_map(|w| w.strip_prefix(key).and_then(|r| r.strip_prefix('=')))
        .unwrap_or_else(|| panic!("no {key}= in {line}"))
}

fn parse(out: &str) -> BTreeMap<String, SceneResult> {
    let mut scenes: BTreeMap<String, SceneResult> = BTreeMap::new();
    for line in out.lines() {
        if line.starts_with("EVENT ") {
            let r = scenes.entry(field(line, "scene").to_string()).or_default();
            r.events.push(Ev {
                kind: field(line, "kind").to_string(),
                t: field(line, "t").parse().unwrap(),
                interface: field(line, "interface").parse().unwrap(),
                after: field(line, "after")
                    .split(',')
                    .map(|s| s.parse().unwrap())
                    .collect(),
            });
        } else if line.starts_with("RESULT ") {
            let r = scenes.entry(field(line, "scene").to_string()).or_default();
            r.stop = field(line, "stop").to_string();
            r.t_end = field(line, "t_end").parse().unwrap();
            r.peak = field(line, "peak")
                .split(',')
                .map(|s| s.parse().unwrap())
                .collect();
        }
    }
    scenes
}

fn status_value(s: Status) -> i8 {
    match s {
        Status::OpenRight => -1,
        Status::Closed => 0,
        Status::OpenLeft => 1,
    }
}

/// The scenes of `stiff_blocks.c` (a, b, c of the harness, dt = 1e-4 s).
fn driver_scene(name: &str) -> SceneResult {
    let granite = |w: f64, h: f64, t: f64| {
        let mut b = Block::rectangle(w, h, 2700.0 * w * h * t);
        b.contact_width = Some(0.096);
        b
    };
    let pi = std::f64::consts::PI;
    let mut opts = SimulationOptions {
        dt: 1e-4,
        integrator: Integrator::Newmark,
        locator: EventLocator::Hermite,
        friction: f64::INFINITY,
        gravity: 9.81,
        exact_velocity_terms: false,
        continue_until_fallen: false,
        ..SimulationOptions::default()
    };
    let (column, motion): (Column, Box<dyn GroundMotion>) = match name {
        "a" => {
            opts.duration = 3.0;
            opts.initial_angles = Some(vec![0.15]);
            opts.model.n_impacts = 1;
            let col = Column::new(vec![Block::rectangle(0.2, 0.6, 100.0)]).unwrap();
            (col, Box::new(NoMotion))
        }
        "b" => {
            opts.duration = 3.0;
            opts.model.n_impacts = 1;
            let (ap, tp) = (1.5 * 9.81 / 3.0, 0.3);
            let col = Column::new(vec![Block::rectangle(0.2, 0.6, 100.0)]).unwrap();
            let m = FnMotion(
                move |t: f64| {
                    if (0.0..=tp).contains(&t) {
                        ap * (pi * t / tp).sin()
                    } else {
                        0.0
                    }
                },
                tp,
            );
            (col, Box::new(m))
        }
        "c" => {
            opts.duration = 1.5;
            opts.initial_angles = Some(vec![0.0, -0.153]);
            opts.model.n_impacts = 2;
            let b = granite(0.1, 0.3, 0.2);
            (Column::new(vec![b, b]).unwrap(), Box::new(NoMotion))
        }
        "d" => {
            opts.duration = 2.0;
            opts.model.n_impacts = 2;
            let (d, period) = (0.045, 0.6);
            let w = 2.0 * pi / period;
            let b = granite(0.1, 0.2, 0.3);
            let m = FnMotion(
                move |t: f64| {
                    if (0.0..=period).contains(&t) {
                        -d * w * w * (w * t).sin()
                    } else {
                        0.0
                    }
                },
                period,
            );
            (Column::new(vec![b, b, b]).unwrap(), Box::new(m))
        }
        _ => unreachable!(),
    };
    let out = simulate(&column, motion.as_ref(), &opts, None).expect("driver runs");
    let events = out
        .events
        .iter()
        .filter_map(|e| {
            let kind = match e.kind {
                EventKind::Opening => "opening",
                EventKind::Impact => "impact",
                EventKind::Settled => "settled",
                _ => return None,
            };
            Some(Ev {
                kind: kind.to_string(),
                t: e.t,
                interface: e.interface.expect("interface of the event"),
                after: e.statuses_after.iter().map(|&s| status_value(s)).collect(),
            })
        })
        .collect();
    let stop = match out.stop_reason {
        StopReason::Duration => "duration",
        StopReason::Overturned { .. } => "overturned",
        other => panic!("scene {name}: the driver stopped with {other:?}"),
    };
    SceneResult {
        events,
        stop: stop.to_string(),
        t_end: out.t_end,
        peak: out.peak_block_rotation.clone(),
    }
}

const RATIOS: [&str; 3] = ["100", "1000", "10000"];

fn same_sequence(h: &SceneResult, d: &SceneResult) -> bool {
    h.events.len() == d.events.len()
        && h.events
            .iter()
            .zip(&d.events)
            .all(|(x, y)| (&x.kind, x.interface, &x.after) == (&y.kind, y.interface, &y.after))
}

#[test]
fn stiff_recipe_converges_to_the_rigid_driver() {
    let out = common::build_and_run("c_examples/stiff_blocks.c", &[], false);
    let runs = parse(&out);
    let dt = 1e-4;
    for name in ["a", "b", "c"] {
        let d = driver_scene(name);
        let mut previous = f64::INFINITY;
        for ratio in RATIOS {
            let key = format!("{name}_recipe_r{ratio}");
            let h = runs
                .get(&key)
                .unwrap_or_else(|| panic!("{key} missing:\n{out}"));
            let max_dt = h
                .events
                .iter()
                .zip(&d.events)
                .map(|(x, y)| (x.t - y.t).abs())
                .fold(0.0_f64, f64::max);
            let max_peak = h
                .peak
                .iter()
                .zip(&d.peak)
                .map(|(x, y)| (x - y).abs() / y.abs().max(1e-12))
                .fold(0.0_f64, f64::max);
            eprintln!(
                "{key}: {} events (driver {}), max |dt| = {max_dt:.3e} s, peak rel. diff \
                 {max_peak:.3e}, stop {} / {}",
                h.events.len(),
                d.events.len(),
                h.stop,
                d.stop
            );
            assert!(
                same_sequence(h, &d),
                "{key}: sequences differ\nstiff {:?}\ndriver {:?}",
                h.events,
                d.events
            );
            assert_eq!(h.stop, d.stop, "{key}: stop");
            assert!(
                max_dt < previous,
                "{key}: event times do not converge ({max_dt} after {previous})"
            );
            previous = max_dt;
            if ratio == "10000" {
                assert!(max_dt <= 0.1 * dt, "{key}: event times {max_dt} s apart");
                assert!(
                    max_peak <= 0.01,
                    "{key}: peaks {:?} vs {:?}",
                    h.peak,
                    d.peak
                );
            }
        }
        if name != "a" {
            for ratio in RATIOS {
                let key = format!("{name}_naive_r{ratio}");
                let h = runs
                    .get(&key)
                    .unwrap_or_else(|| panic!("{key} missing:\n{out}"));
                eprintln!(
                    "{key}: {} events (driver {}), stop {}",
                    h.events.len(),
                    d.events.len(),
                    h.stop
                );
                assert!(
                    !same_sequence(h, &d),
                    "{key}: the naive coupling no longer chatters here; revisit docs/opensees.md"
                );
            }
        }
    }
}
