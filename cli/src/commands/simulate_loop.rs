//! `rocking simulate` on a closed chain (`"arch"` or `"colonnade"` scene; docs/arches.md): the
//! loop driver (`rocking::driver::simulate_loop_with_progress`, with the progress bar).
//!
//! Writes `DIR/history.csv` (t; per joint its signed angle `angle_k = phĭ_k + phî_k`),
//! `DIR/events.jsonl` (`t`, `kind`: opening, closing, locked, settled, collapsed; `joints` that
//! closed, kinetic energy before and after, `statuses` after) and `DIR/summary.json` (collapsed,
//! whether it stands under its own weight,
//! t_end, peak joint angle, events by kind, the joints that ever opened as hinges and about which
//! face, the closure residual after the projection and the drift of one step before it).
//! `--plot FILE` draws the chain in its closed geometry with every hinge that opened marked at its
//! pivot corner, and the joint angles against time in `FILE_history.EXT`.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rocking::chain::colonnade::CappedColonnade;
use rocking::driver::closed::{LoopEventKind, LoopOutcome, LoopState};
use rocking::driver::simulate_loop_with_progress;
use rocking::model::column::Block;
use rocking::scene::{
    hinges, loop_event_name, loop_events, loop_joint_angles, LoopScene, LoopShape, LoopSummary,
};

use crate::output::{json_tree, write_atomic, write_atomic_with};
use crate::plot::{Chart, Marker, Series, Style, COLORS};
use crate::progress;

/// Runs the loop scene and writes its outputs.
pub fn run(
    scene: &LoopScene,
    scene_path: &Path,
    out: &Path,
    plot: Option<&Path>,
) -> Result<(), String> {
    // The progress bar of the column runs (an arch at a fine step runs for seconds to minutes).
    let bar = progress::bar(1000, "simulating");
    let mut report = |fraction: f64| bar.set_position((fraction * 1000.0) as u64);
    let started = Instant::now();
    let outcome = simulate_loop_with_progress(
        &scene.chain,
        &scene.excitation,
        LoopState::at_rest(&scene.chain),
        &scene.options,
        Some(&mut report),
    )
    .map_err(|e| e.to_string())?;
    let wall = started.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let n = scene.chain.n_joints();
    if scene.output.history {
        write_atomic_with(&out.join("history.csv"), |w| {
            write_history_csv(w, &outcome, n)
        })?;
    }
    if scene.output.events {
        let mut lines = String::new();
        for e in loop_events(&outcome) {
            lines.push_str(&e.to_string());
            lines.push('\n');
        }
        write_atomic(&out.join("events.jsonl"), lines.as_bytes())?;
    }
    let path = Some(scene_path.display().to_string());
    let summary = json_tree(&LoopSummary::of(scene, path, &outcome, wall))?;
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    crate::output::remove_unwritten(out, &scene.output)?;
    write_atomic(&out.join("summary.json"), format!("{text}\n").as_bytes())?;
    if let Some(p) = plot {
        geometry_chart(scene, &outcome).write(p)?;
        history_chart(scene, &outcome)?.write(&history_path(p))?;
    }
    println!(
        "{}: {} at t = {:.4} s, {} events, peak joint angle {:.6} rad, closure residual {:.1e} m \
         ({:.3} s wall) -> {}",
        scene.title,
        if outcome.collapsed {
            "collapsed"
        } else {
            "end of duration"
        },
        outcome.state.time,
        outcome.events.len(),
        outcome.peak_angle,
        outcome.max_closure_residual,
        wall,
        out.display()
    );
    // Said, not left to be guessed from a collapse at the first steps with a peak angle of 0.
    if outcome.stands_under_own_weight == Some(false) {
        println!(
            "{}: does not stand under its own weight (below the minimum thickness for its \
             embrace angle and voussoirs: docs/arches.md §1); it moves whatever the ground does",
            scene.title
        );
    }
    Ok(())
}

/// `plot.svg` → `plot_history.svg`.
pub fn history_path(p: &Path) -> PathBuf {
    let stem = p.file_stem().map_or("plot".into(), |s| s.to_string_lossy());
    let ext = p.extension().map_or("svg".into(), |s| s.to_string_lossy());
    p.with_file_name(format!("{stem}_history.{ext}"))
}

/// The history as CSV: t and per joint its signed angle (rad).
pub fn write_history_csv<W: Write>(w: &mut W, o: &LoopOutcome, n: usize) -> std::io::Result<()> {
    let (t, angles) = loop_joint_angles(o, n);
    w.write_all(b"t")?;
    for k in 0..n {
        write!(w, ",angle_{k}")?;
    }
    w.write_all(b"\n")?;
    for (t, row) in t.iter().zip(angles.chunks_exact(n.max(1))) {
        write!(w, "{t}")?;
        for v in row {
            write!(w, ",{v}")?;
        }
        w.write_all(b"\n")?;
    }
    Ok(())
}

