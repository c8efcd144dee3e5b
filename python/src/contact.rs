//! The 3D boundary-element contact solver (`bem3d`) on numpy height maps.

use crate::errors::{convergence, memory_error, value_error};
use crate::on_operator::OnOperator;
use crate::shared_heights::PyHeights;
use bem3d::{
    Choice, ContactSolver, Interrupt, Load, NonPeriodicHalfSpace, Paths, PeriodicHalfSpace,
    Solution, SolverOptions,
};
use numpy::ndarray::Array2;
use numpy::{AllowTypeChange, PyArray2, PyArrayLike1, PyArrayLike2};
use pyo3::prelude::*;
use std::sync::Arc;

/// The solver on one of the two operators.
type Solver = OnOperator<ContactSolver<PeriodicHalfSpace>, ContactSolver<NonPeriodicHalfSpace>>;

impl Solver {
    fn solve(
        &mut self,
        load: Load,
        opts: &SolverOptions,
        warm: Option<&Solution>,
    ) -> bem3d::Result<Solution> {
        on_operator!(self, s => s.solve(load, opts, warm))
    }
    fn stiffness(&mut self, sol: &Solution, opts: &SolverOptions) -> bem3d::Result<f64> {
        on_operator!(self, s => s.tangent_stiffness(sol, opts))
    }
}

step_class! {
    /// A solved contact state (returned by `Contact.solve`).
    ContactResult {
        step: Solution,
        shape: (usize, usize),
        // lx * ly
        area: f64,
        stiffness: Option<f64>,
    }
    getters {
        /// Rigid-body approach from first contact [length].
        approach: f64,
        /// Total normal force, sum of p times cell area [stress x length^2].
        force: f64,
        /// Real contact area, contact cells times cell area [length^2].
        contact_area: f64,
        /// Number of cells carrying pressure.
        contact_cells: usize,
        /// Mean gap over the cells that may touch [length].
        mean_gap: f64,
        /// Iterations of the contact solve.
        iterations: usize,
        /// Convergence criterion reached (pressure-weighted gap and interpenetration
        /// relative to the rms height; see `bem3d/src/solver.rs`).
        residual: f64,
        /// Bound of the energy's duality gap relative to force x rms height; the pressure
        /// error in the norm of K satisfies (p - p*).K(p - p*) <= 2 x certificate x force x
        /// h_rms (see `bem3d/src/solver.rs`, "What a converged solve guarantees"). At most
        /// the tolerance when the solve converged, except in complete contact, where a solve
        /// may stop at the floor that rounding leaves (residual and certificate then above
        /// the tolerance; "Complete contact" there).
        certificate: f64,
        /// Whether the warm start given to the solve was used (small load steps only).
        warm_started: bool,
        /// Whether the full-grid iteration started from the solution on the grid coarsened
        /// 2 x 2 (large grids under force control).
        nested_start: bool,
        /// Of `iterations`, those that applied the preconditioner by its stencil on the
        /// contact cells.
        stencil_iterations: usize,
        /// Whether the iteration stored its direction vectors as 16-bit integers
        /// scaled per row chunk (grids above 2048^2 cells, unless forbidden).
        scaled_directions: bool,
    }
    methods {
        /// Cell pressures, shape (ny, nx) [stress].
        #[getter]
        fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
            grid_array(py, &self.step.pressure, self.shape)
        }
        /// Gap at cell centres, shape (ny, nx) [length]; zero in contact.
        #[getter]
        fn gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
            grid_array(py, &self.step.gap, self.shape)
        }
        /// Mean pressure over the whole grid area [stress].
        #[getter]
        fn mean_pressure(&self) -> f64 {
            self.step.force / self.area
        }
        /// Contact cells over the cells that may touch (the mask's, or all).
        #[getter]
        fn contact_fraction(&self) -> f64 {
            self.step.contact_cells as f64 / self.step.domain_cells as f64
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
            self.step.complete_contact()
        }
        /// Whether the solve ran restricted to part of the grid: a window around a compact
        /// contact on the non-periodic half-space (`iterations` then count iterations on the
        /// window), or a small candidate set of cells at low contact fractions
        /// (`iterations` then count applications of a dense K between them).
        #[getter]
        fn restricted(&self) -> bool {
            self.step.restricted()
        }
        /// The path the solve took: "full grid", "window" (a compact contact on the
        /// non-periodic half-space) or "candidate set" (a small contact set).
        #[getter]
        fn path(&self) -> &'static str {
            self.step.path.name()
        }
        /// Of `iterations`, those with K p carried in single precision.
        #[getter]
        fn single_precision_iterations(&self) -> usize {
            self.step.single_iterations
        }
        fn __repr__(&self) -> String {
            format!(
                "ContactResult(force={:.6e}, approach={:.6e}, contact_fraction={:.4e}, mean_gap={:.6e}, iterations={}, residual={:.2e}, certificate={:.2e})",
                self.step.force,
                self.step.approach,
                self.contact_fraction(),
                self.step.mean_gap,
                self.step.iterations,
                self.step.residual,
                self.step.certificate
            )
        }
    }
}

