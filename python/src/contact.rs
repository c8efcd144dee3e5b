//! The 3D boundary-element contact solver (`bem3d`) on numpy height maps.

use crate::errors::{bem_err, value_error};
use bem3d::{
    Choice, ContactSolver, Interrupt, Load, NonPeriodicHalfSpace, Paths, PeriodicHalfSpace,
    Solution, SolverOptions,
};
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, PyArray2, PyArrayLike1, PyArrayLike2};
use pyo3::prelude::*;

/// The solver on one of the two operators.
enum Solver {
    Periodic(ContactSolver<PeriodicHalfSpace>),
    NonPeriodic(ContactSolver<NonPeriodicHalfSpace>),
}

impl Solver {
    fn solve(
        &mut self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> bem3d::Result<Solution> {
        match self {
            Solver::Periodic(s) => s.solve(load, opts, warm),
            Solver::NonPeriodic(s) => s.solve(load, opts, warm),
        }
    }
    fn stiffness(&mut self, sol: &Solution, opts: &SolverOptions) -> bem3d::Result<f64> {
        match self {
            Solver::Periodic(s) => s.tangent_stiffness(sol, opts),
            Solver::NonPeriodic(s) => s.tangent_stiffness(sol, opts),
        }
    }
}

/// A solved contact state (returned by `Contact.solve`).
#[pyclass(module = "mrdw._mrdw", frozen)]
pub struct ContactResult {
    sol: Solution,
    shape: (usize, usize),
    /// lx * ly
    area: f64,
    stiffness: Option<f64>,
}

impl ContactResult {
    pub fn new(sol: Solution, shape: (usize, usize), area: f64, stiffness: Option<f64>) -> Self {
        Self {
            sol,
            shape,
            area,
            stiffness,
        }
    }
}

pub(crate) fn grid_array<'py>(
    py: Python<'py>,
    v: &[f64],
    shape: (usize, usize),
) -> Bound<'py, PyArray2<f64>> {
    // The shape always matches: the solver returns ny * nx values.
    let a = Array2::from_shape_vec(shape, v.to_vec()).expect("grid shape");
    PyArray2::from_owned_array(py, a)
}

#[pymethods]
impl ContactResult {
    /// Cell pressures, shape (ny, nx) [stress].
    #[getter]
    fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        grid_array(py, &self.sol.pressure, self.shape)
    }
    /// Gap at cell centres, shape (ny, nx) [length]; zero in contact.
    #[getter]
    fn gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        grid_array(py, &self.sol.gap, self.shape)
    }
    /// Rigid-body approach from first contact [length].
    #[getter]
    fn approach(&self) -> f64 {
        self.sol.approach
    }
    /// Total normal force, sum of p times cell area [stress x length^2].
    #[getter]
    fn force(&self) -> f64 {
        self.sol.force
    }
    /// Mean pressure over the whole grid area [stress].
    #[getter]
    fn mean_pressure(&self) -> f64 {
        self.sol.force / self.area
    }
    /// Real contact area, contact cells times cell area [length^2].
    #[getter]
    fn contact_area(&self) -> f64 {
        self.sol.contact_area
    }
    /// Contact cells over the cells that may touch (the mask's, or all).
    #[getter]
    fn contact_fraction(&self) -> f64 {
        self.sol.contact_cells as f64 / self.sol.domain_cells as f64
    }
    /// Number of cells carrying pressure.
    #[getter]
    fn contact_cells(&self) -> usize {
        self.sol.contact_cells
    }
    /// Mean gap over the cells that may touch [length].
    #[getter]
    fn mean_gap(&self) -> f64 {
        self.sol.mean_gap
    }
    /// Iterations of the contact solve.
    #[getter]
    fn iterations(&self) -> usize {
        self.sol.iterations
    }
    /// Convergence criterion reached (pressure-weighted gap and interpenetration
    /// relative to the rms height; see `bem3d/src/solver.rs`).
    #[getter]
    fn residual(&self) -> f64 {
        self.sol.residual
    }
    /// Bound of the energy's duality gap relative to force x rms height: at most the
    /// tolerance when the solve converged, and then the pressure error in the norm of K
    /// satisfies (p - p*).K(p - p*) <= 2 x certificate x force x h_rms (see
    /// `bem3d/src/solver.rs`, "What a converged solve guarantees").
    #[getter]
    fn certificate(&self) -> f64 {
        self.sol.certificate
    }
    /// Tangent normal stiffness dF/dd with the contact set fixed [stress x length], if
    /// requested (`stiffness=True`); +inf at complete contact of a periodic map.
    #[getter]
    fn stiffness(&self) -> Option<f64> {
        self.stiffness
    }
    /// Every cell that may touch is in contact.
    #[getter]
    fn complete_contact(&self) -> bool {
        self.sol.complete_contact()
    }
    /// Whether the warm start given to the solve was used (small load steps only).
    #[getter]
    fn warm_started(&self) -> bool {
        self.sol.warm_started
    }
    /// Whether the solve ran restricted to part of the grid: a window around a compact
    /// contact on the non-periodic half-space (`iterations` then count iterations on the
    /// window), or a small candidate set of cells at low contact fractions
    /// (`iterations` then count applications of a dense K between them).
    #[getter]
    fn restricted(&self) -> bool {
        self.sol.restricted()
    }
    /// The path the solve took: "full grid", "window" (a compact contact on the
    /// non-periodic half-space) or "candidate set" (a small contact set).
    #[getter]
    fn path(&self) -> &'static str {
        self.sol.path.name()
    }
    /// Whether the full-grid iteration started from the solution on the grid coarsened
    /// 2 x 2 (large grids under force control).
    #[getter]
    fn nested_start(&self) -> bool {
        self.sol.nested_start
    }
    /// Of `iterations`, those with K p carried in single precision.
    #[getter]
    fn single_precision_iterations(&self) -> usize {
        self.sol.single_iterations
    }
    /// Of `iterations`, those that applied the preconditioner by its stencil on the
    /// contact cells.
    #[getter]
    fn stencil_iterations(&self) -> usize {
        self.sol.stencil_iterations
    }
    /// Whether the iteration stored its direction vectors as 16-bit integers
    /// scaled per row chunk (grids above 2048^2 cells, unless forbidden).
    #[getter]
    fn scaled_directions(&self) -> bool {
        self.sol.scaled_directions
    }
    fn __repr__(&self) -> String {
        format!(
            "ContactResult(force={:.6e}, approach={:.6e}, contact_fraction={:.4e}, mean_gap={:.6e}, iterations={}, residual={:.2e}, certificate={:.2e})",
            self.sol.force,
            self.sol.approach,
            self.contact_fraction(),
            self.sol.mean_gap,
            self.sol.iterations,
            self.sol.residual,
            self.sol.certificate
        )
    }
}

