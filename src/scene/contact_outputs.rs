//! The outputs of a scene run by the contact scheme (Moreau–Jean or `"scheme": "auto"`,
//! `src/contact/`): `summary.json`, the objects of `events.jsonl` and the columns of
//! `history.csv` — one definition for `rocking simulate` and the Python package's
//! `rocking.simulate`.

use std::collections::BTreeMap;

use serde::Serialize;
use serde_json::{json, Value};

use super::Scene;
use crate::contact::drums::Drums;
use crate::contact::simulation::{DrumEventKind, DrumHistory, DrumOutcome, DrumStop, JointMode};
use crate::model::column::Column;

/// What a contact-scheme run of a scene reports (`summary.json`): the event-driven summary's
/// fields where the two share a meaning, plus the slips, the top's displacement, the joints'
/// modes and the scheme's energy accounts.
#[derive(Debug, Serialize)]
pub struct ContactSummary<'a> {
    /// The scene file's path; `None` (JSON `null`) for a scene given as text.
    pub scene: Option<String>,
    pub title: &'a str,
    /// The excitation, described in words.
    pub excitation: String,
    /// `"moreau"` or `"auto"`.
    pub scheme: &'static str,
    pub overturned: bool,
    /// Time at which the run ended (s).
    pub t_end: f64,
    pub impacts: usize,
    /// Why the run stopped ([`stop_name`]).
    pub stop_reason: &'static str,
    /// The joint (or, for `fallen`, the drum) the stop concerns, if any.
    pub stop_interface: Option<usize>,
    /// Largest absolute rotation of each drum (rad).
    pub peak_block_rotation: &'a [f64],
    /// Largest absolute slip of each joint (m).
    pub peak_slip: &'a [f64],
    /// Slip of each joint at the end (m, signed).
    pub residual_slip: &'a [f64],
    /// Largest absolute horizontal displacement of the top drum's centre (m).
    pub peak_top_displacement: f64,
    /// The joints' modes at the end ([`mode_name`]).
    pub modes_end: Vec<&'static str>,
    /// Events by kind (kinds that occurred).
    pub events: BTreeMap<&'static str, usize>,
    pub energy: ContactEnergy,
    /// Scheme "auto": the hand-overs and the simulated time in the event-driven driver (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scheme_switches: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_event_driven: Option<f64>,
    /// The scheme's time step (s).
    pub dt: f64,
    /// Wall-clock time of the run (s).
    pub wall_time_s: f64,
}

/// The energy balance: `ground_work = potential_change + kinetic_change + impact + friction +
/// residual`; `residual` is the scheme's error (`persistent_contact + projection` up to
/// round-off), `relative_residual` against the largest energy involved.
#[derive(Debug, Serialize)]
pub struct ContactEnergy {
    pub ground_work: f64,
    pub potential_change: f64,
    pub kinetic_change: f64,
    pub impact: f64,
    pub friction: f64,
    pub persistent_contact: f64,
    pub projection: f64,
    pub residual: f64,
    pub relative_residual: f64,
}

/// The kinds counted in [`DrumOutcome::event_counts`], in its order.
const COUNTED_KINDS: [DrumEventKind; 7] = [
    DrumEventKind::Opening,
    DrumEventKind::Impact,
    DrumEventKind::SlipStart,
    DrumEventKind::SlipStop,
    DrumEventKind::LiftOff,
    DrumEventKind::Landing,
    DrumEventKind::Overturned,
];

