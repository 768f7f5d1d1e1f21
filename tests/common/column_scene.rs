//! Random columns for the property tests of the models (`tests/models.rs`) and of their
//! constrained forms without constraints (`tests/closed_chains/columns.rs`): 1–6 blocks of random
//! sizes and masses, statuses, angles, rates and ground acceleration, one closing interface whose
//! DOF moves towards zero.

use proptest::prelude::*;
use rocking::model::column::{Block, Column, GRAVITY};
use rocking::Status;

/// A random column, its configuration and the interface that closes.
#[derive(Clone, Debug)]
pub struct ColumnScene {
    pub column: Column,
    pub statuses: Vec<Status>,
    pub phi: Vec<f64>,
    pub rates: Vec<f64>,
    pub closing: usize,
    pub ground_acc: f64,
}

pub fn column_scene() -> impl Strategy<Value = ColumnScene> {
    (1usize..=6)
        .prop_flat_map(|n| {
            (
                prop::collection::vec((0.2f64..2.0, 0.3f64..3.0, 1.0f64..100.0), n),
                prop::collection::vec(-1i8..=1, n),
                prop::collection::vec(0.001f64..0.3, n),
                prop::collection::vec(-2.0f64..2.0, n),
                0..n,
                -3.0f64..3.0,
            )
        })
        .prop_map(|(blocks, status, angle, rate, closing, acc)| {
            let n = blocks.len();
            let column = Column::new(
                blocks
                    .iter()
                    .map(|&(w, h, m)| Block::rectangle(w, h, m))
                    .collect(),
            )
            .unwrap();
            let mut statuses: Vec<Status> = status
                .iter()
                .map(|&s| Status::from_i8(s).unwrap())
                .collect();
            if statuses[closing] == Status::Closed {
                statuses[closing] = Status::OpenLeft;
            }
            let mut phi = vec![0.0; 2 * n];
            let mut rates = vec![0.0; 2 * n];
            for k in 0..n {
                if let Some(d) = statuses[k].dof(k, n) {
                    phi[d] = statuses[k].sign() * angle[k];
                    rates[d] = rate[k];
                }
            }
            // The closing DOF moves towards zero.
            let d = statuses[closing].dof(closing, n).unwrap();
            phi[d] = statuses[closing].sign() * 1e-9;
            rates[d] = -statuses[closing].sign() * (0.05 + rate[closing].abs());
            ColumnScene {
                column,
                statuses,
                phi,
                rates,
                closing,
                ground_acc: acc * GRAVITY,
            }
        })
}
