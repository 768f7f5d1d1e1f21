//! The models of closed chains (SPEC §9, issue 15):
//! - without constraints and with one closing joint they are the column models to the last bit
//!   (random columns, every solver, 1–3 consecutive impacts);
//! - on random loops (voussoir arches and capped colonnades, random open joints, velocities in
//!   the null space of the closure, loads, `Ġ v`) the projection solver gives the enumeration's
//!   answer, kinetic energy never rises at an impact, the answers satisfy the closure, newly
//!   opened DOFs move the admissible way;
//! - a loop's `M` without its `G` is not positive definite; three open joints are at rest.

#![allow(clippy::needless_range_loop)]

mod common;

use proptest::prelude::*;
use rocking::chain::arch::VoussoirArch;
use rocking::chain::colonnade::CappedColonnade;
use rocking::chain::Chain;
use rocking::model::column::{Block, GRAVITY};
use rocking::{
    impact_model, impact_model_constrained, opening_model, opening_model_constrained, ErrorKind,
    ModelOptions, Solver, Status,
};

#[path = "closed_chains/columns.rs"]
mod columns;

// ---------------------------------------------------------------------------------------------
// Loops.

/// A loop, a configuration (statuses, angles) and DOF rates in the null space of the closure.
#[derive(Clone, Debug)]
struct LoopScene {
    chain: Chain,
    statuses: Vec<Status>,
    phi: Vec<f64>,
    rates: Vec<f64>,
    ground_acc: f64,
}

fn arch() -> impl Strategy<Value = Chain> {
    arch_of(3..=7)
}

fn arch_of(voussoirs: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Chain> {
    (voussoirs, 0.08f64..0.35, 1.6f64..3.6, 1.0f64..8.0).prop_map(|(n, tr, embrace, r)| {
        VoussoirArch {
            radius: r,
            thickness: tr * r,
            embrace_angle: embrace,
            voussoirs: n,
            density: 2200.0,
            depth: 0.7,
        }
        .chain()
        .unwrap()
    })
}

fn colonnade() -> impl Strategy<Value = Chain> {
    colonnade_of(1..=3)
}

/// Capped colonnades; with `equal` the blocks of a column share its first block's width, so
/// that its corners are collinear (faces whose closure columns lose rank).
fn colonnade_of(blocks: std::ops::RangeInclusive<usize>) -> impl Strategy<Value = Chain> {
    (
        prop::collection::vec((0.3f64..1.0, 0.5f64..2.0, 100.0f64..2000.0), blocks.clone()),
        prop::collection::vec((0.3f64..1.0, 0.5f64..2.0, 100.0f64..2000.0), blocks),
        1.2f64..4.0,
        0.2f64..0.8,
        100.0f64..4000.0,
        any::<bool>(),
    )
        .prop_map(|(left, right, span, beam_h, beam_m, equal)| {
            let hl: f64 = left.iter().map(|b| b.1).sum();
            let hr: f64 = right.iter().map(|b| b.1).sum();
            let blocks = |v: &[(f64, f64, f64)], f: f64| -> Vec<Block> {
                v.iter()
                    .map(|&(w, h, m)| Block::rectangle(if equal { v[0].0 } else { w }, h * f, m))
                    .collect()
            };
            CappedColonnade {
                left: blocks(&left, 1.0),
                right: blocks(&right, hl / hr),
                beam: Block::rectangle(span + 1.0, beam_h, beam_m),
                span,
            }
            .chain()
            .unwrap()
        })
}

/// An orthonormal basis of the row space of the `rows × cols` matrix (Gram–Schmidt).
fn row_basis(a: &[f64], rows: usize, cols: usize) -> Vec<Vec<f64>> {
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for r in 0..rows {
        let mut v = a[r * cols..(r + 1) * cols].to_vec();
        let norm0 = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        for q in &basis {
            let d: f64 = q.iter().zip(&v).map(|(x, y)| x * y).sum();
            v.iter_mut().zip(q).for_each(|(x, qi)| *x -= d * qi);
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 1e-10 * norm0 {
            basis.push(v.iter().map(|x| x / norm).collect());
        }
    }
    basis
}

/// Each joint is open with probability `2 / choices` (half each way).
fn loop_scene(choices: u8) -> impl Strategy<Value = LoopScene> {
    scene_of(prop_oneof![arch(), colonnade()].boxed(), choices)
}

fn scene_of(loops: BoxedStrategy<Chain>, choices: u8) -> impl Strategy<Value = LoopScene> {
    (
        loops,
        prop::collection::vec((0u8..choices, 0.001f64..0.05), 32),
        prop::collection::vec(-1.0f64..1.0, 64),
        -1.0f64..1.0,
    )
        .prop_map(|(chain, joints, mix, acc)| {
            let nj = chain.n_joints();
            let m = 2 * nj;
            let mut statuses = vec![Status::Closed; nj];
            let mut phi = vec![0.0; m];
            for k in 0..nj {
                let (s, angle) = joints[k];
                statuses[k] = match s {
                    0 => Status::OpenRight,
                    1 => Status::OpenLeft,
                    _ => Status::Closed,
                };
                if let Some(d) = statuses[k].dof(k, nj) {
                    phi[d] = statuses[k].sign() * angle;
                }
            }
            // Rates: a random vector of the open DOFs projected on the null space of G_F.
            let g = chain.closure_matrix(&chain.pose(&phi));
            let open: Vec<usize> = (0..nj).filter_map(|k| statuses[k].dof(k, nj)).collect();
            let gf: Vec<f64> = (0..3)
                .flat_map(|r| open.iter().map(move |&d| (r, d)))
                .map(|(r, d)| g[r * m + d])
                .collect();
            let basis = row_basis(&gf, 3, open.len());
            let mut x: Vec<f64> = (0..open.len()).map(|i| mix[i]).collect();
            for q in &basis {
                let d: f64 = q.iter().zip(&x).map(|(a, b)| a * b).sum();
                x.iter_mut().zip(q).for_each(|(xi, qi)| *xi -= d * qi);
            }
            let mut rates = vec![0.0; m];
            for (i, &d) in open.iter().enumerate() {
                rates[d] = if x[i].abs() < 1e-12 { 0.0 } else { x[i] };
            }
            LoopScene {
                chain,
                statuses,
                phi,
                rates,
                ground_acc: acc * GRAVITY,
            }
        })
}

fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |a, x| a.max(x.abs()))
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-8 * scale.max(1e-300)
}

