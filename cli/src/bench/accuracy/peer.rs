//! The scipy `solve_ivp` peer (`bench/peer/single_block_scipy.py`): its results, checked to be
//! of the same scenes, judged against the same references.

use std::path::Path;

use rocking::ground::excitation::{Excitation, Pulse};
use rocking::model::single_block::housner_mu;
use serde_json::Value;

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

pub(super) struct PeerData {
    pub(super) scenes: Value,
    pub(super) failures: Vec<Value>,
}

pub(super) fn read_peer(path: &Path) -> Result<PeerData, String> {
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

pub(super) fn num(v: &Value, key: &str) -> Result<f64, String> {
    v.get(key)
        .and_then(Value::as_f64)
        .ok_or_else(|| format!("peer results: missing number {key:?}"))
}

pub(super) fn nums(v: &Value, key: &str) -> Result<Vec<f64>, String> {
    v.get(key)
        .and_then(Value::as_array)
        .ok_or_else(|| format!("peer results: missing array {key:?}"))?
        .iter()
        .map(|x| x.as_f64().ok_or_else(|| format!("peer results: {key:?}")))
        .collect()
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
    let params = s.get("parameters").ok_or("peer results: no parameters")?;
    let blk = scene.column.blocks()[0];
    let mut expected = vec![
        ("width", blk.width),
        ("height", blk.height),
        ("mass", blk.mass),
        ("duration", scene.options.duration),
        ("mu", housner_mu(0.5 * blk.height, 0.5 * blk.width)),
        ("gravity", scene.options.gravity),
    ];
    if let Some(a) = &scene.options.initial_angles {
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
