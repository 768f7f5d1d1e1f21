//! The three reference scenes of the accuracy bench, the exact reference of scene (a), and the
//! integrators and locators compared.

use rocking::driver::reference::SingleBlockExact;
use rocking::driver::{
    self, EventKind, EventLocator, InitialState, Integrator, Outcome, PhysicsOptions, Recording,
    SimulationOptions, StoppingOptions,
};
use rocking::ground::excitation::{Excitation, Pulse};
use rocking::ground::FnMotion;
use rocking::model::column::{Block, Column, GRAVITY};
use rocking::model::single_block::housner_mu;

use super::metrics::{refined_peaks, Metrics};

pub(super) const SCENE_A: (f64, f64, f64) = (0.25, 1.0, 100.0); // half width, half height, mass
pub(super) const SCENE_A_RELEASE: f64 = 0.6; // fraction of δ
pub(super) const SCENE_B: (f64, f64, f64) = (0.5, 2.0, 10_000.0);
pub(super) const SCENE_B_PULSE: (f64, f64) = (4.0, 0.8); // amplitude (m/s²), half period (s)
pub(super) const SCENE_B_DURATION: f64 = 6.0;
pub(super) const K_IMPACTS: usize = 5;
/// Settling interval of every scene (s): fixed rather than four time steps (see the module doc).
pub(super) const SETTLE_INTERVAL: f64 = 1e-2;
pub(super) struct BenchScene {
    pub(super) key: &'static str,
    pub(super) title: String,
    pub(super) column: Column,
    pub(super) excitation: Excitation,
    pub(super) options: SimulationOptions,
    /// Peak measured after the first impact (free rocking) instead of over the whole run.
    pub(super) peak_after_first_impact: bool,
}

impl BenchScene {
    pub(super) fn run(
        &self,
        integrator: Integrator,
        locator: EventLocator,
        dt: f64,
    ) -> Result<Outcome, String> {
        let mut o = self.options.clone();
        o.stepping.integrator = integrator;
        o.stepping.locator = locator;
        o.stepping.dt = dt;
        // History about every 0.1 ms (the peak is refined between samples by cubic Hermite
        // interpolation, whose error at that spacing is far below every error measured here).
        o.recording = Recording {
            history_every: Some(((1e-4 / dt).round() as usize).max(1)),
            events: true,
        };
        let exc = &self.excitation;
        let motion = FnMotion(|t| exc.acceleration(t), exc.end_time());
        driver::simulate(&self.column, &motion, &o, None).map_err(|e| e.to_string())
    }

    pub(super) fn metrics(&self, out: &Outcome) -> Metrics {
        let mut m = Metrics {
            overturned: out.overturned,
            ..Metrics::default()
        };
        for e in &out.events {
            if e.kind == EventKind::Impact {
                m.impacts.push((e.t, e.interface.unwrap_or(usize::MAX)));
                m.losses.push(e.kinetic_before - e.kinetic_after);
            }
        }
        let from = if self.peak_after_first_impact {
            m.impacts.first().map_or(f64::INFINITY, |i| i.0)
        } else {
            f64::NEG_INFINITY
        };
        let event_times: Vec<f64> = out.events.iter().map(|e| e.t).collect();
        m.peak = out
            .history
            .as_ref()
            .map(|h| refined_peaks(h, from, &event_times))
            .unwrap_or_default();
        m
    }
}

pub(super) fn scene_a() -> BenchScene {
    let (b, h, mass) = SCENE_A;
    let exact = SingleBlockExact::new(b, h, GRAVITY);
    let theta0 = SCENE_A_RELEASE * exact.delta;
    let times = exact.impact_times(theta0, housner_mu(h, b), K_IMPACTS + 1);
    // End between impact K and K + 1.
    let duration = 0.5 * (times[K_IMPACTS - 1] + times[K_IMPACTS]);
    BenchScene {
        key: "a",
        title: format!(
            "(a) single block {} × {} m, free rocking from {SCENE_A_RELEASE} δ (exact reference)",
            2.0 * b,
            2.0 * h
        ),
        column: Column::new(vec![Block::rectangle(2.0 * b, 2.0 * h, mass)]).unwrap(),
        excitation: Excitation::None,
        options: SimulationOptions {
            stopping: StoppingOptions {
                duration,
                settle_interval: Some(SETTLE_INTERVAL),
                ..StoppingOptions::default()
            },
            physics: PhysicsOptions {
                friction: f64::INFINITY,
                ..PhysicsOptions::default()
            },
            initial: InitialState {
                angles: Some(vec![-theta0]),
            },
            ..SimulationOptions::default()
        },
        peak_after_first_impact: true,
    }
}

