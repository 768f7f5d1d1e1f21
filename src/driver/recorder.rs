//! What a run keeps ([`Recording`]): the history samples, the events, the peak block rotations,
//! the energy balance and the counts, and the [`Outcome`] they make at the end. Every scheme
//! reports through it.

use super::chain::ChainDynamics;
use super::state::State;
use super::{EnergyBalance, Event, EventKind, History, Outcome, Recording, StopReason};
use crate::model::cone::ModelReport;
use crate::model::configuration::Status;

pub(crate) struct Recorder {
    keep: Recording,
    events: Vec<Event>,
    /// Events so far, kept or not (the cap of `stopping.max_events_per_second`).
    events_counted: usize,
    impacts: usize,
    /// Accepted steps.
    steps: usize,
    /// Interfaces whose part above has tipped beyond its pivot (with `continue_until_fallen`).
    tipped: Vec<bool>,
    peak: Vec<f64>,
    energy: EnergyBalance,
    potential_start: f64,
    history: Option<History>,
}

impl Recorder {
    /// A recorder for `n` interfaces keeping `keep` of a run of about `duration / dt` steps.
    pub fn new(n: usize, keep: Recording, duration: f64, dt: f64) -> Recorder {
        let m = 2 * n;
        Recorder {
            keep,
            events: Vec::new(),
            events_counted: 0,
            impacts: 0,
            steps: 0,
            tipped: vec![false; n],
            peak: vec![0.0; n],
            energy: EnergyBalance::default(),
            potential_start: 0.0,
            history: keep.history_every.map(|every| {
                // Room for the samples of the whole duration (capped), so that the history does
                // not grow by reallocation and copying while it runs.
                let samples = (duration / (dt * every as f64)).min(1e6) as usize + 16;
                History {
                    n_interfaces: n,
                    t: Vec::with_capacity(samples),
                    phi: Vec::with_capacity(samples * m),
                    rates: Vec::with_capacity(samples * m),
                    block_angles: Vec::with_capacity(samples * n),
                    statuses: Vec::with_capacity(samples * n),
                }
            }),
        }
    }

    /// The start of a run: its potential energy (`potential`), the first peaks and sample.
    pub fn start(&mut self, state: &State, potential: f64) {
        self.potential_start = potential;
        for (p, a) in self.peak.iter_mut().zip(state.block_angles()) {
            *p = a.abs();
        }
        self.sample(state);
    }

    fn sample(&mut self, state: &State) {
        if let Some(h) = &mut self.history {
            h.t.push(state.t());
            h.phi.extend_from_slice(&state.phi);
            h.rates.extend_from_slice(&state.rates);
            h.statuses.extend_from_slice(&state.statuses);
            h.block_angles.extend(state.block_angles());
        }
    }

    /// An accepted step: counted, and sampled every `history_every`.
    pub fn accepted_step(&mut self, state: &State) {
        self.steps += 1;
        if let Some(every) = self.keep.history_every {
            if self.steps % every == 0 {
                self.sample(state);
            }
        }
    }

    /// Accepted steps so far.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The block rotations of an accepted step's end, for the peaks.
    pub fn peaks(&mut self, block_angles: &[f64]) {
        for (p, a) in self.peak.iter_mut().zip(block_angles) {
            *p = p.max(a.abs());
        }
    }

    /// An event found (counted towards the cap, not kept).
    pub fn count_event(&mut self) {
        self.events_counted += 1;
    }

    /// Events so far.
    pub fn events_counted(&self) -> usize {
        self.events_counted
    }

    /// An event at `state` (after it); `before`: the configuration before (`None`: unchanged).
    #[allow(clippy::too_many_arguments)]
    pub fn event(
        &mut self,
        state: &State,
        kind: EventKind,
        interface: Option<usize>,
        kinetic_before: f64,
        kinetic_after: f64,
        before: Option<&[Status]>,
        report: Option<ModelReport>,
    ) {
        self.events_counted += 1;
        if kind == EventKind::Impact {
            self.impacts += 1;
        }
        if self.keep.events {
            self.events.push(Event {
                t: state.t(),
                kind,
                interface,
                kinetic_before,
                kinetic_after,
                statuses_before: before.unwrap_or(&state.statuses).to_vec(),
                statuses_after: state.statuses.clone(),
                report,
            });
        }
    }

    /// A stop event at `state` at interface `k` (tension, sliding, overturning).
    pub fn stop_event(&mut self, state: &State, kind: EventKind, k: usize) {
        self.event(state, kind, Some(k), 0.0, 0.0, None, None);
    }

    /// Interface `k` tipped beyond its pivot; whether it is the first time.
    pub fn tipped(&mut self, k: usize) -> bool {
        !std::mem::replace(&mut self.tipped[k], true)
    }

    /// Work of the ground motion over part of a step.
    pub fn ground_work(&mut self, work: f64) {
        self.energy.ground_work += work;
    }

    /// Kinetic energy lost (impact, settling, a grazing DOF stopped).
    pub fn dissipated(&mut self, energy: f64) {
        self.energy.dissipated += energy;
    }

    /// The outcome of a run stopped at `state` for `reason`.
    pub fn finish(
        mut self,
        reason: StopReason,
        state: &State,
        chain: &mut impl ChainDynamics,
    ) -> Outcome {
        let (kin, pot) = chain.energy(&state.open, &state.phi, &state.rates);
        self.energy.kinetic_end = kin;
        self.energy.potential_change = pot - self.potential_start;
        if let Some(h) = &self.history {
            if h.t.last() != Some(&state.t()) {
                self.sample(state);
            }
        }
        Outcome {
            stop_reason: reason,
            t_end: state.t(),
            // With `continue_until_fallen` a column that has tipped beyond a pivot may still end
            // in tension or sliding while it falls (its corner lifts off): it has overturned.
            overturned: matches!(
                reason,
                StopReason::Overturned { .. } | StopReason::Fallen { .. }
            ) || self.tipped.iter().any(|&t| t),
            impacts: self.impacts,
            events: self.events,
            history: self.history,
            peak_block_rotation: self.peak,
            energy: self.energy,
            statuses_end: state.statuses.clone(),
        }
    }
}