impl ContactResult {
    pub fn new(step: Solution, shape: (usize, usize), area: f64, stiffness: Option<f64>) -> Self {
        Self {
            step,
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

/// A height map from an array (ny, nx), a numpy masked array (its masked cells are
/// undefined) or a topography object (see [`Contact`]), not yet copied (its size is
/// checked first), with the object's size and periodicity.
pub struct HeightMap<'py> {
    array: PyArrayLike2<'py, f64, AllowTypeChange>,
    /// The cells a masked array marks undefined, in the array's own indexing.
    undefined: Option<PyArrayLike2<'py, bool, AllowTypeChange>>,
    /// A topography object's heights, indexed (x, y): the map is their transpose.
    by_x: bool,
    pub size: Option<(f64, f64)>,
    pub periodic: Option<bool>,
}

/// The name of a Python object's type, for messages.
fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "?".into())
}

/// A 2D float array as numpy gives it.
type Heights<'py> = PyArrayLike2<'py, f64, AllowTypeChange>;
/// A 2D boolean array as numpy gives it.
type Cells<'py> = PyArrayLike2<'py, bool, AllowTypeChange>;

/// A 2D float array and, for a numpy masked array, its undefined cells (the data there
/// replaced by the smallest defined height: any finite value serves, the cells are
/// left out of the contact).
fn unmask<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<(Heights<'py>, Option<Cells<'py>>)> {
    let py = obj.py();
    let ma = py.import("numpy.ma")?;
    let shape_error = |e: PyErr| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{what} must be a 2D float array (ny, nx), got {} ({e})",
            type_name(obj)
        ))
    };
    if !ma
        .call_method1("isMaskedArray", (obj,))?
        .extract::<bool>()?
    {
        return Ok((obj.extract().map_err(shape_error)?, None));
    }
    let defined: usize = obj.call_method0("count")?.extract()?;
    if defined == 0 {
        return Err(value_error(format!(
            "{what}: every height is masked (undefined)"
        )));
    }
    let filled = obj.call_method1("filled", (obj.call_method0("min")?,))?;
    let undefined = ma.call_method1("getmaskarray", (obj,))?;
    Ok((
        filled.extract().map_err(shape_error)?,
        Some(undefined.extract().map_err(shape_error)?),
    ))
}

