//! `rocking.simulate`: a scene (the CLI's schema, parsed by the library's `rocking::scene`)
//! through the reference driver (thesis 3.3, SPEC §5), with what `rocking simulate` writes: the
//! history (`history.csv`'s columns as numpy arrays), the events (`events.jsonl`'s objects) and
//! the summary (`summary.json`'s fields).

use std::path::PathBuf;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::driver::closed::LoopState;
use rocking::driver::simulate_loop_with_progress;
use rocking::driver::{self, History};
use rocking::ground::excitation::Excitation;
use rocking::ground::FnMotion;
use rocking::scene::{
    self, contact_events, loop_events, loop_joint_angles, AnyScene, ContactHistoryColumns,
    ContactSummary, LoopScene, LoopSummary, Scene, SceneSpec, Summary,
};

use crate::errors::value_error;
use crate::ground::Record;
use crate::json::to_python;
use crate::sweep::interruptible;

/// `message` without serde's trailing ` at line L column C`.
fn without_position(message: &str) -> &str {
    match message.rsplit_once(" at line ") {
        Some((head, tail))
            if tail
                .split_once(" column ")
                .is_some_and(|(l, c)| l.parse::<u64>().is_ok() && c.parse::<u64>().is_ok()) =>
        {
            head
        }
        _ => message,
    }
}

/// Runs a scene file (`path`) or a scene given as JSON text (`text`, record paths relative to
/// `base`, titled `name` unless it has a title). `record`, if given, replaces the scene's
/// excitation (a `Record` object, which the JSON schema can only name by path). Returns a dict:
/// `t`, `dof_angles`, `dof_rates`, `angles`, `rates`, `block_rotations`, `statuses` (arrays),
/// `events` (list of dicts), `summary` (dict), `title`.
#[pyfunction]
#[pyo3(signature = (path = None, text = None, base = None, name = None, record = None))]
pub fn _simulate<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    text: Option<&str>,
    base: Option<PathBuf>,
    name: Option<&str>,
    record: Option<PyRef<'py, Record>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (any, scene_name) = match (&path, text) {
        (Some(p), None) => {
            // A missing file is the OSError Python users expect (FileNotFoundError, …).
            crate::errors::readable(p)?;
            let s = scene::load_any(p).map_err(|e| value_error(e.to_string()))?;
            (s, Some(p.display().to_string()))
        }
        (None, Some(t)) => {
            // The line and column serde gives are those of the JSON the package wrote from the
            // user's dict: the field's path (`scene::parse`) is what locates the mistake.
            let spec: SceneSpec =
                scene::parse(t).map_err(|e| value_error(without_position(&e.0)))?;
            let base = base.unwrap_or_else(|| PathBuf::from("."));
            let s = scene::build_any(spec, &base, name.unwrap_or("scene"))
                .map_err(|e| value_error(e.to_string()))?;
            (s, None)
        }
        _ => return Err(value_error("give either a scene path or its JSON text")),
    };
    let excitation = record
        .map(|r| {
            Excitation::record(r.inner.clone()).map_err(|e| value_error(format!("excitation: {e}")))
        })
        .transpose()?;
    let mut scene = match any {
        AnyScene::Column(s) => s,
        AnyScene::Loop(mut s) => {
            if let Some(e) = excitation {
                s.excitation = e;
            }
            return loop_run(py, &s, scene_name);
        }
    };
    if let Some(e) = excitation {
        scene.excitation = e;
    }
    if scene.contact.is_some() {
        return contact_run(py, &scene, scene_name);
    }
    let (outcome, wall) = interruptible(py, |progress| {
        let excitation = &scene.excitation;
        let motion = FnMotion(|t| excitation.acceleration(t), excitation.end_time());
        driver::simulate(&scene.column, &motion, &scene.options, Some(progress))
    })?;
    let outcome = outcome.map_err(|e| value_error(e.to_string()))?;

    let d = PyDict::new(py);
    let empty = History {
        n_interfaces: scene.column.n_interfaces(),
        ..History::default()
    };
    let kept = outcome.history.as_ref().filter(|_| scene.output.history);
    history_arrays(&d, kept.unwrap_or(&empty))?;
    // As the CLI (no events.jsonl) and the contact and loop runs: none without output.events.
    let events = if scene.output.events {
        &outcome.events[..]
    } else {
        &[]
    };
    d.set_item("events", to_python(py, &events)?)?;
    let summary = Summary::of(&scene, scene_name, &outcome, wall);
    d.set_item("summary", to_python(py, &summary)?)?;
    d.set_item("title", &scene.title)?;
    d.set_item("scheme", "event_driven")?;
    Ok(d)
}

