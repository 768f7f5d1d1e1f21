//! A whole time history of a drum column with the Moreau–Jean scheme ([`super::moreau`]) under
//! the options of [`super::options`] (re-exported here): the joints' modes and their events (opening, impact, slip start and stop, lift-off, landing),
//! the stops (end of the motion, overturning, a drum slid off, or, on request, the first slip or
//! lift-off as the thesis's driver does), peaks, slips and the energy balance.

use super::moreau::{StepCounters, StepError, Stepper};
pub use super::options::{DrumOptionError, DrumOptions, DrumRecording, OnSliding, OnTension};
use super::refine::Refiner;
use crate::ground::GroundMotion;
use crate::model::column::Column;

pub use super::outcome::{
    DrumEnergy, DrumError, DrumEvent, DrumEventKind, DrumHistory, DrumOutcome, DrumStop, JointMode,
    SchemePart, SchemeSwitch,
};

const KINDS: [DrumEventKind; 7] = [
    DrumEventKind::Opening,
    DrumEventKind::Impact,
    DrumEventKind::SlipStart,
    DrumEventKind::SlipStop,
    DrumEventKind::LiftOff,
    DrumEventKind::Landing,
    DrumEventKind::Overturned,
];

/// Modes of the joints from the stepper's geometry and statuses.
fn modes(stepper: &Stepper, out: &mut [JointMode], slipping: &mut [bool]) {
    let eps = stepper.contact_gap();
    for (k, g) in stepper.geometry.iter().enumerate() {
        let r = g.ends[0].gap <= eps;
        let l = g.ends[1].gap <= eps;
        out[k] = match (r, l) {
            (true, true) => JointMode::Closed,
            (true, false) => JointMode::RockingRight,
            (false, true) => JointMode::RockingLeft,
            (false, false) => JointMode::Flying,
        };
        let st = stepper.statuses[k];
        slipping[k] = out[k] != JointMode::Flying
            && st.slip != super::friction::Slip::Stick
            && stepper.joint_impulses[k][0] > 0.0;
    }
}

/// Runs a time history of `column` under `motion` with the Moreau–Jean scheme. `progress` is
/// called with the fraction done (about every 1 %).
pub fn simulate(
    column: &Column,
    motion: &dyn GroundMotion,
    options: &DrumOptions,
    progress: Option<&mut dyn FnMut(f64)>,
) -> Result<DrumOutcome, DrumError> {
    options.validate(column).map_err(DrumError::Option)?;
    let mut run = MoreauRun::new(column, options);
    let stop = match run.steps(motion, options, progress, None)? {
        Paused::Stopped(stop) => stop,
        Paused::Until => unreachable!("no pause rule"),
    };
    Ok(run.finish(stop))
}

/// Why [`MoreauRun::steps`] returned.
pub(crate) enum Paused {
    /// The run stopped (the duration done, or a stop).
    Stopped(DrumStop),
    /// The pause rule held after a step.
    Until,
}

/// What a pause rule sees after a step: the stepper, the joints' modes and whether each slips,
/// and the time of the last event.
pub(crate) type PauseRule<'r> = &'r mut dyn FnMut(&Stepper, &[JointMode], &[bool], f64) -> bool;

/// A run of the scheme: the stepper, the joints' modes, and the record.
pub(crate) struct MoreauRun {
    pub st: Stepper,
    pub mode: Vec<JointMode>,
    slipping: Vec<bool>,
    next_mode: Vec<JointMode>,
    next_slipping: Vec<bool>,
    pub out: DrumOutcome,
    potential0: f64,
    kinetic0: f64,
    /// Time of the last event pushed (s).
    pub last_event: f64,
    /// The error control, when asked for.
    refiner: Option<Refiner>,
}