impl<'py> HeightMap<'py> {
    pub fn extract(obj: &Bound<'py, PyAny>) -> PyResult<Self> {
        let (has_heights, has_sizes) = (obj.hasattr("heights")?, obj.hasattr("physical_sizes")?);
        if !has_heights && !has_sizes {
            let (array, undefined) = unmask(obj, "heights")?;
            return Ok(Self {
                array,
                undefined,
                by_x: false,
                size: None,
                periodic: None,
            });
        }
        let bad = |what: String| value_error(format!("topography object: {what}"));
        let heights = obj.getattr("heights").ok().filter(|h| h.is_callable());
        let Some(heights) = heights else {
            return Err(bad(format!(
                "it needs a method heights() giving a 2D array indexed (x, y){}",
                match obj.getattr("heights") {
                    Ok(h) => format!(", not an attribute of type {}", type_name(&h)),
                    Err(_) => String::new(),
                }
            )));
        };
        if !has_sizes {
            return Err(bad(
                "it has heights() but no physical_sizes: give it physical_sizes = (lx, ly) \
                 (or None and size= to Contact), or pass the heights as an array (ny, nx)"
                    .into(),
            ));
        }
        let (array, undefined) = unmask(&heights.call0()?, "topography object: heights()")?;
        // None where the topography's size is unknown (then `size=` must be given).
        let size = match obj.getattr("physical_sizes")?.extract::<Option<Vec<f64>>>() {
            Ok(None) => None,
            Ok(Some(v)) if v.len() == 2 => Some((v[0], v[1])),
            Ok(Some(v)) => {
                return Err(bad(format!(
                    "physical_sizes must be (lx, ly) or None, got {} values",
                    v.len()
                )))
            }
            Err(e) => {
                return Err(bad(format!(
                    "physical_sizes must be (lx, ly) or None ({e})"
                )))
            }
        };
        let periodic = match obj.getattr("is_periodic") {
            Ok(v) => v
                .extract::<Option<bool>>()
                .map_err(|e| bad(format!("is_periodic must be True, False or None ({e})")))?,
            Err(_) => None,
        };
        Ok(Self {
            array,
            undefined,
            by_x: true,
            size,
            periodic,
        })
    }

    fn oriented<'a, T>(
        &self,
        v: numpy::ndarray::ArrayView2<'a, T>,
    ) -> numpy::ndarray::ArrayView2<'a, T> {
        if self.by_x {
            v.reversed_axes()
        } else {
            v
        }
    }

    fn view(&self) -> numpy::ndarray::ArrayView2<'_, f64> {
        self.oriented(self.array.as_array())
    }

    /// (ny, nx).
    pub fn shape(&self) -> (usize, usize) {
        self.view().dim()
    }

    /// The heights row by row (y) in one copy (a memcpy for a C-ordered array), for the
    /// solvers that keep their own.
    pub fn copy(&self) -> Vec<f64> {
        let view = self.view();
        match view.as_slice() {
            Some(s) => s.to_vec(),
            None => view.iter().copied().collect(),
        }
    }

    /// The heights in place, when numpy holds them as one C-ordered block of rows of y
    /// (a C-ordered array, or a topography's F-ordered one): see [`PyHeights`].
    pub fn shared(&self) -> Option<PyHeights> {
        let array: &Bound<'py, PyArray2<f64>> = &self.array;
        PyHeights::of(array.as_any(), self.view())
    }

    /// The undefined cells row by row (y), if the heights were a masked array.
    pub fn undefined(&self) -> Option<Vec<bool>> {
        let u = self.undefined.as_ref()?;
        Some(self.oriented(u.as_array()).iter().copied().collect())
    }

    /// The solver's mask: the cells `mask` admits (all if None) that are defined, and
    /// how many defined cells there are not; warns when the heights had undefined cells.
    pub fn solver_mask(
        &self,
        py: Python<'_>,
        mask: Option<Vec<bool>>,
    ) -> PyResult<(Option<Vec<bool>>, usize)> {
        let Some(undefined) = self.undefined() else {
            return Ok((mask, 0));
        };
        let count = undefined.iter().filter(|&&u| u).count();
        if count == 0 {
            return Ok((mask, 0));
        }
        let (ny, nx) = self.shape();
        let message = std::ffi::CString::new(format!(
            "heights: {count} of {} cells are undefined (masked); they are left out of the \
             contact, as cells outside mask= are",
            nx * ny
        ))
        .unwrap_or_default();
        PyErr::warn(
            py,
            &py.get_type::<pyo3::exceptions::PyUserWarning>(),
            &message,
            2,
        )?;
        let admitted = undefined
            .iter()
            .enumerate()
            .map(|(i, &u)| !u && mask.as_ref().is_none_or(|m| m[i]))
            .collect();
        Ok((Some(admitted), count))
    }
}

