//! The loop driver's screen of the opening model (`LoopOptions::screen`, docs/arch-performance.md) is
//! exact: with it off, on, or verifying (the model asked always, a panic on any difference) the
//! runs are the same to the bit — events, history, end state, peaks, residuals — on arches and a
//! capped colonnade under pulses and a record; and it answers most of the questions.

use rocking::chain::arch::VoussoirArch;
use rocking::chain::colonnade::CappedColonnade;
use rocking::chain::Chain;
use rocking::driver::closed::{LoopOutcome, Screen};
use rocking::driver::{simulate_loop, LoopOptions, LoopState};
use rocking::ground::records::parse_at2;
use rocking::ground::{FnMotion, GroundMotion};
use rocking::model::column::GRAVITY;

fn half_sine(amp: f64, tp: f64) -> impl Fn(f64) -> f64 {
    move |t| {
        if (0.0..tp).contains(&t) {
            amp * (std::f64::consts::PI * t / tp).sin()
        } else {
            0.0
        }
    }
}

fn run(chain: &Chain, motion: &dyn GroundMotion, duration: f64, screen: Screen) -> LoopOutcome {
    let options = LoopOptions {
        duration,
        dt: 1e-3,
        record_every: 1,
        screen,
        ..LoopOptions::default()
    };
    simulate_loop(chain, motion, LoopState::at_rest(chain), &options).unwrap()
}

/// Off, On and Verify give the same run to the bit; returns (questions, screened).
fn same_runs(chain: &Chain, motion: &dyn GroundMotion, duration: f64) -> (usize, usize) {
    let off = run(chain, motion, duration, Screen::Off);
    let on = run(chain, motion, duration, Screen::On);
    let verify = run(chain, motion, duration, Screen::Verify);
    for other in [&on, &verify] {
        assert_eq!(other.events, off.events);
        assert_eq!(other.history, off.history);
        assert_eq!(other.state, off.state);
        assert_eq!(other.collapsed, off.collapsed);
        assert_eq!(other.peak_angle.to_bits(), off.peak_angle.to_bits());
        assert_eq!(
            other.max_closure_residual.to_bits(),
            off.max_closure_residual.to_bits()
        );
        assert_eq!(other.max_step_drift.to_bits(), off.max_step_drift.to_bits());
        assert_eq!(other.moving_checks, off.moving_checks);
    }
    assert_eq!(off.screened, 0);
    assert_eq!(on.screened, verify.screened);
    (on.moving_checks, on.screened)
}

#[test]
fn the_screen_is_exact_on_arches_and_a_colonnade() {
    let lambda = 0.148875;
    let arch = VoussoirArch::semicircular(5.0, 0.75, 20).chain().unwrap();
    let mut totals = (0, 0);
    // Rocking and closed again (1.5 λ), collapse (3 λ), both with changing hinges.
    for (factor, tp, duration) in [(1.5, 0.5, 2.0), (3.0, 1.0, 1.5)] {
        let motion = FnMotion(half_sine(-factor * lambda * GRAVITY, tp), tp);
        let (q, s) = same_runs(&arch, &motion, duration);
        totals = (totals.0 + q, totals.1 + s);
    }
    // The bundled record as recorded (PGA 0.3 g), its first 6 s, on 20 and 8 voussoirs.
    let record = parse_at2(
        include_str!("../examples/records/synthetic.AT2"),
        "synthetic.AT2",
    )
    .unwrap();
    let motion = FnMotion(|t| record.acceleration(t), record.duration());
    for n in [20, 8] {
        let chain = VoussoirArch::semicircular(5.0, 0.75, n).chain().unwrap();
        let (q, s) = same_runs(&chain, &motion, 6.0);
        totals = (totals.0 + q, totals.1 + s);
    }
    // Makris & Vassiliou's frame rocking over g tan α.
    let frame = CappedColonnade::frame(1.0, 5.0, 12500.0, 4.0, 0.5, 12500.0)
        .chain()
        .unwrap();
    let motion = FnMotion(half_sine(-3.0, 0.5), 0.5);
    let (q, s) = same_runs(&frame, &motion, 4.0);
    totals = (totals.0 + q, totals.1 + s);
    // Most questions after a moving step are answered by the screen.
    println!(
        "{} questions after a moving step, {} screened",
        totals.0, totals.1
    );
    assert!(totals.0 > 1000, "{totals:?}");
    assert!(2 * totals.1 > totals.0, "{totals:?}");
}

/// The options are explicit: the default screen is `On` whatever the environment says (the
/// environment variable is read only by harnesses that call `Screen::from_env`).
#[test]
fn the_default_screen_does_not_read_the_environment() {
    std::env::set_var("ROCKING_LOOP_SCREEN", "off");
    assert_eq!(LoopOptions::default().screen, Screen::On);
    assert_eq!(Screen::from_env(), Screen::Off);
    std::env::remove_var("ROCKING_LOOP_SCREEN");
    assert_eq!(Screen::from_env(), Screen::On);
}
