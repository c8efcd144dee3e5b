//! Elastic-perfectly plastic normal contact in 3D, the pressure-cap model
//! (`bem3d::plastic`), on numpy height maps, on the free or the periodic half-space.

use crate::contact::{grid_array, one_load, Frame, Grid, Signed, Stop};
use crate::errors::value_error;
use crate::on_operator::OnOperator;
use bem3d::plastic::{PlasticContact as Plastic, PlasticStep as Step, STEP_TOLERANCE};
use bem3d::{Load, NonPeriodicHalfSpace, PeriodicHalfSpace};
use numpy::{AllowTypeChange, PyArray2, PyArrayLike2};
use pyo3::prelude::*;

step_class! {
    /// The state after a step of `PlasticContact.step`.
    PlasticStep { step: Step, pressure: Vec<f64>, plastic: Vec<f64>, shape: (usize, usize) }
    getters {
        /// Approach from the first contact of the undeformed surface [length].
        approach: f64,
        /// Total normal force [stress x length^2].
        force: f64,
        /// Cells carrying pressure, and those of them at the hardness.
        contact_cells: usize,
        plastic_cells: usize,
        /// The same as areas [length^2].
        contact_area: f64,
        plastic_area: f64,
        /// The largest plastic displacement so far [length].
        plastic_depth: f64,
        /// Cells whose plastic displacement grew in this step.
        flowed: usize,
        /// Conjugate-gradient iterations and solves of the step (one solve; more where
        /// the solve holding a force stalled and the approach was searched).
        iterations: usize,
        solves: usize,
        /// The last solve's criterion (bem3d/src/kit/box_cg.rs).
        residual: f64,
    }
    methods {
        /// Cell pressures, shape (ny, nx) [stress], in [0, hardness].
        #[getter]
        fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
            grid_array(py, &self.pressure, self.shape)
        }
        /// The plastic displacement so far, shape (ny, nx) [length]: after unloading,
        /// the imprint.
        #[getter]
        fn plastic_displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
            grid_array(py, &self.plastic, self.shape)
        }
        fn __repr__(&self) -> String {
            format!(
                "PlasticStep(approach={:.6e}, force={:.6e}, contact_cells={}, plastic_cells={})",
                self.step.approach, self.step.force, self.step.contact_cells, self.step.plastic_cells
            )
        }
    }
}

/// The solver on the half-space the constructor chose.
type Solver = OnOperator<Plastic<PeriodicHalfSpace>, Plastic<NonPeriodicHalfSpace>>;

impl Solver {
    fn step(&mut self, load: Load, tolerance: f64) -> bem3d::Result<Step> {
        on_operator!(self, c => c.step(load, tolerance))
    }
    fn interrupt_on(&mut self, flag: bem3d::Interrupt) {
        on_operator!(self, c => c.interrupt_on(flag))
    }
    fn pressure(&self) -> &[f64] {
        on_operator!(self, c => c.pressure())
    }
    fn plastic(&self) -> &[f64] {
        on_operator!(self, c => c.plastic_displacement())
    }
    fn force_limit(&self) -> f64 {
        on_operator!(self, c => c.force_limit())
    }
}

/// A rigid surface pressed on an elastic-perfectly plastic half-space (the pressure-cap
/// model: the contact pressure saturates at the hardness H, and where it would exceed it
/// the surface flows and stays lowered), loaded along a history (3D FFT boundary
/// elements; Section 11's elasto-plastic contact).
///
/// PlasticContact(heights, hardness, size=None, e_star=1.0, mask=None, periodic=False)
///
/// `hardness` [stress] > 0 (inf: the elastic contact). heights, size, e_star and mask as
/// for Contact. Each step() loads from the last state: an unloading leaves the plastic
/// displacement (the imprint, `plastic_displacement`), a reloading is elastic up to the
/// largest earlier load. Under a force the approach is the force's multiplier (one solve;
/// a search of the approach where that solve stalls).
#[pyclass(module = "mrdw._mrdw")]
pub struct PlasticContact {
    contact: Solver,
    frame: Frame,
    stop: Stop,
    hardness: f64,
}

grid_getters!(PlasticContact);

#[pymethods]
impl PlasticContact {
    #[new]
    #[pyo3(signature = (heights, hardness, size = None, e_star = 1.0, mask = None, periodic = false))]
    fn new(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        hardness: f64,
        size: Option<(f64, f64)>,
        e_star: f64,
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
        periodic: bool,
    ) -> PyResult<Self> {
        if hardness.is_nan() || hardness <= 0.0 {
            return Err(value_error(format!(
                "hardness = {hardness} must be > 0 (inf: the elastic contact)"
            )));
        }
        let grid = Grid::new(py, heights, (size, Some(periodic)), mask, e_star, false)?;
        crate::errors::check_grid_memory(
            "a plastic",
            grid.frame.shape,
            crate::errors::adhesive_bytes(grid.frame.periodic),
        )?;
        let (h, mask, frame) = (grid.heights, grid.mask, grid.frame);
        let mut contact = frame.solve(py, || -> bem3d::Result<Solver> {
            Ok(built_on!(frame, e_star, op => {
                Plastic::new(op, &h, mask.as_deref(), hardness)?
            }))
        })?;
        let stop = Stop::new("PlasticContact", frame.shape, frame.area());
        contact.interrupt_on(stop.flag.clone());
        Ok(Self {
            contact,
            frame: grid.frame,
            stop,
            hardness,
        })
    }

    /// step(*, mean_pressure=None, force=None, approach=None, tolerance=None) -> PlasticStep
    ///
    /// Loads from the last state to exactly one of: a mean pressure [stress] or a force
    /// [stress x length^2] (>= 0 and below hardness x domain area; 0: the body just
    /// touching the surface as it stands), or an approach [length] from the first contact
    /// of the undeformed surface (any finite value; below first contact the body is
    /// apart). tolerance: relative, in (0, 0.01] (None: bem3d's step default, 1e-8).
    /// Raises ValueError for bad input, ConvergenceError if a solve or the force's
    /// search does not settle. The GIL is released while solving.
    #[pyo3(signature = (*, mean_pressure = None, force = None, approach = None, tolerance = None))]
    fn step(
        &mut self,
        py: Python<'_>,
        mean_pressure: Option<f64>,
        force: Option<f64>,
        approach: Option<f64>,
        tolerance: Option<f64>,
    ) -> PyResult<PlasticStep> {
        let load = one_load(mean_pressure, force, approach, Signed::Approach)?;
        let tolerance = tolerance.unwrap_or(STEP_TOLERANCE);
        let contact = &mut self.contact;
        let step = self.stop.run(py, || contact.step(load, tolerance))?;
        Ok(PlasticStep {
            step,
            pressure: self.contact.pressure().to_vec(),
            plastic: self.contact.plastic().to_vec(),
            shape: self.frame.shape,
        })
    }

    /// The hardness H [stress].
    #[getter]
    fn hardness(&self) -> f64 {
        self.hardness
    }
    /// The largest force a step can carry: H times the domain's area [stress x length^2].
    #[getter]
    fn force_limit(&self) -> f64 {
        self.contact.force_limit()
    }
    fn __repr__(&self) -> String {
        let extra = format!(", hardness={:.4e}", self.hardness);
        self.frame.repr("PlasticContact", &extra)
    }
}
