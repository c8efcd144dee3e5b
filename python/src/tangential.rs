//! Tangential contact in 3D (`bem3d::tangential`): partial slip under Coulomb's law with
//! Cerruti's operator on the periodic or the free half-space, and the stick stiffness of
//! a contact set (periodic), on numpy arrays.

use crate::contact::{bem_err, grid_array, interruptible, Stop};
use crate::errors::value_error;
use bem3d::tangential::{
    CerrutiFree, CerrutiPeriodic, PartialSlip as Slip, TangentialCompliance,
    TangentialStep as Step, ViscoelasticSlip as VeSlip, ViscoelasticStep as VeStep,
};
use bem3d::viscoelastic::Relaxation;
use numpy::{AllowTypeChange, PyArray2, PyArrayLike2, PyUntypedArrayMethods};
use pyo3::prelude::*;

/// The substrate's shear modulus G = E* (1 - nu) / 2 under a rigid body, with E* and
/// nu checked (E* in the normal operators' range, with `Contact`'s words).
fn shear_modulus(e_star: f64, poisson: f64) -> PyResult<f64> {
    bem3d::operator::check_scales(1.0, 1.0, e_star).map_err(|e| value_error(e.to_string()))?;
    check_poisson(poisson)?;
    Ok(e_star * (1.0 - poisson) / 2.0)
}

/// `size` within the range the normal operators take, the error naming size[0] or size[1].
fn check_size((lx, ly): (f64, f64)) -> PyResult<()> {
    bem3d::operator::check_scales(lx, ly, 1.0).map_err(|e| value_error(e.to_string()))
}

fn check_poisson(poisson: f64) -> PyResult<()> {
    if !(0.0..=0.5).contains(&poisson) {
        return Err(value_error(format!(
            "poisson = {poisson} must lie in [0, 0.5]"
        )));
    }
    Ok(())
}

/// The memory of `bytes_per_cell` on the grid, checked.
fn check_memory(shape: (usize, usize), bytes_per_cell: f64) -> PyResult<()> {
    crate::errors::check_grid_memory("a tangential", shape, bytes_per_cell)
}

/// The periodic Cerruti operator of a substrate of modulus E* and Poisson's ratio nu
/// under a rigid body (a dozen grids).
fn cerruti(
    shape: (usize, usize),
    (lx, ly): (f64, f64),
    e_star: f64,
    poisson: f64,
) -> PyResult<CerrutiPeriodic> {
    let g = shear_modulus(e_star, poisson)?;
    check_size((lx, ly))?;
    check_memory(shape, 8.0 * 12.0)?;
    CerrutiPeriodic::new(shape.1, shape.0, lx, ly, g, poisson)
        .map_err(|e| value_error(e.to_string()))
}

/// The periodic or the free Cerruti operator of shear modulus `g` (the free one
/// convolves on a grid padded to four times the cells: about 20 grids).
fn cerruti_on(
    shape: (usize, usize),
    (lx, ly): (f64, f64),
    g: f64,
    poisson: f64,
    periodic: bool,
) -> PyResult<Box<dyn TangentialCompliance + Sync>> {
    check_poisson(poisson)?;
    check_size((lx, ly))?;
    check_memory(shape, if periodic { 8.0 * 12.0 } else { 8.0 * 20.0 })?;
    let (nx, ny) = (shape.1, shape.0);
    let op: Box<dyn TangentialCompliance + Sync> = if periodic {
        Box::new(
            CerrutiPeriodic::new(nx, ny, lx, ly, g, poisson)
                .map_err(|e| value_error(e.to_string()))?,
        )
    } else {
        Box::new(
            CerrutiFree::new(nx, ny, lx, ly, g, poisson).map_err(|e| value_error(e.to_string()))?,
        )
    };
    Ok(op)
}

/// A 2D float64 array as (values row by row, (ny, nx)); any strides (a slice or a
/// transposed view is copied in its logical order).
fn grid_of(a: PyArrayLike2<'_, f64, AllowTypeChange>) -> (Vec<f64>, (usize, usize)) {
    let shape = (a.shape()[0], a.shape()[1]);
    (a.as_array().iter().copied().collect(), shape)
}

