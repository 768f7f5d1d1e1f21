//! `summary.json` of a scene's run through the reference driver: one definition for
//! `rocking simulate` and the Python package's `rocking.simulate`.

use std::collections::BTreeMap;

use serde::Serialize;

use super::Scene;
use crate::driver::{EnergyBalance, Outcome};
use crate::model::configuration::Status;

/// What a run of a scene reports (`summary.json`).
#[derive(Debug, Serialize)]
pub struct Summary<'a> {
    /// The scene file's path; `None` (JSON `null`) for a scene given as text.
    pub scene: Option<String>,
    pub title: &'a str,
    /// The excitation, described in words.
    pub excitation: String,
    pub overturned: bool,
    /// Time at which the run ended (s).
    pub t_end: f64,
    pub impacts: usize,
    /// Why the run stopped ([`crate::driver::StopReason::name`]).
    pub stop_reason: &'static str,
    /// The interface the stop concerns, if any.
    pub stop_interface: Option<usize>,
    /// Largest absolute rotation of each block (rad).
    pub peak_block_rotation: &'a [f64],
    /// The configuration at the end.
    pub statuses_end: &'a [Status],
    /// Events by kind ([`crate::driver::EventKind::name`]).
    pub events: BTreeMap<&'static str, usize>,
    pub energy: Energy,
    /// The driver's time step (s).
    pub dt: f64,
    /// Wall-clock time of the run (s).
    pub wall_time_s: f64,
}

/// The energy balance and its residual.
#[derive(Debug, Serialize)]
pub struct Energy {
    #[serde(flatten)]
    pub balance: EnergyBalance,
    pub residual: f64,
}

impl<'a> Summary<'a> {
    /// The summary of `outcome`, the run of `scene` (read from `path`, if from a file) that took
    /// `wall_time_s`.
    pub fn of(
        scene: &'a Scene,
        path: Option<String>,
        outcome: &'a Outcome,
        wall_time_s: f64,
    ) -> Summary<'a> {
        let mut events = BTreeMap::new();
        for e in &outcome.events {
            *events.entry(e.kind.name()).or_insert(0) += 1;
        }
        Summary {
            scene: path,
            title: &scene.title,
            excitation: scene.excitation.describe(),
            overturned: outcome.overturned,
            t_end: outcome.t_end,
            impacts: outcome.impacts,
            stop_reason: outcome.stop_reason.name(),
            stop_interface: outcome.stop_reason.interface(),
            peak_block_rotation: &outcome.peak_block_rotation,
            statuses_end: &outcome.statuses_end,
            events,
            energy: Energy {
                balance: outcome.energy,
                residual: outcome.energy.residual(),
            },
            dt: scene.options.stepping.dt,
            wall_time_s,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::driver::EventKind;

    /// `events.jsonl` writes an event's kind by serde, `summary.json` counts kinds by name: the two
    /// spellings must agree.
    #[test]
    fn event_kind_names_are_the_serde_names() {
        for k in [
            EventKind::Opening,
            EventKind::Impact,
            EventKind::Settled,
            EventKind::Overturned,
            EventKind::Sliding,
            EventKind::Tension,
        ] {
            assert_eq!(serde_json::to_value(k).unwrap(), k.name());
        }
    }
}
