//! The 1D method for axisymmetric contacts: profiles and the rule of Hess (Eqs. 11-15),
//! normal contact (Eqs. 20, 24-25), Abel pressure (Eq. 26), adhesion (Eqs. 33-37),
//! Cattaneo-Mindlin (Eqs. 41-51) and frictional damping (Section 7).

use crate::errors::{finite, finite_dict, mrd_err, value_error};
use mrd::adhesion::{AdhesiveContact, Control};
use mrd::normal::{AxisymmetricContact, ContactState};
use mrd::profile::{Profile as P, Shape, TabulatedProfile};
use mrd::tangential::TangentialContact;
use numpy::{AllowTypeChange, PyArrayDyn, PyArrayLike1, PyArrayLikeDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// An axisymmetric rigid indenter z(r) (height above its tip): one shape, a sum of
/// shapes (`a + b`), optionally held at a rim radius (a punch with a sharp edge).
/// Build with the static methods: sphere, cone, power_law, flattened_sphere,
/// flat_punch, tabulated.
#[pyclass(module = "mrdw._mrdw", frozen)]
#[derive(Clone)]
pub struct Profile {
    pub inner: P,
}

fn shape(py: Python<'_>, s: mrd::Result<Shape>, rim: Option<f64>) -> PyResult<Profile> {
    let s = s.map_err(|e| mrd_err(py, e))?;
    P::new(vec![s], rim)
        .map(|inner| Profile { inner })
        .map_err(|e| mrd_err(py, e))
}

fn map<'py>(
    py: Python<'py>,
    x: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    name: &str,
    f: impl Fn(f64) -> mrd::Result<f64>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let a = x.as_array();
    crate::errors::no_nan(name, a.iter())?;
    let mut out = a.to_owned();
    for v in out.iter_mut() {
        *v = finite("value", f(*v).map_err(|e| mrd_err(py, e))?)?;
    }
    Ok(PyArrayDyn::from_owned_array(py, out))
}

#[pymethods]
impl Profile {
    /// Sphere of radius R in the paraboloid approximation, z = r^2 / (2 R).
    #[staticmethod]
    #[pyo3(signature = (radius, rim = None))]
    fn sphere(py: Python<'_>, radius: f64, rim: Option<f64>) -> PyResult<Self> {
        shape(py, Shape::paraboloid(radius), rim)
    }
    /// Cone z = r tan(theta) (tan_theta: the slope).
    #[staticmethod]
    #[pyo3(signature = (tan_theta, rim = None))]
    fn cone(py: Python<'_>, tan_theta: f64, rim: Option<f64>) -> PyResult<Self> {
        shape(py, Shape::cone(tan_theta), rim)
    }
    /// Power law z = c r^n for any real n in (0, 1000] (Eq. 12).
    #[staticmethod]
    #[pyo3(signature = (c, n, rim = None))]
    fn power_law(py: Python<'_>, c: f64, n: f64, rim: Option<f64>) -> PyResult<Self> {
        shape(py, Shape::power_law(c, n), rim)
    }
    /// Flattened sphere (Eq. 22): 0 for r < a0, (r^2 - a0^2) / (2 R) beyond.
    #[staticmethod]
    #[pyo3(signature = (radius, flat_radius, rim = None))]
    fn flattened_sphere(
        py: Python<'_>,
        radius: f64,
        flat_radius: f64,
        rim: Option<f64>,
    ) -> PyResult<Self> {
        shape(py, Shape::flattened_paraboloid(radius, flat_radius), rim)
    }
    /// Flat cylindrical punch of radius a (Eq. 1).
    #[staticmethod]
    fn flat_punch(py: Python<'_>, radius: f64) -> PyResult<Self> {
        P::flat_punch(radius)
            .map(|inner| Self { inner })
            .map_err(|e| mrd_err(py, e))
    }
    /// Piecewise-linear profile through (r, z): r strictly increasing from 0, z(0) = 0,
    /// z non-decreasing; defined up to r[-1].
    #[staticmethod]
    #[pyo3(signature = (r, z, rim = None))]
    fn tabulated(
        py: Python<'_>,
        r: PyArrayLike1<'_, f64, AllowTypeChange>,
        z: PyArrayLike1<'_, f64, AllowTypeChange>,
        rim: Option<f64>,
    ) -> PyResult<Self> {
        let t =
            TabulatedProfile::new(r.as_array().to_vec(), z.as_array().to_vec()).map(Shape::Table);
        shape(py, t, rim)
    }

