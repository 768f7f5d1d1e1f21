//! Ground motions: the [`GroundMotion`] trait the driver integrates against, pulses and
//! excitations (thesis Fig. 6, 8), and recorded accelerograms (PEER `.AT2`, plain text).

pub mod excitation;
pub mod records;

/// A horizontal ground acceleration history.
pub trait GroundMotion {
    /// Ground acceleration at time `t` (m/s², +x = right).
    fn acceleration(&self, t: f64) -> f64;
    /// Time after which the motion is zero (or ends) (s).
    fn end_time(&self) -> f64;
    /// An upper bound of `∫_t^∞ |a_g(s)| ds` (m/s), the most velocity the ground can still
    /// impose, or `None` when the motion cannot tell (the default). Used by
    /// [`crate::driver::StoppingOptions::stop_when_safe`].
    fn remaining_impulse(&self, _t: f64) -> Option<f64> {
        None
    }
}

/// A closure `t ↦ a_g(t)` with its end time.
#[derive(Clone, Copy, Debug)]
pub struct FnMotion<F>(pub F, pub f64);

impl<F: Fn(f64) -> f64> GroundMotion for FnMotion<F> {
    fn acceleration(&self, t: f64) -> f64 {
        (self.0)(t)
    }
    fn end_time(&self) -> f64 {
        self.1
    }
}

/// No ground motion (free rocking).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoMotion;

impl GroundMotion for NoMotion {
    fn acceleration(&self, _t: f64) -> f64 {
        0.0
    }
    fn end_time(&self) -> f64 {
        0.0
    }
}
