//! `rocking simulate` on the mistakes a user makes in a scene: every one is an error that names
//! the field and what is allowed, none is ignored, and nothing is written.

mod common;

use std::path::{Path, PathBuf};

fn fresh_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `rocking simulate SCENE --out OUT`.
fn simulate(scene: &Path, out: &Path) -> common::Run {
    common::run([
        "simulate".as_ref(),
        scene.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ])
}

/// Runs each scene text (written next to a copy of the bundled record) and asserts that it fails
/// with every `words` in its message and writes no output.
fn refused(dir: &str, cases: &[(String, &[&str])]) {
    let dir = fresh_dir(dir);
    std::fs::copy(
        common::root().join("examples/records/synthetic.AT2"),
        dir.join("synthetic.AT2"),
    )
    .unwrap();
    let scene = dir.join("scene.json");
    let out = dir.join("out");
    let mut accepted = Vec::new();
    for (text, words) in cases {
        std::fs::write(&scene, text).unwrap();
        let run = simulate(&scene, &out);
        if run.ok || !words.iter().all(|w| run.stderr.contains(w)) {
            accepted.push(format!("{text}\n  -> ok {}: {}", run.ok, run.stderr));
        }
        assert!(!out.exists(), "output written for {text}");
    }
    assert!(accepted.is_empty(), "{}", accepted.join("\n"));
}

const COLUMN: &str = r#""blocks": [{"width": 1, "height": 2, "mass": 5000}, {"width": 1, "height": 2, "mass": 5000}], "duration": 1, "dt": 0.001"#;
const ARCH: &str =
    r#""arch": {"radius": 5, "thickness": 0.75, "voussoirs": 8}, "duration": 0.1, "dt": 0.001"#;

