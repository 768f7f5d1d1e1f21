//! A new user's trial of `rocking simulate` on arches and colonnades (docs/arches.md §2c): what
//! the tool says of arches that cannot stand or cannot move, scenes it must refuse naming the
//! field, and the colonnade's picture.

mod common;

use std::path::{Path, PathBuf};

use common::Run;

fn fresh_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("arch_trial")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `scene` in a fresh directory `name` and runs `rocking simulate` on it into `name/out`
/// (with `--plot name/out/plot.svg` when `plot`).
fn simulate(name: &str, scene: &str, plot: bool) -> (Run, PathBuf) {
    let dir = fresh_dir(name);
    let path = dir.join("scene.json");
    std::fs::write(&path, scene).unwrap();
    let out = dir.join("out");
    let plot_path = out.join("plot.svg");
    let mut args = vec![
        "simulate".as_ref(),
        path.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ];
    if plot {
        args.extend(["--plot".as_ref(), plot_path.as_os_str()]);
    }
    (common::run(args), out)
}

fn summary(out: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

/// A semicircular arch of 20 voussoirs with t/R = 0.10, below its minimum thickness (0.107460
/// with hinges at joints, docs/arches.md §1), under no ground motion: it cannot stand, so it must
/// collapse and the tool must say why. It used to report "end of duration, 0 events" (at rest)
/// with no ground motion, and "collapsed at t = 0.0020 s, peak 0.000000 rad" with any. Just above
/// the minimum (t/R = 0.11) it stands.
#[test]
fn an_arch_below_its_minimum_thickness_is_said_not_to_stand() {
    let scene = |t: f64| {
        format!(
            r#"{{"arch": {{"radius": 5, "thickness": {t}, "voussoirs": 20}},
                "excitation": {{"type": "none"}}, "duration": 1.0, "dt": 0.001}}"#
        )
    };
    let (run, out) = simulate("thin", &scene(0.5), false);
    assert!(run.ok, "{}", run.stderr);
    assert!(
        run.stdout.contains("collapsed") && run.stdout.contains("does not stand"),
        "{}",
        run.stdout
    );
    let s = summary(&out);
    assert_eq!(s["collapsed"], true, "{s}");
    assert_eq!(s["stands_under_own_weight"], false, "{s}");
    let (run, out) = simulate("thick", &scene(0.55), false);
    assert!(run.ok, "{}", run.stderr);
    assert!(!run.stdout.contains("does not stand"), "{}", run.stdout);
    let s = summary(&out);
    assert_eq!(s["collapsed"], false, "{s}");
    assert_eq!(s["stands_under_own_weight"], true, "{s}");
}

/// An arch of one or two voussoirs has two or three joints: no mechanism can open (a loop needs
/// four open joints to move, SPEC §9), so it never moves whatever the ground does. `simulate`
/// took it silently ("end of duration, 0 events" under any pulse) and `arch oc` / `arch oas`
/// said "arch: does not open under 1000 g"; both now refuse it naming `arch.voussoirs` and why.
/// Three voussoirs (four joints) run.
#[test]
fn an_arch_of_fewer_than_three_voussoirs_is_refused_naming_the_field() {
    for n in [1, 2] {
        let scene = format!(
            r#"{{"arch": {{"radius": 5, "thickness": 0.75, "voussoirs": {n}}},
                "excitation": {{"type": "half_sine", "amplitude": -30, "duration": 0.5}},
                "duration": 1.0, "dt": 0.001}}"#
        );
        let (run, out) = simulate(&format!("voussoirs_{n}"), &scene, false);
        assert!(
            !run.ok && run.stderr.contains("arch.voussoirs") && run.stderr.contains("at least 3"),
            "{n}: {}",
            run.stderr
        );
        assert!(!out.exists());
        let n = n.to_string();
        for args in [
            vec![
                "arch",
                "oc",
                "--voussoirs",
                &n,
                "--ptp-n",
                "1",
                "--level-n",
                "2",
            ],
            vec![
                "arch",
                "oas",
                "examples/records/synthetic.AT2",
                "--voussoirs",
                &n,
            ],
        ] {
            let run = common::run(&args);
            assert!(
                !run.ok
                    && run.stderr.contains("arch.voussoirs")
                    && run.stderr.contains("at least 3"),
                "{args:?}: {}",
                run.stderr
            );
        }
    }
    let scene = r#"{"arch": {"radius": 5, "thickness": 0.75, "voussoirs": 3},
        "excitation": {"type": "half_sine", "amplitude": -5, "duration": 0.5},
        "duration": 1.0, "dt": 0.001}"#;
    let (run, _) = simulate("voussoirs_3", scene, false);
    assert!(run.ok, "{}", run.stderr);
}