/// A height map from an array (ny, nx) or a topography object (see [`Contact`]), not
/// yet copied (its size is checked first), with the object's size and periodicity.
pub struct HeightMap<'py> {
    array: PyArrayLike2<'py, f64, AllowTypeChange>,
    /// A topography object's heights, indexed (x, y): the map is their transpose.
    by_x: bool,
    pub size: Option<(f64, f64)>,
    pub periodic: Option<bool>,
}

impl<'py> HeightMap<'py> {
    pub fn extract(obj: &Bound<'py, PyAny>) -> PyResult<Self> {
        let topography =
            obj.hasattr("physical_sizes")? && obj.getattr("heights").is_ok_and(|h| h.is_callable());
        if !topography {
            return Ok(Self {
                array: obj.extract()?,
                by_x: false,
                size: None,
                periodic: None,
            });
        }
        let bad = |what: String| value_error(format!("topography object: {what}"));
        let array = obj
            .call_method0("heights")?
            .extract()
            .map_err(|e| bad(format!("heights() must give a 2D float array ({e})")))?;
        // None where the topography's size is unknown (then `size=` must be given).
        let size: Option<(f64, f64)> = obj
            .getattr("physical_sizes")?
            .extract()
            .map_err(|e| bad(format!("physical_sizes must be (lx, ly) or None ({e})")))?;
        let periodic = match obj.getattr("is_periodic") {
            Ok(v) => Some(
                v.extract::<bool>()
                    .map_err(|e| bad(format!("is_periodic ({e})")))?,
            ),
            Err(_) => None,
        };
        Ok(Self {
            array,
            by_x: true,
            size,
            periodic,
        })
    }

    /// Whether the map came from a topography object (heights indexed (x, y)).
    pub fn by_x(&self) -> bool {
        self.by_x
    }

    fn view(&self) -> numpy::ndarray::ArrayView2<'_, f64> {
        let v = self.array.as_array();
        if self.by_x {
            v.reversed_axes()
        } else {
            v
        }
    }

    /// (ny, nx).
    pub fn shape(&self) -> (usize, usize) {
        self.view().dim()
    }

    /// The heights row by row (y) in one copy (a memcpy for a C-ordered array): the
    /// solver keeps no reference to numpy's memory while the GIL is released.
    pub fn copy(&self) -> Vec<f64> {
        let view = self.view();
        match view.as_slice() {
            Some(s) => s.to_vec(),
            None => view.iter().copied().collect(),
        }
    }
}