step_class! {
    /// The state after a step of `PartialSlip.load`.
    TangentialStep { step: Step }
    getters {
        /// The tangential force reached [stress x length^2].
        force: f64,
        /// Cells that stick (|q| < mu p) and cells that slip.
        stick_cells: usize,
        slip_cells: usize,
        iterations: usize,
        residual: f64,
        /// The force reached the total friction mu P: the body slides as a whole.
        sliding: bool,
    }
    methods {
        /// Rigid shift of the body along x [length]: from the mean surface displacement on
        /// the periodic half-space, absolute on the free one; None when sliding (how far
        /// the body slides at mu P is not set by a quasi-static step).
        #[getter]
        fn shift(&self) -> Option<f64> {
            (!self.step.sliding).then_some(self.step.shift)
        }
        /// Energy dissipated by slip in this step [stress x length^3]; None when sliding
        /// (mu P times a slide distance the step does not set).
        #[getter]
        fn dissipated(&self) -> Option<f64> {
            (!self.step.sliding).then_some(self.step.dissipated)
        }
        fn __repr__(&self) -> String {
            let shift = self.shift().map_or("None".into(), |v| format!("{v:.6e}"));
            format!(
                "TangentialStep(force={:.6e}, shift={shift}, stick_cells={}, sliding={})",
                self.step.force, self.step.stick_cells, self.step.sliding
            )
        }
    }
}

/// Partial slip of a held normal contact under a tangential force history along x
/// (3D FFT boundary elements; Sections 6 and 7 of the MRD review in 3D).
///
/// PartialSlip(pressure, mu, size=(1.0, 1.0), e_star=1.0, poisson=0.5, *, periodic=True)
///
/// `pressure` (ny, nx) [stress] is held (e.g. ContactResult.pressure of a Contact with
/// the same `periodic`); `periodic=False` solves on the free half-space (the traction
/// vanishes outside the map; the shift is then the body's absolute displacement, as in
/// Mindlin's solution); Coulomb's law with friction coefficient `mu` (at most 1e6) cell by cell; the traction acts
/// along x only (q_y = 0, Mindlin's model). The substrate has modulus `e_star` and
/// Poisson's ratio `poisson` (shear modulus E* (1 - nu) / 2 under a rigid body); nu = 0.5
/// uncouples normal and tangential contact exactly. Each load() starts from the last
/// state (friction is path dependent).
#[pyclass(module = "mrdw._mrdw")]
pub struct PartialSlip {
    slip: Slip<Box<dyn TangentialCompliance + Sync>>,
    shape: (usize, usize),
    stop: Stop,
}

#[pymethods]
impl PartialSlip {
    #[new]
    #[pyo3(signature = (pressure, mu, size = (1.0, 1.0), e_star = 1.0, poisson = 0.5, *, periodic = true))]
    fn new(
        pressure: PyArrayLike2<'_, f64, AllowTypeChange>,
        mu: f64,
        size: (f64, f64),
        e_star: f64,
        poisson: f64,
        periodic: bool,
    ) -> PyResult<Self> {
        let (p, shape) = grid_of(pressure);
        let g = shear_modulus(e_star, poisson)?;
        let op = cerruti_on(shape, size, g, poisson, periodic)?;
        let mut slip = Slip::new(op, &p, mu).map_err(|e| value_error(e.to_string()))?;
        let stop = Stop::new("PartialSlip", shape, 1.0);
        slip.interrupt_on(stop.flag.clone());
        Ok(Self { slip, shape, stop })
    }

    /// load(force, *, tolerance=1e-8) -> TangentialStep
    ///
    /// Loads to the tangential force `force` [stress x length^2] from the last state. At
    /// or beyond mu P the body slides (TangentialStep.sliding, not an error). Raises
    /// ValueError for bad input, ConvergenceError if the iteration does not settle.
    #[pyo3(signature = (force, *, tolerance = 1e-8))]
    fn load(&mut self, py: Python<'_>, force: f64, tolerance: f64) -> PyResult<TangentialStep> {
        let slip = &mut self.slip;
        let step = self.stop.run(py, || slip.load(force, tolerance))?;
        Ok(TangentialStep { step })
    }

