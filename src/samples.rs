//! Canonical cases with known answers (SPEC §8), shared by tests, benches, examples and the C and
//! Python smoke tests.

use crate::model::column::{Block, Column, GRAVITY};
use crate::model::configuration::Status;

/// Two granite blocks 0.1 × 0.3 m, 15 kg each (thesis 3.2.3, Eq. 10).
pub fn two_granite_column() -> Column {
    Column::new(vec![
        Block::rectangle(0.1, 0.3, 15.0),
        Block::rectangle(0.1, 0.3, 15.0),
    ])
    .expect("valid blocks")
}

/// An impact problem: mass matrix, configuration and velocities before, closing interface.
#[derive(Clone, Debug, PartialEq)]
pub struct ImpactCase {
    /// `2n × 2n` mass matrix, row-major.
    pub mass: Vec<f64>,
    /// Configuration before the impact.
    pub statuses: Vec<Status>,
    /// DOF rates before the impact.
    pub velocity: Vec<f64>,
    /// The closing interface.
    pub closing: usize,
}

/// Thesis Fig. 22: the lower block at rest, the upper one rotating about its left corner
/// (`phî_1`) closes at 1 rad/s. Expected (one impact): rates `(−0.1079, −0.5965)` about the right
/// corners, 25.6 % loss; two impacts: `(−0.0539, −0.7983)`, 13.9 % loss (SPEC §2 misprints).
pub fn two_block_impact() -> ImpactCase {
    let col = two_granite_column();
    ImpactCase {
        mass: col.mass_matrix(&col.pose(&[0.0; 4])),
        statuses: vec![Status::Closed, Status::OpenLeft],
        velocity: vec![0.0, 0.0, 0.0, -1.0],
        closing: 1,
    }
}

/// An opening problem with the expected configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct OpeningCase {
    /// `2n × 2n` mass matrix, row-major.
    pub mass: Vec<f64>,
    /// Load vector.
    pub load: Vec<f64>,
    /// Expected configuration.
    pub expected: Vec<Status>,
}

/// Thesis Fig. 18–19: the two granite blocks under gravity and a horizontal force at the top of
/// the upper block (10 × the weight of one block, to the right). The top interface opens about
/// its right corner; the bottom one about its LEFT corner — opposite to the "obvious" guess of
/// Fig. 18b, as the thesis says (Fig. 19e).
pub fn two_block_top_push() -> OpeningCase {
    let col = two_granite_column();
    let pose = col.pose(&[0.0; 4]);
    let mut load = col.load_vector(&pose, 0.0, GRAVITY);
    let force = 10.0 * 15.0 * GRAVITY;
    let top = [0.0, 0.6];
    for (a, q) in load.iter_mut().enumerate() {
        let k = a % 2;
        let p = if a < 2 {
            pose.right_pivots[k]
        } else {
            pose.left_pivots[k]
        };
        // Generalised force of a horizontal force F at `top`: −(r − P)_y F.
        *q += -(top[1] - p[1]) * force;
    }
    OpeningCase {
        mass: col.mass_matrix(&pose),
        load,
        expected: vec![Status::OpenLeft, Status::OpenRight],
    }
}
