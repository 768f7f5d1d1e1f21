//! `rocking bench spectra`: wall time of the overturning acceleration spectrum of records with
//! the thesis's grid (80 levels × 120 sizes, H/B = 12, scan from the largest size), against the
//! target of the issue (≤ 5 s per record on a 2-core machine). With `--compare`, each record is
//! run a second time with every simulation run to its end (`--full-runs` of `rocking oas`): the
//! speed ratio of the energy-bound stop measured in the same process, and a check that both
//! spectra are identical. Each OAS is reported with its wall and its CPU time (the process, every
//! thread) and the load average: on a shared machine the CPU ratio is the steadier figure.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use rocking::ground::records::{parse_at2, read_record, PlainFormat, Record};
use rocking::spectra::{self, OasOptions};

use crate::output::write_atomic;
use crate::progress;

/// Options of `rocking bench spectra`.
#[derive(Args, Debug)]
pub struct SpectraBenchArgs {
    /// Records (.AT2 or plain text); none: the bundled synthetic record.
    pub records: Vec<PathBuf>,
    /// Run each record again with every simulation run to its end (no energy-bound stop):
    /// the speed ratio, and a check that both spectra are identical.
    #[arg(long)]
    pub compare: bool,
    /// Also write the Markdown report to this file.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Threads (default: every core).
    #[arg(long, value_parser = crate::commands::sweep::threads)]
    pub threads: Option<usize>,
    /// Run each record again with the time step rule scaled by this factor (e.g. 0.5): the
    /// cost of a finer default step, and t₁ at both steps (convergence).
    #[arg(long = "dt-factor", value_parser = crate::commands::sweep::positive)]
    pub dt_factor: Option<f64>,
    /// Also t₁ converged in the step as `rocking t1` computes it by default (halving the step
    /// until two t₁ agree within TOL, e.g. 0.1, at most four times): its cost against the one
    /// OAS at the step rule (`rocking t1 --single-step`), wall and CPU.
    #[arg(long, value_name = "TOL", value_parser = crate::commands::sweep::non_negative)]
    pub converge_step: Option<f64>,
    /// Equal blocks in the column (thesis Fig. 43: 1, 2, 3).
    #[arg(long, default_value_t = 1, value_parser = crate::commands::sweep::count)]
    pub blocks: usize,
    /// Consecutive impacts per closing (1: Housner; 2: the thesis's recommended model).
    #[arg(long, default_value_t = 1, value_parser = crate::commands::sweep::count)]
    pub impacts: usize,
    /// The exact Lagrangian equations (velocity terms) instead of thesis Eq. 6.
    #[arg(long)]
    pub lagrangian: bool,
    /// With --lagrangian and several blocks: force the column's energy-bound stop (the default
    /// where it is certified: 2 or 3 equal blocks at H/B 12; unproven elsewhere; with --compare
    /// each spectrum is checked against full runs).
    #[arg(long = "column-bound", requires = "lagrangian")]
    pub column_bound: bool,
}

/// One record's figures.
struct Row {
    name: String,
    duration: f64,
    dt: f64,
    simulations: usize,
    seconds: f64,
    /// CPU seconds of the process (every thread) over the OAS, where the OS tells.
    cpu: Option<f64>,
    /// `(seconds, identical)` with full runs.
    full: Option<(f64, bool)>,
    /// CPU seconds of the full runs.
    full_cpu: Option<f64>,
    /// t₁ at the default step.
    t1: Option<f64>,
    /// `(seconds, t₁)` with the step scaled by `--dt-factor`.
    scaled: Option<(f64, Option<f64>)>,
    /// t₁ converged in the step (`--converge-step`).
    converged: Option<Converged>,
}

/// t₁ converged in the step: its cost and its answer.
struct Converged {
    seconds: f64,
    cpu: Option<f64>,
    t1: Option<f64>,
    /// The row's step factor and whether the last two steps agreed.
    factor: f64,
    ok: bool,
}

fn bundled() -> Result<Record, String> {
    parse_at2(
        include_str!("../../../examples/records/synthetic.AT2"),
        "synthetic (bundled)",
    )
    .map_err(|e| e.to_string())
}

/// User plus system CPU time of this process, every thread (Linux `/proc/self/stat`, in clock
/// ticks of 1/100 s, the kernel's fixed `USER_HZ`); `None` elsewhere. On a shared machine the
/// wall time depends on the others' load, the CPU time much less.
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The fields after the command name (which may hold spaces) in parentheses.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // utime and stime are fields 14 and 15 of the line, 12 and 13 after the name.
    let ticks = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// The 1-, 5- and 15-minute load averages (Linux), for the report.