    /// cycle(amplitude, steps=10, cycles=2, *, tolerance=1e-8) -> (dissipated, loop_area)
    ///
    /// An oscillating force of `amplitude` (below mu P) from the current state: a ramp
    /// of `steps` steps, then `cycles` cycles to -amplitude and back (steps x (2 cycles + 1)
    /// loads, at most 1e6); returns the last cycle's dissipated energy and the area of its
    /// force-shift loop [stress x length^3].
    #[pyo3(signature = (amplitude, steps = 10, cycles = 2, *, tolerance = 1e-8))]
    fn cycle(
        &mut self,
        py: Python<'_>,
        amplitude: f64,
        steps: usize,
        cycles: usize,
        tolerance: f64,
    ) -> PyResult<(f64, f64)> {
        let slip = &mut self.slip;
        let c = self
            .stop
            .run(py, || slip.cycle(amplitude, steps, cycles, tolerance))?;
        Ok((c.dissipated, c.loop_area))
    }

    /// The largest tangential force without sliding, mu P [stress x length^2].
    #[getter]
    fn friction_limit(&self) -> f64 {
        self.slip.friction_limit()
    }
    /// The traction of the last step, shape (ny, nx) [stress].
    #[getter]
    fn traction<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        grid_array(py, self.slip.traction(), self.shape)
    }
    /// The accumulated slip of each cell, shape (ny, nx) [length].
    #[getter]
    fn slip<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        grid_array(py, self.slip.slip(), self.shape)
    }
    fn __repr__(&self) -> String {
        format!(
            "PartialSlip(shape={:?}, friction_limit={:.6e})",
            self.shape,
            self.slip.friction_limit()
        )
    }
}

/// stick_stiffness(contact, size=(1.0, 1.0), e_star=1.0, poisson=0.5, *, tolerance=1e-10)
///     -> (k_x, k_y, k_x_along_only)
///
/// Tangential stiffness [stress x length] of the cells `contact` (ny, nx, bool) held in
/// full stick on the periodic half-space, from Cerruti's whole tensor: displaced along
/// x (k_x) or y (k_y) and held in the other direction, and along x with the traction
/// along x only (q_y = 0). Measured from the mean surface displacement, as
/// ContactResult.stiffness measures the normal one: k_x / k_n is 2 (1 - nu) / (2 - nu)
/// for a circle (Mindlin) and MRD's G* / E* for any contact.
#[pyfunction]
#[pyo3(signature = (contact, size = (1.0, 1.0), e_star = 1.0, poisson = 0.5, *, tolerance = 1e-10))]
pub fn stick_stiffness(
    py: Python<'_>,
    contact: PyArrayLike2<'_, bool, AllowTypeChange>,
    size: (f64, f64),
    e_star: f64,
    poisson: f64,
    tolerance: f64,
) -> PyResult<(f64, f64, f64)> {
    let shape = (contact.shape()[0], contact.shape()[1]);
    let c: Vec<bool> = contact.as_array().iter().copied().collect();
    let mut op = cerruti(shape, size, e_star, poisson)?;
    let limit = 20 * shape.0.max(shape.1) + 2000;
    let flag = bem3d::Interrupt::default();
    let k = interruptible(py, &flag, || {
        op.stick_stiffness_until(&c, tolerance, limit, &flag)
    })?
    .map_err(|e| bem_err(py, e, shape, 1.0))?;
    Ok((k.x, k.y, k.x_along_only))
}

