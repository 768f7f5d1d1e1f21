//! The drum suite of issue 11: columns of 3, 5, 10 and 20 equal drums (w × h = 1 × 0.5, 1 × 1,
//! 1.5 × 1, 1 × 2; mass 2500 w h) under the FEMA P695 far-field records scaled to 2, 4 and
//! 6 m/s², μ = 0.5 and 0.7, each to the end of its record, with the Moreau–Jean scheme of
//! `rocking::contact` (sliding and flight allowed).
//!
//! ```text
//! cargo run --release --example drum_suite -- [--records DIR] [--limit N] [--drums 3,5,10,20]
//!     [--shapes 1x0.5,1x1,1.5x1,1x2] [--pga 2,4,6] [--mu 0.5,0.7] [--dt 0.001] [--halve]
//!     [--threads 2] [--shard I/K] [--out runs.csv]
//! ```
//!
//! Prints how the runs ended, the largest energy residuals, and with `--halve` the spread of the
//! results when the step is halved; `--out` writes one line per run. Runs are sharded over
//! threads (and over processes with `--shard`); every run is deterministic.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use rocking::contact::simulation::{simulate, DrumOptions, DrumRecording, DrumStop};
use rocking::ground::excitation::Excitation;
use rocking::ground::records::{read_at2, Record};
use rocking::model::column::{Block, Column};

#[derive(Clone, Debug)]
struct Case {
    record: usize,
    n: usize,
    w: f64,
    h: f64,
    pga: f64,
    mu: f64,
}

#[derive(Clone, Debug)]
struct Run {
    case: Case,
    dt: f64,
    stop: DrumStop,
    t_end: f64,
    duration: f64,
    overturned: bool,
    peak_rotation: f64,
    peak_top: f64,
    residual_slip: f64,
    peak_slip: f64,
    energy_error: f64,
    closure: f64,
    impacts: usize,
    slips: usize,
    lift_offs: usize,
    fallbacks: u64,
    cpu: f64,
}

fn parse_list(s: &str) -> Vec<f64> {
    s.split(',')
        .map(|x| x.trim().parse().expect("a number"))
        .collect()
}

fn run(case: &Case, rec: &Record, dt: f64) -> Run {
    let col = Column::new(
        (0..case.n)
            .map(|_| Block::rectangle(case.w, case.h, 2500.0 * case.w * case.h))
            .collect(),
    )
    .unwrap();
    let motion = Excitation::record(rec.scaled_to_pga(case.pga).unwrap()).unwrap();
    let duration = rec.duration();
    let opts = DrumOptions {
        dt,
        duration,
        friction: case.mu,
        record: DrumRecording {
            history_every: None,
            events: false,
        },
        ..DrumOptions::default()
    };
    let t0 = Instant::now();
    let out = simulate(&col, &motion, &opts, None).unwrap();
    let cpu = t0.elapsed().as_secs_f64();
    let max_abs = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let e = out.energy;
    Run {
        case: case.clone(),
        dt,
        stop: out.stop,
        t_end: out.t_end,
        duration,
        overturned: out.overturned,
        peak_rotation: max_abs(&out.peak_rotation),
        peak_top: out.peak_top_displacement,
        residual_slip: max_abs(&out.residual_slip),
        peak_slip: max_abs(&out.peak_slip),
        energy_error: e.residual() / e.scale(),
        closure: e.closure() / e.scale(),
        impacts: out.event_counts[1],
        slips: out.event_counts[2],
        lift_offs: out.event_counts[4],
        fallbacks: out.counters.fallbacks,
        cpu,
    }
}

