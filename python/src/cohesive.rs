//! Adhesive normal contact in 3D with a finite-range cohesive law (`bem3d::cohesive`:
//! Maugis-Dugdale or exponential) on numpy height maps, under a prescribed approach, on the free or the
//! periodic half-space.

use crate::contact::{grid_array, Frame, Grid, Stop};
use crate::errors::value_error;
use crate::on_operator::OnOperator;
use bem3d::cohesive::{CohesiveContact as Cohesive, CohesiveLaw, CohesiveStep as Step};
use bem3d::{NonPeriodicHalfSpace, PeriodicHalfSpace};
use numpy::{AllowTypeChange, PyArray2, PyArrayLike2};
use pyo3::prelude::*;

step_class! {
    /// The state after a step of `CohesiveContact.step`.
    CohesiveStep { step: Step, pressure: Vec<f64>, shape: (usize, usize) }
    getters {
        /// Approach from first contact [length] (negative: retracted past it).
        approach: f64,
        /// Total normal force [stress x length^2], negative in tension.
        force: f64,
        /// Contact cells (gap 0) times cell area [length^2].
        contact_area: f64,
        /// Cells in contact (gap 0).
        contact_cells: usize,
        /// Cells in the cohesive zone (0 < gap < w / sigma0), under either law.
        cohesive_cells: usize,
        /// Set-update rounds, and conjugate-gradient iterations summed over them.
        rounds: usize,
        iterations: usize,
        /// The last round's criterion value (bem3d/src/cohesive.rs).
        residual: f64,
    }
    methods {
        /// Cell pressures, shape (ny, nx) [stress], negative in tension (>= -sigma0).
        #[getter]
        fn pressure<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
            grid_array(py, &self.pressure, self.shape)
        }
        fn __repr__(&self) -> String {
            format!(
                "CohesiveStep(approach={:.6e}, force={:.6e}, contact_cells={}, cohesive_cells={})",
                self.step.approach, self.step.force, self.step.contact_cells, self.step.cohesive_cells
            )
        }
    }
}

/// The solver on the half-space the constructor chose.
type Solver = OnOperator<Cohesive<PeriodicHalfSpace>, Cohesive<NonPeriodicHalfSpace>>;

impl Solver {
    fn step(&mut self, approach: f64, tolerance: f64) -> bem3d::Result<Step> {
        on_operator!(self, c => c.step(approach, tolerance))
    }
    fn interrupt_on(&mut self, flag: bem3d::Interrupt) {
        on_operator!(self, c => c.interrupt_on(flag))
    }
    fn pressure(&self) -> &[f64] {
        on_operator!(self, c => c.pressure())
    }
    fn dugdale_length(&self) -> f64 {
        on_operator!(self, c => c.dugdale_length())
    }
    fn resolved(&self) -> bool {
        on_operator!(self, c => c.resolved())
    }
    fn law(&self) -> CohesiveLaw {
        on_operator!(self, c => c.law())
    }
}

/// A rigid surface in finite-range adhesive contact with an elastic half-space, free or
/// periodic, loaded along an approach history (3D FFT boundary elements).
///
/// CohesiveContact(heights, work, sigma0, size=None, e_star=1.0, mask=None, periodic=False,
///                 law="dugdale")
///
/// Finite-range adhesion, w = `work` the work of adhesion [stress x length] and
/// rho = w / sigma0 the range [length]. law="dugdale" (Maugis-Dugdale): a constant
/// tension sigma0 [stress] wherever the gap lies below rho. law="exponential": the
/// tension sigma0 exp(-gap / rho) at every gap (the adhesive energy -w exp(-gap / rho),
/// Tamaas' ExponentialAdhesionFunctional with surface_energy = w). With the
/// Tabor-Maugis parameter it spans Bradley's rigid limit to JKR's (the JKR limit is
/// AdhesiveContact). The cohesive zone must span cells: `resolved` says whether the
/// Dugdale length E* w / sigma0^2 spans 10 of them (coarser grids overestimate the
/// pull-off; bem3d/src/cohesive.rs has the measured errors). heights, size, e_star and
/// mask as for Contact. `periodic=False` (the default): the free half-space, the approach
/// measured from first contact. `periodic=True`: the cell repeats and carries no mean
/// displacement, so an approach d fixes the mean gap at mean(max(h) - h) - d (Tamaas'
/// gap control; approaches reaching complete contact are refused). Starts out of
/// contact; each step() loads from the last state.
#[pyclass(module = "mrdw._mrdw")]
pub struct CohesiveContact {
    contact: Solver,
    frame: Frame,
    stop: Stop,
}

