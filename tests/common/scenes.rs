//! The C harness's machine-readable output (`EVENT`/`RESULT` lines) and the same scenes run by
//! the Rust driver, shared by `tests/harness_vs_driver.rs` and `tests/stiff_vs_rigid.rs`.

use std::collections::BTreeMap;

use rocking::driver::{
    simulate, EventKind, EventLocator, Integrator, PhysicsOptions, SimulationOptions,
    SteppingOptions, StopReason, StoppingOptions,
};
use rocking::ground::{FnMotion, GroundMotion, NoMotion};
use rocking::model::column::{Block, Column};
use rocking::Status;

/// One event as the harness prints it (`EVENT scene=… kind=… t=… interface=… after=…`).
#[derive(Debug, Clone, PartialEq)]
pub struct Ev {
    pub kind: String,
    pub t: f64,
    pub interface: usize,
    pub after: Vec<i8>,
}

#[derive(Debug, Default)]
pub struct SceneResult {
    pub events: Vec<Ev>,
    pub stop: String,
    pub t_end: f64,
    pub peak: Vec<f64>,
}

impl SceneResult {
    /// Largest difference of the times of corresponding events (pairs in order).
    pub fn max_event_time_diff(&self, other: &SceneResult) -> f64 {
        self.events
            .iter()
            .zip(&other.events)
            .map(|(x, y)| (x.t - y.t).abs())
            .fold(0.0_f64, f64::max)
    }

    /// Largest relative difference of the peak block rotations, relative to `reference`'s.
    pub fn max_peak_rel_diff(&self, reference: &SceneResult) -> f64 {
        self.peak
            .iter()
            .zip(&reference.peak)
            .map(|(x, y)| (x - y).abs() / y.abs().max(1e-12))
            .fold(0.0_f64, f64::max)
    }
}

pub fn field<'a>(line: &'a str, key: &str) -> &'a str {
    line.split_whitespace()
        .find_map(|w| w.strip_prefix(key).and_then(|r| r.strip_prefix('=')))
        .unwrap_or_else(|| panic!("no {key}= in {line}"))
}

pub fn parse(out: &str) -> BTreeMap<String, SceneResult> {
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

pub fn status_value(s: Status) -> i8 {
    match s {
        Status::OpenRight => -1,
        Status::Closed => 0,
        Status::OpenLeft => 1,
    }
}

/// The scenes of the C harness (keep in step with `scene_a` … `scene_d` there), run by the
/// Rust driver at time step `dt` (the harness uses 1e-3 s, `stiff_blocks.c` 1e-4 s).
pub fn driver_scene(name: &str, dt: f64) -> SceneResult {
    let granite = |w: f64, h: f64, t: f64| {
        let mut b = Block::rectangle(w, h, 2700.0 * w * h * t);
        b.contact_width = Some(0.096);
        b
    };
    let pi = std::f64::consts::PI;
    let mut opts = SimulationOptions {
        stepping: SteppingOptions {
            dt,
            integrator: Integrator::Newmark,
            locator: EventLocator::Hermite,
            ..SteppingOptions::default()
        },
        physics: PhysicsOptions {
            friction: f64::INFINITY,
            gravity: 9.81,
            exact_velocity_terms: false,
            ..PhysicsOptions::default()
        },
        stopping: StoppingOptions {
            continue_until_fallen: false,
            ..StoppingOptions::default()
        },
        ..SimulationOptions::default()
    };
    let (column, motion): (Column, Box<dyn GroundMotion>) = match name {
        "a" => {
            opts.stopping.duration = 3.0;
            opts.initial.angles = Some(vec![0.15]);
            opts.physics.model.n_impacts = 1;
            let col = Column::new(vec![Block::rectangle(0.2, 0.6, 100.0)]).unwrap();
            (col, Box::new(NoMotion))
        }
        "b" => {
            opts.stopping.duration = 3.0;
            opts.physics.model.n_impacts = 1;
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
            opts.stopping.duration = 1.5;
            opts.initial.angles = Some(vec![0.0, -0.153]);
            opts.physics.model.n_impacts = 2;
            let b = granite(0.1, 0.3, 0.2);
            (Column::new(vec![b, b]).unwrap(), Box::new(NoMotion))
        }
        "d" => {
            opts.stopping.duration = 2.0;
            opts.physics.model.n_impacts = 2;
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
