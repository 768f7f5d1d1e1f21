//! `rocking._rocking`: the Python extension of the `rocking` library (PyO3 + rust-numpy). The
//! package `rocking` (the `rocking/` folder beside this crate) re-exports it.
//!
//! Thin by design: every function converts its array-likes once (`arrays.rs`), calls the library
//! function of the same meaning, and returns new numpy arrays; errors become the one exception
//! `rocking.RockingError` with the C ABI's status code (`errors.rs`). The physics lives in the
//! library, free of Python.

mod arch;
mod arrays;
mod column;
mod design;
mod errors;
mod ground;
mod json;
mod models;
mod simulate;
mod spectra;
mod sweep;

use pyo3::prelude::*;

/// The allocator of the `rocking` CLI (cli/src/main.rs): the models allocate a few small vectors
/// per event, and a sweep spends much of its time in glibc's allocator. It serves only this
/// extension's Rust allocations (numpy arrays made from Rust vectors are freed by Rust too);
/// Python's own memory is untouched.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[pymodule]
fn _rocking(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("RockingError", py.get_type::<errors::RockingError>())?;
    m.add_function(wrap_pyfunction!(errors::error_codes, m)?)?;
    m.add_class::<models::Report>()?;
    m.add_function(wrap_pyfunction!(models::impact_model, m)?)?;
    m.add_function(wrap_pyfunction!(models::opening_model, m)?)?;
    m.add_function(wrap_pyfunction!(models::check_configuration, m)?)?;
    m.add_function(wrap_pyfunction!(models::_time_impact_model, m)?)?;
    m.add_function(wrap_pyfunction!(models::_report, m)?)?;
    m.add_function(wrap_pyfunction!(column::column_mass_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(column::reduce, m)?)?;
    m.add_class::<ground::Record>()?;
    m.add_class::<ground::Pulse>()?;
    m.add_function(wrap_pyfunction!(ground::read_record, m)?)?;
    m.add_function(wrap_pyfunction!(ground::half_sine, m)?)?;
    m.add_function(wrap_pyfunction!(ground::full_sine, m)?)?;
    m.add_function(wrap_pyfunction!(ground::half_sines, m)?)?;
    m.add_function(wrap_pyfunction!(ground::rectangular, m)?)?;
    m.add_function(wrap_pyfunction!(ground::triangular, m)?)?;
    m.add_function(wrap_pyfunction!(ground::ricker, m)?)?;
    m.add_function(wrap_pyfunction!(ground::mavroeidis_papageorgiou, m)?)?;
    // The driver, the spectra and the design method: wrapped by the Python side
    // (rocking/_simulate.py, _spectra.py, _design.py), which adds the result classes and plots.
    m.add_function(wrap_pyfunction!(simulate::_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(spectra::_oas, m)?)?;
    m.add_function(wrap_pyfunction!(spectra::_t1, m)?)?;
    // The defaults of `t1`'s convergence in the step (`rocking t1 --converge-step`'s).
    m.add("STEP_TOLERANCE", rocking::spectra::STEP_TOLERANCE)?;
    m.add("STEP_HALVINGS", rocking::spectra::STEP_HALVINGS)?;
    // The most threads a sweep starts (`threads=`).
    m.add("MAX_THREADS", sweep::MAX_THREADS)?;
    // The most points a grid count asks for (`levels=`, `sizes=`, …).
    m.add("MAX_COUNT", sweep::MAX_COUNT)?;
    m.add_function(wrap_pyfunction!(spectra::_oc, m)?)?;
    m.add_function(wrap_pyfunction!(spectra::_simplified_oas, m)?)?;
    m.add_function(wrap_pyfunction!(spectra::_tp, m)?)?;
    m.add_function(wrap_pyfunction!(spectra::_suite, m)?)?;
    m.add_function(wrap_pyfunction!(arch::_arch_oas, m)?)?;
    m.add_function(wrap_pyfunction!(arch::_arch_oc, m)?)?;
    m.add_function(wrap_pyfunction!(arch::_arch_suite, m)?)?;
    m.add_function(wrap_pyfunction!(design::_design_width, m)?)?;
    m.add_function(wrap_pyfunction!(design::_design_check, m)?)?;
    Ok(())
}