/// Frictionless normal contact of a rigid rough surface on an elastic half-space (3D
/// FFT boundary elements, preconditioned Polonsky-Keer).
///
/// Contact(heights, size=None, e_star=1.0, periodic=None, mask=None)
///
/// heights: 2D array (ny, nx) of surface heights, peaks up [length], or a topography
/// object with a `heights()` method and `physical_sizes` (a SurfaceTopography
/// Topography, or any object like it: its heights are indexed (x, y) and are
/// transposed to (ny, nx), its `physical_sizes` (lx, ly) is the size and its
/// `is_periodic`, where present, the default of `periodic`); size: physical size
/// (lx, ly) of the map [length] (default (1, 1), or the object's; required when the
/// object's `physical_sizes` is None); e_star: contact
/// modulus E* [stress] (Eq. 2); periodic: periodic half-space (False: isolated map,
/// zero-padded FFTs; default True, or the object's); arguments given override the
/// object's attributes. mask:
/// optional boolean array (ny, nx) of the cells that may touch. The operator and
/// buffers are built once; solve() may be called for many loads.
#[pyclass(module = "mrdw._mrdw")]
pub struct Contact {
    solver: Solver,
    shape: (usize, usize),
    size: (f64, f64),
    e_star: f64,
    periodic: bool,
    /// Set on Ctrl-C during a solve ([`interruptible`]).
    interrupt: Interrupt,
}

pub(crate) struct Request {
    pub load: Load,
    pub opts: SolverOptions,
    stiffness: bool,
}

/// The solver's strategies from a dict `{name: "forbid" | "allow" | "force"}` (names as
/// the fields of [`Paths`]; a missing name is allowed).
fn parse_paths(given: Option<&std::collections::HashMap<String, String>>) -> PyResult<Paths> {
    let mut paths = Paths::default();
    for (name, choice) in given.into_iter().flatten() {
        let choice: Choice = choice
            .parse()
            .map_err(|e| value_error(format!("paths[{name:?}] = {e}")))?;
        paths
            .set(name, choice)
            .map_err(|e| value_error(format!("paths: {e}")))?;
    }
    Ok(paths)
}

pub(crate) fn request(
    mean_pressure: Option<f64>,
    force: Option<f64>,
    approach: Option<f64>,
    (tolerance, max_iterations): (f64, usize),
    stiffness: bool,
    paths: Paths,
) -> PyResult<Request> {
    let load = match (mean_pressure, force, approach) {
        (Some(p), None, None) => Load::MeanPressure(p),
        (None, Some(f), None) => Load::Force(f),
        (None, None, Some(d)) => Load::Approach(d),
        _ => {
            return Err(value_error(
                "give exactly one of mean_pressure, force and approach",
            ))
        }
    };
    // The command line's check (bem3d::SolverOptions::validate).
    let opts = SolverOptions {
        paths,
        ..SolverOptions::new(tolerance, max_iterations)
    };
    opts.validate().map_err(|e| value_error(e.to_string()))?;
    Ok(Request {
        load,
        opts,
        stiffness,
    })
}

/// A mask array as the solver takes it, checked against the heights' shape (ny, nx).
pub(crate) fn grid_mask(
    mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
    (ny, nx): (usize, usize),
) -> PyResult<Option<Vec<bool>>> {
    let Some(m) = mask else { return Ok(None) };
    let m = m.as_array();
    if m.dim() != (ny, nx) {
        return Err(value_error(format!(
            "mask has shape {:?} but heights have ({ny}, {nx})",
            m.dim()
        )));
    }
    Ok(Some(m.iter().copied().collect()))
}

