//! Overturning (SPEC §5): the centre of mass of the part above an open interface beyond its
//! pivot (static tipping) stops the run — or, with `continue_until_fallen`, is recorded once per
//! interface and the run goes on until a block has rotated by `π/2`.

use crate::driver::chain::Check;
use crate::driver::recorder::Recorder;
use crate::driver::state::State;
use crate::driver::{EventKind, StopReason};

/// The overturning verdict of `check` at `state`.
pub(crate) fn stop(
    check: &Check,
    state: &State,
    recorder: &mut Recorder,
    continue_until_fallen: bool,
) -> Option<StopReason> {
    if let Some(k) = check.tipped {
        if !continue_until_fallen {
            recorder.stop_event(state, EventKind::Overturned, k);
            return Some(StopReason::Overturned { interface: k });
        }
        if recorder.tipped(k) {
            recorder.stop_event(state, EventKind::Overturned, k);
        }
    }
    match check.fallen {
        Some(k) if continue_until_fallen => Some(StopReason::Fallen { interface: k }),
        _ => None,
    }
}
