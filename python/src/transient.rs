//! Transient viscoelastic contact in 3D (`bem3d::viscoelastic`) on numpy height maps.

use crate::contact::{grid_array, interruptible, request, Frame, Grid, Signed};
use crate::errors::value_error;
use crate::on_operator::OnOperator;
use bem3d::viscoelastic::{Relaxation, Step, TransientContact as Transient};
use bem3d::{Interrupt, Load, NonPeriodicHalfSpace, Paths, PeriodicHalfSpace, SolverOptions};
use numpy::{AllowTypeChange, PyArray2, PyArrayLike2};
use pyo3::prelude::*;

/// The history on one of the two operators.
type History = OnOperator<Transient<PeriodicHalfSpace>, Transient<NonPeriodicHalfSpace>>;

impl History {
    fn step(&mut self, dt: f64, load: Load, opts: &SolverOptions) -> bem3d::Result<Step> {
        on_operator!(self, h => h.step(dt, load, opts))
    }
    fn time(&self) -> f64 {
        on_operator!(self, h => h.time())
    }
    fn displacement(&self) -> &[f64] {
        on_operator!(self, h => h.displacement())
    }
}

step_class! {
    /// The state after a step of `TransientContact.step`.
    TransientStep { step: Step, shape: (usize, usize) }
    getters {
        /// Time at the step's end [time].
        time: f64,
        /// Rigid-body position from the first contact of the undeformed surface [length].
        approach: f64,
        /// Total normal force [stress x length^2].
        force: f64,
        /// Real contact area, contact cells times cell area [length^2].
        contact_area: f64,
        /// Number of cells carrying pressure.
        contact_cells: usize,
        /// The step's effective modulus E_eff [stress] (bem3d::viscoelastic docs).
        effective_modulus: f64,
    }
    methods {
        /// Cell pressures, shape (ny, nx) [stress].
        #[getter]
        fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
            grid_array(py, &self.step.pressure, self.shape)
        }
        /// Iterations of the step's elastic solve (0 when the surface is out of contact and
        /// no solve ran).
        #[getter]
        fn iterations(&self) -> usize {
            self.step.solve.as_ref().map_or(0, |s| s.iterations)
        }
        /// Criterion reached by the step's elastic solve (0 without a solve).
        #[getter]
        fn residual(&self) -> f64 {
            self.step.solve.as_ref().map_or(0.0, |s| s.residual)
        }
        /// Certificate of the step's elastic solve (0 without a solve; see Contact).
        #[getter]
        fn certificate(&self) -> f64 {
            self.step.solve.as_ref().map_or(0.0, |s| s.certificate)
        }
        fn __repr__(&self) -> String {
            format!(
                "TransientStep(time={:.6e}, force={:.6e}, approach={:.6e}, contact_cells={}, iterations={})",
                self.step.time,
                self.step.force,
                self.step.approach,
                self.step.contact_cells,
                self.iterations()
            )
        }
    }
}

/// A rigid rough surface on a linear viscoelastic half-space, stepped in time (3D FFT
/// boundary elements; Section 8 of the MRD review in 3D).
///
/// TransientContact(heights, relaxed, terms, size=None, periodic=None, mask=None)
///
/// The contact modulus relaxes as E*(t) = relaxed + sum_k E_k exp(-t / tau_k), `terms` a
/// list of (E_k, tau_k) [stress, time] (E* = 4 G for an incompressible medium). heights,
/// size, periodic and mask as for Contact. The medium starts undeformed at t = 0; each
/// step() advances the time, the load varying linearly over the step (exact time
/// integration for piecewise-linear displacement: bem3d/src/viscoelastic.rs).
#[pyclass(module = "mrdw._mrdw")]
pub struct TransientContact {
    history: History,
    frame: Frame,
    interrupt: Interrupt,
}

grid_getters!(TransientContact);

#[pymethods]
impl TransientContact {
    #[new]
    #[pyo3(signature = (heights, relaxed, terms, size = None, periodic = None, mask = None))]
    fn new(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        relaxed: f64,
        terms: Vec<(f64, f64)>,
        size: Option<(f64, f64)>,
        periodic: Option<bool>,
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
    ) -> PyResult<Self> {
        let modulus = Relaxation::new(relaxed, terms).map_err(|e| value_error(e.to_string()))?;
        // The elastic solve's checks (at the glassy modulus), then the history's arrays:
        // heights, displacement, the raised heights and their lift, one hereditary
        // integral per term.
        let e_ref = modulus.glassy();
        let grid = Grid::new(py, heights, (size, periodic), mask, e_ref, false).map_err(|e| {
            // The operator's check names E*, which this class takes as its terms.
            let text = e.value(py).to_string().replace(
                "e_star (the contact modulus E*)",
                "the glassy modulus relaxed + sum of the terms' E_k",
            );
            if e.is_instance_of::<pyo3::exceptions::PyValueError>(py) {
                value_error(text)
            } else {
                e
            }
        })?;
        let per_cell = 8.0 * (4 + modulus.terms.len()) as f64;
        crate::errors::check_grid_memory("the history of a", grid.frame.shape, per_cell)?;
        let (h, mask, frame) = (grid.heights, grid.mask, grid.frame);
        let history = frame.solve(py, || -> bem3d::Result<History> {
            Ok(built_on!(frame, e_ref, op => Transient::new(op, &h, mask, modulus)?))
        })?;
        Ok(Self {
            history,
            frame: grid.frame,
            interrupt: Interrupt::default(),
        })
    }

    /// step(dt, mean_pressure=None, force=None, approach=None, *, tolerance=1e-10,
    ///      max_iterations=10000) -> TransientStep
    ///
    /// Advances by dt [time] to exactly one of: mean pressure over lx * ly [stress], total
    /// force [stress x length^2] or approach [length] at the step's end. A step that
    /// leaves the surface out of contact (approach control) runs no solve and the medium
    /// recovers freely. Raises ValueError for bad input, ConvergenceError if a solve
    /// reaches its iteration cap. The GIL is released while solving.
    #[pyo3(signature = (dt, mean_pressure = None, force = None, approach = None, *, tolerance = 1e-10, max_iterations = 10_000))]
    #[allow(clippy::too_many_arguments)]
    fn step(
        &mut self,
        py: Python<'_>,
        dt: f64,
        mean_pressure: Option<f64>,
        force: Option<f64>,
        approach: Option<f64>,
        tolerance: f64,
        max_iterations: usize,
    ) -> PyResult<TransientStep> {
        // A negative approach lifts the body off (no contact, the history relaxing).
        let req = request(
            (mean_pressure, force, approach, Signed::Approach),
            (tolerance, max_iterations),
            false,
            Paths::default(),
        )?;
        let opts = SolverOptions {
            interrupt: Some(self.interrupt.clone()),
            ..req.opts.clone()
        };
        let history = &mut self.history;
        let out = interruptible(py, &self.interrupt, || history.step(dt, req.load, &opts))?;
        let step = out.map_err(|e| self.frame.err(py, e))?;
        Ok(TransientStep {
            step,
            shape: self.frame.shape,
        })
    }

    /// Time reached [time].
    #[getter]
    fn time(&self) -> f64 {
        self.history.time()
    }
    /// Surface displacement into the half-space, shape (ny, nx) [length].
    #[getter]
    fn displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        grid_array(py, self.history.displacement(), self.frame.shape)
    }
    fn __repr__(&self) -> String {
        let extra = format!(", time={}", self.history.time());
        self.frame.repr("TransientContact", &extra)
    }
}