/// Runs `work` on a thread of its own while this thread, holding the GIL only briefly,
/// polls Python's signal handlers every 50 ms: on Ctrl-C (or any handler that raises)
/// it sets `interrupt`, which the solver polls once per iteration, waits for the solve
/// to stop and raises the handler's exception (KeyboardInterrupt).
pub fn interruptible<T: Send>(
    py: Python<'_>,
    interrupt: &Interrupt,
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    use std::sync::mpsc::{channel, RecvTimeoutError};
    interrupt.clear();
    let (tx, rx) = channel();
    std::thread::scope(|scope| {
        scope.spawn(move || {
            let _ = tx.send(work());
        });
        let mut raised: Option<PyErr> = None;
        let mut rx = rx;
        loop {
            let (back, got) = py.detach(move || {
                let got = rx.recv_timeout(std::time::Duration::from_millis(50));
                (rx, got)
            });
            rx = back;
            match got {
                Ok(value) => return raised.map_or(Ok(value), Err),
                Err(RecvTimeoutError::Timeout) => {
                    if raised.is_none() {
                        if let Err(e) = py.check_signals() {
                            interrupt.set();
                            raised = Some(e);
                        }
                    }
                }
                Err(RecvTimeoutError::Disconnected) => {
                    return Err(pyo3::exceptions::PyRuntimeError::new_err(
                        "internal error: the solve ended without a result",
                    ))
                }
            }
        }
    })
}

impl Contact {
    /// Solves one load with the GIL released.
    fn run(
        &mut self,
        py: Python<'_>,
        req: &Request,
        warm: Option<&Solution>,
    ) -> PyResult<ContactResult> {
        let solver = &mut self.solver;
        let opts = SolverOptions {
            interrupt: Some(self.interrupt.clone()),
            ..req.opts.clone()
        };
        let out = interruptible(py, &self.interrupt, || {
            let sol = solver.solve(req.load, &opts, warm)?;
            let k = if req.stiffness {
                Some(solver.stiffness(&sol, &opts)?)
            } else {
                None
            };
            Ok::<_, bem3d::BemError>((sol, k))
        })?;
        let (sol, k) = out.map_err(|e| bem_err(py, e, self.shape, self.size.0 * self.size.1))?;
        Ok(ContactResult::new(
            sol,
            self.shape,
            self.size.0 * self.size.1,
            k,
        ))
    }
}

#[pymethods]
impl Contact {
    #[new]
    #[pyo3(signature = (heights, size = None, e_star = 1.0, periodic = None, mask = None))]
    fn new(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        size: Option<(f64, f64)>,
        e_star: f64,
        periodic: Option<bool>,
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
    ) -> PyResult<Self> {
        let map = HeightMap::extract(heights)?;
        if map.by_x && size.is_none() && map.size.is_none() {
            return Err(value_error(
                "the topography has no physical_sizes: give size=(lx, ly)",
            ));
        }
        let size = size.or(map.size).unwrap_or((1.0, 1.0));
        let periodic = periodic.or(map.periodic).unwrap_or(true);
        let (ny, nx) = map.shape();
        if nx < 2 || ny < 2 {
            return Err(value_error(format!(
                "heights must be a 2D array of at least 2 x 2 cells, got {ny} x {nx}"
            )));
        }
        let (lx, ly) = size;
        // The command line's checks: grid, size and modulus ranges, memory.
        bem3d::operator::HalfSpace {
            nx,
            ny,
            lx,
            ly,
            e_star,
        }
        .check(periodic)
        .map_err(|e| bem_err(py, e, (ny, nx), lx * ly))?;
        let h = map.copy();
        let mask = grid_mask(mask, (ny, nx))?;
        let built = py.detach(|| -> bem3d::Result<Solver> {
            Ok(if periodic {
                Solver::Periodic(ContactSolver::new(
                    PeriodicHalfSpace::try_new(nx, ny, lx, ly, e_star)?,
                    &h,
                    mask,
                )?)
            } else {
                Solver::NonPeriodic(ContactSolver::new(
                    NonPeriodicHalfSpace::try_new(nx, ny, lx, ly, e_star)?,
                    &h,
                    mask,
                )?)
            })
        });
        let solver = built.map_err(|e| bem_err(py, e, (ny, nx), lx * ly))?;
        Ok(Self {
            solver,
            shape: (ny, nx),
            size,
            e_star,
            periodic,
            interrupt: Interrupt::default(),
        })
    }

