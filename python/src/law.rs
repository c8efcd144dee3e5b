//! Contact laws a time integrator calls (`dynamics`): MRD's springs or the 3D solve behind
//! one class, with trial, commit and rollback, for a user's own integrator.

use crate::axisym::Profile;
use crate::contact::{Frame, Grid};
use crate::errors::{mrd_err, value_error};
use dynamics::{ContactLaw as Law, DynamicsError, Forces, Motion};
use numpy::{AllowTypeChange, PyArrayLike1, PyArrayLike2};
use pyo3::prelude::*;

/// The forces of one state of a contact law.
#[pyclass(module = "mrdw._mrdw", frozen)]
pub struct LawForces {
    forces: Forces,
}

#[pymethods]
impl LawForces {
    /// Normal force [stress x length^2], >= 0.
    #[getter]
    fn normal(&self) -> f64 {
        self.forces.normal
    }
    /// Tangential force [stress x length^2], resisting the displacement.
    #[getter]
    fn tangential(&self) -> f64 {
        self.forces.tangential
    }
    /// Real contact area [length^2] (MRD: its own measure).
    #[getter]
    fn contact_area(&self) -> f64 {
        self.forces.contact_area
    }
    /// Normal tangent stiffness dF/dd [stress x length] (None where the law does not
    /// compute it: the 3D law).
    #[getter]
    fn stiffness(&self) -> Option<f64> {
        self.forces
            .stiffness
            .is_finite()
            .then_some(self.forces.stiffness)
    }
    /// Energy dissipated by slip in the step [stress x length^3].
    #[getter]
    fn dissipated(&self) -> f64 {
        self.forces.dissipated
    }
    /// The 3D solver's iterations in the step (MRD: 0).
    #[getter]
    fn iterations(&self) -> usize {
        self.forces.iterations
    }
    fn __repr__(&self) -> String {
        format!(
            "LawForces(normal={:.6e}, tangential={:.6e}, contact_area={:.6e})",
            self.forces.normal, self.forces.tangential, self.forces.contact_area
        )
    }
}

/// A contact law with history for a time integrator (the review's Section 12): each step
/// is tried at a motion (`trial`), then accepted (`commit`) or discarded (`rollback`), so
/// implicit and adaptive integrators can try a step several times. Build with the static
/// methods: `body` (MRD's springs for a body of revolution, exact by the rule of Hess,
/// optionally with Coulomb friction), `rough_line` (MRD's rough line), `bem3d` (the 3D
/// boundary-element solve, warm-started from the last accepted step; frictionless), or
/// their viscoelastic counterparts `viscoelastic_body` and `viscoelastic_bem3d`, or their
/// adhesive ones (JKR limit) `adhesive_body` and `adhesive_bem3d`, or `slip_bem3d` (the 3D
/// partial slip at a held normal force, the counterpart of `body` with friction).
///
/// Coordinates: the normal approach from first contact (positive pressing) and the
/// tangential displacement; forces are those the contact exerts against the motion.
#[pyclass(module = "mrdw._mrdw")]
pub struct ContactLaw {
    /// Behind a lock so the class is shared safely between Python threads (one caller
    /// at a time steps it).
    law: std::sync::Mutex<Box<dyn Law>>,
    frame: Option<Frame>,
}

impl ContactLaw {
    fn new(law: Box<dyn Law>, frame: Option<Frame>) -> Self {
        Self {
            law: std::sync::Mutex::new(law),
            frame,
        }
    }

    /// A 3D law with both motions on the free half-space: `heights` read as a free grid,
    /// the solver's default tolerance where none is given, and `build` called with the
    /// heights, (nx, ny), (lx, ly) and the tolerance, the GIL released.
    fn free_3d<L: Law + 'static>(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        size: Option<(f64, f64)>,
        e_star: f64,
        tolerance: Option<f64>,
        build: impl FnOnce(&[f64], (usize, usize), (f64, f64), f64) -> dynamics::Result<L> + Send,
    ) -> PyResult<Self> {
        let grid = Grid::new(py, heights, (size, Some(false)), None, e_star, false)?;
        let (h, frame) = (grid.heights, grid.frame);
        let tolerance = tolerance.unwrap_or(bem3d::SolverOptions::default().tolerance);
        let ((ny, nx), (lx, ly)) = (frame.shape, frame.size);
        let law = py
            .detach(|| build(&h, (nx, ny), (lx, ly), tolerance))
            .map_err(|e| law_err(py, Some(&frame), e))?;
        Ok(Self::new(Box::new(law), Some(frame)))
    }

    /// An MRD spring law, with tangential springs and Coulomb slip when `g_star` and `mu`
    /// are both given.
    fn springs(
        py: Python<'_>,
        law: dynamics::Springs,
        g_star: Option<f64>,
        mu: Option<f64>,
    ) -> PyResult<Self> {
        let law = match (g_star, mu) {
            (Some(g), Some(mu)) => law.with_friction(g, mu).map_err(|e| law_err(py, None, e))?,
            (None, None) => law,
            _ => {
                return Err(value_error(
                    "give g_star and mu together (friction) or neither",
                ))
            }
        };
        Ok(Self::new(Box::new(law), None))
    }

    fn law(&self) -> std::sync::MutexGuard<'_, Box<dyn Law>> {
        // A panic while stepping cannot leave a half-written state worse than the error
        // it raised: the lock is taken again.
        self.law.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The springs' half line: `half_length`, else the profile's rim.
