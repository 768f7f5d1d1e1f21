//! Scenes: a column, an excitation and simulation settings, as JSON — the one schema of
//! `rocking simulate` and the Python package's `rocking.simulate` (behind the `serde` feature).
//!
//! ```json
//! {
//!   "blocks": [{"width": 0.1, "height": 0.3, "mass": 15, "contact_width": 0.096}, ...],
//!   "initial_angles": [0.0, -0.153],
//!   "excitation": {"type": "half_sine", "amplitude": 3.0, "duration": 0.5},
//!   "impacts": 1, "duration": 2.0, "dt": 0.001, "integrator": "wilson"
//! }
//! ```
//! Unknown fields and bad values are errors that name the field. Record paths are relative to
//! the scene file. A closed chain (`"arch"` or `"colonnade"` in place of `"blocks"`,
//! [`closed`]) is read by [`load_any`].

use std::path::Path;

use crate::driver::{
    EventLocator, InitialState, Integrator, PhysicsOptions, Recording, SimulationOptions,
    SteppingOptions, StoppingOptions,
};
use crate::ground::excitation::Excitation;
use crate::model::column::{Block, Column};
use crate::model::cone::{ModelOptions, Solver};
use serde::Deserialize;

pub mod closed;
mod contact;
mod contact_outputs;
mod excitation;
mod json_path;
mod loop_outputs;
mod summary;
use crate::contact::auto::AutoOptions;
use crate::contact::simulation::DrumOptions;
pub use closed::{LoopScene, LoopShape};
pub use contact::{FrictionSpec, SchemeChoice};
pub use contact_outputs::{
    contact_events, mode_name, rest, stop_name, ContactEnergy, ContactHistoryColumns,
    ContactSummary,
};
use excitation::excitation;
pub use excitation::ExcitationSpec;
pub use json_path::parse;
pub use loop_outputs::{hinges, loop_event_name, loop_events, loop_joint_angles, LoopSummary};
pub use summary::{Energy, Summary};

/// One block, bottom to top.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    pub width: f64,
    pub height: f64,
    pub mass: f64,
    #[serde(default)]
    pub inertia: Option<f64>,
    #[serde(default)]
    pub contact_width: Option<f64>,
}

/// Integrator choice: a name, or an object with parameters (no other field: one is refused, not
/// ignored).
#[derive(Debug, Deserialize)]
#[serde(
    untagged,
    deny_unknown_fields,
    expecting = "integrator: a name (\"wilson\", \"newmark\", \"rk4\", \"dop853\") or {\"type\": \"wilson\", \"theta\": θ} and no other field"
)]
pub enum IntegratorSpec {
    Name(String),
    Wilson {
        #[serde(rename = "type")]
        kind: String,
        theta: f64,
    },
}

/// What to write.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Write `history.csv` (default true).
    #[serde(default = "yes")]
    pub history: bool,
    /// Keep every k-th step in the history (default 1).
    #[serde(default = "one")]
    pub every: usize,
    /// Write `events.jsonl` (default true).
    #[serde(default = "yes")]
    pub events: bool,
}

fn yes() -> bool {
    true
}
fn one() -> usize {
    1
}

/// History samples a scene may keep at most (`duration / dt / every`). Beyond it the history alone
/// would need gigabytes of memory (about 85 bytes a sample for one block, more for each block or
/// voussoir), and a run killed for lack of memory takes its caller with it.
pub const MAX_HISTORY_SAMPLES: f64 = 1e8;

impl OutputSpec {
    /// Refuses a history of more than [`MAX_HISTORY_SAMPLES`] samples over `duration` at steps of
    /// `dt`, naming `output.every` and what would do.
    pub(crate) fn check_samples(&self, duration: f64, dt: f64) -> Result<(), SceneError> {
        let steps = duration / dt;
        let samples = steps / self.every.max(1) as f64;
        if self.history && samples > MAX_HISTORY_SAMPLES {
            return Err(err(
                "output.every",
                format!(
                    "{}: {samples:.3e} history samples (duration / dt / every), more than \
                     {MAX_HISTORY_SAMPLES:.0e}: keep every k-th step with k >= {}, or set \
                     output.history false",
                    self.every,
                    (steps / MAX_HISTORY_SAMPLES).ceil()
                ),
            ));
        }
        Ok(())
    }
}

