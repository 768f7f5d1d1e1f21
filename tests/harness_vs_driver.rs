//! The C harness `c_examples/opensees_style_harness.c` (an FE-style analysis: three mass points
//! per block, `B` rebuilt every step, `rocking_reduce`, Newmark, step halving onto events, every
//! decision through the C ABI) against the Rust reference driver (`rocking::driver::simulate`)
//! on the same four scenes, with the driver set up as the harness is: Newmark (average
//! acceleration), dt = 1 ms, thesis Eq. 6 (no velocity terms), no friction check, static tipping
//! stops, the same settling rule.
//!
//! Asserted, scene by scene:
//! - the same sequence of events (kind, interface, configuration after), complete;
//! - event times within two steps (2 ms);
//! - the same stop (duration or overturning) and peak block rotations within 1 %.
//!
//! The measured agreement is far tighter (the test prints it; `cargo test --release --test
//! harness_vs_driver -- --nocapture`): the same sequences, event times within 9e-6 s (so event
//! times are also asserted within dt/10), peaks within 1.4e-5 relative, except the
//! overturning of scene d: the harness lands on static tipping (peak = atan(0.048/0.3) =
//! 0.158655 rad exactly) while the driver stops at the end of the step in which it happens
//! (0.159163 rad, 0.33 ms later), a 0.3 % difference by construction.

mod common;

use common::scenes::{driver_scene, parse};

#[test]
fn harness_agrees_with_the_driver() {
    let out = common::build_and_run("c_examples/opensees_style_harness.c", &[], false);
    let harness = parse(&out);
    let dt = 1e-3;
    for name in ["a", "b", "c", "d"] {
        let h = harness
            .get(name)
            .unwrap_or_else(|| panic!("scene {name} missing:\n{out}"));
        let d = driver_scene(name, dt);
        let max_dt = h.max_event_time_diff(&d);
        let max_peak = h.max_peak_rel_diff(&d);
        eprintln!(
            "scene {name}: harness {} events, driver {}; max |Δt| = {:.3e} s; peak rotations \
             harness {:?} driver {:?} (max rel. diff {:.2e}); stop {} at {:.6} / {} at {:.6}",
            h.events.len(),
            d.events.len(),
            max_dt,
            h.peak,
            d.peak,
            max_peak,
            h.stop,
            h.t_end,
            d.stop,
            d.t_end
        );
        for (i, (x, y)) in h.events.iter().zip(&d.events).enumerate() {
            assert_eq!(
                (&x.kind, x.interface, &x.after),
                (&y.kind, y.interface, &y.after),
                "scene {name}, event {i}: harness {x:?}, driver {y:?}"
            );
            assert!(
                (x.t - y.t).abs() <= 2.0 * dt,
                "scene {name}, event {i}: harness t = {}, driver t = {}",
                x.t,
                y.t
            );
            // Tighter: both locate events far inside a step (measured: 9e-6 s at most, the
            // driver's opening look-ahead of 1e-3 dt in scene b); a tenth of a step catches a
            // regression to step-end or linear event location.
            assert!(
                (x.t - y.t).abs() <= 0.1 * dt,
                "scene {name}, event {i}: harness t = {}, driver t = {} (more than dt/10 apart)",
                x.t,
                y.t
            );
        }
        assert_eq!(
            h.events.len(),
            d.events.len(),
            "scene {name}: event counts differ\nharness {:?}\ndriver {:?}",
            h.events,
            d.events
        );
        assert_eq!(h.stop, d.stop, "scene {name}: stop");
        assert!(
            (h.t_end - d.t_end).abs() <= 2.0 * dt,
            "scene {name}: end {} vs {}",
            h.t_end,
            d.t_end
        );
        assert!(
            max_peak <= 0.01,
            "scene {name}: peaks {:?} vs {:?}",
            h.peak,
            d.peak
        );
    }
}
