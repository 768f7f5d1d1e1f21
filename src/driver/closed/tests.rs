//! The loop driver's own cases (the arches' figures are in `tests/arch_dynamics.rs`).

use super::*;
use crate::chain::arch::VoussoirArch;
use crate::ground::FnMotion;

/// A ground acceleration just beyond the arch's collapse multiplier at every step start and well
/// inside it in between (a record grazing `λ g`): the opening model opens a mechanism at each
/// step start, whose depths' cubic never rises over the step (RK4's mean load is inside what
/// the arch resists), so it closes again at once, at rest, in the state the step started from.
/// This used to repeat at one instant until `LoopError::Stalled` (17 runs of the far-field arch
/// OAS, docs/arch-spectra.md); the loop rests through such a step instead: no event, no motion.
#[test]
fn a_step_whose_opening_closes_at_once_is_rested_through() {
    let chain = VoussoirArch::semicircular(5.0, 0.75, 8).chain().unwrap();
    let (dt, lambda) = (1e-3, 0.159368);
    let g = crate::model::column::GRAVITY;
    let motion = FnMotion(
        move |t: f64| {
            let off_grid = (t / dt - (t / dt).round()).abs();
            let level = if off_grid < 0.01 { 1.001 } else { 0.5 };
            -level * lambda * g
        },
        1.0,
    );
    let options = LoopOptions {
        dt,
        duration: 0.05,
        ..LoopOptions::default()
    };
    let out = simulate_loop(&chain, &motion, LoopState::at_rest(&chain), &options).unwrap();
    assert!(out.events.is_empty(), "{:?}", &out.events[..3]);
    assert!(!out.collapsed && out.peak_angle == 0.0);
    assert!((out.state.time - 0.05).abs() < 1e-9, "{}", out.state.time);
    assert_eq!(
        out.state,
        LoopState {
            time: out.state.time,
            ..LoopState::at_rest(&chain)
        }
    );
}

/// A step that would never end the run is refused, as the column driver refuses it (more than
/// 1e10 steps for the duration; a fuzzer of scenes found an arch with `dt = 5e-324` running for
/// ever); 1e10 steps exactly are allowed.
#[test]
fn a_step_too_small_for_the_duration_is_refused() {
    let chain = VoussoirArch::semicircular(5.0, 0.75, 8).chain().unwrap();
    let motion = FnMotion(|_| 0.0, 1.0);
    for (dt, duration) in [(5e-324, 1.17), (1e-12, 1.0), (1e-10, 1.1)] {
        let options = LoopOptions {
            dt,
            duration,
            ..LoopOptions::default()
        };
        match simulate_loop(&chain, &motion, LoopState::at_rest(&chain), &options) {
            Err(LoopError::Options(m)) => {
                assert!(m.starts_with("dt = ") && m.contains("1e10 steps"), "{m}")
            }
            other => panic!("dt {dt}: {other:?}"),
        }
    }
    let options = LoopOptions {
        dt: 1e-10,
        duration: 1.0,
        quiet_after: Some(0.0),
        ..LoopOptions::default()
    };
    assert!(simulate_loop(&chain, &motion, LoopState::at_rest(&chain), &options).is_ok());
}

/// An arch thinner than its minimum thickness (20 voussoirs: t/R = 0.107460 with hinges at
/// joints, docs/arches.md §1) does not stand under its own weight: with no ground motion at all it
/// must open in the self-weight mechanism and collapse, and the outcome must say it does not
/// stand. It was reported at rest to the end (no event): the at-rest interval of a loop that does
/// not resist `a_g = 0` was `(0, 0)`, which holds `a_g = 0`, so the opening model was never asked.
/// The same arch just above the minimum stands and stays closed.
#[test]
fn an_arch_below_its_minimum_thickness_collapses_without_ground_motion() {
    let motion = FnMotion(|_| 0.0, 1.0);
    let options = LoopOptions {
        duration: 1.0,
        ..LoopOptions::default()
    };
    let thin = VoussoirArch::semicircular(5.0, 0.5, 20).chain().unwrap();
    let out = simulate_loop(&thin, &motion, LoopState::at_rest(&thin), &options).unwrap();
    assert_eq!(out.stands_under_own_weight, Some(false));
    assert!(out.collapsed, "{:?}", out.events);
    assert_eq!(out.events[0].kind, LoopEventKind::Opening);
    // The symmetric five-hinge mechanism of the self-weight limit (0, 10, 20 extrados; 4, 16
    // intrados).
    let open: Vec<(usize, i8)> = (out.events[0].statuses.iter().enumerate())
        .filter(|(_, &s)| s != 0)
        .map(|(k, &s)| (k, s))
        .collect();
    assert_eq!(open, vec![(0, 1), (4, -1), (10, 1), (16, -1), (20, 1)]);
    let thick = VoussoirArch::semicircular(5.0, 0.55, 20).chain().unwrap();
    let out = simulate_loop(&thick, &motion, LoopState::at_rest(&thick), &options).unwrap();
    assert_eq!(out.stands_under_own_weight, Some(true));
    assert!(out.events.is_empty() && !out.collapsed && out.peak_angle == 0.0);
}
