//! Roughness: self-affine spectra (Eq. 70), synthesis (Eqs. 71-72), the 1D spectrum of
//! MRD (Eq. 76), PSD estimators and statistics, topography files, rough lines on the
//! foundation.

use crate::errors::{mrd_err, value_error};
use mrd::rough_contact::{fit_line as fit, RoughLine as Line, RoughState};
use mrd::roughness::stats::{line_moments, line_psd, surface_moments, surface_psd};
use mrd::roughness::synthesis::{self, Amplitudes, Grid};
use mrd::roughness::SelfAffine;
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, PyArray1, PyArray2, PyArrayDyn, PyArrayLike1, PyArrayLikeDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::f64::consts::PI;

/// The normalised 2D spectrum of the arguments shared by the functions below.
fn spectrum_of(
    py: Python<'_>,
    hurst: f64,
    q0: f64,
    qr: f64,
    q1: f64,
    rms_height: Option<f64>,
    rms_slope: Option<f64>,
) -> PyResult<SelfAffine> {
    let s = SelfAffine::new(hurst, q0, qr, q1).map_err(|e| mrd_err(py, e))?;
    match (rms_height, rms_slope) {
        (Some(h), None) => s.with_rms_height(h),
        (None, Some(g)) => s.with_rms_slope(g),
        (None, None) => Ok(s),
        _ => return Err(value_error("give at most one of rms_height and rms_slope")),
    }
    .map_err(|e| mrd_err(py, e))
}

fn amplitudes(gaussian: bool) -> Amplitudes {
    if gaussian {
        Amplitudes::Gaussian
    } else {
        Amplitudes::Deterministic
    }
}

/// spectrum(q, hurst, q0, qr, q1, *, rms_height=None, rms_slope=None) -> ndarray
///
/// Isotropic self-affine 2D power spectrum C2D(q) (Eq. 70) [length^4]: zero outside
/// [q0, q1], a plateau on [q0, qr], C0 (q / qr)^(-2H-2) above; wavenumbers in
/// [1/length] (q = 2 pi / wavelength). Scaled to the given rms height or rms slope
/// (unit plateau otherwise). H in [-1, 3].
#[pyfunction]
#[pyo3(signature = (q, hurst, q0, qr, q1, *, rms_height = None, rms_slope = None))]
#[allow(clippy::too_many_arguments)]
pub fn spectrum<'py>(
    py: Python<'py>,
    q: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    hurst: f64,
    q0: f64,
    qr: f64,
    q1: f64,
    rms_height: Option<f64>,
    rms_slope: Option<f64>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let s = spectrum_of(py, hurst, q0, qr, q1, rms_height, rms_slope)?;
    at_wavenumbers(py, q, |q| s.c2d(q))
}

/// `f` at every wavenumber of `q` (no NaN), as an array of `q`'s shape.
fn at_wavenumbers<'py>(
    py: Python<'py>,
    q: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    f: impl Fn(f64) -> f64,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    crate::errors::no_nan("q", q.as_array().iter())?;
    Ok(PyArrayDyn::from_owned_array(py, q.as_array().mapv(f)))
}

/// line_spectrum(q, hurst, q0, qr, q1, *, lam=pi, rms_height=None, rms_slope=None) -> ndarray
///
/// The 1D spectrum of MRD, C1D(q) = lam |q| C2D(q) (Eq. 76) [length^3], of the 2D
/// spectrum `spectrum(...)` (rms_height, rms_slope: of the 2D surface). lam = pi keeps
/// the rms height in the continuum (Eq. 73; on the discrete wavenumbers the line is
/// rougher, by 1.02-1.5 in mean square from H = -1 to 3); `calibrated_lambda(H)` (this
/// meaning of lambda: the line not rescaled) reproduces the 3D stiffness.
#[pyfunction]
#[pyo3(signature = (q, hurst, q0, qr, q1, *, lam = PI, rms_height = None, rms_slope = None))]
#[allow(clippy::too_many_arguments)]
pub fn line_spectrum<'py>(
    py: Python<'py>,
    q: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    hurst: f64,
    q0: f64,
    qr: f64,
    q1: f64,
    lam: f64,
    rms_height: Option<f64>,
    rms_slope: Option<f64>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let lam = line_lambda(lam, hurst)?;
    let l = spectrum_of(py, hurst, q0, qr, q1, rms_height, rms_slope)?.to_line(lam);
    at_wavenumbers(py, q, |q| l.c1d(q))
}

