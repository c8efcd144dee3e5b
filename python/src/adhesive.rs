//! Adhesive normal contact in 3D (`bem3d::adhesion`: the JKR limit with Pohrt & Popov's
//! mesh-dependent detachment criterion) on numpy height maps.

use crate::contact::{grid_array, Frame, Grid, Stop};
use crate::errors::value_error;
use crate::on_operator::OnOperator;
use bem3d::adhesion::{AdhesiveContact as Adhesive, AdhesiveStep as Step};
use bem3d::{Load, NonPeriodicHalfSpace, PeriodicHalfSpace};
use numpy::{AllowTypeChange, PyArray2, PyArrayLike2};
use pyo3::prelude::*;

/// The contact on one of the two operators.
type State = OnOperator<Adhesive<PeriodicHalfSpace>, Adhesive<NonPeriodicHalfSpace>>;

impl State {
    fn step(&mut self, load: Load, tolerance: f64) -> bem3d::Result<Step> {
        on_operator!(self, c => c.step(load, tolerance))
    }
    fn interrupt_on(&mut self, flag: bem3d::Interrupt) {
        on_operator!(self, c => c.interrupt_on(flag))
    }
    fn pressure(&self) -> &[f64] {
        on_operator!(self, c => c.pressure())
    }
    fn gap(&self) -> Vec<f64> {
        on_operator!(self, c => c.gap())
    }
    fn critical_stress(&self) -> f64 {
        on_operator!(self, c => c.critical_stress())
    }
}

step_class! {
    /// The state after a step of `AdhesiveContact.step`.
    AdhesiveStep { step: Step, pressure: Vec<f64>, shape: (usize, usize) }
    getters {
        /// Approach from first contact [length] (negative: retracted past it).
        approach: f64,
        /// Total normal force [stress x length^2], negative in tension.
        force: f64,
        /// Contact cells times cell area [length^2].
        contact_area: f64,
        contact_cells: usize,
        /// Cells that joined (touched) and detached during the step.
        joined: usize,
        detached: usize,
        /// The largest tension of a contact cell over the critical stress (<= 1).
        tension: f64,
        /// Set-update rounds, and conjugate-gradient iterations summed over them.
        rounds: usize,
        iterations: usize,
        /// The last round's criterion value (bem3d/src/adhesion.rs).
        residual: f64,
        /// No cell is in contact at the end of the step.
        separated: bool,
    }
    methods {
        /// Cell pressures, shape (ny, nx) [stress], negative in tension.
        #[getter]
        fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
            grid_array(py, &self.pressure, self.shape)
        }
        fn __repr__(&self) -> String {
            format!(
                "AdhesiveStep(approach={:.6e}, force={:.6e}, contact_cells={}, separated={})",
                self.step.approach, self.step.force, self.step.contact_cells, self.step.separated
            )
        }
    }
}

/// A rigid surface in adhesive contact with an elastic half-space, loaded along a
/// history (3D FFT boundary elements; Section 5 of the MRD review in 3D).
///
/// AdhesiveContact(heights, work, size=None, e_star=1.0, periodic=None, mask=None)
///
/// Zero-range adhesion in the JKR limit: a cell joins the contact when the body
/// penetrates it and detaches when its tension exceeds the critical stress
/// sqrt(2 w E* / c), c the mean displacement of a uniformly loaded cell per unit
/// pressure (Pohrt & Popov's mesh-dependent criterion; the result converges to JKR as
/// the cells shrink). `work` is the work of adhesion w [stress x length]. heights, size,
/// e_star, periodic and mask as for Contact. Starts out of contact; each step() loads
/// from the last state (adhesion is path dependent).
#[pyclass(module = "mrdw._mrdw")]
pub struct AdhesiveContact {
    state: State,
    frame: Frame,
    stop: Stop,
}

grid_getters!(AdhesiveContact);

#[pymethods]
impl AdhesiveContact {
    #[new]
    #[pyo3(signature = (heights, work, size = None, e_star = 1.0, periodic = None, mask = None))]
    fn new(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        work: f64,
        size: Option<(f64, f64)>,
        e_star: f64,
        periodic: Option<bool>,
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
    ) -> PyResult<Self> {
        if !(work.is_finite() && work > 0.0) {
            return Err(value_error(format!(
                "work = {work}: the work of adhesion must be finite and > 0 (without adhesion use Contact)"
            )));
        }
        let grid = Grid::new(py, heights, (size, periodic), mask, e_star, false)?;
        crate::errors::check_grid_memory(
            "an adhesive",
            grid.frame.shape,
            crate::errors::adhesive_bytes(grid.frame.periodic),
        )?;
        let (h, mask, frame) = (grid.heights, grid.mask, grid.frame);
        let mut state = frame.solve(py, || -> bem3d::Result<State> {
            Ok(built_on!(frame, e_star, op => Adhesive::new(op, &h, mask.as_deref(), work)?))
        })?;
        let stop = Stop::new("AdhesiveContact", frame.shape, frame.area());
        state.interrupt_on(stop.flag.clone());
        Ok(Self {
            state,
            frame: grid.frame,
            stop,
        })
    }

    /// step(mean_pressure=None, force=None, approach=None, *, tolerance=1e-8)
    ///     -> AdhesiveStep
    ///
    /// Loads from the last state to exactly one of: mean pressure over lx * ly [stress],
    /// total force [stress x length^2] (both may be negative: tension) or approach
    /// [length] from first contact (negative: retracted; free half-space only, a
    /// periodic one takes a force). Raises ValueError for bad input, ConvergenceError if
    /// the contact set or a solve does not settle. The GIL is released while solving.
    #[pyo3(signature = (mean_pressure = None, force = None, approach = None, *, tolerance = 1e-8))]
    fn step(
        &mut self,
        py: Python<'_>,
        mean_pressure: Option<f64>,
        force: Option<f64>,
        approach: Option<f64>,
        tolerance: f64,
    ) -> PyResult<AdhesiveStep> {
        let load =
            crate::contact::one_load(mean_pressure, force, approach, crate::contact::Signed::All)?;
        let state = &mut self.state;
        let step = self.stop.run(py, || state.step(load, tolerance))?;
        Ok(AdhesiveStep {
            step,
            pressure: self.state.pressure().to_vec(),
            shape: self.frame.shape,
        })
    }

    /// The critical tension of a cell [stress].
    #[getter]
    fn critical_stress(&self) -> f64 {
        self.state.critical_stress()
    }
    /// Gap of the last step at every cell, shape (ny, nx) [length].
    #[getter]
    fn gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        grid_array(py, &self.state.gap(), self.frame.shape)
    }
    fn __repr__(&self) -> String {
        self.frame.repr("AdhesiveContact", "")
    }
}
