//! `rocking t1`, `oas --merge`, `design width/check`: JSON outputs with the documented fields.

mod common;

use std::path::PathBuf;

use rocking::samples::PIER_EXAMPLE;

/// `rocking args…` from the workspace root: (success, stdout, stderr).
fn rocking(args: &[&str]) -> (bool, String, String) {
    let out = common::run(args);
    (out.ok, out.stdout, out.stderr)
}

const SMALL: [&str; 4] = ["--levels", "8", "--sizes", "24"];

#[test]
fn t1_json_has_the_documented_fields() {
    let mut args = vec!["t1", "examples/records/synthetic.AT2", "--json"];
    args.extend(SMALL);
    let (ok, out, err) = rocking(&args);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let row = &v.as_array().unwrap()[0];
    for k in ["record", "t1", "t1_prime", "beta", "f_min"] {
        assert!(row.get(k).is_some(), "missing {k}: {row}");
    }
    let t1 = row["t1"].as_f64().unwrap();
    assert!(t1 > 0.05 && t1 < 2.0, "{t1}");
}

/// `rocking t1 --band`: the band's fields, t1 inside the range, the conservative t1 its upper
/// end; without `--band` the row has none of them (the default output is unchanged).
#[test]
fn t1_band_adds_the_range_and_the_conservative_t1() {
    let mut args = vec!["t1", "examples/records/synthetic.AT2", "--json", "--band"];
    args.extend(SMALL);
    let (ok, out, err) = rocking(&args);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let row = &v.as_array().unwrap()[0];
    let t1 = row["t1"].as_f64().unwrap();
    let range: Vec<f64> = row["t1_range"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(range[0] <= t1 && t1 <= range[1], "{row}");
    assert_eq!(row["t1_conservative"].as_f64(), Some(range[1]), "{row}");
    for k in [
        "nominal",
        "half-step",
        "levels-shifted",
        "sizes-shifted",
        "other-locator",
    ] {
        assert!(row["band"].get(k).is_some(), "missing {k}: {row}");
    }
    assert_eq!(row["band"]["nominal"].as_f64(), Some(t1));
    let mut plain = vec!["t1", "examples/records/synthetic.AT2", "--json"];
    plain.extend(SMALL);
    let (ok, out, err) = rocking(&plain);
    assert!(ok, "{err}");
    for k in ["t1_range", "t1_conservative", "band"] {
        assert!(!out.contains(k), "{k} without --band: {out}");
    }
}

/// `rocking t1 --converge-step`: the steps tried halve from the given factor, the row is the
/// last step's (its `dt_factor` and `t1`, equal to a plain run at that factor), and a bad
/// tolerance is an error that names the option.
#[test]
fn t1_converge_step_reports_the_steps_and_the_finest_row() {
    let mut args = vec![
        "t1",
        "examples/records/synthetic.AT2",
        "--json",
        "--dt-factor",
        "2",
        "--converge-step",
        "0.1",
    ];
    args.extend(SMALL);
    let (ok, out, err) = rocking(&args);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let row = &v.as_array().unwrap()[0];
    let steps = row["t1_steps"].as_array().unwrap();
    assert!(steps.len() >= 2, "{row}");
    for (k, s) in steps.iter().enumerate() {
        assert_eq!(s[0].as_f64(), Some(2.0 * 0.5f64.powi(k as i32)), "{row}");
    }
    let last = steps.last().unwrap();
    assert_eq!(row["dt_factor"].as_f64(), last[0].as_f64(), "{row}");
    assert_eq!(row["t1"].as_f64(), last[1].as_f64(), "{row}");
    assert!(row["step_converged"].is_boolean(), "{row}");
    let factor = format!("{}", last[0].as_f64().unwrap());
    let mut plain = vec![
        "t1",
        "examples/records/synthetic.AT2",
        "--json",
        "--dt-factor",
        &factor,
        "--single-step",
    ];
    plain.extend(SMALL);
    let (ok, out, err) = rocking(&plain);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v[0]["t1"], row["t1"]);
    assert!(!out.contains("t1_steps"), "{out}");
    let mut bad = vec![
        "t1",
        "examples/records/synthetic.AT2",
        "--converge-step=-0.1",
    ];
    bad.extend(SMALL);
    let (ok, _, err) = rocking(&bad);
    assert!(!ok && err.contains("step_tolerance"), "{err}");
}

