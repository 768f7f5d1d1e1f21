//! The scene fields of the contact scheme (`src/contact/`, docs/multidrum.md): `friction` per
//! joint, `on_sliding`, `on_tension` and `scheme`, and the [`DrumOptions`] they give.
//!
//! ```json
//! "friction": 0.7,            (or one μ per joint: [0.7, 0.6, 0.6])
//! "on_sliding": "slide",      ("stop", the default: the thesis's driver stops at the first slip)
//! "on_tension": "fly",        ("stop", the default: it stops at the first tensile joint)
//! "scheme": "moreau"          ("event_driven", "moreau" or "auto"; default: "moreau" when a
//!                              joint may slide or fly, "event_driven" otherwise)
//! "energy_tolerance": 1e-6    (moreau, auto: the error control, `crate::contact::refine`)
//! "energy_consistent": true   (moreau, auto: the located impacts without their one-signed
//!                              energy errors, `crate::contact::consistent`; default false)
//! ```
//! `"auto"`: the event-driven driver where events are few, Moreau–Jean where they crowd
//! (`crate::contact::auto`, docs/auto-scheme.md); the driver's own settings
//! (integrator, locator, solver, exact velocity terms) apply to its parts.
//! With the defaults a scene runs on the event-driven driver exactly as before these fields.

use serde::Deserialize;

use super::{err, SceneError, SceneSpec};
use crate::contact::moreau::SchemeOptions;
use crate::contact::simulation::{DrumOptions, DrumOutcome, DrumRecording, OnSliding, OnTension};
use crate::ground::FnMotion;
use crate::model::column::{Column, GRAVITY};

/// Friction coefficient μ: one for every joint, or one per joint (bottom to top).
#[derive(Clone, Debug, Deserialize)]
#[serde(
    untagged,
    expecting = "friction: a number, or a list of one number per joint"
)]
pub enum FrictionSpec {
    /// The same μ at every joint.
    All(f64),
    /// One μ per joint.
    PerJoint(Vec<f64>),
}

/// The time stepping a scene asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SchemeChoice {
    /// The thesis's event-driven driver (`src/driver/`).
    EventDriven,
    /// Moreau–Jean time stepping with Coulomb friction and flight (`src/contact/`).
    Moreau,
    /// The driver where events are few, Moreau–Jean where they crowd (`crate::contact::auto`).
    Auto,
}

fn choice(field: &str, value: Option<&str>, allowed: [&str; 2]) -> Result<bool, SceneError> {
    match value {
        None => Ok(false),
        Some(v) if v == allowed[0] => Ok(false),
        Some(v) if v == allowed[1] => Ok(true),
        Some(other) => Err(err(
            field,
            format!("unknown value {other:?} ({}, {})", allowed[0], allowed[1]),
        )),
    }
}

