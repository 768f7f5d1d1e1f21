//! `rocking simulate`: the bundled scenes run and write what they promise; bad scenes fail with
//! the field named and write nothing.

mod common;

use std::path::{Path, PathBuf};

use common::Run;

/// `rocking simulate SCENE --out OUT`, with `--plot PLOT` when given.
fn simulate(scene: &Path, out: &Path, plot: Option<&Path>) -> Run {
    let mut args = vec![
        "simulate".as_ref(),
        scene.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ];
    if let Some(plot) = plot {
        args.extend(["--plot".as_ref(), plot.as_os_str()]);
    }
    common::run(args)
}

fn scenes() -> PathBuf {
    common::root().join("examples/scenes")
}

fn fresh_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn bundled_scenes_run_and_write_their_outputs() {
    for scene in [
        "two_block_free_rocking",
        "single_block_half_sine",
        "column_synthetic_record",
        "three_block_sine_pulse",
    ] {
        let out = fresh_dir(scene);
        let plot = out.join("plot.svg");
        let run = simulate(&scenes().join(format!("{scene}.json")), &out, Some(&plot));
        assert!(run.ok, "{scene}: {}", run.stderr);
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        for key in [
            "overturned",
            "t_end",
            "impacts",
            "stop_reason",
            "peak_block_rotation",
        ] {
            assert!(summary.get(key).is_some(), "{scene}: summary lacks {key}");
        }
        let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
        assert!(history.starts_with("t,angle_0"), "{scene}");
        assert!(history.lines().count() > 10);
        for line in std::fs::read_to_string(out.join("events.jsonl"))
            .unwrap()
            .lines()
        {
            let e: serde_json::Value = serde_json::from_str(line).unwrap();
            for key in [
                "t",
                "kind",
                "interface",
                "kinetic_before",
                "kinetic_after",
                "statuses_before",
                "statuses_after",
                "report",
            ] {
                assert!(e.get(key).is_some(), "{scene}: event lacks {key}");
            }
        }
        assert!(std::fs::read_to_string(&plot).unwrap().starts_with("<svg"));
    }
}

