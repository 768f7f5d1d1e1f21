//! The outputs of a closed chain's run (`"arch"` or `"colonnade"` scene, the loop driver
//! `crate::driver::simulate_loop`): `summary.json`, the objects of `events.jsonl` and the joint
//! angles of `history.csv` — one definition for `rocking simulate` and the Python package's
//! `rocking.simulate`.

use std::collections::{BTreeMap, BTreeSet};

use serde::Serialize;
use serde_json::{json, Value};

use super::LoopScene;
use crate::driver::closed::{LoopEnergy, LoopEventKind, LoopOutcome};

/// What a loop run reports (`summary.json`).
#[derive(Debug, Serialize)]
pub struct LoopSummary<'a> {
    /// The scene file's path; `None` (JSON `null`) for a scene given as text.
    pub scene: Option<String>,
    pub title: &'a str,
    /// The excitation, described in words.
    pub excitation: String,
    pub collapsed: bool,
    /// Whether the closed chain at rest resists its own weight (`null` if the run never was
    /// closed at rest): `false` for an arch thinner than its minimum thickness, which collapses
    /// whatever the ground does ([`LoopOutcome::stands_under_own_weight`]).
    pub stands_under_own_weight: Option<bool>,
    /// Time at which the run ended (s).
    pub t_end: f64,
    /// Largest `|φ|` of any DOF (rad).
    pub peak_angle: f64,
    /// Events by kind ([`loop_event_name`]).
    pub events: BTreeMap<&'static str, usize>,
    /// `[joint, face]` of every hinge that opened (`-1`: about `R_k`, `+1`: about `L_k`).
    pub hinges: Vec<(usize, i8)>,
    pub statuses_end: Vec<i8>,
    /// Largest closure residual after a step (m).
    pub max_closure_residual: f64,
    /// Largest closure residual one step leaves before the projection (m).
    pub max_step_drift: f64,
    /// The energy balance (J) and its residual, the scheme's error.
    pub energy: LoopEnergyReport,
    /// The driver's time step (s).
    pub dt: f64,
    /// The scene's `min_flight` (steps), when set above zero (absent: the default, 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_flight: Option<f64>,
    /// Wall-clock time of the run (s).
    pub wall_time_s: f64,
}

/// [`LoopEnergy`] with its residual.
#[derive(Debug, Serialize)]
pub struct LoopEnergyReport {
    #[serde(flatten)]
    pub balance: LoopEnergy,
    pub residual: f64,
}

impl<'a> LoopSummary<'a> {
    /// The summary of `o`, the run of `scene` (read from `path`, if from a file) that took
    /// `wall_time_s`.
    pub fn of(
        scene: &'a LoopScene,
        path: Option<String>,
        o: &LoopOutcome,
        wall_time_s: f64,
    ) -> LoopSummary<'a> {
        let mut events = BTreeMap::new();
        for e in &o.events {
            *events.entry(loop_event_name(&e.kind)).or_insert(0) += 1;
        }
        LoopSummary {
            scene: path,
            title: &scene.title,
            excitation: scene.excitation.describe(),
            collapsed: o.collapsed,
            stands_under_own_weight: o.stands_under_own_weight,
            t_end: o.state.time,
            peak_angle: o.peak_angle,
            events,
            hinges: hinges(o),
            statuses_end: o.state.statuses.iter().map(|s| s.as_i8()).collect(),
            max_closure_residual: o.max_closure_residual,
            max_step_drift: o.max_step_drift,
            energy: LoopEnergyReport {
                balance: o.energy,
                residual: o.energy.residual(),
            },
            dt: scene.options.dt,
            min_flight: (scene.options.min_flight > 0.0).then_some(scene.options.min_flight),
            wall_time_s,
        }
    }
}

/// An event kind as the outputs name it.
pub fn loop_event_name(k: &LoopEventKind) -> &'static str {
    match k {
        LoopEventKind::Opening => "opening",
        LoopEventKind::Closing { .. } => "closing",
        LoopEventKind::Locked { .. } => "locked",
        LoopEventKind::Settled => "settled",
        LoopEventKind::Collapsed => "collapsed",
    }
}

/// The objects of `events.jsonl`: `t`, `kind`, `statuses` after; a closing (or a locked
/// closing) also `joints`, `kinetic_before`, `kinetic_after`.
pub fn loop_events(o: &LoopOutcome) -> Vec<Value> {
    o.events
        .iter()
        .map(|e| {
            let mut line = json!({
                "t": e.time, "kind": loop_event_name(&e.kind), "statuses": e.statuses,
            });
            if let LoopEventKind::Closing {
                joints,
                kinetic_before,
                kinetic_after,
            }
            | LoopEventKind::Locked {
                joints,
                kinetic_before,
                kinetic_after,
            } = &e.kind
            {
                line["joints"] = json!(joints);
                line["kinetic_before"] = json!(kinetic_before);
                line["kinetic_after"] = json!(kinetic_after);
            }
            line
        })
        .collect()
}

/// Every (joint, face) that was open after some event: `-1` about `R_k` (an arch's intrados),
/// `+1` about `L_k` (extrados).
pub fn hinges(o: &LoopOutcome) -> Vec<(usize, i8)> {
    let mut seen = BTreeSet::new();
    for e in &o.events {
        for (k, &s) in e.statuses.iter().enumerate() {
            if s != 0 {
                seen.insert((k, s));
            }
        }
    }
    seen.into_iter().collect()
}

/// The history's samples: their times and each joint's signed angle `phĭ_k + phî_k` (rad),
/// row-major `samples × n` (`history.csv`'s `angle_k`).
pub fn loop_joint_angles(o: &LoopOutcome, n: usize) -> (Vec<f64>, Vec<f64>) {
    let t = o.history.iter().map(|(t, _)| *t).collect();
    let angles = o
        .history
        .iter()
        .flat_map(|(_, phi)| (0..n).map(move |k| phi[k] + phi[n + k]))
        .collect();
    (t, angles)
}