impl MoreauRun {
    /// At the start: straight, or released from the options' initial angles; the first sample.
    pub fn new(column: &Column, options: &DrumOptions) -> MoreauRun {
        let n = column.n_interfaces();
        let mut st = Stepper::new(column, options.mu(n), options.scheme);
        if let Some(a) = &options.initial_angles {
            let mut phi = vec![0.0; 2 * n];
            for (k, &x) in a.iter().enumerate() {
                if x < 0.0 {
                    phi[k] = x;
                } else if x > 0.0 {
                    phi[n + k] = x;
                }
            }
            let mut q = vec![0.0; 3 * n];
            let mut v = vec![0.0; 3 * n];
            st.drums()
                .from_interface_state(column, &phi, &vec![0.0; 2 * n], &mut q, &mut v);
            st.set_state(0.0, &q, &v);
        }
        let potential0 = st.potential_energy();
        let kinetic0 = st.kinetic_energy();
        let mut mode = vec![JointMode::Closed; n];
        let mut slipping = vec![false; n];
        modes(&st, &mut mode, &mut slipping);
        let next_mode = mode.clone();
        let next_slipping = slipping.clone();
        // The peaks count the start: a column released from its initial angles has its largest
        // rotation there (they were taken after each step only, 0.09999974 of a 0.1 release).
        let q = &st.q;
        let out = DrumOutcome {
            stop: DrumStop::Duration,
            t_end: 0.0,
            overturned: false,
            peak_rotation: (0..n).map(|j| q[3 * j + 2].abs()).collect(),
            peak_slip: vec![0.0; n],
            residual_slip: vec![0.0; n],
            peak_top_displacement: q[3 * (n - 1)].abs(),
            energy: DrumEnergy::default(),
            event_counts: [0; 7],
            events: Vec::new(),
            history: options.record.history_every.map(|_| DrumHistory {
                n,
                ..DrumHistory::default()
            }),
            modes_end: Vec::new(),
            counters: StepCounters::default(),
            clusters: Default::default(),
            switches: Vec::new(),
            time_event_driven: 0.0,
        };
        let mut run = MoreauRun {
            st,
            mode,
            slipping,
            next_mode,
            next_slipping,
            out,
            potential0,
            kinetic0,
            last_event: 0.0,
            refiner: None,
        };
        run.refiner = options
            .scheme
            .energy_tolerance
            .map(|tol| Refiner::new(&run.st, tol));
        run.sample();
        run
    }

    /// Keeps the state in the history (when kept).
    pub fn sample(&mut self) {
        if let Some(h) = &mut self.out.history {
            h.t.push(self.st.t);
            h.q.extend_from_slice(&self.st.q);
            h.slip.extend(self.st.geometry.iter().map(|g| g.slip));
        }
    }

    /// After the state was set from outside (a handover): the joints' modes afresh, no events.
    pub fn remode(&mut self) {
        modes(&self.st, &mut self.mode, &mut self.slipping);
    }

    pub fn push(&mut self, options: &DrumOptions, t: f64, kind: DrumEventKind, joint: usize) {
        let i = KINDS.iter().position(|&k| k == kind).unwrap_or(0);
        self.out.event_counts[i] += 1;
        self.last_event = t;
        if options.record.events {
            self.out.events.push(DrumEvent { t, kind, joint });
        }
    }

