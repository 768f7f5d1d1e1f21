//! The automatic scheme (issue 11; docs/auto-scheme.md): a run starts in
//! the thesis's event-driven driver ([`crate::driver`]) and is handed over to Moreau–Jean time
//! stepping ([`super::moreau`]) where contacts crowd — more events within a window of simulated
//! time than the rule allows, or a slip, tension or the event cap, which the driver can only stop
//! at — and handed back when the column is calm again: no event for a window, every joint closed
//! or rocking about one end, none slipping, and no slip beyond a tolerance (the driver has no
//! slip DOF: a column that has slipped stays in Moreau–Jean). The whole run is one
//! [`DrumOutcome`]: the driver's segments enter it as the scheme's own (events, history in
//! natural coordinates, peaks, energy), and every hand-over is a [`SchemeSwitch`].

use super::handover::{calm, to_interface, to_natural};
use super::simulation::{
    DrumError, DrumEventKind, DrumOptions, DrumOutcome, DrumStop, MoreauRun, Paused, SchemePart,
    SchemeSwitch,
};
use crate::driver::switch::{simulate_segment, CrowdingRule, Handover, InterfaceState, Segment};
use crate::driver::{DriverError, EventKind, SimulationOptions, StopReason};
use crate::ground::GroundMotion;
use crate::model::column::Column;

/// The rules of the hand-overs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoOptions {
    /// To Moreau–Jean: the events crowd.
    pub crowding: CrowdingRule,
    /// Back to the driver: no event for this long (s).
    pub calm_window: f64,
    /// Back to the driver: every joint's slip within this fraction of its contact half-width.
    pub slip_tolerance: f64,
}

impl AutoOptions {
    /// The defaults for a step `dt` (docs/auto-scheme.md): more events
    /// within 0.5 s than half its steps hands over (250 at dt = 1 ms); 0.5 s without an event,
    /// and slips within 1e-4 of the half-width, hand back.
    pub fn for_step(dt: f64) -> AutoOptions {
        let window = 0.5;
        AutoOptions {
            crowding: CrowdingRule {
                window,
                max_events: (0.5 * window / dt).ceil() as usize,
            },
            calm_window: 0.5,
            slip_tolerance: 1e-4,
        }
    }
}

/// Why an automatic run failed.
#[derive(Debug)]
pub enum AutoError {
    /// In the driver.
    Driver(DriverError),
    /// In the contact scheme.
    Contact(DrumError),
}

