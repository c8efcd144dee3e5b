//! `rough_sphere`: Section 9 says MRD "is also applicable to combined profiles (e.g., a
//! rough parabolic indenter)". This output presses a sphere of radius R with self-affine
//! roughness of rms height h superposed on the free half-space, in 3D and by MRD, for a
//! ladder of roughness amplitudes from the smooth sphere (h = 0: Hertz on both sides) to
//! roughness-dominated contact, and reports where MRD's force-approach, stiffness and
//! apparent-radius curves stay within 5 % of 3D.
//!
//! - Roughness: nested self-affine surfaces (C2D ~ q^(-2H-2), modes |k| <= `bandwidth`
//!   in units of 2 pi / side) on a square of side `side` x a_H, a_H the Hertz radius at
//!   the largest load F_H = 4/3 E* R^(1/2) d_H^(3/2); each realisation scaled to rms
//!   height h over the square. h comes from Greenwood and Tripp's alpha = h R / a_H^2
//!   (their sigma is the summit-height rms; the rms height is used here).
//! - 3D: heights -r^2 / (2R) + roughness on `grid`^2 cells, force controlled at `loads`
//!   forces log-spaced from 1e-2 F_H to F_H, warm-started; the approach d of the mean
//!   sphere (from the apex of the smooth sphere: d = approach from first contact - the
//!   highest point), the tangent stiffness k = dF/dd, and the apparent contact radius.
//! - MRD: springs E* dx on [-side/2, side/2] x a_H with the gap of the rule of Hess for
//!   the sphere, x^2 / R (Eq. 11), minus a rough line of the same spectrum mapped by
//!   C1D = lambda q C2D (Eq. 76; same scale factor as the surface), at the same forces.
//! - Apparent radius: a = sqrt(5/2 <r^2>_p) in 3D and sqrt(5 <x^2>_q) in MRD, the
//!   second moments of the pressure and of the spring forces; both are exactly the
//!   Hertz radius for the smooth sphere (p ~ sqrt(a^2 - r^2), q ~ a^2 - x^2) and do not
//!   jump with isolated far contacts. The outermost contact radius is reported too.

mod kind;
mod report;
mod runs;

use crate::experiment::lambda::LambdaSpec;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughSphere {
    /// Sphere radius R.
    radius: f64,
    /// Smooth-sphere approach at the largest load; a_H = sqrt(R d_H).
    hertz_depth: f64,
    /// Hurst exponent H of the self-affine spectrum, in [0, 1].
    hurst: f64,
    /// Greenwood-Tripp alpha = h R / a_H^2 per case; 0 is the smooth sphere.
    alpha: Vec<f64>,
    /// Side of the square (3D map and MRD row) in units of a_H.
    #[serde(default = "six")]
    side: f64,
    /// Cells per side of the 3D grid.
    grid: usize,
    /// Roughness modes |k| <= bandwidth (units of 2 pi / side).
    bandwidth: usize,
    /// Rough surfaces solved in 3D (independent realisations of the spectrum).
    realisations_3d: u64,
    /// MRD rough lines (independent realisations, C1D = lambda q C2D) behind each MRD
    /// curve.
    realisations_1d: u64,
    /// MRD springs per 3D cell along x.
    #[serde(default = "crate::experiment::rough_sphere::default_points_1d_factor")]
    points_1d_factor: usize,
    /// Forces, from 1e-2 F_H to F_H.
    #[serde(default = "crate::checks::default_count::<10>")]
    loads: usize,
    /// lambda of Eq. 76, one MRD curve per entry: a number, "pi" (Eq. 73), "cut",
    /// "calibrated" (the shipped lambda(H) table) or a CSV table's path; default ["pi"].
    #[serde(default = "crate::experiment::lambda::default_lambdas")]
    lambda: Vec<LambdaSpec>,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "crate::checks::default_tolerance")]
    tolerance: f64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
}

fn six() -> f64 {
    6.0
}

/// MRD within this of 3D counts as agreement (the 5 %).
const AGREEMENT: f64 = 0.05;

impl RoughSphere {
    fn a_hertz(&self) -> f64 {
        (self.radius * self.hertz_depth).sqrt()
    }
    fn side_length(&self) -> f64 {
        self.side * self.a_hertz()
    }
    fn forces(&self) -> Vec<f64> {
        let f_h = mrd::reference::hertz::force(1.0, self.radius, self.hertz_depth);
        mrd::friction::log_space(1e-2 * f_h, f_h, self.loads)
    }
    fn geometry(&self) -> crate::experiment::rough_sphere::RoughSphereGeometry {
        crate::experiment::rough_sphere::RoughSphereGeometry {
            radius: self.radius,
            hurst: self.hurst,
            side: self.side_length(),
            grid: self.grid,
            bandwidth: self.bandwidth,
            seed: self.seed,
        }
    }
    fn rms_height(&self, alpha: f64) -> f64 {
        alpha * self.a_hertz().powi(2) / self.radius
    }
    fn realisations(&self, alpha: f64, n: u64) -> u64 {
        // The smooth sphere is deterministic: one realisation.
        if alpha == 0.0 {
            1
        } else {
            n
        }
    }
}