grid_getters!(CohesiveContact);

#[pymethods]
impl CohesiveContact {
    #[new]
    #[pyo3(signature = (heights, work, sigma0, size = None, e_star = 1.0, mask = None, periodic = false, law = "dugdale"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        work: f64,
        sigma0: f64,
        size: Option<(f64, f64)>,
        e_star: f64,
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
        periodic: bool,
        law: &str,
    ) -> PyResult<Self> {
        let law = match law {
            "dugdale" => CohesiveLaw::Dugdale,
            "exponential" => CohesiveLaw::Exponential,
            other => {
                return Err(value_error(format!(
                    "law = {other:?}: expected \"dugdale\" or \"exponential\""
                )))
            }
        };
        for (name, v) in [("work", work), ("sigma0", sigma0)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(value_error(format!(
                    "{name} = {v} must be finite and > 0 (without adhesion use Contact; the JKR limit is AdhesiveContact)"
                )));
            }
        }
        let grid = Grid::new(py, heights, (size, Some(periodic)), mask, e_star, false)?;
        crate::errors::check_grid_memory(
            "a cohesive",
            grid.frame.shape,
            crate::errors::adhesive_bytes(grid.frame.periodic),
        )?;
        let (h, mask, frame) = (grid.heights, grid.mask, grid.frame);
        let mut contact = frame.solve(py, || -> bem3d::Result<Solver> {
            Ok(built_on!(frame, e_star, op => {
                Cohesive::new(op, &h, mask.as_deref(), work, sigma0)?.with_law(law)
            }))
        })?;
        let stop = Stop::new("CohesiveContact", frame.shape, frame.area());
        contact.interrupt_on(stop.flag.clone());
        Ok(Self {
            contact,
            frame: grid.frame,
            stop,
        })
    }

    /// step(approach, *, tolerance=1e-8) -> CohesiveStep
    ///
    /// Loads from the last state to the approach [length] from first contact (negative:
    /// retracted). Raises ValueError for bad input, ConvergenceError if the cohesive set
    /// or a solve does not settle. The GIL is released while solving.
    #[pyo3(signature = (approach, *, tolerance = 1e-8))]
    fn step(&mut self, py: Python<'_>, approach: f64, tolerance: f64) -> PyResult<CohesiveStep> {
        if !approach.is_finite() {
            return Err(value_error(format!("approach = {approach} must be finite")));
        }
        let contact = &mut self.contact;
        let step = self.stop.run(py, || contact.step(approach, tolerance))?;
        Ok(CohesiveStep {
            step,
            pressure: self.contact.pressure().to_vec(),
            shape: self.frame.shape,
        })
    }

    /// The Dugdale length E* w / sigma0^2 [length].
    #[getter]
    fn dugdale_length(&self) -> f64 {
        self.contact.dugdale_length()
    }
    /// Whether the Dugdale length spans at least 10 cells.
    #[getter]
    fn resolved(&self) -> bool {
        self.contact.resolved()
    }
    /// "dugdale" or "exponential".
    #[getter]
    fn law(&self) -> &'static str {
        match self.contact.law() {
            CohesiveLaw::Dugdale => "dugdale",
            CohesiveLaw::Exponential => "exponential",
        }
    }
    fn __repr__(&self) -> String {
        let extra = format!(
            ", law={:?}, dugdale_length={:.4e}",
            self.law(),
            self.contact.dugdale_length()
        );
        self.frame.repr("CohesiveContact", &extra)
    }
}
