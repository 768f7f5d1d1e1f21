//! The arguments of every command go through clap: `--help` prints the usage, bad values are
//! refused with the argument named (exit code 2), before any work is done.

use std::process::Command;

fn rocking(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rocking"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn every_command_has_help() {
    for (cmd, expect) in [
        (vec!["oc"], "--ptp-n"),
        (vec!["oas"], "--merge"),
        (vec!["t1"], "--shard"),
        (vec!["design", "width"], "--mass"),
        (vec!["design", "check"], "--exact-icr"),
        (vec!["simulate"], "--plot"),
        // A drum scene's second chart, written beside the first (the help did not say).
        (vec!["simulate"], "FILE_slips"),
        (vec!["bench", "accuracy"], "--peer"),
        (vec!["bench", "spectra"], "--compare"),
    ] {
        let mut args = cmd.clone();
        args.push("--help");
        let (code, out, err) = rocking(&args);
        assert_eq!(code, 0, "{cmd:?}: {err}");
        assert!(out.contains("Usage: rocking"), "{cmd:?}: {out}");
        assert!(out.contains(expect), "{cmd:?} --help lacks {expect}: {out}");
    }
}

#[test]
fn bad_values_are_refused_naming_the_argument() {
    for (args, named) in [
        (vec!["oc", "--blocks", "0"], "--blocks"),
        (vec!["oc", "--shape", "square"], "--shape"),
        (vec!["oc", "--slenderness=-3"], "--slenderness"),
        (vec!["oc", "--svg", "oc.pdf"], "--svg"),
        (vec!["oas", "x.AT2", "--shard", "2/2"], "--shard"),
        (vec!["oas", "x.AT2", "--dt-factor", "nan"], "--dt-factor"),
        (vec!["oas", "--png", "x.AT2"], "--svg"),
        (vec!["oas"], "<RECORD>"),
        (vec!["t1", "--levels", "many", "x.AT2"], "--levels"),
        (
            vec!["design", "width", "--height", "10", "--pga", "3"],
            "--t1",
        ),
        (
            vec![
                "design", "width", "--height", "10", "--pga", "3", "--t1", "0.2", "--mass", "x",
            ],
            "--mass",
        ),
        (
            vec!["simulate", "s.json", "--out", "d", "--plot", "p.jpg"],
            "--plot",
        ),
        // Counts that would start a million threads or allocate gigabytes of grid: refused
        // before any work (the process was killed, or aborted under a memory limit).
        (vec!["oas", "x.AT2", "--threads", "1000000"], "--threads"),
        (vec!["oas", "x.AT2", "--levels", "1000000000"], "--levels"),
        (vec!["t1", "x.AT2", "--sizes", "100001"], "--sizes"),
        (vec!["oc", "--ptp-n", "1000000"], "--ptp-n"),
        (
            vec!["arch", "oas", "x.AT2", "--radius-n", "1000000"],
            "--radius-n",
        ),
        (vec!["arch", "oc", "--level-n", "1000000"], "--level-n"),
        (vec!["bench", "drums", "--threads", "1025"], "--threads"),
        (vec!["bench", "spectra", "--threads", "0"], "--threads"),
    ] {
        let (code, out, err) = rocking(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?} printed {out}");
        assert!(err.starts_with("error:"), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
    }
}

/// A negative number given as a value (`--pga -1`, not only `--pga=-1`) reaches the option's
/// own check, which names the option and the rule; clap read it as an unknown flag and said
/// "unexpected argument '-1' found", naming neither the option nor what it must be.
#[test]
fn a_negative_value_is_refused_by_its_own_check() {
    for (args, named) in [
        (
            vec![
                "design", "width", "--height", "12", "--pga", "-1", "--t1", "0.7",
            ],
            "--pga",
        ),
        (
            vec![
                "design", "check", "--width", "-1.3", "--height", "12", "--pga", "1", "--t1", "0.7",
            ],
            "--width",
        ),
        (vec!["oc", "--size", "-6.02"], "--size"),
        (vec!["oc", "--slenderness", "-3"], "--slenderness"),
        (vec!["oas", "x.AT2", "--levels", "-3"], "--levels"),
        (vec!["oas", "x.AT2", "--size-min", "-0.1"], "--size-min"),
        (vec!["t1", "x.AT2", "--record-dt", "-0.01"], "--record-dt"),
        (vec!["suite", "x.AT2", "--level-max", "-10"], "--level-max"),
    ] {
        let (code, out, err) = rocking(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?} printed {out}");
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
        assert!(err.contains(named), "{args:?}: {err}");
        assert!(err.contains("got -"), "{args:?}: {err}");
    }
}

/// A failure after the arguments were accepted (here a missing record) exits 1 and says which
/// file.
#[test]
fn run_time_errors_name_the_file() {
    let (code, out, err) = rocking(&["oas", "no-such-record.AT2"]);
    assert_eq!(code, 1);
    assert!(out.is_empty());
    assert!(err.contains("no-such-record.AT2"), "{err}");
}

/// A JSON report given where a record is expected (e.g. `rocking suite a.json` for `--merge`):
/// the parse error says what a record is and where reports go.
#[test]
fn a_report_given_as_a_record_is_named_as_such() {
    let dir = std::env::temp_dir().join(format!("rocking-args-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let report = dir.join("synthetic.json");
    std::fs::write(&report, "{\"record\": \"synthetic\"}\n").unwrap();
    let path = report.to_str().unwrap();
    for cmd in ["suite", "oas", "tp"] {
        let (code, out, err) = rocking(&[cmd, path]);
        assert_eq!(code, 1, "{cmd}: {err}");
        assert!(out.is_empty(), "{cmd}: {out}");
        assert!(
            err.contains("synthetic, line 1") && err.contains("not JSON reports"),
            "{cmd}: {err}"
        );
    }
    let plain = dir.join("synthetic.txt");
    std::fs::write(&plain, "{\n").unwrap();
    let (_, _, err) = rocking(&["oas", plain.to_str().unwrap()]);
    assert!(!err.contains("JSON"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An arch's `--embrace` is judged in the degrees given and `--thickness-ratio` as t/R, both
/// named (they reached the arch's own checks: `arch.embrace_angle = 6.283185307179586: must be
/// less than 2π`, `arch.thickness = 2.5`).
#[test]
fn an_arch_family_out_of_range_is_named_in_its_own_units() {
    for (command, arg, value) in [
        ("oc", "--embrace", "360"),
        ("oc", "--embrace", "400"),
        ("oc", "--thickness-ratio", "2.5"),
        ("oas", "--embrace", "360"),
    ] {
        let mut args = vec!["arch", command, arg, value, "--voussoirs", "4"];
        if command == "oas" {
            args.push("examples/records/synthetic.AT2");
        }
        let (code, _, err) = rocking(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(arg) && err.contains(value), "{args:?}: {err}");
        assert!(
            !err.contains("2π") && !err.contains("arch.thickness"),
            "{err}"
        );
    }
}

/// A reversed range of an OC's or an arch OAS's grid is refused, both arguments named (it ran on
/// a reversed grid: `oc --ptp-min 5 --ptp-max 1`, levels 1 … 0.5 with `--level-max 0.5`).
#[test]
fn a_reversed_grid_range_is_refused_naming_both_ends() {
    for (args, words) in [
        (
            vec![
                "oc",
                "--ptp-min",
                "5",
                "--ptp-max",
                "1",
                "--ptp-n",
                "2",
                "--level-n",
                "2",
            ],
            ["--ptp-min (5)", "--ptp-max (1)"],
        ),
        (
            vec!["oc", "--level-max", "0.5", "--ptp-n", "2", "--level-n", "2"],
            ["--level-max (0.5)", "above 1"],
        ),
        (
            vec![
                "arch",
                "oc",
                "--ptp-min",
                "5",
                "--ptp-max",
                "1",
                "--voussoirs",
                "4",
            ],
            ["--ptp-min (5)", "--ptp-max (1)"],
        ),
        (
            vec!["arch", "oc", "--level-max", "1", "--voussoirs", "4"],
            ["--level-max (1)", "above 1"],
        ),
        (
            vec![
                "oas",
                "examples/records/synthetic.AT2",
                "--size-min",
                "10",
                "--size-max",
                "1",
                "--levels",
                "2",
                "--sizes",
                "2",
            ],
            ["--size-min (10)", "--size-max (1)"],
        ),
        (
            vec![
                "t1",
                "examples/records/synthetic.AT2",
                "--level-max",
                "0.5",
                "--single-step",
            ],
            ["--level-max (0.5)", "above 1"],
        ),
        (
            vec![
                "arch",
                "oas",
                "examples/records/synthetic.AT2",
                "--level-min",
                "5",
                "--level-max",
                "2",
                "--voussoirs",
                "4",
            ],
            ["--level-min (5)", "--level-max (2)"],
        ),
    ] {
        let (code, out, err) = rocking(&args);
        assert_ne!(code, 0, "{args:?} accepted: {out}");
        assert!(words.iter().all(|w| err.contains(w)), "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?} ran: {out}");
    }
}

/// A plain-text record in other units or of one column is read with `--units` and `--record-dt`
/// by every command that takes records (`oas`, `t1`, `suite`, `tp`, `arch oas`): the bundled
/// `.AT2` written as one column of g gives the same record; an `.AT2` refuses both options (it
/// states its units and step), and a one-column file without a step names `--record-dt`.
#[test]
fn a_plain_text_record_takes_its_units_and_step() {
    let root = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let at2 = std::fs::read_to_string(root.join("examples/records/synthetic.AT2")).unwrap();
    let values: Vec<&str> = at2
        .lines()
        .skip(4)
        .flat_map(str::split_whitespace)
        .collect();
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("record_format");
    std::fs::create_dir_all(&dir).unwrap();
    let text = dir.join("synthetic.txt");
    std::fs::write(&text, values.join("\n")).unwrap();
    let text = text.to_str().unwrap();
    let row = |out: &str| {
        out.lines()
            .nth(1)
            .unwrap_or("")
            .split_whitespace()
            .skip(1)
            .collect::<Vec<_>>()
            .join(" ")
    };
    let (code, at2_out, err) = rocking(&["tp", "examples/records/synthetic.AT2"]);
    assert_eq!(code, 0, "{err}");
    let (code, text_out, err) = rocking(&["tp", text, "--units", "g", "--record-dt", "0.01"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(row(&text_out), row(&at2_out));
    let (code, gal_out, _) = rocking(&["tp", text, "--units", "cm/s2", "--record-dt", "0.01"]);
    assert_eq!(code, 0);
    assert_ne!(row(&gal_out), row(&at2_out));
    for (args, words) in [
        (vec!["tp", text], "--record-dt"),
        (
            vec!["tp", "examples/records/synthetic.AT2", "--units", "m/s2"],
            "--units",
        ),
        (
            vec![
                "tp",
                "examples/records/synthetic.AT2",
                "--record-dt",
                "0.01",
            ],
            "--record-dt",
        ),
        (
            vec!["oas", "examples/records/synthetic.AT2", "--units", "cm/s2"],
            "--units",
        ),
        (
            vec![
                "t1",
                "examples/records/synthetic.AT2",
                "--record-dt",
                "0.02",
            ],
            "--record-dt",
        ),
        (
            vec!["suite", "examples/records/synthetic.AT2", "--units", "m/s2"],
            "--units",
        ),
        (
            vec![
                "arch",
                "oas",
                "examples/records/synthetic.AT2",
                "--units",
                "m/s2",
            ],
            "--units",
        ),
        (vec!["tp", text, "--record-dt", "0"], "--record-dt"),
        (vec!["tp", text, "--units", "furlongs"], "--units"),
    ] {
        let (code, _, err) = rocking(&args);
        assert_ne!(code, 0, "{args:?} ran");
        assert!(err.contains(words), "{args:?}: {err}");
    }
}