/// A scene that chose the contact scheme (joints that slide or fly: `scheme` `"moreau"` or
/// `"auto"`, `on_sliding`, `on_tension`; docs/multidrum.md), as `rocking simulate` runs it: the
/// columns of its `history.csv` (`t`, `x`, `y`, `block_rotations`, `slips`), its events and its
/// summary.
fn contact_run<'py>(
    py: Python<'py>,
    scene: &Scene,
    scene_name: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let options = scene.contact.as_ref().expect("a contact-scheme scene");
    let (outcome, wall) = interruptible(py, |progress| {
        scene
            .simulate_contact(Some(progress))
            .expect("a contact-scheme scene")
    })?;
    let outcome = outcome.map_err(value_error)?;
    let d = PyDict::new(py);
    let columns = outcome
        .history
        .as_ref()
        .filter(|_| scene.output.history)
        .map(|h| ContactHistoryColumns::of(h, &scene.column))
        .unwrap_or(ContactHistoryColumns {
            n: scene.column.n_interfaces(),
            ..ContactHistoryColumns::default()
        });
    let (n, len) = (columns.n, columns.len());
    let table = |values: Vec<f64>| {
        Array2::from_shape_vec((len, n), values)
            .expect("len × n values")
            .into_pyarray(py)
    };
    d.set_item("t", PyArray1::from_slice(py, &columns.t))?;
    d.set_item("x", table(columns.x))?;
    d.set_item("y", table(columns.y))?;
    d.set_item("block_rotations", table(columns.block_rotation))?;
    d.set_item("slips", table(columns.slip))?;
    let events = if scene.output.events {
        contact_events(&outcome)
    } else {
        Vec::new()
    };
    d.set_item("events", to_python(py, &events)?)?;
    let summary = ContactSummary::of(scene, scene_name, &outcome, options.dt, wall);
    d.set_item("summary", to_python(py, &summary)?)?;
    d.set_item("title", &scene.title)?;
    d.set_item("scheme", summary.scheme)?;
    Ok(d)
}

/// The history's columns (`history.csv`): per sample the DOF angles and rates (`2n`), the signed
/// interface angles and rates (`phĭ_k + phî_k`), the block rotations and the statuses (`n`).
fn history_arrays(d: &Bound<'_, PyDict>, h: &History) -> PyResult<()> {
    let py = d.py();
    let (n, len) = (h.n_interfaces, h.len());
    let signed = |dof: &[f64]| -> Vec<f64> {
        dof.chunks_exact(2 * n)
            .flat_map(|row| (0..n).map(move |k| row[k] + row[n + k]))
            .collect()
    };
    let table = |values: Vec<f64>, cols: usize| {
        Array2::from_shape_vec((len, cols), values)
            .expect("len × cols values")
            .into_pyarray(py)
    };
    d.set_item("t", PyArray1::from_slice(py, &h.t))?;
    d.set_item("dof_angles", table(h.phi.clone(), 2 * n))?;
    d.set_item("dof_rates", table(h.rates.clone(), 2 * n))?;
    d.set_item("angles", table(signed(&h.phi), n))?;
    d.set_item("rates", table(signed(&h.rates), n))?;
    d.set_item("block_rotations", table(h.block_angles.clone(), n))?;
    let statuses: Vec<i8> = h.statuses.iter().map(|s| s.as_i8()).collect();
    d.set_item(
        "statuses",
        Array2::from_shape_vec((len, n), statuses)
            .expect("len × n statuses")
            .into_pyarray(py),
    )?;
    Ok(())
}

/// A closed chain (`"arch"` or `"colonnade"` scene; docs/arches.md) through the loop driver, as
/// `rocking simulate` runs it: `t` and each joint's signed angle `angles` (`history.csv`), its
/// events and its summary.
fn loop_run<'py>(
    py: Python<'py>,
    scene: &LoopScene,
    scene_name: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    // Interruptible as the column runs are (Ctrl-C within 1 % of the duration).
    let (outcome, wall) = interruptible(py, |progress| {
        simulate_loop_with_progress(
            &scene.chain,
            &scene.excitation,
            LoopState::at_rest(&scene.chain),
            &scene.options,
            Some(progress),
        )
    })?;
    let outcome = outcome.map_err(|e| value_error(e.to_string()))?;
    let n = scene.chain.n_joints();
    let (t, angles) = if scene.output.history {
        loop_joint_angles(&outcome, n)
    } else {
        (Vec::new(), Vec::new())
    };
    let d = PyDict::new(py);
    d.set_item("t", PyArray1::from_slice(py, &t))?;
    d.set_item(
        "angles",
        Array2::from_shape_vec((t.len(), n), angles)
            .expect("len × n angles")
            .into_pyarray(py),
    )?;
    let events = if scene.output.events {
        loop_events(&outcome)
    } else {
        Vec::new()
    };
    d.set_item("events", to_python(py, &events)?)?;
    let summary = LoopSummary::of(scene, scene_name, &outcome, wall);
    d.set_item("summary", to_python(py, &summary)?)?;
    d.set_item("title", &scene.title)?;
    d.set_item("scheme", "loop")?;
    Ok(d)
}