    /// The sum of two profiles (heights add); the smaller rim, if any.
    fn __add__(&self, py: Python<'_>, other: &Profile) -> PyResult<Self> {
        let mut shapes = self.inner.shapes().to_vec();
        shapes.extend(other.inner.shapes().iter().cloned());
        let rim = match (self.inner.rim(), other.inner.rim()) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        P::new(shapes, rim)
            .map(|inner| Self { inner })
            .map_err(|e| mrd_err(py, e))
    }

    /// z(r): the 3D profile [length].
    fn z<'py>(
        &self,
        py: Python<'py>,
        r: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        map(py, r, "r", |r| Ok(self.inner.z(r)))
    }
    /// g(x): the MRD image by the rule of Hess (Eq. 11), closed forms per shape
    /// (Eqs. 13-15, 23) [length].
    fn z1d<'py>(
        &self,
        py: Python<'py>,
        x: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        map(py, x, "x", |x| Ok(self.inner.z1d(x)))
    }
    /// g(x) by tanh-sinh quadrature of Eq. (11): an independent check of z1d.
    fn z1d_numeric<'py>(
        &self,
        py: Python<'py>,
        x: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        map(py, x, "x", |x| self.inner.z1d_numeric(x))
    }
    /// Largest contact radius the profile is defined for (rim or table end; inf).
    #[getter]
    fn max_contact_radius(&self) -> f64 {
        self.inner.max_contact_radius()
    }
    fn __repr__(&self) -> String {
        format!(
            "Profile(shapes={:?}, rim={:?})",
            self.inner.shapes(),
            self.inner.rim()
        )
    }
}

/// hess_inverse(x, g, r) -> ndarray
///
/// The inverse rule of Hess: the 3D profile z(r) = (2/pi) Int_0^r g(x) / sqrt(r^2 - x^2)
/// dx whose MRD image is the piecewise-linear 1D profile through (x, g) (x strictly
/// increasing from 0), evaluated at the radii r <= x[-1].
#[pyfunction]
pub fn hess_inverse<'py>(
    py: Python<'py>,
    x: PyArrayLike1<'py, f64, AllowTypeChange>,
    g: PyArrayLike1<'py, f64, AllowTypeChange>,
    r: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let (x, g) = (x.as_array().to_vec(), g.as_array().to_vec());
    if x.len() < 2 || x.len() != g.len() {
        return Err(value_error("x and g need the same length, at least 2"));
    }
    if x[0] != 0.0
        || x.windows(2).any(|w| w[1] <= w[0] || w[1].is_nan())
        || g.iter().any(|v| !v.is_finite())
    {
        return Err(value_error(
            "x must start at 0 and increase strictly; g must be finite",
        ));
    }
    let last = x[x.len() - 1];
    let interp = |t: f64| -> f64 {
        let k = x.partition_point(|&v| v <= t).clamp(1, x.len() - 1);
        let (x0, x1) = (x[k - 1], x[k]);
        g[k - 1] + (g[k] - g[k - 1]) * (t - x0) / (x1 - x0)
    };
    map(py, r, "r", |rv| {
        if rv.abs() > last * (1.0 + 1e-12) {
            return Err(mrd::MrdError::OutOfRange {
                needed: rv.abs(),
                limit: last,
            });
        }
        mrd::hess::inverse(interp, &x[1..x.len() - 1], rv)
    })
}

