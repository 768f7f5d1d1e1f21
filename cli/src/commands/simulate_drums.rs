//! `rocking simulate` on a scene that chose the contact scheme (`on_sliding: "slide"`,
//! `on_tension: "fly"` or `scheme: "moreau"`; docs/multidrum.md): Moreau–Jean time stepping of
//! the column with Coulomb friction and flight at the joints; or `scheme: "auto"`: the
//! event-driven driver where events are few and Moreau–Jean where they crowd, one record of the
//! whole run (`scheme_switch` events with `from`, `to`, `why`; `scheme_switches` and
//! `time_event_driven` in the summary).
//!
//! Writes `DIR/history.csv` (t; per drum its centre `x_k`, `y_k` relative to rest and its
//! rotation `block_rotation_k`; per joint its slip `slip_k`), `DIR/events.jsonl` (`t`, `kind`:
//! opening, impact, slip_start, slip_stop, lift_off, landing, overturned; `joint`) and
//! `DIR/summary.json` (as the event-driven summary where the two share a meaning, plus
//! `peak_slip` and `residual_slip` per joint, the top's peak displacement, the joints' modes at the
//! end and the scheme's energy accounts). `--plot FILE` draws the drum rotations in `FILE` and the
//! joints' slips in `FILE_slips.EXT`.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rocking::contact::auto;
use rocking::contact::simulation::{self, DrumHistory, DrumOutcome, DrumStop};
use rocking::ground::FnMotion;
use rocking::scene::{contact_events, ContactHistoryColumns, ContactSummary, Scene};

use crate::output::{json_tree, write_atomic, write_atomic_with};
use crate::plot::{Chart, Marker, Series, Style, COLORS};
use crate::progress;

/// Runs the scene with the contact scheme and writes its outputs.
pub fn run(
    scene: &Scene,
    scene_path: &Path,
    out: &Path,
    plot: Option<&Path>,
) -> Result<(), String> {
    let options = scene
        .contact
        .as_ref()
        .ok_or("the scene did not choose the contact scheme")?;
    let excitation = &scene.excitation;
    let motion = FnMotion(|t| excitation.acceleration(t), excitation.end_time());
    let bar = progress::bar(1000, "simulating");
    let mut report = |fraction: f64| bar.set_position((fraction * 1000.0) as u64);
    let started = Instant::now();
    let outcome = match &scene.auto {
        Some(rules) => auto::simulate(
            &scene.column,
            &motion,
            &scene.options,
            options,
            rules,
            Some(&mut report),
        )
        .map_err(|e| e.to_string())?,
        None => simulation::simulate(&scene.column, &motion, options, Some(&mut report))
            .map_err(|e| e.to_string())?,
    };
    let wall = started.elapsed().as_secs_f64();
    bar.finish_and_clear();

    if scene.output.history {
        if let Some(h) = &outcome.history {
            write_atomic_with(&out.join("history.csv"), |w| write_history_csv(w, h))?;
        }
    }
    if scene.output.events {
        let mut lines = String::new();
        for e in contact_events(&outcome) {
            lines.push_str(&e.to_string());
            lines.push('\n');
        }
        write_atomic(&out.join("events.jsonl"), lines.as_bytes())?;
    }
    let path = Some(scene_path.display().to_string());
    let summary = ContactSummary::of(scene, path, &outcome, options.dt, wall);
    let text = serde_json::to_string_pretty(&json_tree(&summary)?).map_err(|e| e.to_string())?;
    crate::output::remove_unwritten(out, &scene.output)?;
    write_atomic(&out.join("summary.json"), format!("{text}\n").as_bytes())?;
    if let Some(p) = plot {
        let (rotations, slips) = charts(scene, &outcome)?;
        rotations.write(p)?;
        slips.write(&slips_path(p))?;
    }
    println!(
        "{}: {} at t = {:.4} s, {} impacts, {} slip starts, {} lift-offs; peak drum rotations {:?} rad, \
         residual slips {:?} mm ({:.3} s wall) -> {}",
        scene.title,
        stop_text(&outcome.stop),
        outcome.t_end,
        outcome.event_counts[1],
        outcome.event_counts[2],
        outcome.event_counts[4],
        outcome.peak_rotation.iter().map(|v| (v * 1e4).round() / 1e4).collect::<Vec<_>>(),
        outcome.residual_slip.iter().map(|v| (v * 1e4).round() / 10.0).collect::<Vec<_>>(),
        wall,
        out.display()
    );
    Ok(())
}