impl std::fmt::Display for AutoError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            AutoError::Driver(e) => e.fmt(f),
            AutoError::Contact(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for AutoError {}

/// Runs `column` under `motion` with the automatic scheme: the driver with `driver` (its step,
/// duration and recording are the contact scheme's, its early stops `quiet_after` and
/// `stop_when_safe*` are off: the contact scheme has none), the contact scheme with `contact`.
pub fn simulate(
    column: &Column,
    motion: &dyn GroundMotion,
    driver: &SimulationOptions,
    contact: &DrumOptions,
    rules: &AutoOptions,
    mut progress: Option<&mut dyn FnMut(f64)>,
) -> Result<DrumOutcome, AutoError> {
    let mut report = |f: f64| {
        if let Some(p) = progress.as_deref_mut() {
            p(f)
        }
    };
    contact
        .validate(column)
        .map_err(|e| AutoError::Contact(DrumError::Option(e)))?;
    let mut driver = driver.clone();
    driver.stepping.dt = contact.dt;
    driver.stopping.duration = contact.duration;
    driver.stopping.quiet_after = None;
    driver.stopping.stop_when_safe = false;
    driver.stopping.stop_when_safe_column = false;
    // Always: the events are counted from them.
    driver.recording.events = true;
    // Every step: the top's displacement is a peak of the record.
    driver.recording.history_every = Some(1);
    driver.initial.angles = contact.initial_angles.clone();
    let mut run = MoreauRun::new(column, contact);
    // Kept apart: the stepper's accounts hold the Moreau–Jean steps only.
    let (mut work, mut dissipated, mut handed) = (0.0, 0.0, 0.0);
    let mut start: Option<InterfaceState> = None;
    loop {
        // The driver, from the start or from a calm column.
        let p: Option<&mut dyn FnMut(f64)> = Some(&mut report);
        let seg = simulate_segment(column, motion, &driver, start.as_ref(), rules.crowding, p)
            .map_err(AutoError::Driver)?;
        work += seg.outcome.energy.ground_work;
        dissipated += seg.outcome.energy.dissipated;
        let t0 = start.as_ref().map_or(0.0, |s| s.t);
        run.out.time_event_driven += seg.end.t - t0;
        enter(&mut run, column, contact, &seg, start.is_none());
        let Some(why) = seg.handover else {
            let stop = match seg.outcome.stop_reason {
                StopReason::Overturned { interface } => DrumStop::Overturned { joint: interface },
                StopReason::Fallen { interface } => DrumStop::Fallen { drum: interface },
                _ => DrumStop::Duration,
            };
            to_natural(&mut run.st, column, &seg.end);
            run.remode();
            return Ok(finish(run, stop, work, dissipated, handed));
        };
        // To Moreau–Jean, at the driver's last state.
        let kinetic = to_natural(&mut run.st, column, &seg.end);
        run.remode();
        let joint = match why {
            Handover::Sliding { interface } | Handover::Tension { interface } => interface,
            _ => 0,
        };
        switch(
            &mut run,
            contact,
            SchemePart::Moreau,
            why.name(),
            joint,
            [seg.outcome.energy.kinetic_end, kinetic],
        );
        let quiet_since = run.st.t;
        run.last_event = quiet_since;
        let (window, tolerance) = (rules.calm_window, rules.slip_tolerance);
        let mut rule = |st: &_, mode: &[_], slipping: &[bool], last: f64| {
            calm(st, mode, slipping, last.max(quiet_since), window, tolerance)
                && to_interface(st, mode).is_some()
        };
        let p: Option<&mut dyn FnMut(f64)> = Some(&mut report);
        match run
            .steps(motion, contact, p, Some(&mut rule))
            .map_err(AutoError::Contact)?
        {
            Paused::Stopped(stop) => return Ok(finish(run, stop, work, dissipated, handed)),
            Paused::Until => {}
        }
        // Back to the driver.
        let s = to_interface(&run.st, &run.mode).expect("checked by the rule");
        let before = run.st.kinetic_energy();
        let after = to_natural(&mut run.st.clone(), column, &s);
        handed += before - after;
        switch(
            &mut run,
            contact,
            SchemePart::EventDriven,
            "calm",
            0,
            [before, after],
        );
        start = Some(s);
    }
}

/// A switch recorded.
fn switch(
    run: &mut MoreauRun,
    options: &DrumOptions,
    to: SchemePart,
    why: &'static str,
    joint: usize,
    [kinetic_before, kinetic_after]: [f64; 2],
) {
    let from = match to {
        SchemePart::Moreau => SchemePart::EventDriven,
        SchemePart::EventDriven => SchemePart::Moreau,
    };
    let t = run.st.t;
    let slip_dropped = match to {
        SchemePart::EventDriven => run
            .st
            .geometry
            .iter()
            .fold(0.0_f64, |m, g| m.max(g.slip.abs())),
        SchemePart::Moreau => 0.0,
    };
    run.out.switches.push(SchemeSwitch {
        t,
        from,
        to,
        why,
        kinetic_before,
        kinetic_after,
        slip_dropped,
    });
    if options.record.events {
        run.out.events.push(super::simulation::DrumEvent {
            t,
            kind: DrumEventKind::SchemeSwitch,
            joint,
        });
    }
}

/// A driver's segment into the record: its events (openings, impacts — settlings, the driver's
/// closings for good, are impacts here — and overturning; the stop events that hand over are
/// the switch), its history in natural coordinates (slips zero: the driver has none), the peaks.
fn enter(run: &mut MoreauRun, column: &Column, options: &DrumOptions, seg: &Segment, first: bool) {
    for e in &seg.outcome.events {
        let kind = match e.kind {
            EventKind::Opening => DrumEventKind::Opening,
            EventKind::Impact | EventKind::Settled => DrumEventKind::Impact,
            EventKind::Overturned => DrumEventKind::Overturned,
            EventKind::Sliding | EventKind::Tension => continue,
        };
        run.push(options, e.t, kind, e.interface.unwrap_or(0));
    }
    let n = column.n_interfaces();
    for (p, a) in run
        .out
        .peak_rotation
        .iter_mut()
        .zip(&seg.outcome.peak_block_rotation)
    {
        *p = p.max(*a);
    }
    let Some(h) = &seg.outcome.history else {
        return;
    };
    let every = options.record.history_every;
    let mut q = vec![0.0; 3 * n];
    let mut v = vec![0.0; 3 * n];
    let rates = vec![0.0; 2 * n];
    let x0 = run.st.drums().rest_positions()[3 * (n - 1)];
    // The segment's first sample is the state handed over, already kept.
    for i in usize::from(!first)..h.len() {
        run.st
            .drums()
            .from_interface_state(column, h.phi_at(i), &rates, &mut q, &mut v);
        let top = (q[3 * (n - 1)] - x0).abs();
        run.out.peak_top_displacement = run.out.peak_top_displacement.max(top);
        let keep = every.is_some_and(|k| i % k == 0) || i + 1 == h.len();
        if let (true, Some(out)) = (keep && !(first && i == 0), run.out.history.as_mut()) {
            out.t.push(h.t[i]);
            out.q.extend_from_slice(&q);
            out.slip.extend(std::iter::repeat(0.0).take(n));
        }
    }
}

/// The outcome: the stepper's accounts with the driver's ground work and dissipation (impacts
/// and settlings) added, and the energy dropped at hand-backs counted as impact dissipation.
fn finish(
    mut run: MoreauRun,
    stop: DrumStop,
    work: f64,
    dissipated: f64,
    handed: f64,
) -> DrumOutcome {
    run.st.energy.ground_work += work;
    run.st.energy.impact += dissipated + handed;
    let mut out = run.finish(stop);
    out.events
        .sort_by(|a, b| a.t.partial_cmp(&b.t).unwrap_or(std::cmp::Ordering::Equal));
    out
}

#[cfg(test)]
#[path = "auto_tests.rs"]
mod tests;
