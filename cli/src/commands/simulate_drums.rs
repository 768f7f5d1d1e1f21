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

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rocking::contact::auto;
use rocking::contact::simulation::{
    self, DrumEventKind, DrumHistory, DrumOutcome, DrumStop, JointMode,
};
use rocking::ground::FnMotion;
use rocking::scene::Scene;
use serde::Serialize;

use crate::output::{json_tree, write_atomic};
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
            write_atomic(&out.join("history.csv"), history_csv(h).as_bytes())?;
        }
    }
    if scene.output.events {
        let mut lines = String::new();
        let mut switches = outcome.switches.iter();
        for e in &outcome.events {
            let line = match (e.kind, e.kind == DrumEventKind::SchemeSwitch) {
                (_, true) => match switches.next() {
                    Some(s) => serde_json::json!({"t": e.t, "kind": e.kind.name(),
                        "from": s.from.name(), "to": s.to.name(), "why": s.why,
                        "kinetic_before": s.kinetic_before, "kinetic_after": s.kinetic_after,
                        "slip_dropped": s.slip_dropped}),
                    None => continue,
                },
                _ => serde_json::json!({"t": e.t, "kind": e.kind.name(), "joint": e.joint}),
            };
            lines.push_str(&line.to_string());
            lines.push('\n');
        }
        write_atomic(&out.join("events.jsonl"), lines.as_bytes())?;
    }
    let summary = json_tree(&Summary::of(scene, scene_path, &outcome, options.dt, wall))?;
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
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
pub fn history_csv(h: &DrumHistory) -> String {
    let n = h.n;
    let mut s = String::from("t");
    for name in ["x", "y", "block_rotation"] {
        for k in 0..n {
            let _ = write!(s, ",{name}_{k}");
        }
    }
    for k in 0..n {
        let _ = write!(s, ",slip_{k}");
    }
    s.push('\n');
    let (q0, _) = h.q.split_at(3 * n);
    for i in 0..h.t.len() {
        let _ = write!(s, "{}", h.t[i]);
        let q = &h.q[3 * n * i..3 * n * (i + 1)];
        for c in 0..3 {
            for k in 0..n {
                let v = q[3 * k + c] - if c < 2 { q0[3 * k + c] } else { 0.0 };
                let _ = write!(s, ",{v}");
            }
        }
        for v in &h.slip[n * i..n * (i + 1)] {
            let _ = write!(s, ",{v}");
        }
        s.push('\n');
    }
    s
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

/// The stop as `summary.json` names it (the event-driven names where they mean the same).
pub fn stop_json(s: &DrumStop) -> (&'static str, Option<usize>) {
    match *s {
        DrumStop::Duration => ("duration", None),
        DrumStop::Overturned { joint } => ("overturned", Some(joint)),
        DrumStop::Fallen { drum } => ("fallen", Some(drum)),
        DrumStop::SlidOff { joint } => ("slid_off", Some(joint)),
        DrumStop::Sliding { joint } => ("sliding", Some(joint)),
        DrumStop::Tension { joint } => ("tension", Some(joint)),
    }
}

fn mode_name(m: JointMode) -> &'static str {
    match m {
        JointMode::Closed => "closed",
        JointMode::RockingRight => "rocking_right",
        JointMode::RockingLeft => "rocking_left",
        JointMode::Flying => "flying",
    }
}

/// `summary.json` of a contact-scheme run.
#[derive(Serialize)]
struct Summary<'a> {
    scene: String,
    title: &'a str,
    excitation: String,
    scheme: &'static str,
    overturned: bool,
    t_end: f64,
    impacts: usize,
    stop_reason: &'static str,
    stop_interface: Option<usize>,
    peak_block_rotation: &'a [f64],
    peak_slip: &'a [f64],
    residual_slip: &'a [f64],
    peak_top_displacement: f64,
    modes_end: Vec<&'static str>,
    /// Events by kind.
    events: BTreeMap<&'static str, usize>,
    energy: Energy,
    /// Scheme "auto": the hand-overs and the simulated time in the event-driven driver (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    scheme_switches: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    time_event_driven: Option<f64>,
    dt: f64,
    wall_time_s: f64,
}

/// The energy balance: `ground_work = potential_change + kinetic_change + impact + friction +
/// residual`; `residual` is the scheme's error (`persistent_contact + projection` up to
/// round-off), `relative_residual` against the largest energy involved.
#[derive(Serialize)]
struct Energy {
    ground_work: f64,
    potential_change: f64,
    kinetic_change: f64,
    impact: f64,
    friction: f64,
    persistent_contact: f64,
    projection: f64,
    residual: f64,
    relative_residual: f64,
}

impl<'a> Summary<'a> {
    fn of(scene: &'a Scene, path: &Path, o: &'a DrumOutcome, dt: f64, wall: f64) -> Summary<'a> {
        let (stop_reason, stop_interface) = stop_json(&o.stop);
        let kinds = [
            "opening",
            "impact",
            "slip_start",
            "slip_stop",
            "lift_off",
            "landing",
            "overturned",
        ];
        let events = kinds
            .iter()
            .zip(o.event_counts)
            .filter(|(_, c)| *c > 0)
            .map(|(k, c)| (*k, c))
            .collect();
        let e = &o.energy;
        let a = &e.accounts;
        Summary {
            scene: path.display().to_string(),
            title: &scene.title,
            excitation: scene.excitation.describe(),
            scheme: if scene.auto.is_some() {
                "auto"
            } else {
                "moreau"
            },
            overturned: o.overturned,
            t_end: o.t_end,
            impacts: o.event_counts[1],
            stop_reason,
            stop_interface,
            peak_block_rotation: &o.peak_rotation,
            peak_slip: &o.peak_slip,
            residual_slip: &o.residual_slip,
            peak_top_displacement: o.peak_top_displacement,
            modes_end: o.modes_end.iter().map(|m| mode_name(*m)).collect(),
            events,
            energy: Energy {
                ground_work: a.ground_work,
                potential_change: e.potential_change,
                kinetic_change: e.kinetic_change,
                impact: a.impact,
                friction: a.friction,
                persistent_contact: a.persistent_contact,
                projection: a.projection,
                residual: e.residual(),
                relative_residual: e.residual() / e.scale(),
            },
            scheme_switches: scene.auto.map(|_| o.switches.len()),
            time_event_driven: scene.auto.map(|_| o.time_event_driven),
            dt,
            wall_time_s: wall,
        }
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
