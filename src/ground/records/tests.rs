use super::at2::fortran_e;
use super::*;
use crate::model::column::GRAVITY;

const SAMPLE: &str = "PEER NGA STRONG MOTION DATABASE RECORD
Test 1999, STATION, 000
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=     7, DT=   .0100 SEC
  1.0000000E-01  -2.0000000E-01  3.0000000E-01  0.0000000E+00  -5.0000000E-02
  2.5000000E-02   0.0
";

/// The tail impulse of the interpolated record against a fine midpoint quadrature of
/// `|a(t)|` (segments that cross zero included), at sample times and between them.
#[test]
fn impulse_after_is_the_integral_of_the_absolute_acceleration() {
    let r = Record {
        name: "r".into(),
        dt: 0.01,
        samples: vec![1.0, -2.0, 3.0, 0.0, -0.5, 0.25, 0.0],
    };
    let table = r.impulse_table();
    let quadrature = |t: f64| {
        let n = 200_000;
        let h = (r.duration() - t) / n as f64;
        (0..n)
            .map(|i| r.acceleration(t + (i as f64 + 0.5) * h).abs() * h)
            .sum::<f64>()
    };
    for t in [0.0, 0.003, 0.01, 0.0149, 0.027, 0.04, 0.0555] {
        let got = r.impulse_after(&table, t);
        assert!((got - quadrature(t)).abs() < 1e-8, "t = {t}: {got}");
    }
    assert_eq!(r.impulse_after(&table, -1.0), table[0]);
    assert_eq!(r.impulse_after(&table, 0.06), 0.0);
    assert_eq!(r.impulse_after(&table, 1.0), 0.0);
}

/// The argument an error names (out of range or inconsistent with the data).
fn field(e: RecordError) -> String {
    match e {
        RecordError::Invalid(v) => v.field,
        RecordError::InvalidArgument { field, .. } => field.to_string(),
        other => panic!("not an argument error: {other}"),
    }
}

fn parse_err(text: &str) -> RecordError {
    parse_at2(text, "t").expect_err("must fail")
}

fn with_line4(line4: &str, body: &str) -> String {
    format!("title\nevent\nACCELERATION TIME SERIES IN UNITS OF G\n{line4}\n{body}")
}

#[test]
fn parses_inline_at2() {
    let r = parse_at2(SAMPLE, "sample").unwrap();
    assert_eq!(r.name, "sample");
    assert_eq!(r.dt, 0.01);
    assert_eq!(r.samples.len(), 7);
    assert!((r.samples[2] - 0.3 * GRAVITY).abs() < 1e-12);
    assert!((r.pga() - 0.3 * GRAVITY).abs() < 1e-12);
    assert!((r.duration() - 0.06).abs() < 1e-12);
}

#[test]
fn header_variants() {
    for line4 in [
        "NPTS=  3, DT=   .0050 SEC",
        "NPTS= 3 DT= 0.005 SEC",
        "npts=3, dt=0.005 sec",
        "NPTS=3,DT=5.0E-03SEC",
        "NPTS: 3, DT: 0.005 SEC",
        "   3   .0050   NPTS, DT",
    ] {
        let r = parse_at2(&with_line4(line4, "0.1 0.2 0.3\n"), "v")
            .unwrap_or_else(|e| panic!("`{line4}`: {e}"));
        assert_eq!(r.samples.len(), 3, "{line4}");
        assert_eq!(r.dt, 0.005, "{line4}");
    }
}

#[test]
fn fortran_d_exponent_and_commas() {
    let r = parse_at2(&with_line4("NPTS=2, DT=0.01", "1.0D-01, -2.0d-01\n"), "d").unwrap();
    assert!((r.samples[1] + 0.2 * GRAVITY).abs() < 1e-12);
}

#[test]
fn error_empty() {
    assert!(matches!(parse_err(""), RecordError::Empty { .. }));
    assert!(matches!(parse_err("  \n\n"), RecordError::Empty { .. }));
}

#[test]
fn error_truncated_header() {
    let e = parse_err("title\nevent\n");
    assert!(matches!(e, RecordError::Parse { line: 3, .. }), "{e}");
    assert!(e.to_string().contains("truncated header"), "{e}");
}