fn half_line(profile: &Profile, half_length: Option<f64>) -> PyResult<f64> {
    match (half_length, profile.inner.rim()) {
        (Some(l), _) => Ok(l),
        (None, Some(rim)) => Ok(rim),
        (None, None) => Err(value_error(
            "half_length: a profile without a rim needs the springs' extent (beyond the largest contact radius)",
        )),
    }
}

fn law_err(py: Python<'_>, frame: Option<&Frame>, e: DynamicsError) -> PyErr {
    match e {
        DynamicsError::InvalidInput(m) => value_error(m),
        DynamicsError::Mrd(e) => mrd_err(py, e),
        DynamicsError::Bem(e) => match frame {
            Some(f) => f.err(py, e),
            None => value_error(e.to_string()),
        },
    }
}

#[pymethods]
impl ContactLaw {
    /// body(profile, e_star=1.0, springs=2000, half_length=None, g_star=None, mu=None)
    ///
    /// MRD's springs for a body of revolution (`Profile`): `springs` springs on the half
    /// line [0, half_length] (mirrored; default: the profile's rim, else give it), gaps
    /// by the rule of Hess. With `g_star` and `mu` also tangential springs G* dx with
    /// Coulomb slip (Cattaneo-Mindlin, exact for bodies of revolution).
    #[staticmethod]
    #[pyo3(signature = (profile, e_star = 1.0, springs = 2000, half_length = None, g_star = None, mu = None))]
    fn body(
        py: Python<'_>,
        profile: &Profile,
        e_star: f64,
        springs: usize,
        half_length: Option<f64>,
        g_star: Option<f64>,
        mu: Option<f64>,
    ) -> PyResult<Self> {
        let half = half_line(profile, half_length)?;
        let law = dynamics::Springs::body(&profile.inner, e_star, springs, half)
            .map_err(|e| law_err(py, None, e))?;
        Self::springs(py, law, g_star, mu)
    }

    /// rough_line(heights, length, e_star=1.0, nominal_area=None, g_star=None, mu=None)
    ///
    /// MRD's rough line: springs E* dx under the 1D heights (peaks up) over `length`;
    /// the contact area is the contact length's fraction of the line times
    /// `nominal_area` (default: a disc of diameter `length`). With `g_star` and `mu`
    /// also tangential springs with Coulomb slip.
    #[staticmethod]
    #[pyo3(signature = (heights, length, e_star = 1.0, nominal_area = None, g_star = None, mu = None))]
    fn rough_line(
        py: Python<'_>,
        heights: PyArrayLike1<'_, f64, AllowTypeChange>,
        length: f64,
        e_star: f64,
        nominal_area: Option<f64>,
        g_star: Option<f64>,
        mu: Option<f64>,
    ) -> PyResult<Self> {
        let h: Vec<f64> = heights.as_array().iter().copied().collect();
        let area = nominal_area.unwrap_or(std::f64::consts::PI * length * length / 4.0);
        let law = dynamics::Springs::rough_line(&h, length, e_star, area)
            .map_err(|e| law_err(py, None, e))?;
        Self::springs(py, law, g_star, mu)
    }