    /// solve(mean_pressure=None, force=None, approach=None, *, tolerance=1e-10,
    ///       max_iterations=10000, stiffness=False, warm=None, paths=None) -> ContactResult
    ///
    /// Solves for exactly one of: mean pressure over lx * ly [stress], total force
    /// [stress x length^2], or rigid-body approach from first contact [length].
    /// `warm`: a previous ContactResult of this Contact, used as the initial iterate
    /// where that pays (force ratios 0.9-1.05, approach ratios 1-1.05). `stiffness`: also
    /// the tangent stiffness dF/dd. Raises ValueError for bad input or an infeasible
    /// load, ConvergenceError (with `.last`) if the iteration cap is reached. The GIL is
    /// released while solving. `paths`: the solver's strategies, e.g.
    /// `{"stencil": "force", "window": "forbid"}` (names: window, candidate_set, stencil,
    /// nested_start, single_precision, scaled_directions; values: "forbid", "allow" (the
    /// default), "force"; ValueError if a forced one cannot run). The result's `path`,
    /// `nested_start`, `single_precision_iterations`, `stencil_iterations` and
    /// `scaled_directions` say what ran.
    #[pyo3(signature = (mean_pressure = None, force = None, approach = None, *, tolerance = 1e-10, max_iterations = 10_000, stiffness = false, warm = None, paths = None))]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &mut self,
        py: Python<'_>,
        mean_pressure: Option<f64>,
        force: Option<f64>,
        approach: Option<f64>,
        tolerance: f64,
        max_iterations: usize,
        stiffness: bool,
        warm: Option<PyRef<'_, ContactResult>>,
        paths: Option<std::collections::HashMap<String, String>>,
    ) -> PyResult<ContactResult> {
        let req = request(
            mean_pressure,
            force,
            approach,
            (tolerance, max_iterations),
            stiffness,
            parse_paths(paths.as_ref())?,
        )?;
        if let Some(w) = &warm {
            if w.shape != self.shape {
                return Err(value_error(format!(
                    "warm start has shape {:?} but this contact is {:?}",
                    w.shape, self.shape
                )));
            }
        }
        let warm = warm.as_ref().map(|w| w.sol.clone());
        self.run(py, &req, warm.as_ref())
    }

    /// solve_many(mean_pressures=None, forces=None, approaches=None, *, tolerance=1e-10,
    ///            max_iterations=10000, stiffness=False, paths=None) -> list[ContactResult]
    ///
    /// A load list solved in order, each warm-started from the previous solution where
    /// that pays (as the CLI's bem_contact output does); `paths` as in solve().
    #[pyo3(signature = (mean_pressures = None, forces = None, approaches = None, *, tolerance = 1e-10, max_iterations = 10_000, stiffness = false, paths = None))]
    #[allow(clippy::too_many_arguments)]
    fn solve_many(
        &mut self,
        py: Python<'_>,
        mean_pressures: Option<PyArrayLike1<'_, f64, AllowTypeChange>>,
        forces: Option<PyArrayLike1<'_, f64, AllowTypeChange>>,
        approaches: Option<PyArrayLike1<'_, f64, AllowTypeChange>>,
        tolerance: f64,
        max_iterations: usize,
        stiffness: bool,
        paths: Option<std::collections::HashMap<String, String>>,
    ) -> PyResult<Vec<ContactResult>> {
        let paths = parse_paths(paths.as_ref())?;
        let list = |a: &Option<PyArrayLike1<'_, f64, AllowTypeChange>>| {
            a.as_ref().map(|a| a.as_array().to_vec())
        };
        let loads: Vec<(Option<f64>, Option<f64>, Option<f64>)> =
            match (list(&mean_pressures), list(&forces), list(&approaches)) {
                (Some(v), None, None) => v.into_iter().map(|p| (Some(p), None, None)).collect(),
                (None, Some(v), None) => v.into_iter().map(|f| (None, Some(f), None)).collect(),
                (None, None, Some(v)) => v.into_iter().map(|d| (None, None, Some(d))).collect(),
                _ => {
                    return Err(value_error(
                        "give exactly one of mean_pressures, forces and approaches",
                    ))
                }
            };
        let mut out: Vec<ContactResult> = Vec::with_capacity(loads.len());
        for (p, f, d) in loads {
            let req = request(p, f, d, (tolerance, max_iterations), stiffness, paths)?;
            let warm = out.last().map(|r| r.sol.clone());
            out.push(self.run(py, &req, warm.as_ref())?);
        }
        Ok(out)
    }

    /// (ny, nx)
    #[getter]
    fn shape(&self) -> (usize, usize) {
        self.shape
    }
    /// (lx, ly) [length]
    #[getter]
    fn size(&self) -> (f64, f64) {
        self.size
    }
    /// E* [stress]
    #[getter]
    fn e_star(&self) -> f64 {
        self.e_star
    }
    #[getter]
    fn periodic(&self) -> bool {
        self.periodic
    }
    fn __repr__(&self) -> String {
        format!(
            "Contact(shape={:?}, size={:?}, e_star={}, periodic={})",
            self.shape, self.size, self.e_star, self.periodic
        )
    }
}
