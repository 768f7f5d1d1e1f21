//! The state handed between the event-driven driver (interface coordinates: per joint a status
//! and the angle and rate of its open DOF; the thesis's) and the Moreau–Jean scheme (natural
//! coordinates `x, y, θ` per drum), and the rule that says when a column is calm enough to be
//! handed back (docs/auto-scheme.md).

use super::moreau::Stepper;
use super::simulation::JointMode;
use crate::driver::switch::InterfaceState;
use crate::model::column::Column;
use crate::model::configuration::Status;

/// Puts the driver's state `s` into the stepper: positions and velocities of the thesis's
/// kinematics ([`super::drums::Drums::from_interface_state`]: exact, no slip, every pivot on its
/// face), the ends in contact marked as persistent (a pivot that carried the column keeps the
/// midpoint rule, as if the scheme had run before). Returns the kinetic energy of the state.
pub(crate) fn to_natural(st: &mut Stepper, column: &Column, s: &InterfaceState) -> f64 {
    let n = column.n_interfaces();
    let mut q = vec![0.0; 3 * n];
    let mut v = vec![0.0; 3 * n];
    st.drums()
        .from_interface_state(column, &s.phi, &s.rates, &mut q, &mut v);
    st.set_state(s.t, &q, &v);
    for k in 0..n {
        st.carried[k] = st.statuses[k].closed;
    }
    st.kinetic_energy()
}

/// The driver's state of the stepper's, when every joint is closed or rocking about one end
/// (`mode`) with its relative rotation on the side of its pivot: per joint the relative rotation
/// and rate of the two drums it joins on the open DOF, zero when closed (the closed joints'
/// relative rates, round-off of a sticking contact, are dropped). `None` when a joint flies or
/// its rotation is on the wrong side of its pivot.
pub(crate) fn to_interface(st: &Stepper, mode: &[JointMode]) -> Option<InterfaceState> {
    let n = mode.len();
    let mut phi = vec![0.0; 2 * n];
    let mut rates = vec![0.0; 2 * n];
    let mut statuses = vec![Status::Closed; n];
    let (mut below, mut below_rate) = (0.0, 0.0);
    for k in 0..n {
        let (theta, omega) = (st.q[3 * k + 2], st.v[3 * k + 2]);
        let (r, w) = (theta - below, omega - below_rate);
        (below, below_rate) = (theta, omega);
        match mode[k] {
            JointMode::Closed => {}
            JointMode::RockingRight if r < 0.0 => {
                statuses[k] = Status::OpenRight;
                phi[k] = r;
                rates[k] = w;
            }
            JointMode::RockingLeft if r > 0.0 => {
                statuses[k] = Status::OpenLeft;
                phi[n + k] = r;
                rates[n + k] = w;
            }
            _ => return None,
        }
    }
    Some(InterfaceState {
        t: st.t,
        phi,
        rates,
        statuses,
    })
}

/// Whether the column is calm: no event for `window` seconds, every joint closed or rocking,
/// none slipping, and every slip within `slip_tolerance` of its joint's contact half-width.
pub(crate) fn calm(
    st: &Stepper,
    mode: &[JointMode],
    slipping: &[bool],
    quiet_since: f64,
    window: f64,
    slip_tolerance: f64,
) -> bool {
    st.t - quiet_since >= window
        && !mode.contains(&JointMode::Flying)
        && !slipping.contains(&true)
        && st
            .geometry
            .iter()
            .enumerate()
            .all(|(k, g)| g.slip.abs() <= slip_tolerance * st.drums().upper_extent(k))
}
