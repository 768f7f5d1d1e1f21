//! The interface mass matrix and load: in closed form for a column of rectangular blocks
//! (`column_mass_matrix`, SPEC §1) or by the FE route of thesis Appendix C (`reduce`, `BᵀMB`).

use pyo3::prelude::*;
use rocking::model::configuration;
use rocking::model::interface_system::{self, BlockArrays};

use crate::arrays::{any_matrix, any_vector, matrix, new_matrix, new_vector, vector};
use crate::errors::IntoPy;

fn optional_vector(obj: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Option<Vec<f64>>> {
    obj.filter(|o| !o.is_none())
        .map(|o| any_vector(o, name))
        .transpose()
}

/// The interface mass matrix ``M`` (``2n × 2n``) and load vector ``q`` (``2n``) of a column of
/// rectangular blocks in the geometry of the DOF angles ``phi`` (SPEC §1; thesis Eq. 4–6 and
/// Eq. 10; equal to ``BᵀMB`` and ``Bᵀp`` of Appendix C, Eq. C12–C16).
///
/// ``width``, ``height``, ``mass``: one value per block, bottom first (m, m, kg). ``inertia``:
/// moments of inertia about the block centres (default: uniform rectangles,
/// ``m (w² + h²) / 12``). ``contact_width``: of the interface under each block (default
/// ``min(w_{k-1}, w_k)``). ``phi``: the ``2n`` DOF angles ``[phĭ_0 … phĭ_{n-1}, phî_0 …
/// phî_{n-1}]`` (default: the straight column). ``ground_acceleration`` (m/s², +x to the
/// right) and ``gravity`` (m/s², positive, acting downwards) make the load.
///
/// Returns ``(mass_matrix, load)``, new arrays.
#[pyfunction]
#[pyo3(signature = (width, height, mass, inertia = None, contact_width = None, phi = None, ground_acceleration = 0.0, gravity = 9.81))]
#[allow(clippy::too_many_arguments)]
pub fn column_mass_matrix<'py>(
    py: Python<'py>,
    width: &Bound<'py, PyAny>,
    height: &Bound<'py, PyAny>,
    mass: &Bound<'py, PyAny>,
    inertia: Option<&Bound<'py, PyAny>>,
    contact_width: Option<&Bound<'py, PyAny>>,
    phi: Option<&Bound<'py, PyAny>>,
    ground_acceleration: f64,
    gravity: f64,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let width = any_vector(width, "width")?;
    let n = width.len();
    configuration::check_size(n).py()?;
    let height = any_vector(height, "height")?;
    let block_mass = any_vector(mass, "mass")?;
    let inertia = optional_vector(inertia, "inertia")?;
    let contact_width = optional_vector(contact_width, "contact_width")?;
    let phi = optional_vector(phi, "phi")?;
    let blocks = BlockArrays {
        width: &width,
        height: &height,
        mass: &block_mass,
        inertia: inertia.as_deref(),
        contact_width: contact_width.as_deref(),
    };
    let system =
        interface_system::column_system(&blocks, phi.as_deref(), ground_acceleration, gravity)
            .py()?;
    Ok((
        new_matrix(py, system.mass, 2 * n, 2 * n).into_any(),
        new_vector(py, system.load).into_any(),
    ))
}

/// The FE route of thesis Appendix C (Eq. C2–C10): ``M̃ = BᵀMB`` and ``p̃ = Bᵀp``.
///
/// ``transformation`` is ``B`` (``n_nodal × n_reduced``: nodal displacements from the reduced
/// coordinates, e.g. the ``2n`` interface DOFs, Eq. C11, C14), ``nodal_mass`` the FE model's
/// ``n_nodal × n_nodal`` mass matrix (symmetric), ``nodal_load`` its ``n_nodal`` nodal loads
/// (optional).
///
/// Returns ``(reduced_mass, reduced_load)``; ``reduced_load`` is None without ``nodal_load``.
#[pyfunction]
#[pyo3(signature = (transformation, nodal_mass, nodal_load = None))]
pub fn reduce<'py>(
    py: Python<'py>,
    transformation: &Bound<'py, PyAny>,
    nodal_mass: &Bound<'py, PyAny>,
    nodal_load: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Option<Bound<'py, PyAny>>)> {
    let (b_rows, n_nodal, n_reduced) = any_matrix(transformation, "transformation")?;
    interface_system::check_reduction_sizes(n_nodal, n_reduced).py()?;
    // The checks of `rocking_reduce`, in its order.
    let mass = matrix(nodal_mass, "nodal_mass", n_nodal, n_nodal)?;
    configuration::check_symmetric(&mass, n_nodal).py()?;
    configuration::check_finite("transformation", &b_rows).py()?;
    let load = match nodal_load.filter(|o| !o.is_none()) {
        Some(p) => {
            let p = vector(p, "nodal_load", n_nodal)?;
            configuration::check_finite("nodal_load", &p).py()?;
            Some(p)
        }
        None => None,
    };
    // The library's storage is column-major (LAPACK, OpenSees); numpy's is row-major.
    let column_major = |rows: &[f64], r: usize, c: usize| -> Vec<f64> {
        (0..r * c).map(|i| rows[(i % r) * c + i / r]).collect()
    };
    let b = column_major(&b_rows, n_nodal, n_reduced);
    let mass = column_major(&mass, n_nodal, n_nodal);
    let p = load.clone().unwrap_or_else(|| vec![0.0; n_nodal]);
    let mut rm = vec![0.0; n_reduced * n_reduced];
    let mut rl = vec![0.0; n_reduced];
    rocking::model::column::reduce(n_nodal, n_reduced, &mass, &b, &p, &mut rm, &mut rl);
    configuration::check_result(&rm, &rl).py()?;
    // Column-major out, row-major for numpy (the reduced matrix is symmetric up to round-off).
    let rm = column_major(&rm, n_reduced, n_reduced);
    Ok((
        new_matrix(py, rm, n_reduced, n_reduced).into_any(),
        load.map(|_| new_vector(py, rl).into_any()),
    ))
}
