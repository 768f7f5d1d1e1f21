//! `rocking bench accuracy --quick`: the report has its sections, and Wilson θ's errors fall
//! with the time step on every scene.

mod common;

use std::path::PathBuf;

#[test]
fn quick_accuracy_bench_writes_a_converging_report() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("bench_accuracy");
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.join("accuracy.md");
    let plot = dir.join("accuracy.svg");
    let run = common::run([
        "bench".as_ref(),
        "accuracy".as_ref(),
        "--quick".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
        "--plot".as_ref(),
        plot.as_os_str(),
    ]);
    assert!(run.ok, "{}", run.stderr);
    let text = std::fs::read_to_string(&out).unwrap();
    for section in [
        "# Accuracy",
        "## Scenes and references",
        "## Observed order of convergence",
        "## Scene (a)",
        "## Scene (b)",
        "## Scene (c)",
    ] {
        assert!(text.contains(section), "missing {section:?}");
    }
    for p in [
        plot.clone(),
        dir.join("accuracy_b.svg"),
        dir.join("accuracy_c.svg"),
    ] {
        assert!(std::fs::read_to_string(&p).unwrap().starts_with("<svg"));
    }
    // Per scene, Wilson θ rows: | Wilson θ | locator | dt | wall | impact | peak | energy |.
    for scene in text.split("\n## Scene ").skip(1) {
        let name = scene.lines().next().unwrap();
        for locator in ["linear", "Hermite"] {
            let rows: Vec<(f64, [f64; 3])> = scene
                .lines()
                .filter(|l| l.starts_with(&format!("| Wilson θ | {locator} |")))
                .map(|l| {
                    let c: Vec<&str> = l.split('|').map(str::trim).collect();
                    let v = |i: usize| c[i].parse::<f64>().unwrap_or(f64::NAN);
                    (v(3), [v(5), v(6), v(7)])
                })
                .collect();
            assert!(rows.len() >= 3, "{name}: {} Wilson θ rows", rows.len());
            assert!(
                rows.windows(2).all(|w| w[1].0 < w[0].0),
                "dt not decreasing"
            );
            for (metric, label) in ["impact times", "peak", "energy"].iter().enumerate() {
                for w in rows.windows(2) {
                    let (a, b) = (w[0].1[metric], w[1].1[metric]);
                    assert!(
                        a.is_finite() && b.is_finite() && b < a,
                        "{name}, Wilson θ {locator}, {label}: error {a} at dt = {} then {b} at dt = {}",
                        w[0].0,
                        w[1].0
                    );
                }
            }
        }
    }
}