    /// bem3d(heights, size=None, e_star=1.0, mask=None, periodic=False, tolerance=None)
    ///
    /// The 3D boundary-element normal contact of the height map (as for Contact): each
    /// trial a solve under the step's approach (from first contact of the highest cell),
    /// warm-started from the last accepted solution; frictionless (a tangential motion
    /// raises ValueError). tolerance: the solver's (None: its default, 1e-10).
    #[staticmethod]
    #[pyo3(signature = (heights, size = None, e_star = 1.0, mask = None, periodic = false, tolerance = None))]
    fn bem3d(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        size: Option<(f64, f64)>,
        e_star: f64,
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
        periodic: bool,
        tolerance: Option<f64>,
    ) -> PyResult<Self> {
        let grid = Grid::new(py, heights, (size, Some(periodic)), mask, e_star, false)?;
        let (h, mask, frame) = (grid.heights, grid.mask, grid.frame);
        let defaults = bem3d::SolverOptions::default();
        let tolerance = tolerance.unwrap_or(defaults.tolerance);
        let law: Box<dyn Law> = frame.solve(py, || -> bem3d::Result<Box<dyn Law>> {
            let ((ny, nx), (lx, ly)) = (frame.shape, frame.size);
            let wrap = |e: DynamicsError| match e {
                DynamicsError::Bem(e) => e,
                other => bem3d::BemError::InvalidInput(other.to_string()),
            };
            Ok(if frame.periodic {
                let op = bem3d::PeriodicHalfSpace::try_new(nx, ny, lx, ly, e_star)?;
                Box::new(
                    dynamics::Bem3d::new(op, &h, mask, tolerance, defaults.max_iterations)
                        .map_err(wrap)?,
                )
            } else {
                let op = bem3d::NonPeriodicHalfSpace::try_new(nx, ny, lx, ly, e_star)?;
                Box::new(
                    dynamics::Bem3d::new(op, &h, mask, tolerance, defaults.max_iterations)
                        .map_err(wrap)?,
                )
            })
        })?;
        Ok(Self::new(law, Some(frame)))
    }

    /// viscoelastic_body(profile, relaxed, terms, springs=2000, half_length=None)
    ///
    /// MRD's viscoelastic springs for a body of revolution: the contact modulus relaxes
    /// as E*(t) = relaxed + sum_k E_k exp(-t / tau_k), `terms` a list of (E_k, tau_k)
    /// [stress, time]; each spring carries the hereditary integral of its elongation
    /// (Eq. 63), separates at zero force and recovers freely while apart. Springs and
    /// half_length as for body(). Frictionless; the force depends on each trial's `dt`.
    #[staticmethod]
    #[pyo3(signature = (profile, relaxed, terms, springs = 2000, half_length = None))]
    fn viscoelastic_body(
        py: Python<'_>,
        profile: &Profile,
        relaxed: f64,
        terms: Vec<(f64, f64)>,
        springs: usize,
        half_length: Option<f64>,
    ) -> PyResult<Self> {
        let half = half_line(profile, half_length)?;
        let modulus = mrd::rheology::Prony::new(relaxed, terms).map_err(|e| mrd_err(py, e))?;
        let law = dynamics::ViscoelasticSprings::body(&profile.inner, &modulus, springs, half)
            .map_err(|e| law_err(py, None, e))?;
        Ok(Self::new(Box::new(law), None))
    }

    /// viscoelastic_bem3d(heights, relaxed, terms, size=None, mask=None, periodic=False, tolerance=None)
    ///
    /// The 3D transient viscoelastic contact of the height map (as TransientContact, the
    /// same modulus arguments) as a contact law: each trial one time step of `dt` under
    /// the step's approach, linear in time over the step; a rollback restores the state
    /// before it. Frictionless. tolerance: the solver's (None: its default, 1e-10).
    #[staticmethod]
    #[pyo3(signature = (heights, relaxed, terms, size = None, mask = None, periodic = false, tolerance = None))]
    #[allow(clippy::too_many_arguments)]
    fn viscoelastic_bem3d(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        relaxed: f64,
        terms: Vec<(f64, f64)>,
        size: Option<(f64, f64)>,
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
        periodic: bool,
        tolerance: Option<f64>,
    ) -> PyResult<Self> {
        let modulus = bem3d::viscoelastic::Relaxation::new(relaxed, terms)
            .map_err(|e| value_error(e.to_string()))?;
        let grid = Grid::new(
            py,
            heights,
            (size, Some(periodic)),
            mask,
            modulus.glassy(),
            false,
        )?;
        let (h, mask, frame) = (grid.heights, grid.mask, grid.frame);
        let defaults = bem3d::SolverOptions::default();
        let tolerance = tolerance.unwrap_or(defaults.tolerance);
        let law: Box<dyn Law> = frame.solve(py, || -> bem3d::Result<Box<dyn Law>> {
            let ((ny, nx), (lx, ly)) = (frame.shape, frame.size);
            let wrap = |e: DynamicsError| match e {
                DynamicsError::Bem(e) => e,
                other => bem3d::BemError::InvalidInput(other.to_string()),
            };
            let e_ref = modulus.glassy();
            Ok(if frame.periodic {
                let op = bem3d::PeriodicHalfSpace::try_new(nx, ny, lx, ly, e_ref)?;
                Box::new(
                    dynamics::ViscoelasticBem3d::new(
                        op,
                        &h,
                        mask,
                        modulus.clone(),
                        tolerance,
                        defaults.max_iterations,
                    )
                    .map_err(wrap)?,
                )
            } else {
                let op = bem3d::NonPeriodicHalfSpace::try_new(nx, ny, lx, ly, e_ref)?;
                Box::new(
                    dynamics::ViscoelasticBem3d::new(
                        op,
                        &h,
                        mask,
                        modulus.clone(),
                        tolerance,
                        defaults.max_iterations,
                    )
                    .map_err(wrap)?,
                )
            })
        })?;
        Ok(Self::new(law, Some(frame)))
    }

