//! Columns: no constraints, one closing joint = the existing models, bit for bit.

use super::*;

use super::common::column_scene::column_scene;

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
