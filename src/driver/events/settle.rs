//! Settling (SPEC §5): repeated impacts of shrinking amplitude must end in a closed interface,
//! not in an endless sequence. After an impact that leaves the closing interface open about its
//! other corner, the interface is closed for good when the kinetic energy left is tiny (a
//! fraction of the energy that tips the column) or the impacts there come too close together;
//! its DOF is removed by the kinetic-metric projection of the rates.

use crate::driver::chain::ChainDynamics;
use crate::driver::options::RunOptions;
use crate::driver::recorder::Recorder;
use crate::driver::state::State;
use crate::driver::EventKind;
use crate::model::cholesky;
use crate::model::configuration::Status;

/// The settling rule and its memory.
pub(crate) struct Settling {
    /// Kinetic energy below which an interface settles (`settle_energy_fraction · E_tip`).
    energy: f64,
    /// Impact interval below which an interface settles (s).
    interval: f64,
    /// Time of the last impact at each interface.
    last_impact: Vec<f64>,
}

impl Settling {
    /// The rule of `opts` for a chain of `n` interfaces whose tipping energy is `e_tip`.
    pub fn new(opts: &RunOptions, n: usize, e_tip: f64) -> Settling {
        let stopping = &opts.stopping;
        Settling {
            energy: stopping.settle_energy_fraction * e_tip,
            interval: stopping.settle_interval.unwrap_or(4.0 * opts.stepping.dt),
            last_impact: vec![f64::NEG_INFINITY; n],
        }
    }

    /// After an impact at interface `k` that left `kinetic_after`: settles it if the rule says
    /// so (the chain's assembled system is the impact's).
    pub fn after_impact(
        &mut self,
        chain: &mut impl ChainDynamics,
        state: &mut State,
        recorder: &mut Recorder,
        k: usize,
        kinetic_after: f64,
    ) {
        let interval = state.t() - self.last_impact[k];
        self.last_impact[k] = state.t();
        let Some(dof) = state.statuses[k].dof(k, state.n()) else {
            return;
        };
        if kinetic_after < self.energy || interval < self.interval {
            let before = state.statuses.clone();
            chain.lock(&state.open, dof, &mut state.rates);
            state.statuses[k] = Status::Closed;
            state.reconfigure(chain);
            let kinetic = chain.kinetic_energy(&state.rates);
            recorder.dissipated(kinetic_after - kinetic);
            recorder.event(
                state,
                EventKind::Settled,
                Some(k),
                kinetic_after,
                kinetic,
                Some(&before),
                None,
            );
        }
    }
}

/// Removes DOF `d` from the open set `open` by the kinetic-metric projection
/// `v_F ← v_F + M_FF⁻¹ M_{F,d} v_d`, `v_d ← 0` (the velocity closest to `v` in kinetic energy with
/// `d` locked). `mass` is the full row-major `m × m` matrix.
pub(crate) fn lock_dof(mass: &[f64], m: usize, open: &[usize], d: usize, rates: &mut [f64]) {
    let others: Vec<usize> = open.iter().copied().filter(|&f| f != d).collect();
    let k = others.len();
    let vd = rates[d];
    rates[d] = 0.0;
    if k == 0 || vd == 0.0 {
        return;
    }
    let mut a = vec![0.0; k * k];
    let mut x = vec![0.0; k];
    for (r, &fr) in others.iter().enumerate() {
        for (c, &fc) in others.iter().enumerate() {
            a[r * k + c] = mass[fr * m + fc];
        }
        x[r] = mass[fr * m + d] * vd;
    }
    if cholesky::factor(&mut a, k) {
        cholesky::solve(&a, k, &mut x);
        for (r, &fr) in others.iter().enumerate() {
            rates[fr] += x[r];
        }
    }
}
