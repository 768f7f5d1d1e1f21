//! The monolith stop of a column under thesis Eq. 6 ([`StopReason::CannotTip`], with
//! `stopping.stop_when_safe` and `stopping.quiet_after`): after the ground has gone quiet for good,
//! a column that rocks as one rigid body about a base corner (every other interface closed) can
//! be proven to go on doing so, and not to tip, to the end of the run
//! (docs/column-early-stop.md).
//!
//! The proof, by the first instant `τ` at which the column stops rocking as a monolith or closed:
//! - **Energy.** One DOF open: Eq. 6 is the exact equation of a rigid body turning about a fixed
//!   pivot `P` (its `M_FF = I_P` is constant, no velocity term), so `E = T + V` changes only by
//!   the ground's power `−M a_g ẋ_G`, `|ẋ_G| ≤ ρ |θ̇|` (`ρ = |G − P|`), `½ I_P θ̇² ≤ E` while
//!   `V ≥ 0`: `√E(s) ≤ √E(t) + M ρ / √(2 I_P) · ∫_t^∞ |a_g| =: x` (the single-block bound).
//!   Impacts (kinetic-metric projections) and settling only lower it. An impact turns the
//!   column about the other corner: the growth, `E_tip` and `θ_m` below are those of both.
//! - **Tipping.** Only the monolith can tip (every other part is closed); it needs
//!   `E_tip = M g (ρ − y_G)`. The stop asks `x ≤ 0.9 √E_tip`, the 0.9 for the integration
//!   error as in the other stops; then `V ≤ E_b = (x / 0.9)² ≤ E_tip` bounds the rotation by
//!   `θ_m`, `V(θ_m) = E_b`.
//! - **No other interface opens.** Under Eq. 6 the reaction margin of a closed DOF `d` above
//!   (interface `k ≥ 1`, corner `C`) does not depend on the rates: with `f` the load per unit mass
//!   `(−a_g, −g)` in the frame of the turned column (`R(−θ) f`), `ε = (W_P × f) / I_P` and
//!   `σ_d (q_d − M_dP ε) / √M_dd = U_d × R(−θ) f`, `U_d = σ_d (W_d − M_dP / I_P · W_P) / √M_dd`,
//!   `W_a = S_0 (g − P_a)` of the straight column (read off its load entries). Over
//!   `|θ| ≤ θ_m` (widened by two steps at the largest rate, for the probes inside and past a
//!   step) and `|a_g| ≤ A` — after `quiet_after` the column's static uplift acceleration —
//!   `U_d × R(−θ) f = −g (R(θ) U_d)_x + a_g (R(θ) U_d)_y
//!   ≤ −g (U_x cos θ_m − |U_y| sin θ_m) + A (U_x sin θ_m + |U_y|)` (if `U_x > 0`); the stop asks
//!   this `≤ −10⁻⁶ g |U_d|` for every such DOF, so no reaction test fails and the opening model
//!   is never called (test `the_reaction_bound_holds_the_drivers_margins`).
//! - **Impacts keep it one body.** A monolith impact happens in the straight pose (the DOF is
//!   set to zero) with only the base rate non-zero; the impact model is a projection, positively
//!   homogeneous in that rate, so its outcome is the same for every rate of a sign. It is checked
//!   once per run (both base corners; zero and six rates from 10⁻⁶ to 10³ rad/s): every other
//!   interface stays closed. After a closing the column is closed, and after `quiet_after` that is
//!   the stop [`StopReason::AtRest`].
//!
//! So up to `τ` the column is a monolith with `E ≤ E_b`, no opening can happen at `τ` and no
//! impact opens anything: `τ` is the end of the run, and nothing tips. The stop proves only
//! that; the run's later events (impacts, a tension stop) are not reported.

use crate::driver::chain::ChainDynamics;
use crate::driver::problem::Problem;
use crate::driver::state::State;
use crate::model::column::Column;
use crate::model::cone::ModelOptions;
use crate::model::configuration::Status;
use crate::model::impact::impact_model;

/// Share of `√E_tip` the energy bound may reach (as [`super::rest`]).
const SAFETY_FACTOR: f64 = 0.9;
/// Relative margin of the reaction bound.
const MARGIN: f64 = 1e-6;
/// Base rates of the check of the impact model (rad/s).
const RATES: [f64; 7] = [0.0, 1e-6, 1e-3, 0.1, 0.7, 1.0, 1e3];