impl Default for OutputSpec {
    fn default() -> OutputSpec {
        OutputSpec {
            history: true,
            every: 1,
            events: true,
        }
    }
}

/// A scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// Optional title for plots and the summary.
    #[serde(default)]
    pub title: Option<String>,
    /// The column, bottom to top (or `arch` / `colonnade`: a closed chain).
    #[serde(default)]
    pub blocks: Vec<BlockSpec>,
    /// A voussoir arch instead of a column ([`closed`]).
    #[serde(default)]
    pub arch: Option<closed::ArchSpec>,
    /// A capped colonnade instead of a column ([`closed`]).
    #[serde(default)]
    pub colonnade: Option<closed::ColonnadeSpec>,
    #[serde(default)]
    pub initial_angles: Option<Vec<f64>>,
    pub excitation: ExcitationSpec,
    /// Consecutive impacts per closing (default 1). Optional, so that a closed chain's scene can
    /// refuse it whatever its value.
    #[serde(default)]
    pub impacts: Option<u32>,
    pub duration: f64,
    pub dt: f64,
    /// "wilson" (default), "newmark", "rk4", "dop853", or `{"type": "wilson", "theta": 1.4}`.
    #[serde(default)]
    pub integrator: Option<IntegratorSpec>,
    /// "linear" (thesis, default) or "hermite" (refined by re-integration with "dop853").
    #[serde(default)]
    pub locator: Option<String>,
    /// "auto" (default), "enumerate" or "projection".
    #[serde(default)]
    pub solver: Option<String>,
    /// Friction coefficient μ (default 0.7): one number, or one per joint (scheme "moreau").
    #[serde(default)]
    pub friction: Option<FrictionSpec>,
    /// What a sliding joint does: "stop" (default: the thesis's driver) or "slide".
    #[serde(default)]
    pub on_sliding: Option<String>,
    /// What a joint that would carry tension does: "stop" (default) or "fly".
    #[serde(default)]
    pub on_tension: Option<String>,
    /// "event_driven", "moreau" or "auto" (default: "moreau" when a joint may slide or fly).
    #[serde(default)]
    pub scheme: Option<String>,
    #[serde(default)]
    pub gravity: Option<f64>,
    /// Closed chains only: a joint an impact opens whose predicted flight is shorter than this
    /// many steps stays closed (`LoopOptions::min_flight`; default 0, docs/arch-performance.md).
    #[serde(default)]
    pub min_flight: Option<f64>,
    /// Schemes "moreau" and "auto": the error control of the time stepping (a step whose energy
    /// error exceeds this fraction of the run's energy scale is redone as two halves; default
    /// none, `crate::contact::refine`).
    #[serde(default)]
    pub energy_tolerance: Option<f64>,
    /// Schemes "moreau" and "auto": remove the located impacts' one-signed energy errors at
    /// their source (default false, `crate::contact::consistent`).
    #[serde(default)]
    pub energy_consistent: Option<bool>,
    /// Exact Lagrangian velocity terms (default false: thesis Eq. 6).
    #[serde(default)]
    pub exact_velocity_terms: Option<bool>,
    /// Integrate on after static tipping until a block has fallen (default false).
    #[serde(default)]
    pub continue_until_fallen: Option<bool>,
    #[serde(default)]
    pub output: OutputSpec,
}

/// A scene ready to simulate.
pub struct Scene {
    pub title: String,
    pub column: Column,
    pub excitation: Excitation,
    /// The event-driven driver's options (the scheme "event_driven").
    pub options: SimulationOptions,
    /// The contact scheme's options when the scene chose it (`src/contact/`); `None`: the
    /// event-driven driver runs the scene.
    pub contact: Option<DrumOptions>,
    /// Scheme "auto": the rules of the hand-overs between `options` (the driver) and `contact`
    /// (Moreau–Jean), both set; `None`: one scheme runs the whole scene.
    pub auto: Option<AutoOptions>,
    pub output: OutputSpec,
}

/// A scene error: the field and what is wrong with it.
#[derive(Debug)]
pub struct SceneError(pub String);

impl std::fmt::Display for SceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