/// The scheme a scene asks for, checked against its other fields.
pub(super) fn scheme(spec: &SceneSpec) -> Result<SchemeChoice, SceneError> {
    let slide = choice("on_sliding", spec.on_sliding.as_deref(), ["stop", "slide"])?;
    let fly = choice("on_tension", spec.on_tension.as_deref(), ["stop", "fly"])?;
    let moreau = match spec.scheme.as_deref() {
        None => slide || fly,
        Some("event_driven") => {
            if slide {
                return Err(err(
                    "on_sliding",
                    "\"slide\" needs scheme \"moreau\" (the event-driven driver stops at a slip)",
                ));
            }
            if fly {
                return Err(err(
                    "on_tension",
                    "\"fly\" needs scheme \"moreau\" (the event-driven driver stops at tension)",
                ));
            }
            false
        }
        Some("moreau") => true,
        Some("auto") => return Ok(SchemeChoice::Auto),
        Some(other) => {
            return Err(err(
                "scheme",
                format!("unknown scheme {other:?} (event_driven, moreau, auto)"),
            ))
        }
    };
    if !moreau {
        if spec.energy_tolerance.is_some() {
            return Err(err(
                "energy_tolerance",
                "applies to schemes \"moreau\" and \"auto\" (the error control of the time \
                 stepping)",
            ));
        }
        if spec.energy_consistent.unwrap_or(false) {
            return Err(err(
                "energy_consistent",
                "applies to schemes \"moreau\" and \"auto\" (the located impacts of the time \
                 stepping)",
            ));
        }
        if let Some(FrictionSpec::PerJoint(_)) = spec.friction {
            return Err(err(
                "friction",
                "one value per joint needs scheme \"moreau\" (the event-driven driver takes one μ)",
            ));
        }
        return Ok(SchemeChoice::EventDriven);
    }
    // The event-driven driver's own settings mean nothing to the time stepping: refuse them
    // rather than ignore them.
    let driver_only = [
        ("integrator", spec.integrator.is_some()),
        ("locator", spec.locator.is_some()),
        ("solver", spec.solver.is_some()),
        (
            "exact_velocity_terms",
            spec.exact_velocity_terms.unwrap_or(false),
        ),
    ];
    if let Some((field, _)) = driver_only.iter().find(|(_, set)| *set) {
        return Err(err(
            field,
            "applies to scheme \"event_driven\" only (the Moreau–Jean scheme integrates exact \
             rigid-body dynamics with its own contact solver)",
        ));
    }
    Ok(SchemeChoice::Moreau)
}

/// The scalar μ the event-driven driver takes (default 0.7).
pub(super) fn driver_friction(spec: &SceneSpec, default: f64) -> f64 {
    match &spec.friction {
        Some(FrictionSpec::All(mu)) => *mu,
        // Only with the Moreau scheme (checked in `scheme`); the driver's options are unused.
        // Scheme "auto": the driver's parts take the smallest (they stop, hand over, at a slip).
        Some(FrictionSpec::PerJoint(mu)) => mu.iter().copied().fold(f64::INFINITY, f64::min),
        None => default,
    }
}

/// An option's rule as a scene reads it: the options say that an infinite μ means no sliding,
/// which a scene cannot write (JSON has no infinity): it takes a large one.
pub(super) fn scene_rule(field: &str, rule: &str) -> String {
    if field == "friction" && rule.contains("infinity") {
        return "must be > 0 (no sliding: a large value such as 1e9; a frictionless joint, \
                μ = 0, is not modelled)"
            .into();
    }
    rule.to_string()
}

/// The options of the contact scheme for a scene that chose it.
pub(super) fn drum_options(spec: &SceneSpec, column: &Column) -> Result<DrumOptions, SceneError> {
    let (friction, joint_friction) = match &spec.friction {
        None => (DrumOptions::default().friction, None),
        Some(FrictionSpec::All(mu)) => (*mu, None),
        Some(FrictionSpec::PerJoint(mu)) => {
            // The count, which the options' check does not give ("needs one value per joint").
            let joints = column.n_interfaces();
            if mu.len() != joints {
                return Err(err(
                    "friction",
                    format!(
                        "{mu:?}: {} values for {joints} joints (one per drum, bottom to top: \
                         joint 0 under drum 0, on the ground)",
                        mu.len()
                    ),
                ));
            }
            (DrumOptions::default().friction, Some(mu.clone()))
        }
    };
    let options = DrumOptions {
        dt: spec.dt,
        duration: spec.duration,
        friction,
        joint_friction,
        on_sliding: if spec.on_sliding.as_deref() == Some("slide") {
            OnSliding::Slide
        } else {
            OnSliding::Stop
        },
        on_tension: if spec.on_tension.as_deref() == Some("fly") {
            OnTension::Fly
        } else {
            OnTension::Stop
        },
        scheme: SchemeOptions {
            n_impacts: spec.impacts.unwrap_or(1),
            gravity: spec.gravity.unwrap_or(GRAVITY),
            energy_tolerance: spec.energy_tolerance,
            energy_consistent: spec.energy_consistent.unwrap_or(false),
            ..SchemeOptions::default()
        },
        continue_until_fallen: spec.continue_until_fallen.unwrap_or(false),
        record: DrumRecording {
            history_every: spec.output.history.then_some(spec.output.every),
            events: true,
        },
        initial_angles: spec.initial_angles.clone(),
    };
    options.validate(column).map_err(|e| {
        // The options' names as the scene spells them.
        let field = match e.field {
            "joint_friction" => "friction",
            "scheme.n_impacts" => "impacts",
            "scheme.gravity" => "gravity",
            "scheme.energy_tolerance" => "energy_tolerance",
            "record.history_every" => "output.every",
            f => f,
        };
        err(field, format!("{}: {}", e.value, scene_rule(field, e.rule)))
    })?;
    spec.output.check_samples(spec.duration, spec.dt)?;
    Ok(options)
}

