//! `rocking oc`, `rocking oas`, `rocking t1`: overturning curves, overturning acceleration
//! spectra and replacement impulse durations (thesis Chapter 5) through `rocking::spectra`.
//! Entry points `run_oc`, `run_oas`, `run_t1` take the arguments after the command name.

use std::io::IsTerminal;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use rocking::driver::{EventLocator, Integrator};
use rocking::ground::records::{read_record, PlainFormat, Record};
use rocking::model::single_block::EquivalentBlock;
use rocking::spectra::{
    self, column_of_size, linear_levels, log_sizes, Oas, OasLevel, OasOptions, PulseShape,
    SizeSearch, SweepOptions,
};
use serde_json::{json, Value};

use crate::args::Args;
use crate::spectra_svg::{Plot, Series};

pub const OC_USAGE: &str =
    "usage: rocking oc [--shape half-sine|full-sine|three-half-sines|rectangular|triangular|ricker]
          [--blocks 1] [--slenderness 12] [--size R=1] [--impacts 1]
          [--ptp-min 0.1] [--ptp-max 10] [--ptp-n 40] [--level-max 10] [--level-n 40]
          [--dt-factor 1] [--full-runs] [--shard i/n] [--json] [--svg FILE.svg|FILE.png]
  safe/unsafe on a grid of p t_p (log) x a_p/a_p,min (linear, from 1); CSV (default) or JSON";

pub const OAS_USAGE: &str =
    "usage: rocking oas RECORD [--slenderness 12] [--levels 80] [--sizes 120]
          [--blocks 1] [--impacts 1] [--bisection] [--dt-factor 1] [--hermite] [--rk4]
          [--full-runs] [--shard i/n] [--json] [--svg PREFIX] [--png]
       rocking oas --merge SHARD.json...
  OAS of a record (thesis grid by default); JSON (default) or CSV with --csv
  --full-runs: run every simulation to its end (by default a single block stops as soon as an
  energy bound proves that the rest of the record cannot tip it: the same verdicts, faster)";

pub const T1_USAGE: &str =
    "usage: rocking t1 RECORD... [--slenderness 12] [--levels 80] [--sizes 120]
          [--blocks 1] [--impacts 1] [--bisection] [--dt-factor 1] [--threads N] [--full-runs]
          [--shard i/n] [--json]
       rocking t1 --merge SHARD.json...
  t_1, t_1', beta, f_min of each record (JSON list with --json, else a table)";

fn fail(usage: &str, msg: &str) -> ExitCode {
    eprintln!("rocking: {msg}\n\n{usage}");
    ExitCode::from(2)
}

fn progress_bar(total: u64) -> ProgressBar {
    if std::io::stderr().is_terminal() {
        let pb = ProgressBar::new(total);
        if let Ok(style) = ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] {pos}/{len} {msg} (eta {eta})",
        ) {
            pb.set_style(style);
        }
        pb
    } else {
        ProgressBar::hidden()
    }
}