/// `plot.svg` → `plot_slips.svg`.
pub fn slips_path(p: &Path) -> PathBuf {
    let stem = p.file_stem().map_or("plot".into(), |s| s.to_string_lossy());
    let ext = p.extension().map_or("svg".into(), |s| s.to_string_lossy());
    p.with_file_name(format!("{stem}_slips.{ext}"))
}

/// The history as CSV: per drum `x_k`, `y_k` (its centre's displacement from rest, m) and
/// `block_rotation_k` (rad, positive counter-clockwise as the driver's), per joint `slip_k` (m).
pub fn write_history_csv<W: Write>(w: &mut W, h: &DrumHistory) -> std::io::Result<()> {
    let n = h.n;
    w.write_all(b"t")?;
    for name in ["x", "y", "block_rotation", "slip"] {
        for k in 0..n {
            write!(w, ",{name}_{k}")?;
        }
    }
    w.write_all(b"\n")?;
    // A block of rows at a time: the columns of the whole history are not copied at once.
    const BLOCK: usize = 4096;
    for start in (0..h.t.len()).step_by(BLOCK) {
        let c = ContactHistoryColumns::of_rows(h, start..h.t.len().min(start + BLOCK));
        for i in 0..c.len() {
            write!(w, "{}", c.t[i])?;
            for column in [&c.x, &c.y, &c.block_rotation, &c.slip] {
                for v in &column[n * i..n * (i + 1)] {
                    write!(w, ",{v}")?;
                }
            }
            w.write_all(b"\n")?;
        }
    }
    Ok(())
}

fn stop_text(s: &DrumStop) -> String {
    match s {
        DrumStop::Duration => "end of duration".into(),
        DrumStop::Overturned { joint } => format!("overturned at joint {joint}"),
        DrumStop::Fallen { drum } => format!("drum {drum} fallen"),
        DrumStop::SlidOff { joint } => format!("slid off at joint {joint}"),
        DrumStop::Sliding { joint } => format!("sliding at joint {joint}"),
        DrumStop::Tension { joint } => format!("tension at joint {joint}"),
    }
}

fn charts(scene: &Scene, o: &DrumOutcome) -> Result<(Chart, Chart), String> {
    let h = o
        .history
        .as_ref()
        .ok_or("--plot needs the history (output.history must be true)")?;
    let n = h.n;
    let title = format!("{} — {}", scene.title, scene.excitation.describe());
    let mut rotations = Chart {
        title: title.clone(),
        x_label: "t [s]".into(),
        y_label: "drum rotation [rad]".into(),
        ..Chart::default()
    };
    let mut slips = Chart {
        title,
        x_label: "t [s]".into(),
        y_label: "joint slip [m]".into(),
        ..Chart::default()
    };
    for k in 0..n {
        let color = COLORS[k % COLORS.len()];
        rotations.series.push(Series {
            name: format!("drum {k}"),
            points: (0..h.t.len())
                .map(|i| (h.t[i], h.q[3 * n * i + 3 * k + 2]))
                .collect(),
            style: Style::Line,
            color,
        });
        slips.series.push(Series {
            name: format!("joint {k}"),
            points: (0..h.t.len())
                .map(|i| (h.t[i], h.slip[n * i + k]))
                .collect(),
            style: Style::Line,
            color,
        });
    }
    for e in &o.events {
        use rocking::contact::simulation::DrumEventKind as K;
        let (chart, color) = match e.kind {
            K::Impact => (&mut rotations, COLORS[1]),
            K::LiftOff | K::Landing => (&mut rotations, COLORS[3]),
            K::SlipStart | K::SlipStop => (&mut slips, COLORS[2]),
            _ => continue,
        };
        chart.markers.push(Marker {
            x: e.t,
            kind: e.kind.name().to_string(),
            color,
        });
    }
    Ok((rotations, slips))
}