fn residual(g: &[f64], m: usize, v: &[f64]) -> f64 {
    (0..3)
        .map(|r| (0..m).map(|a| g[r * m + a] * v[a]).sum::<f64>().abs())
        .fold(0.0, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        max_global_rejects: 1_000_000,
        ..ProptestConfig::default()
    })]

    #[test]
    fn loop_impact_projection_equals_enumeration(s in loop_scene(3), n_impacts in 1u32..=2) {
        let nj = s.chain.n_joints();
        let m = 2 * nj;
        let pose = s.chain.pose(&s.phi);
        let mass = s.chain.mass_matrix(&pose);
        let g = s.chain.closure_matrix(&pose);
        // The joints whose DOF moves towards zero close; if none does, reverse the motion.
        let towards = |v: &[f64]| -> Vec<bool> {
            (0..nj)
                .map(|k| s.statuses[k].dof(k, nj).is_some_and(|d| v[d] * s.statuses[k].sign() < 0.0))
                .collect()
        };
        let mut rates = s.rates.clone();
        let mut closing = towards(&rates);
        if !closing.iter().any(|&c| c) {
            rates.iter_mut().for_each(|v| *v = -*v);
            closing = towards(&rates);
        }
        prop_assume!(closing.iter().any(|&c| c));
        let mut results = Vec::new();
        for solver in [Solver::Enumerate, Solver::Projection] {
            let (mut st, mut v) = (s.statuses.clone(), rates.clone());
            let opts = ModelOptions { n_impacts, solver, ..ModelOptions::default() };
            let rep = impact_model_constrained(&mass, &g, &mut st, &mut v, &closing, &opts)
                .unwrap();
            prop_assert!(rep.kinetic_after <= rep.kinetic_before * (1.0 + 1e-12) + 1e-300,
                "{:?}: {} > {}", solver, rep.kinetic_after, rep.kinetic_before);
            prop_assert!(residual(&g, m, &v) <= 1e-9 * (1.0 + inf_norm(&rates)) * 10.0,
                "closure residual {}", residual(&g, m, &v));
            for k in 0..nj {
                for (d, sign) in [(k, -1.0), (nj + k, 1.0)] {
                    if v[d] != 0.0 {
                        prop_assert_eq!(st[k].dof(k, nj), Some(d));
                        if s.statuses[k] == Status::Closed {
                            prop_assert!(v[d] * sign > 0.0);
                        }
                    }
                }
            }
            results.push((st, v, rep));
        }
        let (e, p) = (&results[0], &results[1]);
        if !e.2.tie {
            prop_assert_eq!(&e.0, &p.0, "configurations differ: {:?} vs {:?}", e.1, p.1);
            let scale = inf_norm(&rates);
            for (a, b) in e.1.iter().zip(&p.1) {
                prop_assert!(close(*a, *b, scale), "velocities differ: {:?} vs {:?}", e.1, p.1);
            }
        }
        prop_assert!(close(e.2.kinetic_after, p.2.kinetic_after, e.2.kinetic_before));
    }

    #[test]
    fn loop_opening_projection_equals_enumeration(s in loop_scene(6), at_rest in any::<bool>()) {
        let nj = s.chain.n_joints();
        let m = 2 * nj;
        let pose = s.chain.pose(&s.phi);
        let mass = s.chain.mass_matrix(&pose);
        let g = s.chain.closure_matrix(&pose);
        let load = s.chain.load_vector(&pose, s.ground_acc, GRAVITY);
        let rates = if at_rest { vec![0.0; m] } else { s.rates.clone() };
        let rhs: Vec<f64> = s.chain.closure_rate(&pose, &rates).iter().map(|x| -x).collect();
        let mut results = Vec::new();
        for solver in [Solver::Enumerate, Solver::Projection] {
            let (mut st, mut a) = (s.statuses.clone(), vec![0.0; m]);
            let opts = ModelOptions { solver, ..ModelOptions::default() };
            let rep = opening_model_constrained(
                &mass, &load, &g, Some(&rhs), &mut st, &mut a, &opts,
            )
            .unwrap();
            let ga: Vec<f64> = (0..3)
                .map(|r| (0..m).map(|d| g[r * m + d] * a[d]).sum::<f64>() - rhs[r])
                .collect();
            let scale = inf_norm(&a) + inf_norm(&rhs) + 1.0;
            prop_assert!(inf_norm(&ga) <= 1e-8 * scale * 100.0, "G a − r = {:?}", ga);
            for k in 0..nj {
                if s.statuses[k] == Status::Closed {
                    for (d, sign) in [(k, -1.0), (nj + k, 1.0)] {
                        if a[d] != 0.0 {
                            prop_assert_eq!(st[k].dof(k, nj), Some(d));
                            prop_assert!(a[d] * sign > 0.0);
                        }
                    }
                }
            }
            results.push((st, a, rep));
        }
        let (e, p) = (&results[0], &results[1]);
        if !e.2.tie {
            prop_assert_eq!(&e.0, &p.0, "configurations differ: {:?} vs {:?}", e.1, p.1);
            // Both solvers are accurate to rounding against the accelerations the loads can
            // produce (|q| over the largest diagonal mass: a lower bound of |M⁻¹q|), not against
            // an acceleration that cancels down near the onset: a 5-voussoir arch at its
            // collapse multiplier moves at 2e-6 rad/s², where the two differ by 3e-13
            // (3e-14 of the loads' scale, 1.5e-7 of the accelerations; the regression seed).
            let largest_mass = (0..m).map(|d| mass[d * m + d]).fold(0.0, f64::max);
            let load_scale = inf_norm(&load) / largest_mass;
            let scale = inf_norm(&e.1).max(inf_norm(&p.1)).max(load_scale);
            for (x, y) in e.1.iter().zip(&p.1) {
                prop_assert!(close(*x, *y, scale), "accelerations differ: {:?} vs {:?}", e.1, p.1);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 150, ..ProptestConfig::default() })]

    /// Loops too large to enumerate (arches of 8–30 voussoirs, colonnades of 4–6 blocks a
    /// column): the projection answers without error, satisfies the closure, opens only the
    /// admissible way and never gains kinetic energy at an impact.
    #[test]
    fn large_loops_projection_is_consistent(
        s in scene_of(prop_oneof![arch_of(8..=30), colonnade_of(4..=6)].boxed(), 8),
        at_rest in any::<bool>(),
    ) {
        let nj = s.chain.n_joints();
        let m = 2 * nj;
        let pose = s.chain.pose(&s.phi);
        let mass = s.chain.mass_matrix(&pose);
        let g = s.chain.closure_matrix(&pose);
        let opts = ModelOptions { solver: Solver::Projection, ..ModelOptions::default() };
        let load = s.chain.load_vector(&pose, s.ground_acc, GRAVITY);
        let rates = if at_rest { vec![0.0; m] } else { s.rates.clone() };
        let rhs: Vec<f64> = s.chain.closure_rate(&pose, &rates).iter().map(|x| -x).collect();
        let (mut st, mut a) = (s.statuses.clone(), vec![0.0; m]);
        opening_model_constrained(&mass, &load, &g, Some(&rhs), &mut st, &mut a, &opts).unwrap();
        let ga: Vec<f64> = (0..3)
            .map(|r| (0..m).map(|d| g[r * m + d] * a[d]).sum::<f64>() - rhs[r])
            .collect();
        prop_assert!(inf_norm(&ga) <= 1e-6 * (inf_norm(&a) + inf_norm(&rhs) + 1.0), "{:?}", ga);
        for k in 0..nj {
            for (d, sign) in [(k, -1.0), (nj + k, 1.0)] {
                if a[d] != 0.0 {
                    prop_assert_eq!(st[k].dof(k, nj), Some(d));
                    if s.statuses[k] == Status::Closed {
                        prop_assert!(a[d] * sign > 0.0);
                    }
                }
            }
        }
        let towards: Vec<bool> = (0..nj)
            .map(|k| s.statuses[k].dof(k, nj).is_some_and(|d| s.rates[d] * s.statuses[k].sign() < 0.0))
            .collect();
        if towards.iter().any(|&c| c) {
            let (mut st, mut v) = (s.statuses.clone(), s.rates.clone());
            let rep = impact_model_constrained(&mass, &g, &mut st, &mut v, &towards, &opts).unwrap();
            prop_assert!(rep.kinetic_after <= rep.kinetic_before * (1.0 + 1e-12));
            prop_assert!(residual(&g, m, &v) <= 1e-8 * (1.0 + inf_norm(&s.rates)));
            for k in 0..nj {
                for (d, sign) in [(k, -1.0), (nj + k, 1.0)] {
                    if v[d] != 0.0 {
                        prop_assert_eq!(st[k].dof(k, nj), Some(d));
                        if s.statuses[k] == Status::Closed {
                            prop_assert!(v[d] * sign > 0.0);
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn a_loop_without_its_closure_is_not_positive_definite() {
    let chain = VoussoirArch::semicircular(5.0, 0.8, 5).chain().unwrap();
    let nj = chain.n_joints();
    let pose = chain.pose(&vec![0.0; 2 * nj]);
    let mass = chain.mass_matrix(&pose);
    let load = chain.load_vector(&pose, 0.0, GRAVITY);
    let mut st = vec![Status::Closed; nj];
    let mut a = vec![0.0; 2 * nj];
    let e = opening_model_constrained(
        &mass,
        &load,
        &[],
        None,
        &mut st,
        &mut a,
        &ModelOptions::default(),
    )
    .unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotPositiveDefinite);
    // Only the rotation row of G: the cut joint's two massless DOFs, turning opposite ways,
    // translate the support without kinetic energy — not positive definite on that null space.
    let g = chain.closure_matrix(&pose);
    let e = opening_model_constrained(
        &mass,
        &load,
        &g[..2 * nj],
        None,
        &mut st,
        &mut a,
        &ModelOptions::default(),
    )
    .unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotPositiveDefinite);
    // With G it is a valid problem: a thick arch under gravity stays closed.
    for solver in [Solver::Enumerate, Solver::Projection] {
        let opts = ModelOptions {
            solver,
            ..ModelOptions::default()
        };
        let rep =
            opening_model_constrained(&mass, &load, &g, None, &mut st, &mut a, &opts).unwrap();
        assert!(!rep.changed);
        assert_eq!(a, vec![0.0; 2 * nj]);
    }
}

/// A negative diagonal entry of a loop's mass matrix is refused by both models, naming it: the
/// cut joint's zero rows are allowed (`M` is only semi-definite), a negative entry is not. The
/// fuzzer of the C ABI found an impact whose closing DOF had `M_77 = −9.3`: its kinetic energy
/// before was negative and the one after larger.
#[test]
fn a_negative_diagonal_mass_entry_is_refused() {
    let chain = VoussoirArch::semicircular(5.0, 0.8, 5).chain().unwrap();
    let nj = chain.n_joints();
    let m = 2 * nj;
    let pose = chain.pose(&vec![0.0; m]);
    let g = chain.closure_matrix(&pose);
    let load = chain.load_vector(&pose, 0.0, GRAVITY);
    let mut mass = chain.mass_matrix(&pose);
    let cut = m - 1; // the cut joint's phî: a zero row and column
    assert_eq!(mass[cut * m + cut], 0.0);
    mass[cut * m + cut] = -9.3;
    let mut st = vec![Status::Closed; nj];
    st[nj - 1] = Status::OpenLeft;
    let mut v = vec![0.0; m];
    v[cut] = -2.6;
    let mut closing = vec![false; nj];
    closing[nj - 1] = true;
    let (st0, v0) = (st.clone(), v.clone());
    let e = impact_model_constrained(
        &mass,
        &g,
        &mut st,
        &mut v,
        &closing,
        &ModelOptions::default(),
    )
    .unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotPositiveDefinite);
    assert!(
        e.detail.starts_with(&format!("mass[{cut}][{cut}] = -9.3")),
        "{}",
        e.detail
    );
    assert_eq!((st, v), (st0, v0));
    let (mut st, mut a) = (vec![Status::Closed; nj], vec![0.0; m]);
    let e = opening_model_constrained(
        &mass,
        &load,
        &g,
        None,
        &mut st,
        &mut a,
        &ModelOptions::default(),
    )
    .unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotPositiveDefinite);
}

/// Three open joints of a loop leave no degree of freedom: without loads the loop is at rest,
/// not in error (under gravity these three hinges — extrados at the springings, intrados at the
/// crown — are no thrust line, and more joints open).
#[test]
fn three_open_joints_are_at_rest() {
    let chain = VoussoirArch::semicircular(5.0, 1.0, 6).chain().unwrap();
    let nj = chain.n_joints();
    let mut st = vec![Status::Closed; nj];
    st[0] = Status::OpenLeft;
    st[3] = Status::OpenRight;
    st[6] = Status::OpenLeft;
    let mut phi = vec![0.0; 2 * nj];
    phi[nj] = 0.01;
    phi[3] = -0.01;
    phi[nj + 6] = 0.01;
    let pose = chain.pose(&phi);
    let mass = chain.mass_matrix(&pose);
    let g = chain.closure_matrix(&pose);
    let load = vec![0.0; 2 * nj];
    for solver in [Solver::Enumerate, Solver::Projection] {
        let opts = ModelOptions {
            solver,
            ..ModelOptions::default()
        };
        let mut s = st.clone();
        let mut a = vec![1.0; 2 * nj];
        let rep = opening_model_constrained(&mass, &load, &g, None, &mut s, &mut a, &opts).unwrap();
        assert!(!rep.changed, "{solver:?}");
        assert_eq!(s, st);
        assert!(inf_norm(&a) < 1e-12, "{a:?}");
        let gravity = chain.load_vector(&pose, 0.0, GRAVITY);
        let mut s = st.clone();
        let rep =
            opening_model_constrained(&mass, &gravity, &g, None, &mut s, &mut a, &opts).unwrap();
        assert!(rep.changed, "{solver:?}");
        // Symmetric loads, symmetric hinges: the two haunches open together (five hinges).
        assert_eq!(s.iter().filter(|x| x.is_open()).count(), 5, "{s:?}");
    }
}

/// Bad inputs are named and leave the caller's arrays untouched.
#[test]
fn bad_inputs_are_refused_without_writing() {
    let chain = VoussoirArch::semicircular(5.0, 0.8, 4).chain().unwrap();
    let nj = chain.n_joints();
    let pose = chain.pose(&vec![0.0; 2 * nj]);
    let mass = chain.mass_matrix(&pose);
    let g = chain.closure_matrix(&pose);
    let opts = ModelOptions::default();
    let mut st = vec![Status::Closed; nj];
    st[1] = Status::OpenLeft;
    let mut v = vec![0.0; 2 * nj];
    v[nj + 1] = -1.0;
    let before = (st.clone(), v.clone());
    let no_flag = vec![false; nj];
    let e = impact_model_constrained(&mass, &g, &mut st, &mut v, &no_flag, &opts).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidClosingInterface);
    let mut closed_flag = vec![false; nj];
    closed_flag[2] = true;
    let e = impact_model_constrained(&mass, &g, &mut st, &mut v, &closed_flag, &opts).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidClosingInterface);
    assert!(e.detail.contains("closing[2]"), "{}", e.detail);
    let e = impact_model_constrained(&mass, &g[..5], &mut st, &mut v, &no_flag, &opts).unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidSize);
    let mut bad_g = g.clone();
    bad_g[3] = f64::NAN;
    let mut flag = vec![false; nj];
    flag[1] = true;
    let e = impact_model_constrained(&mass, &bad_g, &mut st, &mut v, &flag, &opts).unwrap_err();
    assert_eq!(e.kind, ErrorKind::NotFinite);
    assert_eq!((st.clone(), v.clone()), before);
    // A right-hand side the open DOFs cannot meet: the configuration does not close.
    let load = chain.load_vector(&pose, 0.0, GRAVITY);
    let mut a = vec![0.0; 2 * nj];
    let mut st2 = vec![Status::Closed; nj];
    let e = opening_model_constrained(
        &mass,
        &load,
        &g,
        Some(&[1.0, 0.0, 0.0]),
        &mut st2,
        &mut a,
        &opts,
    )
    .unwrap_err();
    assert_eq!(e.kind, ErrorKind::InconsistentState);
    let e = opening_model_constrained(&mass, &load, &g, Some(&[1.0]), &mut st2, &mut a, &opts)
        .unwrap_err();
    assert_eq!(e.kind, ErrorKind::InvalidSize);
    assert_eq!(a, vec![0.0; 2 * nj]);
}

