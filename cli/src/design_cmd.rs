//! `rocking design width|check`: the thesis's design method (Eq. 21, 23, 24, 31) through
//! `rocking::design`. Entry point `run_design` takes the arguments after `design`.

use std::process::ExitCode;

use rocking::design::{self, Branch, EquivalentBlock, ImpulseFactor, MassDistribution};
use rocking::model::column::GRAVITY;
use serde_json::json;

use crate::args::Args;

pub const DESIGN_USAGE: &str = "usage: rocking design width --height H --pga A --t1 T [--mass uniform|top] [--json]
       rocking design check --width B --height H --pga A --t1 T [--mass uniform|top] [--exact-icr] [--json]
  A in m/s²; width: the required width by Eq. 31 (Eq. 23 solved exactly, Eq. 24 approximation);
  check: the Eq. 31 verdict (i_cr = 1; --exact-icr: Eq. 21 with i_cr of Eq. 18)";

fn mass(a: &Args) -> Result<MassDistribution, String> {
    match a.str("mass").unwrap_or("uniform") {
        "uniform" => Ok(MassDistribution::Uniform),
        "top" => Ok(MassDistribution::Top),
        m => Err(format!("--mass: expected uniform or top, got {m}")),
    }
}

fn branch(b: Branch) -> &'static str {
    match b {
        Branch::NoRocking => "no-rocking",
        Branch::Impulse => "impulse",
    }
}

pub fn run_design(args: &[String]) -> ExitCode {
    match design(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rocking design: {e}\n\n{DESIGN_USAGE}");
            ExitCode::from(2)
        }
    }
}

fn design(args: &[String]) -> Result<(), String> {
    let a = Args::parse(args, &["json", "exact-icr"])?;
    let g = a.f64_or("g", GRAVITY)?;
    match a.positional.first().map(String::as_str) {
        Some("width") => {
            let (h, pga, t1) = (a.f64_req("height")?, a.f64_req("pga")?, a.f64_req("t1")?);
            let m = mass(&a)?;
            let w = design::pier_width(h, pga, t1, m, g).map_err(|e| e.to_string())?;
            if a.flag("json") {
                let v = json!({
                    "width": w.required, "governing": branch(w.governing), "eq23": w.eq23,
                    "eq21_exact_icr": w.eq21_exact_icr, "eq24": w.eq24, "at_rest": w.at_rest,
                    "height": h, "pga": pga, "t1": t1, "mass": a.str("mass").unwrap_or("uniform"),
                });
                println!(
                    "{}",
                    serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?
                );
            } else {
                println!(
                    "required width B = {:.4} m ({} branch of Eq. 31)",
                    w.required,
                    branch(w.governing)
                );
                println!("  Eq. 23 (i_cr = 1, exact)      {:.4} m", w.eq23);
                println!("  Eq. 21 with i_cr of Eq. 18    {:.4} m", w.eq21_exact_icr);
                println!("  Eq. 24 (slender approx.)      {:.4} m", w.eq24);
                println!("  at rest (a_p = a_p,min)       {:.4} m", w.at_rest);
            }
            Ok(())
        }
        Some("check") => {
            let pier = EquivalentBlock::new(a.f64_req("width")?, a.f64_req("height")?, mass(&a)?)
                .map_err(|e| e.to_string())?;
            let (pga, t1) = (a.f64_req("pga")?, a.f64_req("t1")?);
            let factor = if a.flag("exact-icr") {
                ImpulseFactor::Exact
            } else {
                ImpulseFactor::One
            };
            let c = design::design_check(&pier, pga, t1, g, factor).map_err(|e| e.to_string())?;
            if a.flag("json") {
                let v = json!({
                    "safe": c.safe, "a_p": c.a_p, "a_p_min": c.a_p_min, "p": c.p, "i_cr": c.i_cr,
                    "impulse_limit": c.impulse_limit, "limit": c.limit,
                    "governing": branch(c.governing), "utilisation": c.utilisation,
                });
                println!(
                    "{}",
                    serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?
                );
            } else {
                println!(
                    "{}: a_p = {:.4} m/s² {} limit {:.4} m/s² (utilisation {:.3})",
                    if c.safe { "SAFE" } else { "UNSAFE" },
                    c.a_p,
                    if c.safe { "<=" } else { ">" },
                    c.limit,
                    c.utilisation
                );
                println!(
                    "  a_p,min = g tan δ = {:.4} m/s², p = {:.4} 1/s, i_cr = {:.4}",
                    c.a_p_min, c.p, c.i_cr
                );
                println!(
                    "  impulse branch a_p,min i_cr / (t_1 p) = {:.4} m/s²; governing: {}",
                    c.impulse_limit,
                    branch(c.governing)
                );
            }
            Ok(())
        }
        _ => Err("expected `width` or `check`".into()),
    }
}