/// The constants of the column rocking about one base corner.
#[derive(Clone, Debug)]
struct Side {
    /// `W_P = S_0 (g − P)` of the whole column.
    w: [f64; 2],
    /// `I_P`.
    ip: f64,
    /// The DOFs of the interfaces above the base and their `U_d`.
    u: Vec<(usize, [f64; 2])>,
}

/// The monolith stop of a column of two or more blocks under Eq. 6.
#[derive(Clone, Debug)]
pub(crate) struct Monolith {
    n: usize,
    g: f64,
    /// The column's static uplift acceleration, above `|a_g|` after `quiet_after`.
    accel: f64,
    /// Right corner (DOF 0), left corner (DOF n).
    sides: [Side; 2],
    /// `2n × 2n` mass matrix of the straight column.
    straight_mass: Vec<f64>,
    /// Whether the impact model keeps a monolith one body (checked once, when first needed).
    impacts_keep: Option<bool>,
}

impl Monolith {
    /// The constants of `col` under gravity `g`.
    pub fn of_column(col: &Column, g: f64) -> Monolith {
        let n = col.n_interfaces();
        let pose = col.pose(&vec![0.0; 2 * n]);
        let w_of = |a: usize| [-pose.load_entry(a, 0.0, 1.0), pose.load_entry(a, 1.0, 0.0)];
        let side = |p: usize| {
            let (w, ip) = (w_of(p), pose.mass_entry(p, p));
            let mut u = Vec::with_capacity(2 * n);
            for k in 1..n {
                for d in [k, n + k] {
                    let sigma = if d < n { -1.0 } else { 1.0 };
                    let (wd, r) = (w_of(d), pose.mass_entry(d, p) / ip);
                    let s = sigma / pose.mass_entry(d, d).sqrt();
                    u.push((d, [s * (wd[0] - r * w[0]), s * (wd[1] - r * w[1])]));
                }
            }
            Side { w, ip, u }
        };
        Monolith {
            n,
            g,
            accel: col.static_uplift_acceleration(g),
            sides: [side(0), side(n)],
            straight_mass: col.mass_matrix(&pose),
            impacts_keep: None,
        }
    }

    /// Whether, at `state` (after `quiet_after`), the column provably rocks on as a monolith and
    /// never tips.
    pub fn proves<C: ChainDynamics>(&mut self, problem: &mut Problem<C>, state: &State) -> bool {
        let n = self.n;
        let [p] = state.open[..] else {
            return false;
        };
        if (p != 0 && p != n) || state.statuses[1..].iter().any(|s| s.is_open()) {
            return false;
        }
        let straight = (0..2 * n).all(|d| d == p || (state.phi[d] == 0.0 && state.rates[d] == 0.0));
        if !straight {
            return false;
        }
        let Some(impulse) = problem.motion.remaining_impulse(state.t()) else {
            return false;
        };
        let g = self.g;
        // An impact turns the column about the other corner: the bound of both.
        let (mut growth, mut e_tip) = (0.0_f64, f64::INFINITY);
        for side in &self.sides {
            let rho_m = side.w[0].hypot(side.w[1]);
            growth = growth.max(rho_m / (2.0 * side.ip).sqrt());
            e_tip = e_tip.min(g * (rho_m - side.w[1]));
        }
        let (kin, pot) = problem.chain.energy(&state.open, &state.phi, &state.rates);
        let x = (kin + pot).max(0.0).sqrt() + growth * impulse;
        if !(e_tip > 0.0 && x <= SAFETY_FACTOR * e_tip.sqrt()) {
            return false;
        }
        let (e_bound, dt) = ((x / SAFETY_FACTOR).powi(2), problem.opts.stepping.dt);
        let reactions_hold = [0, n].iter().all(|&q| {
            // The largest rotation about this corner: `V(θ) = g (ρ_M cos(β − θ) − W_y)`,
            // `ρ_M = M ρ`.
            let side = &self.sides[usize::from(q != 0)];
            let [wx, wy] = side.w;
            let rho_m = wx.hypot(wy);
            let beta = wx.abs().atan2(wy);
            let c = ((wy + e_bound / g) / rho_m).min(1.0);
            let omega = (2.0 * e_bound / side.ip).sqrt();
            let theta = ((beta - c.acos()).max(0.0) * (1.0 + 1e-6) + 2.0 * dt * omega + 1e-12)
                .min(0.5 * std::f64::consts::PI);
            self.reaction_bounds(q, theta, self.accel)
                .all(|(_, bound, u)| bound <= -MARGIN * g * u)
        });
        reactions_hold && self.impacts_keep_it(&problem.opts.physics.model)
    }

