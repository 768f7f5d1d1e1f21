//! The overturning curve (OC) of an arch under pulses: collapse on a grid of pulse durations
//! and levels `a_p / (λ g)` (see `arch.rs` for the axes, `p` and the verdict).

use super::arch::{run_loop, ArchFailure, ArchOnset, ArchRun, ArchRunCounts, ArchShape};
use super::overturning_curve::PulseShape;
use super::sweep::map_indexed;
use super::{arch_onset, ArchSweepOptions, Progress, SpectraError};
use crate::validate::{all_positive, positive};

/// The arch of radius `radius` under the pulse `shape(level · λ g, t_p)`, from rest.
pub fn arch_pulse_run(
    pulse: PulseShape,
    onset: &ArchOnset,
    level: f64,
    t_p: f64,
    radius: f64,
    options: &ArchSweepOptions,
) -> Result<ArchRun, SpectraError> {
    if level <= 1.0 {
        return Ok(ArchRun::NEVER_MOVES);
    }
    let g = options.simulation.gravity;
    let excitation =
        crate::ground::excitation::Excitation::Pulse(pulse.pulse(level * onset.lambda * g, t_p)?);
    let p = onset.p(radius);
    let dt = options.time_step.dt(None, Some(t_p), p);
    let run = options.run(dt, excitation.end_time() + options.tail / p, None);
    let chain = options.shape.chain(radius)?;
    run_loop(&chain, &excitation, &run)
}

/// The overturning curve of one arch: collapse on a grid of pulse durations `t_p` (rows) and
/// levels `a_p / (λ g)` (columns).
#[derive(Clone, Debug, PartialEq)]
pub struct ArchOc {
    pub pulse: PulseShape,
    pub shape: ArchShape,
    pub radius: f64,
    pub onset: ArchOnset,
    pub gravity: f64,
    pub t_p: Vec<f64>,
    pub levels: Vec<f64>,
    /// `collapsed[i * levels.len() + j]` (`false` also where the run failed: see
    /// `runs.failures`).
    pub collapsed: Vec<bool>,
    pub runs: ArchRunCounts,
}

impl ArchOc {
    /// `p` of the arch (1/s).
    pub fn p(&self) -> f64 {
        self.onset.p(self.radius)
    }

    /// For each `t_p`, the smallest level that collapses the arch (`None`: none).
    pub fn envelope(&self) -> Vec<Option<f64>> {
        let n = self.levels.len();
        (0..self.t_p.len())
            .map(|i| (0..n).find(|&j| self.collapsed[i * n + j]))
            .map(|j| j.map(|j| self.levels[j]))
            .collect()
    }
    /// Appends the row of `t_p` ([`arch_oc_row`] over `self.levels`): its verdicts, and its runs
    /// counted in order.
    pub fn push_row(&mut self, t_p: f64, row: Vec<Result<ArchRun, ArchFailure>>) {
        self.t_p.push(t_p);
        for (j, r) in row.into_iter().enumerate() {
            match r {
                Ok(r) => {
                    self.runs.add(&r, self.levels[j], t_p);
                    self.collapsed.push(r.collapsed);
                }
                Err(f) => {
                    self.runs.failures.push(f);
                    self.collapsed.push(false);
                }
            }
        }
    }
}

/// The OC of the arch of radius `radius` for `pulse`, parallel over `t_p`. `levels` ascending.
pub fn arch_overturning_curve(
    pulse: PulseShape,
    radius: f64,
    t_p: &[f64],
    levels: &[f64],
    options: &ArchSweepOptions,
    progress: Option<Progress<'_>>,
) -> Result<ArchOc, SpectraError> {
    options.validate()?;
    positive("radius", radius)?;
    all_positive("t_p", t_p)?;
    all_positive("levels", levels)?;
    let sim = &options.simulation;
    let onset = arch_onset(&options.shape, sim.gravity, &sim.model)?;
    let rows = map_indexed(t_p.len(), |i| {
        let row = arch_oc_row(pulse, &onset, t_p[i], levels, radius, options);
        if let Some(p) = progress {
            p();
        }
        row
    });
    let mut oc = ArchOc {
        pulse,
        shape: options.shape,
        radius,
        onset,
        gravity: sim.gravity,
        t_p: Vec::with_capacity(t_p.len()),
        levels: levels.to_vec(),
        collapsed: Vec::with_capacity(t_p.len() * levels.len()),
        runs: ArchRunCounts::default(),
    };
    for (i, row) in rows.into_iter().enumerate() {
        oc.push_row(t_p[i], row?);
    }
    Ok(oc)
}

/// One row of an arch OC: the runs at `t_p` over `levels`, in order (a run the loop driver
/// failed on: its failure). Every row is independent of the others ([`ArchOc::push_row`]
/// assembles them).
pub fn arch_oc_row(
    pulse: PulseShape,
    onset: &ArchOnset,
    t_p: f64,
    levels: &[f64],
    radius: f64,
    options: &ArchSweepOptions,
) -> Result<Vec<Result<ArchRun, ArchFailure>>, SpectraError> {
    levels
        .iter()
        .map(
            |&l| match arch_pulse_run(pulse, onset, l, t_p, radius, options) {
                Ok(r) => Ok(Ok(r)),
                Err(SpectraError::Loop(message)) => Ok(Err(ArchFailure {
                    level: l,
                    radius: t_p,
                    message,
                })),
                Err(e) => Err(e),
            },
        )
        .collect()
}