    /// Steps on the grid `i dt` from the stepper's time to a stop, or until `until` holds after
    /// a step.
    pub fn steps(
        &mut self,
        motion: &dyn GroundMotion,
        options: &DrumOptions,
        mut progress: Option<&mut dyn FnMut(f64)>,
        mut until: Option<PauseRule<'_>>,
    ) -> Result<Paused, DrumError> {
        let n = self.mode.len();
        let n_steps = (options.duration / options.dt).round().max(0.0) as u64;
        // The first grid point after the stepper's time (0 from the start).
        let mut first = (self.st.t / options.dt).floor().max(0.0) as u64;
        while first < n_steps && (first + 1) as f64 * options.dt <= self.st.t + 1e-9 * options.dt {
            first += 1;
        }
        let mut next_progress = 0.01;
        let mut stop: Option<DrumStop> = None;
        for i in first..n_steps {
            let st = &mut self.st;
            // The last step lands exactly on the duration.
            let t_target = if i + 1 == n_steps {
                options.duration
            } else {
                (i + 1) as f64 * options.dt
            };
            let h = t_target - st.t;
            let result = match self.refiner.as_mut() {
                None => st.step(h, motion),
                Some(r) => r.step(st, h, motion, self.potential0, self.kinetic0),
            };
            match result {
                Ok(()) => {}
                Err(StepError::SlidOff(k)) => {
                    stop = Some(DrumStop::SlidOff { joint: k });
                }
                Err(StepError::Contact) => return Err(DrumError::Contact { t: st.t }),
            }
            for m in 0..self.st.impacts.len() {
                let imp = self.st.impacts[m];
                self.push(options, imp.t, DrumEventKind::Impact, imp.joint);
            }
            modes(&self.st, &mut self.next_mode, &mut self.next_slipping);
            let t = self.st.t;
            for k in 0..n {
                let (a, b) = (self.mode[k], self.next_mode[k]);
                if a != b {
                    use JointMode::*;
                    let kind = match (a, b) {
                        (Closed, RockingLeft | RockingRight) => Some(DrumEventKind::Opening),
                        (Flying, _) => Some(DrumEventKind::Landing),
                        (_, Flying) => Some(DrumEventKind::LiftOff),
                        // A located impact was pushed already.
                        (RockingLeft | RockingRight, _) => {
                            if self.st.impacts.iter().any(|m| m.joint == k) {
                                None
                            } else {
                                Some(DrumEventKind::Impact)
                            }
                        }
                        _ => None,
                    };
                    if let Some(kind) = kind {
                        self.push(options, t, kind, k);
                        if kind == DrumEventKind::LiftOff && options.on_tension == OnTension::Stop {
                            stop = stop.or(Some(DrumStop::Tension { joint: k }));
                        }
                    }
                }
                if self.slipping[k] != self.next_slipping[k] {
                    let kind = if self.next_slipping[k] {
                        DrumEventKind::SlipStart
                    } else {
                        DrumEventKind::SlipStop
                    };
                    self.push(options, t, kind, k);
                    if self.next_slipping[k] && options.on_sliding == OnSliding::Stop {
                        stop = stop.or(Some(DrumStop::Sliding { joint: k }));
                    }
                }
            }
            std::mem::swap(&mut self.mode, &mut self.next_mode);
            std::mem::swap(&mut self.slipping, &mut self.next_slipping);
            let (st, out) = (&self.st, &mut self.out);
            // Peaks.
            for j in 0..n {
                out.peak_rotation[j] = out.peak_rotation[j].max(st.q[3 * j + 2].abs());
            }
            for (k, g) in st.geometry.iter().enumerate() {
                out.peak_slip[k] = out.peak_slip[k].max(g.slip.abs());
            }
            out.peak_top_displacement = out.peak_top_displacement.max(st.q[3 * (n - 1)].abs());
            // Overturning: static tipping of the part above a rocking joint, or a fallen drum.
            if stop.is_none() {
                if options.continue_until_fallen {
                    if let Some(j) =
                        (0..n).find(|&j| st.q[3 * j + 2].abs() >= 0.5 * std::f64::consts::PI)
                    {
                        stop = Some(DrumStop::Fallen { drum: j });
                    }
                } else if let Some(k) = tipped(st, &self.mode) {
                    self.push(options, t, DrumEventKind::Overturned, k);
                    stop = Some(DrumStop::Overturned { joint: k });
                }
            }
            if self.out.history.is_some() {
                let every = options.record.history_every.unwrap_or(1) as u64;
                if (i + 1) % every == 0 || i + 1 == n_steps || stop.is_some() {
                    self.sample();
                }
            }
            if let Some(stop) = stop {
                return Ok(Paused::Stopped(stop));
            }
            if let Some(p) = progress.as_deref_mut() {
                let f = (i + 1) as f64 / n_steps as f64;
                if f >= next_progress {
                    p(f);
                    next_progress = f + 0.01;
                }
            }
            if let Some(rule) = until.as_deref_mut() {
                if i + 1 < n_steps && rule(&self.st, &self.mode, &self.slipping, self.last_event) {
                    return Ok(Paused::Until);
                }
            }
        }
        Ok(Paused::Stopped(DrumStop::Duration))
    }

    /// The outcome of the run stopped for `stop`.
    pub fn finish(mut self, stop: DrumStop) -> DrumOutcome {
        let st = &self.st;
        let out = &mut self.out;
        out.stop = stop;
        out.overturned = matches!(
            out.stop,
            DrumStop::Overturned { .. } | DrumStop::Fallen { .. } | DrumStop::SlidOff { .. }
        );
        out.t_end = st.t;
        for (k, g) in st.geometry.iter().enumerate() {
            out.residual_slip[k] = g.slip;
        }
        out.energy = DrumEnergy {
            potential_change: st.potential_energy() - self.potential0,
            kinetic_change: st.kinetic_energy() - self.kinetic0,
            accounts: st.energy,
        };
        out.modes_end = self.mode;
        out.counters = st.counters;
        out.clusters = st.cluster_counters;
        self.out
    }
}

/// The lowest rocking joint whose part above has its centre of mass beyond the pivot, along the
/// lower face (as the thesis's driver measures static tipping).
fn tipped(st: &Stepper, mode: &[JointMode]) -> Option<usize> {
    let n = mode.len();
    let d = st.drums();
    // Suffix sums of m and m c.
    let (mut m, mut sx, mut sy) = (0.0, 0.0, 0.0);
    let mut found = None;
    for k in (0..n).rev() {
        m += d.mass(k);
        sx += d.mass(k) * st.q[3 * k];
        sy += d.mass(k) * st.q[3 * k + 1];
        let end = match mode[k] {
            JointMode::RockingRight => 0,
            JointMode::RockingLeft => 1,
            _ => continue,
        };
        let e = &st.geometry[k].ends[end];
        let t = [e.normal[1], -e.normal[0]];
        let along = (sx / m - e.point[0]) * t[0] + (sy / m - e.point[1]) * t[1];
        let outward = if end == 0 { along > 0.0 } else { along < 0.0 };
        if outward {
            found = Some(k);
        }
    }
    found
}