/// A scene's title: its own, or the name it was read under when it has none or a blank one
/// (an empty title printed ": end of duration" and drew charts titled " — record …").
fn title(own: Option<String>, name: &str) -> String {
    own.filter(|t| !t.trim().is_empty())
        .unwrap_or_else(|| name.to_string())
}

fn err(field: &str, message: impl std::fmt::Display) -> SceneError {
    SceneError(format!("{field}: {message}"))
}

/// Reads and checks a scene file of a column.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let (spec, base) = read(path)?;
    build(spec, base, &path.display().to_string())
}

fn read(path: &Path) -> Result<(SceneSpec, &Path), SceneError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| SceneError(format!("cannot read {}: {e}", path.display())))?;
    // Without the byte-order mark Windows editors write first (serde refused it at 1:1).
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let spec = parse(text).map_err(|e| SceneError(format!("{}: {e}", path.display())))?;
    Ok((spec, path.parent().unwrap_or(Path::new("."))))
}

/// A scene of a column or of a closed chain.
pub enum AnyScene {
    Column(Box<Scene>),
    Loop(Box<LoopScene>),
}

/// Reads and checks a scene file of a column or of a closed chain (`arch`, `colonnade`).
pub fn load_any(path: &Path) -> Result<AnyScene, SceneError> {
    let (spec, base) = read(path)?;
    build_any(spec, base, &path.display().to_string())
}

/// [`build`] for a column, [`closed`] for an arch or a colonnade.
pub fn build_any(spec: SceneSpec, base: &Path, name: &str) -> Result<AnyScene, SceneError> {
    if spec.arch.is_none() && spec.colonnade.is_none() {
        return build(spec, base, name).map(|s| AnyScene::Column(Box::new(s)));
    }
    let excitation = excitation(&spec.excitation, base)?;
    closed::build(spec, excitation, name).map(|s| AnyScene::Loop(Box::new(s)))
}

