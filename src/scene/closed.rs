//! Scenes of closed chains (SPEC §9): `{"arch": {...}}` or `{"colonnade": {...}}` in place of
//! `blocks`, with the same excitation, duration, dt, solver, gravity and output settings.
//!
//! ```json
//! {
//!   "arch": {"radius": 5, "thickness": 0.75, "embrace_angle": 180, "voussoirs": 20,
//!            "density": 2000, "depth": 1},
//!   "excitation": {"type": "half_sine", "amplitude": -4.4, "duration": 1.0},
//!   "duration": 2.0, "dt": 0.001
//! }
//! ```
//! `embrace_angle` is in degrees (180: semicircular). The colonnade is Makris & Vassiliou's
//! frame: `{"width", "height", "column_mass", "span", "beam_height", "beam_mass"}` (two equal
//! monolithic columns, a beam `span + width` long flush with their outer faces), optionally
//! `"drums"` (each column cut into that many equal drums) and `"beam_length"` (an overhanging
//! beam).
//!
//! `"min_flight": k` (optional, default 0) sets the driver's [`LoopOptions::min_flight`]: a joint
//! an impact opens whose predicted flight is shorter than `k` steps stays closed (the treatment
//! of sub-step flights measured in docs/arch-performance.md; an option, off by default).

use serde::Deserialize;

use super::{err, SceneError, SceneSpec};
use crate::chain::arch::VoussoirArch;
use crate::chain::colonnade::CappedColonnade;
use crate::chain::Chain;
use crate::driver::closed::LoopOptions;
use crate::ground::excitation::Excitation;
use crate::model::cone::{ModelOptions, Solver};

/// A voussoir arch (SPEC §9).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArchSpec {
    pub radius: f64,
    pub thickness: f64,
    /// Angle of embrace `2β` in degrees (default 180).
    #[serde(default)]
    pub embrace_angle: Option<f64>,
    pub voussoirs: usize,
    /// kg/m³ (default 2000).
    #[serde(default)]
    pub density: Option<f64>,
    /// Out of plane (m, default 1).
    #[serde(default)]
    pub depth: Option<f64>,
}

/// Makris & Vassiliou's capped colonnade (two equal columns and a beam).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ColonnadeSpec {
    pub width: f64,
    pub height: f64,
    pub column_mass: f64,
    pub span: f64,
    pub beam_height: f64,
    pub beam_mass: f64,
    /// Equal drums each column is cut into (default 1: monolithic), each `height / drums` tall
    /// with `column_mass / drums`.
    #[serde(default)]
    pub drums: Option<usize>,
    /// Length of the beam (m; default `span + width`, flush with the columns' outer faces); at
    /// least that, so that it covers both column tops.
    #[serde(default)]
    pub beam_length: Option<f64>,
}

/// The geometry a loop scene was built from (to draw it).
#[derive(Clone, Debug, PartialEq)]
pub enum LoopShape {
    Arch(VoussoirArch),
    Colonnade(CappedColonnade),
}

/// A loop scene ready to simulate with [`crate::driver::simulate_loop`].
pub struct LoopScene {
    pub title: String,
    pub shape: LoopShape,
    pub chain: Chain,
    pub excitation: Excitation,
    /// The loop driver's options (`record_every` from `output.every` when a history is written).
    pub options: LoopOptions,
    pub output: super::OutputSpec,
}

