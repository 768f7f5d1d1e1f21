//! The opening transition (thesis 3.2.2, SPEC §3): the opening model decides which interfaces
//! open, and which way. At the instant the reaction test fires the violated reaction is exactly
//! zero, so no opening configuration is strictly admissible there (SPEC §5 trap (a)): the model
//! is judged a little past the instant, the state carried ahead by a Taylor step.

use super::Probe;
use crate::driver::chain::ChainDynamics;
use crate::driver::problem::Problem;
use crate::driver::recorder::Recorder;
use crate::driver::state::State;
use crate::driver::{DriverError, EventKind};

/// Look-ahead ladder of the opening judgement, in time steps.
const LOOK_AHEAD: [f64; 4] = [1e-3, 1e-2, 1e-1, 1.0];

/// The opening judgement a little past the current instant: returns whether something opened
/// (then `state` is the new configuration, evaluated, and the event recorded). `escalate`:
/// widen the look-ahead up to one step while the reaction test holds there or the model keeps
/// the configuration.
pub(crate) fn judge<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &mut State,
    probe: &mut Probe,
    recorder: &mut Recorder,
    escalate: bool,
) -> Result<bool, DriverError> {
    let ladder = if escalate {
        &LOOK_AHEAD[..]
    } else {
        &LOOK_AHEAD[..1]
    };
    for &f in ladder {
        let eps = f * problem.opts.stepping.dt;
        for d in 0..state.phi.len() {
            probe.phi[d] = state.phi[d] + eps * state.rates[d] + 0.5 * eps * eps * state.acc[d];
            probe.rates[d] = state.rates[d] + eps * state.acc[d];
        }
        let ag = problem.ag(state.t() + eps);
        let chain = &mut problem.chain;
        if probe.check(chain, state, ag).max_margin <= 0.0 {
            continue;
        }
        chain.assemble(&state.statuses, ag, &probe.phi, &probe.rates);
        let mut statuses = state.statuses.clone();
        let report = chain.opening(&mut statuses, &problem.opts.physics.model)?;
        if !report.changed {
            continue;
        }
        let before = std::mem::replace(&mut state.statuses, statuses);
        let first = (0..state.n()).find(|&k| before[k] != state.statuses[k]);
        state.reconfigure(chain);
        let kinetic = chain.kinetic_energy(&state.rates);
        recorder.event(
            state,
            EventKind::Opening,
            first,
            kinetic,
            kinetic,
            Some(&before),
            Some(report),
        );
        state.refresh(chain)?;
        return Ok(true);
    }
    Ok(false)
}