/// calibrated_lambda(hurst) -> float
///
/// lambda(H) of Eq. (76) from the project's calibration (the table the CLI's
/// `lambda = "calibrated"` uses: the `fig6-converged` study at bandwidth 128, 95 %
/// intervals within +/- 10 % for H <= 1.5; provenance in `calibrated_lambda_table()`),
/// linear between its rows. Use as `line_spectrum(..., lam=calibrated_lambda(H))`.
/// ValueError outside the table's range [-1, 3].
#[pyfunction]
pub fn calibrated_lambda(hurst: f64) -> PyResult<f64> {
    mrd::roughness::LambdaTable::from_csv(compare::experiment::lambda::DEFAULT_LAMBDA_CSV)
        .and_then(|t| t.at(hurst))
        .map_err(|e| value_error(format!("calibrated_lambda({hurst}): {e}")))
}

/// calibrated_lambda_table() -> str
///
/// The shipped calibration as CSV text: provenance comments, then the columns hurst,
/// lambda, lambda_lo95, lambda_hi95, misfit_max, misfit_rms, bandwidth,
/// realisations_3d, cells_per_min_wavelength.
#[pyfunction]
pub fn calibrated_lambda_table() -> &'static str {
    compare::experiment::lambda::DEFAULT_LAMBDA_CSV
}

fn grid_of(shape: (usize, usize), size: (f64, f64)) -> Grid {
    Grid {
        nx: shape.1,
        ny: shape.0,
        lx: size.0,
        ly: size.1,
    }
}

/// surface(shape, size, hurst, q0, qr, q1, *, rms_height=None, rms_slope=None, seed=0,
///         realisation=0, gaussian=False) -> ndarray (ny, nx)
///
/// A periodic random-phase surface (Eq. 71) of `spectrum(...)` on a (ny, nx) grid of
/// physical size (lx, ly). Deterministic: the same seed and realisation give the same
/// surface, bit for bit, as the CLI's scenes. gaussian=True: Gaussian mode amplitudes
/// (a Gaussian random field) instead of |H(q)| fixed by the spectrum.
#[pyfunction]
#[pyo3(signature = (shape, size, hurst, q0, qr, q1, *, rms_height = None, rms_slope = None, seed = 0, realisation = 0, gaussian = false))]
#[allow(clippy::too_many_arguments)]
pub fn surface<'py>(
    py: Python<'py>,
    shape: (usize, usize),
    size: (f64, f64),
    hurst: f64,
    q0: f64,
    qr: f64,
    q1: f64,
    rms_height: Option<f64>,
    rms_slope: Option<f64>,
    seed: u64,
    realisation: u64,
    gaussian: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let s = spectrum_of(py, hurst, q0, qr, q1, rms_height, rms_slope)?;
    let grid = grid_of(shape, size);
    let h = py
        .detach(|| synthesis::surface(&s, &grid, seed, realisation, amplitudes(gaussian)))
        .map_err(|e| mrd_err(py, e))?;
    let a = Array2::from_shape_vec(shape, h).map_err(|e| value_error(e.to_string()))?;
    Ok(PyArray2::from_owned_array(py, a))
}

/// line(n, length, hurst, q0, qr, q1, *, lam=pi, rms_height=None, rms_slope=None,
///      seed=0, realisation=0, gaussian=False) -> ndarray (n,)
///
/// A periodic random-phase rough line (Eq. 72) with the MRD spectrum
/// C1D = lam q C2D (Eq. 76) of `spectrum(...)`; rms_height, rms_slope: of the 2D
/// surface, so that the line is that surface's MRD image.
#[pyfunction]
#[pyo3(signature = (n, length, hurst, q0, qr, q1, *, lam = PI, rms_height = None, rms_slope = None, seed = 0, realisation = 0, gaussian = false))]
#[allow(clippy::too_many_arguments)]
pub fn line<'py>(
    py: Python<'py>,
    n: usize,
    length: f64,
    hurst: f64,
    q0: f64,
    qr: f64,
    q1: f64,
    lam: f64,
    rms_height: Option<f64>,
    rms_slope: Option<f64>,
    seed: u64,
    realisation: u64,
    gaussian: bool,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let lam = line_lambda(lam, hurst)?;
    let l = spectrum_of(py, hurst, q0, qr, q1, rms_height, rms_slope)?.to_line(lam);
    let h = synthesis::line(&l, n, length, seed, realisation, amplitudes(gaussian))
        .map_err(|e| mrd_err(py, e))?;
    Ok(PyArray1::from_vec(py, h))
}

