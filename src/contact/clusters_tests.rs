//! Condensed steps ([`super::ClusterWork`]) against the full step.

use super::super::friction::Slip;
use super::super::moreau::{SchemeOptions, Stepper};
use super::super::outcome::DrumOutcome;
use super::super::simulation::{simulate, DrumOptions};
use crate::ground::excitation::{Excitation, Pulse};
use crate::ground::records::read_at2;
use crate::model::column::{Block, Column};

fn column(n: usize) -> Column {
    Column::new(vec![Block::rectangle(1.0, 1.0, 2500.0); n]).unwrap()
}

fn synthetic(pga: f64) -> Excitation {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let rec = read_at2(&dir.join("examples/records/synthetic.AT2")).unwrap();
    Excitation::record(rec.scaled_to_pga(pga).unwrap()).unwrap()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// What the one-step comparison found.
#[derive(Default)]
struct OneStep {
    condensed: usize,
    /// Largest difference of the velocities and of the positions of a condensed step from the full
    /// step's (relative to the largest velocity and to the step's largest displacement, or a
    /// millionth of the largest coordinate if larger).
    worst_v: f64,
    worst_q: f64,
    /// Condensed steps where one of the two projected the positions and the other did not.
    projection_flips: usize,
    /// Steps whose full step opened or slipped a joint that was closed, sticking and carrying
    /// both corners (one that could condense); of those, the steps taken condensed, and those
    /// redone in full because the check of a condensed joint's impulse failed.
    breaks: usize,
    missed_breaks: usize,
    caught: usize,
}

/// From every state of a 10-drum run under the synthetic record with condensed steps, the full
/// step too.
fn one_step_against_full(steps: usize) -> OneStep {
    let n = 10;
    let motion = synthetic(4.0);
    let options = SchemeOptions {
        clusters: true,
        ..SchemeOptions::default()
    };
    let mut st = Stepper::new(&column(n), vec![0.5; n], options);
    let mut r = OneStep::default();
    for _ in 0..steps {
        let mut full = st.clone();
        full.options.clusters = false;
        let before = st.cluster_counters;
        let located = st.counters.located_impacts;
        let condensable: Vec<bool> = (0..n)
            .map(|k| {
                k > 0
                    && st.statuses[k].closed == [true, true]
                    && st.statuses[k].slip == Slip::Stick
                    && st.carried[k] == [true, true]
            })
            .collect();
        // The synthetic record at 4 m/s² slides the column off in the end.
        if st.step(1e-3, &motion).is_err() || full.step(1e-3, &motion).is_err() {
            break;
        }
        let held = |k: usize| {
            full.statuses[k].closed == [true, true] && full.statuses[k].slip == Slip::Stick
        };
        // A whole step condensed: one sub-step, no impact located (an impact's problem is the
        // full one).
        let whole = st.cluster_counters.condensed == before.condensed + 1
            && st.counters.located_impacts == full.counters.located_impacts
            && st.counters.substeps == full.counters.substeps
            && full.counters.located_impacts == located;
        if whole {
            r.condensed += 1;
            let scale_v = max_abs(&full.v);
            let mut scale_q = 0.0_f64;
            for i in 0..3 * n {
                r.worst_v = r.worst_v.max((st.v[i] - full.v[i]).abs() / scale_v);
                scale_q = scale_q.max((full.q[i] - full.saved.as_ref().unwrap().q[i]).abs());
            }
            // Positions of the order of 10 m: their last bits are 1e-15 m whatever the step.
            let scale_q = scale_q.max(1e-6 * max_abs(&full.q));
            // The projection runs when a gap exceeds its tolerance: rounding can decide it.
            if st.counters.projections != full.counters.projections {
                r.projection_flips += 1;
            } else {
                for i in 0..3 * n {
                    r.worst_q = r.worst_q.max((st.q[i] - full.q[i]).abs() / scale_q);
                }
            }
        }
        if (0..n).any(|k| condensable[k] && !held(k)) {
            r.breaks += 1;
            if whole {
                r.missed_breaks += 1;
            }
            if st.cluster_counters.broken > before.broken {
                r.caught += 1;
            }
        }
    }
    r
}

/// From the same state, a condensed step gives the full step's velocities and positions up to
/// rounding (but for the rare step where rounding decides whether a gap is over the projection's
/// tolerance).
#[test]
fn a_condensed_step_is_the_full_step() {
    let r = one_step_against_full(20_000);
    assert!(r.condensed > 10_000, "{} condensed steps", r.condensed);
    assert!(r.worst_v < 1e-10, "velocities differ by {:e}", r.worst_v);
    assert!(r.worst_q < 1e-10, "positions differ by {:e}", r.worst_q);
    assert!(
        r.projection_flips * 1000 < r.condensed,
        "{} flips",
        r.projection_flips
    );
}

/// Where a joint that could condense must break (the full step opens it or slips it), the step is
/// not taken condensed: the check of the condensed joints' impulses catches it (or a landing
/// to locate keeps the step full).
#[test]
fn a_joint_that_must_break_is_caught() {
    let r = one_step_against_full(20_000);
    assert!(r.breaks > 10, "{} breaks", r.breaks);
    assert!(r.caught > 10, "{} caught by the check", r.caught);
    assert_eq!(r.missed_breaks, 0);
}

fn run_pulse(n: usize, a: f64, tp: f64, clusters: bool) -> DrumOutcome {
    let motion = Excitation::pulse(Pulse::half_sine(a, tp).unwrap()).unwrap();
    let mut o = DrumOptions::quiet(3.0, 0.5, 1);
    o.scheme.clusters = clusters;
    simulate(&column(n), &motion, &o, None).unwrap()
}

/// A few seconds of a pulse (rocking, impacts, no chaos): the run with condensed steps gives the
/// default run's figures to 1e-9.
#[test]
fn a_pulse_run_agrees_with_the_default() {
    for (n, a, tp) in [(3, 5.0, 0.3), (5, 3.0, 0.5), (5, 4.0, 0.5), (10, 3.0, 0.5)] {
        let x = run_pulse(n, a, tp, false);
        let y = run_pulse(n, a, tp, true);
        assert!(y.clusters.condensed > 1000, "{:?}", y.clusters);
        assert_eq!(x.stop, y.stop);
        let rel = |p: f64, q: f64| (p - q).abs() / p.abs();
        assert!(rel(x.peak_top_displacement, y.peak_top_displacement) < 1e-9);
        for k in 0..n {
            assert!(
                rel(x.peak_rotation[k], y.peak_rotation[k]) < 1e-9,
                "{n} drums, {k}"
            );
            let ds = (x.residual_slip[k] - y.residual_slip[k]).abs();
            assert!(ds < 1e-9 * x.peak_top_displacement, "{n} drums, slip {k}");
        }
        let (ex, ey) = (x.energy.accounts, y.energy.accounts);
        assert!(rel(ex.ground_work, ey.ground_work) < 1e-9);
        assert!(rel(ex.impact, ey.impact) < 1e-9);
    }
}

/// Ten drums rocking as one body on the ground joint: with condensed steps (as without) the upper
/// joints stay closed, the drums turn together, and the faces drift along each other only as in
/// the full steps, step after step.
#[test]
fn a_column_rocking_as_one_body_keeps_its_upper_joints_still() {
    let n = 10;
    let motion = Excitation::pulse(Pulse::half_sine(3.0, 0.5).unwrap()).unwrap();
    let mut drift = [0.0; 2];
    for clusters in [false, true] {
        let options = SchemeOptions {
            clusters,
            ..SchemeOptions::default()
        };
        let mut st = Stepper::new(&column(n), vec![0.5; n], options);
        let slip0: Vec<f64> = st.geometry.iter().map(|g| g.slip).collect();
        let (mut peak, mut turn, mut slip, mut gap) = (0.0_f64, 0.0_f64, 0.0_f64, 0.0_f64);
        for _ in 0..3000 {
            st.step(1e-3, &motion).unwrap();
            peak = peak.max(st.q[2].abs());
            for k in 1..n {
                turn = turn.max((st.q[3 * k + 2] - st.q[3 * k - 1]).abs());
                slip = slip.max((st.geometry[k].slip - slip0[k]).abs());
                for e in &st.geometry[k].ends {
                    gap = gap.max(e.gap.abs());
                }
            }
        }
        assert!(peak > 0.04, "the column rocks: {peak}");
        assert!(turn < 1e-12, "relative rotation {turn:e}");
        assert!(gap < st.contact_gap(), "gap {gap:e}");
        drift[clusters as usize] = slip;
        if clusters {
            let c = st.cluster_counters;
            assert!(
                c.condensed > 2500 && c.condensed_joints == 9 * c.condensed,
                "{c:?}"
            );
        }
    }
    // The faces' drift along each other (the projection's, O(h²) per step) is the full step's.
    assert!((drift[1] - drift[0]).abs() < 1e-12, "{drift:?}");
}
