//! The ground motion of a scene: the `excitation` object (a pulse, a record file, the synthetic
//! record, or none) and its conversion to an [`Excitation`], with errors that name the field.

use std::path::{Path, PathBuf};

use super::{err, SceneError};
use crate::ground::excitation::{Excitation, Pulse};
use crate::ground::records::{self, PlainFormat};
use serde::Deserialize;

/// The ground motion.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum ExcitationSpec {
    /// No excitation (free rocking from `initial_angles`). A struct variant with no field, so
    /// that a field given with it is refused (serde ignores them beside a unit variant).
    None {},
    /// `amplitude · sin(π t / duration)` on `[0, duration]` (thesis Fig. 8a).
    HalfSine { amplitude: f64, duration: f64 },
    /// One full period of a sine; `duration` is the WHOLE period (each lobe lasts duration/2;
    /// the thesis's `t_p` of Fig. 8b is the lobe).
    FullSine { amplitude: f64, duration: f64 },
    /// `count` consecutive half sines of alternating sign, each lasting `duration` (thesis Fig. 8c:
    /// three half sines).
    HalfSines {
        amplitude: f64,
        duration: f64,
        count: u32,
    },
    /// Constant `amplitude` on `[0, duration)`.
    Rectangular { amplitude: f64, duration: f64 },
    /// Symmetric triangle peaking at `duration / 2`.
    Triangular { amplitude: f64, duration: f64 },
    /// Ricker wavelet of peak `amplitude` and central `frequency` (Hz).
    Ricker { amplitude: f64, frequency: f64 },
    /// Mavroeidis–Papageorgiou (2003) pulse of peak acceleration `amplitude`.
    MavroeidisPapageorgiou {
        amplitude: f64,
        frequency: f64,
        gamma: f64,
        nu: f64,
    },
    /// A recorded motion: PEER `.AT2` (in g), or plain text (one column with `dt`, or two
    /// columns t, a) in m/s² unless `units` is "g" or "cm/s2". Scaled to `scale_to_pga` [m/s²]
    /// if given.
    Record {
        path: PathBuf,
        #[serde(default)]
        scale_to_pga: Option<f64>,
        #[serde(default)]
        dt: Option<f64>,
        #[serde(default)]
        units: Option<String>,
    },
}

