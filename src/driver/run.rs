//! The event-driven run loop (thesis 3.3, SPEC §5).

use super::chain::{not_positive_definite, ChainDynamics};
use super::events::monolith::Monolith;
use super::events::rest::CannotTip;
use super::events::settle::Settling;
use super::events::{detect, forces, impact, opening, overturn, refine, rest, Found, Probe};
use super::problem::Problem;
use super::recorder::Recorder;
use super::state::State;
use super::step::Step;
use super::switch::{Crowding, CrowdingRule, InterfaceState};
use super::{DriverError, Outcome, StopReason};

/// Runs `problem` from its initial state to a stop; `progress` hears the fraction of the
/// duration done (about every 1 %).
pub(crate) fn run<C: ChainDynamics>(
    problem: Problem<'_, C>,
    progress: Option<&mut dyn FnMut(f64)>,
) -> Result<Outcome, DriverError> {
    Ok(run_segment(problem, progress, None, None)?.0)
}

/// How a segment of a run ended: its outcome, the state it stopped at, and whether the crowding
/// rule stopped it (the outcome's stop reason is then a placeholder,
/// [`StopReason::TooManyEvents`]).
pub(crate) type SegmentEnd = (Outcome, State, bool);

/// [`run`] from `start` (`None`: released at rest at time 0, as [`run`]) until a stop or, with
/// `crowding`, until the events crowd (docs/auto-scheme.md). Without
/// `start` and `crowding` the same run as [`run`], bit for bit.
pub(crate) fn run_segment<C: ChainDynamics>(
    mut problem: Problem<'_, C>,
    progress: Option<&mut dyn FnMut(f64)>,
    start: Option<&InterfaceState>,
    crowding: Option<CrowdingRule>,
) -> Result<SegmentEnd, DriverError> {
    let mut run = Run::new(&problem);
    if let Some(s) = start {
        run.state = State::resumed(s);
    }
    let mut crowding = crowding.map(Crowding::new);
    let mut progress = Progress::new(progress, problem.opts.stopping.duration);
    // Released at rest: the column stands, or opens at once (the reaction test fails).
    run.start(&mut problem)?;
    loop {
        progress.at(run.state.t());
        if let Some(c) = crowding.as_mut() {
            if c.observe(run.state.t(), run.recorder.events_counted()) {
                let Run {
                    state, recorder, ..
                } = run;
                let outcome =
                    recorder.finish(StopReason::TooManyEvents, &state, &mut problem.chain);
                return Ok((outcome, state, true));
            }
        }
        let stop = match run.stop_before_step(&mut problem) {
            Some(reason) => Some(reason),
            None => {
                run.step.plan(&problem, &run.state);
                if run.state.is_closed() {
                    run.closed_step(&mut problem)?
                } else {
                    run.rocking_step(&mut problem)?
                }
            }
        };
        if let Some(reason) = stop {
            if reason == StopReason::Duration {
                progress.at_end();
            }
            let Run {
                state, recorder, ..
            } = run;
            let outcome = recorder.finish(reason, &state, &mut problem.chain);
            return Ok((outcome, state, false));
        }
    }
}

/// The parts of a run beside its problem: the state, the step, what is kept, and the memory of
/// the settling rule and of the energy bound.
struct Run {
    state: State,
    step: Step,
    probe: Probe,
    recorder: Recorder,
    settling: Settling,
    cannot_tip: Option<CannotTip>,
    monolith: Option<Monolith>,
}

impl Run {
    fn new<C: ChainDynamics>(problem: &Problem<C>) -> Run {
        let opts = &problem.opts;
        let n = problem.chain.n_joints();
        let e_tip = problem.chain.tipping_energy();
        Run {
            state: State::released(n, opts.initial_angles),
            step: Step::new(n, opts.stepping.integrator),
            probe: Probe::new(n),
            recorder: Recorder::new(n, opts.recording, opts.stopping.duration, opts.stepping.dt),
            settling: Settling::new(opts, n, e_tip),
            cannot_tip: CannotTip::new(problem, n, e_tip),
            monolith: rest::monolith(problem),
        }
    }

    fn start<C: ChainDynamics>(&mut self, problem: &mut Problem<C>) -> Result<(), DriverError> {
        let state = &mut self.state;
        state.ag = problem.ag(state.t());
        let (_, potential) = problem.chain.energy(&state.open, &state.phi, &state.rates);
        state.refresh(&mut problem.chain)?;
        self.recorder.start(state, potential);
        if state.margin.iter().any(|&v| v > 0.0) {
            opening::judge(problem, state, &mut self.probe, &mut self.recorder, true)?;
        }
        Ok(())
    }

