//! `c_examples/stiff_blocks.c` (axially elastic blocks, axial frequency 100, 1000 and 10 000
//! times the rocking frequency) against the rigid Rust driver (`rocking::driver::simulate`, set
//! up as in `tests/harness_vs_driver.rs` but with the program's dt = 1e-4 s).
//!
//! Asserted for the recipe (docs/opensees.md section 6) at every stiffness ratio and scene:
//! - the same event sequence as the driver (kind, interface, configuration after), complete, and
//!   the same stop;
//! - event times and peak rotations converge to the driver's as the stiffness grows: the
//!   largest event-time difference falls with the ratio, and at 10 000x it is within dt/10 and
//!   the peaks within 1 %.
//!
//! And, as the evidence the recipe is needed, that the naive coupling (decisions on the total,
//! vibrating interface forces) does NOT reproduce the rigid sequence in the half-sine (b) and
//! two-block (c) scenes at any ratio.
//!
//! `cargo test --release --test stiff_vs_rigid -- --nocapture` prints the measured figures.

mod common;

use common::scenes::{driver_scene, parse, SceneResult};

const RATIOS: [&str; 3] = ["100", "1000", "10000"];

fn same_sequence(h: &SceneResult, d: &SceneResult) -> bool {
    h.events.len() == d.events.len()
        && h.events
            .iter()
            .zip(&d.events)
            .all(|(x, y)| (&x.kind, x.interface, &x.after) == (&y.kind, y.interface, &y.after))
}

#[test]
fn stiff_recipe_converges_to_the_rigid_driver() {
    let out = common::build_and_run("c_examples/stiff_blocks.c", &[], false);
    let runs = parse(&out);
    let dt = 1e-4;
    for name in ["a", "b", "c"] {
        let d = driver_scene(name, 1e-4);
        let mut previous = f64::INFINITY;
        for ratio in RATIOS {
            let key = format!("{name}_recipe_r{ratio}");
            let h = runs
                .get(&key)
                .unwrap_or_else(|| panic!("{key} missing:\n{out}"));
            let max_dt = h.max_event_time_diff(&d);
            let max_peak = h.max_peak_rel_diff(&d);
            eprintln!(
                "{key}: {} events (driver {}), max |dt| = {max_dt:.3e} s, peak rel. diff \
                 {max_peak:.3e}, stop {} / {}",
                h.events.len(),
                d.events.len(),
                h.stop,
                d.stop
            );
            assert!(
                same_sequence(h, &d),
                "{key}: sequences differ\nstiff {:?}\ndriver {:?}",
                h.events,
                d.events
            );
            assert_eq!(h.stop, d.stop, "{key}: stop");
            assert!(
                max_dt < previous,
                "{key}: event times do not converge ({max_dt} after {previous})"
            );
            previous = max_dt;
            if ratio == "10000" {
                assert!(max_dt <= 0.1 * dt, "{key}: event times {max_dt} s apart");
                assert!(
                    max_peak <= 0.01,
                    "{key}: peaks {:?} vs {:?}",
                    h.peak,
                    d.peak
                );
            }
        }
        if name != "a" {
            for ratio in RATIOS {
                let key = format!("{name}_naive_r{ratio}");
                let h = runs
                    .get(&key)
                    .unwrap_or_else(|| panic!("{key} missing:\n{out}"));
                eprintln!(
                    "{key}: {} events (driver {}), stop {}",
                    h.events.len(),
                    d.events.len(),
                    h.stop
                );
                assert!(
                    !same_sequence(h, &d),
                    "{key}: the naive coupling no longer chatters here; revisit docs/opensees.md"
                );
            }
        }
    }
}
