//! Which event comes first inside a step, and where: the checks of SPEC §5 at the step's end —
//! (2) an open DOF that crossed zero moving back towards it (an impact; a DOF that has just
//! opened starts at zero and must not fire at once, trap (b): its return is located on the
//! Hermite cubic of the step with either locator), (1) a closed interface whose
//! reaction takes the inadmissible sign (an opening) — each located by the chosen
//! [`EventLocator`] as a fraction `s ∈ [0, 1]` of the step.

use super::locate::{hermite, hermite_crossing, hermite_rate, illinois};
use super::{Found, Probe};
use crate::driver::chain::ChainDynamics;
use crate::driver::problem::Problem;
use crate::driver::state::State;
use crate::driver::step::Step;
use crate::driver::EventLocator;

/// The first event of the step from `state` to `step`'s end, whose largest reaction margin is
/// `margin1` (the chain's last check is the step's end).
#[inline]
pub(crate) fn first_event<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &State,
    step: &Step,
    probe: &mut Probe,
    margin1: f64,
) -> Option<(f64, Found)> {
    let locator = problem.opts.stepping.locator;
    let mut found: Option<(f64, Found)> = None;
    for &d in &state.open {
        let sigma = state.sign(d);
        let (g0, g1) = (sigma * state.phi[d], sigma * step.phi1[d]);
        if g1 < 0.0 && g0 >= 0.0 {
            let s = match locator {
                // A DOF at exactly zero at the start of the step has just opened (SPEC §5 trap
                // (b)): the chord from zero would put its crossing at the start, the instant of
                // the opening, although it moved away and came back within the step. Its return
                // is located on the Hermite cubic instead (the root after its maximum on (0, 1]).
                EventLocator::Linear if g0 > 0.0 => g0 / (g0 - g1),
                _ => hermite_crossing(
                    step.h,
                    g0,
                    g1,
                    sigma * state.rates[d],
                    sigma * step.rates1[d],
                ),
            };
            if found.as_ref().map_or(true, |f| s < f.0) {
                found = Some((s, Found::Impact(d)));
            }
        }
    }
    if margin1 > 0.0 {
        let s = opening_fraction(problem, state, step, probe, margin1);
        if found.as_ref().map_or(true, |f| s < f.0) {
            found = Some((s, Found::Opening));
        }
    }
    found
}

/// Fraction of the step where the reaction test first fails (`margin1 > 0` at the end): the
/// linear interpolation of the margins (thesis), or Illinois on the largest margin evaluated on
/// the Hermite-interpolated state (with every interface closed: the straight column under the
/// ground acceleration of each instant).
pub(crate) fn opening_fraction<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &State,
    step: &Step,
    probe: &mut Probe,
    margin1: f64,
) -> f64 {
    match problem.opts.stepping.locator {
        EventLocator::Linear => linear_opening(&state.margin, problem.chain.margins()),
        EventLocator::Hermite => hermite_opening(problem, state, step, probe, margin1),
    }
}

/// Linear interpolation of the margins (thesis): earliest crossing over the violated DOFs.
fn linear_opening(m0: &[f64], m1: &[f64]) -> f64 {
    let mut s = 1.0_f64;
    for (&a, &b) in m0.iter().zip(m1) {
        if b > 0.0 {
            let si = if a > 0.0 || !a.is_finite() {
                0.0
            } else {
                a / (a - b)
            };
            s = s.min(si);
        }
    }
    s
}

fn hermite_opening<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &State,
    step: &Step,
    probe: &mut Probe,
    g1: f64,
) -> f64 {
    let g0 = state.largest_margin();
    if g0 > 0.0 {
        return 0.0;
    }
    let (t0, h) = (step.t0, step.h);
    let Problem { chain, motion, .. } = problem;
    let f = |s: f64| {
        probe.phi.copy_from_slice(&state.phi);
        probe.rates.copy_from_slice(&state.rates);
        for &d in &state.open {
            let (y0, y1) = (state.phi[d], step.phi1[d]);
            let (v0, v1) = (state.rates[d], step.rates1[d]);
            probe.phi[d] = hermite(s, h, y0, y1, v0, v1);
            probe.rates[d] = hermite_rate(s, h, y0, y1, v0, v1);
        }
        probe
            .check(chain, state, motion.acceleration(t0 + s * h))
            .max_margin
    };
    illinois(f, 0.0, g0, 1.0, g1, 1e-13)
}
