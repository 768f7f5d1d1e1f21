//! Static onset of a voussoir arch (issue 15, SPEC §9): a closed loop has no reaction test, the
//! opening model itself answers — an arch at rest under gravity and a horizontal acceleration
//! `λ g` starts to move exactly at the collapse multiplier of limit analysis with hinges at the
//! joints, with the four hinges limit analysis predicts. The limit analysis is computed
//! independently (`arch_statics/limit_analysis.rs`: mechanisms and thrust lines from scratch).
//!
//! Also: the continuous reference values of SPEC §9 (λ for t/R = 0.12 … 0.30, hinge positions,
//! minimum thickness 0.1075) from the independent routine; the discrete values tend to them (λ
//! from above, minimum thickness from below); and the capped colonnade starts to rock at
//! `g tan α` like a single column of the same slenderness (Makris & Vassiliou 2013).
//!
//! `cargo test --release --test arch_statics -- --ignored --nocapture onset_table` prints the
//! table of `docs/arches.md`.

#[path = "arch_statics/limit_analysis.rs"]
mod limit_analysis;

use limit_analysis::{Arch, Face, Hinge, Mechanism};
use rocking::chain::arch::VoussoirArch;
use rocking::chain::colonnade::CappedColonnade;
use rocking::chain::Chain;
use rocking::model::column::GRAVITY;
use rocking::{opening_model_constrained, ModelOptions, Solver, Status};
use std::f64::consts::PI;

/// `value` prints as `printed` with `decimals` decimals.
fn assert_printed(value: f64, printed: f64, decimals: i32, what: &str) {
    let half_unit = 0.5 * 10f64.powi(-decimals);
    assert!(
        (value - printed).abs() <= half_unit * (1.0 + 1e-9),
        "{what}: {value} does not print as {printed}"
    );
}

/// Sections of an arch of `n` voussoirs (angles from the left springing).
fn joints(n: usize) -> Vec<f64> {
    (0..=n).map(|k| PI * k as f64 / n as f64).collect()
}

/// The collapse mechanism with hinges at `sections`, checked by both theorems: least multiplier
/// over admissible mechanisms, and its thrust line inside the arch at every section.
fn certified_collapse(arch: &Arch, sections: &[f64]) -> Mechanism {
    let m = arch
        .discrete_collapse(sections)
        .expect("a mechanism exists");
    let thrust = arch
        .thrust(m.hinges)
        .expect("the hinge conditions are regular");
    assert!(
        (thrust[3] - m.lambda).abs() <= 1e-9 * (1.0 + m.lambda.abs()),
        "static λ {} vs kinematic λ {}",
        thrust[3],
        m.lambda
    );
    assert!(
        arch.admissible(thrust, sections, 1e-9),
        "the thrust line of the best mechanism leaves the arch: not the collapse mechanism"
    );
    m
}

/// An arch of the library, its matrices at rest and the loads per unit gravity and per unit λ.
struct Onset {
    chain: Chain,
    mass: Vec<f64>,
    g: Vec<f64>,
    gravity: Vec<f64>,
    horizontal: Vec<f64>,
}

impl Onset {
    fn new(thickness_ratio: f64, voussoirs: usize) -> Onset {
        let chain = VoussoirArch::semicircular(5.0, 5.0 * thickness_ratio, voussoirs)
            .chain()
            .unwrap();
        let pose = chain.pose(&vec![0.0; chain.n_dofs()]);
        Onset {
            mass: chain.mass_matrix(&pose),
            g: chain.closure_matrix(&pose),
            gravity: chain.load_vector(&pose, 0.0, GRAVITY),
            // A horizontal load λ m g pushing +x is the ground acceleration a_g = −λ g.
            horizontal: chain.load_vector(&pose, -GRAVITY, 0.0),
            chain,
        }
    }

    /// The opening model at rest under `λ`: the configuration it chooses (None if it stays).
    fn open(&self, lambda: f64, solver: Solver) -> Option<Vec<Status>> {
        let nj = self.chain.n_joints();
        let load: Vec<f64> = self
            .gravity
            .iter()
            .zip(&self.horizontal)
            .map(|(g, h)| g + lambda * h)
            .collect();
        let mut st = vec![Status::Closed; nj];
        let mut a = vec![0.0; 2 * nj];
        let opts = ModelOptions {
            solver,
            ..ModelOptions::default()
        };
        let rep =
            opening_model_constrained(&self.mass, &load, &self.g, None, &mut st, &mut a, &opts)
                .unwrap();
        rep.changed.then_some(st)
    }

