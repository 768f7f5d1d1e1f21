//! The state moved to an event located inside a step: by linear interpolation (thesis), or by
//! integrating again from the start of the step over the located fraction (Hermite) — for a
//! high-order integrator after refining the event time on the integrated solution itself
//! ([`crate::driver::EventLocator::Hermite`]).

use super::locate::{illinois, quintic};
use super::{Found, Probe};
use crate::driver::chain::{not_positive_definite, ChainDynamics};
use crate::driver::problem::Problem;
use crate::driver::recorder::Recorder;
use crate::driver::state::State;
use crate::driver::step::Step;
use crate::driver::{DriverError, EventLocator};

/// Most re-integrations of one impact time refinement (high-order integrators).
const MAX_REFINE: usize = 8;

/// Moves `state` (the start of `step`) to the fraction `s` of the step, where `found` happens
/// (`margin1`: the largest reaction margin at the step's end). Open DOFs that would pass zero
/// there are held at zero (the located one is set to zero by the impact; others, crossing in
/// the same step a hair later, wait); the ground's work is booked, and the state is evaluated
/// afresh: every method (Wilson's acceleration state included) restarts from the equations of
/// motion at the event.
#[allow(clippy::too_many_arguments)]
pub(crate) fn move_to_event<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &mut State,
    step: &mut Step,
    probe: &mut Probe,
    recorder: &mut Recorder,
    s: f64,
    found: Found,
    margin1: f64,
) -> Result<(), DriverError> {
    let mut s = s;
    match problem.opts.stepping.locator {
        EventLocator::Linear => {
            for &d in &state.open {
                state.phi[d] += s * (step.phi1[d] - state.phi[d]);
                state.rates[d] += s * (step.rates1[d] - state.rates[d]);
            }
        }
        EventLocator::Hermite => {
            if s > 0.0 {
                if problem.opts.stepping.integrator.refines_events() {
                    s = match found {
                        Found::Impact(d) => refine_impact(problem, state, step, s, d)?,
                        Found::Opening => refine_opening(problem, state, step, probe, s, margin1)?,
                    };
                } else {
                    step.advance_to(problem, state, s)?;
                }
                step.stepper
                    .write_open(&state.open, &mut state.phi, &mut state.rates);
            }
        }
    }
    let h = step.h;
    let clock = state.clock.advanced(s * h);
    let ag = problem.ag(clock.t);
    for &d in &state.open {
        let sigma = state.sign(d);
        if sigma * state.phi[d] < 0.0 {
            state.phi[d] = 0.0;
        }
    }
    state.set_time(clock, ag);
    let power = problem
        .chain
        .power(&state.open, ag, &state.phi, &state.rates);
    recorder.ground_work(0.5 * s * h * (state.power + power));
    state.refresh(&mut problem.chain)
}

