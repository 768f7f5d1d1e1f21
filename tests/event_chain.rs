//! Events at one instant are chained consistently (issue 11): the state that leaves an event is
//! the state the next one at the same instant receives — its configuration, and its kinetic
//! energy (a later event at the same instant may only take energy away).
//!
//! The chain used to break where a DOF that has just opened (at exactly zero angle, moving away)
//! turns back within the next step: the linear locator put the crossing at the start of that
//! step, the same instant, and the impact routine treated the DOF as grazing and zeroed its rate
//! alone — not a projection in the kinetic metric, so the energy could rise (up to 6× on ten
//! 1 × 1 m drums under MUL009 at 4.9 m/s²). See docs/robustness.md, "Events at one instant".

use std::path::Path;

use rocking::driver::{
    simulate, Event, InitialState, PhysicsOptions, Recording, SimulationOptions, SteppingOptions,
    StoppingOptions,
};
use rocking::ground::excitation::{Excitation, Pulse};
use rocking::ground::records::read_at2;
use rocking::ground::{GroundMotion, NoMotion};
use rocking::model::column::{Block, Column};
use rocking::ModelOptions;

/// Pairs of events at the same instant whose chaining breaks: `(index, reason)`.
fn broken_chains(events: &[Event]) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (i, w) in events.windows(2).enumerate() {
        let (a, b) = (&w[0], &w[1]);
        if a.t != b.t {
            continue;
        }
        if b.statuses_before != a.statuses_after {
            out.push((i, "configuration".to_string()));
        } else if b.kinetic_before > a.kinetic_after * (1.0 + 1e-9) + 1e-300 {
            out.push((
                i,
                format!(
                    "kinetic energy {:.4e} J → {:.4e} J at t = {}",
                    a.kinetic_after, b.kinetic_before, a.t
                ),
            ));
        }
    }
    out
}

fn run(name: &str, column: &Column, motion: &dyn GroundMotion, opts: SimulationOptions) -> usize {
    let opts = SimulationOptions {
        recording: Recording {
            history_every: None,
            events: true,
        },
        ..opts
    };
    let out = simulate(column, motion, &opts, None).unwrap();
    let same = out.events.windows(2).filter(|w| w[0].t == w[1].t).count();
    let broken = broken_chains(&out.events);
    println!(
        "{name}: {} events, {same} at the instant of the previous one, {} broken chains{}",
        out.events.len(),
        broken.len(),
        broken
            .first()
            .map(|(_, r)| format!(" (first: {r})"))
            .unwrap_or_default()
    );
    broken.len()
}

#[test]
fn simultaneous_events_chain() {
    let mut broken = 0;
    let two = PhysicsOptions {
        model: ModelOptions {
            n_impacts: 2,
            ..ModelOptions::default()
        },
        ..PhysicsOptions::default()
    };
    let opts = |dt: f64, duration: f64, physics: PhysicsOptions| SimulationOptions {
        physics,
        stepping: SteppingOptions {
            dt,
            ..SteppingOptions::default()
        },
        stopping: StoppingOptions {
            duration,
            ..StoppingOptions::default()
        },
        ..SimulationOptions::default()
    };
    // The bundled scenes.
    let col = Column::new(vec![Block::rectangle(1.0, 4.0, 10000.0)]).unwrap();
    let m = Excitation::pulse(Pulse::half_sine(6.0, 0.8).unwrap()).unwrap();
    broken += run(
        "single block, half sine",
        &col,
        &m,
        opts(1e-3, 8.0, PhysicsOptions::default()),
    );
    let granite = |h: f64| Block {
        contact_width: Some(0.096),
        ..Block::rectangle(0.1, h, 16.2)
    };
    broken += run(
        "thesis 4.2",
        &Column::new(vec![granite(0.3); 2]).unwrap(),
        &NoMotion,
        SimulationOptions {
            initial: InitialState {
                angles: Some(vec![0.0, 0.153]),
            },
            ..opts(1e-4, 1.5, two)
        },
    );
    broken += run(
        "thesis 4.3",
        &Column::new(vec![granite(0.2); 3]).unwrap(),
        &Excitation::pulse(Pulse::full_sine(-2.467, 0.6).unwrap()).unwrap(),
        opts(2e-4, 3.0, two),
    );
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/records/synthetic.AT2");
    let rec = read_at2(&path).unwrap().scaled_to_pga(4.0).unwrap();
    broken += run(
        "three drums, synthetic record",
        &Column::new(vec![Block::rectangle(0.6, 1.2, 1100.0); 3]).unwrap(),
        &Excitation::record(rec).unwrap(),
        opts(1e-3, 25.0, two),
    );
    // Extreme scenes: ten drums H/B = 1.2 under a pulse, thirty squat drums.
    for (n, w, h) in [(10, 1.0, 1.2), (30, 1.0, 0.4)] {
        broken += run(
            &format!("{n} drums {w} × {h}, full sine"),
            &Column::new(vec![Block::rectangle(w, h, 2500.0 * w * h); n]).unwrap(),
            &Excitation::pulse(Pulse::full_sine(6.0, 0.6).unwrap()).unwrap(),
            opts(1e-3, 5.0, two),
        );
    }
    // The case: ten 1 × 1 m drums under MUL009 at 4.9 m/s² (needs ../shared).
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/records/fema-p695/farfield/RSN953_NORTHR_MUL009.AT2");
    if let Ok(rec) = read_at2(&path) {
        broken += run(
            "ten 1 × 1 m drums, MUL009 at 4.9 m/s²",
            &Column::new(vec![Block::rectangle(1.0, 1.0, 2500.0); 10]).unwrap(),
            &Excitation::record(rec.scaled_to_pga(4.9).unwrap()).unwrap(),
            opts(1e-3, 40.0, two),
        );
    }
    assert_eq!(broken, 0, "events at one instant must chain");
}