/// A PEER `.AT2` record is in g and states its step: `"units": "m/s2"` or a `dt` given for one
/// were silently dropped (the record ran in g at its own step).
#[test]
fn units_or_a_step_given_for_an_at2_record_are_named() {
    let record = |extra: &str| {
        format!(
            r#"{{{COLUMN}, "excitation": {{"type": "record", "path": "synthetic.AT2"{extra}}}}}"#
        )
    };
    refused(
        "at2_units",
        &[
            (
                record(r#", "units": "m/s2""#),
                &["excitation.units", "in g"],
            ),
            (
                record(r#", "units": "cm/s2""#),
                &["excitation.units", "in g"],
            ),
            (record(r#", "dt": 0.005"#), &["excitation.dt", "DT"]),
        ],
    );
    // "g" is what the file is in: accepted.
    let dir = fresh_dir("at2_units_g");
    std::fs::copy(
        common::root().join("examples/records/synthetic.AT2"),
        dir.join("synthetic.AT2"),
    )
    .unwrap();
    std::fs::write(dir.join("scene.json"), record(r#", "units": "g""#)).unwrap();
    let out = dir.join("out");
    let run = simulate(&dir.join("scene.json"), &out);
    assert!(run.ok, "{}", run.stderr);
}

/// The contact scheme's error control and consistent impacts mean nothing to the loop driver:
/// an arch scene with them ran as if they were not there.
#[test]
fn the_contact_schemes_settings_in_an_arch_scene_are_named() {
    let none = r#""excitation": {"type": "none"}"#;
    refused(
        "arch_energy",
        &[
            (
                format!(r#"{{{ARCH}, {none}, "energy_tolerance": 1e-6}}"#),
                &["energy_tolerance", "closed chain"],
            ),
            (
                format!(r#"{{{ARCH}, {none}, "energy_consistent": true}}"#),
                &["energy_consistent", "closed chain"],
            ),
        ],
    );
}

/// A value of the wrong type names its field (serde's message gave only a line and column), and
/// an integrator object takes no field but `type` and `theta` (others were ignored).
#[test]
fn a_value_of_the_wrong_type_names_its_field() {
    let none = r#""excitation": {"type": "none"}"#;
    refused(
        "wrong_types",
        &[
            (
                format!(r#"{{{COLUMN}, {none}, "impacts": 2.0}}"#),
                &["impacts: invalid type"],
            ),
            (
                format!(r#"{{{COLUMN}, {none}, "gravity": "9.81"}}"#),
                &["gravity: invalid type"],
            ),
            (
                format!(
                    r#"{{{COLUMN}, "excitation": {{"type": "half_sine", "amplitude": NaN, "duration": 1}}}}"#
                ),
                &["excitation.amplitude: expected value"],
            ),
            (
                format!(
                    r#"{{"blocks": [{{"width": 1, "height": 2, "mass": 5000}}, {{"width": 1, "height": true, "mass": 5000}}], {none}, "duration": 1, "dt": 0.001}}"#
                ),
                &["blocks[1].height: invalid type"],
            ),
            (
                format!(
                    r#"{{{COLUMN}, {none}, "integrator": {{"type": "wilson", "theta": 1.4, "gamma": 0.5}}}}"#
                ),
                &["integrator: ", "no other field"],
            ),
            (
                format!(r#"{{{COLUMN}, {none}, "integrator": {{"type": "newmark"}}}}"#),
                &["integrator: ", "wilson", "dop853"],
            ),
            (
                format!(r#"{{{ARCH}, {none}, "output": {{"every": 2.5}}}}"#),
                &["output.every: invalid type"],
            ),
            (
                format!(
                    r#"{{"arch": {{"radius": 5, "thickness": 0.75, "voussoirs": 8.5}}, {none}, "duration": 0.1, "dt": 0.001}}"#
                ),
                &["arch.voussoirs: invalid type"],
            ),
            (
                format!(
                    r#"{{{COLUMN}, "excitation": {{"type": "half_sine", "amplitude": 3, "phase": 1, "duration": 1}}}}"#
                ),
                &["excitation: unknown field `phase`"],
            ),
            // Lists where objects belong were read by position (width, height, mass; type, θ).
            (
                format!(r#"{{"blocks": [[1, 2, 5000]], {none}, "duration": 1, "dt": 0.001}}"#),
                &["blocks[0]: a list where an object"],
            ),
            (
                format!(r#"{{{COLUMN}, {none}, "integrator": ["wilson", 1.4]}}"#),
                &["integrator: a list where an object"],
            ),
            // A field beside `"type": "none"` was dropped: the column rocked freely.
            (
                format!(r#"{{{COLUMN}, "excitation": {{"type": "none", "amplitude": 5}}}}"#),
                &["excitation: unknown field `amplitude`"],
            ),
        ],
    );
}

/// An arch scene whose duration needs more than the loop driver's 1e10 steps is refused as a
/// column's is, `dt` named, at the scene (it reached the driver, whose message printed the
/// duration's 301 digits).
#[test]
fn an_arch_scene_of_too_many_steps_names_dt() {
    let arch = r#""arch": {"radius": 5, "thickness": 0.75, "voussoirs": 8}, "excitation": {"type": "none"}"#;
    refused(
        "arch_steps",
        &[(
            format!(r#"{{{arch}, "duration": 1e300, "dt": 0.001}}"#),
            &["dt: 0.001: more than 1e10 steps"],
        )],
    );
    let dir = fresh_dir("arch_steps_message");
    std::fs::write(
        dir.join("scene.json"),
        format!(r#"{{{arch}, "duration": 1e300, "dt": 0.001}}"#),
    )
    .unwrap();
    let run = simulate(&dir.join("scene.json"), &dir.join("out"));
    assert!(run.stderr.len() < 200, "{}", run.stderr);
}

/// A zero duration is a run of no step for an arch as for a column (an arch scene refused it as
/// "greater than zero"); a negative one is refused for both, naming `duration`.
#[test]
fn a_zero_duration_runs_for_an_arch_as_for_a_column() {
    let arch = r#""arch": {"radius": 5, "thickness": 0.75, "voussoirs": 8}, "excitation": {"type": "none"}"#;
    let column =
        r#""blocks": [{"width": 1, "height": 2, "mass": 5000}], "excitation": {"type": "none"}"#;
    for (name, body) in [("arch", arch), ("column", column)] {
        let dir = fresh_dir(&format!("zero_duration_{name}"));
        std::fs::write(
            dir.join("scene.json"),
            format!(r#"{{{body}, "duration": 0, "dt": 0.001}}"#),
        )
        .unwrap();
        let run = simulate(&dir.join("scene.json"), &dir.join("out"));
        assert!(run.ok, "{name}: {}", run.stderr);
        let summary = std::fs::read_to_string(dir.join("out/summary.json")).unwrap();
        assert!(summary.contains("\"t_end\": 0.0"), "{name}: {summary}");
        refused(
            &format!("negative_duration_{name}"),
            &[(
                format!(r#"{{{body}, "duration": -1, "dt": 0.001}}"#),
                &["duration"],
            )],
        );
    }
}

/// A colonnade's fields are named as the scene spells them: a negative `column_mass` was
/// `colonnade.left[0].mass` and a negative `span` `colonnade.beam.width: 0.0` (the beam the
/// frame builds, `span + width` long).
#[test]
fn a_colonnades_bad_field_is_named_as_the_scene_spells_it() {
    let colonnade = |field: &str, value: f64| {
        let mut fields = [
            ("width", 1.0),
            ("height", 4.0),
            ("column_mass", 1000.0),
            ("span", 3.0),
            ("beam_height", 0.5),
            ("beam_mass", 500.0),
        ];
        for f in fields.iter_mut().filter(|f| f.0 == field) {
            f.1 = value;
        }
        let fields: Vec<String> = fields
            .iter()
            .map(|(k, v)| format!(r#""{k}": {v}"#))
            .collect();
        format!(
            r#"{{"colonnade": {{{}}}, "excitation": {{"type": "none"}}, "duration": 0.1, "dt": 0.001}}"#,
            fields.join(", ")
        )
    };
    let cases: Vec<(String, &[&str])> = vec![
        (
            colonnade("column_mass", -1.0),
            &["colonnade.column_mass: -1"],
        ),
        (colonnade("span", -1.0), &["colonnade.span: -1"]),
        (colonnade("beam_height", 0.0), &["colonnade.beam_height: 0"]),
        (colonnade("width", -1.0), &["colonnade.width: -1"]),
        // A span within the columns' width: the frame's own check, already by the scene's name.
        (colonnade("span", 0.5), &["colonnade.span: 0.5", "overlap"]),
    ];
    refused("colonnade_fields", &cases);
}

/// A plain-text record in cm/s² (`"units": "cm/s2"`, as `rocking.read_record` reads it; the
/// scene knew only m/s2 and g) runs as the same record written in m/s².
#[test]
fn a_record_in_cm_s2_runs_as_the_same_record_in_m_s2() {
    let dir = fresh_dir("cm_s2");
    let samples: Vec<(f64, f64)> = (0..400)
        .map(|k| {
            let t = k as f64 * 0.005;
            (t, 9.0 * (std::f64::consts::PI * t / 1.0).sin().powi(3))
        })
        .collect();
    let write = |name: &str, factor: f64| {
        let text: String = samples
            .iter()
            .map(|(t, a)| format!("{t} {}\n", a * factor))
            .collect();
        std::fs::write(dir.join(name), text).unwrap();
    };
    write("m.txt", 1.0);
    write("cm.txt", 100.0);
    let mut outputs = Vec::new();
    for (record, units) in [("m.txt", "m/s2"), ("cm.txt", "cm/s2")] {
        let scene = dir.join(format!("{units}.json").replace('/', "_"));
        std::fs::write(
            &scene,
            format!(
                r#"{{"blocks": [{{"width": 1, "height": 4, "mass": 1000}}], "excitation": {{"type": "record", "path": "{record}", "units": "{units}"}}, "duration": 2, "dt": 0.001}}"#
            ),
        )
        .unwrap();
        let out = dir.join(format!("out_{record}"));
        let run = simulate(&scene, &out);
        assert!(run.ok, "{units}: {}", run.stderr);
        let events = std::fs::read_to_string(out.join("events.jsonl")).unwrap();
        let events: Vec<(String, f64)> = events
            .lines()
            .map(|l| {
                let e: serde_json::Value = serde_json::from_str(l).unwrap();
                (e["kind"].to_string(), e["t"].as_f64().unwrap())
            })
            .collect();
        outputs.push(events);
    }
    // The same events at the same instants (the samples differ by the round-off of × 100 × 0.01).
    let (m, cm) = (&outputs[0], &outputs[1]);
    assert!(m.len() >= 2, "{m:?}");
    assert_eq!(m.len(), cm.len(), "{m:?} {cm:?}");
    for (a, b) in m.iter().zip(cm) {
        assert!(a.0 == b.0 && (a.1 - b.1).abs() < 1e-9, "{a:?} {b:?}");
    }
}

/// `--plot` with `"output": {"history": false}` is refused before the run, nothing written (it
/// was refused after the run, its files written and, for an arch, its first chart drawn).
#[test]
fn plot_without_history_is_refused_before_the_run() {
    let dir = fresh_dir("plot_no_history");
    let none = r#""excitation": {"type": "half_sine", "amplitude": -6, "duration": 1}"#;
    for (k, body) in [
        format!(r#"{COLUMN}, {none}"#),
        format!(r#"{ARCH}, {none}"#),
        format!(r#"{COLUMN}, {none}, "on_sliding": "slide""#),
    ]
    .iter()
    .enumerate()
    {
        let scene = dir.join(format!("scene{k}.json"));
        std::fs::write(
            &scene,
            format!(r#"{{{body}, "output": {{"history": false}}}}"#),
        )
        .unwrap();
        let out = dir.join(format!("out{k}"));
        let run = common::run([
            "simulate".as_ref(),
            scene.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
            "--plot".as_ref(),
            out.join("plot.svg").as_os_str(),
        ]);
        assert!(
            !run.ok && run.stderr.contains("--plot needs the history"),
            "{body}: {}",
            run.stderr
        );
        assert!(!out.exists(), "{body}: written");
    }
}

/// A run that writes no history or events (`output.history` / `output.events` false) into the
/// folder of an earlier run removes that run's `history.csv` and `events.jsonl`: they stayed,
/// an earlier run's events (an overturning) beside this run's summary (end of duration).
#[test]
fn a_run_without_history_leaves_no_earlier_history_beside_its_summary() {
    let dir = fresh_dir("stale_outputs");
    let pulse = r#""excitation": {"type": "half_sine", "amplitude": -6, "duration": 1}"#;
    for (k, body) in [
        format!(r#"{COLUMN}, {pulse}"#),
        format!(r#"{ARCH}, {pulse}"#),
        format!(r#"{COLUMN}, {pulse}, "on_sliding": "slide""#),
    ]
    .iter()
    .enumerate()
    {
        let out = dir.join(format!("out{k}"));
        let run_with = |output: &str| {
            let scene = dir.join(format!("scene{k}.json"));
            std::fs::write(&scene, format!(r#"{{{body}{output}}}"#)).unwrap();
            let run = simulate(&scene, &out);
            assert!(run.ok, "{body}{output}: {}", run.stderr);
        };
        run_with("");
        assert!(out.join("history.csv").exists() && out.join("events.jsonl").exists());
        run_with(r#", "output": {"history": false}"#);
        assert!(
            !out.join("history.csv").exists(),
            "{body}: an earlier history.csv stayed"
        );
        assert!(out.join("events.jsonl").exists());
        run_with(r#", "output": {"events": false, "history": false}"#);
        assert!(
            !out.join("events.jsonl").exists(),
            "{body}: an earlier events.jsonl stayed"
        );
        assert!(out.join("summary.json").exists());
    }
}

/// A history too large for memory (`duration / dt / every` above 1e8 samples: a scene of 1e9
/// steps would hold about 85 GB and be killed, not refused) is refused before the run, naming
/// `output.every` and the `every` that would do, for a column, a drum column and an arch.
#[test]
fn a_history_too_large_for_memory_is_refused_naming_output_every() {
    let long = r#""excitation": {"type": "none"}, "duration": 1e6, "dt": 0.001"#;
    let cases: Vec<(String, &[&str])> = [
        r#""blocks": [{"width": 1, "height": 2, "mass": 5000}]"#,
        r#""blocks": [{"width": 1, "height": 2, "mass": 5000}], "on_sliding": "slide""#,
        r#""arch": {"radius": 5, "thickness": 0.75, "voussoirs": 8}"#,
    ]
    .iter()
    .map(|body| {
        (
            format!("{{{body}, {long}}}"),
            &["output.every", "k >= 10", "output.history false"][..],
        )
    })
    .collect();
    refused("history_too_large", &cases);
}

/// A scene saved with a UTF-8 byte-order mark (Windows editors) runs as the same scene without
/// it: the mark was refused as "expected value at line 1 column 1".
#[test]
fn a_scene_saved_with_a_byte_order_mark_runs() {
    let dir = fresh_dir("scene-bom");
    let text =
        std::fs::read_to_string(common::root().join("examples/scenes/single_block_half_sine.json"))
            .unwrap();
    let (plain, marked) = (dir.join("plain.json"), dir.join("marked.json"));
    std::fs::write(&plain, &text).unwrap();
    std::fs::write(&marked, format!("\u{feff}{text}")).unwrap();
    let a = simulate(&plain, &dir.join("a"));
    let b = simulate(&marked, &dir.join("b"));
    assert!(a.ok && b.ok, "{}", b.stderr);
    let events = |d: &str| std::fs::read_to_string(dir.join(d).join("events.jsonl")).unwrap();
    assert_eq!(events("a"), events("b"));
}

/// A step that skips the ground motion is refused for columns and drum columns as for arches:
/// a 0.5 s half-sine at `dt = 1` left a column at rest ("0 events"), and a step longer than a
/// record's own skipped its samples. A step of a tenth of the pulse, or the record's own, runs.
#[test]
fn a_step_that_skips_the_ground_motion_is_refused_for_columns_and_drums() {
    let blocks = r#""blocks": [{"width": 1, "height": 2, "mass": 5000}, {"width": 1, "height": 2, "mass": 5000}], "duration": 1"#;
    let pulse = r#""excitation": {"type": "half_sine", "amplitude": 6, "duration": 0.5}"#;
    let record = r#""excitation": {"type": "record", "path": "synthetic.AT2"}"#;
    let drums = r#""friction": 0.5, "on_sliding": "slide", "on_tension": "fly""#;
    refused(
        "step_skips",
        &[
            (
                format!(r#"{{{blocks}, {pulse}, "dt": 1}}"#),
                &["dt: 1", "tenth of the pulse", "at most 0.05"],
            ),
            (
                format!(r#"{{{blocks}, {record}, "dt": 0.02}}"#),
                &["dt: 0.02", "record's own step", "at most 0.01"],
            ),
            (
                format!(r#"{{{blocks}, {pulse}, {drums}, "dt": 0.06}}"#),
                &["dt: 0.06", "tenth of the pulse"],
            ),
            (
                format!(r#"{{{blocks}, {record}, {drums}, "dt": 0.011}}"#),
                &["dt: 0.011", "record's own step"],
            ),
        ],
    );
    let dir = fresh_dir("step_resolves");
    std::fs::copy(
        common::root().join("examples/records/synthetic.AT2"),
        dir.join("synthetic.AT2"),
    )
    .unwrap();
    for text in [
        format!(r#"{{{blocks}, {pulse}, "dt": 0.05}}"#),
        format!(r#"{{{blocks}, {record}, "dt": 0.01}}"#),
        format!(r#"{{{blocks}, {record}, {drums}, "dt": 0.01}}"#),
    ] {
        std::fs::write(dir.join("scene.json"), &text).unwrap();
        let run = simulate(&dir.join("scene.json"), &dir.join("out"));
        assert!(run.ok, "{text}: {}", run.stderr);
    }
}