pub(super) fn exact_a() -> Metrics {
    let (b, h, mass) = SCENE_A;
    let exact = SingleBlockExact::new(b, h, GRAVITY);
    let theta0 = SCENE_A_RELEASE * exact.delta;
    let mu = housner_mu(h, b);
    let r = (b * b + h * h).sqrt();
    let e0 = mass * GRAVITY * r * exact.potential(theta0);
    let times = exact.impact_times(theta0, mu, K_IMPACTS);
    let mut losses = Vec::new();
    let mut e = e0;
    for _ in 0..K_IMPACTS {
        losses.push(e * (1.0 - mu * mu));
        e *= mu * mu;
    }
    Metrics {
        impacts: times.into_iter().map(|t| (t, 0)).collect(),
        losses,
        peak: vec![exact.amplitudes_after_impacts(theta0, mu, 1)[0]],
        overturned: false,
    }
}

pub(super) fn scene_b() -> BenchScene {
    let (b, h, mass) = SCENE_B;
    let (amp, tp) = SCENE_B_PULSE;
    BenchScene {
        key: "b",
        title: format!(
            "(b) single block {} × {} m, half sine {amp} m/s² × {tp} s",
            2.0 * b,
            2.0 * h
        ),
        column: Column::new(vec![Block::rectangle(2.0 * b, 2.0 * h, mass)]).unwrap(),
        excitation: Excitation::pulse(Pulse::half_sine(amp, tp).unwrap()).unwrap(),
        options: SimulationOptions {
            stopping: StoppingOptions {
                duration: SCENE_B_DURATION,
                settle_interval: Some(SETTLE_INTERVAL),
                ..StoppingOptions::default()
            },
            physics: PhysicsOptions {
                friction: f64::INFINITY,
                ..PhysicsOptions::default()
            },
            ..SimulationOptions::default()
        },
        peak_after_first_impact: false,
    }
}

pub(super) fn scene_c() -> BenchScene {
    let column = Column::new(vec![
        Block::rectangle(0.5, 1.0, 600.0),
        Block::rectangle(0.4, 0.8, 300.0),
        Block::rectangle(0.3, 0.6, 130.0),
    ])
    .unwrap();
    let mut options = SimulationOptions {
        stopping: StoppingOptions {
            duration: 0.5,
            settle_interval: Some(SETTLE_INTERVAL),
            ..StoppingOptions::default()
        },
        physics: PhysicsOptions {
            friction: f64::INFINITY,
            ..PhysicsOptions::default()
        },
        ..SimulationOptions::default()
    };
    options.physics.model.n_impacts = 2;
    BenchScene {
        key: "c",
        title: "(c) three blocks 0.5 × 1.0, 0.4 × 0.8, 0.3 × 0.6 m, full sine 4 m/s² × 2 × 0.3 s, 2 impacts".into(),
        column,
        excitation: Excitation::pulse(Pulse::full_sine(4.0, 0.3).unwrap()).unwrap(),
        options,
        peak_after_first_impact: false,
    }
}

pub(super) fn integrators() -> [(Integrator, &'static str); 4] {
    [
        (Integrator::WilsonTheta { theta: 1.4 }, "Wilson θ"),
        (Integrator::Newmark, "Newmark"),
        (Integrator::Rk4, "RK4"),
        (Integrator::Dop853, "DOP853"),
    ]
}

pub(super) fn locators() -> [(EventLocator, &'static str); 2] {
    [
        (EventLocator::Linear, "linear"),
        (EventLocator::Hermite, "Hermite"),
    ]
}
