//! `rocking bench drums`: the drum suite of docs/multidrum.md — columns of 3, 5, 10 and 20
//! equal drums (w × h = 1 × 0.5, 1 × 1, 1.5 × 1, 1 × 2; mass 2500 w h) under the FEMA P695
//! far-field records scaled to 2, 4 and 6 m/s², μ = 0.5 and 0.7, each to the end of its record,
//! with the Moreau–Jean scheme of `rocking::contact` (sliding and flight allowed, the thesis's
//! two-impact law at located impacts, dt = 1 ms).
//!
//! Prints (Markdown) how the runs ended, the energy residuals, per column the overturned runs,
//! peaks, slips and run times, and with `--halve` the spread of the results when dt halves.
//! `--csv` writes one line per run. `--quick` is the reduced form CI runs: the first three
//! records, 3, 5 and 10 drums of 1 × 1 and 1 × 2, 4 m/s², μ = 0.5. Runs are spread over
//! threads (rayon) and over processes with `--shard i/n`; every run is deterministic and the
//! results do not depend on either.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rayon::prelude::*;
use rocking::contact::simulation::{simulate, DrumOptions, DrumStop};
use rocking::ground::excitation::Excitation;
use rocking::ground::records::{read_at2, Record};
use rocking::model::column::{Block, Column};

use crate::commands::sweep::{count, positive, set_threads, Shard};
use crate::output::{check_writable, write_atomic};
use crate::progress;

/// Options of `rocking bench drums`.
#[derive(Args, Debug)]
pub struct DrumsBenchArgs {
    /// Folder of `.AT2` records (all of them, in name order).
    #[arg(long, default_value = "../shared/records/fema-p695/farfield")]
    pub records: PathBuf,
    /// The reduced suite of CI (first three records, 3/5/10 drums of 1 x 1 and 1 x 2, 4 m/s²,
    /// μ = 0.5); the lists below still override it.
    #[arg(long)]
    pub quick: bool,
    /// Only the first N records.
    #[arg(long, value_parser = count)]
    pub limit: Option<usize>,
    /// Numbers of drums, e.g. 3,5,10,20.
    #[arg(long, value_delimiter = ',')]
    pub drums: Option<Vec<usize>>,
    /// Drum shapes WxH, e.g. 1x0.5,1x1,1.5x1,1x2.
    #[arg(long, value_delimiter = ',', value_parser = shape)]
    pub shapes: Option<Vec<(f64, f64)>>,
    /// Peak ground accelerations (m/s²).
    #[arg(long, value_delimiter = ',', value_parser = positive)]
    pub pga: Option<Vec<f64>>,
    /// Friction coefficients (> 0; `inf`: no sliding).
    #[arg(long, value_delimiter = ',', value_parser = friction)]
    pub mu: Option<Vec<f64>>,
    /// Time step (s).
    #[arg(long, default_value_t = 1e-3)]
    pub dt: f64,
    /// Run every case again at dt / 2 and report the spread.
    #[arg(long)]
    pub halve: bool,
    /// The scheme's error control: a step whose energy error exceeds this fraction of the run's
    /// energy scale is redone as two halves (down to dt / 64); the CSV gains the columns
    /// `refined,refine_floor`.
    #[arg(long)]
    pub energy_tol: Option<f64>,
    /// The scheme's located impacts without their one-signed energy errors
    /// (`SchemeOptions::energy_consistent`, docs/energy-control.md); with `--energy-tol`, both.
    #[arg(long)]
    pub consistent: bool,
    /// Threads (default: every core).
    #[arg(long, value_parser = crate::commands::sweep::threads)]
    pub threads: Option<usize>,
    /// Run only the cases `k` with `k % n == i` (`i/n`).
    #[arg(long, default_value = "0/1")]
    pub shard: Shard,
    /// One line per run (CSV).
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Also write the report to this file.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// `values` without repeats, in their first order.
fn distinct<T: PartialEq>(values: Vec<T>) -> Vec<T> {
    let mut out: Vec<T> = Vec::with_capacity(values.len());
    for v in values {
        if !out.contains(&v) {
            out.push(v);
        }
    }
    out
}

/// A friction coefficient: a number > 0, infinity (no sliding) included; checked with the
/// other arguments, before any run (a NaN or 0 failed in the first run of that μ, naming the
/// scheme's option, not `--mu`).
fn friction(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(mu) if mu > 0.0 => Ok(mu),
        _ => Err(format!(
            "{s}: a friction coefficient must be a number > 0 (inf: no sliding)"
        )),
    }
}

