//! `rocking bench drums --quick`: the reduced drum suite (three FEMA P695 far-field records,
//! 3/5/10 drums of 1 x 1 and 1 x 2 m, 4 m/s², μ = 0.5, sliding and flight allowed). Needs
//! `../shared` (skipped when absent; CI has it).

mod common;

use std::path::PathBuf;

fn quick_suite() -> Option<Vec<Vec<String>>> {
    quick_suite_with(&[])
}

fn quick_suite_with(extra: &[&str]) -> Option<Vec<Vec<String>>> {
    let records = common::root().join("../shared/records/fema-p695/farfield");
    if !records.exists() {
        println!("skipped: {} not found", records.display());
        return None;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("bench_drums{}", extra.join("_").replace('-', "")));
    let _ = std::fs::remove_dir_all(&dir);
    let csv = dir.join("runs.csv");
    let mut args = vec![
        "bench".as_ref(),
        "drums".as_ref(),
        "--quick".as_ref(),
        "--records".as_ref(),
        records.as_os_str(),
        "--csv".as_ref(),
        csv.as_os_str(),
    ];
    args.extend(extra.iter().map(std::ffi::OsStr::new));
    let run = common::run(args);
    assert!(run.ok, "{}", run.stderr);
    assert!(run.stdout.contains("How the runs ended"), "{}", run.stdout);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[7], "stop");
    assert_eq!(header[15], "energy_error");
    assert_eq!(header[16], "closure");
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    assert_eq!(rows.len(), 18);
    Some(rows)
}

#[test]
fn every_run_ends_at_the_end_of_the_record_or_by_overturning() {
    let Some(rows) = quick_suite() else { return };
    for r in &rows {
        let (stop, t_end, duration) = (&r[7], &r[8], &r[9]);
        match stop.as_str() {
            "end of record" => assert_eq!(t_end, duration, "{r:?}"),
            "overturned" | "fallen" | "slid off" => assert_eq!(r[10], "true", "{r:?}"),
            other => panic!("run ended by {other}: {r:?}"),
        }
        // The scheme's energy identity (with its own error terms) holds to round-off.
        let closure: f64 = r[16].parse().unwrap();
        assert!(closure.abs() < 1e-6, "closure {closure}: {r:?}");
    }
}

/// The runs whose energy residual (column 15) exceeds `limit`, for the message.
fn energy_above(rows: &[Vec<String>], limit: f64) -> Vec<String> {
    rows.iter()
        .filter(|r| r[15].parse::<f64>().unwrap().abs() > limit)
        .map(|r| format!("{} {} drums {}x{}: {}", r[0], r[1], r[2], r[3], r[15]))
        .collect()
}

/// The target: ground work = ΔV + ΔT + impacts + friction within 0.1 % on every run.
/// Not met yet (docs/multidrum.md, "Energy"): the scheme's error — ends caught within a step,
/// the projections after slow arrivals — is first order in dt and reaches 2 % on some runs of
/// this reduced suite. Run with `--ignored` to see the residuals.
#[test]
#[ignore = "open target of issue 11: energy residual 0.1 % on every run (see docs/multidrum.md)"]
fn energy_residual_is_within_a_thousandth_on_every_run() {
    let Some(rows) = quick_suite() else { return };
    let bad = energy_above(&rows, 1e-3);
    assert!(bad.is_empty(), "{} runs above 1e-3: {bad:#?}", bad.len());
}

/// The same target with the scheme's error control (`--energy-tol`, docs/energy-control.md): a
/// step whose own energy error exceeds 1e-6 of the run's energy scale is redone as two halves.
/// Every run of the reduced suite is then within 0.1 % (largest 4.9e-4 when this was written),
/// and the identity with the scheme's terms still closes at round-off.
#[test]
fn energy_residual_is_within_a_thousandth_with_the_error_control() {
    let Some(rows) = quick_suite_with(&["--energy-tol", "1e-6"]) else {
        return;
    };
    let bad = energy_above(&rows, 1e-3);
    assert!(bad.is_empty(), "{} runs above 1e-3: {bad:#?}", bad.len());
    for r in &rows {
        let closure: f64 = r[16].parse().unwrap();
        assert!(closure.abs() < 1e-6, "closure {closure}: {r:?}");
        assert_eq!(r.len(), 24, "refined,refine_floor columns: {r:?}");
    }
    assert!(rows.iter().any(|r| r[22] != "0"), "no step was refined");
}

