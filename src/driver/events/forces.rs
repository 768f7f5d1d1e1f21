//! The contact-force stops (SPEC §5 check (3)): at every interface the normal force must be
//! compressive (`N ≥ 0`, else the column is coming apart: [`StopReason::Tension`]) and within
//! the friction cone (`μ N ≥ |V|`, else it slides: [`StopReason::Sliding`]). The rigid rocking
//! model holds no longer, so the run stops and says so.

use crate::driver::chain::Check;
use crate::driver::recorder::Recorder;
use crate::driver::state::State;
use crate::driver::{EventKind, StopReason};

/// The stop the forces of `check` (at `state`) call for, recorded as an event.
pub(crate) fn stop(check: &Check, state: &State, recorder: &mut Recorder) -> Option<StopReason> {
    if let Some(k) = check.tension {
        recorder.stop_event(state, EventKind::Tension, k);
        return Some(StopReason::Tension { interface: k });
    }
    sliding(check, state, recorder)
}

/// The sliding stop alone (a closed column: no tension is possible).
pub(crate) fn sliding(check: &Check, state: &State, recorder: &mut Recorder) -> Option<StopReason> {
    let k = check.sliding?;
    recorder.stop_event(state, EventKind::Sliding, k);
    Some(StopReason::Sliding { interface: k })
}