    /// The least λ at which the opening model opens something (bisection to `rel`).
    fn onset(&self, upper: f64, rel: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, upper);
        assert!(self.open(hi, Solver::Projection).is_some());
        assert!(self.open(lo, Solver::Projection).is_none());
        while hi - lo > rel * hi {
            let mid = 0.5 * (lo + hi);
            if self.open(mid, Solver::Projection).is_some() {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// The hinges of a configuration as (joint, face).
fn hinges_of(st: &[Status]) -> Vec<(usize, Face)> {
    st.iter()
        .enumerate()
        .filter_map(|(k, s)| match s {
            Status::OpenRight => Some((k, Face::Intrados)),
            Status::OpenLeft => Some((k, Face::Extrados)),
            Status::Closed => None,
        })
        .collect()
}

fn expected_hinges(m: &Mechanism, n: usize) -> Vec<(usize, Face)> {
    m.hinges
        .iter()
        .map(|h: &Hinge| ((h.psi * n as f64 / PI).round() as usize, h.face))
        .collect()
}

/// SPEC §9 reference values (continuous hinges, semicircular, radial joints): λ for t/R = 0.12 …
/// 0.30 to the printed digit, and at 0.15 the hinges 156°, 98°, 40° (intrados, extrados,
/// intrados) and 0° (extrados) from the springing the load pushes towards.
#[test]
fn continuous_reference_values() {
    let fine: Vec<f64> = (0..=3600).map(|k| PI * k as f64 / 3600.0).collect();
    for (tr, printed) in [
        (0.12, 0.046),
        (0.15, 0.144),
        (0.20, 0.284),
        (0.25, 0.406),
        (0.30, 0.518),
    ] {
        let arch = Arch::new(1.0, tr, PI);
        let m = arch.continuous_collapse(36);
        assert_printed(m.lambda, printed, 3, &format!("λ at t/R = {tr}"));
        let thrust = arch.thrust(m.hinges).unwrap();
        assert!(arch.admissible(thrust, &fine, 1e-6), "t/R = {tr}");
        if tr == 0.15 {
            let from_right: Vec<(f64, Face)> = m
                .hinges
                .iter()
                .rev()
                .map(|h| ((PI - h.psi).to_degrees(), h.face))
                .collect();
            let printed = [
                (0.0, Face::Extrados),
                (40.0, Face::Intrados),
                (98.0, Face::Extrados),
                (156.0, Face::Intrados),
            ];
            for ((deg, face), (p, pf)) in from_right.iter().zip(printed) {
                assert_eq!(*face, pf);
                assert_printed(*deg, p, 0, "hinge angle (degrees)");
            }
        }
    }
}

/// Minimum t/R under self-weight with continuous hinges (bisection on the sign of λ).
fn continuous_minimum(tolerance: f64) -> f64 {
    let (mut lo, mut hi) = (0.1, 0.115);
    while hi - lo > tolerance {
        let mid = 0.5 * (lo + hi);
        if Arch::new(1.0, mid, PI).continuous_collapse(18).lambda < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Minimum t/R under self-weight with hinges at the joints of `n` voussoirs.
fn discrete_minimum(n: usize) -> f64 {
    let sections = joints(n);
    let (mut lo, mut hi) = (0.02, 0.14);
    while hi - lo > 1e-9 {
        let mid = 0.5 * (lo + hi);
        if Arch::new(1.0, mid, PI).collapses_under_gravity(&sections) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Minimum thickness under self-weight with continuous hinges: t/R = 0.1075 (Milankovitch).
#[test]
fn continuous_minimum_thickness() {
    assert_printed(continuous_minimum(1e-6), 0.1075, 4, "minimum t/R");
}

/// The opening model starts to move exactly at the discrete collapse multiplier, with its four
/// hinges, for both solvers; the discrete multiplier lies above the continuous one.
#[test]
fn opening_model_onset_is_the_collapse_multiplier() {
    for (tr, continuous) in [(0.15, 0.144), (0.20, 0.284)] {
        let lc = Arch::new(1.0, tr, PI).continuous_collapse(36).lambda;
        assert_printed(lc, continuous, 3, "continuous λ");
        for n in [5usize, 8, 12, 20] {
            let arch = Arch::new(5.0, 5.0 * tr, PI);
            let m = certified_collapse(&arch, &joints(n));
            assert!(
                m.lambda >= lc * (1.0 - 1e-12),
                "N = {n}: {} < {lc}",
                m.lambda
            );
            let onset = Onset::new(tr, n);
            let found = onset.onset(2.0 * m.lambda + 0.1, 1e-12);
            assert!(
                (found - m.lambda).abs() <= 1e-9 * m.lambda,
                "t/R = {tr}, N = {n}: onset {found} vs limit analysis {}",
                m.lambda
            );
            let above = m.lambda * (1.0 + 1e-6);
            let solvers: &[Solver] = if n <= 8 {
                &[Solver::Enumerate, Solver::Projection]
            } else {
                &[Solver::Projection]
            };
            for &solver in solvers {
                assert!(onset.open(m.lambda * (1.0 - 1e-6), solver).is_none());
                let st = onset.open(above, solver).expect("opens above the onset");
                assert_eq!(
                    hinges_of(&st),
                    expected_hinges(&m, n),
                    "t/R = {tr}, N = {n}, {solver:?}"
                );
            }
        }
    }
}

/// Under self-weight alone the arch stands exactly when limit analysis says so; the discrete
/// minimum thickness lies below the continuous 0.1075 and grows towards it as the joints are
/// refined (nested joint sets: 6, 12, 24 voussoirs).
#[test]
fn self_weight_minimum_thickness() {
    let mut previous = 0.0;
    for n in [6usize, 12, 24] {
        let t = discrete_minimum(n);
        assert!(t < 0.1075 && t >= previous - 1e-9, "N = {n}: t_min {t}");
        previous = t;
        for (factor, opens) in [(0.999, true), (1.001, false)] {
            let onset = Onset::new(t * factor, n);
            assert_eq!(
                onset.open(0.0, Solver::Projection).is_some(),
                opens,
                "N = {n}, t/R = {}",
                t * factor
            );
        }
    }
}

/// Makris & Vassiliou (2013): a frame of two columns capped by a freely supported beam starts to
/// rock at `g tan α` (`tan α = b / h`), whatever the beam, like a single column; the frame opens
/// as a four-hinge mechanism (the column bases and tops about opposite corners).
#[test]
fn capped_colonnade_uplift_is_the_single_column_one() {
    for (width, height, beam_mass) in [(0.5, 3.0, 800.0), (0.8, 4.0, 5000.0), (1.0, 2.5, 100.0)] {
        let frame = CappedColonnade::frame(width, height, 1200.0, 3.0, 0.5, beam_mass);
        let chain = frame.chain().unwrap();
        let nj = chain.n_joints();
        let pose = chain.pose(&vec![0.0; 2 * nj]);
        let mass = chain.mass_matrix(&pose);
        let g = chain.closure_matrix(&pose);
        let tan_alpha = width / height;
        for (factor, opens) in [(1.0 - 1e-9, false), (1.0 + 1e-9, true)] {
            let load = chain.load_vector(&pose, -factor * tan_alpha * GRAVITY, GRAVITY);
            for solver in [Solver::Enumerate, Solver::Projection] {
                let mut st = vec![Status::Closed; nj];
                let mut a = vec![0.0; 2 * nj];
                let opts = ModelOptions {
                    solver,
                    ..ModelOptions::default()
                };
                let rep = opening_model_constrained(&mass, &load, &g, None, &mut st, &mut a, &opts)
                    .unwrap();
                assert_eq!(rep.changed, opens, "b/h = {tan_alpha}, {solver:?}");
                if opens {
                    // Pushed +x, both columns tip about their bases' right corners and the beam
                    // rides on their tops' left corners. Left column (n = +y): base R_0, top
                    // L_1. Right column (chain order runs down, n = −y, so R is the corner on
                    // the left): top R_2, base L_3.
                    assert_eq!(
                        st,
                        vec![
                            Status::OpenRight,
                            Status::OpenLeft,
                            Status::OpenRight,
                            Status::OpenLeft
                        ],
                        "{solver:?}"
                    );
                }
            }
        }
    }
}

/// Makris & Vassiliou (2013), Eq. of motion of the frame: with both columns rotated by `θ`
/// (clockwise, about their right base corners) and the beam riding on their top left corners,
/// `θ̈ = −p̂² [sin(α − θ) + (ü_g / g) cos(α − θ)]`, `p̂² = p² (1 + 2γ) / (1 + 3γ)`,
/// `p² = 3g / (4R)`, `γ = m_beam / (2 m_column)`: the frame rocks like one column of the same
/// slenderness with a modified frequency parameter. Checked at rotated, closed poses through the
/// chain helpers (`M`, `q`, `G` projected on the mechanism) and through the opening model of a
/// frame at rest in the mechanism.
#[test]
fn capped_colonnade_rocks_like_one_column() {
    let (width, height, m_col, m_beam) = (0.6, 3.6, 1500.0, 2400.0);
    let frame = CappedColonnade::frame(width, height, m_col, 3.0, 0.5, m_beam);
    let chain = frame.chain().unwrap();
    let nj = chain.n_joints();
    let alpha = (width / height).atan();
    let r = 0.5 * width.hypot(height);
    let gamma = m_beam / (2.0 * m_col);
    let p2 = 3.0 * GRAVITY / (4.0 * r) * (1.0 + 2.0 * gamma) / (1.0 + 3.0 * gamma);
    // The mechanism's DOFs (phĭ_0, phî_1, phĭ_2, phî_3) per unit θ.
    let dofs = [0, nj + 1, 2, nj + 3];
    let z = [-1.0, 1.0, -1.0, 1.0];
    let statuses = vec![
        Status::OpenRight,
        Status::OpenLeft,
        Status::OpenRight,
        Status::OpenLeft,
    ];
    for theta in [1e-9, 0.02, 0.08, 0.15] {
        let mut phi = vec![0.0; 2 * nj];
        for (&d, &zi) in dofs.iter().zip(&z) {
            phi[d] = zi * theta;
        }
        let pose = chain.pose(&phi);
        let residual = chain.closure_residual(&pose);
        assert!(residual.iter().all(|x| x.abs() < 1e-12), "{residual:?}");
        let mass = chain.mass_matrix(&pose);
        let g = chain.closure_matrix(&pose);
        let m = 2 * nj;
        for row in 0..3 {
            let gz: f64 = dofs
                .iter()
                .zip(&z)
                .map(|(&d, zi)| g[row * m + d] * zi)
                .sum();
            assert!(gz.abs() < 1e-12, "the mechanism leaves the closure: {gz}");
        }
        for ag in [0.0, -0.4 * GRAVITY, 0.7 * GRAVITY] {
            let q = chain.load_vector(&pose, ag, GRAVITY);
            let m_eff: f64 = (0..4)
                .map(|i| {
                    (0..4)
                        .map(|j| z[i] * mass[dofs[i] * m + dofs[j]] * z[j])
                        .sum::<f64>()
                })
                .sum();
            let q_eff: f64 = (0..4).map(|i| z[i] * q[dofs[i]]).sum();
            let expected = -p2 * ((alpha - theta).sin() + ag / GRAVITY * (alpha - theta).cos());
            assert!(
                (q_eff / m_eff - expected).abs() <= 1e-12 * p2,
                "θ = {theta}, a_g = {ag}: {} vs {expected}",
                q_eff / m_eff
            );
            // The opening model of the frame at rest in the mechanism: nothing else opens, and
            // its accelerations are those of the single column with p̂.
            if expected > 0.0 {
                for solver in [Solver::Enumerate, Solver::Projection] {
                    let mut st = statuses.clone();
                    let mut a = vec![0.0; m];
                    let opts = ModelOptions {
                        solver,
                        ..ModelOptions::default()
                    };
                    opening_model_constrained(&mass, &q, &g, None, &mut st, &mut a, &opts).unwrap();
                    assert_eq!(st, statuses);
                    for (&d, zi) in dofs.iter().zip(&z) {
                        assert!(
                            (a[d] - zi * expected).abs() <= 1e-10 * p2,
                            "θ = {theta}, a_g = {ag}, {solver:?}: {} vs {}",
                            a[d],
                            zi * expected
                        );
                    }
                }
            }
        }
    }
}

/// The table of `docs/arches.md`: λ against the number of voussoirs, the onset found by the
/// opening model, the hinges; the minimum thickness.
#[test]
#[ignore]
fn onset_table() {
    println!("continuous minimum t/R = {:.6}", continuous_minimum(1e-8));
    for n in [4usize, 6, 8, 10, 12, 16, 20, 24, 36] {
        let t = discrete_minimum(n);
        let below = Onset::new(t * (1.0 - 1e-6), n).open(0.0, Solver::Projection);
        let above = Onset::new(t * (1.0 + 1e-6), n).open(0.0, Solver::Projection);
        println!(
            "N = {n}: minimum t/R = {t:.6}; opening model at (1 ∓ 1e-6) t_min: {:?} / {:?}",
            below.map(|st| hinges_of(&st)),
            above.map(|st| hinges_of(&st))
        );
    }
    for tr in [0.15, 0.20] {
        let lc = Arch::new(1.0, tr, PI).continuous_collapse(36);
        println!(
            "t/R = {tr}: continuous λ = {:.5}, hinges {:?}",
            lc.lambda,
            lc.hinges
                .iter()
                .map(|h| (format!("{:.1}°", h.psi.to_degrees()), h.face))
                .collect::<Vec<_>>()
        );
        println!("| N | λ limit analysis | λ opening model | hinges (joint, face) |");
        for n in [4usize, 5, 6, 8, 10, 12, 16, 20, 24, 30, 40, 60] {
            let arch = Arch::new(5.0, 5.0 * tr, PI);
            let m = certified_collapse(&arch, &joints(n));
            let onset = Onset::new(tr, n);
            let found = onset.onset(2.0 * m.lambda + 0.1, 1e-12);
            let st = onset
                .open(m.lambda * (1.0 + 1e-6), Solver::Projection)
                .unwrap();
            println!(
                "| {n} | {:.6} | {:.6} | {:?} |",
                m.lambda,
                found,
                hinges_of(&st)
            );
        }
    }
}