/// `lam` checked by the rule every scene's `lambda` follows (`mrd::roughness::Lambda`).
fn line_lambda(lam: f64, hurst: f64) -> PyResult<f64> {
    mrd::roughness::Lambda::Value(lam)
        .at(hurst)
        .map_err(|e| value_error(format!("lam: {e}")))
}

fn check_length(name: &str, v: f64) -> PyResult<()> {
    let (lo, hi) = mrd::error::MAGNITUDE_RANGE;
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(value_error(format!(
            "{name} = {v:e} must lie in [{lo:e}, {hi:e}]"
        )))
    }
}

/// Refuses results that overflow double precision (extreme heights and sizes together).
fn representable(values: impl IntoIterator<Item = f64>) -> PyResult<()> {
    if values.into_iter().all(f64::is_finite) {
        Ok(())
    } else {
        Err(value_error(
            "the result overflows double precision for these heights and sizes: rescale the units",
        ))
    }
}

type Pairs<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

fn pairs<'py>(py: Python<'py>, v: Vec<(f64, f64)>) -> Pairs<'py> {
    let (q, c): (Vec<f64>, Vec<f64>) = v.into_iter().unzip();
    (PyArray1::from_vec(py, q), PyArray1::from_vec(py, c))
}

fn finite_heights(h: &[f64]) -> PyResult<()> {
    if h.len() < 4 {
        return Err(value_error("need at least 4 heights"));
    }
    match mrd::error::bad_height(h) {
        Some((i, what)) => Err(value_error(format!("{what} at index {i}"))),
        None => Ok(()),
    }
}

/// psd(h, size, bins=32) -> (q, C)
///
/// PSD estimate of a periodic line (1D h, size = length L: one-sided C1D(q_k) =
/// L / (2 pi) |H_k|^2 [length^3], k = 1 .. n/2) or surface (2D h (ny, nx), size =
/// (lx, ly): C2D radially averaged in `bins` logarithmic bins [length^4]); q in
/// [1/length].
#[pyfunction]
#[pyo3(signature = (h, size, bins = 32))]
pub fn psd<'py>(
    py: Python<'py>,
    h: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    size: &Bound<'py, PyAny>,
    bins: usize,
) -> PyResult<Pairs<'py>> {
    let a = h.as_array();
    let data: Vec<f64> = a.iter().copied().collect();
    finite_heights(&data)?;
    match a.ndim() {
        1 => {
            let l: f64 = size.extract()?;
            check_length("size", l)?;
            let v = line_psd(&data, l);
            representable(v.iter().flat_map(|&(q, c)| [q, c]))?;
            Ok(pairs(py, v))
        }
        2 => {
            let (lx, ly): (f64, f64) = size.extract()?;
            check_length("lx", lx)?;
            check_length("ly", ly)?;
            let (ny, nx) = (a.shape()[0], a.shape()[1]);
            // More bins than modes leaves bins empty.
            if !(1..=nx * ny).contains(&bins) {
                return Err(value_error(format!(
                    "bins = {bins} must lie in 1..={} (the map's cells)",
                    nx * ny
                )));
            }
            let v = surface_psd(&data, nx, ny, lx, ly, bins);
            representable(v.iter().flat_map(|&(q, c)| [q, c]))?;
            Ok(pairs(py, v))
        }
        d => Err(value_error(format!(
            "h must be 1D or 2D, got {d} dimensions"
        ))),
    }
}