fn shape(s: &str) -> Result<(f64, f64), String> {
    let (w, h) = s
        .split_once('x')
        .ok_or_else(|| format!("expected WxH, got {s}"))?;
    let parse = |v: &str| match v.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("{v}: a size must be a number > 0")),
    };
    Ok((parse(w)?, parse(h)?))
}

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
    refined: u64,
    refine_floor: u64,
    cpu: f64,
}

fn run_case(
    case: &Case,
    rec: &Record,
    dt: f64,
    tol: Option<f64>,
    consistent: bool,
) -> Result<Run, String> {
    let col = Column::new(
        (0..case.n)
            .map(|_| Block::rectangle(case.w, case.h, 2500.0 * case.w * case.h))
            .collect(),
    )
    .map_err(|e| e.to_string())?;
    let motion = Excitation::record(rec.scaled_to_pga(case.pga).map_err(|e| e.to_string())?)
        .map_err(|e| e.to_string())?;
    let duration = rec.duration();
    let mut opts = DrumOptions {
        dt,
        ..DrumOptions::quiet(duration, case.mu, 2)
    };
    opts.scheme.energy_tolerance = tol;
    opts.scheme.energy_consistent = consistent;
    let t0 = Instant::now();
    let out = simulate(&col, &motion, &opts, None).map_err(|e| e.to_string())?;
    let cpu = t0.elapsed().as_secs_f64();
    let max_abs = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let e = out.energy;
    Ok(Run {
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
        refined: out.counters.refined,
        refine_floor: out.counters.refine_floor,
        cpu,
    })
}

/// How a run ended, as the report and the CSV name it.
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

