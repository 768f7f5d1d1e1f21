//! The impact transition (thesis 3.2.3, SPEC §2): an open DOF is back at zero; the impact model
//! gives the configuration and the rates after, and the energy lost is booked. Shrinking impacts
//! may then settle the interface ([`super::settle`]).

use super::settle::Settling;
use crate::driver::chain::ChainDynamics;
use crate::driver::problem::Problem;
use crate::driver::recorder::Recorder;
use crate::driver::state::State;
use crate::driver::{DriverError, EventKind};

/// Impact of DOF `d` at the current instant (its angle is set to zero); the state is evaluated
/// after it (and after settling).
pub(crate) fn apply<C: ChainDynamics>(
    problem: &mut Problem<C>,
    state: &mut State,
    recorder: &mut Recorder,
    settling: &mut Settling,
    d: usize,
) -> Result<(), DriverError> {
    let k = d % state.n();
    state.phi[d] = 0.0;
    let chain = &mut problem.chain;
    chain.assemble(&state.statuses, state.ag, &state.phi, &state.rates);
    if state.sign(d) * state.rates[d] > 0.0 {
        // Touching zero without moving towards it (a grazing DOF, located at zero with a rate
        // the wrong way): the DOF is removed by the kinetic-metric projection (the rates closest
        // to the state's in kinetic energy with its rate zero, as settling does), which never
        // raises the energy — zeroing its rate alone would leave the other interfaces' rates as
        // they are, and the blocks' absolute velocities would no longer cancel: the energy could
        // rise (it did, up to 6× on drum columns). The loss is booked as dissipated, so the
        // event reports the energy the impact model actually received.
        let grazing = chain.kinetic_energy(&state.rates);
        chain.lock(&state.open, d, &mut state.rates);
        recorder.dissipated(grazing - chain.kinetic_energy(&state.rates));
    }
    let kinetic_before = chain.kinetic_energy(&state.rates);
    let mut statuses = state.statuses.clone();
    let mut rates = state.rates.clone();
    let report = chain.impact(&mut statuses, &mut rates, &[k], &problem.opts.physics.model)?;
    let before = std::mem::replace(&mut state.statuses, statuses);
    state.rates.copy_from_slice(&rates);
    state.reconfigure(chain);
    let kinetic_after = report.kinetic_after;
    recorder.dissipated(kinetic_before - kinetic_after);
    recorder.event(
        state,
        EventKind::Impact,
        Some(k),
        kinetic_before,
        kinetic_after,
        Some(&before),
        Some(report),
    );
    settling.after_impact(chain, state, recorder, k, kinetic_after);
    state.refresh(chain)
}