/// The impact time of DOF `d` on the re-integrated solution, from the Hermite estimate
/// `s_est`, first improved on the quintic Hermite interpolant of the step (angles, rates and
/// accelerations at both ends: error `O(h⁶)`): Newton's method on `σ φ_d(s)`, each iterate
/// one integrator step of `s h` from the start of the step, the derivative the integrated
/// rate. Once the correction `Δt` is below `1e-8` s and its own error (`|φ̈ Δt² / φ̇|`, twice
/// the remainder of the Newton step) below `1e-15` s, it is applied to the state by a
/// second-order Taylor shift instead of a further step (the shift's error in the rates,
/// `Δt²/2` times the jerk, is then of round-off size). Falls back to the Hermite time (the
/// plain locator) for a DOF not moving towards zero there or after `MAX_REFINE` iterates.
/// Leaves the state at the returned fraction in the stepper.
fn refine_impact<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &State,
    step: &mut Step,
    s_est: f64,
    d: usize,
) -> Result<f64, DriverError> {
    let i = state.open.iter().position(|&f| f == d).unwrap_or(0);
    let sigma = state.sign(d);
    let h = step.h;
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let mut s = s_est;
    {
        // The stepper still holds the whole step.
        let (y0, v0, a0) = (step.x0[i], step.v0[i], step.a0[i]);
        let (y1, v1, a1) = (step.phi1[d], step.rates1[d], step.stepper.a1[i]);
        let mut q = s_est;
        for _ in 0..4 {
            let (y, r) = quintic(q, h, y0, y1, v0, v1, a0, a1);
            if sigma * r >= 0.0 {
                q = f64::NAN;
                break;
            }
            let dq = -y / (r * h);
            q += dq;
            if dq.abs() < 1e-15 {
                break;
            }
        }
        if q > 0.0 && q <= 1.0 {
            s = q;
        }
    }
    for _ in 0..MAX_REFINE {
        step.advance_to(problem, state, s)?;
        let st = &mut step.stepper;
        let g = sigma * st.x1[i];
        let rate = sigma * st.v1[i];
        if g >= 0.0 {
            lo = lo.max(s);
        } else {
            hi = hi.min(s);
        }
        if rate.is_nan() || rate >= 0.0 {
            break;
        }
        let dt = -g / rate;
        let remainder = (sigma * st.a1[i] * dt * dt / rate).abs();
        if dt.abs() <= 1e-8 && remainder <= 1e-15 {
            for r in 0..state.open.len() {
                let (v, a) = (st.v1[r], st.a1[r]);
                st.x1[r] += dt * (v + 0.5 * dt * a);
                st.v1[r] += dt * a;
            }
            return Ok(s + dt / h);
        }
        let next = s + dt / h;
        s = if next > lo && next < hi {
            next
        } else {
            0.5 * (lo + hi)
        };
    }
    step.advance_to(problem, state, s_est)?;
    Ok(s_est)
}

/// Largest reaction margin after one integrator step of `s h` from the start of the step.
fn margin_at<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &State,
    step: &mut Step,
    probe: &mut Probe,
    s: f64,
) -> Result<f64, DriverError> {
    step.advance_to(problem, state, s)?;
    probe.phi.copy_from_slice(&state.phi);
    probe.rates.copy_from_slice(&state.rates);
    step.stepper
        .write_open(&state.open, &mut probe.phi, &mut probe.rates);
    let ag = problem.ag(step.t0 + s * step.h);
    let c = probe.check(&mut problem.chain, state, ag);
    if c.ok {
        Ok(c.max_margin)
    } else {
        Err(not_positive_definite())
    }
}

/// The opening time on the re-integrated solution, from the Hermite estimate `s_est`:
/// a bracket of the largest margin grown from `1e-7` of the step on the side of the root
/// (factor 100; the step's ends bracket it in any case: `margin1 > 0` at the end), then
/// Illinois down to `1e-14` s. Leaves the state at the returned fraction in the stepper.
fn refine_opening<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &State,
    step: &mut Step,
    probe: &mut Probe,
    s_est: f64,
    margin1: f64,
) -> Result<f64, DriverError> {
    let g0 = state.largest_margin();
    let fe = margin_at(problem, state, step, probe, s_est)?;
    let after = fe > 0.0;
    let (mut a, mut fa, mut b, mut fb) = if after {
        (0.0, g0, s_est, fe)
    } else {
        (s_est, fe, 1.0, margin1)
    };
    let mut w = 1e-7;
    loop {
        let p = if after { s_est - w } else { s_est + w };
        if !(p > a && p < b) {
            break;
        }
        let fp = margin_at(problem, state, step, probe, p)?;
        if fp > 0.0 {
            (b, fb) = (p, fp);
        } else {
            (a, fa) = (p, fp);
        }
        if (fp > 0.0) != after {
            break;
        }
        w *= 100.0;
    }
    let tol = 1e-14 / step.h;
    let mut failed = None;
    let s = illinois(
        |s| match margin_at(problem, state, step, probe, s) {
            Ok(v) => v,
            Err(e) => {
                failed = Some(e);
                f64::NAN
            }
        },
        a,
        fa,
        b,
        fb,
        tol,
    );
    if let Some(e) = failed {
        return Err(e);
    }
    step.advance_to(problem, state, s)?;
    Ok(s)
}
