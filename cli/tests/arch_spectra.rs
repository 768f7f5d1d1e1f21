//! `rocking arch oas` / `rocking arch oc`: the arch spectra on the bundled record and a pulse
//! (small grids), their JSON and charts; bad arguments are named.

mod common;

use std::path::PathBuf;

fn tmp(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn arch_oas_reports_the_scan_and_the_t1_check() {
    let dir = tmp("arch-oas");
    let prefix = dir.join("a");
    let run = common::run([
        "arch",
        "oas",
        "examples/records/synthetic.AT2",
        "--voussoirs",
        "8",
        "--radius-max",
        "20",
        "--radius-min",
        "5",
        "--radius-n",
        "2",
        "--level-min",
        "1",
        "--level-max",
        "2",
        "--level-n",
        "2",
        "--t1",
        "0.2276",
        "--svg",
        prefix.to_str().unwrap(),
    ]);
    assert!(run.ok, "{}", run.stderr);
    let v: serde_json::Value = serde_json::from_str(&run.stdout).unwrap();
    // λ of the 8-voussoir arch (docs/arches.md §1, independent limit analysis).
    let lambda = v["onset"]["lambda"].as_f64().unwrap();
    assert!((lambda - 0.159368).abs() < 5e-7, "{lambda}");
    assert_eq!(v["onset"]["hinges"].as_array().unwrap().len(), 4);
    let levels = v["levels"].as_array().unwrap();
    assert_eq!(levels.len(), 2);
    // Level 1: the record never exceeds λ g, nothing runs, nothing collapses.
    assert_eq!(levels[0]["simulations"], 0);
    assert!(levels[0]["size"].is_null());
    assert_eq!(v["check"]["t1"], 0.2276);
    for name in ["oas", "transformed"] {
        let svg = std::fs::read_to_string(dir.join(format!("a-{name}.svg"))).unwrap();
        assert!(svg.contains("<svg"));
    }
}

#[test]
fn arch_oc_reports_an_envelope() {
    let run = common::run([
        "arch",
        "oc",
        "--voussoirs",
        "8",
        "--ptp-n",
        "1",
        "--ptp-min",
        "2",
        "--ptp-max",
        "2",
        "--level-n",
        "2",
        "--level-max",
        "1.5",
    ]);
    assert!(run.ok, "{}", run.stderr);
    let v: serde_json::Value = serde_json::from_str(&run.stdout).unwrap();
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    // Level 1 never moves the arch.
    assert_eq!(points[0]["level"], 1.0);
    assert_eq!(points[0]["collapses"], false);
    let p = v["p"].as_f64().unwrap();
    assert!((points[0]["p_tp"].as_f64().unwrap() - 2.0).abs() < 1e-9 * p.max(1.0));
}

#[test]
fn arch_bad_arguments_are_named() {
    let run = common::run([
        "arch",
        "oas",
        "examples/records/synthetic.AT2",
        "--voussoirs",
        "0",
    ]);
    assert!(
        !run.ok && run.stderr.contains("--voussoirs"),
        "{}",
        run.stderr
    );
    let run = common::run([
        "arch",
        "oas",
        "examples/records/synthetic.AT2",
        "--thickness-ratio",
        "0.05",
    ]);
    assert!(!run.ok && run.stderr.contains("arch"), "{}", run.stderr);
    let run = common::run(["arch", "oc", "--radius=-1"]);
    assert!(!run.ok && run.stderr.contains("--radius"), "{}", run.stderr);
}
