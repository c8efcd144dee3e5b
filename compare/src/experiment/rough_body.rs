//! A rough body on the free half-space, as the 3D studies of rough spheres and rough
//! flat punches give it: the body from the scene's `radius` or `punch_radius`, its
//! cases (the smooth body first, then each Hurst exponent with each roughness), the
//! realisations of a case, and the checks of those keys and of the grid ladder. The
//! surfaces themselves are [`super::rough_sphere::RoughSphereGeometry`] (the punch is
//! the sphere with R infinite, cut to its disc).

use crate::checks::{bad, count_in, positive};
use crate::error::Result;

/// The indenter under the roughness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Body {
    Sphere(f64),
    Punch(f64),
}

impl Body {
    /// The body the scene names (validation checks that exactly one radius is given:
    /// [`Body::check`]).
    pub fn of(radius: Option<f64>, punch_radius: Option<f64>) -> Self {
        match (radius, punch_radius) {
            (_, Some(a)) => Body::Punch(a),
            (r, None) => Body::Sphere(r.unwrap_or(f64::NAN)),
        }
    }

    /// The radius of the body the scene names, if it names exactly one.
    pub fn check(radius: Option<f64>, punch_radius: Option<f64>) -> Result<f64> {
        match (radius, punch_radius) {
            (Some(r), None) => Ok(r),
            (None, Some(a)) => Ok(a),
            _ => bad("give radius (a sphere) or punch_radius (a flat punch), not both"),
        }
    }

    /// The distance from the axis within which the body can touch.
    pub fn reach(self) -> f64 {
        match self {
            Body::Sphere(_) => f64::INFINITY,
            Body::Punch(a) => a,
        }
    }

    /// The radius of curvature of the surface: R, or infinite for the punch.
    pub fn curvature(self) -> f64 {
        match self {
            Body::Sphere(r) => r,
            Body::Punch(_) => f64::INFINITY,
        }
    }
}

/// The cases: (hurst, roughness), the smooth body (0, 0) first.
pub fn cases(hurst: &[f64], roughness: &[f64]) -> Vec<(f64, f64)> {
    let mut c = vec![(0.0, 0.0)];
    for &h in hurst {
        c.extend(roughness.iter().map(|&r| (h, r)));
    }
    c
}

/// Realisations of a case on one side: the smooth body is deterministic.
pub fn realisations(roughness: f64, n: u64) -> u64 {
    if roughness == 0.0 {
        1
    } else {
        n
    }
}

/// `hurst` in [0, 1] and `roughness` (rms heights over `unit`) in (0, 100], each at
/// least one; `cells` an increasing ladder of grids that resolve `bandwidth`.
pub fn check_cases(
    hurst: &[f64],
    roughness: &[f64],
    unit: &str,
    cells: &[usize],
    bandwidth: usize,
) -> Result<()> {
    if hurst.is_empty() || hurst.iter().any(|h| !(0.0..=1.0).contains(h)) {
        return bad(format!(
            "hurst = {hurst:?}: give at least one Hurst exponent in [0, 1]"
        ));
    }
    if roughness.is_empty() || roughness.iter().any(|r| !(positive(*r) && *r <= 100.0)) {
        return bad(format!(
            "roughness = {roughness:?}: give rms heights over {unit} in (0, 100] (the smooth body is always run)"
        ));
    }
    if cells.is_empty() || cells.windows(2).any(|w| w[1] <= w[0]) {
        return bad(format!(
            "cells = {cells:?}: give increasing grid sizes (a refinement ladder)"
        ));
    }
    for &n in cells {
        count_in("cells", n as u64, 16..=2048)?;
        count_in("bandwidth", bandwidth as u64, 1..=(n as u64 - 1) / 2)?;
    }
    Ok(())
}
