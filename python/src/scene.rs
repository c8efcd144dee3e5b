//! Scenes (the CLI's TOML case files) run from Python: every table as numpy columns.

use crate::errors::compare_err;
use compare::Scene;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// scenes() -> list[tuple[str, str]]
///
/// The embedded scenes: (name, title), as `mrdw scenes` lists them.
#[pyfunction]
pub fn scenes() -> Vec<(String, String)> {
    compare::scenes::EMBEDDED
        .iter()
        .map(|(name, text)| (name.to_string(), compare::scenes::title(text)))
        .collect()
}

/// run_scene(scene) -> dict
///
/// Runs a scene (a .toml path, or an embedded scene's name) in memory, as `mrdw run`
/// computes it, and returns {"name", "plan": {output: [stages]}, "tables": {table:
/// {column header (with unit): ndarray}}, "results": {label.key: value}, "warnings",
/// "failures"}. Figures are not drawn; no files are written. The GIL is released while
/// it runs. Raises ValueError for a bad scene (the CLI's message), MemoryError for sizes
/// that do not fit, and ConvergenceError when requested results are missing (a solve
/// stopped short, a fit without resolved points: where the CLI exits with code 4); the
/// exception's `last` holds the dictionary above and `failures` the list.
#[pyfunction]
pub fn run_scene<'py>(py: Python<'py>, scene: &str) -> PyResult<Bound<'py, PyDict>> {
    let s = Scene::open(scene).map_err(|e| compare_err(py, e))?;
    let report = py
        .detach(|| compare::run(&s))
        .map_err(|e| compare_err(py, e))?;
    let out = PyDict::new(py);
    out.set_item("name", &s.name)?;
    let plan = PyDict::new(py);
    for (label, stages) in &report.plan.outputs {
        let names: Vec<&str> = stages.iter().map(|st| st.name()).collect();
        plan.set_item(label, names)?;
    }
    out.set_item("plan", plan)?;
    let tables = PyDict::new(py);
    for t in report.tables() {
        let cols = PyDict::new(py);
        for (j, header) in t.columns.iter().enumerate() {
            let v: Vec<f64> = t.rows.iter().map(|r| r[j]).collect();
            cols.set_item(header, PyArray1::from_vec(py, v))?;
        }
        tables.set_item(&t.name, cols)?;
    }
    out.set_item("tables", tables)?;
    // Results are JSON values (numbers, strings, lists): through Python's json module.
    let json = serde_json::Value::Object(report.results()).to_string();
    let results = py.import("json")?.call_method1("loads", (json,))?;
    out.set_item("results", results)?;
    out.set_item("warnings", report.warnings())?;
    let failures = report.failures();
    out.set_item("failures", &failures)?;
    if let Some(first) = failures.first() {
        let err = crate::errors::convergence(
            py,
            format!(
                "{} requested results are missing (first: {first}); the partial results are in .last",
                failures.len()
            ),
            "scene",
            0,
            f64::NAN,
            Some(out.into_any().unbind()),
        );
        let _ = err.value(py).setattr("failures", failures);
        return Err(err);
    }
    Ok(out)
}

/// _run_to_folder(scene, out, work, progress) -> dict
///
/// Runs a scene file as `mrdw run SCENE --out OUT [--work WORK]` does: writes the report
/// folder `out` (CSV, PNG, summary.json), keeps checkpoints in `work` when given (a rerun
/// resumes from them), shows progress bars on stderr when `progress`. Returns
/// {"results", "warnings", "files"}. The GIL is released while it runs. `mrdw.calibrate`
/// calls it.
#[pyfunction]
#[pyo3(signature = (scene, out, work = None, progress = false))]
pub fn _run_to_folder<'py>(
    py: Python<'py>,
    scene: &str,
    out: std::path::PathBuf,
    work: Option<std::path::PathBuf>,
    progress: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let s = Scene::open(scene).map_err(|e| compare_err(py, e))?;
    let control = compare::RunControl {
        progress,
        ..Default::default()
    };
    let (report, files) = py
        .detach(|| compare::run::run_to_folder(&s, &out, work.as_deref(), &control))
        .map_err(|e| compare_err(py, e))?;
    let d = PyDict::new(py);
    let json = serde_json::Value::Object(report.results()).to_string();
    d.set_item(
        "results",
        py.import("json")?.call_method1("loads", (json,))?,
    )?;
    d.set_item("warnings", report.warnings())?;
    let files: Vec<String> = files.iter().map(|p| p.display().to_string()).collect();
    d.set_item("files", files)?;
    Ok(d)
}
