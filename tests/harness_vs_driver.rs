//! The C harness `c_examples/opensees_style_harness.c` (an FE-style analysis: three mass points
//! per block, `B` rebuilt every step, `rocking_reduce`, Newmark, step halving onto events, every
//! decision through the C ABI) against the Rust reference driver (`rocking::driver::simulate`)
//! on the same four scenes, with the driver set up as the harness is: Newmark (average
//! acceleration), dt = 1 ms, thesis Eq. 6 (no velocity terms), no friction check, static tipping
//! stops, the same settling rule.
//!
//! Asserted, scene by scene:
//! - the same sequence of events (kind, interface, configuration after), complete;
//! - event times within two steps (2 ms);
//! - the same stop (duration or overturning) and peak block rotations within 1 %.
//!
//! The measured agreement is far tighter (the test prints it; `cargo test --release --test
//! harness_vs_driver -- --nocapture`): the same sequences, event times within 9e-6 s (so event
//! times are also asserted within dt/10), peaks within 1.4e-5 relative, except the
//! overturning of scene d: the harness lands on static tipping (peak = atan(0.048/0.3) =
//! 0.158655 rad exactly) while the driver stops at the end of the step in which it happens
//! (0.159163 rad, 0.33 ms later), a 0.3 % difference by construction.

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

/// The scenes of the harness (keep in step with `scene_a` … `scene_d` there).
fn driver_scene(name: &str) -> SceneResult {
    let granite = |w: f64, h: f64, t: f64| {
        let mut b = Block::rectangle(w, h, 2700.0 * w * h * t);
        b.contact_width = Some(0.096);
        b
    };
    let pi = std::f64::consts::PI;
    let mut opts = SimulationOptions {
        dt: 1e-3,
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

#[test]
fn harness_agrees_with_the_driver() {
    let out = common::build_and_run("c_examples/opensees_style_harness.c", &[], false);
    let harness = parse(&out);
    let dt = 1e-3;
    for name in ["a", "b", "c", "d"] {
        let h = harness
            .get(name)
            .unwrap_or_else(|| panic!("scene {name} missing:\n{out}"));
        let d = driver_scene(name);
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
            "scene {name}: harness {} events, driver {}; max |Δt| = {:.3e} s; peak rotations \
             harness {:?} driver {:?} (max rel. diff {:.2e}); stop {} at {:.6} / {} at {:.6}",
            h.events.len(),
            d.events.len(),
            max_dt,
            h.peak,
            d.peak,
            max_peak,
            h.stop,
            h.t_end,
            d.stop,
            d.t_end
        );
        for (i, (x, y)) in h.events.iter().zip(&d.events).enumerate() {
            assert_eq!(
                (&x.kind, x.interface, &x.after),
                (&y.kind, y.interface, &y.after),
                "scene {name}, event {i}: harness {x:?}, driver {y:?}"
            );
            assert!(
                (x.t - y.t).abs() <= 2.0 * dt,
                "scene {name}, event {i}: harness t = {}, driver t = {}",
                x.t,
                y.t
            );
            // Tighter: both locate events far inside a step (measured: 9e-6 s at most, the
            // driver's opening look-ahead of 1e-3 dt in scene b); a tenth of a step catches a
            // regression to step-end or linear event location.
            assert!(
                (x.t - y.t).abs() <= 0.1 * dt,
                "scene {name}, event {i}: harness t = {}, driver t = {} (more than dt/10 apart)",
                x.t,
                y.t
            );
        }
        assert_eq!(
            h.events.len(),
            d.events.len(),
            "scene {name}: event counts differ\nharness {:?}\ndriver {:?}",
            h.events,
            d.events
        );
        assert_eq!(h.stop, d.stop, "scene {name}: stop");
        assert!(
            (h.t_end - d.t_end).abs() <= 2.0 * dt,
            "scene {name}: end {} vs {}",
            h.t_end,
            d.t_end
        );
        assert!(
            max_peak <= 0.01,
            "scene {name}: peaks {:?} vs {:?}",
            h.peak,
            d.peak
        );
    }
}