/// `rocking t1` converges t₁ in the step by default (`--converge-step 0.1 --converge-halvings
/// 4`); `--single-step` is one OAS at the step rule, the first of the default's steps, and with
/// `--band` the band is taken at the row's (converged) step, its nominal the row's t₁.
#[test]
fn t1_converges_in_the_step_by_default() {
    let run = |extra: &[&str]| {
        let mut args = vec!["t1", "examples/records/synthetic.AT2", "--json"];
        args.extend(SMALL);
        args.extend(extra);
        let (ok, out, err) = rocking(&args);
        assert!(ok, "{err}");
        let mut v: serde_json::Value = serde_json::from_str(&out).unwrap();
        let row = v.as_array_mut().unwrap().remove(0);
        let mut row = row.as_object().unwrap().clone();
        row.remove("seconds");
        row
    };
    let default = run(&[]);
    let explicit = run(&["--converge-step", "0.1", "--converge-halvings", "4"]);
    assert_eq!(default, explicit);
    let steps = default["t1_steps"].as_array().unwrap();
    assert!(steps.len() >= 2, "{default:?}");
    assert_eq!(default["dt_factor"], steps.last().unwrap()[0]);
    let single = run(&["--single-step"]);
    assert!(single.get("t1_steps").is_none(), "{single:?}");
    assert!(single.get("step_converged").is_none(), "{single:?}");
    assert_eq!(single["dt_factor"].as_f64(), Some(1.0));
    assert_eq!(single["t1"], steps[0][1]);
    let band = run(&["--band"]);
    assert_eq!(band["t1"], default["t1"]);
    assert_eq!(band["t1_steps"], default["t1_steps"]);
    assert_eq!(band["band"]["nominal"], default["t1"]);
    let (ok, _, err) = rocking(&[
        "t1",
        "examples/records/synthetic.AT2",
        "--single-step",
        "--converge-step",
        "0.2",
    ]);
    assert!(!ok && err.contains("--single-step"), "{err}");
}

/// `rocking oas --converge-step 0.1 --band`: the spectrum is the finest step's (equal to `oas
/// --dt-factor` at that step), with the same band and steps as `rocking t1 --band`; a plain
/// `oas` has none of them, and the band refuses level shards.
#[test]
fn oas_band_and_converge_step_are_t1s() {
    let json = |args: &[&str]| {
        let mut all = vec![args[0], "examples/records/synthetic.AT2"];
        all.extend(&args[1..]);
        all.extend(SMALL);
        let (ok, out, err) = rocking(&all);
        assert!(ok, "{err}");
        serde_json::from_str::<serde_json::Value>(&out).unwrap()
    };
    let oas = json(&["oas", "--converge-step", "0.1", "--band"]);
    let t1 = json(&["t1", "--band", "--json"]);
    let row = &t1[0];
    for k in [
        "t1_range",
        "t1_conservative",
        "band",
        "t1_steps",
        "step_converged",
    ] {
        assert!(oas.get(k).is_some(), "missing {k}: {oas}");
        assert_eq!(oas[k], row[k], "{k}");
    }
    assert_eq!(oas["summary"]["t1"], row["t1"]);
    let factor = format!("{}", row["dt_factor"].as_f64().unwrap());
    let finest = json(&["oas", "--dt-factor", &factor]);
    assert_eq!(oas["levels"], finest["levels"]);
    // A suite of converged spectra: `rocking suite --merge` of such reports.
    let file = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("oas-converged.json");
    std::fs::write(&file, oas.to_string()).unwrap();
    let (ok, out, err) = rocking(&["suite", "--merge", file.to_str().unwrap(), "--json"]);
    assert!(ok, "{err}");
    let suite: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(suite["records"][0]["summary"]["t1"], row["t1"]);
    assert_eq!(suite["records"][0]["levels"], oas["levels"]);
    let plain = json(&["oas"]);
    for k in ["t1_range", "band", "t1_steps", "step_converged"] {
        assert!(plain.get(k).is_none(), "{k} in a plain oas");
    }
    let (ok, _, err) = rocking(&[
        "oas",
        "examples/records/synthetic.AT2",
        "--band",
        "--shard",
        "0/2",
    ]);
    assert!(!ok && err.contains("--shard"), "{err}");
}