fn stop_name(s: &DrumStop) -> &'static str {
    match s {
        DrumStop::Duration => "end of record",
        DrumStop::Overturned { .. } => "overturned",
        DrumStop::Fallen { .. } => "fallen",
        DrumStop::SlidOff { .. } => "slid off",
        DrumStop::Sliding { .. } => "sliding (stop)",
        DrumStop::Tension { .. } => "tension (stop)",
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let mut dir = PathBuf::from("../shared/records/fema-p695/farfield");
    let mut limit = usize::MAX;
    let mut drums = vec![3usize, 5, 10, 20];
    let mut shapes = vec![(1.0, 0.5), (1.0, 1.0), (1.5, 1.0), (1.0, 2.0)];
    let mut pgas = vec![2.0, 4.0, 6.0];
    let mut mus = vec![0.5, 0.7];
    let mut dt = 1e-3;
    let mut halve = false;
    let mut threads = 2usize;
    let mut shard = (0usize, 1usize);
    let mut out_path: Option<PathBuf> = None;
    while let Some(a) = args.next() {
        let mut val = || args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--records" => dir = PathBuf::from(val()),
            "--limit" => limit = val().parse().unwrap(),
            "--drums" => drums = parse_list(&val()).iter().map(|&x| x as usize).collect(),
            "--shapes" => {
                shapes = val()
                    .split(',')
                    .map(|s| {
                        let (w, h) = s.split_once('x').expect("WxH");
                        (w.parse().unwrap(), h.parse().unwrap())
                    })
                    .collect()
            }
            "--pga" => pgas = parse_list(&val()),
            "--mu" => mus = parse_list(&val()),
            "--dt" => dt = val().parse().unwrap(),
            "--halve" => halve = true,
            "--threads" => threads = val().parse().unwrap(),
            "--shard" => {
                let v = val();
                let (i, k) = v.split_once('/').expect("I/K");
                shard = (i.parse().unwrap(), k.parse().unwrap());
            }
            "--out" => out_path = Some(PathBuf::from(val())),
            other => panic!("unknown argument {other}"),
        }
    }
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("at2")))
        .collect();
    files.sort();
    files.truncate(limit);
    let records: Vec<Record> = files.iter().map(|p| read_at2(p).unwrap()).collect();
    let mut cases = Vec::new();
    for (r, _) in records.iter().enumerate() {
        for &n in &drums {
            for &(w, h) in &shapes {
                for &pga in &pgas {
                    for &mu in &mus {
                        cases.push(Case {
                            record: r,
                            n,
                            w,
                            h,
                            pga,
                            mu,
                        });
                    }
                }
            }
        }
    }
    // Longest first (20 drums, long records) for a better balance between threads.
    cases.sort_by(|a, b| {
        let ka = a.n as f64 * records[a.record].duration();
        let kb = b.n as f64 * records[b.record].duration();
        kb.partial_cmp(&ka).unwrap()
    });
    let cases: Vec<Case> = cases
        .into_iter()
        .enumerate()
        .filter(|(i, _)| i % shard.1 == shard.0)
        .map(|(_, c)| c)
        .collect();
    let steps: Vec<f64> = if halve { vec![dt, 0.5 * dt] } else { vec![dt] };
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Vec<Run>>> = Mutex::new(vec![Vec::new(); cases.len()]);
    let wall = Instant::now();
    std::thread::scope(|s| {
        for _ in 0..threads.max(1) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= cases.len() {
                    break;
                }
                let c = &cases[i];
                let runs: Vec<Run> = steps
                    .iter()
                    .map(|&d| run(c, &records[c.record], d))
                    .collect();
                results.lock().unwrap()[i] = runs;
            });
        }
    });
    let wall = wall.elapsed().as_secs_f64();
    let results = results.into_inner().unwrap();
    report(&results, &files, wall, threads, halve);
    if let Some(p) = out_path {
        write_csv(&p, &results, &files);
    }
}

