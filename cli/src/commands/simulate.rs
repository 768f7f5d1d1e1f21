//! `rocking simulate SCENE.json --out DIR [--plot FILE.svg|png]`: a time history of a scene.
//! A scene whose joints may slide or fly runs the contact scheme instead ([`super::simulate_drums`]);
//! an arch or a colonnade runs the loop driver ([`super::simulate_loop`]).
//!
//! Writes `DIR/history.csv` (t, interface angles and rates, block rotations, statuses),
//! `DIR/events.jsonl` (one JSON object per event) and `DIR/summary.json`. Files are written only
//! after the simulation succeeded, each atomically; then a `history.csv` or `events.jsonl` the
//! scene does not write (`output`) is removed from `DIR`, where it was an earlier run's.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rocking::driver::{self, EventKind, Outcome, StopReason};
use rocking::ground::FnMotion;

use crate::output::{check_writable, json_tree, write_atomic, write_atomic_with};
use crate::plot::{member_color, member_name, Chart, Marker, Series, Style, COLORS};
use crate::progress;
use rocking::scene::{self, Scene, Summary};

/// Options of `rocking simulate`.
#[derive(Args, Debug)]
pub struct SimulateArgs {
    /// The scene file (JSON: blocks, excitation, settings; see examples/scenes).
    pub scene: PathBuf,
    /// Output directory (created if needed).
    #[arg(long)]
    pub out: PathBuf,
    /// Draw block rotations against time with the events marked (.svg or .png); a drum scene
    /// on the contact scheme also draws the joints' slips (mm) in FILE_slips.svg|png, an arch
    /// or colonnade its joint angles.
    #[arg(long, value_parser = crate::plot::plot_path)]
    pub plot: Option<PathBuf>,
}

/// Runs the command.
pub fn run(a: &SimulateArgs) -> Result<(), String> {
    let (scene_path, out, plot) = (a.scene.as_path(), a.out.as_path(), a.plot.as_deref());
    let any = scene::load_any(scene_path).map_err(|e| e.to_string())?;
    // Before the run (it was found after it, its files written and an arch's chart drawn).
    let history = match &any {
        scene::AnyScene::Column(s) => s.output.history,
        scene::AnyScene::Loop(s) => s.output.history,
    };
    if plot.is_some() && !history {
        return Err("--plot needs the history (output.history must be true)".into());
    }
    // The folder and the chart before the run, which can be long (drums, records).
    check_writable("--out", &out.join("summary.json"))?;
    if let Some(p) = plot {
        check_writable("--plot", p)?;
    }
    let scene = match any {
        scene::AnyScene::Column(scene) => scene,
        scene::AnyScene::Loop(scene) => {
            return super::simulate_loop::run(&scene, scene_path, out, plot)
        }
    };
    if scene.contact.is_some() {
        return super::simulate_drums::run(&scene, scene_path, out, plot);
    }
    let excitation = &scene.excitation;
    let motion = FnMotion(|t| excitation.acceleration(t), excitation.end_time());
    let bar = progress::bar(1000, "simulating");
    let mut report = |fraction: f64| bar.set_position((fraction * 1000.0) as u64);
    let started = Instant::now();
    let outcome = driver::simulate(&scene.column, &motion, &scene.options, Some(&mut report))
        .map_err(|e| e.to_string())?;
    let wall = started.elapsed().as_secs_f64();
    bar.finish_and_clear();

    if scene.output.history {
        if let Some(h) = &outcome.history {
            write_atomic_with(&out.join("history.csv"), |w| write_history_csv(w, h))?;
        }
    }
    if scene.output.events {
        let mut lines = String::new();
        for e in &outcome.events {
            lines.push_str(&json_tree(e)?.to_string());
            lines.push('\n');
        }
        write_atomic(&out.join("events.jsonl"), lines.as_bytes())?;
    }
    let summary = json_tree(&Summary::of(
        &scene,
        Some(scene_path.display().to_string()),
        &outcome,
        wall,
    ))?;
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    crate::output::remove_unwritten(out, &scene.output)?;
    write_atomic(&out.join("summary.json"), format!("{text}\n").as_bytes())?;
    if let Some(p) = plot {
        chart(&scene, &outcome)?.write(p)?;
    }
    println!(
        "{}: {} at t = {:.4} s, {} impacts, {} events; {} ({:.3} s wall) -> {}",
        scene.title,
        stop_text(&outcome.stop_reason),
        outcome.t_end,
        outcome.impacts,
        outcome.events.len(),
        peaks_text(&outcome.peak_block_rotation),
        wall,
        out.display()
    );
    Ok(())
}

/// The peak block rotations for the summary line: every block's of a short column, the largest
/// of a long one (all of them are in `summary.json`).
fn peaks_text(peaks: &[f64]) -> String {
    const LISTED: usize = 12;
    if peaks.len() <= LISTED {
        let rounded: Vec<f64> = peaks.iter().map(|v| (v * 1e4).round() / 1e4).collect();
        return format!("peak block rotations {rounded:?} rad");
    }
    let (block, peak) = peaks
        .iter()
        .enumerate()
        .fold((0, 0.0_f64), |(kb, pb), (k, &p)| {
            if p.abs() > pb.abs() {
                (k, p)
            } else {
                (kb, pb)
            }
        });
    format!(
        "largest peak block rotation {peak:.4e} rad (block {block} of {}; all in summary.json)",
        peaks.len()
    )
}

