//! Columns: no constraints, one closing joint = the existing models, bit for bit.

use super::*;

#[derive(Clone, Debug)]
struct ColumnScene {
    column: Column,
    statuses: Vec<Status>,
    phi: Vec<f64>,
    rates: Vec<f64>,
    closing: usize,
    ground_acc: f64,
}

fn column_scene() -> impl Strategy<Value = ColumnScene> {
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

fn solver_of(i: u8) -> Solver {
    [Solver::Auto, Solver::Enumerate, Solver::Projection][i as usize % 3]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn unconstrained_impact_is_the_column_model(
        s in column_scene(), n_impacts in 1u32..=3, solver in 0u8..3
    ) {
        let n = s.column.n_interfaces();
        let mass = s.column.mass_matrix(&s.column.pose(&s.phi));
        let opts = ModelOptions { n_impacts, solver: solver_of(solver), ..ModelOptions::default() };
        let (mut st0, mut v0) = (s.statuses.clone(), s.rates.clone());
        let rep0 = impact_model(&mass, &mut st0, &mut v0, s.closing, &opts).unwrap();
        let mut closing = vec![false; n];
        closing[s.closing] = true;
        let (mut st1, mut v1) = (s.statuses.clone(), s.rates.clone());
        let rep1 =
            impact_model_constrained(&mass, &[], &mut st1, &mut v1, &closing, &opts).unwrap();
        prop_assert_eq!(st0, st1);
        prop_assert_eq!(
            v0.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            v1.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
        prop_assert_eq!(format!("{rep0:?}"), format!("{rep1:?}"));
    }

    #[test]
    fn unconstrained_opening_is_the_column_model(s in column_scene(), solver in 0u8..3) {
        let n = s.column.n_interfaces();
        let pose = s.column.pose(&s.phi);
        let mass = s.column.mass_matrix(&pose);
        let load = s.column.load_vector(&pose, s.ground_acc, GRAVITY);
        let opts = ModelOptions { solver: solver_of(solver), ..ModelOptions::default() };
        let (mut st0, mut a0) = (s.statuses.clone(), vec![0.0; 2 * n]);
        let rep0 = opening_model(&mass, &load, &mut st0, &mut a0, &opts).unwrap();
        let (mut st1, mut a1) = (s.statuses.clone(), vec![0.0; 2 * n]);
        let rep1 =
            opening_model_constrained(&mass, &load, &[], None, &mut st1, &mut a1, &opts).unwrap();
        prop_assert_eq!(st0, st1);
        prop_assert_eq!(
            a0.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            a1.iter().map(|x| x.to_bits()).collect::<Vec<_>>()
        );
        prop_assert_eq!(format!("{rep0:?}"), format!("{rep1:?}"));
    }
}
