//! What the driver asks of a chain of rigid bodies (SPEC §1, §9): its equations of motion, the
//! checks at a state, its energies, and the two models. The stepper and every event transition
//! go through these traits, never through column code. The column's implementation is
//! `ColumnDynamics` (`dynamics.rs`) with the crate's models. Closed loops (an arch, a capped
//! colonnade) do not implement them yet: their driver (`closed/`) has its own fixed-step loop
//! on [`crate::chain`]'s geometry and the models of [`crate::model::constrained`]. To go through
//! these traits, `assemble` would also build the closure `G` and `Ġ v`, `impact` would take the
//! set of joints closing at once, and `check`, without a reaction test in a loop, would take its
//! opening margin from the opening model (e.g. the load power of the best admissible mechanism,
//! which crosses zero where the loop starts to move); the position and rate projections onto
//! the closure after every step have no counterpart in the column's loop yet.

use super::DriverError;
use crate::error::{ErrorKind, RockingError};
use crate::model::cone::{ModelOptions, ModelReport};
use crate::model::configuration::Status;

/// The equations of motion of the open DOFs, as the integrators need them.
pub(crate) trait Equations {
    /// Accelerations of the open DOFs `open` (reduced vectors `x`, `v`, output `out`, all of
    /// length `open.len()`) under the ground acceleration `ag`. Returns `false` if the mass
    /// matrix is not positive definite.
    fn accel(
        &mut self,
        open: &[usize],
        statuses: &[Status],
        ag: f64,
        x: &[f64],
        v: &[f64],
        out: &mut [f64],
    ) -> bool;

    /// When DOF `dof`, open alone, turns a rigid part about a pivot fixed to the ground: that
    /// rotation and gravity, whose scalar law `θ̈(θ, a_g)` the implicit integrators iterate on
    /// directly. `None`: no such closed form (e.g. a loop).
    fn rigid_rotation(&self, dof: usize) -> Option<(Rigid, f64)>;
}

/// A chain: its equations, the checks at a state, energies and the models.
pub(crate) trait ChainDynamics: Equations {
    /// Number of interfaces (joints) `n`; the DOFs are `2n`.
    fn n_joints(&self) -> usize;
    /// The configuration changed (scratch that depends on it is reset).
    fn reconfigured(&mut self);

    /// The end-of-step checks at a state (full `2n` angles and rates): accelerations, reaction
    /// margins, contact forces (with `forces`), tipping, power. The accelerations, margins and
    /// block rotations are then in [`ChainDynamics::accelerations`], [`ChainDynamics::margins`],
    /// [`ChainDynamics::block_angles`].
    fn check(
        &mut self,
        open: &[usize],
        statuses: &[Status],
        ag: f64,
        phi: &[f64],
        rates: &[f64],
        forces: bool,
    ) -> Check;
    fn accelerations(&self) -> &[f64];
    fn margins(&self) -> &[f64];
    fn block_angles(&self) -> &[f64];

    /// Kinetic and potential energy of a state (potential relative to the straight chain).
    fn energy(&mut self, open: &[usize], phi: &[f64], rates: &[f64]) -> (f64, f64);
    /// Power of the ground motion's inertial load at a state.
    fn power(&mut self, open: &[usize], ag: f64, phi: &[f64], rates: &[f64]) -> f64;
    /// Smallest potential energy that tips a part of the chain statically.
    fn tipping_energy(&self) -> f64;
    /// How fast `√E` can grow per unit ground acceleration when one rigid part rocks
    /// ([`super::StoppingOptions::stop_when_safe`]).
    fn energy_growth_bound(&self) -> f64;
    /// `√(M/2)`, `M` the total mass: how fast `√E` can grow per unit ground acceleration
    /// whatever moves, since the ground's power is `−a_g Σ m_j ẋ_j` and
    /// `|Σ m_j ẋ_j| ≤ √(M Σ m_j ẋ_j²) ≤ √(2 M T)` ([`super::StoppingOptions::stop_when_safe_column`]).
    fn column_growth_bound(&self) -> f64;
    /// Whether the barrier lemmas behind the column stop are certified for this chain
    /// ([`super::column_is_certified`]); the stop is then part of
    /// [`super::StoppingOptions::stop_when_safe`].
    fn barrier_certified(&self) -> bool {
        false
    }
    /// The monolith stop of a column under thesis Eq. 6 (`events/monolith.rs`), where it
    /// applies (a column of two or more blocks without the exact velocity terms).
    fn monolith(&self) -> Option<super::events::monolith::Monolith> {
        None
    }

    /// Assembles the models' input (mass matrix, loads) at a state; the next four calls use it.
    fn assemble(&mut self, statuses: &[Status], ag: f64, phi: &[f64], rates: &[f64]);
    /// Kinetic energy of the DOF rates `rates`.
    fn kinetic_energy(&self, rates: &[f64]) -> f64;
    /// The opening model (thesis 3.2.2): `statuses` becomes the chosen configuration.
    fn opening(
        &self,
        statuses: &mut [Status],
        options: &ModelOptions,
    ) -> Result<ModelReport, RockingError>;
    /// The impact model (thesis 3.2.3) as the interfaces `closing` close (a column: one):
    /// `statuses` and `rates` become the configuration and the rates after.
    fn impact(
        &self,
        statuses: &mut [Status],
        rates: &mut [f64],
        closing: &[usize],
        options: &ModelOptions,
    ) -> Result<ModelReport, RockingError>;
    /// Removes the open DOF `dof` by the kinetic-metric projection of `rates` (settling).
    fn lock(&self, open: &[usize], dof: usize, rates: &mut [f64]);
}

/// Rigid rotation of the part above interface `k_a` about the pivot of DOF `a` (straight column).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Rigid {
    pub s0: f64,
    /// `G − P` in the straight column.
    pub dx: f64,
    pub dy: f64,
    /// Inverse of the moment of inertia about the pivot, `1 / M_aa`.
    pub inv_ip: f64,
}

impl Rigid {
    /// `(r_x, r_y)` for the rotation `theta`.
    #[inline(always)]
    pub fn arm(&self, theta: f64) -> (f64, f64) {
        let (s, c) = theta.sin_cos();
        (c * self.dx - s * self.dy, s * self.dx + c * self.dy)
    }

    #[inline(always)]
    pub fn accel(&self, theta: f64, ag: f64, g: f64) -> f64 {
        let (rx, ry) = self.arm(theta);
        self.s0 * (ag * ry - g * rx) * self.inv_ip
    }
}

/// Results of the checks at a state ([`ChainDynamics::check`]; the accelerations, margins and block
/// rotations are left in the chain).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Check {
    /// Largest opening margin over the closed DOFs (`> 0`: the reaction test fails).
    pub max_margin: f64,
    pub tension: Option<usize>,
    pub sliding: Option<usize>,
    pub tipped: Option<usize>,
    pub fallen: Option<usize>,
    /// Power of the ground motion's inertial load, `Σ_f q^{ag}_f φ̇_f`.
    pub power: f64,
    /// `false` when the mass matrix of the configuration was not positive definite.
    pub ok: bool,
}

pub(crate) fn not_positive_definite() -> DriverError {
    DriverError::Model(RockingError::new(
        ErrorKind::NotPositiveDefinite,
        "the mass matrix of the open DOFs is not positive definite",
    ))
}