/// Columns of equal blocks have collinear corners (every right corner of a column on one
/// vertical line): faces whose closure columns lose rank. Both solvers agree over a sweep of
/// loads, and the opened mechanisms move.
#[test]
fn equal_blocks_collinear_pivots() {
    let column = vec![Block::rectangle(0.5, 1.0, 500.0); 3];
    let frame = CappedColonnade {
        left: column.clone(),
        right: column,
        beam: Block::rectangle(3.5, 0.5, 1500.0),
        span: 3.0,
    };
    let chain = frame.chain().unwrap();
    let nj = chain.n_joints();
    let pose = chain.pose(&vec![0.0; 2 * nj]);
    let mass = chain.mass_matrix(&pose);
    let g = chain.closure_matrix(&pose);
    let mut opened = 0;
    for i in 0..20 {
        let lambda = 0.05 + 0.04 * i as f64;
        let load = chain.load_vector(&pose, -lambda * GRAVITY, GRAVITY);
        let mut answers = Vec::new();
        for solver in [Solver::Enumerate, Solver::Projection] {
            let opts = ModelOptions {
                solver,
                ..ModelOptions::default()
            };
            let mut st = vec![Status::Closed; nj];
            let mut a = vec![0.0; 2 * nj];
            let rep =
                opening_model_constrained(&mass, &load, &g, None, &mut st, &mut a, &opts).unwrap();
            answers.push((st, a, rep.tie));
        }
        if !answers[0].2 {
            assert_eq!(answers[0].0, answers[1].0, "λ = {lambda}");
            let scale = inf_norm(&answers[0].1);
            for (x, y) in answers[0].1.iter().zip(&answers[1].1) {
                assert!(close(*x, *y, scale), "λ = {lambda}");
            }
        }
        if inf_norm(&answers[1].1) > 0.0 {
            opened += 1;
        }
    }
    assert!(opened > 10, "{opened}");
}
