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
//! joints' slips (mm) in `FILE_slips.EXT`.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rocking::contact::simulation::{DrumEventKind, DrumHistory, DrumOutcome, DrumStop};
use rocking::scene::{contact_events, ContactHistoryColumns, ContactSummary, Scene};

use crate::output::{json_tree, write_atomic, write_atomic_with};
use crate::plot::{member_color, member_name, Chart, Marker, Rgb, Series, Style, COLORS};
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
    let bar = progress::bar(1000, "simulating");
    let mut report = |fraction: f64| bar.set_position((fraction * 1000.0) as u64);
    let started = Instant::now();
    let outcome = scene
        .simulate_contact(Some(&mut report))
        .expect("a contact-scheme scene")?;
    let wall = started.elapsed().as_secs_f64();
    bar.finish_and_clear();

    if scene.output.history {
        if let Some(h) = &outcome.history {
            let rest = rocking::scene::rest(&scene.column);
            write_atomic_with(&out.join("history.csv"), |w| write_history_csv(w, h, &rest))?;
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
        rounded(&outcome.peak_rotation, 1.0, 4),
        rounded(&outcome.residual_slip, 1e3, 1),
        wall,
        out.display()
    );
    Ok(())
}

/// `values × scale` to `digits` decimals, for the console; a value that rounds to zero is 0,
/// not -0 (a residual slip of -2e-6 m printed as -0.0 mm).
fn rounded(values: &[f64], scale: f64, digits: i32) -> Vec<f64> {
    let f = 10f64.powi(digits);
    values
        .iter()
        .map(|v| (v * scale * f).round() / f + 0.0)
        .collect()
}

/// `plot.svg` → `plot_slips.svg`.
pub fn slips_path(p: &Path) -> PathBuf {
    let stem = p.file_stem().map_or("plot".into(), |s| s.to_string_lossy());
    let ext = p.extension().map_or("svg".into(), |s| s.to_string_lossy());
    p.with_file_name(format!("{stem}_slips.{ext}"))
}

