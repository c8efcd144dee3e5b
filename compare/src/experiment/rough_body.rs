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

/// Fewest cells the coarsest grid puts on the smooth body's contact radius (the embedded
/// scenes put 15-53).
pub const MIN_CELLS_PER_CONTACT_RADIUS: f64 = 8.0;

/// The map of `side` holds the smooth body's contact of radius `a` (`which`: how the
/// study defines it) with a margin, at least 2.2 radii, and the coarsest of `cells`
/// resolves it with [`MIN_CELLS_PER_CONTACT_RADIUS`].
pub fn check_map(side: f64, a: f64, which: &str, cells: &[usize]) -> Result<()> {
    if side < 2.2 * a {
        return bad(format!(
            "side = {side} must be at least 2.2 contact radii ({which}) = {:.4e}: the contact stays inside the map",
            2.2 * a
        ));
    }
    let coarsest = cells.first().copied().unwrap_or(16);
    let per = a * coarsest as f64 / side;
    if per.is_nan() || per < MIN_CELLS_PER_CONTACT_RADIUS {
        return bad(format!(
            "side = {side} over cells = {coarsest} (the coarsest grid) puts {per:.3e} cells on the contact radius ({which}) {a:.4e}, at least {MIN_CELLS_PER_CONTACT_RADIUS} needed: give side <= {:.4e} or more cells",
            a * coarsest as f64 / MIN_CELLS_PER_CONTACT_RADIUS
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_map_must_hold_and_resolve_the_contact() {
        // rough-slip-3d-ci: a = 0.0316 on 0.13 with 64 cells, 15.6 cells a radius.
        assert!(check_map(0.13, 0.0316, "smooth", &[64, 128]).is_ok());
        let small = check_map(0.06, 0.0316, "smooth", &[64]).unwrap_err();
        assert!(
            small.to_string().contains("at least 2.2 contact radii"),
            "{small}"
        );
        // The coarsest grid decides: 8 cells a radius at side = a * 64 / 8.
        assert!(check_map(0.0316 * 8.0, 0.0316, "smooth", &[64, 2048]).is_ok());
        let coarse = check_map(0.0316 * 8.01, 0.0316, "smooth", &[64, 2048]).unwrap_err();
        assert!(
            coarse
                .to_string()
                .contains("cells = 64 (the coarsest grid)"),
            "{coarse}"
        );
        assert!(check_map(1.0, f64::NAN, "smooth", &[64]).is_err());
    }
}