step_class! {
    /// The state after a step of `ViscoelasticSlip.step`.
    ViscoelasticStep { step: VeStep }
    getters {
        /// Time at the end of the step [time].
        time: f64,
        /// The prescribed shift [length].
        shift: f64,
        /// The tangential force it takes [stress x length^2].
        force: f64,
        stick_cells: usize,
        slip_cells: usize,
        /// Energy dissipated by slip in this step [stress x length^3].
        dissipated: f64,
        /// Solves the step took: 1 on the free half-space (the shift held), the trials
        /// of the force on the periodic one, 0 where the body slides.
        solves: usize,
        /// Conjugate-gradient iterations of those solves.
        iterations: usize,
        /// The body slides: every contact cell at its bound.
        sliding: bool,
    }
    methods {
        fn __repr__(&self) -> String {
            format!(
                "ViscoelasticStep(time={:.6e}, shift={:.6e}, force={:.6e}, stick_cells={}, sliding={})",
                self.step.time,
                self.step.shift,
                self.step.force,
                self.step.stick_cells,
                self.step.sliding
            )
        }
    }
}

/// Partial slip of a held normal contact on a viscoelastic half-space under a
/// prescribed tangential shift history along x (3D; Section 8, Eqs. 64-65 in 3D).
///
/// ViscoelasticSlip(pressure, mu, relaxed, terms=(), size=(1.0, 1.0), poisson=0.5, *,
///                  periodic=False)
///
/// `pressure` (ny, nx) [stress] is held (the relaxed normal contact); the substrate's
/// shear modulus relaxes as G(t) = relaxed + sum G_k exp(-t / tau_k) [stress] with
/// `terms` = [(G_k, tau_k), ...] and Poisson's ratio `poisson` held in time; Coulomb's
/// law with `mu` cell by cell, the traction along x (q_y = 0). Each step() moves the
/// body linearly in time to the given shift (exact time integration for that) and
/// returns the force it takes; beyond the friction limit the body slides (reported).
#[pyclass(module = "mrdw._mrdw")]
pub struct ViscoelasticSlip {
    slip: VeSlip<Box<dyn TangentialCompliance + Sync>>,
    shape: (usize, usize),
    stop: Stop,
}

#[pymethods]
impl ViscoelasticSlip {
    #[new]
    #[pyo3(signature = (pressure, mu, relaxed, terms = Vec::new(), size = (1.0, 1.0), poisson = 0.5, *, periodic = false))]
    fn new(
        pressure: PyArrayLike2<'_, f64, AllowTypeChange>,
        mu: f64,
        relaxed: f64,
        terms: Vec<(f64, f64)>,
        size: (f64, f64),
        poisson: f64,
        periodic: bool,
    ) -> PyResult<Self> {
        let (p, shape) = grid_of(pressure);
        let modulus = Relaxation::new(relaxed, terms).map_err(|e| value_error(e.to_string()))?;
        // The operator of unit shear modulus; the moduli live in the relaxation.
        let op = cerruti_on(shape, size, 1.0, poisson, periodic)?;
        let mut slip = VeSlip::new(op, &p, mu, modulus).map_err(|e| value_error(e.to_string()))?;
        let stop = Stop::new("ViscoelasticSlip", shape, 1.0);
        slip.interrupt_on(stop.flag.clone());
        Ok(Self { slip, shape, stop })
    }

    /// step(dt, shift, *, tolerance=1e-8) -> ViscoelasticStep
    ///
    /// Moves the body to `shift` [length] over `dt` [time]. Raises ValueError for bad
    /// input, ConvergenceError if the force of the shift is not found.
    #[pyo3(signature = (dt, shift, *, tolerance = 1e-8))]
    fn step(
        &mut self,
        py: Python<'_>,
        dt: f64,
        shift: f64,
        tolerance: f64,
    ) -> PyResult<ViscoelasticStep> {
        let slip = &mut self.slip;
        let step = self.stop.run(py, || slip.step(dt, shift, tolerance))?;
        Ok(ViscoelasticStep { step })
    }

    /// The largest tangential force without sliding, mu P [stress x length^2].
    #[getter]
    fn friction_limit(&self) -> f64 {
        self.slip.friction_limit()
    }
    fn __repr__(&self) -> String {
        format!(
            "ViscoelasticSlip(shape={:?}, friction_limit={:.6e})",
            self.shape,
            self.slip.friction_limit()
        )
    }
}