impl<'a> ContactSummary<'a> {
    /// The summary of `o`, the contact-scheme run of `scene` (read from `path`, if from a file)
    /// at step `dt` that took `wall_time_s`.
    pub fn of(
        scene: &'a Scene,
        path: Option<String>,
        o: &'a DrumOutcome,
        dt: f64,
        wall_time_s: f64,
    ) -> ContactSummary<'a> {
        let (stop_reason, stop_interface) = stop_name(&o.stop);
        let events = COUNTED_KINDS
            .iter()
            .zip(o.event_counts)
            .filter(|(_, c)| *c > 0)
            .map(|(k, c)| (k.name(), c))
            .collect();
        let e = &o.energy;
        let a = &e.accounts;
        ContactSummary {
            scene: path,
            title: &scene.title,
            excitation: scene.excitation.describe(),
            scheme: if scene.auto.is_some() {
                "auto"
            } else {
                "moreau"
            },
            overturned: o.overturned,
            t_end: o.t_end,
            impacts: o.event_counts[1],
            stop_reason,
            stop_interface,
            peak_block_rotation: &o.peak_rotation,
            peak_slip: &o.peak_slip,
            residual_slip: &o.residual_slip,
            peak_top_displacement: o.peak_top_displacement,
            modes_end: o.modes_end.iter().map(|m| mode_name(*m)).collect(),
            events,
            energy: ContactEnergy {
                ground_work: a.ground_work,
                potential_change: e.potential_change,
                kinetic_change: e.kinetic_change,
                impact: a.impact,
                friction: a.friction,
                persistent_contact: a.persistent_contact,
                projection: a.projection,
                residual: e.residual(),
                relative_residual: e.residual() / e.scale(),
            },
            scheme_switches: scene.auto.map(|_| o.switches.len()),
            time_event_driven: scene.auto.map(|_| o.time_event_driven),
            dt,
            wall_time_s,
        }
    }
}

/// The objects of `events.jsonl`: `t`, `kind`, `joint`; a scheme switch (scheme `"auto"`) with
/// `from`, `to`, `why`, `kinetic_before`, `kinetic_after`, `slip_dropped` in place of `joint`.
pub fn contact_events(o: &DrumOutcome) -> Vec<Value> {
    let mut switches = o.switches.iter();
    o.events
        .iter()
        .filter_map(|e| {
            if e.kind == DrumEventKind::SchemeSwitch {
                switches.next().map(|s| {
                    json!({"t": e.t, "kind": e.kind.name(),
                        "from": s.from.name(), "to": s.to.name(), "why": s.why,
                        "kinetic_before": s.kinetic_before, "kinetic_after": s.kinetic_after,
                        "slip_dropped": s.slip_dropped})
                })
            } else {
                Some(json!({"t": e.t, "kind": e.kind.name(), "joint": e.joint}))
            }
        })
        .collect()
}

/// The positions `x, y, θ` of each drum of `column` straight at rest, from which `history.csv`
/// gives the displacements.
pub fn rest(column: &Column) -> Vec<f64> {
    Drums::new(column).rest_positions()
}

/// The stop as `summary.json` names it (the event-driven names where they mean the same), and
/// the joint (the drum for `fallen`) it concerns.
pub fn stop_name(s: &DrumStop) -> (&'static str, Option<usize>) {
    match *s {
        DrumStop::Duration => ("duration", None),
        DrumStop::Overturned { joint } => ("overturned", Some(joint)),
        DrumStop::Fallen { drum } => ("fallen", Some(drum)),
        DrumStop::SlidOff { joint } => ("slid_off", Some(joint)),
        DrumStop::Sliding { joint } => ("sliding", Some(joint)),
        DrumStop::Tension { joint } => ("tension", Some(joint)),
    }
}

/// A joint's mode as the outputs name it.
pub fn mode_name(m: JointMode) -> &'static str {
    match m {
        JointMode::Closed => "closed",
        JointMode::RockingRight => "rocking_right",
        JointMode::RockingLeft => "rocking_left",
        JointMode::Flying => "flying",
    }
}

/// The columns of `history.csv`, each row-major (`samples × drums`, `samples × joints`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ContactHistoryColumns {
    /// Drums (= joints).
    pub n: usize,
    /// Sample times (s).
    pub t: Vec<f64>,
    /// Each drum's centre, horizontal displacement from its place in the straight column at
    /// rest (m), as `peak_top_displacement`.
    pub x: Vec<f64>,
    /// Each drum's centre, vertical displacement from its place at rest (m).
    pub y: Vec<f64>,
    /// Each drum's rotation (rad, counter-clockwise positive as the driver's).
    pub block_rotation: Vec<f64>,
    /// Each joint's slip (m).
    pub slip: Vec<f64>,
}

impl ContactHistoryColumns {
    /// The columns of a run's history of `column`.
    pub fn of(h: &DrumHistory, column: &Column) -> Self {
        Self::of_rows(h, 0..h.t.len(), &rest(column))
    }

