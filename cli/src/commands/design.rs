//! `rocking design width|check`: the thesis's design method (Eq. 21, 23, 24, 31) through
//! `rocking::design`.

use clap::{Args, Subcommand, ValueEnum};
use rocking::design::{self, Branch, EquivalentBlock, ImpulseFactor, MassDistribution};
use rocking::model::column::GRAVITY;
use serde::Serialize;

use super::sweep::positive;
use crate::output::print_json;

/// `rocking design width|check`.
#[derive(Subcommand, Debug)]
pub enum Design {
    /// The required width by Eq. 31 (Eq. 23 solved exactly, Eq. 24 approximation).
    Width(WidthArgs),
    /// The Eq. 31 verdict for a given width (i_cr = 1; --exact-icr: Eq. 21 with i_cr of Eq. 18).
    Check(CheckArgs),
}

/// How the pier's mass is distributed.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum Mass {
    /// A uniform pier.
    Uniform,
    /// The mass at the top (a pier carrying a heavy deck).
    Top,
}

impl Mass {
    fn distribution(self) -> MassDistribution {
        match self {
            Mass::Uniform => MassDistribution::Uniform,
            Mass::Top => MassDistribution::Top,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Mass::Uniform => "uniform",
            Mass::Top => "top",
        }
    }
}

/// A peak ground acceleration as given: in m/s², or in units of g with a `g` suffix (`0.14g`,
/// the thesis's "a_g = 0.14 g"), resolved with `--g`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pga {
    /// In m/s².
    MetresPerSecondSquared(f64),
    /// In units of `--g`.
    G(f64),
}

impl Pga {
    /// In m/s².
    fn value(self, g: f64) -> f64 {
        match self {
            Pga::MetresPerSecondSquared(a) => a,
            Pga::G(a) => a * g,
        }
    }
}

/// clap's check of `--pga`: a number > 0 in m/s² (an optional `m/s2` or `m/s²` suffix), or
/// with a `g` suffix in units of g.
fn pga(s: &str) -> Result<Pga, String> {
    let t = s.trim();
    let (number, in_g) = if let Some(n) = t.strip_suffix('g').or_else(|| t.strip_suffix('G')) {
        (n, true)
    } else if let Some(n) = t.strip_suffix("m/s2").or_else(|| t.strip_suffix("m/s²")) {
        (n, false)
    } else {
        (t, false)
    };
    let v = positive(number.trim()).map_err(|e| {
        format!("{e} (a peak ground acceleration in m/s², or in g with a g suffix: 0.14g)")
    })?;
    Ok(if in_g {
        Pga::G(v)
    } else {
        Pga::MetresPerSecondSquared(v)
    })
}

/// The load and the pier, common to both.
#[derive(Args, Debug)]
pub struct Load {
    /// Height H [m].
    #[arg(long, value_parser = positive)]
    pub height: f64,
    /// Peak ground acceleration a_p [m/s²]; with a g suffix in units of g (`--pga 0.14g` is
    /// 0.14 × --g).
    #[arg(long, value_parser = pga, allow_hyphen_values = true)]
    pub pga: Pga,
    /// Replacement impulse duration t_1 of the site [s] (`rocking t1`).
    #[arg(long, value_parser = positive)]
    pub t1: f64,
    /// Mass distribution.
    #[arg(long, value_enum, default_value_t = Mass::Uniform)]
    pub mass: Mass,
    /// Gravity [m/s²].
    #[arg(long, default_value_t = GRAVITY, value_parser = positive)]
    pub g: f64,
    /// JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Options of `rocking design width`.
#[derive(Args, Debug)]
pub struct WidthArgs {
    #[command(flatten)]
    pub load: Load,
}

/// Options of `rocking design check`.
#[derive(Args, Debug)]
pub struct CheckArgs {
    /// Width B [m].
    #[arg(long, value_parser = positive)]
    pub width: f64,
    #[command(flatten)]
    pub load: Load,
    /// Eq. 21 with i_cr of Eq. 18 instead of i_cr = 1.
    #[arg(long = "exact-icr")]
    pub exact_icr: bool,
}

/// `design width --json`.
#[derive(Serialize)]
struct WidthJson {
    width: f64,
    governing: Branch,
    eq23: f64,
    eq21_exact_icr: f64,
    eq24: f64,
    at_rest: f64,
    height: f64,
    pga: f64,
    t1: f64,
    mass: &'static str,
}

fn branch(b: Branch) -> &'static str {
    match b {
        Branch::NoRocking => "no-rocking",
        Branch::Impulse => "impulse",
    }
}

