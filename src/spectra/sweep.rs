//! What every sweep shares: the simulation options, the columns of a size grid, the parallel
//! map over the points and the progress callback.

use super::{at_least_one_block, SpectraError, TimeStep};
use crate::driver::{PhysicsOptions, Recording, RunOptions, SimulationOptions, StoppingOptions};
use crate::model::column::{Block, Column};
use crate::model::single_block::EquivalentBlock;
use crate::validate::{non_negative, positive};

/// A column of `n_blocks` equal uniform blocks whose equivalent block
/// ([`EquivalentBlock::of_size`]) has slenderness `H/B = slenderness` and size
/// `R = ½√(B² + H²) = size` \[m\] (unit total mass: overturning does not depend on it).
pub fn column_of_size(
    size: f64,
    slenderness: f64,
    n_blocks: usize,
) -> Result<Column, SpectraError> {
    positive("size", size)?;
    positive("slenderness", slenderness)?;
    at_least_one_block(n_blocks)?;
    let block = EquivalentBlock::of_size(size, slenderness);
    let n = n_blocks as f64;
    Ok(Column::new(
        (0..n_blocks)
            .map(|_| Block::rectangle(block.width, block.height / n, 1.0 / n))
            .collect(),
    )?)
}

/// Options shared by the OC and OAS sweeps.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepOptions {
    /// Template of every simulation: integrator, event locator, impact model
    /// (`physics.model.n_impacts`: 1 = Housner, 2 = the thesis's recommended model, 10 ≈
    /// rolling), friction, gravity, overturning criterion. Every simulation shares its physics
    /// and stops, with its own `stepping.dt` and `stopping.duration`, recording nothing.
    pub simulation: SimulationOptions,
    /// Time step rule.
    pub time_step: TimeStep,
    /// Simulated time after the motion ends, in units of `1/p` (a column still rocking when the
    /// motion ends may yet tip over).
    pub tail: f64,
    /// Records: end each simulation `tail / p` after the last instant at which the scaled record
    /// reaches the uplift acceleration, instead of after the end of the record. After that
    /// instant a column at rest can no longer lift off, and one still rocking is driven only by
    /// accelerations below `a_p,min` for the rest of the record, which it can survive the tail
    /// of but, in principle, not always the whole coda: an approximation that saves the weak
    /// codas of long records. `false` simulates the whole record.
    pub cut_after_last_exceedance: bool,
}

impl Default for SweepOptions {
    /// Driver defaults (Wilson θ = 1.4, linear event location, Housner impacts, static tipping),
    /// except friction: infinite (the thesis does not check sliding), and
    /// [`StoppingOptions::stop_when_safe`]: a single block that the rest of a record provably
    /// cannot tip stops early (same verdicts: `oas_energy_bound_changes_nothing` in the tests).
    fn default() -> SweepOptions {
        SweepOptions {
            simulation: SimulationOptions {
                physics: PhysicsOptions {
                    friction: f64::INFINITY,
                    ..PhysicsOptions::default()
                },
                stopping: StoppingOptions {
                    stop_when_safe: true,
                    ..StoppingOptions::default()
                },
                recording: Recording::NONE,
                ..SimulationOptions::default()
            },
            time_step: TimeStep::default(),
            tail: 2.0,
            cut_after_last_exceedance: false,
        }
    }
}

impl SweepOptions {
    pub(super) fn validate(&self) -> Result<(), SpectraError> {
        self.time_step.validate()?;
        non_negative("tail", self.tail)?;
        Ok(())
    }

    pub(super) fn simulation(&self, dt: f64, duration: f64) -> RunOptions<'_> {
        self.simulation.sweep_run(dt, duration)
    }
}

/// `(0..n).map(f)` collected in order, in parallel with the `parallel` feature.
pub(super) fn map_indexed<T: Send, F: Fn(usize) -> T + Sync + Send>(n: usize, f: F) -> Vec<T> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        (0..n).into_par_iter().map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        (0..n).map(f).collect()
    }
}

/// Called once per finished unit of work (a level of an OAS, a pulse duration of an OC).
pub type Progress<'a> = &'a (dyn Fn() + Sync);