fn report(results: &[Vec<Run>], files: &[PathBuf], wall: f64, threads: usize, halve: bool) {
    let first: Vec<&Run> = results.iter().map(|r| &r[0]).collect();
    let cpu: f64 = results.iter().flatten().map(|r| r.cpu).sum();
    println!(
        "{} runs ({} records), wall {wall:.1} s on {threads} threads, run time summed {cpu:.1} s",
        results.iter().map(Vec::len).sum::<usize>(),
        files.len()
    );
    let mut by_stop: std::collections::BTreeMap<&str, usize> = Default::default();
    for r in &first {
        *by_stop.entry(stop_name(&r.stop)).or_default() += 1;
    }
    println!("how the runs ended (dt = {}): {by_stop:?}", first[0].dt);
    let worst = first
        .iter()
        .max_by(|a, b| a.energy_error.abs().total_cmp(&b.energy_error.abs()))
        .unwrap();
    let over = first.iter().filter(|r| r.energy_error.abs() > 1e-3).count();
    println!(
        "energy error (ground work − ΔV − ΔT − impacts − friction, of the scale): largest {:.2e} ({} drums {}x{} {} {} m/s² μ {}), {over} runs above 1e-3; closure (with the scheme's own terms) largest {:.1e}",
        worst.energy_error,
        worst.case.n,
        worst.case.w,
        worst.case.h,
        file_stem(files, worst.case.record),
        worst.case.pga,
        worst.case.mu,
        first.iter().map(|r| r.closure.abs()).fold(0.0, f64::max)
    );
    let falls: u64 = first.iter().map(|r| r.fallbacks).sum();
    println!("contact problems that needed a fallback: {falls}");
    // Per column.
    let mut table = String::new();
    let _ = writeln!(
        table,
        "| drums | w × h | runs | overturned | slid off | end of record | max peak rotation | max residual slip (m) | mean run time (ms) |"
    );
    let _ = writeln!(table, "|---|---|---|---|---|---|---|---|---|");
    let mut keys: Vec<(usize, u64, u64)> = first
        .iter()
        .map(|r| (r.case.n, r.case.w.to_bits(), r.case.h.to_bits()))
        .collect();
    keys.sort();
    keys.dedup();
    for (n, w, h) in keys {
        let rs: Vec<&&Run> = first
            .iter()
            .filter(|r| r.case.n == n && r.case.w.to_bits() == w && r.case.h.to_bits() == h)
            .collect();
        let count = |f: &dyn Fn(&Run) -> bool| rs.iter().filter(|r| f(r)).count();
        let _ = writeln!(
            table,
            "| {n} | {} × {} | {} | {} | {} | {} | {:.3} | {:.4} | {:.1} |",
            f64::from_bits(w),
            f64::from_bits(h),
            rs.len(),
            count(&|r| matches!(
                r.stop,
                DrumStop::Overturned { .. } | DrumStop::Fallen { .. }
            )),
            count(&|r| matches!(r.stop, DrumStop::SlidOff { .. })),
            count(&|r| matches!(r.stop, DrumStop::Duration)),
            rs.iter().map(|r| r.peak_rotation).fold(0.0, f64::max),
            rs.iter().map(|r| r.residual_slip).fold(0.0, f64::max),
            1e3 * rs.iter().map(|r| r.cpu).sum::<f64>() / rs.len() as f64,
        );
    }
    print!("{table}");
    if halve {
        let pairs: Vec<(&Run, &Run)> = results.iter().map(|r| (&r[0], &r[1])).collect();
        let same = pairs
            .iter()
            .filter(|(a, b)| a.overturned == b.overturned)
            .count();
        let survived: Vec<&(&Run, &Run)> = pairs
            .iter()
            .filter(|(a, b)| !a.overturned && !b.overturned)
            .collect();
        let rel = |a: f64, b: f64, floor: f64| (a - b).abs() / b.abs().max(floor);
        let mut peak: Vec<f64> = survived
            .iter()
            .map(|(a, b)| rel(a.peak_rotation, b.peak_rotation, 1e-3))
            .collect();
        let mut slip: Vec<f64> = survived
            .iter()
            .map(|(a, b)| (a.residual_slip - b.residual_slip).abs())
            .collect();
        peak.sort_by(f64::total_cmp);
        slip.sort_by(f64::total_cmp);
        let q = |v: &[f64], p: f64| {
            if v.is_empty() {
                f64::NAN
            } else {
                v[((v.len() - 1) as f64 * p).round() as usize]
            }
        };
        println!(
            "dt halved: verdicts agree in {same} of {} runs; surviving runs ({}): peak rotation relative change median {:.3}, 90 % {:.3}, max {:.3}; residual slip change (m) median {:.1e}, 90 % {:.1e}, max {:.1e}",
            pairs.len(),
            survived.len(),
            q(&peak, 0.5),
            q(&peak, 0.9),
            q(&peak, 1.0),
            q(&slip, 0.5),
            q(&slip, 0.9),
            q(&slip, 1.0)
        );
    }
}

fn file_stem(files: &[PathBuf], i: usize) -> String {
    files[i]
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn write_csv(path: &Path, results: &[Vec<Run>], files: &[PathBuf]) {
    let mut s = String::from(
        "record,drums,w,h,pga,mu,dt,stop,t_end,duration,overturned,peak_rotation,peak_top,residual_slip,peak_slip,energy_error,closure,impacts,slip_starts,lift_offs,fallbacks,cpu_s\n",
    );
    for r in results.iter().flatten() {
        let c = &r.case;
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{:.4},{:.4},{},{:.6},{:.6},{:.6},{:.6},{:.3e},{:.3e},{},{},{},{},{:.4}",
            file_stem(files, c.record),
            c.n,
            c.w,
            c.h,
            c.pga,
            c.mu,
            r.dt,
            stop_name(&r.stop),
            r.t_end,
            r.duration,
            r.overturned,
            r.peak_rotation,
            r.peak_top,
            r.residual_slip,
            r.peak_slip,
            r.energy_error,
            r.closure,
            r.impacts,
            r.slips,
            r.lift_offs,
            r.fallbacks,
            r.cpu
        );
    }
    std::fs::write(path, s).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}
