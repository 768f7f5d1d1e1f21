//! `rocking thesis`: the thesis's reference values (SPEC §8) through the library.

use std::process::ExitCode;

use rocking::model::column::{Block, Column, GRAVITY};
use rocking::{impact_model, opening_model, samples, ModelOptions, Solver, Status};

/// One line of the comparison table; returns whether it matches to the printed digits.
fn line(what: &str, got: f64, printed: f64, decimals: i32) -> bool {
    let half = 0.5 * 10f64.powi(-decimals);
    let ok = (got - printed).abs() <= half * (1.0 + 1e-9);
    let width = (decimals + 6) as usize;
    println!(
        "  {what:<52} {got:>width$.prec$}   thesis {printed:>width$.dec$}   {}",
        if ok { "ok" } else { "MISMATCH" },
        prec = (decimals + 2) as usize,
        dec = decimals as usize,
    );
    ok
}

fn loss(before: f64, after: f64) -> f64 {
    100.0 * (1.0 - after / before)
}

/// Runs the command.
pub fn run() -> ExitCode {
    let mut ok = true;
    println!(
        "rocking {}: the thesis's reference values (SPEC §8)\n",
        env!("CARGO_PKG_VERSION")
    );

    println!("Housner energy loss, Table 1 (single block, impact model):");
    for (h_over_b, printed) in [(2.0, 51.0), (3.0, 27.8), (4.0, 16.9)] {
        let column =
            Column::new(vec![Block::rectangle(0.1, 0.1 * h_over_b, 1.0)]).expect("valid block");
        let mass = column.mass_matrix(&column.pose(&[0.0, 0.0]));
        let mut st = vec![Status::OpenLeft];
        let mut v = vec![0.0, -1.0];
        let r = impact_model(&mass, &mut st, &mut v, 0, &ModelOptions::default())
            .expect("valid impact");
        ok &= line(
            &format!("h/b = {h_over_b} [%]"),
            loss(r.kinetic_before, r.kinetic_after),
            printed,
            1,
        );
    }
    let prieto = Column::new(vec![Block {
        width: 0.246,
        height: 0.5,
        mass: 1.0,
        inertia: None,
        contact_width: Some(0.160),
    }])
    .expect("valid block");
    let mass = prieto.mass_matrix(&prieto.pose(&[0.0, 0.0]));
    let mut st = vec![Status::OpenLeft];
    let mut v = vec![0.0, -1.0];
    let r =
        impact_model(&mass, &mut st, &mut v, 0, &ModelOptions::default()).expect("valid impact");
    ok &= line(
        "Prieto 2007 cut corners, Eq. A3 [%]",
        loss(r.kinetic_before, r.kinetic_after),
        25.2,
        1,
    );

    println!("\nTwo blocks 0.1 x 0.3 m, 15 kg; the upper one closes at 1 rad/s (Eq. 10, 11):");
    let case = samples::two_block_impact();
    ok &= line("M[0][2] (Eq. 10)", case.mass[2], 3.550, 3);
    for (n_impacts, rates, block2, printed_loss) in [
        (1, [-0.1079, -0.5965], 0.7044, 25.6),
        (2, [-0.0539, -0.7983], 0.8522, 13.9),
    ] {
        for solver in [Solver::Enumerate, Solver::Projection] {
            let mut st = case.statuses.clone();
            let mut v = case.velocity.clone();
            let opts = ModelOptions {
                n_impacts,
                solver,
                ..ModelOptions::default()
            };
            let r = impact_model(&case.mass, &mut st, &mut v, case.closing, &opts)
                .expect("valid impact");
            let tag = format!("{n_impacts} impact(s), {solver:?}");
            ok &= st == vec![Status::OpenRight, Status::OpenRight];
            ok &= line(
                &format!("{tag}: rate of interface 0 [rad/s]"),
                v[0],
                rates[0],
                4,
            );
            ok &= line(
                &format!("{tag}: rate of interface 1 [rad/s]"),
                v[1],
                rates[1],
                4,
            );
            ok &= line(
                &format!("{tag}: block 2 [rad/s]"),
                -(v[0] + v[1]),
                block2,
                4,
            );
            ok &= line(
                &format!("{tag}: energy lost [%]"),
                loss(r.kinetic_before, r.kinetic_after),
                printed_loss,
                1,
            );
        }
    }

    println!("\nOpening, Fig. 18-19 (top push): the bottom opens the 'wrong' way (Fig. 19e):");
    let case = samples::two_block_top_push();
    let mut st = vec![Status::Closed; 2];
    let mut a = vec![0.0; 4];
    let r = opening_model(
        &case.mass,
        &case.load,
        &mut st,
        &mut a,
        &ModelOptions::default(),
    )
    .expect("valid opening");
    let codes: Vec<i8> = st.iter().map(|s| s.as_i8()).collect();
    let matches = st == case.expected;
    ok &= matches;
    println!(
        "  statuses after {codes:?} (bottom about its left corner, top about its right)   {}  [{} configurations]",
        if matches { "ok" } else { "MISMATCH" },
        r.configurations_examined
    );

    println!("\nAppendix C, two 1 x 4 m blocks of 1 kg, a_g = -1 m/s^2:");
    let column = Column::new(vec![
        Block::rectangle(1.0, 4.0, 1.0),
        Block::rectangle(1.0, 4.0, 1.0),
    ])
    .expect("valid");
    for (label, phi, m11, m12, m22, p1, p2) in [
        (
            "straight (C12, C13)",
            [0.0, 0.0, 0.0, 0.0],
            43.333,
            13.667,
            5.667,
            1.810,
            2.905,
        ),
        (
            "upper block at 10 deg (C15, C16)",
            [0.0, -10f64.to_radians(), 0.0, 0.0],
            43.785,
            13.892,
            5.667,
            -1.728,
            -0.633,
        ),
    ] {
        let pose = column.pose(&phi);
        let m = column.mass_matrix(&pose);
        let q = column.load_vector(&pose, -1.0, GRAVITY);
        ok &= line(&format!("{label}: M11"), m[0], m11, 3);
        ok &= line(&format!("{label}: M12"), m[1], m12, 3);
        ok &= line(&format!("{label}: M22"), m[5], m22, 3);
        ok &= line(&format!("{label}: p1 [Nm]"), q[0], p1, 3);
        ok &= line(&format!("{label}: p2 [Nm]"), q[1], p2, 3);
    }

    println!(
        "\n{}",
        if ok {
            "all reference values reproduced"
        } else {
            "SOME VALUES DO NOT MATCH"
        }
    );
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