/// moments(h, size) -> dict(rms_height, rms_slope, rms_curvature)
///
/// Spectral statistics of a periodic line (1D h, size = L) or surface (2D h, size =
/// (lx, ly)): rms height about the mean [length], rms slope (gradient) [-] and rms
/// curvature [1/length] (Eqs. 74-75), from the Fourier coefficients.
#[pyfunction]
pub fn moments<'py>(
    py: Python<'py>,
    h: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    size: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let a = h.as_array();
    let data: Vec<f64> = a.iter().copied().collect();
    finite_heights(&data)?;
    let m = match a.ndim() {
        1 => {
            let l: f64 = size.extract()?;
            check_length("size", l)?;
            line_moments(&data, l)
        }
        2 => {
            let (lx, ly): (f64, f64) = size.extract()?;
            check_length("lx", lx)?;
            check_length("ly", ly)?;
            surface_moments(&data, a.shape()[1], a.shape()[0], lx, ly)
        }
        d => {
            return Err(value_error(format!(
                "h must be 1D or 2D, got {d} dimensions"
            )))
        }
    };
    representable([m.rms_height, m.rms_slope, m.rms_curvature])?;
    let d = PyDict::new(py);
    d.set_item("rms_height", m.rms_height)?;
    d.set_item("rms_slope", m.rms_slope)?;
    d.set_item("rms_curvature", m.rms_curvature)?;
    Ok(d)
}

/// A height map and its cell size (dx, dy), where known.
type MapAndCell<'py> = (Bound<'py, PyArray2<f64>>, Option<(f64, f64)>);

/// _read_topography_file(path) -> (ndarray (rows, cols), (dx, dy) or None)
///
/// A height map from a file (`.npy`, `.xyz`, an ESRI ASCII grid or a text matrix, read
/// by the CLI's code) and its cell size where the file states it; the file is read on a
/// thread of its own without the GIL, so other Python threads run (a pipe fed by one of
/// them included) and Ctrl-C stops the wait. `mrdw.read_topography` wraps it.
#[pyfunction]
pub fn _read_topography_file<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
) -> PyResult<MapAndCell<'py>> {
    use std::sync::mpsc::{channel, RecvTimeoutError};
    let (tx, rx) = channel();
    // Not scoped: a read that never ends (a pipe nobody writes) must not hold Ctrl-C.
    std::thread::spawn(move || {
        let _ = tx.send(mrd::topography::HeightMap::read_with_cell(&path));
    });
    let mut rx = rx;
    let read = loop {
        let (back, got) = py.detach(move || {
            let got = rx.recv_timeout(std::time::Duration::from_millis(50));
            (rx, got)
        });
        rx = back;
        match got {
            Ok(read) => break read,
            Err(RecvTimeoutError::Timeout) => py.check_signals()?,
            Err(RecvTimeoutError::Disconnected) => {
                return Err(pyo3::exceptions::PyRuntimeError::new_err(
                    "internal error: the read ended without a result",
                ))
            }
        }
    };
    let (m, cell) = read.map_err(|e| mrd_err(py, e))?;
    let a =
        Array2::from_shape_vec((m.rows, m.cols), m.data).map_err(|e| value_error(e.to_string()))?;
    Ok((PyArray2::from_owned_array(py, a), cell))
}

/// The parts of a height map as Contact reads it: (heights (ny, nx) as rows of y,
/// undefined cells (ny, nx) or None, (lx, ly) or None, periodic or None).
type Parts<'py> = (
    Bound<'py, PyArray2<f64>>,
    Option<Bound<'py, PyArray2<bool>>>,
    Option<(f64, f64)>,
    Option<bool>,
);