    /// adhesive_body(profile, e_star, work, springs=2000, half_length=None)
    ///
    /// MRD's adhesive springs for a body of revolution in the JKR limit (zero-range
    /// adhesion of work w [energy / length^2]): springs by the rule of Hess on both halves
    /// of the line, each attached once touched and detached by Eq. 33; tensile forces are
    /// negative. Springs and half_length as for body(). Frictionless. approach_at() is
    /// refused: the force depends on which springs are attached.
    #[staticmethod]
    #[pyo3(signature = (profile, e_star, work, springs = 2000, half_length = None))]
    fn adhesive_body(
        py: Python<'_>,
        profile: &Profile,
        e_star: f64,
        work: f64,
        springs: usize,
        half_length: Option<f64>,
    ) -> PyResult<Self> {
        let half = half_line(profile, half_length)?;
        let law = dynamics::AdhesiveSprings::body(&profile.inner, e_star, work, springs, half)
            .map_err(|e| law_err(py, None, e))?;
        Ok(Self::new(Box::new(law), None))
    }

    /// adhesive_bem3d(heights, e_star, work, size=None, mask=None, periodic=False, tolerance=None)
    ///
    /// The 3D adhesive contact of the height map (as AdhesiveContact: Pohrt & Popov's
    /// detachment criterion, the JKR limit) as a contact law: each trial one step to the
    /// trial's approach; a rollback restores the state before it. Frictionless.
    /// tolerance: the solver's (None: its default, 1e-10).
    #[staticmethod]
    #[pyo3(signature = (heights, e_star, work, size = None, mask = None, periodic = false, tolerance = None))]
    #[allow(clippy::too_many_arguments)]
    fn adhesive_bem3d(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        e_star: f64,
        work: f64,
        size: Option<(f64, f64)>,
        mask: Option<PyArrayLike2<'_, bool, AllowTypeChange>>,
        periodic: bool,
        tolerance: Option<f64>,
    ) -> PyResult<Self> {
        let grid = Grid::new(py, heights, (size, Some(periodic)), mask, e_star, false)?;
        let (h, mask, frame) = (grid.heights, grid.mask, grid.frame);
        let tolerance = tolerance.unwrap_or(bem3d::SolverOptions::default().tolerance);
        let law: Box<dyn Law> = frame.solve(py, || -> bem3d::Result<Box<dyn Law>> {
            let ((ny, nx), (lx, ly)) = (frame.shape, frame.size);
            let wrap = |e: DynamicsError| match e {
                DynamicsError::Bem(e) => e,
                other => bem3d::BemError::InvalidInput(other.to_string()),
            };
            Ok(if frame.periodic {
                let op = bem3d::PeriodicHalfSpace::try_new(nx, ny, lx, ly, e_star)?;
                Box::new(
                    dynamics::AdhesiveBem3d::new(op, &h, mask.as_deref(), work, tolerance)
                        .map_err(wrap)?,
                )
            } else {
                let op = bem3d::NonPeriodicHalfSpace::try_new(nx, ny, lx, ly, e_star)?;
                Box::new(
                    dynamics::AdhesiveBem3d::new(op, &h, mask.as_deref(), work, tolerance)
                        .map_err(wrap)?,
                )
            })
        })?;
        Ok(Self::new(law, Some(frame)))
    }