#[test]
fn error_missing_npts_or_dt() {
    let e = parse_err(&with_line4("DT= 0.01 SEC", "0.1\n"));
    assert!(matches!(e, RecordError::Parse { line: 4, .. }), "{e}");
    assert!(e.to_string().contains("NPTS"), "{e}");
    let e = parse_err(&with_line4("NPTS= 1", "0.1\n"));
    assert!(matches!(e, RecordError::Parse { line: 4, .. }), "{e}");
    assert!(e.to_string().contains("DT"), "{e}");
    let e = parse_err(&with_line4("NPTS= -1, DT= 0.01", "0.1\n"));
    assert!(e.to_string().contains("NPTS"), "{e}");
}

#[test]
fn error_bad_dt() {
    for dt in ["0", "-0.01", "0.0000", "abc", "nan"] {
        let e = parse_err(&with_line4(&format!("NPTS= 1, DT= {dt} SEC"), "0.1\n"));
        assert!(matches!(e, RecordError::Parse { line: 4, .. }), "{dt}: {e}");
        assert!(e.to_string().contains("DT"), "{e}");
    }
}

#[test]
fn error_non_numeric_value_names_line() {
    let e = parse_err(&with_line4("NPTS= 4, DT= 0.01", "0.1 0.2\n0.3 x7\n"));
    assert_eq!(
        e,
        RecordError::Parse {
            record: "t".into(),
            line: 6,
            message: "`x7` is not a finite number".into()
        }
    );
    let e = parse_err(&with_line4("NPTS= 2, DT= 0.01", "0.1 NaN\n"));
    assert!(matches!(e, RecordError::Parse { line: 5, .. }), "{e}");
}

#[test]
fn error_count_mismatch_reports_both() {
    let e = parse_err(&with_line4("NPTS= 5, DT= 0.01", "0.1 0.2\n0.3\n"));
    assert_eq!(
        e,
        RecordError::CountMismatch {
            record: "t".into(),
            npts: 5,
            values: 3
        }
    );
    let msg = e.to_string();
    assert!(msg.contains('5') && msg.contains('3'), "{msg}");
    let e = parse_err(&with_line4("NPTS= 1, DT= 0.01", "0.1 0.2\n"));
    assert!(matches!(
        e,
        RecordError::CountMismatch {
            npts: 1,
            values: 2,
            ..
        }
    ));
}

#[test]
fn error_units() {
    let text = "t\ne\nVELOCITY TIME SERIES IN UNITS OF CM/S\nNPTS= 1, DT= 0.01\n0.1\n";
    assert!(matches!(
        parse_err(text),
        RecordError::Parse { line: 3, .. }
    ));
    let text = "t\ne\nACCELERATION TIME SERIES IN UNITS OF CM/S/S\nNPTS= 1, DT= 0.01\n0.1\n";
    assert!(matches!(
        parse_err(text),
        RecordError::Parse { line: 3, .. }
    ));
}

#[test]
fn read_errors_name_the_path() {
    let path = Path::new("/nonexistent/dir/x.AT2");
    let e = read_at2(path).unwrap_err();
    assert!(matches!(e, RecordError::Io { .. }));
    assert!(e.to_string().contains("/nonexistent/dir/x.AT2"), "{e}");
    assert!(read_record(path, &PlainFormat::default()).is_err());
}

#[test]
fn interpolation_and_zero_outside() {
    let r = Record::new("r", 0.5, vec![0.0, 2.0, -2.0]).unwrap();
    assert_eq!(r.acceleration(-1e-9), 0.0);
    assert_eq!(r.acceleration(0.0), 0.0);
    assert!((r.acceleration(0.25) - 1.0).abs() < 1e-15);
    assert_eq!(r.acceleration(0.5), 2.0);
    assert!((r.acceleration(0.75) - 0.0).abs() < 1e-15);
    assert_eq!(r.acceleration(1.0), -2.0);
    assert_eq!(r.acceleration(1.0 + 1e-9), 0.0);
    assert_eq!(r.acceleration(f64::NAN), 0.0);
    assert_eq!(r.acceleration(f64::INFINITY), 0.0);
    assert_eq!(r.duration(), 1.0);
    let empty = Record {
        name: "e".into(),
        dt: 0.1,
        samples: vec![],
    };
    assert_eq!(empty.acceleration(0.0), 0.0);
    assert_eq!(empty.pga(), 0.0);
}