impl Design {
    /// Runs the command.
    pub fn run(&self) -> Result<(), String> {
        match self {
            Design::Width(a) => width(a),
            Design::Check(a) => check(a),
        }
    }
}

impl Load {
    /// The peak ground acceleration in m/s².
    fn pga(&self) -> f64 {
        self.pga.value(self.g)
    }

    /// One line with the inputs as they were understood, units and the PGA in g included, so
    /// that a PGA given in g where m/s² was expected shows at once (`--pga 0.14` is 0.014 g).
    fn echo(&self, width: Option<f64>) -> String {
        let pier = match width {
            Some(b) => format!("B = {b} m, H = {} m", self.height),
            None => format!("H = {} m", self.height),
        };
        format!(
            "pier {pier}, {} mass; a_p = {:.4} m/s² ({:.3} g), t_1 = {} s, g = {} m/s²",
            self.mass.name(),
            self.pga(),
            self.pga() / self.g,
            self.t1,
            self.g
        )
    }
}

fn width(a: &WidthArgs) -> Result<(), String> {
    let l = &a.load;
    let w = design::pier_width(l.height, l.pga(), l.t1, l.mass.distribution(), l.g)
        .map_err(|e| e.to_string())?;
    if l.json {
        print_json(&WidthJson {
            width: w.required,
            governing: w.governing,
            eq23: w.eq23,
            eq21_exact_icr: w.eq21_exact_icr,
            eq24: w.eq24,
            at_rest: w.at_rest,
            height: l.height,
            pga: l.pga(),
            t1: l.t1,
            mass: l.mass.name(),
        })?;
    } else {
        println!("{}", l.echo(None));
        println!(
            "required width B = {:.4} m ({} branch of Eq. 31)",
            w.required,
            branch(w.governing)
        );
        println!("  Eq. 23 (i_cr = 1, exact)      {:.4} m", w.eq23);
        println!("  Eq. 21 with i_cr of Eq. 18    {:.4} m", w.eq21_exact_icr);
        println!("  Eq. 24 (slender approx.)      {:.4} m", w.eq24);
        println!("  at rest (a_p = a_p,min)       {:.4} m", w.at_rest);
        let pier = EquivalentBlock::new(w.required, l.height, l.mass.distribution())
            .map_err(|e| e.to_string())?;
        println!("{}", sliding_note(pier.tan_delta()));
    }
    Ok(())
}

/// The premise of Eq. 31, said with the numbers: the pier rocks, it does not slide, which
/// takes a friction coefficient of at least tan δ (rocking starts at a_p,min = g tan δ, sliding
/// at μ g). A squat pier (`--width 20 --height 12`, tan δ = 1.67) was called SAFE with nothing
/// to say that it only rocks with a friction coefficient above 1.67.
fn sliding_note(tan_delta: f64) -> String {
    let squat = if tan_delta >= 1.0 {
        " (a pier this squat, tan δ ≥ 1, will most likely slide before it rocks: check sliding)"
    } else {
        ""
    };
    format!("  Eq. 31 assumes rocking without sliding: friction μ ≥ tan δ = {tan_delta:.3}{squat}")
}

fn check(a: &CheckArgs) -> Result<(), String> {
    let l = &a.load;
    let pier = EquivalentBlock::new(a.width, l.height, l.mass.distribution())
        .map_err(|e| e.to_string())?;
    let factor = if a.exact_icr {
        ImpulseFactor::Exact
    } else {
        ImpulseFactor::One
    };
    let c = design::design_check(&pier, l.pga(), l.t1, l.g, factor).map_err(|e| e.to_string())?;
    if l.json {
        print_json(&c)?;
    } else {
        println!("{}", l.echo(Some(a.width)));
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
        println!("{}", sliding_note(pier.tan_delta()));
    }
    Ok(())
}
