//! `rocking suite`: the design curves of a record suite on the bundled record (fast), and on
//! three far-field records of `../shared` when present (skipped otherwise).

mod common;

use std::path::{Path, PathBuf};

const SMALL: [&str; 4] = ["--levels", "8", "--sizes", "24"];

fn json(args: &[&str]) -> serde_json::Value {
    let out = common::run(args);
    assert!(out.ok, "{}", out.stderr);
    serde_json::from_str(&out.stdout).unwrap()
}

fn tmp(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

#[test]
fn suite_of_the_bundled_record() {
    let prefix = tmp("suite-synthetic");
    let p = prefix.to_str().unwrap();
    let mut args = vec![
        "suite",
        "examples/records/synthetic.AT2",
        "--json",
        "--fractile",
        "0.5,0.84",
        "--svg",
        p,
        "--csv",
        p,
    ];
    args.extend(SMALL);
    let v = json(&args);
    let record = &v["records"][0];
    let t1 = record["summary"]["t1"].as_f64().unwrap();
    let c = v["characteristic"].as_array().unwrap();
    assert_eq!(c.len(), 2);
    for c in c {
        // One record: the characteristic OAS at any fractile is the record's own.
        assert_eq!(c["design_t1"].as_f64(), Some(t1), "{c}");
        assert_eq!(c["record_t1_fractile"].as_f64(), Some(t1));
        let v = c["violations"].as_array().unwrap();
        let below: Vec<_> = v.iter().map(|v| v["level_below"].as_f64()).collect();
        assert_eq!(below, vec![Some(4.0), Some(6.0), Some(12.0), None]);
        assert_eq!(v[3]["eq21"]["points"], 0);
    }
    assert_eq!(v["hulls"].as_array().unwrap().len(), 1);
    let f_min = v["hulls"][0]["f_min"].as_f64().unwrap();
    assert_eq!(Some(f_min), record["summary"]["f_min"].as_f64());
    for name in ["oas", "transformed", "hulls", "size"] {
        let f = format!("{p}-{name}.svg");
        assert!(std::fs::read_to_string(&f).unwrap().contains("<svg"), "{f}");
    }
    let csv = std::fs::read_to_string(format!("{p}-characteristic.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 8, "{csv}");

    // The same suite from `rocking oas --json`, merged: the same curves.
    let oas_json = tmp("suite-synthetic-oas.json");
    let mut args = vec!["oas", "examples/records/synthetic.AT2", "--json"];
    args.extend(SMALL);
    let out = common::run(&args);
    assert!(out.ok, "{}", out.stderr);
    std::fs::write(&oas_json, out.stdout).unwrap();
    let m = json(&["suite", "--merge", oas_json.to_str().unwrap(), "--json"]);
    assert_eq!(m["characteristic"], v["characteristic"]);
    assert_eq!(m["hulls"], v["hulls"]);
    // A record given twice is an error that names it.
    let out = common::run([
        "suite",
        "--merge",
        oas_json.to_str().unwrap(),
        oas_json.to_str().unwrap(),
    ]);
    assert!(
        !out.ok && out.stderr.contains("already in the suite"),
        "{}",
        out.stderr
    );
}

#[test]
fn a_bad_fractile_names_the_argument() {
    for bad in ["0", "1.2", "x"] {
        let out = common::run(["suite", "examples/records/synthetic.AT2", "--fractile", bad]);
        assert!(
            !out.ok && out.stderr.contains("--fractile"),
            "{bad}: {}",
            out.stderr
        );
    }
}

/// Three far-field records on a small grid: the design t₁ grows with the fractile, and the
/// fractile 1 (the largest unsafe size of every level) is conservative for every record.
#[test]
fn suite_of_shared_far_field_records() {
    let dir = std::env::var_os("ROCKING_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| common::root().join("../shared"));
    let records = dir.join("records/fema-p695/farfield");
    if !records.join("RSN953_NORTHR_MUL009.AT2").exists() {
        println!("skipped: ../shared (or $ROCKING_SHARED) with records/fema-p695 not found");
        return;
    }
    let files: Vec<String> = [
        "RSN953_NORTHR_MUL009.AT2",
        "RSN960_NORTHR_LOS000.AT2",
        "RSN1111_KOBE_NIS000.AT2",
    ]
    .iter()
    .map(|f| Path::new(&records).join(f).display().to_string())
    .collect();
    let mut args = vec!["suite", "--json", "--fractile", "0.5,0.84,1"];
    args.extend(files.iter().map(String::as_str));
    args.extend(["--levels", "12", "--sizes", "40"]);
    let v = json(&args);
    let t1: Vec<f64> = v["characteristic"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["design_t1"].as_f64().unwrap())
        .collect();
    assert!(t1[0] <= t1[1] && t1[1] <= t1[2], "{t1:?}");
    let own_max = v["records"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["summary"]["t1"].as_f64().unwrap())
        .fold(0.0, f64::max);
    assert!(t1[2] >= own_max, "{t1:?} {own_max}");
    let all = &v["characteristic"][2]["violations"][3];
    assert_eq!(all["eq21"]["points"], 0, "{all}");
    // Each record's own t1: Eq. 21 (exact i_cr) holds by the definition of t1, and the fit is
    // left of every point.
    let own = &v["own_parameters"][3];
    assert_eq!(own["eq21"]["points"], 0, "{own}");
    assert_eq!(own["eq29"]["points"], 0, "{own}");
}
