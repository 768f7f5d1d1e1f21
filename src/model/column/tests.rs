use super::*;
use crate::samples;
use crate::test_support::assert_printed;

/// Thesis Eq. 10: the 4×4 mass matrix of two 0.1 × 0.3 m, 15 kg blocks.
#[test]
fn thesis_eq10_mass_matrix() {
    let col = samples::two_granite_column();
    let m = col.mass_matrix(&col.pose(&[0.0; 4]));
    for (r, row) in samples::THESIS_EQ10_MASS.iter().enumerate() {
        for (c, &printed) in row.iter().enumerate() {
            let printed = samples::Printed::new(printed, samples::THESIS_EQ10_DECIMALS);
            assert_printed(m[r * 4 + c], printed);
        }
    }
}

/// Appendix C, straight (`M̃` Eq. C13, `p̃` Eq. C12, rotations about the right corners) and the
/// upper block inclined by 10° about its right corner (Eq. C16, C15).
#[test]
fn appendix_c_printed_values() {
    for case in [
        samples::appendix_c_straight(),
        samples::appendix_c_inclined(),
    ] {
        let col = &case.column;
        let pose = col.pose(&case.phi);
        let m = col.mass_matrix(&pose);
        let q = col.load_vector(&pose, case.ground_acc, GRAVITY);
        for &(r, c, printed) in &case.mass {
            assert_printed(m[r * 4 + c], printed);
        }
        for &(r, printed) in &case.load {
            assert_printed(q[r], printed);
        }
    }
}

/// The FE route gives the same numbers: three mass points per block, `B` from the geometry,
/// `BᵀMB`, `Bᵀp` (thesis Eq. C9–C16).
#[test]
fn appendix_c_reduction_matches_direct_route() {
    let col = samples::appendix_c_straight().column;
    for phi in [
        [0.0, 0.0, 0.0, 0.0],
        [0.0, -10f64.to_radians(), 0.0, 0.0],
        [-0.05, 0.0, 0.0, 0.2],
    ] {
        let pose = col.pose(&phi);
        let pts = three_mass_points(&col, &pose);
        let np = pts.len();
        let points: Vec<[f64; 2]> = pts.iter().map(|p| p.0).collect();
        let owner: Vec<usize> = (0..np).map(|i| i / 3).collect();
        let b = transformation_matrix(&col, &pose, &points, &owner);
        let nn = 2 * np;
        let mut nodal_mass = vec![0.0; nn * nn];
        let mut nodal_load = vec![0.0; nn];
        for (i, (_, m)) in pts.iter().enumerate() {
            nodal_mass[i * nn + i] = *m;
            nodal_mass[(np + i) * nn + np + i] = *m;
            nodal_load[i] = -m * -1.0;
            nodal_load[np + i] = -m * GRAVITY;
        }
        let mut rm = vec![0.0; 16];
        let mut rl = vec![0.0; 4];
        reduce(nn, 4, &nodal_mass, &b, &nodal_load, &mut rm, &mut rl);
        let m = col.mass_matrix(&pose);
        let q = col.load_vector(&pose, -1.0, GRAVITY);
        for i in 0..16 {
            assert!((rm[i] - m[i]).abs() < 1e-10, "{i}: {} vs {}", rm[i], m[i]);
        }
        for i in 0..4 {
            assert!((rl[i] - q[i]).abs() < 1e-10);
        }
    }
}

#[test]
fn single_block_matches_appendix_b() {
    // Eq. B7: θ0 = 4/3 m (h² + b²), θ1 = 4/3 m (h² − b²/2) with 2h × 2b.
    let (h, b, m) = (1.3, 0.4, 7.0);
    let col = Column::new(vec![Block::rectangle(2.0 * b, 2.0 * h, m)]).unwrap();
    let mm = col.mass_matrix(&col.pose(&[0.0, 0.0]));
    assert!((mm[0] - 4.0 / 3.0 * m * (h * h + b * b)).abs() < 1e-12);
    assert!((mm[1] - 4.0 / 3.0 * m * (h * h - 0.5 * b * b)).abs() < 1e-12);
    assert!((col.static_uplift_acceleration(GRAVITY) - GRAVITY * b / h).abs() < 1e-12);
}

/// The velocity terms are the exact Lagrangian ones: compare with a finite-difference
/// derivative of the centre velocities for a two-block chain.
#[test]
fn velocity_load_matches_finite_differences() {
    let col = Column::new(vec![
        Block::rectangle(0.4, 1.2, 3.0),
        Block::rectangle(0.3, 0.9, 2.0),
    ])
    .unwrap();
    let phi = [0.0, -0.1, 0.05, 0.0];
    let rates = [0.0, -0.7, 0.4, 0.0];
    let pose = col.pose(&phi);
    let mut vl = [0.0; 4];
    col.velocity_load_into(&pose, &phi, &rates, &mut vl);
    // Centre positions along the path φ(t) = φ + t·rates (zero DOF acceleration).
    let centres = |t: f64| {
        let p: Vec<f64> = phi.iter().zip(&rates).map(|(a, r)| a + t * r).collect();
        col.pose(&p).centres
    };
    let h = 1e-4;
    let (cm, c0, cp) = (centres(-h), centres(0.0), centres(h));
    for a in 0..4 {
        let k = a % 2;
        let p = pose.pivot(a);
        let mut s = 0.0;
        for j in k..2 {
            let acc = [
                (cp[j][0] - 2.0 * c0[j][0] + cm[j][0]) / (h * h),
                (cp[j][1] - 2.0 * c0[j][1] + cm[j][1]) / (h * h),
            ];
            let r = [c0[j][0] - p[0], c0[j][1] - p[1]];
            s -= col.blocks()[j].mass * (r[0] * acc[1] - r[1] * acc[0]);
        }
        assert!((s - vl[a]).abs() < 1e-5, "a={a}: fd {s} vs {}", vl[a]);
    }
}

#[test]
fn rejects_bad_blocks() {
    assert_eq!(Column::new(vec![]), Err(ColumnError::Empty));
    let max = crate::model::configuration::MAX_INTERFACES;
    let block = Block::rectangle(1.0, 1.0, 2500.0);
    assert!(Column::new(vec![block; max]).is_ok());
    assert_eq!(
        Column::new(vec![block; max + 1]),
        Err(ColumnError::TooManyBlocks { blocks: max + 1 })
    );
    let e = Column::new(vec![Block::rectangle(1.0, f64::NAN, 1.0)]).unwrap_err();
    assert!(e.to_string().contains("height"));
    let mut b = Block::rectangle(1.0, 1.0, 1.0);
    b.contact_width = Some(2.0);
    assert!(Column::new(vec![b])
        .unwrap_err()
        .to_string()
        .contains("contact_width"));
    // Finite inputs that overflow: the derived inertia and the stacked height, named as such.
    assert!(matches!(
        Column::new(vec![Block::rectangle(1e200, 1.0, 1e10)]),
        Err(ColumnError::TooLarge { block: 0, .. })
    ));
    let tall = Block {
        inertia: Some(1.0),
        ..Block::rectangle(1.0, 1e308, 1.0)
    };
    assert!(matches!(
        Column::new(vec![tall; 2]),
        Err(ColumnError::TooLarge { block: 1, .. })
    ));
    // A given inertia is the caller's field: an infinite one stays an invalid block.
    let given = Block {
        inertia: Some(f64::INFINITY),
        ..Block::rectangle(1.0, 1.0, 1.0)
    };
    assert!(matches!(
        Column::new(vec![given]),
        Err(ColumnError::InvalidBlock { block: 0, .. })
    ));
}