/// The chain in its closed geometry (each joint's face, the corners joined in chain order: an
/// arch's intrados and extrados as polygons), every hinge that opened marked at its pivot.
fn geometry_chart(scene: &LoopScene, o: &LoopOutcome) -> Chart {
    let joints = scene.chain.joints();
    let mut chart = Chart {
        title: format!("{} — hinges that opened", scene.title),
        x_label: "x [m]".into(),
        y_label: "y [m]".into(),
        ..Chart::default()
    };
    let right: Vec<(f64, f64)> = joints
        .iter()
        .map(|j| (j.right_corner()[0], j.right_corner()[1]))
        .collect();
    let left: Vec<(f64, f64)> = joints
        .iter()
        .map(|j| (j.left_corner()[0], j.left_corner()[1]))
        .collect();
    match &scene.shape {
        LoopShape::Arch(_) => {
            chart.series.push(Series {
                name: "R corners (intrados)".into(),
                points: right.clone(),
                style: Style::Line,
                color: COLORS[0],
            });
            chart.series.push(Series {
                name: "L corners (extrados)".into(),
                points: left.clone(),
                style: Style::Line,
                color: COLORS[0],
            });
        }
        // The blocks themselves: the corner polylines of a colonnade are the columns' faces
        // joined at their tops, without the beam.
        LoopShape::Colonnade(frame) => {
            for (k, outline) in colonnade_outlines(frame).into_iter().enumerate() {
                chart.series.push(Series {
                    name: if k == 0 {
                        "blocks".into()
                    } else {
                        String::new()
                    },
                    points: outline,
                    style: Style::Line,
                    color: COLORS[0],
                });
            }
        }
    }
    // An arch's joint faces as one polyline: R_0 → L_0 → L_1 → R_1 → R_2 → L_2 → … (the steps
    // between faces run along the edges already drawn). A colonnade's, each on its own (a step
    // from one column top to the other would run along the beam's underside, which is no joint).
    let faces: Vec<Vec<(f64, f64)>> = match scene.shape {
        LoopShape::Arch(_) => vec![right
            .iter()
            .zip(&left)
            .enumerate()
            .flat_map(|(k, (r, l))| if k % 2 == 0 { [*r, *l] } else { [*l, *r] })
            .collect()],
        LoopShape::Colonnade(_) => right.iter().zip(&left).map(|(r, l)| vec![*r, *l]).collect(),
    };
    for (k, points) in faces.into_iter().enumerate() {
        chart.series.push(Series {
            name: if k == 0 {
                "joints".into()
            } else {
                String::new()
            },
            points,
            style: Style::Dashed,
            color: COLORS[7],
        });
    }
    let hinges = hinges(o);
    for (face, name, color) in [
        (-1i8, "hinge about R", COLORS[1]),
        (1, "hinge about L", COLORS[2]),
    ] {
        let points: Vec<(f64, f64)> = hinges
            .iter()
            .filter(|h| h.1 == face)
            .map(|&(k, _)| if face < 0 { right[k] } else { left[k] })
            .collect();
        if !points.is_empty() {
            chart.series.push(Series {
                name: name.into(),
                points,
                style: Style::Points,
                color,
            });
        }
    }
    chart
}

/// The closed outline of every block of `frame` in its closed geometry: the columns' blocks
/// stacked on their axes (`x = 0` and `x = span`), the beam centred between them on top.
fn colonnade_outlines(frame: &CappedColonnade) -> Vec<Vec<(f64, f64)>> {
    let rectangle = |x: f64, y: f64, b: &Block| {
        let (l, r, t) = (x - 0.5 * b.width, x + 0.5 * b.width, y + b.height);
        vec![(l, y), (r, y), (r, t), (l, t), (l, y)]
    };
    let mut outlines = Vec::new();
    let mut top = 0.0;
    for (x, column) in [(0.0, &frame.left), (frame.span, &frame.right)] {
        let mut y = 0.0;
        for b in column {
            outlines.push(rectangle(x, y, b));
            y += b.height;
        }
        top = y;
    }
    outlines.push(rectangle(0.5 * frame.span, top, &frame.beam));
    outlines
}

