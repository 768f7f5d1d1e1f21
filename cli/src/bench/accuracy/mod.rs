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

mod metrics;
mod peer;
mod report;
mod scenes;
mod velocity;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use rocking::driver::{EventLocator, Integrator};

use crate::output::write_atomic;
use crate::plot::{Chart, Series, Style, COLORS};
use metrics::{errors, Errors};
use peer::{peer_rows_for, read_peer, PeerRow};
use report::{fmt_err, nan0, report};
use scenes::{exact_a, integrators, locators, scene_a, scene_b, scene_c, BenchScene, K_IMPACTS};
use velocity::velocity_terms_section;

/// Options of `rocking bench accuracy`.
#[derive(Args, Debug)]
pub struct AccuracyArgs {
    /// The Markdown report.
    #[arg(long, default_value = "docs/accuracy.md")]
    pub out: PathBuf,
    /// Error against run time (.svg or .png); scenes (b), (c) go to FILE_b, FILE_c.
    #[arg(long, value_parser = crate::plot::plot_path)]
    pub plot: Option<PathBuf>,
    /// A reduced grid (a few seconds).
    #[arg(long)]
    pub quick: bool,
    /// Results of the scipy peer (bench/peer/results.json) to compare with.
    #[arg(long)]
    pub peer: Option<PathBuf>,
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

/// Runs the command.
pub fn run(args: &AccuracyArgs) -> Result<(), String> {
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
    // One series per scipy method that completed a run (failed runs come first in the peer's
    // rows: a plain dedup listed a method twice, once without points).
    let mut methods: Vec<&str> = Vec::new();
    for p in r.peer.iter().filter(|p| p.failed.is_none()) {
        if !methods.contains(&p.method.as_str()) {
            methods.push(&p.method);
        }
    }
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
        x_scale: crate::plot::Scale::Log,
        y_scale: crate::plot::Scale::Log,
        series,
        ..Chart::default()
    }
}