/// The grid of a class that solves on one: shape (ny, nx), size (lx, ly) [length] and
/// whether the half-space repeats with the cell.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub shape: (usize, usize),
    pub size: (f64, f64),
    pub periodic: bool,
}

impl Frame {
    /// lx * ly [length^2].
    pub fn area(&self) -> f64 {
        self.size.0 * self.size.1
    }

    /// A solver's error on this grid as the Python exception (see `contact::bem_err`).
    pub fn err(&self, py: Python<'_>, e: bem3d::BemError) -> PyErr {
        bem_err(py, e, self.shape, self.area())
    }

    /// Runs `solve` with the GIL released; its error as the Python exception.
    pub fn solve<T: Send>(
        &self,
        py: Python<'_>,
        solve: impl FnOnce() -> bem3d::Result<T> + Send,
    ) -> PyResult<T> {
        py.detach(solve).map_err(|e| self.err(py, e))
    }

    /// `Class(shape=.., size=.., periodic=..EXTRA)` for `__repr__`; `extra` starts with
    /// ", " when not empty.
    pub fn repr(&self, class: &str, extra: &str) -> String {
        format!(
            "{class}(shape={:?}, size={:?}, periodic={}{extra})",
            self.shape,
            self.size,
            crate::grid_getters::py_bool(self.periodic)
        )
    }
}

/// The grid a constructor builds on: the heights (rows of y), the solver's mask, the
/// size and periodicity from the arguments or else the topography object's.
pub struct Grid {
    /// The heights, copied; empty where `shared` holds them.
    pub heights: Vec<f64>,
    /// The caller's heights read in place (constructors that ask for them).
    pub shared: Option<PyHeights>,
    pub mask: Option<Vec<bool>>,
    /// Cells the heights left undefined (a masked array's masked cells).
    pub undefined: usize,
    pub frame: Frame,
}