/// The loop driver asks the opening model at the start of each step while the arch is at rest:
/// a step longer than the pulse skips it. A half-sine of 5 m/s² (about 3 λ g) lasting 0.5 s
/// with `dt = 1` s was reported as "end of duration, 0 events" — the arch never saw it — and a
/// record sampled every 0.01 s run with `dt = 0.02` s skips every other sample. Both are now
/// refused naming `dt` and the largest step that would do: at least 10 steps over a pulse, at
/// most the record's own step.
#[test]
fn a_step_that_skips_the_ground_motion_is_refused_naming_dt() {
    let scene = |excitation: &str, dt: f64| {
        format!(
            r#"{{"arch": {{"radius": 5, "thickness": 0.75, "voussoirs": 8}},
                "excitation": {excitation}, "duration": 2.0, "dt": {dt}}}"#
        )
    };
    let pulse = r#"{"type": "half_sine", "amplitude": -5, "duration": 0.5}"#;
    let record = r#"{"type": "record", "path": "RECORD"}"#.replace(
        "RECORD",
        &common::root()
            .join("examples/records/synthetic.AT2")
            .display()
            .to_string(),
    );
    for (name, excitation, dt, limit) in [
        ("pulse", pulse, 1.0, "0.05"),
        ("pulse_coarse", pulse, 0.06, "0.05"),
        ("record", record.as_str(), 0.02, "0.01"),
    ] {
        let (run, out) = simulate(name, &scene(excitation, dt), false);
        assert!(
            !run.ok && run.stderr.contains("rocking: dt: ") && run.stderr.contains(limit),
            "{name}: {}",
            run.stderr
        );
        assert!(!out.exists());
    }
    for (name, excitation, dt) in [("pulse_ok", pulse, 0.05), ("record_ok", &record, 0.01)] {
        let (run, _) = simulate(name, &scene(excitation, dt), false);
        assert!(run.ok, "{name}: {}", run.stderr);
    }
}