/// Checks a parsed scene and builds the column, excitation and options.
pub fn build(spec: SceneSpec, base: &Path, name: &str) -> Result<Scene, SceneError> {
    if spec.arch.is_some() || spec.colonnade.is_some() {
        let field = if spec.arch.is_some() {
            "arch"
        } else {
            "colonnade"
        };
        return Err(err(
            field,
            "a closed chain, not a column: read it with scene::load_any",
        ));
    }
    if spec.min_flight.is_some() {
        return Err(err(
            "min_flight",
            "used by a closed chain (arch, colonnade) only",
        ));
    }
    if spec.blocks.is_empty() {
        return Err(err("blocks", "needs at least one block"));
    }
    let blocks = spec
        .blocks
        .iter()
        .map(|b| Block {
            width: b.width,
            height: b.height,
            mass: b.mass,
            inertia: b.inertia,
            contact_width: b.contact_width,
        })
        .collect();
    let column = Column::new(blocks).map_err(|e| match e {
        crate::model::column::ColumnError::InvalidBlock { block, invalid } => err(
            &format!("blocks[{block}].{}", invalid.field),
            format!("{}: {}", invalid.value, invalid.rule),
        ),
        crate::model::column::ColumnError::TooLarge { block, quantity } => err(
            &format!("blocks[{block}]"),
            format!(
                "{quantity} is not finite in double precision: the inputs are too large (use \
                 other units)"
            ),
        ),
        other => err("blocks", other),
    })?;
    let excitation = excitation(&spec.excitation, base)?;
    let scheme = contact::scheme(&spec)?;
    let contact = match scheme {
        SchemeChoice::EventDriven => None,
        SchemeChoice::Moreau | SchemeChoice::Auto => Some(contact::drum_options(&spec, &column)?),
    };
    let auto = (scheme == SchemeChoice::Auto).then(|| AutoOptions::for_step(spec.dt));
    let integrator = match &spec.integrator {
        None => Integrator::default(),
        Some(IntegratorSpec::Name(n)) => match n.as_str() {
            "wilson" | "wilson_theta" => Integrator::default(),
            "newmark" => Integrator::Newmark,
            "rk4" => Integrator::Rk4,
            "dop853" => Integrator::Dop853,
            other => {
                return Err(err(
                    "integrator",
                    format!("unknown integrator {other:?} (wilson, newmark, rk4, dop853)"),
                ))
            }
        },
        Some(IntegratorSpec::Wilson { kind, theta }) => {
            if kind != "wilson" && kind != "wilson_theta" {
                return Err(err(
                    "integrator.type",
                    format!("{kind:?}: only \"wilson\" takes parameters"),
                ));
            }
            Integrator::WilsonTheta { theta: *theta }
        }
    };
    let locator = match spec.locator.as_deref() {
        None | Some("linear") => EventLocator::Linear,
        Some("hermite") => EventLocator::Hermite,
        Some(other) => {
            return Err(err(
                "locator",
                format!("unknown locator {other:?} (linear, hermite)"),
            ))
        }
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
    if spec.output.every == 0 {
        return Err(err("output.every", "must be >= 1"));
    }
    let defaults = SimulationOptions::default();
    let options = SimulationOptions {
        stepping: SteppingOptions {
            dt: spec.dt,
            integrator,
            locator,
            ..defaults.stepping
        },
        stopping: StoppingOptions {
            duration: spec.duration,
            continue_until_fallen: spec.continue_until_fallen.unwrap_or(false),
            ..defaults.stopping
        },
        physics: PhysicsOptions {
            model: ModelOptions {
                n_impacts: spec.impacts.unwrap_or(1),
                solver,
                ..ModelOptions::default()
            },
            friction: contact::driver_friction(&spec, defaults.physics.friction),
            gravity: spec.gravity.unwrap_or(defaults.physics.gravity),
            exact_velocity_terms: spec.exact_velocity_terms.unwrap_or(false),
        },
        recording: Recording {
            history_every: spec.output.history.then_some(spec.output.every),
            events: true,
        },
        initial: InitialState {
            angles: spec.initial_angles,
        },
    };
    options.validate(&column).map_err(|e| match e {
        crate::driver::DriverError::InvalidOption(v) => {
            // The option's path without its group (`stepping.dt` → `dt`), as the scene names it.
            let field = match v.field.split_once('.').map_or(v.field.as_str(), |(_, f)| f) {
                "angles" => "initial_angles",
                "history_every" => "output.every",
                f => f,
            };
            err(
                field,
                format!("{}: {}", v.value, contact::scene_rule(field, v.rule)),
            )
        }
        crate::driver::DriverError::Model(e) => {
            let field = if e.kind == crate::ErrorKind::InvalidOptions {
                "impacts"
            } else {
                "scene"
            };
            err(field, e)
        }
    })?;
    // Before the run: it failed at the first opening with "model error: enumeration refused",
    // the field not named (a thirty-drum column with "solver": "enumerate").
    let limit = options.physics.model.max_enumerated_closed;
    if solver == Solver::Enumerate && column.n_interfaces() > limit {
        return Err(err(
            "solver",
            format!(
                "\"enumerate\" takes at most {limit} closed joints and the column has {}: \
                 \"projection\" or \"auto\"",
                column.n_interfaces()
            ),
        ));
    }
    excitation::check_step_resolves(&excitation, spec.dt)?;
    check_step_fits_the_column(&column, spec.dt, options.physics.gravity)?;
    spec.output.check_samples(spec.duration, spec.dt)?;
    Ok(Scene {
        title: title(spec.title, name),
        column,
        excitation,
        options,
        contact,
        auto,
        output: spec.output,
    })
}

/// Refuses a step longer than a tenth of the column's own time `√(H/g)`, `H` its height, as loop
/// scenes refuse a step beyond a tenth of their chain's `√(L/g)`: a 10 nm block at `dt` = 1 ms
/// (some 30 of its own times a step) ended by "tension" with a peak rotation of 88 rad. Real
/// columns (H of decimetres and more: 0.01 s and longer) pass any usual step.
fn check_step_fits_the_column(column: &Column, dt: f64, gravity: f64) -> Result<(), SceneError> {
    let height: f64 = column.blocks().iter().map(|b| b.height).sum();
    let own_time = (height / gravity).sqrt();
    if gravity > 0.0 && dt > 0.1 * own_time {
        return Err(err(
            "dt",
            format!(
                "{dt}: more than a tenth of the column's own time √(H/g) = {own_time:.3e} s \
                 (H = {height:.3e} m, its height): at most {:.3e}",
                0.1 * own_time
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests;