    /// The columns of the samples `rows` of a run's history, displacements from `rest` (the
    /// straight column's positions, [`rest`]), so that a long history can be written a block of
    /// rows at a time. (They were from the run's first sample: a column released from initial
    /// angles started at x = 0 and ended at rest at minus its tilt, and its history's top
    /// displacement was not the summary's `peak_top_displacement`.)
    pub fn of_rows(h: &DrumHistory, rows: std::ops::Range<usize>, rest: &[f64]) -> Self {
        let n = h.n;
        let len = rows.len();
        let mut c = ContactHistoryColumns {
            n,
            t: h.t[rows.clone()].to_vec(),
            x: Vec::with_capacity(len * n),
            y: Vec::with_capacity(len * n),
            block_rotation: Vec::with_capacity(len * n),
            slip: h.slip[rows.start * n..rows.end * n].to_vec(),
        };
        if len == 0 || n == 0 {
            return c;
        }
        let q0 = &rest[..3 * n];
        for q in h.q[3 * n * rows.start..].chunks_exact(3 * n).take(len) {
            for k in 0..n {
                c.x.push(q[3 * k] - q0[3 * k]);
                c.y.push(q[3 * k + 1] - q0[3 * k + 1]);
                c.block_rotation.push(q[3 * k + 2]);
            }
        }
        c
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// No samples.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A drum released from 0.1 rad: its peak rotation is the release (it was 0.09999974, the
    /// first step's), the history's displacements are from rest (the first sample is the tilt,
    /// not 0; the drum back at rest is at 0, not at minus the tilt), and the history's largest top
    /// displacement is the summary's `peak_top_displacement`.
    #[test]
    fn a_released_drum_is_measured_from_rest() {
        let text = r#"{"blocks": [{"width": 1, "height": 4, "mass": 2500}],
            "excitation": {"type": "none"}, "initial_angles": [0.1], "duration": 3,
            "dt": 0.001, "friction": 0.7, "on_sliding": "slide", "on_tension": "fly"}"#;
        let spec = super::super::parse(text).unwrap();
        let scene = super::super::build(spec, std::path::Path::new("."), "test").unwrap();
        let motion = crate::ground::FnMotion(|_| 0.0, 0.0);
        let o = crate::contact::simulation::simulate(
            &scene.column,
            &motion,
            scene.contact.as_ref().unwrap(),
            None,
        )
        .unwrap();
        assert_eq!(o.peak_rotation, [0.1]);
        let c = ContactHistoryColumns::of(o.history.as_ref().unwrap(), &scene.column);
        // Turned by +0.1 (counter-clockwise) about its left corner, half-width 0.5 below a
        // centre 2 m up.
        let tilt = -2.0 * 0.1_f64.sin() - 0.5 * (1.0 - 0.1_f64.cos());
        assert!((c.x[0] - tilt).abs() < 1e-12, "{} against {tilt}", c.x[0]);
        assert!(c.y[0] > 0.0, "{}", c.y[0]);
        let top = c.x.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        assert_eq!(top, o.peak_top_displacement);
    }

    /// The columns taken a block of rows at a time are those of the whole history, bit for bit
    /// (displacements from the rest positions, not from the block's first sample).
    #[test]
    fn columns_by_blocks_of_rows_are_the_whole_columns() {
        let (n, rows) = (3, 11);
        let value = |i: usize| (i as f64 * 0.37).sin() * 1e-3 + i as f64;
        let h = DrumHistory {
            n,
            t: (0..rows).map(|i| i as f64 * 1e-3).collect(),
            q: (0..rows * 3 * n).map(value).collect(),
            slip: (0..rows * n).map(|i| -value(i)).collect(),
        };
        let rest: Vec<f64> = (0..3 * n).map(|i| 0.1 * i as f64).collect();
        let whole = ContactHistoryColumns::of_rows(&h, 0..rows, &rest);
        let mut joined = ContactHistoryColumns {
            n,
            ..ContactHistoryColumns::default()
        };
        for start in (0..rows).step_by(4) {
            let c = ContactHistoryColumns::of_rows(&h, start..rows.min(start + 4), &rest);
            joined.t.extend(c.t);
            joined.x.extend(c.x);
            joined.y.extend(c.y);
            joined.block_rotation.extend(c.block_rotation);
            joined.slip.extend(c.slip);
        }
        assert_eq!(joined, whole);
        assert_eq!(whole.x[n * 5 + 1], h.q[3 * n * 5 + 3] - rest[3]);
        assert!(ContactHistoryColumns::of_rows(&h, 4..4, &rest).is_empty());
    }
}