/// `summary.json`'s `peak_angle` is the largest joint angle of the run: no row of `history.csv`
/// may exceed it. It was taken at step ends only, while the history also has the state at every
/// event, where an impact that reverses a joint's rate leaves that joint's largest angle: the
/// bundled record's arch (`arch_synthetic_record.json`) reported 0.01648666 rad with a row of
/// 0.01648697 rad in its history.
#[test]
fn the_peak_angle_is_the_largest_angle_of_the_history() {
    let dir = fresh_dir("peak");
    let out = dir.join("out");
    let scene = common::root().join("examples/scenes/arch_synthetic_record.json");
    let run = common::run([
        "simulate".as_ref(),
        scene.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert!(run.ok, "{}", run.stderr);
    let peak = summary(&out)["peak_angle"].as_f64().unwrap();
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let largest = history
        .lines()
        .skip(1)
        .flat_map(|l| {
            l.split(',')
                .skip(1)
                .map(|v| v.parse::<f64>().unwrap().abs())
        })
        .fold(0.0, f64::max);
    assert!(largest > 0.0);
    assert!(largest <= peak, "history {largest} > summary {peak}");
}

/// A colonnade of multi-drum columns and a beam of its own length (ancient colonnades are built
/// of drums; a beam may overhang the columns): `"drums"` cuts each column into that many equal
/// drums (default 1, Makris & Vassiliou's monolithic frame) and `"beam_length"` sets the beam's
/// length (default `span + width`, flush with the outer faces). The scene could only describe
/// monolithic columns with a flush beam. Each drum adds a joint per column; bad values are
/// refused naming the field.
#[test]
fn a_colonnade_of_drums_with_an_overhanging_beam_runs() {
    let scene = |extra: &str| {
        format!(
            r#"{{"colonnade": {{"width": 1, "height": 5, "column_mass": 12500, "span": 4,
                "beam_height": 1, "beam_mass": 12500{extra}}},
                "excitation": {{"type": "half_sine", "amplitude": -4, "duration": 0.5}},
                "duration": 3.0, "dt": 0.001}}"#
        )
    };
    let (run, out) = simulate("frame", &scene(""), false);
    assert!(run.ok, "{}", run.stderr);
    let monolithic = summary(&out);
    assert_eq!(monolithic["statuses_end"].as_array().unwrap().len(), 4);
    // The defaults spelled out give the same run.
    let (run, out) = simulate(
        "frame_defaults",
        &scene(r#", "drums": 1, "beam_length": 5"#),
        true,
    );
    assert!(run.ok, "{}", run.stderr);
    let same = summary(&out);
    for key in ["t_end", "peak_angle", "events", "hinges", "collapsed"] {
        assert_eq!(same[key], monolithic[key], "{key}");
    }
    for drums in [2usize, 3, 5] {
        let (run, out) = simulate(
            &format!("drums_{drums}"),
            &scene(&format!(r#", "drums": {drums}, "beam_length": 6"#)),
            true,
        );
        assert!(run.ok, "{drums}: {}", run.stderr);
        let s = summary(&out);
        assert_eq!(
            s["statuses_end"].as_array().unwrap().len(),
            2 * drums + 2,
            "{s}"
        );
        assert!(s["events"]["opening"].as_u64().unwrap() >= 1, "{s}");
        assert!(s["max_closure_residual"].as_f64().unwrap() < 1e-9, "{s}");
    }
    for (extra, field) in [
        (r#", "drums": 0"#, "colonnade.drums"),
        (r#", "drums": 500"#, "colonnade.drums"),
        (r#", "beam_length": 4.5"#, "colonnade.beam_length"),
        (r#", "beam_length": -1"#, "colonnade.beam_length"),
    ] {
        let (run, _) = simulate("bad_frame", &scene(extra), false);
        assert!(
            !run.ok && run.stderr.contains(&format!("rocking: {field}")),
            "{extra}: {}",
            run.stderr
        );
    }
}

/// A shallow arch thick enough to hold a thrust line under any load (embrace 60°, t/R = 0.15),
/// or an embrace given in radians by mistake (3.14°), never opens: `arch oc` said only "arch:
/// does not open under 1000 g". It now says what that means for the spectrum and names the
/// embrace angle's unit.
#[test]
fn an_arch_that_never_opens_is_explained() {
    for embrace in ["60", "3.14"] {
        let run = common::run([
            "arch",
            "oc",
            "--embrace",
            embrace,
            "--voussoirs",
            "8",
            "--ptp-n",
            "1",
            "--level-n",
            "2",
        ]);
        assert!(
            !run.ok
                && run.stderr.contains("no collapse multiplier")
                && run.stderr.contains("degrees"),
            "{embrace}: {}",
            run.stderr
        );
    }
}

/// A scene of 4095 voussoirs (the models' maximum) ran for ever: at rest the driver bisects the
/// ground accelerations the closed arch resists with the dense opening model, whose cost grows
/// as the cube of the joints (measured at rest under a quiet pulse: 500 voussoirs 6 s, 1000
/// 45 s, 2000 over 200 s and 0.5 GB, 4095 over 120 s and 2.1 GB before it was stopped). Time
/// histories and spectra refuse more than 1000, naming `arch.voussoirs`, at once.
#[test]
fn an_arch_of_too_many_voussoirs_is_refused_at_once() {
    let scene = r#"{"arch": {"radius": 5, "thickness": 0.75, "voussoirs": 4095},
        "excitation": {"type": "half_sine", "amplitude": 0.5, "duration": 0.5},
        "duration": 1.0, "dt": 0.001}"#;
    let started = std::time::Instant::now();
    let (run, out) = simulate("voussoirs_4095", scene, false);
    assert!(
        !run.ok && run.stderr.contains("arch.voussoirs") && run.stderr.contains("at most 1000"),
        "{}",
        run.stderr
    );
    assert!(!out.exists());
    let run = common::run(["arch", "oc", "--voussoirs", "1001", "--ptp-n", "1"]);
    assert!(
        !run.ok && run.stderr.contains("arch.voussoirs") && run.stderr.contains("at most 1000"),
        "{}",
        run.stderr
    );
    assert!(started.elapsed().as_secs() < 10, "{:?}", started.elapsed());
}

/// Two arch OAS of one record for two different arches (8 and 20 voussoirs, as stored in
/// docs/data) given to `arch suite` by mistake: it said only "record … is already in the set",
/// as for a file given twice; it now says the two are for different arches.
#[test]
fn a_suite_mixing_two_arches_of_one_record_says_so() {
    let file = |dir: &str| {
        common::root()
            .join("docs/data")
            .join(dir)
            .join("oas-RSN1111_KOBE_NIS000.json")
            .display()
            .to_string()
    };
    let run = common::run(["arch", "suite", &file("arch"), &file("arch20")]);
    assert!(
        !run.ok && run.stderr.contains("already in the set") && run.stderr.contains("another arch"),
        "{}",
        run.stderr
    );
    let run = common::run(["arch", "suite", &file("arch"), &file("arch")]);
    assert!(
        !run.ok && run.stderr.contains("already in the set") && !run.stderr.contains("another"),
        "{}",
        run.stderr
    );
}

/// An arch of R = 1 µm run with `dt` = 1 ms (a mistake of units): the step is three times the
/// arch's own time `√(L/g)`, and the run reported a collapse with a peak joint angle of 1.26 rad
/// and a closure residual of 2 % of the arch's size, silently. A step longer than a tenth of
/// `√(L/g)` (`L` the chain's span between its farthest joints) is refused naming `dt`; the
/// bundled arch (R = 5 m) may step up to 0.07 s.
#[test]
fn a_step_longer_than_the_chains_own_time_is_refused() {
    let scene = |radius: f64, dt: f64| {
        format!(
            r#"{{"arch": {{"radius": {radius}, "thickness": {}, "voussoirs": 12}},
                "excitation": {{"type": "none"}}, "duration": 1.0, "dt": {dt}}}"#,
            0.15 * radius
        )
    };
    let (run, out) = simulate("tiny_arch", &scene(1e-6, 1e-3), false);
    assert!(
        !run.ok && run.stderr.contains("rocking: dt: ") && run.stderr.contains("own time"),
        "{}",
        run.stderr
    );
    assert!(!out.exists());
    let (run, _) = simulate("tiny_arch_fine", &scene(1e-6, 1e-6), false);
    assert!(run.ok, "{}", run.stderr);
    let (run, _) = simulate("arch_coarse", &scene(5.0, 0.07), false);
    assert!(run.ok, "{}", run.stderr);
}

/// A column scene's settings copied into an arch scene with their default values ("impacts":
/// 1, "continue_until_fallen": false, "energy_consistent": false, "exact_velocity_terms": false)
/// were taken silently, while any other value was refused as "not used by a closed chain": the
/// field is refused whatever its value, as the page promises.
#[test]
fn a_column_setting_at_its_default_value_is_refused_in_an_arch_scene() {
    for (field, value) in [
        ("impacts", "1"),
        ("continue_until_fallen", "false"),
        ("energy_consistent", "false"),
        ("exact_velocity_terms", "false"),
    ] {
        let scene = format!(
            r#"{{"arch": {{"radius": 5, "thickness": 0.75, "voussoirs": 8}}, "{field}": {value},
                "excitation": {{"type": "none"}}, "duration": 0.1, "dt": 0.001}}"#
        );
        let (run, out) = simulate(&format!("column_field_{field}"), &scene, false);
        assert!(
            !run.ok && run.stderr.contains(&format!("rocking: {field}: ")),
            "{field}: {}",
            run.stderr
        );
        assert!(!out.exists());
    }
}
