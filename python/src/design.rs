//! The thesis's design method (Eq. 21, 23, 24, 31) through `rocking::design`, with the fields
//! of `rocking design width|check --json`, elementwise over arrays of equal length (the Python
//! side broadcasts and reshapes).

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rocking::design::{self, Branch, EquivalentBlock, ImpulseFactor, MassDistribution};

use crate::errors::value_error;

fn mass_of(name: &str) -> PyResult<MassDistribution> {
    match name {
        "uniform" => Ok(MassDistribution::Uniform),
        "top" => Ok(MassDistribution::Top),
        _ => Err(value_error(format!(
            "mass = {name:?}: expected \"uniform\" or \"top\""
        ))),
    }
}

fn branch(b: Branch) -> &'static str {
    match b {
        Branch::NoRocking => "no-rocking",
        Branch::Impulse => "impulse",
    }
}

/// The library's error, the element named when the call is over arrays (`pga[3] = …`).
fn element_error(e: design::DesignError, index: Option<usize>) -> PyErr {
    match (e, index) {
        (design::DesignError::Invalid(mut v), Some(i)) => {
            v.field = format!("{}[{i}]", v.field);
            value_error(v)
        }
        (e, _) => value_error(e),
    }
}

/// Columns of floats, one per field, filled element by element.
struct Columns<'a> {
    names: &'a [&'static str],
    values: Vec<Vec<f64>>,
}

impl<'a> Columns<'a> {
    fn new(names: &'a [&'static str], len: usize) -> Columns<'a> {
        Columns {
            names,
            values: vec![Vec::with_capacity(len); names.len()],
        }
    }

    fn push(&mut self, row: &[f64]) {
        for (c, v) in self.values.iter_mut().zip(row) {
            c.push(*v);
        }
    }

    fn into_dict<'py>(self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, v) in self.names.iter().zip(self.values) {
            d.set_item(*name, PyArray1::from_vec(py, v))?;
        }
        Ok(d)
    }
}

/// `design width` (Eq. 31: Eq. 23 solved exactly, Eq. 24, at rest) for each `(height, pga, t1)`:
/// a dict of arrays `width`, `eq23`, `eq21_exact_icr`, `eq24`, `at_rest` and `governing` (a list
/// of ``"impulse"`` / ``"no-rocking"``).
#[pyfunction]
pub fn _design_width<'py>(
    py: Python<'py>,
    height: Vec<f64>,
    pga: Vec<f64>,
    t1: Vec<f64>,
    mass: &str,
    g: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let mass = mass_of(mass)?;
    let len = height.len();
    let index = |i| (len > 1).then_some(i);
    let names = ["width", "eq23", "eq21_exact_icr", "eq24", "at_rest"];
    let mut cols = Columns::new(&names, len);
    let mut governing = Vec::with_capacity(len);
    for i in 0..len {
        let w = design::pier_width(height[i], pga[i], t1[i], mass, g)
            .map_err(|e| element_error(e, index(i)))?;
        cols.push(&[w.required, w.eq23, w.eq21_exact_icr, w.eq24, w.at_rest]);
        governing.push(branch(w.governing));
    }
    let d = cols.into_dict(py)?;
    d.set_item("governing", governing)?;
    Ok(d)
}

/// `design check` (Eq. 31 with `i_cr = 1`, or Eq. 21 with `i_cr` of Eq. 18 when `exact_icr`) for
/// each `(width, height, pga, t1)`: a dict of arrays `safe` (bools), `a_p`, `a_p_min`, `p`,
/// `i_cr`, `impulse_limit`, `limit`, `utilisation` and `governing` (a list of strings).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn _design_check<'py>(
    py: Python<'py>,
    width: Vec<f64>,
    height: Vec<f64>,
    pga: Vec<f64>,
    t1: Vec<f64>,
    mass: &str,
    g: f64,
    exact_icr: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let mass = mass_of(mass)?;
    let factor = if exact_icr {
        ImpulseFactor::Exact
    } else {
        ImpulseFactor::One
    };
    let len = width.len();
    let index = |i| (len > 1).then_some(i);
    let names = [
        "a_p",
        "a_p_min",
        "p",
        "i_cr",
        "impulse_limit",
        "limit",
        "utilisation",
    ];
    let mut cols = Columns::new(&names, len);
    let (mut safe, mut governing) = (Vec::with_capacity(len), Vec::with_capacity(len));
    for i in 0..len {
        let pier = EquivalentBlock::new(width[i], height[i], mass)
            .map_err(|e| element_error(e.into(), index(i)))?;
        let c = design::design_check(&pier, pga[i], t1[i], g, factor)
            .map_err(|e| element_error(e, index(i)))?;
        cols.push(&[
            c.a_p,
            c.a_p_min,
            c.p,
            c.i_cr,
            c.impulse_limit,
            c.limit,
            c.utilisation,
        ]);
        safe.push(c.safe);
        governing.push(branch(c.governing));
    }
    let d = cols.into_dict(py)?;
    d.set_item("safe", PyArray1::from_vec(py, safe))?;
    d.set_item("governing", governing)?;
    Ok(d)
}
