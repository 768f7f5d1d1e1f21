//! Checks of the chain geometry against the column (an open chain), against finite differences
//! of the pose (kinetic energy, power of the loads, `Ġ v`, the Lagrangian velocity terms), and
//! the closed forms of the arch and the frame.

use super::arch::VoussoirArch;
use super::colonnade::CappedColonnade;
use super::*;
use crate::model::column::{Block, Column, GRAVITY};

fn column_chain(column: &Column) -> Chain {
    let mut y = 0.0;
    let mut bodies = Vec::new();
    let mut joints = Vec::new();
    for (k, b) in column.blocks().iter().enumerate() {
        joints.push(Joint {
            centre: [0.0, y],
            normal: [0.0, 1.0],
            half_width: column.half_contact_width(k),
        });
        bodies.push(Body {
            mass: b.mass,
            inertia: column.inertia(k),
            centre: [0.0, y + 0.5 * b.height],
        });
        y += b.height;
    }
    Chain::new(bodies, joints).unwrap()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn open_chain_is_the_column() {
    let column = Column::new(vec![
        Block::rectangle(0.8, 2.0, 500.0),
        Block::rectangle(0.6, 1.5, 300.0),
        Block::rectangle(0.7, 1.0, 200.0),
    ])
    .unwrap();
    let chain = column_chain(&column);
    assert!(!chain.is_loop());
    let phi = [-0.02, 0.0, -0.01, 0.0, 0.03, 0.0];
    let rates = [-0.5, 0.0, -0.2, 0.0, 0.7, 0.0];
    let (cp, pose) = (column.pose(&phi), chain.pose(&phi));
    let (mc, mch) = (column.mass_matrix(&cp), chain.mass_matrix(&pose));
    for (a, b) in mc.iter().zip(&mch) {
        assert!(close(*a, *b, 1e-12), "{a} vs {b}");
    }
    let (qc, qch) = (
        column.load_vector(&cp, 1.3, GRAVITY),
        chain.load_vector(&pose, 1.3, GRAVITY),
    );
    for (a, b) in qc.iter().zip(&qch) {
        assert!(close(*a, *b, 1e-12), "{a} vs {b}");
    }
    let mut vc = vec![0.0; 6];
    column.velocity_load_into(&cp, &phi, &rates, &mut vc);
    let vch = chain.velocity_load(&pose, &phi, &rates);
    for (a, b) in vc.iter().zip(&vch) {
        assert!(close(*a, *b, 1e-12), "{a} vs {b}");
    }
    assert!(chain.closure_matrix(&pose).is_empty());
}

/// A semicircular arch of 8 voussoirs with one DOF open per joint (a pose away from the
/// reference), its rates, and the chain.
fn bent_arch() -> (Chain, Vec<f64>, Vec<f64>) {
    let arch = VoussoirArch::semicircular(5.0, 0.9, 8);
    let chain = arch.chain().unwrap();
    let nj = chain.n_joints();
    let mut phi = vec![0.0; 2 * nj];
    let mut rates = vec![0.0; 2 * nj];
    for k in 0..nj {
        let a = 0.01 + 0.003 * k as f64;
        if k % 2 == 0 {
            phi[k] = -a;
            rates[k] = -0.4 + 0.1 * k as f64;
        } else {
            phi[nj + k] = a;
            rates[nj + k] = 0.3 - 0.05 * k as f64;
        }
    }
    (chain, phi, rates)
}

fn moved(phi: &[f64], rates: &[f64], h: f64) -> Vec<f64> {
    phi.iter().zip(rates).map(|(p, v)| p + h * v).collect()
}

/// `½ vᵀMv` equals the kinetic energy of the bodies whose velocities are finite differences of
/// the pose, and `qᵀv` the power of the loads.
#[test]
fn mass_matrix_and_load_are_kinetic_energy_and_power() {
    let (chain, phi, rates) = bent_arch();
    let pose = chain.pose(&phi);
    let m = chain.n_dofs();
    let mass = chain.mass_matrix(&pose);
    let ke: f64 = 0.5
        * (0..m)
            .map(|a| {
                (0..m)
                    .map(|b| rates[a] * mass[a * m + b] * rates[b])
                    .sum::<f64>()
            })
            .sum::<f64>();
    let h = 1e-6;
    let (p1, p0) = (
        chain.pose(&moved(&phi, &rates, h)),
        chain.pose(&moved(&phi, &rates, -h)),
    );
    let (ag, g) = (-2.1, GRAVITY);
    let mut ke_fd = 0.0;
    let mut power_fd = 0.0;
    for (j, body) in chain.bodies().iter().enumerate() {
        let v = [
            (p1.centres[j][0] - p0.centres[j][0]) / (2.0 * h),
            (p1.centres[j][1] - p0.centres[j][1]) / (2.0 * h),
        ];
        let w = (p1.maps[j].angle - p0.maps[j].angle) / (2.0 * h);
        ke_fd += 0.5 * body.mass * dot(v, v) + 0.5 * body.inertia * w * w;
        power_fd += body.mass * (-ag * v[0] - g * v[1]);
    }
    assert!(close(ke, ke_fd, 1e-8), "{ke} vs {ke_fd}");
    let q = chain.load_vector(&pose, ag, g);
    let power: f64 = q.iter().zip(&rates).map(|(a, b)| a * b).sum();
    assert!(close(power, power_fd, 1e-8), "{power} vs {power_fd}");
    // The cut joint moves no mass.
    let nj = chain.n_joints();
    for cut in [nj - 1, 2 * nj - 1] {
        assert!((0..m).all(|b| mass[cut * m + b] == 0.0));
        assert_eq!(q[cut], 0.0);
    }
}

/// `Ġ v` is the derivative of `G(φ + t v) v` at `t = 0`.
#[test]
fn closure_rate_is_the_derivative_of_g() {
    let (chain, phi, rates) = bent_arch();
    let m = chain.n_dofs();
    let gv = |h: f64| -> Vec<f64> {
        let g = chain.closure_matrix(&chain.pose(&moved(&phi, &rates, h)));
        (0..3)
            .map(|r| (0..m).map(|a| g[r * m + a] * rates[a]).sum())
            .collect()
    };
    let h = 1e-6;
    let (plus, minus) = (gv(h), gv(-h));
    let gdot = chain.closure_rate(&chain.pose(&phi), &rates);
    for r in 0..3 {
        let fd = (plus[r] - minus[r]) / (2.0 * h);
        assert!(close(gdot[r], fd, 1e-7), "row {r}: {} vs {fd}", gdot[r]);
    }
}

/// The velocity terms are those of Lagrange's equations: `M φ̈ = q + f_v` with
/// `f_v = −Ṁ v + ½ ∂(vᵀMv)/∂φ`, by finite differences on the open DOFs.
#[test]
fn velocity_load_is_lagrangian() {
    let (chain, phi, rates) = bent_arch();
    let m = chain.n_dofs();
    let h = 1e-6;
    let mass_at = |p: &[f64]| chain.mass_matrix(&chain.pose(p));
    let (m1, m0) = (
        mass_at(&moved(&phi, &rates, h)),
        mass_at(&moved(&phi, &rates, -h)),
    );
    let fv = chain.velocity_load(&chain.pose(&phi), &phi, &rates);
    let quad = |mm: &[f64]| -> f64 {
        (0..m)
            .map(|a| {
                (0..m)
                    .map(|b| rates[a] * mm[a * m + b] * rates[b])
                    .sum::<f64>()
            })
            .sum()
    };
    for a in (0..m).filter(|&a| phi[a] != 0.0) {
        let mdot_v: f64 = (0..m)
            .map(|b| (m1[a * m + b] - m0[a * m + b]) / (2.0 * h) * rates[b])
            .sum();
        let mut pp = phi.clone();
        pp[a] += h;
        let mut pm = phi.clone();
        pm[a] -= h;
        let dt = 0.5 * (quad(&mass_at(&pp)) - quad(&mass_at(&pm))) / (2.0 * h);
        let expected = -mdot_v + dt;
        assert!(
            close(fv[a], expected, 1e-6),
            "dof {a}: {} vs {expected}",
            fv[a]
        );
    }
}

#[test]
fn arch_mass_properties() {
    let arch = VoussoirArch {
        radius: 4.0,
        thickness: 0.6,
        embrace_angle: 2.0,
        voussoirs: 7,
        density: 2400.0,
        depth: 0.8,
    };
    let chain = arch.chain().unwrap();
    // Total mass: ρ d (2β) R t.
    let total = 2400.0 * 0.8 * 2.0 * 4.0 * 0.6;
    assert!(close(chain.total_mass(), total, 1e-13));
    // Joint frames: t points to the centre, R is the intrados corner.
    for (k, j) in chain.joints().iter().enumerate() {
        let r = j.right_corner();
        let l = j.left_corner();
        assert!(close(r[0].hypot(r[1]), 3.7, 1e-13), "joint {k}");
        assert!(close(l[0].hypot(l[1]), 4.3, 1e-13), "joint {k}");
    }
    // Springings symmetric about the y axis.
    let (j0, jn) = (chain.joints()[0], chain.joints()[7]);
    assert!(close(j0.centre[0], -jn.centre[0], 1e-13));
    assert!(close(j0.centre[1], jn.centre[1], 1e-13));
    // A thin sector: centroid on the centre line, I ≈ m (t² + (R·2α)²) / 12.
    let thin = VoussoirArch::semicircular(10.0, 0.01, 3000)
        .chain()
        .unwrap();
    let b = thin.bodies()[1500];
    let len = 10.0 * std::f64::consts::PI / 3000.0;
    assert!(close(b.centre[0].hypot(b.centre[1]), 10.0, 1e-6));
    assert!(close(
        b.inertia,
        b.mass * (0.01f64.powi(2) + len * len) / 12.0,
        1e-4
    ));
    assert!(VoussoirArch::semicircular(1.0, 2.0, 4).chain().is_err());
    let e = VoussoirArch::semicircular(1.0, 0.2, 0).chain().unwrap_err();
    assert_eq!(e.field, "arch.voussoirs");
}

#[test]
fn rest_pose_is_closed_and_g_has_rank_three() {
    let chain = VoussoirArch::semicircular(3.0, 0.5, 6).chain().unwrap();
    let pose = chain.pose(&vec![0.0; chain.n_dofs()]);
    assert_eq!(chain.closure_residual(&pose), [0.0, 0.0, 0.0]);
    let g = chain.closure_matrix(&pose);
    assert_eq!(g.len(), 3 * chain.n_dofs());
    // Rotations about the two springing corners and the crown cancel only trivially.
    let colonnade = CappedColonnade::frame(0.5, 3.0, 1000.0, 2.0, 0.4, 800.0);
    let c = colonnade.chain().unwrap();
    assert_eq!(c.n_bodies(), 3);
    assert_eq!(c.n_joints(), 4);
    let js = c.joints();
    // Left column: R is the right corner; right column (chain order runs down): R is the left.
    assert_eq!(js[0].right_corner(), [0.25, 0.0]);
    assert_eq!(js[3].right_corner(), [1.75, 0.0]);
    assert_eq!(js[2].right_corner(), [1.75, 3.0]);
    assert!(CappedColonnade::frame(0.5, 3.0, 1000.0, 0.4, 0.4, 800.0)
        .chain()
        .is_err());
}
