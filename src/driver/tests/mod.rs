//! Physics acceptance tests of the driver (thesis 3.3, 4.2, 4.3, Fig. 40; SPEC §5), by theme.

mod barrier;
mod checks;
mod integrators;
mod single_block;
mod thesis;

use super::chain::{ChainDynamics, Equations};
use super::dynamics::ColumnDynamics;
use super::reference::SingleBlockExact;
use super::*;
use crate::ground::{FnMotion, NoMotion};
use crate::model::column::{Block, GRAVITY};
use crate::model::configuration::Status;
use crate::model::opening::check_configuration;

const G: f64 = GRAVITY;

/// A uniform block `2b × 2h` (half dimensions, as Housner and Appendix A).
fn block(b: f64, h: f64) -> Column {
    Column::new(vec![Block::rectangle(2.0 * b, 2.0 * h, 100.0)]).unwrap()
}

fn free(angle: f64, duration: f64) -> SimulationOptions {
    SimulationOptions {
        stopping: StoppingOptions {
            duration,
            ..StoppingOptions::default()
        },
        initial: InitialState {
            angles: Some(vec![angle]),
        },
        ..SimulationOptions::default()
    }
}

/// Housner's velocity ratio (thesis Eq. 1, half dimensions h, b).
fn housner(b: f64, h: f64) -> f64 {
    (2.0 * h * h - b * b) / (2.0 * h * h + 2.0 * b * b)
}

/// Two consecutive impacts (thesis Eq. A8).
fn two_impacts(b: f64, h: f64) -> f64 {
    (2.0 * h * h + 0.5 * b * b) / (2.0 * h * h + 2.0 * b * b)
}

fn impacts(out: &Outcome) -> Vec<&Event> {
    out.events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .collect()
}
