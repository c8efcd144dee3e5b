//! Python bindings of the MRD validation workbench (module `mrdw._mrdw`, re-exported by
//! the package `mrdw`). Thin wrappers: every computation is the Rust crates' own, so
//! results are bit-identical to the CLI's. Arrays come in as numpy (converted once) and
//! go out as numpy arrays that own their data; long solves release the GIL.

#[macro_use]
mod grid_getters;
#[macro_use]
mod on_operator;
#[macro_use]
mod step_class;
mod adhesive;
mod axisym;
mod cohesive;
mod contact;
mod errors;
mod law;
mod plastic;
mod rough;
mod scene;
mod shared_heights;
mod tangential;
mod transient;

use pyo3::prelude::*;

#[pymodule]
fn _mrdw(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add(
        "ConvergenceError",
        py.get_type::<errors::ConvergenceError>(),
    )?;
    // 3D
    m.add_class::<contact::Contact>()?;
    m.add_class::<contact::ContactResult>()?;
    m.add_class::<transient::TransientContact>()?;
    m.add_class::<transient::TransientStep>()?;
    m.add_class::<adhesive::AdhesiveContact>()?;
    m.add_class::<adhesive::AdhesiveStep>()?;
    m.add_class::<cohesive::CohesiveContact>()?;
    m.add_class::<cohesive::CohesiveStep>()?;
    m.add_class::<law::ContactLaw>()?;
    m.add_class::<law::LawForces>()?;
    m.add_class::<plastic::PlasticContact>()?;
    m.add_class::<plastic::PlasticStep>()?;
    m.add_class::<tangential::PartialSlip>()?;
    m.add_class::<tangential::TangentialStep>()?;
    m.add_class::<tangential::ViscoelasticSlip>()?;
    m.add_class::<tangential::ViscoelasticStep>()?;
    m.add_function(wrap_pyfunction!(tangential::stick_stiffness, m)?)?;
    // roughness
    m.add_function(wrap_pyfunction!(rough::spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(rough::line_spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(rough::calibrated_lambda, m)?)?;
    m.add_function(wrap_pyfunction!(rough::calibrated_lambda_table, m)?)?;
    m.add_function(wrap_pyfunction!(rough::surface, m)?)?;
    m.add_function(wrap_pyfunction!(rough::line, m)?)?;
    m.add_function(wrap_pyfunction!(rough::psd, m)?)?;
    m.add_function(wrap_pyfunction!(rough::moments, m)?)?;
    m.add_function(wrap_pyfunction!(rough::_read_topography_file, m)?)?;
    m.add_function(wrap_pyfunction!(rough::_topography_parts, m)?)?;
    m.add_function(wrap_pyfunction!(rough::fit_line, m)?)?;
    m.add_class::<rough::RoughLine>()?;
    m.add_class::<rough::PlasticLine>()?;
    // MRD, axisymmetric
    m.add_class::<axisym::Profile>()?;
    m.add_function(wrap_pyfunction!(axisym::hess_inverse, m)?)?;
    m.add_function(wrap_pyfunction!(axisym::normal, m)?)?;
    m.add_function(wrap_pyfunction!(axisym::pressure, m)?)?;
    m.add_function(wrap_pyfunction!(axisym::adhesion, m)?)?;
    m.add_function(wrap_pyfunction!(axisym::pull_off, m)?)?;
    m.add_function(wrap_pyfunction!(axisym::cattaneo_mindlin, m)?)?;
    m.add_function(wrap_pyfunction!(axisym::damping, m)?)?;
    // scenes
    m.add_function(wrap_pyfunction!(scene::scenes, m)?)?;
    m.add_function(wrap_pyfunction!(scene::run_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::_run_to_folder, m)?)?;
    Ok(())
}
