//! Section "Exact Lagrangian vs thesis Eq. 6" of the accuracy report.

use std::fmt::Write as _;
use std::path::Path;

use rocking::driver::{self, Integrator};
use rocking::ground::excitation::{Excitation, Pulse};
use rocking::ground::FnMotion;

use super::metrics::{errors, Metrics};
use super::report::fmt_err;
use super::scenes::{locators, scene_b, scene_c, BenchScene, K_IMPACTS, SCENE_B_PULSE};

/// Section "Exact Lagrangian vs thesis Eq. 6".
pub(super) fn velocity_terms_section() -> Result<String, String> {
    let mut s = String::new();
    let _ = writeln!(s, "\n## Exact Lagrangian vs thesis Eq. 6\n");
    let _ = writeln!(
        s,
        "Thesis Eq. 6 (`M φ̈ = q`) leaves out the velocity terms of the exact Lagrangian equations \
         (`exact_velocity_terms = true` adds them). Same scenes, Wilson θ and linear location as the \
         thesis, Hermite to check that the difference is not a location artefact.\n"
    );
    // Thesis 4.2 two-block scene, as bundled.
    let two = {
        let spec: rocking::scene::SceneSpec = serde_json::from_str(include_str!(
            "../../../../examples/scenes/two_block_free_rocking.json"
        ))
        .map_err(|e| e.to_string())?;
        rocking::scene::build(spec, Path::new("."), "two_block_free_rocking.json")
            .map_err(|e| e.to_string())?
    };
    let two_scene = BenchScene {
        key: "4.2",
        title: format!(
            "thesis 4.2 two blocks ({})",
            "examples/scenes/two_block_free_rocking.json"
        ),
        column: two.column,
        excitation: two.excitation,
        options: two.options,
        peak_after_first_impact: false,
    };
    let c = scene_c();
    let _ = writeln!(
        s,
        "| scene | locator | dt (s) | Eq. 6: first impacts (s, interface) | exact: first impacts | max |Δt| first {K_IMPACTS} | peak rotations Eq. 6 (rad) | exact | overturned Eq. 6 / exact |\n|---|---|---:|---|---|---:|---|---|---|"
    );
    for (scene, dt) in [(&two_scene, 1e-4), (&c, 1e-4)] {
        for (loc, lname) in locators() {
            let mut o = scene.options.clone();
            o.stepping.dt = dt;
            o.stepping.locator = loc;
            o.stepping.integrator = Integrator::default();
            let run = |exact: bool| -> Result<Metrics, String> {
                let mut o = o.clone();
                o.physics.exact_velocity_terms = exact;
                let exc = &scene.excitation;
                let motion = FnMotion(|t| exc.acceleration(t), exc.end_time());
                let out = driver::simulate(&scene.column, &motion, &o, None)
                    .map_err(|e| e.to_string())?;
                Ok(scene.metrics(&out))
            };
            let (a, b) = (run(false)?, run(true)?);
            let first = |m: &Metrics| {
                m.impacts
                    .iter()
                    .take(4)
                    .map(|(t, k)| format!("{t:.4} ({k})"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let e = errors(&b, &a);
            let _ = writeln!(
                s,
                "| {} | {lname} | {dt:.0e} | {} | {} | {} | {:.4?} | {:.4?} | {} / {} |",
                scene.title,
                first(&a),
                first(&b),
                fmt_err(e.impact),
                a.peak,
                b.peak,
                a.overturned,
                b.overturned
            );
        }
    }
    // Single block near its overturning boundary (half sine, 1 × 4 m, 0.8 s).
    let b = scene_b();
    let over = |amp: f64, exact: bool| -> Result<(bool, Metrics), String> {
        let mut o = b.options.clone();
        o.physics.exact_velocity_terms = exact;
        o.stepping.dt = 1e-4;
        let exc = Excitation::pulse(Pulse::half_sine(amp, SCENE_B_PULSE.1).unwrap()).unwrap();
        let motion = FnMotion(|t| exc.acceleration(t), exc.end_time());
        let out = driver::simulate(&b.column, &motion, &o, None).map_err(|e| e.to_string())?;
        Ok((out.overturned, b.metrics(&out)))
    };
    // Bisection of the overturning amplitude with Eq. 6.
    let (mut lo, mut hi) = (SCENE_B_PULSE.0, 3.0 * SCENE_B_PULSE.0);
    if over(lo, false)?.0 || !over(hi, false)?.0 {
        return Err("velocity-terms section: the bisection bracket does not bracket".into());
    }
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if over(mid, false)?.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let _ = writeln!(
        s,
        "\nSingle block 1 × 4 m, half sine of 0.8 s, Wilson θ, linear location, dt = 1e-4 s: the \
         overturning amplitude found by bisection with Eq. 6 lies in [{lo:.6}, {hi:.6}] m/s². At \
         its two ends:\n"
    );
    let _ = writeln!(
        s,
        "| amplitude (m/s²) | overturned Eq. 6 / exact | impacts Eq. 6 / exact | peak Eq. 6 / exact (rad) | max |Δt| of impacts | |Δ peak| |\n|---:|---|---|---|---:|---:|"
    );
    for amp in [lo, hi] {
        let (oa, ma) = over(amp, false)?;
        let (ob, mb) = over(amp, true)?;
        let e = errors(&mb, &ma);
        let _ = writeln!(
            s,
            "| {amp:.6} | {oa} / {ob} | {} / {} | {:.6} / {:.6} | {} | {:.1e} |",
            ma.impacts.len(),
            mb.impacts.len(),
            ma.peak[0],
            mb.peak[0],
            if ma.impacts.is_empty() {
                "no impacts".to_string()
            } else {
                fmt_err(e.impact)
            },
            (ma.peak[0] - mb.peak[0]).abs()
        );
    }
    let _ = writeln!(
        s,
        "\nWhy the velocity terms vanish for a single block: rocking about a fixed corner, the \
         block has one DOF θ and its kinetic energy is `T = ½ I_P θ̇²` with `I_P` (the inertia \
         about the corner) independent of θ. The Lagrangian velocity terms are `(∂M/∂θ) θ̇² / 2` \
         (the Christoffel symbols of `M`), zero when `M` does not depend on the configuration. \
         Physically, the centripetal acceleration `R θ̇²` of the centre points at the pivot, so its \
         force has no moment about the pivot. With two or more open DOFs `M` depends on the relative \
         angles (the upper block's pivot moves with the lower block), and the Coriolis and \
         centripetal terms do work on the DOF equations; Eq. 6 then also loses exact energy \
         conservation between impacts."
    );
    Ok(s)
}