    /// The stop before the next step: the duration done, too many events, at rest for good, or
    /// provably safe.
    fn stop_before_step<C: ChainDynamics>(
        &mut self,
        problem: &mut Problem<C>,
    ) -> Option<StopReason> {
        let (t, stopping) = (self.state.t(), &problem.opts.stopping);
        if stopping.duration - t <= 1e-9 * problem.opts.stepping.dt {
            Some(StopReason::Duration)
        } else if self.recorder.events_counted() as f64
            > stopping.max_events_per_second * t.max(1.0)
        {
            Some(StopReason::TooManyEvents)
        } else {
            let (cannot_tip, steps) = (self.cannot_tip.as_ref(), self.recorder.steps());
            let monolith = self.monolith.as_mut();
            rest::stop(problem, &self.state, cannot_tip, monolith, steps)
        }
    }

    /// Every interface closed: the column moves with the ground until the reaction test fails.
    fn closed_step<C: ChainDynamics>(
        &mut self,
        problem: &mut Problem<C>,
    ) -> Result<Option<StopReason>, DriverError> {
        let Run { state, step, .. } = self;
        let c = problem.chain.check(
            &[],
            &state.statuses,
            step.ag1,
            &state.phi,
            &state.rates,
            true,
        );
        if c.max_margin > 0.0 {
            let s = detect::opening_fraction(problem, state, step, &mut self.probe, c.max_margin);
            let clock = state.clock.advanced(s * step.h);
            state.set_time(clock, problem.ag(clock.t));
            state.refresh(&mut problem.chain)?;
            if !opening::judge(problem, state, &mut self.probe, &mut self.recorder, true)? {
                // The model keeps the column closed: accept the step (counted as an event so
                // that a disagreement can never loop).
                self.recorder.count_event();
                state.set_time(step.end, step.ag1);
                state.refresh(&mut problem.chain)?;
            }
            return Ok(None);
        }
        state.set_time(step.end, step.ag1);
        if let Some(stop) = forces::sliding(&c, state, &mut self.recorder) {
            return Ok(Some(stop));
        }
        state.margin.copy_from_slice(problem.chain.margins());
        state.power = 0.0;
        self.recorder.accepted_step(state);
        Ok(None)
    }

    /// Some interface open: integrate the open DOFs (thesis Eq. 6), check the step's end, and
    /// either move to the first event inside the step and apply its model, or accept the step.
    fn rocking_step<C: ChainDynamics>(
        &mut self,
        problem: &mut Problem<C>,
    ) -> Result<Option<StopReason>, DriverError> {
        let Run {
            state,
            step,
            probe,
            recorder,
            ..
        } = self;
        step.advance(problem, state)?;
        let c = problem.chain.check(
            &state.open,
            &state.statuses,
            step.ag1,
            &step.phi1,
            &step.rates1,
            true,
        );
        if !c.ok {
            return Err(not_positive_definite());
        }
        // Checks (1)-(2) of SPEC §5: the first opening or impact inside the step, located, the
        // state moved there and the model applied; the next step starts from the event.
        if let Some((s, found)) = detect::first_event(problem, state, step, probe, c.max_margin) {
            recorder.count_event();
            refine::move_to_event(
                problem,
                state,
                step,
                probe,
                recorder,
                s,
                found,
                c.max_margin,
            )?;
            match found {
                Found::Impact(d) => {
                    impact::apply(problem, state, recorder, &mut self.settling, d)?;
                    opening::judge(problem, state, probe, recorder, false)?;
                }
                Found::Opening => {
                    if !opening::judge(problem, state, probe, recorder, true)? {
                        state.refresh(&mut problem.chain)?;
                    }
                }
            }
            return Ok(None);
        }
        // No event: accept the step, then checks (3)-(4) at its end (contact forces, tipping).
        recorder.ground_work(0.5 * step.h * (state.power + c.power));
        step.accept(state, &problem.chain, c.power);
        recorder.peaks(problem.chain.block_angles());
        let stop = forces::stop(&c, state, recorder).or_else(|| {
            overturn::stop(
                &c,
                state,
                recorder,
                problem.opts.stopping.continue_until_fallen,
            )
        });
        if stop.is_none() {
            recorder.accepted_step(state);
        }
        Ok(stop)
    }
}

/// The progress callback, called about every 1 % of the duration.
struct Progress<'p> {
    callback: Option<&'p mut dyn FnMut(f64)>,
    duration: f64,
    next: f64,
}

impl<'p> Progress<'p> {
    fn new(callback: Option<&'p mut dyn FnMut(f64)>, duration: f64) -> Self {
        Progress {
            callback,
            duration,
            next: 0.0,
        }
    }

    fn at(&mut self, t: f64) {
        if let Some(cb) = self.callback.as_mut() {
            if t >= self.next {
                cb((t / self.duration).min(1.0));
                self.next += 0.01 * self.duration;
            }
        }
    }

    fn at_end(&mut self) {
        if let Some(cb) = self.callback.as_mut() {
            cb(1.0);
        }
    }
}