#[test]
fn the_two_block_experiment_opens_and_impacts_near_the_thesis_times() {
    let out = fresh_dir("two_block_times");
    let run = simulate(&scenes().join("two_block_free_rocking.json"), &out, None);
    assert!(run.ok, "{}", run.stderr);
    let events: Vec<serde_json::Value> = std::fs::read_to_string(out.join("events.jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    // Thesis 4.2: lower interface opens about 0.13 s, upper impact about 0.187 s, lower impact
    // about 0.193 s (read off the thesis's simulation to two or three digits).
    let first = |kind: &str, interface: u64| {
        events
            .iter()
            .find(|e| e["kind"] == kind && e["interface"] == interface)
            .map(|e| e["t"].as_f64().unwrap())
            .unwrap()
    };
    assert!((first("opening", 0) - 0.13).abs() < 0.005);
    assert!((first("impact", 1) - 0.187).abs() < 0.005);
    assert!((first("impact", 0) - 0.193).abs() < 0.005);
}

#[test]
fn a_bad_scene_fails_naming_the_field_and_writes_nothing() {
    let dir = fresh_dir("bad_scene");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("bad.json");
    std::fs::write(
        &scene,
        r#"{"blocks": [{"width": 0.2, "height": 1.0, "mass": 10}], "excitation": {"type": "none"}, "duration": 1.0, "dt": 0.0}"#,
    )
    .unwrap();
    let out = dir.join("out");
    let run = simulate(&scene, &out, None);
    assert!(!run.ok);
    assert!(run.stderr.contains("dt"), "{}", run.stderr);
    assert!(!out.exists(), "output written for a failed scene");
    std::fs::write(&scene, r#"{"blocks": [], "excitation": {"type": "none"}, "duration": 1.0, "dt": 0.01, "speed": 3}"#).unwrap();
    let run = simulate(&scene, &out, None);
    assert!(run.stderr.contains("unknown field `speed`"));
}

#[test]
fn a_drum_scene_rocks_slides_and_flies_and_writes_slips() {
    // Five 1 x 1 m drums, μ = 0.5, `on_sliding: "slide"`, `on_tension: "fly"`: the contact scheme.
    let out = fresh_dir("drums_sliding_column");
    let plot = out.join("plot.svg");
    let run = simulate(
        &scenes().join("drums_sliding_column.json"),
        &out,
        Some(&plot),
    );
    assert!(run.ok, "{}", run.stderr);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["scheme"], "moreau");
    assert_eq!(summary["stop_reason"], "duration", "{summary}");
    for key in [
        "peak_slip",
        "residual_slip",
        "peak_block_rotation",
        "modes_end",
    ] {
        assert_eq!(summary[key].as_array().unwrap().len(), 5, "{key}");
    }
    let peak: Vec<f64> = summary["peak_slip"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let residual = summary["residual_slip"].as_array().unwrap();
    for (p, r) in peak.iter().zip(residual) {
        assert!(r.as_f64().unwrap().abs() <= p + 1e-15);
    }
    assert!(peak.iter().any(|&p| p > 1e-4), "no joint slid: {peak:?}");
    // Energy: ground work = Δ potential + Δ kinetic + impacts + friction within 0.1 %.
    let rel = summary["energy"]["relative_residual"].as_f64().unwrap();
    assert!(rel.abs() < 1e-3, "energy residual {rel}");
    let events = std::fs::read_to_string(out.join("events.jsonl")).unwrap();
    let mut kinds = std::collections::BTreeSet::new();
    for line in events.lines() {
        let e: serde_json::Value = serde_json::from_str(line).unwrap();
        assert!(e["t"].is_f64() && e["joint"].is_u64(), "{line}");
        kinds.insert(e["kind"].as_str().unwrap().to_string());
    }
    for kind in ["slip_start", "slip_stop", "lift_off", "landing", "impact"] {
        assert!(kinds.contains(kind), "no {kind} event: {kinds:?}");
    }
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let header = history.lines().next().unwrap();
    assert!(header.starts_with("t,x_0"), "{header}");
    assert!(header.ends_with(",slip_3,slip_4"), "{header}");
    assert!(history.lines().count() > 20_000);
    assert!(std::fs::read_to_string(&plot).unwrap().starts_with("<svg"));
    assert!(std::fs::read_to_string(out.join("plot_slips.svg"))
        .unwrap()
        .starts_with("<svg"));
}

/// An `--out` that is a file or cannot be created, or an unwritable `--plot`, is refused
/// before the run (it failed after it: the outputs of a long drum run lost, or written and
/// the command failing at the chart), naming the argument.
#[test]
fn an_unwritable_out_or_plot_is_refused_before_the_run() {
    let dir = fresh_dir("simulate_unwritable");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("a_file");
    std::fs::write(&file, "").unwrap();
    let scene = scenes().join("drums_sliding_column.json");
    for (out, plot, flag) in [
        (file.clone(), None, "--out"),
        (PathBuf::from("/proc/rocking/out"), None, "--out"),
        (
            dir.join("out"),
            Some(PathBuf::from("/proc/rocking/p.svg")),
            "--plot",
        ),
    ] {
        let run = simulate(&scene, &out, plot.as_deref());
        assert!(!run.ok, "{out:?} {plot:?} accepted");
        assert!(run.stderr.contains(flag), "{flag}: {}", run.stderr);
        assert!(run.stdout.is_empty(), "it ran: {}", run.stdout);
        assert!(!dir.join("out").exists(), "outputs written");
    }
    // Nothing created for the check: a run that then fails leaves no folder behind.
    let deep = dir.join("a/b/out");
    let run = simulate(&scene, &deep, Some(&dir.join("c/d/plot.svg")));
    assert!(run.ok, "{}", run.stderr);
    assert!(deep.join("summary.json").exists() && dir.join("c/d/plot_slips.svg").exists());
}

#[test]
fn an_auto_scene_writes_one_record_with_its_scheme_switches() {
    // The bundled sliding column with `"scheme": "auto"`: the driver until contacts crowd.
    let dir = fresh_dir("drums_auto");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(scenes().join("drums_sliding_column.json")).unwrap();
    let mut spec: serde_json::Value = serde_json::from_str(&text).unwrap();
    spec["scheme"] = "auto".into();
    if let Some(p) = spec["excitation"]["path"].as_str() {
        let abs = scenes().join(p);
        spec["excitation"]["path"] = abs.display().to_string().into();
    }
    let scene = dir.join("auto.json");
    std::fs::write(&scene, spec.to_string()).unwrap();
    let out = dir.join("out");
    let run = simulate(&scene, &out, None);
    assert!(run.ok, "{}", run.stderr);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["scheme"], "auto");
    let t_end = summary["t_end"].as_f64().unwrap();
    let ed = summary["time_event_driven"].as_f64().unwrap();
    assert!(ed > 0.0 && ed <= t_end, "{summary}");
    let switches = summary["scheme_switches"].as_u64().unwrap();
    let events = std::fs::read_to_string(out.join("events.jsonl")).unwrap();
    let lines: Vec<serde_json::Value> = events
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .filter(|e: &serde_json::Value| e["kind"] == "scheme_switch")
        .collect();
    assert_eq!(lines.len() as u64, switches);
    assert!(switches >= 1, "{summary}");
    for e in &lines {
        assert!(e["from"] != e["to"], "{e}");
        assert!(e["why"].is_string(), "{e}");
    }
    assert_eq!(lines[0]["from"], "event_driven");
    assert_eq!(summary["stop_reason"], "duration", "{summary}");
}

#[test]
fn a_drum_scene_with_a_bad_field_fails_naming_it() {
    let dir = fresh_dir("bad_drum_scene");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("bad.json");
    let base = r#"{"blocks": [{"width": 1, "height": 1, "mass": 2500}, {"width": 1, "height": 1, "mass": 2500}], "excitation": {"type": "none"}, "duration": 1.0, "dt": 0.001"#;
    for (extra, field) in [
        (r#", "on_sliding": "slide", "friction": [0.5]"#, "friction"),
        (r#", "on_tension": "float""#, "on_tension"),
        (
            r#", "scheme": "event_driven", "on_sliding": "slide""#,
            "on_sliding",
        ),
    ] {
        std::fs::write(&scene, format!("{base}{extra}}}")).unwrap();
        let out = dir.join("out");
        let run = simulate(&scene, &out, None);
        assert!(!run.ok, "{extra}");
        assert!(run.stderr.contains(field), "{extra}: {}", run.stderr);
        assert!(!out.exists(), "output written for a failed scene");
    }
}

/// An arch scene runs the loop driver: the bundled 20-voussoir arch under a half-sine of 3 λ
/// collapses (as `tests/arch_dynamics.rs`, `driver_pulse_well_above_lambda_collapses`), with the
/// closure kept, its hinges listed and both charts drawn; an arch scene with a column's setting
/// fails naming it.
#[test]
fn an_arch_scene_runs_the_loop_driver() {
    let out = fresh_dir("arch_half_sine");
    let plot = out.join("plot.svg");
    let run = simulate(&scenes().join("arch_half_sine.json"), &out, Some(&plot));
    assert!(run.ok, "{}", run.stderr);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["collapsed"], true, "{summary}");
    let t_end = summary["t_end"].as_f64().unwrap();
    // 0.720272 s before the closings were located on the step's cubic (docs/arches.md §2b: the
    // instant converges to 0.7195 s as dt shrinks; the new figure is 0.65 ms nearer to it).
    assert!((t_end - 0.719618).abs() < 1e-6, "{t_end}");
    assert!(summary["max_closure_residual"].as_f64().unwrap() < 1e-12);
    assert_eq!(summary["statuses_end"].as_array().unwrap().len(), 21);
    // The first mechanism: the limit-analysis hinges (3, 15 intrados; 9, 20 extrados).
    let events = std::fs::read_to_string(out.join("events.jsonl")).unwrap();
    let first: serde_json::Value = serde_json::from_str(events.lines().next().unwrap()).unwrap();
    assert_eq!(first["kind"], "opening");
    let open: Vec<(usize, i64)> = first["statuses"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
        .filter(|(_, s)| s.as_i64() != Some(0))
        .map(|(k, s)| (k, s.as_i64().unwrap()))
        .collect();
    assert_eq!(open, vec![(3, -1), (9, 1), (15, -1), (20, 1)]);
    assert!(events.lines().any(|l| l.contains("\"kind\":\"closing\"")));
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    assert!(history.starts_with("t,angle_0,"));
    // A row per moving step (the arch opens at 0.109 s and collapses at 0.7196 s: some 600
    // steps of 1 ms) and per event (46), 641 rows (over 700 when the linearly located closings
    // made 161 events).
    assert!(history.lines().count() > 600);
    for chart in [plot.clone(), out.join("plot_history.svg")] {
        assert!(std::fs::read_to_string(&chart).unwrap().contains("<svg"));
    }

    let dir = fresh_dir("bad_arch");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("bad.json");
    std::fs::write(
        &scene,
        r#"{"arch": {"radius": 5, "thickness": 0.75, "voussoirs": 20}, "impacts": 2, "excitation": {"type": "none"}, "duration": 1.0, "dt": 0.001}"#,
    )
    .unwrap();
    let run = simulate(&scene, &dir.join("out"), None);
    assert!(!run.ok && run.stderr.contains("impacts"), "{}", run.stderr);
    std::fs::write(
        &scene,
        r#"{"arch": {"radius": 5, "thickness": -0.75, "voussoirs": 20}, "excitation": {"type": "none"}, "duration": 1.0, "dt": 0.001}"#,
    )
    .unwrap();
    let run = simulate(&scene, &dir.join("out"), None);
    assert!(
        !run.ok && run.stderr.contains("arch.thickness"),
        "{}",
        run.stderr
    );
    assert!(!dir.join("out").exists());
}