/// The history as CSV: per drum `x_k`, `y_k` (its centre's displacement from `rest`, the
/// straight column at rest, m) and `block_rotation_k` (rad, positive counter-clockwise as the
/// driver's), per joint `slip_k` (m).
pub fn write_history_csv<W: Write>(
    w: &mut W,
    h: &DrumHistory,
    rest: &[f64],
) -> std::io::Result<()> {
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
        let c = ContactHistoryColumns::of_rows(h, start..h.t.len().min(start + BLOCK), rest);
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

/// The colour of an event kind's markers: each kind its own (lift-off and landing, slip start
/// and stop were drawn alike), `None` for the kinds not marked.
fn marker_color(kind: DrumEventKind) -> Option<Rgb> {
    use DrumEventKind as K;
    match kind {
        K::Impact => Some(COLORS[1]),
        K::LiftOff => Some(COLORS[4]),
        K::Landing => Some(COLORS[5]),
        K::SlipStart => Some(COLORS[2]),
        K::SlipStop => Some(COLORS[6]),
        K::Overturned => Some((0, 0, 0)),
        K::SchemeSwitch => Some(COLORS[7]),
        K::Opening => None,
    }
}

/// The drum rotations (rad) and the joints' slips (mm), with the events marked: impacts,
/// lift-offs, landings and scheme switches on the rotations, slip starts and stops on the slips,
/// the overturning on both.
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
        y_label: "joint slip [mm]".into(),
        ..Chart::default()
    };
    for k in 0..n {
        let color = member_color(k, n);
        rotations.series.push(Series {
            name: member_name("drum", k, n),
            points: (0..h.t.len())
                .map(|i| (h.t[i], h.q[3 * n * i + 3 * k + 2]))
                .collect(),
            style: Style::Line,
            color,
        });
        slips.series.push(Series {
            name: member_name("joint", k, n),
            points: (0..h.t.len())
                .map(|i| (h.t[i], 1e3 * h.slip[n * i + k]))
                .collect(),
            style: Style::Line,
            color,
        });
    }
    for e in &o.events {
        use DrumEventKind as K;
        let Some(color) = marker_color(e.kind) else {
            continue;
        };
        let marker = Marker {
            x: e.t,
            kind: e.kind.name().to_string(),
            color,
        };
        match e.kind {
            K::SlipStart | K::SlipStop => slips.markers.push(marker),
            K::Overturned => {
                slips.markers.push(marker.clone());
                rotations.markers.push(marker);
            }
            _ => rotations.markers.push(marker),
        }
    }
    Ok((rotations, slips))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rocking::contact::simulation;
    use rocking::ground::FnMotion;
    use std::collections::BTreeMap;

    /// The scene of `n` 1 × 1 m drums under a full sine of `amplitude` m/s², and its run.
    fn run(n: usize, amplitude: f64, duration: f64) -> (Scene, DrumOutcome) {
        let blocks = vec![r#"{"width": 1, "height": 1, "mass": 2500}"#; n].join(",");
        let text = format!(
            r#"{{"blocks": [{blocks}], "impacts": 2, "duration": {duration}, "dt": 0.001,
                "excitation": {{"type": "full_sine", "amplitude": {amplitude}, "duration": 1.0}},
                "friction": 0.5, "on_sliding": "slide", "on_tension": "fly"}}"#
        );
        let spec = rocking::scene::parse(&text).unwrap();
        let scene = rocking::scene::build(spec, Path::new("."), "test").unwrap();
        let options = scene.contact.as_ref().unwrap();
        let e = &scene.excitation;
        let motion = FnMotion(|t| e.acceleration(t), e.end_time());
        let outcome = simulation::simulate(&scene.column, &motion, options, None).unwrap();
        (scene, outcome)
    }

    #[test]
    fn console_values_round_without_negative_zeros() {
        let text = format!("{:?}", rounded(&[-2e-6, 0.00446, -0.0155388], 1e3, 1));
        assert_eq!(text, "[0.0, 4.5, -15.5]");
        assert_eq!(rounded(&[0.059965, -0.00004], 1.0, 4), [0.06, 0.0]);
    }

    /// Each kind of marker its own colour on each chart.
    fn colors(chart: &Chart) -> BTreeMap<String, Rgb> {
        let mut kinds = BTreeMap::new();
        for m in &chart.markers {
            let c = *kinds.entry(m.kind.clone()).or_insert(m.color);
            assert_eq!(c, m.color, "{}", m.kind);
        }
        let mut distinct: Vec<Rgb> = kinds.values().copied().collect();
        distinct.sort_unstable();
        distinct.dedup();
        assert_eq!(distinct.len(), kinds.len(), "{kinds:?}");
        kinds
    }

    /// Every kind of event is told apart from the others (lift-offs and landings were drawn in
    /// one colour, slip starts and stops in another), the overturning is marked on both charts
    /// (it was on neither), the slips are in mm, and ten drums are ten colours (the palette
    /// repeated every eight) with a legend of at most seven of them.
    #[test]
    fn the_charts_tell_every_event_and_drum_apart() {
        let (scene, o) = run(10, 5.0, 3.0);
        let (rotations, slips) = charts(&scene, &o).unwrap();
        let (r, s) = (colors(&rotations), colors(&slips));
        for kind in ["impact", "lift_off", "landing"] {
            assert!(r.contains_key(kind), "{kind}: {r:?}");
        }
        assert!(
            s.contains_key("slip_start") && s.contains_key("slip_stop"),
            "{s:?}"
        );
        let h = o.history.as_ref().unwrap();
        let i = h.t.len() - 1;
        assert_eq!(slips.series[9].points[i].1, 1e3 * h.slip[10 * i + 9]);
        let mut series: Vec<Rgb> = rotations.series.iter().map(|s| s.color).collect();
        series.sort_unstable();
        series.dedup();
        assert_eq!(series.len(), 10);
        let named = rotations.series.iter().filter(|s| !s.name.is_empty());
        assert_eq!(named.count(), crate::plot::palette::MAX_NAMED);

        let (scene, o) = run(3, 8.0, 2.0);
        assert!(o.overturned, "{:?}", o.stop);
        let (rotations, slips) = charts(&scene, &o).unwrap();
        for chart in [&rotations, &slips] {
            assert!(chart.markers.iter().any(|m| m.kind == "overturned"));
        }
    }
}
