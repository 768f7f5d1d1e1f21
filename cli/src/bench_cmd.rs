//! `rocking bench accuracy`: error against time step and against run time for the four
//! integrators and the two event locators, on three reference scenes, with the observed order of
//! convergence, an optional comparison with a scipy `solve_ivp` peer, and the comparison of the
//! exact Lagrangian equations with the thesis's Eq. 6.
//!
//! Scenes (the scipy peer in `bench/peer/single_block_scipy.py` mirrors (a) and (b); its output
//! echoes the parameters and they are checked here):
//! - (a) a uniform block 0.5 × 2 m (100 kg) released from rest at 0.6 δ about its right corner,
//!   Housner impacts: exact reference by quadrature
//!   ([`rocking::driver::reference::SingleBlockExact`]);
//! - (b) a uniform block 1 × 4 m (10 t) under a half sine of 4 m/s² lasting 0.8 s, 6 s,
//!   Housner impacts: reference DOP853 + Hermite (events refined by re-integration) at a small
//!   time step, its spread against twice that step and, in the full run, its difference from
//!   RK4 + Hermite at 0.1 ms (an independent method and locator) reported;
//! - (c) a three-block column (0.5 × 1.0, 0.4 × 0.8, 0.3 × 0.6 m; 600, 300, 130 kg) under a full
//!   sine of 4 m/s², half period 0.3 s, two consecutive impacts, 0.5 s: reference likewise.
//!
//! Every scene fixes the settling interval at 10 ms instead of the default four time steps, so
//! that the coarse steps of the grid (up to 0.2 s) do not settle a block that is still rocking:
//! the same model at every step. A run that fails (a driver error) is reported as such.
//!
//! Measures per run: the largest error in the times of the first `K` impacts (the impact sequence
//! must match the reference's, interface by interface, or the error is reported as "sequence
//! differs"), the error in the peak rotation (scene (a): the swing after the first impact; (b),
//! (c): the largest over the run and over the blocks), refined between history samples by cubic
//! Hermite interpolation of the block angle (the driver's own `peak_block_rotation` is sampled at
//! step ends), and the relative error in the kinetic energy lost in the first `K` impacts. Wall
//! time: the best of several repetitions of the whole simulation (with the history about every
//! 0.1 ms, which the peak needs; at steps above 0.1 ms the history has every step and the peak's
//! error includes the cubic interpolation's `O(dt⁴)` between step ends).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rocking::driver::reference::SingleBlockExact;
use rocking::driver::{
    self, EventKind, EventLocator, InitialState, Integrator, Outcome, PhysicsOptions, Recording,
    SimulationOptions, StoppingOptions,
};
use rocking::ground::excitation::{Excitation, Pulse};
use rocking::ground::FnMotion;
use rocking::model::column::{Block, Column, GRAVITY};
use rocking::model::single_block::housner_mu;
use serde_json::Value;

use crate::output::write_atomic;
use crate::plot::{Chart, Series, Style, COLORS};

/// Options of `rocking bench accuracy`.
pub struct AccuracyArgs {
    /// The Markdown report.
    pub out: PathBuf,
    /// The error-against-run-time chart (.svg or .png); one more file per extra scene.
    pub plot: Option<PathBuf>,
    /// A reduced grid (a few seconds).
    pub quick: bool,
    /// Results of the scipy peer (`bench/peer/results.json`).
    pub peer: Option<PathBuf>,
}

const SCENE_A: (f64, f64, f64) = (0.25, 1.0, 100.0); // half width, half height, mass
const SCENE_A_RELEASE: f64 = 0.6; // fraction of δ
const SCENE_B: (f64, f64, f64) = (0.5, 2.0, 10_000.0);
const SCENE_B_PULSE: (f64, f64) = (4.0, 0.8); // amplitude (m/s²), half period (s)
const SCENE_B_DURATION: f64 = 6.0;
const K_IMPACTS: usize = 5;
/// Settling interval of every scene (s): fixed rather than four time steps (see the module doc).
const SETTLE_INTERVAL: f64 = 1e-2;

/// What a run is judged by.
#[derive(Clone, Debug, Default)]
struct Metrics {
    /// Times and interfaces of the impacts (all of them).
    impacts: Vec<(f64, usize)>,
    /// Kinetic energy lost at each impact (J).
    losses: Vec<f64>,
    /// Peak rotation per block (as the scene defines it) (rad).
    peak: Vec<f64>,
    overturned: bool,
}

#[derive(Clone, Copy, Debug, Default)]
struct Errors {
    impact: f64,
    peak: f64,
    energy: f64,
}

struct BenchScene {
    key: &'static str,
    title: String,
    column: Column,
    excitation: Excitation,
    options: SimulationOptions,
    /// Peak measured after the first impact (free rocking) instead of over the whole run.
    peak_after_first_impact: bool,
}