/// The same target with the located impacts' one-signed errors removed at their source
/// (`--consistent`, `SchemeOptions::energy_consistent`, docs/energy-control.md), no step
/// refined: every run of the reduced suite within 0.1 % (largest 5.2e-5 when this was written),
/// the identity closing at round-off.
#[test]
fn energy_residual_is_within_a_thousandth_with_consistent_impacts() {
    let Some(rows) = quick_suite_with(&["--consistent"]) else {
        return;
    };
    let bad = energy_above(&rows, 1e-3);
    assert!(bad.is_empty(), "{} runs above 1e-3: {bad:#?}", bad.len());
    for r in &rows {
        let closure: f64 = r[16].parse().unwrap();
        assert!(closure.abs() < 1e-9, "closure {closure}: {r:?}");
        assert_eq!(r.len(), 22, "no refine columns without --energy-tol: {r:?}");
    }
}

/// `rocking bench drums` on one tall drum under the bundled record, one thread, with `extra`
/// arguments (later ones override).
fn one_drum(extra: &[&str]) -> common::Run {
    let base = [
        "bench",
        "drums",
        "--records",
        "examples/records",
        "--drums",
        "1",
        "--shapes",
        "1x10",
        "--threads",
        "1",
    ];
    common::run(base.iter().chain(extra))
}

/// A bad `--pga` or `--mu` (or more drums than a column can have, or a `--dt` of more than 1e10
/// steps for a record or longer than a record's own step, which ran on the ground motion's
/// samples skipped) is refused before any run,
/// naming the argument (a NaN, 0 or negative value failed in the middle of the suite, after the
/// runs of the values before it, as `target = NaN`, `invalid drum option friction` or `5000
/// blocks: …`).
#[test]
fn a_bad_pga_or_mu_is_refused_before_any_run() {
    for bad in [
        "--drums=3,5000",
        "--pga=nan",
        "--pga=-1",
        "--pga=0",
        "--pga=4,inf",
        "--mu=nan",
        "--mu=0",
        "--mu=0.5,-1",
        "--dt=1e-300",
        "--dt=0.05",
    ] {
        let run = one_drum(&[bad]);
        let arg = bad.split('=').next().unwrap();
        assert!(!run.ok, "{bad} accepted: {}", run.stdout);
        assert!(run.stderr.contains(arg), "{bad}: {}", run.stderr);
        assert!(
            !run.stdout.contains("How the runs ended"),
            "{bad} ran: {}",
            run.stdout
        );
    }
    let run = one_drum(&["--pga", "4", "--mu", "inf"]);
    assert!(run.ok, "--mu inf (no sliding): {}", run.stderr);
}

/// An output that cannot be written is refused before the runs (a suite of hours wrote its
/// `--csv` or `--out` only at the end, and failed there).
#[test]
fn an_unwritable_output_is_refused_before_any_run() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench_drums_unwritable");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let folder = dir.to_string_lossy().into_owned();
    for (flag, path) in [
        ("--csv", "/proc/rocking/runs.csv"),
        ("--out", "/proc/rocking/report.md"),
        ("--csv", folder.as_str()),
    ] {
        let run = one_drum(&["--pga", "4", "--mu", "0.5", flag, path]);
        assert!(!run.ok, "{flag} {path} accepted");
        assert!(run.stderr.contains(flag), "{flag} {path}: {}", run.stderr);
        assert!(
            !run.stdout.contains("How the runs ended"),
            "{flag} {path} ran: {}",
            run.stdout
        );
    }
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "a probe was left behind"
    );
}

/// A value given twice is run once (`--pga 4,4` ran and counted every case twice), and a
/// missing records folder (the default one on a fresh clone) says what to give.
#[test]
fn repeated_values_run_once_and_a_missing_records_folder_says_what_to_give() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench_drums_repeated");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("runs.csv");
    let csv = csv.to_string_lossy();
    let run = one_drum(&["--pga", "4,4", "--mu", "0.5,0.5", "--csv", &csv]);
    assert!(run.ok, "{}", run.stderr);
    let rows = std::fs::read_to_string(dir.join("runs.csv")).unwrap();
    assert_eq!(rows.lines().count(), 2, "{rows}");
    let run = common::run(["bench", "drums", "--records", "no/such/folder"]);
    assert!(!run.ok);
    for part in ["--records no/such/folder", ".AT2", "examples/records"] {
        assert!(run.stderr.contains(part), "{part}: {}", run.stderr);
    }
}
