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
    // The arch spectra (their default grids take minutes).
    for args in [
        vec!["arch", "oas", record, "--svg", svg.as_str()],
        vec!["arch", "oc", "--svg", plot.as_str()],
    ] {
        let out = run_within(&args, Duration::from_secs(30))
            .unwrap_or_else(|| panic!("{args:?} computed instead of refusing"));
        assert_eq!(out.code, Some(1), "{args:?}: {}", out.stderr);
        assert!(out.stdout.is_empty(), "{args:?} printed {}", out.stdout);
        assert!(out.stderr.contains("--svg") && out.stderr.contains("not a folder"));
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

/// `rocking design`: the text report starts with the inputs as understood, the PGA also in g,
/// so that a PGA typed in g where m/s² is expected shows (`--pga 0.14` is 0.014 g: a 0.13 m
/// pier instead of 1.30 m, with nothing on screen to say so); `--pga 0.14g` takes the thesis's
/// "a_g = 0.14 g" as written and gives the same answer as 1.3734 m/s².
#[test]
fn design_reports_its_inputs_and_takes_a_pga_in_g() {
    let width = |pga: &str, json: bool| {
        let mut args = vec![
            "design", "width", "--height", "12", "--pga", pga, "--t1", "0.7",
        ];
        if json {
            args.push("--json");
        }
        let out = common::run(&args);
        assert!(out.ok, "{pga}: {}", out.stderr);
        out.stdout
    };
    let text = width("0.14", false);
    let first = text.lines().next().unwrap();
    assert!(first.contains("a_p = 0.1400 m/s² (0.014 g)"), "{text}");
    assert!(
        first.contains("H = 12 m") && first.contains("t_1 = 0.7 s"),
        "{text}"
    );
    let text = width("0.14g", false);
    assert!(text.contains("a_p = 1.3734 m/s² (0.140 g)"), "{text}");
    assert!(text.contains("required width B = 1.2985 m"), "{text}");
    // The same width as the PGA in m/s² (0.14 × 9.81 rounds to 1.3734 within an ulp).
    let json = |s: String| -> serde_json::Value { serde_json::from_str(&s).unwrap() };
    let (in_g, in_ms2) = (json(width("0.14g", true)), json(width("1.3734", true)));
    let w = |v: &serde_json::Value| v["width"].as_f64().unwrap();
    assert!((w(&in_g) - w(&in_ms2)).abs() < 1e-12, "{in_g} {in_ms2}");
    let check = common::run([
        "design", "check", "--width", "1.3", "--height", "12", "--pga", "0.14g", "--t1", "0.7",
    ]);
    assert!(check.ok, "{}", check.stderr);
    assert!(check
        .stdout
        .starts_with("pier B = 1.3 m, H = 12 m, uniform mass; a_p = 1.3734 m/s²"));
    for bad in ["0g", "-0.1g", "3gal"] {
        let out = common::run([
            "design", "width", "--height", "12", "--pga", bad, "--t1", "0.7",
        ]);
        assert_eq!(out.code, Some(2), "{bad}: {}", out.stderr);
        assert!(
            out.stderr.contains("--pga") && out.stderr.contains("in g"),
            "{}",
            out.stderr
        );
    }
}

/// `rocking suite --fractile 0.5,0.5`: refused before the spectra, naming the option. Every
/// curve, row and CSV line of that fractile came out twice.
#[test]
fn a_fractile_given_twice_is_refused_before_the_spectra() {
    let out = long_run(
        &["suite", "examples/records/synthetic.AT2"],
        &["--fractile", "0.5,0.84,0.5"],
    );
    assert_eq!(out.code, Some(1), "{}", out.stderr);
    assert!(out.stdout.is_empty(), "{}", out.stdout);
    assert!(
        out.stderr.contains("--fractile") && out.stderr.contains("0.5 is given twice"),
        "{}",
        out.stderr
    );
}

/// β of Eq. 28–30 is a time (s): the t₁ table's header and the OAS charts' legends gave its
/// value without the unit, beside t₁ [s] and t₁' [s].
#[test]
fn beta_is_given_with_its_unit() {
    let dir = fresh_dir("beta");
    let prefix = dir.join("syn");
    let out = common::run([
        "oas",
        "examples/records/synthetic.AT2",
        "--levels",
        "16",
        "--sizes",
        "40",
        "--threads",
        "1",
        "--svg",
        prefix.to_str().unwrap(),
    ]);
    assert!(out.ok, "{}", out.stderr);
    for chart in ["oas", "transformed", "size"] {
        let svg = std::fs::read_to_string(dir.join(format!("syn-{chart}.svg"))).unwrap();
        let legend: Vec<String> = svg_texts(&svg)
            .into_iter()
            .filter(|t| t.contains("beta"))
            .collect();
        assert!(!legend.is_empty(), "{chart}");
        for t in legend {
            assert!(t.ends_with(" s"), "{chart}: {t}");
        }
    }
    let out = common::run([
        "t1",
        "examples/records/synthetic.AT2",
        "--single-step",
        "--levels",
        "8",
        "--sizes",
        "24",
        "--threads",
        "1",
    ]);
    assert!(out.ok, "{}", out.stderr);
    let header = out.stdout.lines().next().unwrap();
    assert!(header.contains("beta [s]"), "{header}");
}

/// `rocking … | head`: a reader that closes the pipe early ends the program quietly with the
/// status of SIGPIPE (141), as any Unix filter; it panicked, "failed printing to stdout:
/// Broken pipe", with a backtrace on stderr.
#[test]
fn a_closed_pipe_ends_the_program_quietly() {
    // About 200 kB of JSON: more than a pipe holds, so the writer meets the closed end.
    let mut child = rocking()
        .args([
            "oc",
            "--ptp-n",
            "40",
            "--level-n",
            "40",
            "--threads",
            "1",
            "--json",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(141), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}

/// A report joined by the wrong command (`t1 --merge` of an OAS, `oas --merge` of a t₁ list or
/// of a simulation's summary): the error says which report was expected and which was given.
/// It was serde's "invalid type: map, expected a sequence at line 1 column 0".
#[test]
fn a_report_merged_by_the_wrong_command_is_named() {
    let dir = fresh_dir("merge");
    let run_json = |args: &[&str], name: &str| {
        let out = common::run(args);
        assert!(out.ok, "{args:?}: {}", out.stderr);
        let path = dir.join(name);
        std::fs::write(&path, out.stdout).unwrap();
        path.to_str().unwrap().to_string()
    };
    let record = "examples/records/synthetic.AT2";
    let grid = ["--levels", "4", "--sizes", "6", "--threads", "1"];
    let oas = run_json(&[&["oas", record][..], &grid].concat(), "oas.json");
    let t1 = run_json(
        &[&["t1", record, "--single-step", "--json"][..], &grid].concat(),
        "t1.json",
    );
    for (args, expected, given) in [
        (
            vec!["t1", "--merge", oas.as_str()],
            "`rocking t1 --json`",
            "an OAS report",
        ),
        (
            vec!["oas", "--merge", t1.as_str()],
            "an OAS report",
            "a list",
        ),
        (
            vec!["oas", "--overlay", t1.as_str()],
            "an OAS report",
            "a list",
        ),
        (
            vec![
                "t1",
                "--merge",
                "examples/scenes/single_block_half_sine.json",
            ],
            "`rocking t1 --json`",
            "a scene",
        ),
    ] {
        let out = common::run(&args);
        assert_eq!(out.code, Some(1), "{args:?}: {}", out.stderr);
        let e = &out.stderr;
        assert!(e.contains(expected) && e.contains(" expected, "), "{e}");
        assert!(e.contains(&format!("this is {given}")), "{e}");
    }
}

/// `rocking oc --help` said `--slenderness` was the "H/B of each block", but the column of
/// `--blocks n` is n blocks of the one monolith's H/B cut in n (a_p,min = g B/H of the whole
/// column): a 3-drum column of H/B-4 drums entered as told was a column of H/B 4, drums of 1.33.
#[test]
fn the_oc_slenderness_is_said_to_be_the_columns() {
    let help = common::run(["oc", "--help"]).stdout;
    let line = help
        .lines()
        .skip_while(|l| !l.contains("--slenderness"))
        .take(3)
        .collect::<Vec<_>>()
        .join(" ");
    assert!(!line.contains("of each block"), "{line}");
    assert!(line.contains("whole column"), "{line}");
    // What it does: the column's a_p,min is g / slenderness whatever the number of blocks.
    for blocks in ["1", "3"] {
        let out = common::run([
            "oc",
            "--blocks",
            blocks,
            "--slenderness",
            "12",
            "--ptp-n",
            "1",
            "--level-n",
            "1",
            "--json",
        ]);
        assert!(out.ok, "{}", out.stderr);
        let v: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
        assert!(
            (v["a_p_min"].as_f64().unwrap() - 9.81 / 12.0).abs() < 1e-12,
            "{v}"
        );
    }
}

/// `simulate --plot` of a column that rocks as one (thesis 4.3's three blocks): one line for
/// the blocks with the same rotation throughout, its legend saying which; three coincident
/// lines showed only the last while the legend listed blocks 0, 1 and 2. Blocks that part keep
/// their own lines (the stone column under the record: its joints open).
#[test]
fn blocks_rocking_as_one_are_one_line_in_the_plot() {
    let dir = fresh_dir("plot_as_one");
    for (scene, entries) in [
        ("three_block_sine_pulse", vec!["blocks 0, 1, 2 (as one)"]),
        (
            "column_synthetic_record",
            vec!["block 0", "block 1", "block 2"],
        ),
    ] {
        let svg = dir.join(format!("{scene}.svg"));
        let out = common::run([
            "simulate",
            &format!("examples/scenes/{scene}.json"),
            "--out",
            dir.join(scene).to_str().unwrap(),
            "--plot",
            svg.to_str().unwrap(),
        ]);
        assert!(out.ok, "{}", out.stderr);
        let texts = svg_texts(&std::fs::read_to_string(&svg).unwrap());
        let blocks: Vec<&str> = texts
            .iter()
            .map(String::as_str)
            .filter(|t| t.starts_with("block") && !t.starts_with("block rotation"))
            .collect();
        assert_eq!(blocks, entries, "{scene}");
    }
}

/// `rocking design`: Eq. 31 is a rocking check, and the report says what it takes, a friction
/// coefficient of at least tan δ, and warns for a squat pier (tan δ ≥ 1), which was called SAFE
/// (`--width 20 --height 12`: a_p,min = 16.35 m/s²) with nothing to say it would slide first.
#[test]
fn the_design_report_states_the_no_sliding_premise() {
    let check = |width: &str| {
        let out = common::run([
            "design", "check", "--width", width, "--height", "12", "--pga", "1.37", "--t1", "0.7",
        ]);
        assert!(out.ok, "{}", out.stderr);
        out.stdout
    };
    let slender = check("1.3");
    assert!(slender.contains("friction μ ≥ tan δ = 0.108"), "{slender}");
    assert!(!slender.contains("squat"), "{slender}");
    let squat = check("20");
    assert!(squat.contains("friction μ ≥ tan δ = 1.667"), "{squat}");
    assert!(
        squat.contains("squat") && squat.contains("check sliding"),
        "{squat}"
    );
    let width = common::run([
        "design", "width", "--height", "12", "--pga", "0.14g", "--t1", "0.7", "--mass", "top",
    ]);
    // Mass at the top: tan δ = (B/2) / H for the required B = 2.1224 m.
    assert!(width.stdout.contains("tan δ = 0.088"), "{}", width.stdout);
}

/// A suite with a record that overturns no size on the grid (a weak record, a coarse grid): the
/// text says so beside the records' t₁ range, and the fractile of the records' t₁ counts it as
/// the lowest (here the 0.5 fractile falls on it: none, as the 0.5 design t₁). The range was
/// the other records' without a word, and the 0.5 fractile was the other record's t₁.
#[test]
fn a_record_that_overturns_nothing_is_counted_in_the_suite() {
    let dir = fresh_dir("weak");
    let weak = dir.join("weak.txt");
    std::fs::write(&weak, "0 0\n0.01 1\n0.02 -1\n0.03 0\n").unwrap();
    let out = common::run([
        "suite",
        weak.to_str().unwrap(),
        "examples/records/synthetic.AT2",
        "--levels",
        "4",
        "--sizes",
        "6",
        "--threads",
        "1",
    ]);
    assert!(out.ok, "{}", out.stderr);
    let mut lines = out.stdout.lines();
    let head = lines.next().unwrap();
    assert!(
        head.contains("2 records") && head.contains("1 record overturns no size"),
        "{head}"
    );
    let median = lines.find(|l| l.starts_with("0.5 ")).unwrap();
    let cells: Vec<&str> = median.split_whitespace().collect();
    assert_eq!(cells[1], "-", "{median}"); // design t1
    assert_eq!(cells.last(), Some(&"-"), "{median}"); // fractile of the records' t1
}