    /// slip_bem3d(heights, normal_force, g_star, mu, size=None, e_star=1.0, tolerance=None)
    ///
    /// The 3D partial slip of the height map on the free half-space as a tangential
    /// contact law: the normal contact solved once at `normal_force` and held (its
    /// approach: `approach_at(normal_force)`, the only normal motion a trial takes), each
    /// trial the partial slip under the trial's tangential displacement (Coulomb's `mu`
    /// cell by cell; the contact moduli E* and G* of one elastic body under a rigid one,
    /// G* / E* in [2/3, 1]); a rollback restores the slip before it. tolerance: the
    /// solves' (None: the solver's default, 1e-10).
    #[staticmethod]
    #[pyo3(signature = (heights, normal_force, g_star, mu, size = None, e_star = 1.0, tolerance = None))]
    #[allow(clippy::too_many_arguments)]
    fn slip_bem3d(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        normal_force: f64,
        g_star: f64,
        mu: f64,
        size: Option<(f64, f64)>,
        e_star: f64,
        tolerance: Option<f64>,
    ) -> PyResult<Self> {
        Self::free_3d(
            py,
            heights,
            size,
            e_star,
            tolerance,
            |h, n, l, tolerance| {
                dynamics::SlipBem3d::new(h, n, l, (e_star, g_star), mu, normal_force, tolerance)
            },
        )
    }

    /// oblique_bem3d(heights, g_star, mu, size=None, e_star=1.0, tolerance=None)
    ///
    /// The 3D contact of the height map on the free half-space with both motions free:
    /// each trial solves the normal contact at its approach (from first contact of the
    /// highest cell), then the partial slip under that pressure at its tangential
    /// displacement (Coulomb's `mu` cell by cell, the slip carried from step to step, a
    /// cell entering contact sticking where it is; E* and G* of one elastic body under a
    /// rigid one, G* / E* in [2/3, 1]). It starts apart; a contact that forms again
    /// after separating is a first contact again (no traction, its origin the
    /// tangential displacement of that moment). tolerance: the solves'
    /// (None: the solver's default, 1e-10).
    #[staticmethod]
    #[pyo3(signature = (heights, g_star, mu, size = None, e_star = 1.0, tolerance = None))]
    fn oblique_bem3d(
        py: Python<'_>,
        heights: &Bound<'_, PyAny>,
        g_star: f64,
        mu: f64,
        size: Option<(f64, f64)>,
        e_star: f64,
        tolerance: Option<f64>,
    ) -> PyResult<Self> {
        Self::free_3d(
            py,
            heights,
            size,
            e_star,
            tolerance,
            |h, n, l, tolerance| {
                dynamics::ObliqueBem3d::new(h, n, l, (e_star, g_star), mu, tolerance)
            },
        )
    }

    /// trial(normal, tangential=0.0, dt=1.0) -> LawForces
    ///
    /// The forces at the step's end motion (approach `normal`, displacement
    /// `tangential`) after `dt` from the last accepted state; held until commit() or
    /// rollback() (another trial replaces it). Releases the GIL.
    #[pyo3(signature = (normal, tangential = 0.0, dt = 1.0))]
    fn trial(&self, py: Python<'_>, normal: f64, tangential: f64, dt: f64) -> PyResult<LawForces> {
        let motion = Motion {
            normal,
            tangential,
            dt,
        };
        let out = py.detach(|| self.law().trial(motion));
        out.map(|forces| LawForces { forces })
            .map_err(|e| law_err(py, self.frame.as_ref(), e))
    }

    /// Accepts the last trial as the new state (ValueError if none is held).
    fn commit(&self, py: Python<'_>) -> PyResult<()> {
        self.law()
            .commit()
            .map_err(|e| law_err(py, self.frame.as_ref(), e))
    }

    /// Discards the last trial: the state is the last accepted one.
    fn rollback(&self) {
        self.law().rollback()
    }

    /// The forces of the last accepted state.
    #[getter]
    fn committed(&self) -> LawForces {
        LawForces {
            forces: self.law().committed(),
        }
    }

    /// approach_at(force) -> float: the approach carrying the normal force with the
    /// history as accepted (a query: the state does not change).
    fn approach_at(&self, py: Python<'_>, force: f64) -> PyResult<f64> {
        let out = py.detach(|| self.law().approach_at(force));
        out.map_err(|e| law_err(py, self.frame.as_ref(), e))
    }

    fn __repr__(&self) -> String {
        format!("ContactLaw({})", self.law().describe())
    }
}