impl super::Scene {
    /// Runs a scene of the contact scheme (`contact` set): Moreau–Jean, or the automatic scheme
    /// where `auto` is set, reporting to `progress` as the drivers do; `None` for a scene of the
    /// event-driven driver. The one choice of scheme for the CLI and the Python package.
    pub fn simulate_contact(
        &self,
        progress: Option<&mut dyn FnMut(f64)>,
    ) -> Option<Result<DrumOutcome, String>> {
        let options = self.contact.as_ref()?;
        let excitation = &self.excitation;
        let motion = FnMotion(|t| excitation.acceleration(t), excitation.end_time());
        Some(match &self.auto {
            Some(rules) => crate::contact::auto::simulate(
                &self.column,
                &motion,
                &self.options,
                options,
                rules,
                progress,
            )
            .map_err(|e| e.to_string()),
            None => crate::contact::simulation::simulate(&self.column, &motion, options, progress)
                .map_err(|e| e.to_string()),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{build, Scene, SceneError, SceneSpec};
    use super::*;
    use std::path::Path;

    fn parse(extra: &str) -> Result<Scene, SceneError> {
        let text = format!(
            r#"{{"blocks": [{{"width": 1, "height": 1, "mass": 2500}},
                {{"width": 1, "height": 1, "mass": 2500}}],
            "excitation": {{"type": "half_sine", "amplitude": 5.0, "duration": 0.3}},
            "duration": 1.0, "dt": 0.001{extra}}}"#
        );
        let spec: SceneSpec = serde_json::from_str(&text).map_err(|e| SceneError(e.to_string()))?;
        build(spec, Path::new("."), "test")
    }