/// The joint angles against time (every joint that moved), events marked.
fn history_chart(scene: &LoopScene, o: &LoopOutcome) -> Result<Chart, String> {
    if o.history.is_empty() {
        return Err("--plot needs the history (output.history must be true)".into());
    }
    let n = scene.chain.n_joints();
    let mut chart = Chart {
        title: format!("{} — {}", scene.title, scene.excitation.describe()),
        x_label: "t [s]".into(),
        y_label: "joint angle [rad]".into(),
        ..Chart::default()
    };
    for k in 0..n {
        let points: Vec<(f64, f64)> = o
            .history
            .iter()
            .map(|(t, phi)| (*t, phi[k] + phi[n + k]))
            .collect();
        if points.iter().any(|p| p.1 != 0.0) {
            // The i-th moved joint: the colours in turn, solid and then dashed (16 lines apart).
            let i = chart.series.len();
            chart.series.push(Series {
                name: format!("joint {k}"),
                points,
                style: if (i / COLORS.len()).is_multiple_of(2) {
                    Style::Line
                } else {
                    Style::Dashed
                },
                color: COLORS[i % COLORS.len()],
            });
        }
    }
    for e in &o.events {
        let color = match e.kind {
            LoopEventKind::Closing { .. } => COLORS[1],
            LoopEventKind::Opening => COLORS[2],
            LoopEventKind::Collapsed => (0, 0, 0),
            _ => COLORS[7],
        };
        chart.markers.push(Marker {
            x: e.time,
            kind: loop_event_name(&e.kind).to_string(),
            color,
        });
    }
    Ok(chart)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rocking::driver::simulate_loop;

    /// The loop scene of the JSON `text` (written to a file of its own, as a user's) and its run.
    fn run_scene(name: &str, text: &str) -> (LoopScene, LoopOutcome) {
        let dir = std::env::temp_dir().join(format!("rocking_{name}_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.json");
        std::fs::write(&path, text).unwrap();
        let scene = match rocking::scene::load_any(&path).unwrap() {
            rocking::scene::AnyScene::Loop(s) => s,
            _ => panic!("not a loop scene"),
        };
        let _ = std::fs::remove_dir_all(&dir);
        let outcome = simulate_loop(
            &scene.chain,
            &scene.excitation,
            LoopState::at_rest(&scene.chain),
            &scene.options,
        )
        .unwrap();
        (*scene, outcome)
    }

    /// The colonnade's picture draws its blocks: both columns and the beam on them. It drew the
    /// arch's two corner polylines instead ("R corners (intrados)", "L corners (extrados)"),
    /// which for a colonnade are the inner and outer faces of the columns joined at the top: the
    /// beam (1 m deep here) was not drawn at all, the chart ended at the column tops.
    #[test]
    fn the_colonnade_picture_draws_the_columns_and_the_beam() {
        let (scene, outcome) = run_scene(
            "colonnade",
            r#"{"colonnade": {"width": 1, "height": 5, "column_mass": 1000, "span": 3,
                "beam_height": 1, "beam_mass": 1000},
                "excitation": {"type": "none"}, "duration": 0.01, "dt": 0.001}"#,
        );
        let chart = geometry_chart(&scene, &outcome);
        assert!(
            chart.series.iter().all(|s| !s.name.contains("intrados")),
            "{:?}",
            chart.series.iter().map(|s| &s.name).collect::<Vec<_>>()
        );
        let points: Vec<(f64, f64)> = chart
            .series
            .iter()
            .filter(|s| s.style == Style::Line)
            .flat_map(|s| s.points.iter().copied())
            .collect();
        // Every corner of the three blocks: the columns [−0.5, 0.5] and [2.5, 3.5] × [0, 5],
        // the beam [−0.5, 3.5] × [5, 6].
        for corner in [
            (-0.5, 0.0),
            (0.5, 0.0),
            (2.5, 0.0),
            (3.5, 0.0),
            (-0.5, 6.0),
            (3.5, 6.0),
            (-0.5, 5.0),
            (3.5, 5.0),
        ] {
            assert!(
                points
                    .iter()
                    .any(|p| (p.0 - corner.0).abs() < 1e-12 && (p.1 - corner.1).abs() < 1e-12),
                "{corner:?} not drawn: {points:?}"
            );
        }
    }

    /// The joint angles' chart tells its joints apart: up to 16 joints moved, no two share a
    /// colour and a line style. Colours were `COLORS[joint % 8]`, all solid: joints 1, 9 and 17
    /// of the bundled 20-voussoir arch were the same red line (and two moved joints whose numbers
    /// differ by 8 always looked alike).
    #[test]
    fn the_history_chart_tells_the_joints_apart() {
        let (scene, outcome) = run_scene(
            "history",
            r#"{"arch": {"radius": 5, "thickness": 0.75, "voussoirs": 12},
                "excitation": {"type": "half_sines", "amplitude": 3, "duration": 0.5, "count": 3},
                "duration": 3.0, "dt": 0.001}"#,
        );
        let chart = history_chart(&scene, &outcome).unwrap();
        let joints: Vec<_> = chart
            .series
            .iter()
            .filter(|s| s.name.starts_with("joint"))
            .map(|s| (s.color, s.style == Style::Line))
            .collect();
        assert!(joints.len() > COLORS.len(), "{} joints moved", joints.len());
        for (i, a) in joints.iter().enumerate() {
            assert!(!joints[..i].contains(a), "series {i} repeats {a:?}");
        }
    }
}