#[test]
fn record_validation() {
    assert_eq!(field(Record::new("r", 0.0, vec![1.0]).unwrap_err()), "dt");
    let e = Record::new("r", 0.1, vec![1.0, f64::NAN]).unwrap_err();
    assert_eq!(field(e.clone()), "samples[1]");
    assert_eq!(e.to_string(), "samples[1] = NaN: must be a finite number");
}

#[test]
fn scaling_to_pga() {
    let r = parse_at2(SAMPLE, "sample").unwrap();
    let s = r.scaled_to_pga(1.5).unwrap();
    assert!((s.pga() - 1.5).abs() < 1e-12);
    assert!((s.samples[0] / r.samples[0] - 1.5 / r.pga()).abs() < 1e-12);
    assert_eq!(s.dt, r.dt);
    assert!((r.scaled(-2.0).pga() - 2.0 * r.pga()).abs() < 1e-12);
    assert_eq!(field(r.scaled_to_pga(0.0).unwrap_err()), "target");
    assert!(r.scaled_to_pga(f64::NAN).is_err());
    let zero = Record::new("z", 0.1, vec![0.0; 3]).unwrap();
    assert!(zero.scaled_to_pga(1.0).is_err());
}

#[test]
fn plain_one_column() {
    let text = "# accelerations in g\n0.1\n-0.2\n\n0.05\n";
    let r = parse_plain(text, "p", &PlainFormat::with_dt(0.02).in_g()).unwrap();
    assert_eq!(r.dt, 0.02);
    assert_eq!(r.samples.len(), 3);
    assert!((r.samples[1] + 0.2 * GRAVITY).abs() < 1e-12);
    let e = parse_plain(text, "p", &PlainFormat::default()).unwrap_err();
    assert_eq!(field(e), "dt");
    let e = parse_plain("0.1\nabc\n", "p", &PlainFormat::with_dt(0.1)).unwrap_err();
    assert!(matches!(e, RecordError::Parse { line: 2, .. }), "{e}");
    let e = parse_plain("0.1\n0.2 0.3\n", "p", &PlainFormat::with_dt(0.1)).unwrap_err();
    assert!(matches!(e, RecordError::Parse { line: 2, .. }), "{e}");
    let e = parse_plain("# only a comment\n", "p", &PlainFormat::with_dt(0.1)).unwrap_err();
    assert!(matches!(e, RecordError::Empty { .. }));
    let e = parse_plain("0.1\n", "p", &PlainFormat::with_dt(-1.0)).unwrap_err();
    assert_eq!(field(e), "dt");
    let zero = PlainFormat {
        dt: Some(0.1),
        scale: 0.0,
    };
    assert_eq!(
        field(parse_plain("0.1\n", "p", &zero).unwrap_err()),
        "scale"
    );
}

#[test]
fn plain_two_columns() {
    let text = "0.00, 0.0\n0.01, 1.0\n0.02, -1.0\n0.03, 0.5\n";
    let r = parse_plain(text, "p", &PlainFormat::default()).unwrap();
    assert!((r.dt - 0.01).abs() < 1e-15);
    assert_eq!(r.samples, vec![0.0, 1.0, -1.0, 0.5]);
    // Given dt must agree.
    assert!(parse_plain(text, "p", &PlainFormat::with_dt(0.01)).is_ok());
    let e = parse_plain(text, "p", &PlainFormat::with_dt(0.02)).unwrap_err();
    assert_eq!(field(e), "dt");
    // Uneven spacing: the line is reported.
    let e = parse_plain(
        "0 0\n0.01 1\n0.025 2\n0.03 3\n",
        "p",
        &PlainFormat::default(),
    )
    .unwrap_err();
    assert!(matches!(e, RecordError::Parse { line: 3, .. }), "{e}");
    // Starting at dt: a zero sample in front.
    let r = parse_plain("0.01 1\n0.02 2\n0.03 3\n", "p", &PlainFormat::default()).unwrap();
    assert_eq!(r.samples, vec![0.0, 1.0, 2.0, 3.0]);
    // Starting off the grid or before 0.
    assert!(parse_plain("0.005 1\n0.015 2\n", "p", &PlainFormat::default()).is_err());
    assert!(parse_plain("-0.01 1\n0.0 2\n", "p", &PlainFormat::default()).is_err());
    // Decreasing times.
    assert!(parse_plain("0.02 1\n0.01 2\n", "p", &PlainFormat::default()).is_err());
    // Three columns.
    let e = parse_plain("0 1 2\n", "p", &PlainFormat::default()).unwrap_err();
    assert!(matches!(e, RecordError::Parse { line: 1, .. }), "{e}");
}

