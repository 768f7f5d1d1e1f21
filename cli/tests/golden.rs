//! The answers the architecture redesign (issue 10) must keep bit for bit: `tools/golden/capture.sh`
//! re-runs every captured output (`rocking thesis`, every bundled scene's events, summary and
//! history, t₁/OAS/OC of the bundled record, design, `bench accuracy --quick` without its wall
//! times, what each C example prints) and the result must equal `tests/golden/` byte for byte;
//! t₁ of three FEMA P695 records (when `../shared` is present) must equal the captured
//! `t1-farfield.json` entries in every field but the wall time. The full 44-record comparison is
//! `tools/golden/capture.sh --shared DIR && diff -r tests/golden DIR`.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{bin, root};

fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(files(&p));
        } else {
            out.push(p);
        }
    }
    out.sort();
    out
}

#[test]
fn every_captured_output_is_unchanged() {
    let lib = Path::new(bin()).parent().unwrap();
    if !lib.join("librocking.so").exists() {
        // `cargo test --release` builds the CLI but the cdylib only with `cargo build`.
        let ok = Command::new(env!("CARGO"))
            .args(["build", "--release", "-p", "rocking"])
            .current_dir(root())
            .status()
            .unwrap()
            .success();
        assert!(ok, "cargo build of the library failed");
    }
    let dir = std::env::temp_dir().join(format!("rocking-golden-{}", std::process::id()));
    let status = Command::new(root().join("tools/golden/capture.sh"))
        .arg(&dir)
        .env("ROCKING_BIN", bin())
        .current_dir(root())
        .status()
        .unwrap();
    assert!(status.success(), "capture.sh failed");
    let golden = root().join("tests/golden");
    let mut differ = Vec::new();
    for want in files(&golden) {
        let rel = want.strip_prefix(&golden).unwrap();
        if rel == Path::new("t1-farfield.json") {
            continue;
        }
        let got = std::fs::read(dir.join(rel)).unwrap_or_default();
        if got != std::fs::read(&want).unwrap() {
            differ.push(rel.display().to_string());
        }
    }
    assert!(
        differ.is_empty(),
        "outputs differ from tests/golden (new ones in {}): {differ:?}",
        dir.display()
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `rocking t1 --json EXTRA…` of far-field records of `../shared` (`None`, with a note, when it
/// is absent), checked against the rows of `stored` (a path from the root) in every field but the
/// wall time; the rows computed.
fn t1_of_shared_records_against(
    names: &[&str],
    extra: &[&str],
    stored: &str,
) -> Option<Vec<serde_json::Value>> {
    let shared = std::env::var_os("ROCKING_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("../shared"));
    let far = shared.join("records/fema-p695/farfield");
    if !far.exists() {
        println!("skipped: {} not found", far.display());
        return None;
    }
    let mut args = vec!["t1".to_string(), "--json".to_string()];
    args.extend(extra.iter().map(|a| a.to_string()));
    args.extend(
        names
            .iter()
            .map(|n| format!("../shared/records/fema-p695/farfield/{n}.AT2")),
    );
    let out = common::run(&args);
    assert!(out.ok, "{}", out.stderr);
    let got: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
    let want: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root().join(stored)).unwrap()).unwrap();
    let without_seconds = |r: &serde_json::Value| {
        let mut r = r.clone();
        r.as_object_mut().unwrap().remove("seconds");
        r
    };
    let rows = got.as_array().unwrap().clone();
    for row in &rows {
        let name = row["record"].as_str().unwrap();
        let w = want
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["record"] == name)
            .unwrap_or_else(|| panic!("{name} not in {stored}"));
        assert_eq!(without_seconds(row), without_seconds(w), "{name}");
    }
    Some(rows)
}

/// The step rule's t₁ (the default before it converged in the step) of three records.
#[test]
fn t1_of_shared_records_is_unchanged() {
    let names = [
        "RSN953_NORTHR_MUL009",
        "RSN1158_KOCAELI_DZC180",
        "RSN960_NORTHR_LOS000",
    ];
    t1_of_shared_records_against(&names, &["--single-step"], "tests/golden/t1-farfield.json");
}

/// t₁ converged in the step (`rocking t1`'s default) of two FEMA P695 records equals the stored
/// rows of `docs/data/t1-dt/converge/farfield-converge.json` in every field but the wall time:
/// LOS270, converged at half the step, and MUL279, whose t₁ moves by 11 % at half the step and
/// converges at a quarter (issue 14's case of a step rule too coarse for one record).
#[test]
fn t1_converged_of_shared_records_is_the_stored_one() {
    let names = ["RSN953_NORTHR_MUL279", "RSN960_NORTHR_LOS270"];
    let stored = "docs/data/t1-dt/converge/farfield-converge.json";
    let Some(rows) = t1_of_shared_records_against(&names, &[], stored) else {
        return;
    };
    let steps = |i: usize| rows[i]["t1_steps"].as_array().unwrap().len();
    assert_eq!((steps(0), steps(1)), (3, 2));
}
