//! The fused path of small columns (`small.rs`) against the general path, bit for bit.

use super::{ColumnDynamics, Kernel};
use crate::driver::chain::{ChainDynamics, Check, Equations};
use crate::model::column::{Block, Column};
use crate::model::configuration::{open_dofs, Status};

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn key(c: &Check) -> String {
    format!(
        "{:x} {:?} {:?} {:?} {:?} {:x} {}",
        c.max_margin.to_bits(),
        c.tension,
        c.sliding,
        c.tipped,
        c.fallen,
        c.power.to_bits(),
        c.ok
    )
}

/// The fused path of two- and three-block columns gives the general path's accelerations,
/// checks, margins and block rotations bit for bit, on random states (unequal blocks, both
/// equations, small and large rotations, with and without the contact forces).
#[test]
fn small_columns_are_the_general_path_bit_for_bit() {
    let mut rnd = crate::test_support::uniform(987654321u64);
    let three = Column::new(vec![
        Block::rectangle(0.5, 1.5, 200.0),
        Block::rectangle(0.4, 1.0, 120.0),
        Block::rectangle(0.3, 0.8, 60.0),
    ])
    .unwrap();
    let two = Column::uniform(2, 1.0, 12.0, 3000.0).unwrap();
    let columns = [three, two, Column::uniform(3, 0.7, 8.4, 50.0).unwrap()];
    let mut fused_calls = 0;
    for col in &columns {
        let n = col.n_interfaces();
        for exact in [false, true] {
            let mut fused = ColumnDynamics::new(col, 9.81, exact, 1e-9, 0.7);
            let mut general = ColumnDynamics::new(col, 9.81, exact, 1e-9, 0.7);
            assert!(!matches!(fused.kernel, Kernel::General));
            general.kernel = Kernel::General;
            for case in 0..4000 {
                let statuses: Vec<Status> = (0..n)
                    .map(|_| match (rnd() * 3.0) as usize {
                        0 => Status::OpenRight,
                        1 => Status::Closed,
                        _ => Status::OpenLeft,
                    })
                    .collect();
                let open = open_dofs(&statuses);
                let big = if case % 4 == 0 { 2.0 } else { 0.05 };
                let mut phi = vec![0.0; 2 * n];
                let mut rates = vec![0.0; 2 * n];
                for &d in &open {
                    let sigma = if d < n { -1.0 } else { 1.0 };
                    phi[d] = sigma * big * rnd();
                    rates[d] = 4.0 * (rnd() - 0.5);
                }
                let ag = 20.0 * (rnd() - 0.5);
                if open.is_empty() {
                    continue;
                }
                for dy in [&mut fused, &mut general] {
                    dy.reconfigured();
                }
                let forces = case % 3 != 0;
                let a = fused.check(&open, &statuses, ag, &phi, &rates, forces);
                let b = general.check(&open, &statuses, ag, &phi, &rates, forces);
                assert_eq!(key(&a), key(&b), "{statuses:?} {phi:?}");
                assert_eq!(bits(&fused.acc_full), bits(&general.acc_full));
                assert_eq!(bits(&fused.margin), bits(&general.margin));
                assert_eq!(bits(&fused.block_angles), bits(&general.block_angles));
                fused_calls += 1;
                if open.len() >= 2 {
                    let k = open.len();
                    let x: Vec<f64> = open.iter().map(|&d| phi[d] * 1.01).collect();
                    let v: Vec<f64> = open.iter().map(|&d| rates[d] * 0.99).collect();
                    let (mut oa, mut ob) = (vec![0.0; k], vec![0.0; k]);
                    let ra = fused.accel(&open, &statuses, ag, &x, &v, &mut oa);
                    let rb = general.accel(&open, &statuses, ag, &x, &v, &mut ob);
                    assert_eq!((ra, bits(&oa)), (rb, bits(&ob)), "{statuses:?} {phi:?}");
                    fused_calls += 1;
                }
                let (ea, eb) = (
                    fused.energy(&open, &phi, &rates),
                    general.energy(&open, &phi, &rates),
                );
                assert_eq!(bits(&[ea.0, ea.1]), bits(&[eb.0, eb.1]));
                assert_eq!(bits(&fused.phi), bits(&general.phi));
                assert_eq!(bits(&fused.rates), bits(&general.rates));
            }
        }
    }
    assert!(fused_calls > 20_000, "{fused_calls}");
}