fn contact(py: Python<'_>, profile: &Profile, e_star: f64) -> PyResult<AxisymmetricContact> {
    AxisymmetricContact::new(profile.inner.clone(), e_star).map_err(|e| mrd_err(py, e))
}

fn state_dict<'py>(py: Python<'py>, s: &ContactState) -> PyResult<Bound<'py, PyDict>> {
    finite_dict(
        py,
        &[
            ("depth", s.depth),
            ("radius", s.radius),
            ("force", s.force),
            ("stiffness", s.stiffness),
        ],
    )
}

fn one_of(names: [&str; 3], values: [Option<f64>; 3]) -> PyResult<(usize, f64)> {
    let given: Vec<(usize, f64)> = values
        .iter()
        .enumerate()
        .filter_map(|(i, v)| v.map(|v| (i, v)))
        .collect();
    match given[..] {
        [one] => Ok(one),
        _ => Err(value_error(format!(
            "give exactly one of {}, {} and {}",
            names[0], names[1], names[2]
        ))),
    }
}

/// normal(profile, e_star, *, depth=None, force=None, radius=None) -> dict
///
/// Frictionless normal contact by MRD, semi-analytically: depth d [length], contact
/// radius a [length], force F [stress x length^2] and stiffness dF/dd = 2 a E* (Eq. 20)
/// from exactly one of them (Eqs. 24-25: d = g(a), F = 2 E* Int_0^a (d - g(x)) dx).
#[pyfunction]
#[pyo3(signature = (profile, e_star, *, depth = None, force = None, radius = None))]
pub fn normal<'py>(
    py: Python<'py>,
    profile: &Profile,
    e_star: f64,
    depth: Option<f64>,
    force: Option<f64>,
    radius: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let c = contact(py, profile, e_star)?;
    let s = match one_of(["depth", "force", "radius"], [depth, force, radius])? {
        (0, d) => c.state_at_depth(d),
        (1, f) => c.state_at_force(f),
        (_, a) => c.state_at_reached_radius(a),
    }
    .map_err(|e| mrd_err(py, e))?;
    state_dict(py, &s)
}

/// pressure(profile, e_star, r, *, depth=None, force=None) -> ndarray
///
/// Contact pressure p(r) [stress] by the Abel transform of the 1D line load (Eq. 26),
/// at depth or force.
#[pyfunction]
#[pyo3(signature = (profile, e_star, r, *, depth = None, force = None))]
pub fn pressure<'py>(
    py: Python<'py>,
    profile: &Profile,
    e_star: f64,
    r: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    depth: Option<f64>,
    force: Option<f64>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let c = contact(py, profile, e_star)?;
    let s = match one_of(["depth", "force", "radius"], [depth, force, None])? {
        (0, d) => c.state_at_depth(d),
        (_, f) => c.state_at_force(f),
    }
    .map_err(|e| mrd_err(py, e))?;
    map(py, r, "r", |r| {
        mrd::pressure::abel_pressure(&profile.inner, e_star, s.depth, s.radius, 0.0, r)
    })
}

/// adhesion(profile, e_star, gamma, radius) -> dict(radius, depth, force)
///
/// The adhesive (JKR-type) branch by the rule of Hess at contact radius a: the boundary
/// springs stretch by the critical elongation sqrt(2 pi a gamma / E*) (Eq. 33), so
/// d = g(a) - that (Eq. 35) and F = F_Hertz-type(a) - 2 a E* times that (Eq. 36).
/// gamma: work of adhesion [energy / length^2].
#[pyfunction]
pub fn adhesion<'py>(
    py: Python<'py>,
    profile: &Profile,
    e_star: f64,
    gamma: f64,
    radius: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let a =
        AdhesiveContact::new(contact(py, profile, e_star)?, gamma).map_err(|e| mrd_err(py, e))?;
    let depth = a.depth_at_radius(radius).map_err(|e| mrd_err(py, e))?;
    let force = a.force_at_radius(radius).map_err(|e| mrd_err(py, e))?;
    finite_dict(
        py,
        &[("radius", radius), ("depth", depth), ("force", force)],
    )
}