impl Grid {
    /// From `heights` as `Contact` and `TransientContact` take them, `e_star` the
    /// modulus the operator is built with (for the command line's range checks);
    /// `share`: the heights read in place where numpy's layout allows, else copied.
    pub fn new(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        (size, periodic): (Option<(f64, f64)>, Option<bool>),
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
        e_star: f64,
        share: bool,
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
        let (mask, undefined) = map.solver_mask(py, grid_mask(mask, (ny, nx))?)?;
        if mask.as_ref().is_some_and(|m| !m.iter().any(|&m| m)) {
            return Err(value_error(
                "no cell may touch: every cell is undefined or outside mask=",
            ));
        }
        let shared = if share { map.shared() } else { None };
        Ok(Self {
            heights: if shared.is_some() {
                Vec::new()
            } else {
                map.copy()
            },
            shared,
            mask,
            undefined,
            frame: Frame {
                shape: (ny, nx),
                size,
                periodic,
            },
        })
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
/// optional boolean array (ny, nx) of the cells that may touch. A numpy masked array
/// (as SurfaceTopography's heights() gives for maps with undefined points) leaves its
/// masked cells out of the contact, as mask= does, with a UserWarning that counts them
/// (`undefined_cells`). The operator and buffers are built once; solve() may be called
/// for many loads. A float64 array in C order (or a topography object's heights in F
/// order) is read in place, not copied, so a caller who keeps it does not hold the map
/// twice: do not write to it while a solve runs, and a solve after it changed raises
/// ValueError (build a new Contact).
#[pyclass(module = "mrdw._mrdw")]
pub struct Contact {
    solver: Solver,
    frame: Frame,
    e_star: f64,
    /// Cells the heights left undefined (a masked array's), outside the contact.
    undefined: usize,
    /// Set on Ctrl-C during a solve ([`interruptible`]).
    interrupt: Interrupt,
    /// The caller's heights, where the solver reads them in place: checked unchanged
    /// before each solve.
    shared: Option<Arc<PyHeights>>,
}

grid_getters!(Contact);

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

/// Which loads may be negative: none (a non-adhesive contact), the approach (a body
/// that lifts off), or all (an adhesive contact pulls).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Signed {
    None,
    Approach,
    All,
}

/// The one load of the keywords `mean_pressure`, `force` and `approach` (exactly one
/// given), finite and >= 0 unless `signed` lets it be negative; messages name the
/// keyword.
pub(crate) fn one_load(
    mean_pressure: Option<f64>,
    force: Option<f64>,
    approach: Option<f64>,
    signed: Signed,
) -> PyResult<Load> {
    for (name, v) in [
        ("mean_pressure", mean_pressure),
        ("force", force),
        ("approach", approach),
    ] {
        let negative = signed == Signed::All || (signed == Signed::Approach && name == "approach");
        if let Some(v) = v.filter(|v| !(v.is_finite() && (negative || *v >= 0.0))) {
            let need = if negative {
                "finite"
            } else {
                "finite and >= 0"
            };
            return Err(value_error(format!("{name} = {v} must be {need}")));
        }
    }
    match (mean_pressure, force, approach) {
        (Some(p), None, None) => Ok(Load::MeanPressure(p)),
        (None, Some(f), None) => Ok(Load::Force(f)),
        (None, None, Some(d)) => Ok(Load::Approach(d)),
        _ => Err(value_error(
            "give exactly one of mean_pressure, force and approach",
        )),
    }
}

pub(crate) fn request(
    (mean_pressure, force, approach, signed): (Option<f64>, Option<f64>, Option<f64>, Signed),
    (tolerance, max_iterations): (f64, usize),
    stiffness: bool,
    paths: Paths,
) -> PyResult<Request> {
    // Checked here, under the names the caller gave (a solver may see the load rescaled).
    let load = one_load(mean_pressure, force, approach, signed)?;
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

/// A history solver's stop on Ctrl-C: each step runs through [`interruptible`] (the
/// solver polls `flag` once per iteration), and once a step was interrupted the next is
/// refused, since the state is then the unfinished step's.
pub struct Stop {
    pub flag: Interrupt,
    stopped: bool,
    /// The Python class, for the refusal.
    class: &'static str,
    /// The grid and its area, for the solver's errors ([`bem_err`]).
    shape: (usize, usize),
    area: f64,
}

impl Stop {
    pub fn new(class: &'static str, shape: (usize, usize), area: f64) -> Self {
        Self {
            flag: Interrupt::default(),
            stopped: false,
            class,
            shape,
            area,
        }
    }

    /// Runs a step with the GIL released and Ctrl-C polled; a solver's error becomes
    /// the Python exception.
    pub fn run<T: Send>(
        &mut self,
        py: Python<'_>,
        step: impl FnOnce() -> bem3d::Result<T> + Send,
    ) -> PyResult<T> {
        let class = self.class;
        if self.stopped {
            return Err(pyo3::exceptions::PyRuntimeError::new_err(format!(
                "a step of this {class} was interrupted: its state is the unfinished \
                 step's; build a new {class} to go on"
            )));
        }
        let err = |e| bem_err(py, e, self.shape, self.area);
        match interruptible(py, &self.flag, step) {
            Err(raised) => {
                self.stopped = true;
                Err(raised)
            }
            Ok(Err(e @ bem3d::BemError::Interrupted { .. })) => {
                self.stopped = true;
                Err(err(e))
            }
            Ok(out) => out.map_err(err),
        }
    }
}

impl Contact {
    /// Solves one load with the GIL released.
    fn run(
        &mut self,
        py: Python<'_>,
        req: &Request,
        warm: Option<&Solution>,
    ) -> PyResult<ContactResult> {
        if self.shared.as_ref().is_some_and(|h| !h.unchanged()) {
            return Err(value_error(
                "heights: the array changed since this Contact was built (Contact reads it in \
                 place, without a copy): build a new Contact for the new heights",
            ));
        }
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
        let (sol, k) = out.map_err(|e| self.frame.err(py, e))?;
        Ok(ContactResult::new(
            sol,
            self.frame.shape,
            self.frame.area(),
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
        let grid = Grid::new(py, heights, (size, periodic), mask, e_star, true)?;
        let (h, mask) = (&grid.heights, grid.mask);
        let shared = grid.shared.map(Arc::new);
        let heights = shared.clone();
        let solver = grid.frame.solve(py, || -> bem3d::Result<Solver> {
            // The caller's heights in place where numpy's layout allows, else the copy.
            fn solver<K: bem3d::SolverOperator>(
                op: K,
                h: &[f64],
                shared: Option<Arc<PyHeights>>,
                mask: Option<Vec<bool>>,
            ) -> bem3d::Result<ContactSolver<K>> {
                match shared {
                    Some(s) => ContactSolver::new_shared(op, s, mask),
                    None => ContactSolver::new(op, h, mask),
                }
            }
            Ok(built_on!(grid.frame, e_star, op => solver(op, h, heights, mask)?))
        })?;
        Ok(Self {
            solver,
            frame: grid.frame,
            e_star,
            undefined: grid.undefined,
            interrupt: Interrupt::default(),
            shared,
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
            (mean_pressure, force, approach, Signed::None),
            (tolerance, max_iterations),
            stiffness,
            parse_paths(paths.as_ref())?,
        )?;
        if let Some(w) = &warm {
            if w.shape != self.frame.shape {
                return Err(value_error(format!(
                    "warm start has shape {:?} but this contact is {:?}",
                    w.shape, self.frame.shape
                )));
            }
        }
        let warm = warm.as_ref().map(|w| w.step.clone());
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
            let req = request(
                (p, f, d, Signed::None),
                (tolerance, max_iterations),
                stiffness,
                paths,
            )?;
            let warm = out.last().map(|r| r.step.clone());
            out.push(self.run(py, &req, warm.as_ref())?);
        }
        Ok(out)
    }

    /// E* [stress]
    #[getter]
    fn e_star(&self) -> f64 {
        self.e_star
    }
    /// Cells the heights left undefined (a numpy masked array's masked cells, as
    /// SurfaceTopography gives for maps with missing points): left out of the contact.
    #[getter]
    fn undefined_cells(&self) -> usize {
        self.undefined
    }
    fn __repr__(&self) -> String {
        format!(
            "Contact(shape={:?}, size={:?}, e_star={}, periodic={})",
            self.frame.shape,
            self.frame.size,
            self.e_star,
            crate::grid_getters::py_bool(self.frame.periodic)
        )
    }
}

/// Errors of the 3D solver; the last iterate of an unconverged contact solve becomes a
/// `ContactResult`.
pub fn bem_err(py: Python<'_>, e: bem3d::BemError, shape: (usize, usize), area: f64) -> PyErr {
    let message = e.to_string();
    match e {
        bem3d::BemError::InvalidInput(_)
        | bem3d::BemError::Infeasible(_)
        | bem3d::BemError::PathUnavailable { .. } => value_error(message),
        bem3d::BemError::NoConvergence {
            what,
            iterations,
            residual,
            last,
            ..
        } => {
            let last = ContactResult::new(*last, shape, area, None);
            let last = Py::new(py, last).ok().map(|o| o.into_any());
            convergence(py, message, what, iterations, residual, last)
        }
        bem3d::BemError::Breakdown {
            what,
            iterations,
            residual,
            ..
        } => convergence(py, message, what, iterations, residual, None),
        bem3d::BemError::Memory(m) => memory_error(m),
        bem3d::BemError::Interrupted { .. } => {
            pyo3::exceptions::PyKeyboardInterrupt::new_err(message)
        }
    }
}