/// _topography_parts(obj) -> (heights, undefined, size, periodic)
///
/// An array, masked array or topography object taken apart as `Contact` takes it (one
/// reading for both): heights as rows of y with NaN in undefined cells.
#[pyfunction]
pub fn _topography_parts<'py>(py: Python<'py>, source: &Bound<'py, PyAny>) -> PyResult<Parts<'py>> {
    let m = crate::contact::HeightMap::extract(source)?;
    let mut heights = m.copy();
    let undefined = m.undefined();
    if let Some(u) = &undefined {
        heights
            .iter_mut()
            .zip(u)
            .filter(|(_, &u)| u)
            .for_each(|(h, _)| *h = f64::NAN);
    }
    let shape = m.shape();
    let grid = |v| Array2::from_shape_vec(shape, v).map_err(|e| value_error(e.to_string()));
    let undefined = match undefined {
        Some(u) => Some(PyArray2::from_owned_array(
            py,
            Array2::from_shape_vec(shape, u).map_err(|e| value_error(e.to_string()))?,
        )),
        None => None,
    };
    Ok((
        PyArray2::from_owned_array(py, grid(heights)?),
        undefined,
        m.size,
        m.periodic,
    ))
}

fn state_dict<'py>(py: Python<'py>, s: &RoughState) -> PyResult<Bound<'py, PyDict>> {
    let d = crate::errors::finite_dict(
        py,
        &[
            ("depth", s.depth),
            ("force", s.force),
            ("contact_length", s.contact_length),
            ("stiffness", s.stiffness),
            ("contact_slope", s.contact_slope),
        ],
    )?;
    d.set_item("contacts", s.contacts)?;
    Ok(d)
}

/// A rough line on the MRD foundation (springs E* dx, Eq. 3), with exact O(log N)
/// force- and depth-controlled queries.
///
/// RoughLine(heights, length, e_star)
///
/// heights: 1D array of the line's heights, peaks up [length]; length L [length];
/// e_star [stress]. Spring i carries E* dx times its overlap (Eq. 3), so forces are in
/// [stress x length^2] and stiffnesses in [stress x length], as in 3D.
#[pyclass(module = "mrdw._mrdw", frozen)]
pub struct RoughLine {
    line: Line,
}

#[pymethods]
impl RoughLine {
    #[new]
    fn new(
        py: Python<'_>,
        heights: PyArrayLike1<'_, f64, AllowTypeChange>,
        length: f64,
        e_star: f64,
    ) -> PyResult<Self> {
        let h = heights.as_array().to_vec();
        Line::new(&h, length, e_star)
            .map(|line| Self { line })
            .map_err(|e| mrd_err(py, e))
    }

    /// at_force(force) -> dict(depth, force, contacts, contact_length, stiffness,
    /// contact_slope): the state carrying `force`; stiffness k = dF/dd = E* dx m (m
    /// springs in contact), contact_slope the rms slope over the contacts (Eq. 86).
    fn at_force<'py>(&self, py: Python<'py>, force: f64) -> PyResult<Bound<'py, PyDict>> {
        let s = self.line.at_force(force).map_err(|e| mrd_err(py, e))?;
        state_dict(py, &s)
    }

    /// at_depth(depth) -> dict: the state at rigid-body approach `depth` from first
    /// contact [length].
    fn at_depth<'py>(&self, py: Python<'py>, depth: f64) -> PyResult<Bound<'py, PyDict>> {
        let s = self.line.at_depth(depth).map_err(|e| mrd_err(py, e))?;
        state_dict(py, &s)
    }

    /// Depth at which every spring touches [length].
    #[getter]
    fn full_contact_depth(&self) -> f64 {
        self.line.full_contact_depth()
    }

    /// rms height of the line about its mean (Eq. 87) [length].
    #[getter]
    fn rms_height(&self) -> f64 {
        self.line.rms_height
    }

    /// Reduced force f = F / (E* h L) (Eq. 90).
    fn reduced_force(&self, force: f64) -> f64 {
        self.line.reduced_force(force)
    }

    /// Reduced stiffness k / (E* L).
    fn reduced_stiffness(&self, stiffness: f64) -> f64 {
        self.line.reduced_stiffness(stiffness)
    }

    fn __len__(&self) -> usize {
        self.line.len()
    }
}