/// pull_off(profile, e_star, gamma, *, control="force", max_radius=None) -> dict
///
/// The point where the adhesive contact separates when unloaded from contact radius
/// `max_radius` (default: the profile's rim or table end; required for unbounded
/// profiles) under force or displacement control: radius, depth, force (negative,
/// tensile). Sphere: F = -3/2 pi R gamma (force control, Eq. 34), -5/6 pi R gamma
/// (displacement control, Eq. 37).
#[pyfunction]
#[pyo3(signature = (profile, e_star, gamma, *, control = "force", max_radius = None))]
pub fn pull_off<'py>(
    py: Python<'py>,
    profile: &Profile,
    e_star: f64,
    gamma: f64,
    control: &str,
    max_radius: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let control = match control {
        "force" => Control::Force,
        "displacement" => Control::Displacement,
        other => {
            return Err(value_error(format!(
                "control = {other:?}: expected \"force\" or \"displacement\""
            )))
        }
    };
    let a_max = match max_radius {
        Some(a) => a,
        None if profile.inner.max_contact_radius().is_finite() => {
            profile.inner.max_contact_radius()
        }
        None => {
            return Err(value_error(
                "max_radius is needed for a profile without a rim or table end",
            ))
        }
    };
    let a =
        AdhesiveContact::new(contact(py, profile, e_star)?, gamma).map_err(|e| mrd_err(py, e))?;
    let p = a.pull_off(a_max, control).map_err(|e| mrd_err(py, e))?;
    finite_dict(
        py,
        &[("radius", p.radius), ("depth", p.depth), ("force", p.force)],
    )
}

/// cattaneo_mindlin(profile, e_star, g_star, mu, normal_force, tangential_force) -> dict
///
/// Tangential contact at constant normal force (Cattaneo-Mindlin, Jaeger for any
/// profile; Eqs. 41-51): stick radius c [length] and tangential displacement u_x
/// [length] under the tangential force (|F_x| <= mu F_N); also the contact radius a and
/// the displacement at full sliding. g_star: the tangential contact modulus G* (Eq. 5).
#[pyfunction]
pub fn cattaneo_mindlin<'py>(
    py: Python<'py>,
    profile: &Profile,
    e_star: f64,
    g_star: f64,
    mu: f64,
    normal_force: f64,
    tangential_force: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let t = TangentialContact::new(contact(py, profile, e_star)?, g_star, mu, normal_force)
        .map_err(|e| mrd_err(py, e))?;
    let s = t.at_force(tangential_force).map_err(|e| mrd_err(py, e))?;
    finite_dict(
        py,
        &[
            ("force", s.force),
            ("stick_radius", s.stick_radius),
            ("displacement", s.displacement),
            ("contact_radius", t.normal.radius),
            ("max_displacement", t.max_displacement()),
        ],
    )
}

/// damping(profile, e_star, g_star, mu, depth, amplitude) -> float
///
/// Energy dissipated per cycle of a small tangential oscillation of amplitude A [length]
/// at constant depth (Section 7): the continuous-foundation limit
/// W = 2 Int_0^a 4 mu E* delta(x) (A - mu beta delta(x))+ dx, delta = d - g(x),
/// beta = E* / G* (Eqs. 56-57 for any profile) [energy].
#[pyfunction]
pub fn damping(
    py: Python<'_>,
    profile: &Profile,
    e_star: f64,
    g_star: f64,
    mu: f64,
    depth: f64,
    amplitude: f64,
) -> PyResult<f64> {
    let w = mrd::oscillation::dissipation_semi_analytic(
        &profile.inner,
        e_star,
        g_star,
        mu,
        depth,
        amplitude,
    )
    .map_err(|e| mrd_err(py, e))?;
    finite("dissipated energy", w)
}
