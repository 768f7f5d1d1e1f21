//! `rocking tp` (Eq. 25), t_p beside t₁ in `rocking t1` (Fig. 53) and `rocking t1 --procedure`.

mod common;

use std::f64::consts::FRAC_2_PI;
use std::path::PathBuf;

use serde_json::Value;

const SMALL: [&str; 4] = ["--levels", "8", "--sizes", "24"];

fn json(args: &[&str]) -> Value {
    let out = common::run(args);
    assert!(out.ok, "{}", out.stderr);
    serde_json::from_str(&out.stdout).unwrap()
}

#[test]
fn tp_json_has_the_documented_fields() {
    let v = json(&["tp", "examples/records/synthetic.AT2", "--json"]);
    let row = &v.as_array().unwrap()[0];
    assert_eq!(row["record"], "synthetic");
    let (a_max, i_max, t_p) = (
        row["a_max"].as_f64().unwrap(),
        row["i_max"].as_f64().unwrap(),
        row["t_p"].as_f64().unwrap(),
    );
    assert!(
        (t_p - i_max / (FRAC_2_PI * a_max)).abs() < 1e-12 * t_p,
        "{row}"
    );
    let lobe = row["lobe_end"].as_f64().unwrap() - row["lobe_start"].as_f64().unwrap();
    // The largest lobe's impulse is at most a_max times its duration.
    assert!(lobe > 0.0 && i_max <= a_max * lobe, "{row}");
}

#[test]
fn tp_names_a_missing_record() {
    let out = common::run(["tp", "no/such/record.AT2"]);
    assert!(!out.ok);
    assert!(out.stderr.contains("no/such/record.AT2"), "{}", out.stderr);
}

/// `t1 --json` carries the record's t_p (the same as `tp`'s), `--procedure` is named in the row
/// when it is not the default, and `--merge` fills t_p into rows written without it.
#[test]
fn t1_rows_carry_t_p_and_the_procedure() {
    let tp = json(&["tp", "examples/records/synthetic.AT2", "--json"])[0]["t_p"].clone();
    let mut args = vec!["t1", "examples/records/synthetic.AT2", "--json"];
    args.extend(SMALL);
    let v = json(&args);
    assert_eq!(v[0]["t_p"], tp);
    assert!(v[0].get("procedure").is_none(), "{}", v[0]);

    args.extend(["--procedure", "record-end"]);
    let w = json(&args);
    assert_eq!(w[0]["procedure"], "record-end");

    let dir = std::env::temp_dir().join(format!("rocking-tp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut old = v.clone();
    old[0].as_object_mut().unwrap().remove("t_p");
    let shard = dir.join("old.json");
    std::fs::write(&shard, old.to_string()).unwrap();
    let merged = json(&["t1", "--merge", shard.to_str().unwrap(), "--json"]);
    assert_eq!(merged[0]["t_p"], tp);
    std::fs::remove_dir_all(&dir).ok();
}

/// `t1 --svg PREFIX` draws t₁ against t_p and the text output states the correlation.
#[test]
fn t1_draws_fig_53() {
    let dir = std::env::temp_dir().join(format!("rocking-fig53-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let prefix = dir.join("ff");
    let mut args = vec![
        "t1".to_string(),
        "examples/records/synthetic.AT2".into(),
        "--svg".into(),
        prefix.display().to_string(),
    ];
    args.extend(SMALL.map(String::from));
    let out = common::run(&args);
    assert!(out.ok, "{}", out.stderr);
    let svg = std::fs::read_to_string(dir.join("ff-tp.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("t_p"), "{svg}");
    // One record: no correlation to state.
    assert!(!out.stdout.contains("Pearson"), "{}", out.stdout);
    std::fs::remove_dir_all(&dir).ok();
}

fn shared() -> Option<PathBuf> {
    let dir = std::env::var_os("ROCKING_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| common::root().join("../shared"));
    dir.join("records/fema-p695/farfield")
        .exists()
        .then_some(dir)
}

/// The t_p column of thesis Table 4, parsed from the thesis text: FF id → t_p.
fn table_4(shared: &std::path::Path) -> Vec<(String, f64)> {
    let text = std::fs::read_to_string(shared.join("seed/thesis-rocking-mechanisms.txt")).unwrap();
    text.lines()
        .filter_map(|l| {
            let p: Vec<&str> = l.split('\t').collect();
            (p.len() >= 9 && p[0].starts_with("FF-"))
                .then(|| Some((p[0].to_string(), p[5].parse().ok()?)))
                .flatten()
        })
        .collect()
}

/// Table 4's t_p, one to one: 43 of the 44 far-field records to the printed three digits (FF-24
/// computes to 0.29945 against the printed 0.300), every one within 0.001 s.
#[test]
fn tp_reproduces_table_4() {
    let Some(shared) = shared() else {
        println!("skipped: ../shared/records not found");
        return;
    };
    let index = std::fs::read_to_string(shared.join("records/fema-p695/index.csv")).unwrap();
    let mut files = Vec::new();
    let mut ids = Vec::new();
    for line in index.lines().skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        if c[0] == "farfield" {
            // Station names may hold quoted commas: the file is the field naming an .AT2.
            let file = c.iter().find(|f| f.ends_with(".AT2")).unwrap();
            ids.push(c[2].to_string());
            files.push(
                shared
                    .join("records/fema-p695")
                    .join(file)
                    .display()
                    .to_string(),
            );
        }
    }
    let mut args = vec!["tp".to_string(), "--json".into()];
    args.extend(files);
    let out = common::run(&args);
    assert!(out.ok, "{}", out.stderr);
    let rows: Value = serde_json::from_str(&out.stdout).unwrap();
    let table = table_4(&shared);
    assert_eq!(table.len(), 44);
    let mut exact = 0;
    for (id, row) in ids.iter().zip(rows.as_array().unwrap()) {
        let printed = table.iter().find(|(k, _)| k == id).unwrap().1;
        let ours = row["t_p"].as_f64().unwrap();
        assert!(
            (ours - printed).abs() <= 0.001,
            "{id}: {ours} against {printed}"
        );
        exact += usize::from(((ours * 1000.0).round() - printed * 1000.0).abs() < 0.5);
    }
    assert_eq!(exact, 43);
}

/// `--explain` on merged rows reruns only the governing point: the same answer as `--explain`
/// while computing, and an error naming the file when the options differ from the rows'.
#[test]
fn explain_on_merged_rows_matches_the_computed_one() {
    let mut args = vec![
        "t1",
        "examples/records/synthetic.AT2",
        "--json",
        "--explain",
    ];
    args.extend(SMALL);
    let computed = json(&args);
    let g = &computed[0]["governing"];
    assert!(
        g["end"].as_f64().unwrap() > g["start"].as_f64().unwrap(),
        "{g}"
    );
    let dir = std::env::temp_dir().join(format!("rocking-explain-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut plain = computed.clone();
    plain[0].as_object_mut().unwrap().remove("governing");
    let shard = dir.join("rows.json");
    std::fs::write(&shard, plain.to_string()).unwrap();
    let shard = shard.to_str().unwrap();
    let mut merge = vec!["t1", "--merge", shard, "--json", "--explain"];
    merge.extend(SMALL);
    assert_eq!(json(&merge)[0]["governing"], *g);
    merge.extend(["--dt-factor", "0.5"]);
    let out = common::run(&merge);
    assert!(
        !out.ok && out.stderr.contains("synthetic.AT2"),
        "{}",
        out.stderr
    );
    std::fs::remove_dir_all(&dir).ok();
}