#[test]
fn read_record_by_extension() {
    let dir = std::env::temp_dir().join(format!("rocking-records-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let at2 = dir.join("sample.at2");
    std::fs::write(&at2, SAMPLE).unwrap();
    let r = read_record(&at2, &PlainFormat::default()).unwrap();
    assert_eq!((r.name.as_str(), r.samples.len()), ("sample", 7));
    let txt = dir.join("plain.txt");
    std::fs::write(&txt, "0 1\n0.1 2\n").unwrap();
    let r = read_record(&txt, &PlainFormat::default()).unwrap();
    assert_eq!((r.name.as_str(), r.samples.len()), ("plain", 2));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A file saved with a UTF-8 byte-order mark (Windows editors, spreadsheets) read as one without:
/// the mark was part of the first number ("`\u{feff}0` is not a finite number", the mark
/// invisible in the message).
#[test]
fn a_byte_order_mark_is_not_part_of_the_first_value() {
    let dir = std::env::temp_dir().join(format!("rocking-records-bom-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in [("plain.txt", "0 1\n0.1 2\n"), ("sample.AT2", SAMPLE)] {
        let (with, without) = (dir.join(format!("bom-{name}")), dir.join(name));
        std::fs::write(&with, format!("\u{feff}{text}")).unwrap();
        std::fs::write(&without, text).unwrap();
        let a = read_record(&with, &PlainFormat::default()).unwrap();
        let b = read_record(&without, &PlainFormat::default()).unwrap();
        assert_eq!((a.dt, &a.samples), (b.dt, &b.samples), "{name}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A spreadsheet's CSV starts with a line of column names: the error says so, and that the
/// units are not read from it ("`time` is not a finite number" left the user to guess). A word
/// after the first data line is still a bad value.
#[test]
fn a_line_of_column_names_is_named_as_such() {
    let format = PlainFormat::default();
    for text in [
        "time,acc\n0,1\n0.01,2\n",
        "# from the table\nt [s]; a [g]\n0;1\n",
    ] {
        let e = parse_plain(text, "site", &format).unwrap_err().to_string();
        assert!(e.contains("column names"), "{e}");
        assert!(e.contains("start it with #") && e.contains("m/s²"), "{e}");
    }
    let e = parse_plain("0 1\n0.01 x\n", "site", &format)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 2") && e.contains("`x` is not a finite number"),
        "{e}"
    );
    assert!(!e.contains("column names"), "{e}");
    // Commented out, the same file reads.
    let r = parse_plain("# time,acc\n0,1\n0.01,2\n", "site", &format).unwrap();
    assert_eq!(r.samples, vec![1.0, 2.0]);
}

#[test]
fn fortran_format() {
    assert_eq!(fortran_e(-1.607847e-4), "-1.6078470E-04");
    assert_eq!(fortran_e(0.0), "0.0000000E+00");
    assert_eq!(fortran_e(12.5), "1.2500000E+01");
    assert_eq!(fortran_e(1e-100), "1.0000000E-100");
}

#[test]
fn write_then_parse_round_trips() {
    let r = Record::new("w", 0.0024, vec![0.1, -2.0, 0.0, 3.3e-5, 1.0, 0.7]).unwrap();
    let text = write_at2(&r, ["title", "two\nlines"]);
    assert_eq!(text.lines().count(), 4 + 2);
    let back = parse_at2(&text, "w").unwrap();
    assert_eq!(back.dt, r.dt);
    for (a, b) in r.samples.iter().zip(&back.samples) {
        assert!((a - b).abs() <= 1e-7 * a.abs().max(1e-12), "{a} {b}");
    }
    let odd = Record::new("o", 0.001234567891, vec![1.0]).unwrap();
    assert_eq!(
        parse_at2(&write_at2(&odd, ["", ""]), "o").unwrap().dt,
        odd.dt
    );
}

#[test]
fn synthetic_record_properties() {
    let r = synthetic_record(1, 20.0, 0.01, 0.3 * GRAVITY).unwrap();
    assert_eq!(r.samples.len(), 2001);
    assert!((r.pga() - 0.3 * GRAVITY).abs() < 1e-12);
    assert_eq!(r, synthetic_record(1, 20.0, 0.01, 0.3 * GRAVITY).unwrap());
    assert_ne!(
        r.samples,
        synthetic_record(2, 20.0, 0.01, 0.3 * GRAVITY)
            .unwrap()
            .samples
    );
    // Strong phase in the middle, quiet ends.
    let rms = |s: &[f64]| (s.iter().map(|a| a * a).sum::<f64>() / s.len() as f64).sqrt();
    assert!(rms(&r.samples[500..1000]) > 3.0 * rms(&r.samples[1900..]));
    assert!(synthetic_record(1, 0.0, 0.01, 1.0).is_err());
    assert!(synthetic_record(1, 1.0, f64::NAN, 1.0).is_err());
    assert!(synthetic_record(1, 1.0, 0.01, -1.0).is_err());
}

fn bundled_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/records/synthetic.AT2")
}

#[test]
fn bundled_record_is_what_the_generator_writes() {
    let text = std::fs::read_to_string(bundled_path()).unwrap();
    assert!(
        text == bundled_synthetic_at2().unwrap(),
        "examples/records/synthetic.AT2 differs from records::bundled_synthetic_at2(); \
             regenerate with `cargo test --lib -- --ignored regenerate_synthetic_record`"
    );
    assert!(text.len() < 60_000);
    let r = read_record(&bundled_path(), &PlainFormat::default()).unwrap();
    assert_eq!(r.samples.len(), 2001);
    assert_eq!(r.dt, SYNTHETIC_DT);
    assert!((r.pga() / GRAVITY - SYNTHETIC_PGA_G).abs() < 1e-7);
    assert!(text.lines().next().unwrap().contains("SYNTHETIC"));
}

/// Rewrites `examples/records/synthetic.AT2` (run with `--ignored`).
#[test]
#[ignore]
fn regenerate_synthetic_record() {
    let path = bundled_path();
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(&path, bundled_synthetic_at2().unwrap()).unwrap();
}

/// The 100 FEMA P695 records of the shared data directory (skipped when it is absent). Each
/// must parse and agree with `index.csv` (dt, npts, PGA to the printed 4 decimals).
#[test]
fn shared_fema_p695_records_parse() {
    // `../shared` beside the checkout (as on the developers' machines and in CI), or
    // $ROCKING_SHARED.
    let shared = std::env::var_os("ROCKING_SHARED")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared"));
    let root = shared.join("records/fema-p695");
    let root = root.as_path();
    let index = match std::fs::read_to_string(root.join("index.csv")) {
        Ok(text) => text,
        Err(_) => {
            println!("skipped: {} is absent", root.display());
            return;
        }
    };
    let mut parsed = 0;
    for (k, row) in index.lines().enumerate().skip(1) {
        let fields: Vec<&str> = row.split(',').collect();
        let n = fields.len();
        assert!(n >= 12, "index.csv line {}: {row}", k + 1);
        let (file, dt, npts, pga) = (fields[n - 4], fields[n - 3], fields[n - 2], fields[n - 1]);
        let r = read_record(&root.join(file), &PlainFormat::default())
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(r.dt, dt.parse::<f64>().unwrap(), "{file}");
        assert_eq!(r.samples.len(), npts.parse::<usize>().unwrap(), "{file}");
        let pga_g = r.pga() / GRAVITY;
        assert!(
            (pga_g - pga.parse::<f64>().unwrap()).abs() <= 0.5e-4 + 1e-9,
            "{file}: PGA {pga_g} g, index says {pga}"
        );
        parsed += 1;
    }
    assert_eq!(parsed, 100);
    println!("{parsed} FEMA P695 records parsed");
}