pub(super) fn excitation(spec: &ExcitationSpec, base: &Path) -> Result<Excitation, SceneError> {
    let pulse = |p: Result<Pulse, crate::ground::excitation::ExcitationError>| {
        p.and_then(Excitation::pulse)
            .map_err(|e| err("excitation", e))
    };
    let positive = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(err(
                &format!("excitation.{field}"),
                format!("{v}: must be a finite number greater than zero"),
            ))
        }
    };
    let finite = |field: &str, v: f64| {
        if v.is_finite() {
            Ok(())
        } else {
            Err(err(
                &format!("excitation.{field}"),
                format!("{v}: must be finite"),
            ))
        }
    };
    match spec {
        ExcitationSpec::None {} | ExcitationSpec::Record { .. } => {}
        ExcitationSpec::HalfSine {
            amplitude,
            duration,
        }
        | ExcitationSpec::FullSine {
            amplitude,
            duration,
        }
        | ExcitationSpec::Rectangular {
            amplitude,
            duration,
        }
        | ExcitationSpec::Triangular {
            amplitude,
            duration,
        }
        | ExcitationSpec::HalfSines {
            amplitude,
            duration,
            ..
        } => {
            finite("amplitude", *amplitude)?;
            positive("duration", *duration)?;
        }
        ExcitationSpec::Ricker {
            amplitude,
            frequency,
        } => {
            finite("amplitude", *amplitude)?;
            positive("frequency", *frequency)?;
        }
        ExcitationSpec::MavroeidisPapageorgiou {
            amplitude,
            frequency,
            nu,
            ..
        } => {
            finite("amplitude", *amplitude)?;
            positive("frequency", *frequency)?;
            finite("nu", *nu)?;
        }
    }
    if let ExcitationSpec::HalfSines { count: 0, .. } = spec {
        return Err(err("excitation.count", "0: must be >= 1"));
    }
    match spec {
        ExcitationSpec::None {} => Ok(Excitation::None),
        ExcitationSpec::HalfSine {
            amplitude,
            duration,
        } => pulse(Pulse::half_sine(*amplitude, *duration)),
        ExcitationSpec::FullSine {
            amplitude,
            duration,
        } => pulse(Pulse::full_sine(*amplitude, 0.5 * duration)),
        ExcitationSpec::HalfSines {
            amplitude,
            duration,
            count,
        } => pulse(Pulse::half_sines(*amplitude, *duration, *count)),
        ExcitationSpec::Rectangular {
            amplitude,
            duration,
        } => pulse(Pulse::rectangular(*amplitude, *duration)),
        ExcitationSpec::Triangular {
            amplitude,
            duration,
        } => pulse(Pulse::triangular(*amplitude, *duration)),
        ExcitationSpec::Ricker {
            amplitude,
            frequency,
        } => pulse(Pulse::ricker(*amplitude, *frequency)),
        ExcitationSpec::MavroeidisPapageorgiou {
            amplitude,
            frequency,
            gamma,
            nu,
        } => pulse(Pulse::mavroeidis_papageorgiou(
            *amplitude, *frequency, *gamma, *nu,
        )),
        ExcitationSpec::Record {
            path,
            scale_to_pga,
            dt,
            units,
        } => {
            let full = if path.is_absolute() {
                path.clone()
            } else {
                base.join(path)
            };
            // A PEER `.AT2` file states its own step and is in g: a `dt` or other `units` given
            // for it would be ignored, so name them (a record in m/s² under an `.AT2` name would
            // run 9.81 times too strong).
            if records::is_at2(&full) {
                if let Some(step) = dt {
                    return Err(err(
                        "excitation.dt",
                        format!(
                            "{step}: a PEER .AT2 record gives its own step (DT in its header); \
                             dt is for plain-text records of one column"
                        ),
                    ));
                }
                if let Some(u) = units.as_deref().filter(|u| *u != "g") {
                    return Err(err(
                        "excitation.units",
                        format!(
                            "{u:?}: a PEER .AT2 record is in g (units \"g\" or none); other \
                             units are for plain-text records"
                        ),
                    ));
                }
            }
            // As `rocking.read_record` reads them (many catalogues are in gal).
            let scale = match units.as_deref() {
                None => 1.0,
                Some(u) => records::units_scale(u).ok_or_else(|| {
                    err(
                        "excitation.units",
                        format!("unknown units {u:?} (m/s2, g, cm/s2)"),
                    )
                })?,
            };
            let format = PlainFormat { dt: *dt, scale };
            let mut record =
                records::read_record(&full, &format).map_err(|e| err("excitation.path", e))?;
            if let Some(target) = scale_to_pga {
                record = record
                    .scaled_to_pga(*target)
                    .map_err(|e| err("excitation.scale_to_pga", e))?;
            }
            Excitation::record(record).map_err(|e| err("excitation", e))
        }
    }
}

/// Steps over a pulse a driver needs at least. At rest the drivers ask the opening model (or the
/// reaction test) at each step, so a step as long as the pulse can skip it whole (a 0.5 s
/// half-sine with `dt = 1` left an arch, and a column, at rest: "0 events"); ten steps over the
/// pulse see it.
const STEPS_PER_PULSE: f64 = 10.0;

/// Refuses a step that skips the ground motion: longer than a tenth of a pulse, or than a
/// record's own step (the record's samples between two steps would be skipped). Column, drum
/// and loop scenes alike.
pub(super) fn check_step_resolves(excitation: &Excitation, dt: f64) -> Result<(), SceneError> {
    let (limit, what) = match excitation {
        Excitation::None => return Ok(()),
        Excitation::Pulse(p) => (
            p.end_time() / STEPS_PER_PULSE,
            format!(
                "more than a tenth of the pulse ({} s): at most {}, or the structure at rest can \
                 miss the pulse",
                p.end_time(),
                p.end_time() / STEPS_PER_PULSE
            ),
        ),
        Excitation::Record(r) => (
            r.dt,
            format!(
                "more than the record's own step: at most {}, or the samples between two steps \
                 are skipped",
                r.dt
            ),
        ),
    };
    if dt > limit * (1.0 + 1e-9) {
        return Err(err("dt", format!("{dt}: {what}")));
    }
    Ok(())
}
