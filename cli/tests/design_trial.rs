//! A structural engineer's trial of the column design workflow (`simulate`, `oc`, `oas`, `t1`,
//! `suite`, `design`): inputs that must be refused before a long computation, not after it.

mod common;

use std::path::PathBuf;
use std::process::Stdio;
use std::time::{Duration, Instant};

use common::{rocking, Run};

fn fresh_dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("design_trial")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `rocking args…` and waits at most `limit`; `None` when it was still running then (it is
/// killed): the refusal did not come before the work.
fn run_within(args: &[&str], limit: Duration) -> Option<Run> {
    let mut child = rocking()
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the rocking binary");
    let start = Instant::now();
    while start.elapsed() < limit {
        if child.try_wait().unwrap().is_some() {
            let out = child.wait_with_output().unwrap();
            return Some(Run {
                ok: out.status.success(),
                code: out.status.code(),
                stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
                stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
            });
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

/// A grid whose spectra take many minutes on one thread: a refusal that waits for them times out.
const LONG_GRID: [&str; 7] = [
    "--levels",
    "2000",
    "--sizes",
    "2000",
    "--threads",
    "1",
    "--full-runs",
];

fn long_run(head: &[&str], tail: &[&str]) -> Run {
    let mut args: Vec<&str> = head.to_vec();
    args.extend(LONG_GRID);
    args.extend(tail);
    run_within(&args, Duration::from_secs(30))
        .unwrap_or_else(|| panic!("{args:?} was still computing after 30 s instead of refusing"))
}

/// A suite or t₁ run over many records read each record just before its spectrum: a missing or
/// all-zero file (or a duplicate, for a suite) late in the list was refused only after the
/// spectra of every record before it, an hour into a 44-record suite.
#[test]
fn every_record_is_read_before_the_first_spectrum() {
    let dir = fresh_dir("records");
    let zero = dir.join("zero.txt");
    std::fs::write(&zero, "0\n0\n0\n0\n").unwrap();
    let zero = zero.to_str().unwrap();
    let synthetic = "examples/records/synthetic.AT2";
    for (command, extra, named) in [
        ("suite", vec!["no-such-record.AT2"], "no-such-record.AT2"),
        ("t1", vec!["no-such-record.AT2"], "no-such-record.AT2"),
        ("suite", vec![synthetic], "already in the suite"),
    ] {
        let mut head = vec![command, synthetic];
        head.extend(extra);
        let out = long_run(&head, &[]);
        assert_eq!(out.code, Some(1), "{head:?}: {}", out.stderr);
        assert!(out.stdout.is_empty(), "{head:?} printed {}", out.stdout);
        assert!(out.stderr.contains(named), "{head:?}: {}", out.stderr);
    }
    // A plain-text record that is zero everywhere has no peak to scale to the levels.
    let mut grid_only: Vec<&str> = vec!["t1", zero, "--record-dt", "0.01"];
    grid_only.extend(LONG_GRID);
    let out = run_within(&grid_only, Duration::from_secs(30)).expect("refused at once");
    assert_eq!(out.code, Some(1), "{}", out.stderr);
    assert!(out.stderr.contains("zero everywhere"), "{}", out.stderr);
}

/// The output files of a long run (`--svg`, `--csv`, `--out`, `--plot`) under a path through an
/// existing file: refused before the work, naming the option and the file in the way. The OAS
/// was computed and printed first, and the error said only "cannot create …: File exists".
#[test]
fn an_output_path_through_a_file_is_refused_before_the_work() {
    let dir = fresh_dir("outputs");
    let file = dir.join("a-file");
    std::fs::write(&file, "not a folder").unwrap();
    let under = |name: &str| file.join(name).to_str().unwrap().to_string();
    let record = "examples/records/synthetic.AT2";
    let (svg, csv) = (under("spectra"), under("tables"));
    for (head, tail, flag) in [
        (vec!["oas", record], vec!["--svg", svg.as_str()], "--svg"),
        (vec!["t1", record], vec!["--svg", svg.as_str()], "--svg"),
        (vec!["suite", record], vec!["--svg", svg.as_str()], "--svg"),
        (vec!["suite", record], vec!["--csv", csv.as_str()], "--csv"),
    ] {
        let out = long_run(&head, &tail);
        assert_eq!(out.code, Some(1), "{head:?} {tail:?}: {}", out.stderr);
        assert!(out.stdout.is_empty(), "{head:?} printed {}", out.stdout);
        assert!(out.stderr.contains(flag), "{head:?}: {}", out.stderr);
        assert!(
            out.stderr.contains("a-file is a file, not a folder"),
            "{head:?}: {}",
            out.stderr
        );
    }
    let scene = "examples/scenes/single_block_half_sine.json";
    let plot = under("plot.svg");
    let out_dir = dir.join("run");
    for (args, flag) in [
        (
            vec!["simulate", scene, "--out", file.to_str().unwrap()],
            "--out",
        ),
        (
            vec![
                "simulate",
                scene,
                "--out",
                out_dir.to_str().unwrap(),
                "--plot",
                plot.as_str(),
            ],
            "--plot",
        ),
    ] {
        let out = common::run(&args);
        assert_eq!(out.code, Some(1), "{args:?}: {}", out.stderr);
        assert!(out.stderr.contains(flag), "{args:?}: {}", out.stderr);
        assert!(
            out.stderr.contains("is a file, not a folder"),
            "{}",
            out.stderr
        );
        // Nothing of the run was written.
        assert!(!out_dir.join("summary.json").exists());
    }
    let out = common::run([
        "oc",
        "--ptp-n",
        "2",
        "--level-n",
        "2",
        "--svg",
        &under("oc.svg"),
    ]);
    assert_eq!(out.code, Some(1), "{}", out.stderr);
    assert!(out.stdout.is_empty(), "oc printed {}", out.stdout);
    assert!(out.stderr.contains("--svg") && out.stderr.contains("not a folder"));
}

/// The text of every `<text>` element of an SVG chart (titles, labels, ticks, legend).
fn svg_texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..];
            Some(body[..body.find("</text>")?].trim().to_string())
        })
        .collect()
}

/// `rocking oc --svg`: the p t_p axis spans the grid that was computed. It was fitted to the
/// points that overturn, so a grid from p t_p = 0.1 whose shortest pulses overturn nothing was
/// drawn from 0.2, as if it began there.
#[test]
fn the_oc_chart_spans_the_whole_grid() {
    let dir = fresh_dir("oc_chart");
    let svg = dir.join("oc.svg");
    let out = common::run([
        "oc",
        "--size",
        "6.02",
        "--ptp-min",
        "0.1",
        "--ptp-max",
        "10",
        "--ptp-n",
        "12",
        "--level-n",
        "12",
        "--threads",
        "1",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert!(out.ok, "{}", out.stderr);
    // The first pulse duration (p t_p = 0.1) overturns nothing at any level.
    let first: Vec<&str> = out
        .stdout
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(4).and_then(|x| x.parse::<f64>().ok()) < Some(0.11))
        .collect();
    assert!(!first.is_empty() && first.iter().all(|l| l.ends_with(",0")));
    let texts = svg_texts(&std::fs::read_to_string(&svg).unwrap());
    assert!(texts.iter().any(|t| t == "0.1"), "{texts:?}");
    assert!(texts.iter().any(|t| t == "10"), "{texts:?}");
}