fn load_average() -> Option<String> {
    let s = std::fs::read_to_string("/proc/loadavg").ok()?;
    Some(s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
}

/// An OAS with its wall and CPU seconds.
fn timed_oas(
    record: &Record,
    options: &OasOptions,
) -> Result<(spectra::Oas, f64, Option<f64>), String> {
    let (t0, c0) = (Instant::now(), process_cpu_seconds());
    let oas = spectra::oas(record, options, None).map_err(|e| e.to_string())?;
    let cpu = match (c0, process_cpu_seconds()) {
        (Some(a), Some(b)) => Some(b - a),
        _ => None,
    };
    Ok((oas, t0.elapsed().as_secs_f64(), cpu))
}

/// Runs the benchmark and prints the report (Markdown) on stdout.
pub fn run(args: &SpectraBenchArgs) -> Result<(), String> {
    if let Some(n) = args.threads {
        crate::commands::sweep::set_threads(n);
    }
    let mut records = Vec::new();
    if args.records.is_empty() {
        records.push(bundled()?);
    }
    for path in &args.records {
        records.push(
            read_record(path, &PlainFormat::default())
                .map_err(|e| format!("{}: {e}", path.display()))?,
        );
    }
    let mut options = OasOptions {
        n_blocks: args.blocks,
        ..OasOptions::default()
    };
    let sim = &mut options.sweep.simulation;
    sim.physics.model.n_impacts = args.impacts as u32;
    sim.physics.exact_velocity_terms = args.lagrangian;
    sim.stopping.stop_when_safe_column = args.column_bound;
    let mut full_options = options.clone();
    full_options.sweep.simulation.stopping.stop_when_safe = false;
    full_options.sweep.simulation.stopping.stop_when_safe_column = false;
    let scaled_options = options.at_step(args.dt_factor.unwrap_or(1.0));
    let load_before = load_average();
    let bar = progress::bar(records.len() as u64, "OAS");
    let mut rows = Vec::new();
    for record in &records {
        bar.set_message(record.name.clone());
        let (oas, seconds, cpu) = timed_oas(record, &options)?;
        let (full, full_cpu) = if args.compare {
            let (whole, s, c) = timed_oas(record, &full_options)?;
            (Some((s, whole.levels == oas.levels)), c)
        } else {
            (None, None)
        };
        let converged = match args.converge_step {
            Some(tol) => {
                let method = spectra::T1Method {
                    converge: Some((tol, spectra::STEP_HALVINGS)),
                    band: false,
                };
                let (t0, c0) = (Instant::now(), process_cpu_seconds());
                let r =
                    spectra::t1_of(record, &options, method, None).map_err(|e| e.to_string())?;
                Some(Converged {
                    seconds: t0.elapsed().as_secs_f64(),
                    cpu: c0.zip(process_cpu_seconds()).map(|(a, b)| b - a),
                    t1: r.oas.t1(),
                    factor: r.factor(),
                    ok: r.steps.is_some_and(|c| c.converged),
                })
            }
            None => None,
        };
        let scaled = match args.dt_factor {
            Some(_) => {
                let (o, s, _) = timed_oas(record, &scaled_options)?;
                Some((s, o.t1()))
            }
            None => None,
        };
        rows.push(Row {
            name: record.name.clone(),
            duration: record.duration(),
            dt: record.dt,
            simulations: oas.simulations(),
            seconds,
            cpu,
            full,
            full_cpu,
            t1: oas.t1(),
            scaled,
            converged,
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    let setup = format!(
        "{} block(s), {} impact(s), {}{}",
        args.blocks,
        args.impacts,
        if args.lagrangian {
            "exact Lagrangian equations"
        } else {
            "thesis Eq. 6"
        },
        if args.column_bound {
            ", column energy-bound stop (forced)"
        } else if args.blocks > 1
            && args.lagrangian
            && rocking::driver::column_stop_is_certified(args.blocks, options.slenderness)
        {
            ", column energy-bound stop (certified)"
        } else {
            ""
        }
    );
    let mut text = report(&rows, rayon::current_num_threads(), &setup);
    if let (Some(before), Some(after)) = (&load_before, load_average()) {
        let _ = writeln!(
            text,
            "Load average (1, 5, 15 min) before: {before}; after: {after} (a shared machine \
             inflates wall times: compare the ratios, and the CPU times)."
        );
    }
    if let Some(f) = args.dt_factor {
        text.push_str(&scaled_report(&rows, f));
    }
    if let Some(tol) = args.converge_step {
        text.push_str(&converged_report(&rows, tol));
    }
    print!("{text}");
    if let Some(out) = &args.out {
        write_atomic(out, text.as_bytes())?;
    }
    if rows.iter().any(|r| r.full.is_some_and(|(_, same)| !same)) {
        return Err("the energy-bound stop changed an OAS (see the table)".into());
    }
    Ok(())
}

/// The cost and the t₁ of the step scaled by `factor`, against the default's.
fn scaled_report(rows: &[Row], factor: f64) -> String {
    let f = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.4}"));
    let mut s = format!(
        "\nTime step rule x {factor}:\n\n| record | t1 (s) | t1 at dt x {factor} (s) | change | wall (s) | wall at dt x {factor} (s) | cost ratio |\n|---|---:|---:|---:|---:|---:|---:|\n"
    );
    for r in rows {
        let Some((seconds, t1)) = r.scaled else {
            continue;
        };
        let change = match (r.t1, t1) {
            (Some(a), Some(b)) => format!("{:+.1} %", (b / a - 1.0) * 100.0),
            _ => "-".into(),
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {change} | {:.2} | {seconds:.2} | {:.2} |",
            r.name,
            f(r.t1),
            f(t1),
            r.seconds,
            seconds / r.seconds
        );
    }
    s
}

/// The cost and the t₁ of the step converged within `tol`, against the step rule's.
fn converged_report(rows: &[Row], tol: f64) -> String {
    let f = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.4}"));
    let mut s = format!(
        "\nt1 converged in the step (tolerance {tol}, at most {} halvings; `rocking t1`'s \
         default) against one OAS at the step rule (`--single-step`):\n\n| record | t1 (s) | \
         converged t1 (s) | step | converged | wall (s) | converged wall (s) | wall ratio | \
         CPU ratio |\n|---|---:|---:|---:|---|---:|---:|---:|---:|\n",
        spectra::STEP_HALVINGS
    );
    let (mut cpu, mut cpu_converged) = (0.0, 0.0);
    for r in rows {
        let Some(c) = &r.converged else {
            continue;
        };
        let cpu_ratio = match (r.cpu, c.cpu) {
            (Some(a), Some(b)) if a > 0.0 => {
                cpu += a;
                cpu_converged += b;
                format!("{:.2}", b / a)
            }
            _ => "-".into(),
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | x{} | {} | {:.2} | {:.2} | {:.2} | {cpu_ratio} |",
            r.name,
            f(r.t1),
            f(c.t1),
            c.factor,
            if c.ok { "yes" } else { "no" },
            r.seconds,
            c.seconds,
            c.seconds / r.seconds
        );
    }
    if cpu > 0.0 {
        let _ = writeln!(
            s,
            "\nCPU over the records: {cpu:.2} s at the step rule, {cpu_converged:.2} s converged \
             (x{:.2}).",
            cpu_converged / cpu
        );
    }
    s
}

fn percentile(sorted: &[f64], q: f64) -> f64 {
    let i = ((sorted.len() - 1) as f64 * q).round() as usize;
    sorted[i]
}

fn report(rows: &[Row], threads: usize, setup: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "OAS with the thesis's grid (80 levels x 120 sizes, H/B = 12, scan), {setup}, {threads} thread(s)\n"
    );
    let compare = rows.iter().any(|r| r.full.is_some());
    if compare {
        s.push_str(
            "| record | duration (s) | dt (s) | simulations | wall (s) | full runs (s) | ratio | same OAS | CPU (s) | full runs CPU (s) | CPU ratio |\n\
             |---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|\n",
        );
    } else {
        s.push_str(
            "| record | duration (s) | dt (s) | simulations | wall (s) | CPU (s) |\n|---|---:|---:|---:|---:|---:|\n",
        );
    }
    for r in rows {
        let _ = write!(
            s,
            "| {} | {:.1} | {} | {} | {:.2} |",
            r.name, r.duration, r.dt, r.simulations, r.seconds
        );
        let cpu = |c: Option<f64>| c.map_or("-".to_string(), |c| format!("{c:.2}"));
        if let Some((full, same)) = r.full {
            let ratio = match (r.cpu, r.full_cpu) {
                (Some(a), Some(b)) if a > 0.0 => format!("{:.2}", b / a),
                _ => "-".into(),
            };
            let _ = write!(
                s,
                " {full:.2} | {:.2} | {} | {} | {} | {ratio} |",
                full / r.seconds,
                if same { "yes" } else { "**no**" },
                cpu(r.cpu),
                cpu(r.full_cpu)
            );
        } else {
            let _ = write!(s, " {} |", cpu(r.cpu));
        }
        s.push('\n');
    }
    let mut times: Vec<f64> = rows.iter().map(|r| r.seconds).collect();
    times.sort_by(f64::total_cmp);
    let over = times.iter().filter(|&&t| t > 5.0).count();
    let _ = writeln!(
        s,
        "\n{} record(s): median {:.2} s, 90th percentile {:.2} s, slowest {:.2} s; {over} above 5 s.",
        rows.len(),
        percentile(&times, 0.5),
        percentile(&times, 0.9),
        times[times.len() - 1],
    );
    if compare {
        let mut ratios: Vec<f64> = rows
            .iter()
            .filter_map(|r| r.full.map(|(f, _)| f / r.seconds))
            .collect();
        ratios.sort_by(f64::total_cmp);
        let _ = writeln!(
            s,
            "Speed-up of the energy-bound stop (full runs / default): smallest {:.2}, median {:.2}, largest {:.2}.",
            ratios[0],
            percentile(&ratios, 0.5),
            ratios[ratios.len() - 1]
        );
    }
    s
}