#[test]
fn design_width_reproduces_the_pier_example() {
    // Thesis 5.3.4: a_g = 0.14 g, t_1 = 0.7 s, H = 12 m: B_a = 1.299 m, B_b = 2.122 m (Eq. 23
    // gives 1.29847 for case a, printed 1.299 after double rounding: see the design tests).
    let e = PIER_EXAMPLE;
    let pga = format!("{}", e.pga_g * e.gravity);
    let (height, t1) = (e.height.to_string(), e.t1.to_string());
    for (mass, printed) in [("uniform", e.uniform.eq23), ("top", e.top.eq23)] {
        let (ok, out, err) = rocking(&[
            "design", "width", "--height", &height, "--pga", &pga, "--t1", &t1, "--mass", mass,
            "--json",
        ]);
        assert!(ok, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert!(
            (v["width"].as_f64().unwrap() - printed.value).abs() < 1e-3,
            "{v}"
        );
    }
    let (ok, out, _) = rocking(&[
        "design", "check", "--width", "1.2", "--height", &height, "--pga", &pga, "--t1", &t1,
        "--json",
    ]);
    assert!(ok);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["safe"], false);
}

/// `rocking bench spectra --compare` on the bundled record: one row, the stop changes nothing
/// (the command fails otherwise), and the report says so.
#[test]
fn spectra_bench_compares_with_full_runs() {
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench_spectra.md");
    let _ = std::fs::remove_file(&out);
    let (ok, stdout, err) = rocking(&[
        "bench",
        "spectra",
        "--compare",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text, stdout);
    let row = text
        .lines()
        .find(|l| l.starts_with("| synthetic (bundled)"))
        .expect("a row for the bundled record");
    // The "same OAS" column, then the CPU times and their ratio.
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    assert_eq!(cells[8], "yes", "{row}");
    assert!(text.contains("| same OAS | CPU (s) | full runs CPU (s) | CPU ratio |"));
    assert!(text.contains("1 record(s): median"));
    assert!(text.contains("Speed-up of the energy-bound stop"));
}

/// `rocking bench spectra --dt-factor 2 --converge-step 0.1` on the bundled record: t₁ at both
/// steps and the cost ratio; t₁ at the default step is the one `rocking t1 --single-step` prints
/// (golden: 0.2276 s); the converged t₁, its step and its cost, as `rocking t1` computes them.
#[test]
fn spectra_bench_prices_a_scaled_and_a_converged_step() {
    let (ok, stdout, err) = rocking(&[
        "bench",
        "spectra",
        "--dt-factor",
        "2",
        "--converge-step",
        "0.1",
    ]);
    assert!(ok, "{err}");
    assert!(stdout.contains("Time step rule x 2:"), "{stdout}");
    let rows: Vec<Vec<&str>> = stdout
        .lines()
        .filter(|l| l.starts_with("| synthetic (bundled)"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    let scaled = &rows[1];
    assert_eq!(scaled[2], "0.2276", "{scaled:?}");
    let t1: f64 = scaled[3].parse().unwrap();
    assert!(t1 > 0.05 && t1 < 2.0, "{scaled:?}");
    let ratio: f64 = scaled[7].parse().unwrap();
    assert!(ratio > 0.0, "{scaled:?}");
    assert!(stdout.contains("t1 converged in the step"), "{stdout}");
    let converged = &rows[2];
    assert_eq!(converged[2], "0.2276", "{converged:?}");
    let (ok, out, err) = rocking(&["t1", "examples/records/synthetic.AT2", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        converged[3],
        format!("{:.4}", v[0]["t1"].as_f64().unwrap()),
        "{converged:?}"
    );
    assert_eq!(
        converged[4],
        format!("x{}", v[0]["dt_factor"]),
        "{converged:?}"
    );
    assert!(stdout.contains("CPU over the records"), "{stdout}");
}

/// An output without its wall-time lines (`"seconds": …`), which differ from run to run.
fn without_seconds(json: &str) -> String {
    json.lines()
        .filter(|l| !l.trim_start().starts_with("\"seconds\""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Runs `args` whole, then as `n` shards merged with `--merge`, and returns both outputs (wall
/// times removed).
fn whole_and_merged(command: &str, args: &[&str], n: usize, tag: &str) -> (String, String) {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("merge-{tag}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut whole_args = vec![command];
    whole_args.extend(args);
    let (ok, whole, err) = rocking(&whole_args);
    assert!(ok, "{err}");
    let mut files = Vec::new();
    for i in 0..n {
        let shard = format!("{i}/{n}");
        let mut a = whole_args.clone();
        a.extend(["--shard", shard.as_str()]);
        let (ok, out, err) = rocking(&a);
        assert!(ok, "{err}");
        let f = dir.join(format!("s{i}.json"));
        std::fs::write(&f, out).unwrap();
        files.push(f.to_string_lossy().into_owned());
    }
    let mut a = vec![command, "--json", "--merge"];
    a.extend(files.iter().map(String::as_str));
    let (ok, merged, err) = rocking(&a);
    assert!(ok, "{err}");
    let _ = std::fs::remove_dir_all(&dir);
    (without_seconds(&whole), without_seconds(&merged))
}

/// Sharded and merged, `rocking oas` prints the whole run's JSON byte for byte: every number
/// read back from the shards is the number written (no last-digit drift in the sizes, levels or
/// the fits recomputed from them).
#[test]
fn oas_shards_merge_bitwise_to_the_whole() {
    let mut args = vec!["examples/records/synthetic.AT2", "--json"];
    args.extend(["--levels", "16", "--sizes", "40"]);
    let (whole, merged) = whole_and_merged("oas", &args, 3, "oas");
    assert_eq!(whole, merged);
}

/// Sharded and merged, `rocking t1` prints the whole run's rows byte for byte (the records are
/// given in file-name order, the order `--merge` sorts by). With `../shared` (issue 10's case):
/// MUL009, MUL279 and LOS000, where LOS000's beta came back one ulp off.
#[test]
fn t1_shards_merge_bitwise_to_the_whole() {
    let far = "../shared/records/fema-p695/farfield";
    let shared = common::root().join(far).exists();
    let records: Vec<String> = if shared {
        [
            "RSN953_NORTHR_MUL009",
            "RSN953_NORTHR_MUL279",
            "RSN960_NORTHR_LOS000",
        ]
        .iter()
        .map(|n| format!("{far}/{n}.AT2"))
        .collect()
    } else {
        println!("../shared absent: the bundled record only");
        vec!["examples/records/synthetic.AT2".into(); 3]
    };
    // The step rule's rows (what issue 10 found; one OAS each), then converged rows with their
    // steps on a small grid.
    let mut args: Vec<&str> = records.iter().map(String::as_str).collect();
    args.extend(["--json", "--single-step"]);
    let (whole, merged) = whole_and_merged("t1", &args, 2, "t1");
    assert_eq!(whole, merged);
    let mut args = vec!["examples/records/synthetic.AT2"; 3];
    args.push("--json");
    args.extend(SMALL);
    let (whole, merged) = whole_and_merged("t1", &args, 2, "t1-converged");
    assert!(whole.contains("t1_steps"), "{whole}");
    assert_eq!(whole, merged);
}

/// `rocking oas --overlay`: two OAS of the bundled record for H/B = 5 and 12 on one chart, the
/// table of both and the slenderness check of the pair, whose count is that of the levels where
/// the H/B = 5 spectrum has the larger unsafe size (recounted here from the two reports).
#[test]
fn oas_overlay_compares_slenderness() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("overlay");
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = Vec::new();
    let mut reports = Vec::new();
    for s in ["5", "12"] {
        let mut args = vec!["oas", "examples/records/synthetic.AT2", "--slenderness", s];
        args.extend(SMALL);
        let (ok, out, err) = rocking(&args);
        assert!(ok, "{err}");
        let file = dir.join(format!("oas-{s}.json"));
        std::fs::write(&file, &out).unwrap();
        reports.push(serde_json::from_str::<serde_json::Value>(&out).unwrap());
        files.push(file.to_str().unwrap().to_string());
    }
    let prefix = dir.join("fig45");
    let mut args = vec!["oas", "--overlay"];
    args.extend(files.iter().map(String::as_str));
    args.extend(["--svg", prefix.to_str().unwrap()]);
    let (ok, out, err) = rocking(&args);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["spectra"].as_array().unwrap().len(), 2);
    let check = &v["slenderness_check"];
    assert_eq!(check["records"], 1);
    let pair = &check["pairs"][0];
    assert_eq!(
        (pair["lower"].as_f64(), pair["higher"].as_f64()),
        (Some(5.0), Some(12.0))
    );
    let index = |r: &serde_json::Value, k: usize| {
        r["levels"][k]["largest_unsafe"]
            .as_u64()
            .unwrap_or(u64::MAX)
    };
    let expected = (0..8)
        .filter(|&k| index(&reports[0], k) < index(&reports[1], k))
        .count();
    assert_eq!(pair["violations"].as_u64(), Some(expected as u64));
    assert_eq!(pair["levels_compared"], 8);
    let svg = std::fs::read_to_string(dir.join("fig45-overlay.svg")).unwrap();
    assert!(svg.contains("H/B = 5") && svg.contains("H/B = 12"));
}