/// Runs the benchmark.
pub fn run(args: &DrumsBenchArgs) -> Result<(), String> {
    if let Some(n) = args.threads {
        set_threads(n);
    }
    for (flag, path) in [("--csv", &args.csv), ("--out", &args.out)] {
        if let Some(p) = path {
            check_writable(flag, p)?;
        }
    }
    if !(args.dt.is_finite() && args.dt > 0.0) {
        return Err(format!("--dt: {}: must be a number > 0", args.dt));
    }
    if let Some(tol) = args.energy_tol {
        if !(tol.is_finite() && tol > 0.0) {
            return Err(format!("--energy-tol: {tol}: must be a number > 0"));
        }
    }
    // The default is where the FEMA P695 records are on the machines of docs/multidrum.md; a
    // fresh clone has none there (they are not in the repository).
    let mut files: Vec<PathBuf> = std::fs::read_dir(&args.records)
        .map_err(|e| {
            format!(
                "--records {}: {e}: give the folder of the records, PEER .AT2 files (the suite of \
                 docs/multidrum.md: the 44 FEMA P695 far-field records; any folder of .AT2 \
                 records runs, e.g. --records examples/records)",
                args.records.display()
            )
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| rocking::ground::records::is_at2(p))
        .collect();
    files.sort();
    let (drums, shapes, pgas, mus, limit) = if args.quick {
        (
            vec![3, 5, 10],
            vec![(1.0, 1.0), (1.0, 2.0)],
            vec![4.0],
            vec![0.5],
            3,
        )
    } else {
        (
            vec![3, 5, 10, 20],
            vec![(1.0, 0.5), (1.0, 1.0), (1.5, 1.0), (1.0, 2.0)],
            vec![2.0, 4.0, 6.0],
            vec![0.5, 0.7],
            usize::MAX,
        )
    };
    files.truncate(args.limit.unwrap_or(limit));
    if files.is_empty() {
        return Err(format!(
            "--records {}: no .AT2 record found",
            args.records.display()
        ));
    }
    // Each value once: a value given twice ran every case twice and counted it twice.
    let drums = distinct(args.drums.clone().unwrap_or(drums));
    if drums.contains(&0) {
        return Err("--drums: a column needs at least one drum".into());
    }
    // Before any run (it failed in the first run of that size, as '5000 blocks: …', after the
    // runs of the sizes before it).
    let max = rocking::model::configuration::MAX_INTERFACES;
    if let Some(n) = drums.iter().find(|&&n| n > max) {
        return Err(format!("--drums: {n}: a column has at most {max} drums"));
    }
    let shapes = distinct(args.shapes.clone().unwrap_or(shapes));
    let pgas = distinct(args.pga.clone().unwrap_or(pgas));
    let mus = distinct(args.mu.clone().unwrap_or(mus));
    let records = files
        .iter()
        .map(|p| read_at2(p).map_err(|e| format!("{}: {e}", p.display())))
        .collect::<Result<Vec<Record>, String>>()?;
    // A step longer than a record's own skips its samples (as a scene's `dt` is refused).
    if let Some(r) = records.iter().find(|r| args.dt > r.dt * (1.0 + 1e-9)) {
        return Err(format!(
            "--dt: {:?}: more than the step of {} ({:?} s): at most that, or the record's samples \
             between two steps are skipped",
            args.dt, r.name, r.dt
        ));
    }
    // The scheme's step limit, before any run (it failed in the first run, as a drum option).
    let finest = if args.halve { 0.5 * args.dt } else { args.dt };
    if let Some(r) = records
        .iter()
        .find(|r| rocking::validate::too_many_steps(r.duration(), finest))
    {
        return Err(format!(
            "--dt: {:?}: more than 1e10 steps for {} ({:?} s)",
            args.dt,
            r.name,
            r.duration()
        ));
    }
    let mut cases = Vec::new();
    for r in 0..records.len() {
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
    let cases = args.shard.keep(&cases);
    let steps: Vec<f64> = if args.halve {
        vec![args.dt, 0.5 * args.dt]
    } else {
        vec![args.dt]
    };
    let bar = progress::bar(cases.len() as u64, "drum columns");
    let wall = Instant::now();
    let results = cases
        .par_iter()
        .map(|c| {
            let runs = steps
                .iter()
                .map(|&d| run_case(c, &records[c.record], d, args.energy_tol, args.consistent))
                .collect::<Result<Vec<Run>, String>>();
            bar.inc(1);
            runs
        })
        .collect::<Result<Vec<Vec<Run>>, String>>()?;
    let wall = wall.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let mut text = report(&results, &files, wall, rayon::current_num_threads());
    if let Some(tol) = args.energy_tol {
        let runs = results.iter().flatten();
        let (refined, floor) = runs.fold((0, 0), |(a, b), r| (a + r.refined, b + r.refine_floor));
        let _ = writeln!(
            text,
            "\nError control (energy tolerance {tol:e} of the run's scale per step): {refined} \
             steps redone as two halves, {floor} kept at dt / 64 above the tolerance."
        );
    }
    if args.consistent {
        let _ = writeln!(
            text,
            "\nLocated impacts without their one-signed energy errors (--consistent)."
        );
    }
    print!("{text}");
    if let Some(out) = &args.out {
        write_atomic(out, text.as_bytes())?;
    }
    if let Some(p) = &args.csv {
        write_atomic(
            p,
            csv(&results, &files, args.energy_tol.is_some()).as_bytes(),
        )?;
    }
    Ok(())
}

fn quantile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

fn report(results: &[Vec<Run>], files: &[PathBuf], wall: f64, threads: usize) -> String {
    let mut s = String::new();
    let first: Vec<&Run> = results.iter().map(|r| &r[0]).collect();
    let cpu: f64 = results.iter().flatten().map(|r| r.cpu).sum();
    let _ = writeln!(
        s,
        "{} runs ({} records), wall {wall:.1} s on {threads} threads, run time summed {cpu:.1} s\n",
        results.iter().map(Vec::len).sum::<usize>(),
        files.len()
    );
    if first.is_empty() {
        return s;
    }
    let mut by_stop: BTreeMap<&str, usize> = BTreeMap::new();
    for r in &first {
        *by_stop.entry(stop_name(&r.stop)).or_default() += 1;
    }
    let _ = writeln!(
        s,
        "How the runs ended (dt = {} s): {by_stop:?}\n",
        first[0].dt
    );
    let worst = first
        .iter()
        .max_by(|a, b| a.energy_error.abs().total_cmp(&b.energy_error.abs()))
        .unwrap();
    let over = first.iter().filter(|r| r.energy_error.abs() > 1e-3).count();
    let _ = writeln!(
        s,
        "Energy residual (ground work − ΔV − ΔT − impacts − friction, of the largest energy): \
         largest {:.2e} ({} drums {}x{} {} {} m/s² μ {}), {over} runs above 1e-3; closure (with \
         the scheme's own terms) largest {:.1e}. Contact problems that needed a fallback: {}.\n",
        worst.energy_error,
        worst.case.n,
        worst.case.w,
        worst.case.h,
        file_stem(files, worst.case.record),
        worst.case.pga,
        worst.case.mu,
        first.iter().map(|r| r.closure.abs()).fold(0.0, f64::max),
        first.iter().map(|r| r.fallbacks).sum::<u64>()
    );
    s.push_str(
        "| drums | w × h | runs | overturned | slid off | end of record | max peak rotation | \
         max residual slip (m) | median energy residual | mean run time (ms) |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
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
        let mut energy: Vec<f64> = rs.iter().map(|r| r.energy_error.abs()).collect();
        energy.sort_by(f64::total_cmp);
        let _ = writeln!(
            s,
            "| {n} | {} × {} | {} | {} | {} | {} | {:.3} | {:.4} | {:.1e} | {:.1} |",
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
            quantile(&energy, 0.5),
            1e3 * rs.iter().map(|r| r.cpu).sum::<f64>() / rs.len() as f64,
        );
    }
    if results.iter().all(|r| r.len() == 2) {
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
        let _ = writeln!(
            s,
            "\ndt halved: verdicts agree in {same} of {} runs; surviving runs ({}): peak rotation \
             relative change median {:.3}, 90 % {:.3}, max {:.3}; residual slip change (m) median \
             {:.1e}, 90 % {:.1e}, max {:.1e}",
            pairs.len(),
            survived.len(),
            quantile(&peak, 0.5),
            quantile(&peak, 0.9),
            quantile(&peak, 1.0),
            quantile(&slip, 0.5),
            quantile(&slip, 0.9),
            quantile(&slip, 1.0)
        );
    }
    s
}

fn file_stem(files: &[PathBuf], i: usize) -> String {
    files[i]
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn csv(results: &[Vec<Run>], files: &[PathBuf], refine: bool) -> String {
    let mut s = String::from(
        "record,drums,w,h,pga,mu,dt,stop,t_end,duration,overturned,peak_rotation,peak_top,\
         residual_slip,peak_slip,energy_error,closure,impacts,slip_starts,lift_offs,fallbacks,cpu_s",
    );
    s.push_str(if refine {
        ",refined,refine_floor\n"
    } else {
        "\n"
    });
    for r in results.iter().flatten() {
        let c = &r.case;
        let _ = write!(
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
        if refine {
            let _ = write!(s, ",{},{}", r.refined, r.refine_floor);
        }
        s.push('\n');
    }
    s
}
