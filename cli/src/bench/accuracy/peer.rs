//! The scipy `solve_ivp` peer (`bench/peer/single_block_scipy.py`): its results, checked to be
//! of the same scenes, judged against the same references.

use std::collections::BTreeMap;
use std::path::Path;

use rocking::ground::excitation::{Excitation, Pulse};
use rocking::model::single_block::housner_mu;
use serde::Deserialize;

use super::metrics::{errors, Errors, Metrics};
use super::scenes::BenchScene;

pub(super) struct PeerRow {
    pub(super) method: String,
    pub(super) rtol: f64,
    pub(super) atol: f64,
    pub(super) wall: f64,
    pub(super) err: Errors,
    /// The scipy run raised this error.
    pub(super) failed: Option<String>,
}

/// `bench/peer/results.json`: per scene key, the parameters and the runs; the runs that failed.
#[derive(Deserialize)]
pub(super) struct PeerData {
    scenes: BTreeMap<String, PeerScene>,
    #[serde(default)]
    failures: Vec<Failure>,
}

#[derive(Deserialize)]
struct PeerScene {
    /// The scene as the peer simulated it (width, height, mass, duration, mu, gravity, and
    /// theta0 or amplitude and half_period).
    parameters: BTreeMap<String, f64>,
    runs: Vec<Run>,
}

/// One `solve_ivp` run.
#[derive(Deserialize)]
struct Run {
    method: String,
    rtol: f64,
    atol: f64,
    wall_s: f64,
    impact_times: Vec<f64>,
    impact_losses: Vec<f64>,
    peak: f64,
    peak_after_first_impact: f64,
    #[serde(default)]
    overturned: bool,
}

/// A run that raised inside `solve_ivp`.
#[derive(Deserialize)]
struct Failure {
    scene: String,
    method: String,
    rtol: f64,
    error: String,
}

pub(super) fn read_peer(path: &Path) -> Result<PeerData, String> {
    crate::output::read_json(path).map_err(|e| format!("--peer {e}"))
}

pub(super) fn peer_rows_for(
    p: &PeerData,
    scene: &BenchScene,
    reference: &Metrics,
) -> Result<Vec<PeerRow>, String> {
    let Some(s) = p.scenes.get(scene.key) else {
        return Ok(vec![]);
    };
    // The peer must have simulated the same scene.
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
        let got = *s
            .parameters
            .get(k)
            .ok_or_else(|| format!("peer results, scene ({}): no parameter {k:?}", scene.key))?;
        if (got - v).abs() > 1e-12 * v.abs().max(1.0) {
            return Err(format!(
                "peer results, scene ({}): {k} = {got}, the bench uses {v}",
                scene.key
            ));
        }
    }
    let mut rows = Vec::new();
    for f in p.failures.iter().filter(|f| f.scene == scene.key) {
        rows.push(PeerRow {
            method: f.method.clone(),
            rtol: f.rtol,
            atol: f64::NAN,
            wall: f64::NAN,
            err: Errors::default(),
            failed: Some(f.error.clone()),
        });
    }
    for run in &s.runs {
        let m = Metrics {
            impacts: run.impact_times.iter().map(|&t| (t, 0)).collect(),
            losses: run.impact_losses.clone(),
            peak: vec![if scene.peak_after_first_impact {
                run.peak_after_first_impact
            } else {
                run.peak
            }],
            overturned: run.overturned,
        };
        rows.push(PeerRow {
            method: run.method.clone(),
            rtol: run.rtol,
            atol: run.atol,
            wall: run.wall_s,
            err: errors(&m, reference),
            failed: None,
        });
    }
    Ok(rows)
}
