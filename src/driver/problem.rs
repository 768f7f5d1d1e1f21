//! What a run simulates: a chain under a ground motion, with its options.

use super::chain::ChainDynamics;
use super::options::RunOptions;
use crate::ground::GroundMotion;

pub(crate) struct Problem<'a, C: ChainDynamics> {
    /// The chain: its equations, checks and models.
    pub chain: C,
    pub motion: &'a dyn GroundMotion,
    /// [`GroundMotion::end_time`] of `motion`.
    pub motion_end: f64,
    pub opts: RunOptions<'a>,
}

impl<'a, C: ChainDynamics> Problem<'a, C> {
    pub fn new(chain: C, motion: &'a dyn GroundMotion, opts: RunOptions<'a>) -> Self {
        Problem {
            chain,
            motion,
            motion_end: motion.end_time(),
            opts,
        }
    }

    /// Ground acceleration at `t`.
    #[inline]
    pub fn ag(&self, t: f64) -> f64 {
        self.motion.acceleration(t)
    }
}