/// A rough line on an elastic-perfectly plastic MRD foundation: springs E* dx whose line
/// loads are capped patch by patch at a fully plastic microcontact's, 2 H sqrt(a^2 -
/// (x - c)^2) for a run of springs in contact of half-length a centred at c (Section 11
/// in incremental form; the rule and its limits: docs/results.md, "Rough surfaces with
/// yielding"). A spring pressed beyond its cap takes a permanent set; unloading is
/// elastic and reloading retraces it up to the largest earlier load.
///
/// PlasticLine(heights, length, e_star, hardness)
///
/// heights: 1D array at the springs' centres, peaks up [length]; length L [length] (the
/// line is open: its ends are a punch's edge); e_star and hardness H [stress] (H = inf:
/// the elastic RoughLine). Forces in [stress x length^2], as in 3D. Starts apart.
#[pyclass(module = "mrdw._mrdw")]
pub struct PlasticLine {
    line: mrd::plastic_line::PlasticLine,
}

fn line_step_dict<'py>(
    py: Python<'py>,
    s: &mrd::plastic_line::LineStep,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("approach", s.approach)?;
    d.set_item("force", s.force)?;
    d.set_item("contacts", s.contacts)?;
    d.set_item("capped", s.capped)?;
    d.set_item("patches", s.patches)?;
    d.set_item("stiffness", s.stiffness)?;
    d.set_item("largest_set", s.largest_set)?;
    Ok(d)
}

#[pymethods]
impl PlasticLine {
    #[new]
    fn new(
        py: Python<'_>,
        heights: PyArrayLike1<'_, f64, AllowTypeChange>,
        length: f64,
        e_star: f64,
        hardness: f64,
    ) -> PyResult<Self> {
        let h = heights.as_array().to_vec();
        mrd::plastic_line::PlasticLine::new(&h, length, e_star, hardness)
            .map(|line| Self { line })
            .map_err(|e| mrd_err(py, e))
    }

    /// step(approach) -> dict(approach, force, contacts, capped, patches, stiffness,
    /// largest_set): loads to the approach from the first contact of the undeformed line
    /// [length] and keeps the state; stiffness is the unloading one, E* dx contacts.
    fn step<'py>(&mut self, py: Python<'py>, approach: f64) -> PyResult<Bound<'py, PyDict>> {
        let s = self.line.step(approach).map_err(|e| mrd_err(py, e))?;
        line_step_dict(py, &s)
    }

    /// step_to_force(force, tolerance=None) -> dict: loads to the force [stress x
    /// length^2] in [0, force_limit), to `tolerance` relative (default
    /// mrd's STEP_TOLERANCE, 1e-10), and keeps the state.
    #[pyo3(signature = (force, tolerance = None))]
    fn step_to_force<'py>(
        &mut self,
        py: Python<'py>,
        force: f64,
        tolerance: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let tol = tolerance.unwrap_or(mrd::plastic_line::STEP_TOLERANCE);
        let s = self
            .line
            .step_to_force(force, tol)
            .map_err(|e| mrd_err(py, e))?;
        line_step_dict(py, &s)
    }

    /// Each spring's permanent set so far [length]: the residual line after unloading
    /// lies this far below the undeformed one.
    #[getter]
    fn set<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.line.set())
    }

    /// Line loads of the last step [stress x length].
    #[getter]
    fn load<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.line.load())
    }

    /// The largest force a step can carry: the whole line one fully plastic patch
    /// (about H pi L^2 / 4) [stress x length^2].
    #[getter]
    fn force_limit(&self) -> f64 {
        self.line.force_limit()
    }

    fn __len__(&self) -> usize {
        self.line.set().len()
    }
}

/// fit_line(x, y) -> dict(a, b, se_a, se_b)
///
/// Least-squares line y = a + b x with the standard errors of a and b (used for
/// log k - log F fits: alpha = b, Eq. 80; and Eq. 91).
#[pyfunction]
pub fn fit_line<'py>(
    py: Python<'py>,
    x: PyArrayLike1<'py, f64, AllowTypeChange>,
    y: PyArrayLike1<'py, f64, AllowTypeChange>,
) -> PyResult<Bound<'py, PyDict>> {
    let f = fit(&x.as_array().to_vec(), &y.as_array().to_vec()).map_err(|e| mrd_err(py, e))?;
    let d = PyDict::new(py);
    d.set_item("a", f.a)?;
    d.set_item("b", f.b)?;
    d.set_item("se_a", f.se_a)?;
    d.set_item("se_b", f.se_b)?;
    Ok(d)
}