fn num(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// Options shared by `oas` and `t1`.
fn oas_options(a: &Args) -> Result<OasOptions, String> {
    let mut o = OasOptions {
        slenderness: a.f64_or("slenderness", 12.0)?,
        levels: linear_levels(1.0, a.f64_or("level-max", 10.0)?, a.usize_or("levels", 80)?),
        sizes: log_sizes(
            a.f64_or("size-max", 1000.0)?,
            a.f64_or("size-min", 0.1)?,
            a.usize_or("sizes", 120)?,
        ),
        n_blocks: a.usize_or("blocks", 1)?,
        search: if a.flag("bisection") {
            SizeSearch::Bisection
        } else {
            SizeSearch::Scan
        },
        ..OasOptions::default()
    };
    sweep_common(a, &mut o.sweep)?;
    Ok(o)
}

/// Sizes rayon's global pool for the sweeps (`--threads N`). Results do not depend on it; only
/// the first call in a process can set the pool, later ones are ignored.
pub fn set_threads(n: usize) {
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build_global();
}

fn sweep_common(a: &Args, s: &mut SweepOptions) -> Result<(), String> {
    if let Some(n) = a.str("threads") {
        set_threads(n.parse().map_err(|_| format!("--threads: bad count {n}"))?);
    }
    s.simulation.model.n_impacts = a.usize_or("impacts", 1)? as u32;
    s.time_step = s.time_step.scaled(a.f64_or("dt-factor", 1.0)?);
    s.tail = a.f64_or("tail", s.tail)?;
    if a.flag("hermite") || a.flag("rk4") {
        s.simulation.locator = EventLocator::Hermite;
    }
    if a.flag("rk4") {
        s.simulation.integrator = Integrator::Rk4;
    }
    // Same verdicts either way (tested); only for checking that claim, or timing it.
    s.simulation.stop_when_safe = !a.flag("full-runs");
    Ok(())
}

fn read(path: &str) -> Result<Record, String> {
    read_record(Path::new(path), &PlainFormat::default()).map_err(|e| e.to_string())
}

// ---------------------------------------------------------------------------------------------
// OC

fn parse_shape(s: &str) -> Result<PulseShape, String> {
    Ok(match s {
        "half-sine" => PulseShape::half_sine(),
        "full-sine" => PulseShape::full_sine(),
        "three-half-sines" => PulseShape::three_half_sines(),
        "rectangular" => PulseShape::Rectangular,
        "triangular" => PulseShape::Triangular,
        "ricker" => PulseShape::Ricker,
        _ => return Err(format!("unknown pulse shape {s}")),
    })
}

pub fn run_oc(args: &[String]) -> ExitCode {
    match oc(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(OC_USAGE, &e),
    }
}

fn oc(args: &[String]) -> Result<(), String> {
    let a = Args::parse(args, &["json", "hermite", "rk4", "full-runs"])?;
    let shape = parse_shape(a.str("shape").unwrap_or("half-sine"))?;
    let n_blocks = a.usize_or("blocks", 1)?;
    let column = column_of_size(
        a.f64_or("size", 1.0)?,
        a.f64_or("slenderness", 12.0)?,
        n_blocks,
    )
    .map_err(|e| e.to_string())?;
    let mut sweep = SweepOptions::default();
    sweep_common(&a, &mut sweep)?;
    let block = EquivalentBlock::of_column(&column);
    let g = sweep.simulation.gravity;
    let (mono_p, mono_a_p_min) = (block.frequency_parameter(g), block.a_p_min(g));
    let ptp = log_sizes(
        a.f64_or("ptp-max", 10.0)?,
        a.f64_or("ptp-min", 0.1)?,
        a.usize_or("ptp-n", 40)?,
    );
    let (si, sn) = a.shard()?;
    let t_p: Vec<f64> = ptp
        .iter()
        .rev()
        .enumerate()
        .filter(|(k, _)| k % sn == si)
        .map(|(_, x)| x / mono_p)
        .collect();
    let levels = linear_levels(
        1.0,
        a.f64_or("level-max", 10.0)?,
        a.usize_or("level-n", 40)?,
    );
    let a_p: Vec<f64> = levels.iter().map(|l| l * mono_a_p_min).collect();
    let pb = progress_bar(t_p.len() as u64);
    let tick = || pb.inc(1);
    let res = spectra::overturning_curve(&column, shape, &t_p, &a_p, &sweep, Some(&tick))
        .map_err(|e| e.to_string())?;
    pb.finish_and_clear();
    if a.flag("json") {
        let pts: Vec<Value> = res
            .normalised()
            .iter()
            .zip(res.t_p.iter().flat_map(|t| a_p.iter().map(move |ap| (*t, *ap))))
            .map(|(&(x, y, u), (t, ap))| {
                json!({"t_p": t, "a_p": ap, "p_tp": x, "level": y, "unsafe": u})
            })
            .collect();
        let env: Vec<Value> = res
            .normalised_envelope()
            .iter()
            .map(|(x, e)| json!({"p_tp": x, "level": e}))
            .collect();
        let out = json!({
            "shape": shape.name(), "blocks": n_blocks, "p": mono_p, "a_p_min": mono_a_p_min,
            "points": pts, "envelope": env,
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?
        );
    } else {
        println!("shape,blocks,t_p,a_p,p_tp,level,unsafe");
        for (i, &t) in res.t_p.iter().enumerate() {
            for (j, &ap) in res.a_p.iter().enumerate() {
                println!(
                    "{},{n_blocks},{t},{ap},{},{},{}",
                    shape.name(),
                    mono_p * t,
                    ap / mono_a_p_min,
                    u8::from(res.is_unsafe(i, j))
                );
            }
        }
    }
    if let Some(path) = a.str("svg") {
        let pts = res.normalised();
        let unsafe_pts: Vec<(f64, f64)> = pts.iter().filter(|p| p.2).map(|p| (p.0, p.1)).collect();
        let env: Vec<(f64, f64)> = res
            .normalised_envelope()
            .iter()
            .filter_map(|(x, e)| e.map(|y| (*x, y)))
            .collect();
        let xmax = pts.iter().map(|p| p.0).fold(0.0, f64::max);
        let ymax = pts.iter().map(|p| p.1).fold(1.0, f64::max);
        let plot = Plot {
            title: format!("OC, {}, {} block(s)", shape.name(), n_blocks),
            x_label: "p t_p".into(),
            y_label: "a_p / a_p,min".into(),
            x_range: (0.0, xmax),
            y_range: (0.0, ymax),
            series: vec![
                Series {
                    label: "overturns".into(),
                    points: unsafe_pts,
                    color: "#1f77b4",
                    line: false,
                    dashed: false,
                },
                Series {
                    label: "envelope".into(),
                    points: env,
                    color: "#d62728",
                    line: true,
                    dashed: false,
                },
            ],
        };
        save_plot(path, &plot.to_svg())?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// OAS

fn oas_json(o: &Oas, seconds: f64) -> Value {
    let s = o.summary();
    let levels: Vec<Value> = o
        .levels
        .iter()
        .map(|l| {
            let pt = l.largest_unsafe.map(|i| {
                let p = o.block(o.sizes[i]).frequency_parameter(o.gravity);
                (o.sizes[i], p, p * l.level)
            });
            json!({
                "level": l.level, "largest_unsafe": l.largest_unsafe,
                "size": pt.map(|p| p.0), "p": pt.map(|p| p.1), "f": pt.map(|p| p.2),
                "simulations": l.simulations,
            })
        })
        .collect();
    let check = s.t1.map(|t1| o.check(t1, s.fit));
    json!({
        "record": o.record, "slenderness": o.slenderness, "blocks": o.n_blocks,
        "impacts": o.n_impacts, "search": format!("{:?}", o.search), "gravity": o.gravity,
        "sizes": o.sizes, "levels": levels,
        "summary": summary_json(o, seconds),
        "conservative": check.map(|c| json!({
            "eq21": c.eq21.len(), "eq21_approx": c.eq21_approx.len(),
            "eq29": c.eq29.len(), "eq30": c.eq30.len(),
        })),
    })
}

fn summary_json(o: &Oas, seconds: f64) -> Value {
    let s = o.summary();
    json!({
        "record": o.record,
        "t1": s.t1,
        "t1_prime": s.fit.map(|f| num(f.t1_prime)),
        "beta": s.fit.map(|f| num(f.beta)),
        "f_min": s.f_min.map(|m| m.f),
        "level_at_f_min": s.f_min.map(|m| m.level),
        "size_at_f_min": s.f_min.map(|m| m.size),
        "simulations": s.simulations,
        "seconds": seconds,
    })
}

/// Rebuilds an OAS from (merged) `oas --json` outputs.
fn oas_from_json(parts: &[Value]) -> Result<Oas, String> {
    let first = parts.first().ok_or("nothing to merge")?;
    let get = |v: &Value, k: &str| v.get(k).cloned().ok_or(format!("missing field {k}"));
    let mut levels: Vec<OasLevel> = Vec::new();
    for p in parts {
        for l in get(p, "levels")?.as_array().ok_or("levels: not a list")? {
            levels.push(OasLevel {
                level: l["level"].as_f64().ok_or("level")?,
                largest_unsafe: l["largest_unsafe"].as_u64().map(|i| i as usize),
                simulations: l["simulations"].as_u64().unwrap_or(0) as usize,
            });
        }
    }
    levels.sort_by(|a, b| a.level.total_cmp(&b.level));
    let sizes: Vec<f64> = get(first, "sizes")?
        .as_array()
        .ok_or("sizes")?
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    Ok(Oas {
        record: first["record"].as_str().unwrap_or("").to_string(),
        slenderness: first["slenderness"].as_f64().ok_or("slenderness")?,
        n_blocks: first["blocks"].as_u64().unwrap_or(1) as usize,
        n_impacts: first["impacts"].as_u64().unwrap_or(1) as u32,
        search: if first["search"] == "Bisection" {
            SizeSearch::Bisection
        } else {
            SizeSearch::Scan
        },
        sizes,
        levels,
        gravity: first["gravity"].as_f64().unwrap_or(9.81),
    })
}

fn read_json(path: &str) -> Result<Value, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    serde_json::from_str(&text).map_err(|e| format!("{path}: {e}"))
}

pub fn run_oas(args: &[String]) -> ExitCode {
    match oas(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(OAS_USAGE, &e),
    }
}

fn oas(args: &[String]) -> Result<(), String> {
    let a = Args::parse(
        args,
        &[
            "json",
            "csv",
            "bisection",
            "merge",
            "hermite",
            "rk4",
            "png",
            "full-runs",
        ],
    )?;
    let t0 = Instant::now();
    let result = if a.flag("merge") {
        let parts: Vec<Value> = a
            .positional
            .iter()
            .map(|p| read_json(p))
            .collect::<Result<_, _>>()?;
        oas_from_json(&parts)?
    } else {
        let [path] = a.positional.as_slice() else {
            return Err("expected one RECORD".into());
        };
        let record = read(path)?;
        let mut o = oas_options(&a)?;
        let (si, sn) = a.shard()?;
        o.levels = o
            .levels
            .iter()
            .enumerate()
            .filter(|(k, _)| k % sn == si)
            .map(|(_, l)| *l)
            .collect();
        let pb = progress_bar(o.levels.len() as u64);
        let tick = || pb.inc(1);
        let r = spectra::oas(&record, &o, Some(&tick)).map_err(|e| e.to_string())?;
        pb.finish_and_clear();
        r
    };
    let seconds = t0.elapsed().as_secs_f64();
    if a.flag("csv") {
        println!("record,level,size,p,f,simulations");
        for l in &result.levels {
            let (size, p) = match l.largest_unsafe {
                Some(i) => (
                    result.sizes[i],
                    result
                        .block(result.sizes[i])
                        .frequency_parameter(result.gravity),
                ),
                None => (f64::NAN, f64::NAN),
            };
            println!(
                "{},{},{size},{p},{},{}",
                result.record,
                l.level,
                p * l.level,
                l.simulations
            );
        }
    } else {
        let v = oas_json(&result, seconds);
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?
        );
    }
    if let Some(prefix) = a.str("svg") {
        write_oas_svgs(&result, prefix, a.flag("png"))?;
    }
    Ok(())
}

fn write_oas_svgs(o: &Oas, prefix: &str, png: bool) -> Result<(), String> {
    let s = o.summary();
    let b = o.boundary();
    let i_cr = o.i_cr();
    let pmax = b.iter().map(|q| q.p).fold(1.0, f64::max) * 1.1;
    let lmax = o.levels.iter().map(|l| l.level).fold(1.0, f64::max);
    let ps: Vec<f64> = (1..=200).map(|k| pmax * k as f64 / 200.0).collect();
    let mut series = vec![Series {
        label: "largest unsafe size".into(),
        points: b.iter().map(|q| (q.p, q.level)).collect(),
        color: "#1f77b4",
        line: false,
        dashed: false,
    }];
    let mut tseries = vec![Series {
        label: "largest unsafe size".into(),
        points: b.iter().map(|q| (q.f, q.level)).collect(),
        color: "#1f77b4",
        line: false,
        dashed: false,
    }];
    if let Some(t1) = s.t1 {
        series.push(Series {
            label: format!("Eq. 21, t1 = {t1:.3} s"),
            points: ps
                .iter()
                .map(|&p| (p, rocking::design::simplified_oas(p, t1, i_cr)))
                .collect(),
            color: "#d62728",
            line: true,
            dashed: true,
        });
        tseries.push(Series {
            label: "f_min (Eq. 20)".into(),
            points: vec![(i_cr / t1, 1.0), (i_cr / t1, lmax)],
            color: "#d62728",
            line: true,
            dashed: true,
        });
        if let Some(fit) = s.fit {
            series.push(Series {
                label: format!("Eq. 30, t1' = {:.3}, beta = {:.2}", fit.t1_prime, fit.beta),
                points: ps
                    .iter()
                    .map(|&p| {
                        (
                            p,
                            rocking::design::improved_oas_eq30(p, t1, fit.t1_prime, fit.beta),
                        )
                    })
                    .collect(),
                color: "#2ca02c",
                line: true,
                dashed: true,
            });
            tseries.push(Series {
                label: "Eq. 28 line".into(),
                points: vec![
                    (1.0 / fit.beta + 1.0 / fit.t1_prime, 1.0),
                    (lmax / fit.beta + 1.0 / fit.t1_prime, lmax),
                ],
                color: "#2ca02c",
                line: true,
                dashed: true,
            });
        }
    }
    let fmax = b.iter().map(|q| q.f).fold(1.0, f64::max) * 1.1;
    let plots = [
        (
            "oas",
            Plot {
                title: format!("OAS, {}", o.record),
                x_label: "p [1/s]".into(),
                y_label: "a_p / a_p,min".into(),
                x_range: (0.0, pmax),
                y_range: (0.0, lmax),
                series,
            },
        ),
        (
            "transformed",
            Plot {
                title: format!("transformed OAS, {}", o.record),
                x_label: "f = p a_p / a_p,min [1/s]".into(),
                y_label: "a_p / a_p,min".into(),
                x_range: (0.0, fmax),
                y_range: (0.0, lmax),
                series: tseries,
            },
        ),
    ];
    for (name, plot) in plots {
        let svg = plot.to_svg();
        save_plot(&format!("{prefix}-{name}.svg"), &svg)?;
        if png {
            save_plot(&format!("{prefix}-{name}.png"), &svg)?;
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// t1

pub fn run_t1(args: &[String]) -> ExitCode {
    match t1(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(T1_USAGE, &e),
    }
}

fn t1(args: &[String]) -> Result<(), String> {
    let a = Args::parse(
        args,
        &["json", "bisection", "merge", "hermite", "rk4", "full-runs"],
    )?;
    let rows: Vec<Value> = if a.flag("merge") {
        let mut rows = Vec::new();
        for p in &a.positional {
            match read_json(p)? {
                Value::Array(v) => rows.extend(v),
                _ => return Err(format!("{p}: expected a JSON list")),
            }
        }
        rows.sort_by(|x, y| x["file"].as_str().cmp(&y["file"].as_str()));
        rows
    } else {
        if a.positional.is_empty() {
            return Err("expected at least one RECORD".into());
        }
        let o = oas_options(&a)?;
        let (si, sn) = a.shard()?;
        let files: Vec<&String> = a
            .positional
            .iter()
            .enumerate()
            .filter(|(k, _)| k % sn == si)
            .map(|(_, f)| f)
            .collect();
        let pb = progress_bar((files.len() * o.levels.len()) as u64);
        let mut rows = Vec::new();
        for f in files {
            pb.set_message(f.clone());
            let record = read(f)?;
            let t0 = Instant::now();
            let tick = || pb.inc(1);
            let r = spectra::oas(&record, &o, Some(&tick)).map_err(|e| e.to_string())?;
            let mut v = summary_json(&r, t0.elapsed().as_secs_f64());
            v["file"] = json!(f);
            v["slenderness"] = json!(o.slenderness);
            v["blocks"] = json!(o.n_blocks);
            v["dt_factor"] = json!(a.f64_or("dt-factor", 1.0)?);
            v["search"] = json!(format!("{:?}", o.search));
            rows.push(v);
        }
        pb.finish_and_clear();
        rows
    };
    if a.flag("json") {
        println!(
            "{}",
            serde_json::to_string_pretty(&rows).map_err(|e| e.to_string())?
        );
    } else {
        println!("record                          t1 [s]   t1' [s]  beta     f_min [1/s]");
        for r in &rows {
            let f = |k: &str| r[k].as_f64().map_or("-".to_string(), |x| format!("{x:.3}"));
            println!(
                "{:<30} {:>8} {:>8} {:>8} {:>8}",
                r["record"].as_str().unwrap_or(""),
                f("t1"),
                f("t1_prime"),
                f("beta"),
                f("f_min")
            );
        }
    }
    Ok(())
}

/// Writes a chart as SVG, or as PNG when the path ends in `.png` (rendered with resvg).
fn save_plot(path: &str, svg: &str) -> Result<(), String> {
    let p = std::path::Path::new(path);
    if path.to_ascii_lowercase().ends_with(".png") {
        crate::output::write_atomic(p, &crate::plot::svg_to_png(svg)?)
    } else {
        crate::output::write_atomic(p, svg.as_bytes())
    }
}