    #[test]
    fn the_defaults_keep_the_event_driven_driver() {
        let s = parse("").unwrap();
        assert!(s.contact.is_none());
        assert_eq!(s.options.physics.friction, 0.7);
        let s = parse(r#", "friction": 0.5, "on_sliding": "stop", "on_tension": "stop""#).unwrap();
        assert!(s.contact.is_none());
        assert_eq!(s.options.physics.friction, 0.5);
    }

    #[test]
    fn sliding_or_flight_chooses_the_contact_scheme() {
        let s = parse(r#", "on_sliding": "slide", "impacts": 2"#).unwrap();
        let c = s.contact.unwrap();
        assert_eq!(c.on_sliding, OnSliding::Slide);
        assert_eq!(c.on_tension, OnTension::Stop);
        assert_eq!(c.scheme.n_impacts, 2);
        assert_eq!(c.friction, 0.7);
        let s = parse(r#", "on_tension": "fly", "friction": [0.5, 0.6]"#).unwrap();
        let c = s.contact.unwrap();
        assert_eq!(
            (c.on_sliding, c.on_tension),
            (OnSliding::Stop, OnTension::Fly)
        );
        assert_eq!(c.joint_friction, Some(vec![0.5, 0.6]));
        let s = parse(r#", "scheme": "auto", "on_sliding": "slide", "integrator": "rk4""#).unwrap();
        assert!(s.auto.is_some());
        assert_eq!(s.contact.unwrap().on_sliding, OnSliding::Slide);
        let s = parse(r#", "scheme": "auto", "energy_tolerance": 1e-6"#).unwrap();
        assert_eq!(s.contact.unwrap().scheme.energy_tolerance, Some(1e-6));
        let s = parse(r#", "scheme": "moreau", "energy_consistent": true"#).unwrap();
        assert!(s.contact.unwrap().scheme.energy_consistent);
        let s = parse(r#", "scheme": "moreau", "friction": 0.4"#).unwrap();
        let c = s.contact.unwrap();
        assert_eq!(
            (c.on_sliding, c.on_tension),
            (OnSliding::Stop, OnTension::Stop)
        );
        assert_eq!(c.friction, 0.4);
    }

    /// A list of the wrong length says how many values the column needs (it said "needs one
    /// value per joint", and the user had to count the joints, the ground one included).
    #[test]
    fn a_friction_list_of_the_wrong_length_gives_the_count() {
        for (list, given) in [("[0.5]", 1), ("[0.5, 0.6, 0.7]", 3), ("[]", 0)] {
            let extra = format!(r#", "on_sliding": "slide", "friction": {list}"#);
            let e = parse(&extra).err().expect("accepted");
            assert!(
                e.0.starts_with("friction: ")
                    && e.0.contains(&format!("{given} values for 2 joints")),
                "{list}: {}",
                e.0
            );
        }
    }

    /// μ = 0 or below is refused in words a scene can act on: the options' "infinity: no
    /// sliding" cannot be written in JSON (a large μ can), on either scheme.
    #[test]
    fn a_friction_of_zero_says_what_a_scene_can_write() {
        for extra in [
            r#", "friction": 0"#,
            r#", "friction": -1"#,
            r#", "on_sliding": "slide", "friction": 0"#,
        ] {
            let e = parse(extra).err().expect("accepted");
            assert!(
                e.0.starts_with("friction: ") && e.0.contains("1e9") && !e.0.contains("infinity"),
                "{extra}: {}",
                e.0
            );
        }
    }

    #[test]
    fn errors_name_the_field() {
        for (extra, field) in [
            (r#", "on_sliding": "glide""#, "on_sliding"),
            (r#", "on_tension": "jump""#, "on_tension"),
            (r#", "scheme": "euler""#, "scheme"),
            (
                r#", "scheme": "event_driven", "on_sliding": "slide""#,
                "on_sliding",
            ),
            (
                r#", "scheme": "event_driven", "on_tension": "fly""#,
                "on_tension",
            ),
            (r#", "friction": [0.5, 0.6]"#, "friction"),
            (r#", "on_sliding": "slide", "friction": [0.5]"#, "friction"),
            (
                r#", "on_sliding": "slide", "friction": [0.5, -1]"#,
                "friction",
            ),
            (r#", "on_sliding": "slide", "friction": -1"#, "friction"),
            (
                r#", "on_sliding": "slide", "integrator": "rk4""#,
                "integrator",
            ),
            (
                r#", "on_sliding": "slide", "locator": "hermite""#,
                "locator",
            ),
            (r#", "on_sliding": "slide", "impacts": 0"#, "impacts"),
            (
                r#", "on_sliding": "slide", "initial_angles": [0.1]"#,
                "initial_angles",
            ),
            (r#", "friction": "much""#, "friction"),
            (r#", "energy_tolerance": 1e-6"#, "energy_tolerance"),
            (r#", "energy_consistent": true"#, "energy_consistent"),
            (
                r#", "on_sliding": "slide", "energy_tolerance": 0"#,
                "energy_tolerance",
            ),
        ] {
            let e = parse(extra)
                .err()
                .unwrap_or_else(|| panic!("accepted: {extra}"));
            assert!(e.0.contains(field), "{extra}: {}", e.0);
        }
    }
}