/// The history as CSV: per interface its signed angle and rate (`phĭ + phî`), per block its
/// absolute rotation, per interface its status.
pub fn write_history_csv<W: Write>(w: &mut W, h: &driver::History) -> std::io::Result<()> {
    let n = h.n_interfaces;
    w.write_all(b"t")?;
    for k in 0..n {
        write!(w, ",angle_{k}")?;
    }
    for k in 0..n {
        write!(w, ",rate_{k}")?;
    }
    for k in 0..n {
        write!(w, ",block_rotation_{k}")?;
    }
    for k in 0..n {
        write!(w, ",status_{k}")?;
    }
    w.write_all(b"\n")?;
    for i in 0..h.len() {
        write!(w, "{}", h.t[i])?;
        let phi = h.phi_at(i);
        let rates = &h.rates[i * 2 * n..(i + 1) * 2 * n];
        for k in 0..n {
            write!(w, ",{}", phi[k] + phi[n + k])?;
        }
        for k in 0..n {
            write!(w, ",{}", rates[k] + rates[n + k])?;
        }
        for v in h.block_angles_at(i) {
            write!(w, ",{v}")?;
        }
        for st in &h.statuses[i * n..(i + 1) * n] {
            write!(w, ",{}", st.as_i8())?;
        }
        w.write_all(b"\n")?;
    }
    Ok(())
}

fn stop_text(s: &StopReason) -> String {
    match s {
        StopReason::Duration => "end of duration".into(),
        StopReason::Overturned { interface } => format!("overturned at interface {interface}"),
        StopReason::Fallen { interface } => format!("fallen at interface {interface}"),
        StopReason::Sliding { interface } => format!("sliding at interface {interface}"),
        StopReason::Tension { interface } => format!("tension at interface {interface}"),
        StopReason::TooManyEvents => "too many events (cap reached)".into(),
        StopReason::AtRest => "at rest for good (the ground can no longer open the column)".into(),
        StopReason::CannotTip => {
            "safe for good (the rest of the ground motion cannot tip the block)".into()
        }
    }
}

fn chart(scene: &Scene, o: &Outcome) -> Result<Chart, String> {
    let h = o
        .history
        .as_ref()
        .ok_or("--plot needs the history (output.history must be true)")?;
    let n = h.n_interfaces;
    let mut chart = Chart {
        title: format!("{} — {}", scene.title, scene.excitation.describe()),
        x_label: "t [s]".into(),
        y_label: "block rotation [rad]".into(),
        ..Chart::default()
    };
    // Blocks with the same rotation throughout (a column rocking as one) are one line with one
    // legend entry: drawn one over the other, all but the last were invisible while the
    // legend listed each.
    type Group = (Vec<usize>, Vec<(f64, f64)>);
    let mut groups: Vec<Group> = Vec::new();
    for k in 0..n {
        let points: Vec<(f64, f64)> = (0..h.len())
            .map(|i| (h.t[i], h.block_angles_at(i)[k]))
            .collect();
        match groups.iter_mut().find(|(_, p)| *p == points) {
            Some((blocks, _)) => blocks.push(k),
            None => groups.push((vec![k], points)),
        }
    }
    for (blocks, points) in groups {
        let name = match blocks.as_slice() {
            [k] => member_name("block", *k, n),
            _ => {
                let list: Vec<String> = blocks.iter().map(usize::to_string).collect();
                format!("blocks {} (as one)", list.join(", "))
            }
        };
        chart.series.push(Series {
            name,
            points,
            style: Style::Line,
            color: member_color(blocks[0], n),
        });
    }
    for e in &o.events {
        let color = match e.kind {
            EventKind::Impact => COLORS[1],
            EventKind::Opening => COLORS[2],
            EventKind::Settled => COLORS[7],
            _ => (0, 0, 0),
        };
        chart.markers.push(Marker {
            x: e.t,
            kind: e.kind.name().to_string(),
            color,
        });
    }
    Ok(chart)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A column of twelve drums on the event-driven driver: twelve colours (the palette
    /// repeated every eight) and seven named in the legend; the event kinds keep their colours.
    /// Every joint starts open (1 mrad), so that no two drums turn alike (drums
    /// rocking as one are one line).
    #[test]
    fn a_tall_column_chart_tells_its_blocks_apart() {
        let blocks = [r#"{"width": 1, "height": 1, "mass": 2500}"#; 12].join(",");
        let angles = ["0.001"; 12].join(",");
        let text = format!(
            r#"{{"blocks": [{blocks}], "duration": 1.0, "dt": 0.001,
                "initial_angles": [{angles}],
                "excitation": {{"type": "half_sine", "amplitude": 6.0, "duration": 0.5}}}}"#
        );
        let spec = rocking::scene::parse(&text).unwrap();
        let scene = scene::build(spec, std::path::Path::new("."), "test").unwrap();
        let e = &scene.excitation;
        let motion = FnMotion(|t| e.acceleration(t), e.end_time());
        let o = driver::simulate(&scene.column, &motion, &scene.options, None).unwrap();
        let c = chart(&scene, &o).unwrap();
        let mut colors: Vec<_> = c.series.iter().map(|s| s.color).collect();
        colors.sort_unstable();
        colors.dedup();
        assert_eq!(colors.len(), 12);
        let named = c.series.iter().filter(|s| !s.name.is_empty()).count();
        assert_eq!(named, crate::plot::palette::MAX_NAMED);
        assert!(c
            .markers
            .iter()
            .all(|m| m.kind != "impact" || m.color == COLORS[1]));
    }
}