/// Builds the loop scene of `spec` (which has `arch` or `colonnade`); `excitation` already built.
pub(super) fn build(
    spec: SceneSpec,
    excitation: Excitation,
    name: &str,
) -> Result<LoopScene, SceneError> {
    // Settings of the column drivers have no meaning here, whatever their value (their
    // defaults included): name them rather than ignore them.
    let column_only: [(&str, bool); 12] = [
        ("blocks", !spec.blocks.is_empty()),
        ("initial_angles", spec.initial_angles.is_some()),
        ("impacts", spec.impacts.is_some()),
        ("integrator", spec.integrator.is_some()),
        ("locator", spec.locator.is_some()),
        ("friction", spec.friction.is_some()),
        ("on_sliding", spec.on_sliding.is_some()),
        ("on_tension", spec.on_tension.is_some()),
        ("scheme", spec.scheme.is_some()),
        (
            "continue_until_fallen",
            spec.continue_until_fallen.is_some(),
        ),
        ("energy_tolerance", spec.energy_tolerance.is_some()),
        ("energy_consistent", spec.energy_consistent.is_some()),
    ];
    if let Some((field, _)) = column_only.iter().find(|(_, set)| *set) {
        return Err(err(field, "not used by a closed chain (arch, colonnade)"));
    }
    if spec.exact_velocity_terms.is_some() {
        return Err(err(
            "exact_velocity_terms",
            "a closed chain always uses the exact velocity terms",
        ));
    }
    let invalid =
        |v: crate::validate::InvalidValue| err(&v.field, format!("{}: {}", v.value, v.rule));
    let (shape, chain) = match (spec.arch, spec.colonnade) {
        (Some(a), None) => {
            // In degrees here (the library's `VoussoirArch` takes radians): say so in its unit.
            let embrace = a.embrace_angle.unwrap_or(180.0);
            if !(embrace > 0.0 && embrace < 360.0) {
                return Err(err(
                    "arch.embrace_angle",
                    format!(
                        "{embrace}: must be greater than 0 and less than 360 degrees (a full \
                         ring has no abutments)"
                    ),
                ));
            }
            let arch = VoussoirArch {
                radius: a.radius,
                thickness: a.thickness,
                embrace_angle: embrace.to_radians(),
                voussoirs: a.voussoirs,
                density: a.density.unwrap_or(2000.0),
                depth: a.depth.unwrap_or(1.0),
            };
            let chain = arch.chain().map_err(invalid)?;
            arch.runnable().map_err(invalid)?;
            (LoopShape::Arch(arch), chain)
        }
        (None, Some(c)) => {
            // The scene's own fields, named as it spells them (the frame's checks name the
            // blocks it builds: `colonnade.left[0].mass`, and `colonnade.beam.width` for a
            // negative span).
            for (field, v) in [
                ("width", c.width),
                ("height", c.height),
                ("column_mass", c.column_mass),
                ("span", c.span),
                ("beam_height", c.beam_height),
                ("beam_mass", c.beam_mass),
            ] {
                crate::validate::positive(format!("colonnade.{field}"), v).map_err(invalid)?;
            }
            let mut frame = CappedColonnade::frame(
                c.width,
                c.height,
                c.column_mass,
                c.span,
                c.beam_height,
                c.beam_mass,
            );
            // Two columns of `drums` blocks and the beam: `2 drums + 2` joints, at most as many as
            // an arch of `MAX_RUN_VOUSSOIRS` has (the at-rest bisection's cost grows as their
            // cube: `VoussoirArch::runnable`).
            let max_drums = (crate::chain::arch::MAX_RUN_VOUSSOIRS - 1) / 2;
            match c.drums {
                None | Some(1) => {}
                Some(k) if (2..=max_drums).contains(&k) => {
                    let drum = crate::model::column::Block::rectangle(
                        c.width,
                        c.height / k as f64,
                        c.column_mass / k as f64,
                    );
                    frame.left = vec![drum; k];
                    frame.right = vec![drum; k];
                }
                Some(k) => {
                    return Err(err(
                        "colonnade.drums",
                        format!(
                            "{k}: must be at least 1 and at most {max_drums} (2 drums + 2 joints, \
                             as many as an arch of {} voussoirs: the time to find what the \
                             closed frame resists grows as the cube of the joints)",
                            crate::chain::arch::MAX_RUN_VOUSSOIRS
                        ),
                    ))
                }
            }
            if let Some(length) = c.beam_length {
                crate::validate::positive("colonnade.beam_length", length).map_err(invalid)?;
                if length < (c.span + c.width) * (1.0 - 1e-12) {
                    return Err(err(
                        "colonnade.beam_length",
                        format!(
                            "{length}: the beam must cover both column tops (at least span + \
                             width = {})",
                            c.span + c.width
                        ),
                    ));
                }
                frame.beam.width = length;
            }
            let chain = frame.chain().map_err(invalid)?;
            (LoopShape::Colonnade(frame), chain)
        }
        _ => return Err(err("arch", "give one of arch and colonnade")),
    };
    let solver = match spec.solver.as_deref() {
        None | Some("auto") => Solver::Auto,
        Some("enumerate") => Solver::Enumerate,
        Some("projection") => Solver::Projection,
        Some(other) => {
            return Err(err(
                "solver",
                format!("unknown solver {other:?} (auto, enumerate, projection)"),
            ))
        }
    };
    let positive = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(err(
                field,
                format!("{v}: must be a finite number greater than zero"),
            ))
        }
    };
    if spec.output.every == 0 {
        return Err(err("output.every", "must be >= 1"));
    }
    let defaults = LoopOptions::default();
    let min_flight = match spec.min_flight {
        None => defaults.min_flight,
        Some(k) if k.is_finite() && k >= 0.0 => k,
        Some(k) => {
            return Err(err(
                "min_flight",
                format!("{k}: must be a finite number of steps, zero or more"),
            ))
        }
    };
    // A zero duration is a run of no step, as for a column scene (the driver takes it).
    let duration = if spec.duration.is_finite() && spec.duration >= 0.0 {
        spec.duration
    } else {
        return Err(err(
            "duration",
            format!("{}: must be a finite number, zero or more", spec.duration),
        ));
    };
    let dt = positive("dt", spec.dt)?;
    // The loop driver's own limit, named as a column scene names it (the driver's message
    // printed the duration with all its digits: 300 of them for 1e300 s).
    if crate::validate::too_many_steps(duration, dt) {
        return Err(err(
            "dt",
            format!("{dt}: more than 1e10 steps for the duration"),
        ));
    }
    super::excitation::check_step_resolves(&excitation, dt)?;
    check_step_fits_the_chain(&chain, dt, spec.gravity.unwrap_or(defaults.gravity))?;
    spec.output.check_samples(duration, dt)?;
    let options = LoopOptions {
        gravity: positive("gravity", spec.gravity.unwrap_or(defaults.gravity))?,
        dt,
        duration,
        model: ModelOptions {
            solver,
            ..ModelOptions::default()
        },
        record_every: if spec.output.history {
            spec.output.every
        } else {
            0
        },
        min_flight,
        ..defaults
    };
    Ok(LoopScene {
        title: super::title(spec.title, name),
        shape,
        chain,
        excitation,
        options,
        output: spec.output,
    })
}

/// Refuses a step longer than a tenth of the chain's own time `√(L/g)`, `L` the distance between
/// its farthest joints: an arch of R = 1 µm with `dt` = 1 ms (three of its own times a step)
/// reported a collapse at 1.26 rad with a closure residual of 2 % of its size. Any real arch or
/// colonnade (L of metres: 0.05–0.1 s) passes any usual step.
fn check_step_fits_the_chain(chain: &Chain, dt: f64, gravity: f64) -> Result<(), SceneError> {
    let joints = chain.joints();
    let span = joints
        .iter()
        .flat_map(|a| joints.iter().map(move |b| (a.centre, b.centre)))
        .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
        .fold(0.0, f64::max);
    let own_time = (span / gravity).sqrt();
    if gravity > 0.0 && dt > 0.1 * own_time {
        return Err(err(
            "dt",
            format!(
                "{dt}: more than a tenth of the chain's own time √(L/g) = {own_time:.3e} s (L = \
                 {span:.3e} m between its farthest joints): at most {:.3e}",
                0.1 * own_time
            ),
        ));
    }
    Ok(())
}