impl BenchScene {
    fn run(
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

    fn metrics(&self, out: &Outcome) -> Metrics {
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

/// Largest |block angle| per block after `from`, refined between consecutive samples with no
/// event in between by the cubic Hermite interpolant of (angle, rate).
fn refined_peaks(h: &driver::History, from: f64, events: &[f64]) -> Vec<f64> {
    let n = h.n_interfaces;
    let mut peaks = vec![0.0_f64; n];
    let block_rate = |i: usize, j: usize| -> f64 {
        let r = &h.rates[i * 2 * n..(i + 1) * 2 * n];
        (0..=j).map(|k| r[k] + r[n + k]).sum()
    };
    for i in 0..h.len() {
        if h.t[i] < from {
            continue;
        }
        for (j, p) in peaks.iter_mut().enumerate() {
            *p = p.max(h.block_angles_at(i)[j].abs());
        }
        if i + 1 == h.len()
            || h.statuses[i * n..(i + 1) * n] != h.statuses[(i + 1) * n..(i + 2) * n]
        {
            continue;
        }
        let (t0, t1) = (h.t[i], h.t[i + 1]);
        if events.iter().any(|&te| te > t0 && te <= t1) {
            continue;
        }
        let dt = t1 - t0;
        for (j, p) in peaks.iter_mut().enumerate() {
            let (y0, y1) = (h.block_angles_at(i)[j], h.block_angles_at(i + 1)[j]);
            let (d0, d1) = (block_rate(i, j) * dt, block_rate(i + 1, j) * dt);
            if d0 * d1 >= 0.0 {
                continue;
            }
            // y(s) = h00 y0 + h10 d0 + h01 y1 + h11 d1; y'(s) = a s² + b s + c.
            let a = 6.0 * y0 + 3.0 * d0 - 6.0 * y1 + 3.0 * d1;
            let b = -6.0 * y0 - 4.0 * d0 + 6.0 * y1 - 2.0 * d1;
            let c = d0;
            let roots = if a.abs() < 1e-300 {
                vec![-c / b]
            } else {
                let disc = (b * b - 4.0 * a * c).max(0.0).sqrt();
                vec![(-b + disc) / (2.0 * a), (-b - disc) / (2.0 * a)]
            };
            for s in roots {
                if (0.0..=1.0).contains(&s) {
                    let s2 = s * s;
                    let s3 = s2 * s;
                    let y = (2.0 * s3 - 3.0 * s2 + 1.0) * y0
                        + (s3 - 2.0 * s2 + s) * d0
                        + (-2.0 * s3 + 3.0 * s2) * y1
                        + (s3 - s2) * d1;
                    *p = p.max(y.abs());
                }
            }
        }
    }
    peaks
}

fn errors(m: &Metrics, r: &Metrics) -> Errors {
    let k = K_IMPACTS.min(r.impacts.len());
    let same = m.impacts.len() >= k
        && m.impacts[..k]
            .iter()
            .zip(&r.impacts[..k])
            .all(|(a, b)| a.1 == b.1);
    let impact = if same {
        m.impacts[..k]
            .iter()
            .zip(&r.impacts[..k])
            .map(|(a, b)| (a.0 - b.0).abs())
            .fold(0.0, f64::max)
    } else {
        f64::NAN
    };
    let energy = if same && k > 0 {
        let d: f64 = m.losses[..k].iter().sum();
        let dr: f64 = r.losses[..k].iter().sum();
        (d - dr).abs() / dr
    } else {
        f64::NAN
    };
    let peak = if m.peak.len() == r.peak.len() && m.overturned == r.overturned {
        m.peak
            .iter()
            .zip(&r.peak)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    } else {
        f64::NAN
    };
    Errors {
        impact,
        peak,
        energy,
    }
}

fn scene_a() -> BenchScene {
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

fn exact_a() -> Metrics {
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

fn scene_b() -> BenchScene {
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

fn scene_c() -> BenchScene {
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

fn integrators() -> [(Integrator, &'static str); 4] {
    [
        (Integrator::WilsonTheta { theta: 1.4 }, "Wilson θ"),
        (Integrator::Newmark, "Newmark"),
        (Integrator::Rk4, "RK4"),
        (Integrator::Dop853, "DOP853"),
    ]
}

fn locators() -> [(EventLocator, &'static str); 2] {
    [
        (EventLocator::Linear, "linear"),
        (EventLocator::Hermite, "Hermite"),
    ]
}

/// Best wall time (s) of repeated runs: at least `min_reps`, more while the total stays under
/// `budget` seconds (at most 20).
fn best_time(min_reps: usize, budget: f64, mut f: impl FnMut()) -> f64 {
    let mut best = f64::INFINITY;
    let mut total = 0.0;
    let mut reps = 0;
    while reps < min_reps || (total < budget && reps < 20) {
        let s = Instant::now();
        f();
        let e = s.elapsed().as_secs_f64();
        best = best.min(e);
        total += e;
        reps += 1;
    }
    best
}

struct Row {
    integrator: &'static str,
    locator: &'static str,
    dt: f64,
    wall: f64,
    err: Errors,
    /// The driver's error, when the run failed.
    failed: Option<String>,
}

struct SceneResult {
    scene: BenchScene,
    reference: String,
    /// Difference between the reference and the same at twice its step (None: exact).
    reference_spread: Option<Errors>,
    reference_impacts: Vec<(f64, usize)>,
    reference_peak: Vec<f64>,
    rows: Vec<Row>,
    /// DOP853 + Hermite on [`LADDER`] (full run only).
    ladder: Vec<(f64, Errors)>,
    peer: Vec<PeerRow>,
}

/// Coarse steps (s) on which DOP853's order is observed: on the grid its error reaches the
/// references' accuracy within two steps.
const LADDER: [f64; 5] = [0.2, 0.16, 0.12, 0.1, 0.08];

/// The observed orders of the grid use the steps up to this (s): the coarser ones are there for
/// the comparisons at equal error, and are pre-asymptotic for the low-order methods.
const ORDER_MAX_DT: f64 = 1.0001e-2;

/// Floors of the observed orders: 10× the reference's own spread, and round-off (1e-12 of the
/// quantity).
fn floors(r: &SceneResult) -> Errors {
    let spread = r.reference_spread.unwrap_or_default();
    let t_last = r.reference_impacts.last().map_or(1.0, |i| i.0);
    let peak = r.reference_peak.iter().copied().fold(0.0, f64::max);
    Errors {
        impact: (10.0 * nan0(spread.impact)).max(1e-12 * t_last),
        peak: (10.0 * nan0(spread.peak)).max(1e-12 * peak),
        energy: (10.0 * nan0(spread.energy)).max(1e-12),
    }
}

struct PeerRow {
    method: String,
    rtol: f64,
    atol: f64,
    wall: f64,
    err: Errors,
    /// The scipy run raised this error.
    failed: Option<String>,
}

/// Observed order: least-squares slope of log(error) against log(dt), `points` in decreasing dt,
/// over the leading run of finite errors above `floor` that keep decreasing (past it the error
/// has reached round-off or the reference's own error).
fn observed_order(points: &[(f64, f64)], floor: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = Vec::new();
    for p in points {
        let ok = p.1.is_finite() && p.1 > floor && pts.last().is_none_or(|l| p.1.ln() < l.1);
        if !ok {
            break;
        }
        pts.push((p.0.ln(), p.1.ln()));
    }
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    Some(sxy / sxx)
}

/// Time a curve needs to reach `err`, on the Pareto front of `(time, error)` points, by
/// interpolation in log-log. `None` if `err` is below every point.
fn time_at_error(points: &[(f64, f64)], err: f64) -> Option<(f64, bool)> {
    let mut pts: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|p| p.1.is_finite() && p.1 > 0.0)
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Pareto front: time ascending, error strictly descending.
    let mut front: Vec<(f64, f64)> = Vec::new();
    for p in pts {
        if front.last().is_none_or(|l| p.1 < l.1) {
            front.push(p);
        }
    }
    let first = *front.first()?;
    if err >= first.1 {
        // Reached already by the cheapest run: its time is an upper bound.
        return Some((first.0, true));
    }
    for w in front.windows(2) {
        let (a, b) = (w[0], w[1]);
        if err <= a.1 && err >= b.1 {
            let f = (err.ln() - a.1.ln()) / (b.1.ln() - a.1.ln());
            return Some(((a.0.ln() + f * (b.0.ln() - a.0.ln())).exp(), false));
        }
    }
    None
}

fn fmt_err(v: f64) -> String {
    if v.is_nan() {
        "sequence differs".into()
    } else {
        format!("{v:.2e}")
    }
}

fn fmt_ratio(r: f64) -> String {
    if r < 10.0 {
        format!("{r:.1}")
    } else {
        format!("{r:.0}")
    }
}

fn fmt_time(s: f64) -> String {
    if s < 1e-3 {
        format!("{:.1} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.2} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

/// Runs the command.
pub fn run(args: &AccuracyArgs) -> Result<(), String> {
    if let Some(p) = &args.plot {
        match p.extension().and_then(|e| e.to_str()) {
            Some("svg") | Some("png") => {}
            _ => return Err(format!("--plot {}: must end in .svg or .png", p.display())),
        }
    }
    let dts: Vec<f64> = if args.quick {
        vec![8e-3, 4e-3, 2e-3, 1e-3]
    } else {
        vec![
            2e-1, 1e-1, 5e-2, 2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5,
        ]
    };
    let ref_dt = if args.quick { 1e-3 } else { 5e-4 };
    let (min_reps, budget) = if args.quick { (1, 0.0) } else { (3, 0.3) };
    let peer = match &args.peer {
        Some(p) => Some(read_peer(p)?),
        None => None,
    };

    let started = Instant::now();
    let mut results = Vec::new();
    for scene in [scene_a(), scene_b(), scene_c()] {
        let dop = Integrator::Dop853;
        let herm = EventLocator::Hermite;
        let (reference, ref_text, spread) = if scene.key == "a" {
            (
                exact_a(),
                "exact (quadrature of the single-block equation)".to_string(),
                None,
            )
        } else {
            let r = scene.metrics(&scene.run(dop, herm, ref_dt)?);
            let r2 = scene.metrics(&scene.run(dop, herm, 2.0 * ref_dt)?);
            let spread = errors(&r2, &r);
            let mut text = format!(
                "DOP853 + Hermite (refined) at dt = {ref_dt:.0e} s (against dt = {:.0e} s: impact times {}, peak {}, energy {}",
                2.0 * ref_dt,
                fmt_err(spread.impact),
                fmt_err(spread.peak),
                fmt_err(spread.energy)
            );
            if !args.quick {
                let rk = 1e-4;
                let other = errors(&scene.metrics(&scene.run(Integrator::Rk4, herm, rk)?), &r);
                let _ = write!(
                    text,
                    "; against RK4 + Hermite at dt = {rk:.0e} s: impact times {}, peak {}, energy {}",
                    fmt_err(other.impact),
                    fmt_err(other.peak),
                    fmt_err(other.energy)
                );
            }
            text.push(')');
            (r, text, Some(spread))
        };
        eprintln!("{}: reference {ref_text}", scene.title);
        let mut rows = Vec::new();
        for (integ, iname) in integrators() {
            for (loc, lname) in locators() {
                for &dt in &dts {
                    let (err, wall, failed) = match scene.run(integ, loc, dt) {
                        Ok(out) => (
                            errors(&scene.metrics(&out), &reference),
                            best_time(min_reps, budget, || {
                                std::hint::black_box(scene.run(integ, loc, dt).unwrap());
                            }),
                            None,
                        ),
                        Err(e) => {
                            let nan = Errors {
                                impact: f64::NAN,
                                peak: f64::NAN,
                                energy: f64::NAN,
                            };
                            (nan, f64::NAN, Some(e))
                        }
                    };
                    rows.push(Row {
                        integrator: iname,
                        locator: lname,
                        dt,
                        wall,
                        err,
                        failed,
                    });
                }
            }
        }
        let mut ladder = Vec::new();
        if !args.quick {
            for dt in LADDER {
                let err = match scene.run(dop, herm, dt) {
                    Ok(out) => errors(&scene.metrics(&out), &reference),
                    Err(_) => Errors {
                        impact: f64::NAN,
                        peak: f64::NAN,
                        energy: f64::NAN,
                    },
                };
                ladder.push((dt, err));
            }
        }
        let mut peer_rows = Vec::new();
        if let Some(p) = &peer {
            peer_rows = peer_rows_for(p, &scene, &reference)?;
        }
        results.push(SceneResult {
            scene,
            reference: ref_text,
            reference_spread: spread,
            reference_impacts: reference.impacts[..K_IMPACTS.min(reference.impacts.len())].to_vec(),
            reference_peak: reference.peak.clone(),
            rows,
            ladder,
            peer: peer_rows,
        });
    }
    let velocity = if args.quick {
        None
    } else {
        Some(velocity_terms_section()?)
    };
    let text = report(
        args,
        &results,
        velocity.as_deref(),
        &dts,
        started.elapsed().as_secs_f64(),
    );
    write_atomic(&args.out, text.as_bytes())?;
    if let Some(p) = &args.plot {
        for (i, r) in results.iter().enumerate() {
            let path = if i == 0 {
                p.clone()
            } else {
                sibling(p, r.scene.key)
            };
            chart(r).write(&path)?;
        }
    }
    println!(
        "wrote {} ({:.1} s)",
        args.out.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// `docs/accuracy.svg` → `docs/accuracy_b.svg`.
fn sibling(p: &Path, key: &str) -> PathBuf {
    let stem = p.file_stem().and_then(|s| s.to_str()).unwrap_or("accuracy");
    let ext = p.extension().and_then(|s| s.to_str()).unwrap_or("svg");
    p.with_file_name(format!("{stem}_{key}.{ext}"))
}

fn chart(r: &SceneResult) -> Chart {
    let mut series = Vec::new();
    let mut c = 0;
    for (_, iname) in integrators() {
        for (_, lname) in locators() {
            let points: Vec<(f64, f64)> = r
                .rows
                .iter()
                .filter(|x| x.integrator == iname && x.locator == lname && x.err.impact > 0.0)
                .map(|x| (x.wall, x.err.impact))
                .collect();
            series.push(Series {
                name: format!("{iname}, {lname}"),
                points,
                style: if lname == "linear" {
                    Style::Dashed
                } else {
                    Style::Line
                },
                color: COLORS[c / 2],
            });
            c += 1;
        }
    }
    let mut methods: Vec<&str> = r.peer.iter().map(|p| p.method.as_str()).collect();
    methods.dedup();
    for (i, m) in methods.iter().enumerate() {
        series.push(Series {
            name: format!("scipy {m}"),
            points: r
                .peer
                .iter()
                .filter(|p| p.method == *m && p.err.impact > 0.0)
                .map(|p| (p.wall, p.err.impact))
                .collect(),
            style: Style::Line,
            color: COLORS[4 + i.min(3)],
        });
    }
    Chart {
        title: format!(
            "Scene ({}): error in impact times against run time",
            r.scene.key
        ),
        x_label: "wall time (s), best of repetitions".into(),
        y_label: "largest error in the first impact times (s)".into(),
        x_log: true,
        y_log: true,
        series,
        markers: vec![],
    }
}

struct PeerData {
    scenes: Value,
    failures: Vec<Value>,
}

fn read_peer(path: &Path) -> Result<PeerData, String> {
    let text =
        std::fs::read_to_string(path).map_err(|e| format!("--peer {}: {e}", path.display()))?;
    let v: Value =
        serde_json::from_str(&text).map_err(|e| format!("--peer {}: {e}", path.display()))?;
    let scenes = v
        .get("scenes")
        .cloned()
        .ok_or_else(|| format!("--peer {}: no \"scenes\"", path.display()))?;
    let failures = v
        .get("failures")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    Ok(PeerData { scenes, failures })
}

fn num(v: &Value, key: &str) -> Result<f64, String> {
    v.get(key)
        .and_then(Value::as_f64)
        .ok_or_else(|| format!("peer results: missing number {key:?}"))
}

fn nums(v: &Value, key: &str) -> Result<Vec<f64>, String> {
    v.get(key)
        .and_then(Value::as_array)
        .ok_or_else(|| format!("peer results: missing array {key:?}"))?
        .iter()
        .map(|x| x.as_f64().ok_or_else(|| format!("peer results: {key:?}")))
        .collect()
}

fn peer_rows_for(
    p: &PeerData,
    scene: &BenchScene,
    reference: &Metrics,
) -> Result<Vec<PeerRow>, String> {
    let Some(s) = p.scenes.get(scene.key) else {
        return Ok(vec![]);
    };
    // The peer must have simulated the same scene.
    let params = s.get("parameters").ok_or("peer results: no parameters")?;
    let blk = scene.column.blocks()[0];
    let mut expected = vec![
        ("width", blk.width),
        ("height", blk.height),
        ("mass", blk.mass),
        ("duration", scene.options.stopping.duration),
        ("mu", housner_mu(0.5 * blk.height, 0.5 * blk.width)),
        ("gravity", scene.options.physics.gravity),
    ];
    if let Some(a) = &scene.options.initial.angles {
        expected.push(("theta0", a[0]));
    }
    if let Excitation::Pulse(Pulse::HalfSines {
        amplitude,
        half_period,
        ..
    }) = scene.excitation
    {
        expected.push(("amplitude", amplitude));
        expected.push(("half_period", half_period));
    }
    for (k, v) in expected {
        let got = num(params, k)?;
        if (got - v).abs() > 1e-12 * v.abs().max(1.0) {
            return Err(format!(
                "peer results, scene ({}): {k} = {got}, the bench uses {v}",
                scene.key
            ));
        }
    }
    let mut rows = Vec::new();
    for f in p
        .failures
        .iter()
        .filter(|f| f.get("scene").and_then(Value::as_str) == Some(scene.key))
    {
        rows.push(PeerRow {
            method: f
                .get("method")
                .and_then(Value::as_str)
                .unwrap_or("?")
                .to_string(),
            rtol: num(f, "rtol")?,
            atol: f64::NAN,
            wall: f64::NAN,
            err: Errors::default(),
            failed: Some(
                f.get("error")
                    .and_then(Value::as_str)
                    .unwrap_or("?")
                    .to_string(),
            ),
        });
    }
    for run in s
        .get("runs")
        .and_then(Value::as_array)
        .ok_or("peer results: no runs")?
    {
        let times = nums(run, "impact_times")?;
        let losses = nums(run, "impact_losses")?;
        let peak_key = if scene.peak_after_first_impact {
            "peak_after_first_impact"
        } else {
            "peak"
        };
        let m = Metrics {
            impacts: times.iter().map(|&t| (t, 0)).collect(),
            losses,
            peak: vec![num(run, peak_key)?],
            overturned: run
                .get("overturned")
                .and_then(Value::as_bool)
                .unwrap_or(false),
        };
        rows.push(PeerRow {
            method: run
                .get("method")
                .and_then(Value::as_str)
                .unwrap_or("?")
                .to_string(),
            rtol: num(run, "rtol")?,
            atol: num(run, "atol")?,
            wall: num(run, "wall_s")?,
            err: errors(&m, reference),
            failed: None,
        });
    }
    Ok(rows)
}

fn report(
    args: &AccuracyArgs,
    results: &[SceneResult],
    velocity: Option<&str>,
    dts: &[f64],
    elapsed: f64,
) -> String {
    let mut s = String::new();
    let cmd = format!(
        "rocking bench accuracy{} --out {}{}{}",
        if args.quick { " --quick" } else { "" },
        args.out.display(),
        args.plot
            .as_ref()
            .map(|p| format!(" --plot {}", p.display()))
            .unwrap_or_default(),
        args.peer
            .as_ref()
            .map(|p| format!(" --peer {}", p.display()))
            .unwrap_or_default(),
    );
    let _ = writeln!(s, "# Accuracy: error against time step and run time\n");
    let _ = writeln!(
        s,
        "Generated by `{cmd}` (release build; {elapsed:.0} s). Every figure below is measured by that run; \
         wall times are the best of several repetitions of the whole simulation on a shared 2-core \
         machine, so compare ratios within this file only.\n"
    );
    let _ = writeln!(
        s,
        "Errors: **impact** = largest |Δt| over the first {K_IMPACTS} impacts (\"sequence differs\" when the \
         run's impacts are not the reference's, interface by interface); **peak** = largest |Δ| of \
         the peak block rotation (scene (a): the swing after the first impact), refined between \
         history samples by cubic Hermite interpolation; **energy** = relative error in the kinetic \
         energy lost in the first {K_IMPACTS} impacts. Time steps: {}. Every scene fixes the settling \
         interval at {} ms (not the default four time steps), so that the coarse steps do not settle a \
         block that is still rocking.\n",
        dts.iter()
            .map(|d| format!("{d:.0e}"))
            .collect::<Vec<_>>()
            .join(", "),
        SETTLE_INTERVAL * 1e3
    );
    let _ = writeln!(s, "## Scenes and references\n");
    for r in results {
        let _ = writeln!(s, "- {}: reference {}.", r.scene.title, r.reference);
    }
    let _ = writeln!(s, "\n## Observed order of convergence\n");
    let _ = writeln!(
        s,
        "Least-squares slope of log(error) against log(dt) over the leading time steps from 1e-2 s \
         down whose error keeps falling and stays above a floor (10× the reference's own spread, and 1e-12 of the \
         quantity for round-off). RK4 + Hermite reaches the floor after few steps, so its slope uses \
         few points, and DOP853 + Hermite within two steps (see the ladder below); \"—\": fewer \
         than three usable points. At steps above 1e-4 s the history has one sample per step and \
         the peak's error includes the cubic interpolation between samples (`O(dt⁴)`), whatever \
         the integrator.\n"
    );
    let _ = writeln!(
        s,
        "| scene | integrator | locator | impact times | peak rotation | energy |\n|---|---|---|---:|---:|---:|"
    );
    for r in results {
        let floor = floors(r);
        for (_, iname) in integrators() {
            for (_, lname) in locators() {
                let rows: Vec<&Row> = r
                    .rows
                    .iter()
                    .filter(|x| x.integrator == iname && x.locator == lname && x.dt <= ORDER_MAX_DT)
                    .collect();
                let ord = |f: &dyn Fn(&Errors) -> f64, fl: f64| {
                    let pts: Vec<(f64, f64)> = rows.iter().map(|x| (x.dt, f(&x.err))).collect();
                    observed_order(&pts, fl)
                        .map(|o| format!("{o:.2}"))
                        .unwrap_or_else(|| "—".into())
                };
                let _ = writeln!(
                    s,
                    "| ({}) | {iname} | {lname} | {} | {} | {} |",
                    r.scene.key,
                    ord(&|e| e.impact, floor.impact),
                    ord(&|e| e.peak, floor.peak),
                    ord(&|e| e.energy, floor.energy),
                );
            }
        }
    }
    if results.iter().any(|r| !r.ladder.is_empty()) {
        let _ = writeln!(
            s,
            "\nDOP853 + Hermite (events refined by re-integration) on coarser steps, where its error \
             is still above the floor: largest error of the impact times (s) and the observed order \
             (least-squares slope over the leading points above the floor).\n"
        );
        let _ = writeln!(
            s,
            "| scene | {} | order |\n|---|{}---:|",
            LADDER
                .iter()
                .map(|d| format!("dt = {d} s"))
                .collect::<Vec<_>>()
                .join(" | "),
            "---:|".repeat(LADDER.len())
        );
        for r in results.iter().filter(|r| !r.ladder.is_empty()) {
            let pts: Vec<(f64, f64)> = r.ladder.iter().map(|(d, e)| (*d, e.impact)).collect();
            let _ = writeln!(
                s,
                "| ({}) | {} | {} |",
                r.scene.key,
                r.ladder
                    .iter()
                    .map(|(_, e)| fmt_err(e.impact))
                    .collect::<Vec<_>>()
                    .join(" | "),
                observed_order(&pts, floors(r).impact)
                    .map(|o| format!("{o:.2}"))
                    .unwrap_or_else(|| "—".into())
            );
        }
    }
    for r in results {
        let _ = writeln!(s, "\n## Scene {}\n", r.scene.title);
        if let Some(p) = &args.plot {
            let key = r.scene.key;
            let file = if key == "a" {
                p.clone()
            } else {
                sibling(p, key)
            };
            let _ = writeln!(
                s,
                "![error against run time, scene ({key})]({})\n",
                file.file_name()
                    .map(|f| f.to_string_lossy())
                    .unwrap_or_default()
            );
        }
        let _ = writeln!(
            s,
            "| integrator | locator | dt (s) | wall time | impact times (s) | peak rotation (rad) | energy (rel.) |\n|---|---|---:|---:|---:|---:|---:|"
        );
        for x in &r.rows {
            if let Some(e) = &x.failed {
                let _ = writeln!(
                    s,
                    "| {} | {} | {:.0e} | — | failed: {e} | — | — |",
                    x.integrator, x.locator, x.dt
                );
                continue;
            }
            let _ = writeln!(
                s,
                "| {} | {} | {:.0e} | {} | {} | {} | {} |",
                x.integrator,
                x.locator,
                x.dt,
                fmt_time(x.wall),
                fmt_err(x.err.impact),
                fmt_err(x.err.peak),
                fmt_err(x.err.energy)
            );
        }
        if !r.peer.is_empty() {
            peer_section(&mut s, r);
        }
    }
    if let Some(v) = velocity {
        s.push_str(v);
    }
    s
}

fn nan0(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

fn peer_section(s: &mut String, r: &SceneResult) {
    let _ = writeln!(
        s,
        "\n### Against scipy `solve_ivp` (bench/peer/single_block_scipy.py)\n\n\
         Speed ratio at equal error in the impact times: for each scipy run, the time the fastest \
         Rust method needs for the same error, interpolated in log-log on its error-against-time \
         front (\"≥\": that method's cheapest run, at the largest time step, is already more accurate, so the ratio \
         is at least this).\n"
    );
    let _ = writeln!(
        s,
        "| scipy | rtol | atol | wall time | impact times (s) | peak (rad) | energy (rel.) | fastest Rust at equal impact error | speed ratio |\n|---|---:|---:|---:|---:|---:|---:|---|---:|"
    );
    let mut ratios = Vec::new();
    for p in r.peer.iter().filter(|p| p.failed.is_none()) {
        let mut best: Option<(f64, bool, String)> = None;
        for (_, iname) in integrators() {
            for (_, lname) in locators() {
                let pts: Vec<(f64, f64)> = r
                    .rows
                    .iter()
                    .filter(|x| x.integrator == iname && x.locator == lname)
                    .map(|x| (x.wall, x.err.impact))
                    .collect();
                if let Some((t, bound)) = time_at_error(&pts, p.err.impact) {
                    if best.as_ref().is_none_or(|b| t < b.0) {
                        best = Some((t, bound, format!("{iname}, {lname}")));
                    }
                }
            }
        }
        let (who, ratio) = match (&best, p.err.impact.is_finite()) {
            (Some((t, bound, name)), true) => {
                let ratio = p.wall / t;
                ratios.push(ratio);
                (
                    format!("{name}: {}", fmt_time(*t)),
                    format!("{}{}×", if *bound { "≥ " } else { "" }, fmt_ratio(ratio)),
                )
            }
            _ => ("below every Rust run's error".into(), "—".into()),
        };
        let _ = writeln!(
            s,
            "| {} | {:.0e} | {:.0e} | {} | {} | {} | {} | {who} | {ratio} |",
            p.method,
            p.rtol,
            p.atol,
            fmt_time(p.wall),
            fmt_err(p.err.impact),
            fmt_err(p.err.peak),
            fmt_err(p.err.energy)
        );
    }
    for p in &r.peer {
        if let Some(e) = &p.failed {
            let _ = writeln!(
                s,
                "\nscipy {} at rtol = {:.0e} failed inside `solve_ivp`'s event location: {e}",
                p.method, p.rtol
            );
        }
    }
    if !ratios.is_empty() {
        ratios.sort_by(f64::total_cmp);
        let _ = writeln!(
            s,
            "\nSpeed ratio over the {} scipy runs with a Rust run as accurate (lower bounds \"≥\" counted at their value): smallest {}×, median {}×, largest {}×.",
            ratios.len(),
            fmt_ratio(ratios[0]),
            fmt_ratio(ratios[ratios.len() / 2]),
            fmt_ratio(ratios[ratios.len() - 1])
        );
    }
}

/// Section "Exact Lagrangian vs thesis Eq. 6".
fn velocity_terms_section() -> Result<String, String> {
    let mut s = String::new();
    let _ = writeln!(s, "\n## Exact Lagrangian vs thesis Eq. 6\n");
    let _ = writeln!(
        s,
        "Thesis Eq. 6 (`M φ̈ = q`) leaves out the velocity terms of the exact Lagrangian equations \
         (`exact_velocity_terms = true` adds them). Same scenes, Wilson θ and linear location as the \
         thesis, Hermite to check that the difference is not a location artefact.\n"
    );
    // Thesis 4.2 two-block scene, as bundled.
    let two = {
        let spec: crate::scene::SceneSpec = serde_json::from_str(include_str!(
            "../../examples/scenes/two_block_free_rocking.json"
        ))
        .map_err(|e| e.to_string())?;
        crate::scene::build(spec, Path::new("."), "two_block_free_rocking.json")
            .map_err(|e| e.to_string())?
    };
    let two_scene = BenchScene {
        key: "4.2",
        title: format!(
            "thesis 4.2 two blocks ({})",
            "examples/scenes/two_block_free_rocking.json"
        ),
        column: two.column,
        excitation: two.excitation,
        options: two.options,
        peak_after_first_impact: false,
    };
    let c = scene_c();
    let _ = writeln!(
        s,
        "| scene | locator | dt (s) | Eq. 6: first impacts (s, interface) | exact: first impacts | max |Δt| first {K_IMPACTS} | peak rotations Eq. 6 (rad) | exact | overturned Eq. 6 / exact |\n|---|---|---:|---|---|---:|---|---|---|"
    );
    for (scene, dt) in [(&two_scene, 1e-4), (&c, 1e-4)] {
        for (loc, lname) in locators() {
            let mut o = scene.options.clone();
            o.stepping.dt = dt;
            o.stepping.locator = loc;
            o.stepping.integrator = Integrator::default();
            let run = |exact: bool| -> Result<Metrics, String> {
                let mut o = o.clone();
                o.physics.exact_velocity_terms = exact;
                let exc = &scene.excitation;
                let motion = FnMotion(|t| exc.acceleration(t), exc.end_time());
                let out = driver::simulate(&scene.column, &motion, &o, None)
                    .map_err(|e| e.to_string())?;
                Ok(scene.metrics(&out))
            };
            let (a, b) = (run(false)?, run(true)?);
            let first = |m: &Metrics| {
                m.impacts
                    .iter()
                    .take(4)
                    .map(|(t, k)| format!("{t:.4} ({k})"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let e = errors(&b, &a);
            let _ = writeln!(
                s,
                "| {} | {lname} | {dt:.0e} | {} | {} | {} | {:.4?} | {:.4?} | {} / {} |",
                scene.title,
                first(&a),
                first(&b),
                fmt_err(e.impact),
                a.peak,
                b.peak,
                a.overturned,
                b.overturned
            );
        }
    }
    // Single block near its overturning boundary (half sine, 1 × 4 m, 0.8 s).
    let b = scene_b();
    let over = |amp: f64, exact: bool| -> Result<(bool, Metrics), String> {
        let mut o = b.options.clone();
        o.physics.exact_velocity_terms = exact;
        o.stepping.dt = 1e-4;
        let exc = Excitation::pulse(Pulse::half_sine(amp, SCENE_B_PULSE.1).unwrap()).unwrap();
        let motion = FnMotion(|t| exc.acceleration(t), exc.end_time());
        let out = driver::simulate(&b.column, &motion, &o, None).map_err(|e| e.to_string())?;
        Ok((out.overturned, b.metrics(&out)))
    };
    // Bisection of the overturning amplitude with Eq. 6.
    let (mut lo, mut hi) = (SCENE_B_PULSE.0, 3.0 * SCENE_B_PULSE.0);
    if over(lo, false)?.0 || !over(hi, false)?.0 {
        return Err("velocity-terms section: the bisection bracket does not bracket".into());
    }
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if over(mid, false)?.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let _ = writeln!(
        s,
        "\nSingle block 1 × 4 m, half sine of 0.8 s, Wilson θ, linear location, dt = 1e-4 s: the \
         overturning amplitude found by bisection with Eq. 6 lies in [{lo:.6}, {hi:.6}] m/s². At \
         its two ends:\n"
    );
    let _ = writeln!(
        s,
        "| amplitude (m/s²) | overturned Eq. 6 / exact | impacts Eq. 6 / exact | peak Eq. 6 / exact (rad) | max |Δt| of impacts | |Δ peak| |\n|---:|---|---|---|---:|---:|"
    );
    for amp in [lo, hi] {
        let (oa, ma) = over(amp, false)?;
        let (ob, mb) = over(amp, true)?;
        let e = errors(&mb, &ma);
        let _ = writeln!(
            s,
            "| {amp:.6} | {oa} / {ob} | {} / {} | {:.6} / {:.6} | {} | {:.1e} |",
            ma.impacts.len(),
            mb.impacts.len(),
            ma.peak[0],
            mb.peak[0],
            if ma.impacts.is_empty() {
                "no impacts".to_string()
            } else {
                fmt_err(e.impact)
            },
            (ma.peak[0] - mb.peak[0]).abs()
        );
    }
    let _ = writeln!(
        s,
        "\nWhy the velocity terms vanish for a single block: rocking about a fixed corner, the \
         block has one DOF θ and its kinetic energy is `T = ½ I_P θ̇²` with `I_P` (the inertia \
         about the corner) independent of θ. The Lagrangian velocity terms are `(∂M/∂θ) θ̇² / 2` \
         (the Christoffel symbols of `M`), zero when `M` does not depend on the configuration. \
         Physically, the centripetal acceleration `R θ̇²` of the centre points at the pivot, so its \
         force has no moment about the pivot. With two or more open DOFs `M` depends on the relative \
         angles (the upper block's pivot moves with the lower block), and the Coriolis and \
         centripetal terms do work on the DOF equations; Eq. 6 then also loses exact energy \
         conservation between impacts."
    );
    Ok(s)
}