    /// Rocking about base DOF `p`: for each DOF `d` above the base, an upper bound of its
    /// reaction margin over `|θ| ≤ theta` and `|a_g| ≤ a` (`+∞` unless `U_x > 0`), and `|U_d|`.
    fn reaction_bounds(
        &self,
        p: usize,
        theta: f64,
        a: f64,
    ) -> impl Iterator<Item = (usize, f64, f64)> + '_ {
        let g = self.g;
        let (s, co) = theta.sin_cos();
        self.sides[usize::from(p != 0)]
            .u
            .iter()
            .map(move |&(d, [ux, uy])| {
                let bound = if ux > 0.0 {
                    -g * (ux * co - uy.abs() * s) + a * (ux * s + uy.abs())
                } else {
                    f64::INFINITY
                };
                (d, bound, ux.hypot(uy))
            })
    }

    /// Whether a monolith impact, about either base corner, leaves every other interface closed.
    fn impacts_keep_it(&mut self, options: &ModelOptions) -> bool {
        let (n, mass) = (self.n, &self.straight_mass);
        *self.impacts_keep.get_or_insert_with(|| {
            [0, n].iter().all(|&p| {
                let corner = Status::of_dof(p, n);
                RATES.iter().all(|&rate| {
                    let mut statuses = vec![Status::Closed; n];
                    statuses[0] = corner;
                    let mut rates = vec![0.0; 2 * n];
                    rates[p] = -corner.sign() * rate;
                    impact_model(mass, &mut statuses, &mut rates, 0, options).is_ok()
                        && statuses[1..].iter().all(|s| !s.is_open())
                })
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::driver::chain::ChainDynamics;
    use crate::driver::dynamics::ColumnDynamics;
    use crate::spectra::column_of_size;

    /// The driver's reaction margins of `col` rocking about base DOF `p` at `theta`, `a_g` and
    /// base rate `rate` (Eq. 6, tolerance 0, so that a margin is the raw reaction test).
    fn margins(
        chain: &mut ColumnDynamics,
        n: usize,
        p: usize,
        theta: f64,
        ag: f64,
        rate: f64,
    ) -> Vec<f64> {
        let corner = Status::of_dof(p, n);
        let mut statuses = vec![Status::Closed; n];
        statuses[0] = corner;
        let (mut phi, mut rates) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        phi[p] = corner.sign() * theta;
        rates[p] = rate;
        chain.check(&[p], &statuses, ag, &phi, &rates, false);
        chain.margins().to_vec()
    }

    /// At `count` random poses `|θ| ≤ theta_max`, rates and ground accelerations `|a_g| ≤ A`
    /// (the column's static uplift acceleration), every margin of a DOF above the base lies
    /// below the bound of its `|θ|` and `|a_g|`.
    fn bound_holds_at_random_states(
        col: &Column,
        p: usize,
        theta_max: f64,
        count: usize,
        next: &mut impl FnMut() -> f64,
    ) {
        let g = 9.81;
        let mut chain = ColumnDynamics::new(col, g, false, 0.0, f64::INFINITY);
        let mono = Monolith::of_column(col, g);
        let big_a = col.static_uplift_acceleration(g);
        for _ in 0..count {
            let theta = theta_max * next().powi(2);
            let ag = big_a * (2.0 * next() - 1.0);
            let rate = 10.0 * (2.0 * next() - 1.0);
            let m = margins(&mut chain, col.n_interfaces(), p, theta, ag, rate);
            for (d, bound, u) in mono.reaction_bounds(p, theta, ag.abs()) {
                assert!(
                    m[d] <= bound + 1e-12 * g * u,
                    "DOF {d}: θ {theta}, a_g {ag}: {} > {bound}",
                    m[d]
                );
            }
        }
    }

    /// The closed form of the stop against the driver's own reaction margins: at the straight
    /// pose the bound is the largest margin over `a_g = ±A`, to rounding; at 4 000 random poses,
    /// rates and ground accelerations every margin lies below the bound of its `|θ|` and `|a_g|`
    /// — whatever the rate (Eq. 6 has no velocity term). 2 and 3 blocks, H/B 4 and 12, both base
    /// corners.
    #[test]
    fn the_reaction_bound_holds_the_drivers_margins() {
        let g = 9.81;
        let mut next = crate::test_support::uniform(0x005e_ed0f_b10c);
        for n in [2, 3] {
            for slenderness in [4.0, 12.0] {
                let col = column_of_size(1.5, slenderness, n).unwrap();
                let mut chain = ColumnDynamics::new(&col, g, false, 0.0, f64::INFINITY);
                let mono = Monolith::of_column(&col, g);
                let big_a = col.static_uplift_acceleration(g);
                for p in [0, n] {
                    let plus = margins(&mut chain, n, p, 0.0, big_a, 0.0);
                    let minus = margins(&mut chain, n, p, 0.0, -big_a, 1.0);
                    let mut count = 0;
                    for (d, bound, u) in mono.reaction_bounds(p, 0.0, big_a) {
                        let largest = plus[d].max(minus[d]);
                        assert!(bound.is_finite() && bound < 0.0, "{n} blocks, DOF {d}");
                        assert!(
                            (largest - bound).abs() <= 1e-12 * g * u,
                            "{largest} {bound}"
                        );
                        count += 1;
                    }
                    assert_eq!(count, 2 * (n - 1));
                    bound_holds_at_random_states(&col, p, 0.05, 1000, &mut next);
                }
            }
        }
    }

    /// On columns of equal blocks (the sweeps' columns) only the energy condition ever decides.
    /// On unequal ones the other two do:
    /// - a 1 × 2 m block under a 0.8 × 2 m one: the bound still holds the driver's margins; with
    ///   the column rocking as one body below its tipping angle and `|a_g|` within the column's
    ///   static uplift acceleration `A` (the stop's range after `quiet_after`), the driver's
    ///   margin of the upper interface turns positive (it would open), and the bound over that
    ///   range is positive: the stop declines this column, whatever its energy;
    /// - a 0.5 × 2 m block on the same base: rocking about a base corner already loads the upper
    ///   interface open (`U_x ≤ 0` for one of its DOFs: no bound), and an impact of the monolith opens it, so the stop
    ///   never fires.
    #[test]
    fn the_reaction_and_impact_conditions_decide_on_unequal_columns() {
        use crate::model::column::Block;
        let g = 9.81;
        let mut next = crate::test_support::uniform(0x0b10_c5ed);
        let base = Block::rectangle(1.0, 2.0, 5000.0);
        let col = Column::new(vec![base, Block::rectangle(0.8, 2.0, 4000.0)]).unwrap();
        let (n, top) = (2, [1, 3]);
        let mut chain = ColumnDynamics::new(&col, g, false, 0.0, f64::INFINITY);
        let mut mono = Monolith::of_column(&col, g);
        let big_a = col.static_uplift_acceleration(g);
        // Tipping angle of the whole column: its centre of mass 17/9 m above the base.
        let tipping = (0.5_f64 / (17.0 / 9.0)).atan();
        for p in [0, n] {
            bound_holds_at_random_states(&col, p, tipping, 2000, &mut next);
            let opening = (0..100)
                .flat_map(|k| [-big_a, big_a].map(|ag| (tipping * f64::from(k) / 100.0, ag)))
                .find(|&(theta, ag)| {
                    let m = margins(&mut chain, n, p, theta, ag, 0.0);
                    top.iter().any(|&d| m[d] > 0.0)
                });
            assert!(
                opening.is_some(),
                "corner {p}: the upper interface never opens"
            );
            assert!(mono
                .reaction_bounds(p, 0.0, big_a)
                .any(|(_, bound, _)| bound > 0.0));
        }
        assert!(mono.impacts_keep_it(&ModelOptions::default()));

        let col = Column::new(vec![base, Block::rectangle(0.5, 2.0, 2500.0)]).unwrap();
        let mut mono = Monolith::of_column(&col, g);
        for p in [0, n] {
            assert!(mono
                .reaction_bounds(p, 0.0, 0.0)
                .any(|(_, bound, _)| bound == f64::INFINITY));
        }
        assert!(!mono.impacts_keep_it(&ModelOptions::default()));
        let corner = Status::of_dof(0, n);
        let opened = RATES.iter().any(|&rate| {
            let mut statuses = vec![corner, Status::Closed];
            let mut rates = vec![0.0; 2 * n];
            rates[0] = -corner.sign() * rate;
            let mass = col.mass_matrix(&col.pose(&[0.0; 4]));
            impact_model(
                &mass,
                &mut statuses,
                &mut rates,
                0,
                &ModelOptions::default(),
            )
            .is_ok()
                && statuses[1].is_open()
        });
        assert!(
            opened,
            "a monolith impact about the right corner opens the upper interface"
        );
    }
}
