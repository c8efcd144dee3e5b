//! `rough_slip_3d`: partial slip of a rough sphere and of a rough flat punch in 3D
//! against MRD (Sections 6-7 on rough surfaces; Section 9's "rough parabolic indenter").
//!
//! A sphere of radius R, or a flat punch of radius a, with self-affine roughness of rms
//! height h ([`crate::experiment::rough_sphere`]; the punch is the sphere with R
//! infinite, cut to the disc r < a) is held at the normal force F_N and loaded by a
//! tangential force Q along x, on both sides:
//!
//! - 3D, on the free half-space: the normal contact at F_N (force controlled), then
//!   partial slip under Coulomb's law with Cerruti's operator under the held pressure
//!   ([`bem3d::tangential::PartialSlip`] with [`bem3d::tangential::CerrutiFree`],
//!   traction along x, q_y = 0; the normal-tangential coupling vanishes at nu = 0.5 and
//!   is neglected otherwise): the absolute shift of the body at the `fractions` of
//!   mu F_N, the stick fraction, the energy per cycle of a force oscillating with each
//!   of the `amplitudes` (a fresh contact ramped to the amplitude, then one full cycle:
//!   Masing's steady loop), and the stick stiffness k_t (the same solver with the
//!   friction bound lifted) over the normal one k_n = dF/dd.
//! - MRD: the body's 1D profile (x^2 / R for the sphere, flat on |x| < a for the punch,
//!   the rule of Hess, Eq. 11) plus a rough line of C1D = lambda q C2D (Eq. 76), on
//!   springs E* dx and G* dx: the shift u(Q) = mu (E*/G*) [d(F_N) - d(F_N - Q/mu)] and
//!   Masing's energy ([`crate::experiment::tangential_map`]), exact for the springs;
//!   k_t / k_n = G* / E*.
//! - The same law applied to each 3D surface's own normal curve ("law on the 3D normal
//!   curve"): it separates the error of MRD's tangential law from that of its normal
//!   curve (lambda's subject).
//!
//! Roughness is given as h over d_0, the smooth body's approach at F_N (Hertz's
//! (3 F_N / (4 E* R^(1/2)))^(2/3), the punch's F_N / (2 a E*)); the shifts are reported
//! over mu d_0, the energies over mu^2 F_N d_0. The cells ladder samples the same
//! surfaces on finer grids (nested synthesis).

mod figures;
mod kind;
mod quantity;
mod report;
mod runs;

use crate::experiment::lambda::LambdaSpec;
use crate::experiment::rough_body::Body;
use crate::experiment::rough_sphere::RoughSphereGeometry;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughSlip3d {
    /// Sphere radius R [length]; or
    radius: Option<f64>,
    /// the radius a of a flat punch [length] (give one of the two).
    punch_radius: Option<f64>,
    /// Normal force held, F_N [force].
    force: f64,
    /// Coulomb friction coefficient.
    mu: f64,
    /// Poisson's ratios of the substrate, each in [0, 0.5] (E* fixed).
    #[serde(default = "half")]
    poisson: Vec<f64>,
    /// Hurst exponents of the roughness, each in [0, 1].
    hurst: Vec<f64>,
    /// rms heights over d_0 (module docs), each > 0; the smooth body is always run.
    roughness: Vec<f64>,
    /// Side of the square map and of the MRD row [length].
    side: f64,
    /// Roughness modes |k| <= bandwidth (units of 2 pi / side).
    bandwidth: usize,
    /// Cells per side of the 3D grids, coarse to fine (a refinement ladder).
    cells: Vec<usize>,
    /// Rough surfaces solved in 3D (independent realisations of the spectrum).
    realisations_3d: u64,
    /// MRD rough lines (independent realisations, C1D = lambda q C2D) behind each MRD
    /// curve.
    realisations_1d: u64,
    /// MRD springs per cell of the finest 3D grid.
    #[serde(default = "crate::experiment::rough_sphere::default_points_1d_factor")]
    points_1d_factor: usize,
    /// Tangential forces of the monotonic loading over mu F_N, increasing, in [1e-6, 1).
    fractions: Vec<f64>,
    /// Force amplitudes of the cycles over mu F_N, in [1e-6, 1).
    amplitudes: Vec<f64>,
    /// Force steps per half cycle.
    #[serde(default = "crate::checks::default_count::<8>")]
    steps: usize,
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

fn half() -> Vec<f64> {
    vec![0.5]
}

impl RoughSlip3d {
    /// The body (validation checks that exactly one radius is given).
    fn body(&self) -> Body {
        Body::of(self.radius, self.punch_radius)
    }

    /// The smooth body's approach at F_N: Hertz's, or the punch's F_N / (2 a E*).
    fn smooth_approach(&self, e_star: f64) -> f64 {
        match self.body() {
            Body::Sphere(r) => (0.75 * self.force / (e_star * r.sqrt())).powf(2.0 / 3.0),
            Body::Punch(a) => self.force / (2.0 * a * e_star),
        }
    }

    /// The smooth body's contact radius at F_N.
    fn contact_radius(&self, e_star: f64) -> f64 {
        match self.body() {
            Body::Sphere(r) => (r * self.smooth_approach(e_star)).sqrt(),
            Body::Punch(a) => a,
        }
    }

    fn geometry(&self, hurst: f64, grid: usize) -> RoughSphereGeometry {
        RoughSphereGeometry {
            radius: self.body().curvature(),
            hurst,
            side: self.side,
            grid,
            bandwidth: self.bandwidth,
            seed: self.seed,
        }
    }

    fn springs(&self) -> usize {
        self.points_1d_factor * self.cells.last().copied().unwrap_or(0)
    }

    /// The cases: (hurst, rms height over d_0), the smooth body (0, 0) first.
    fn cases(&self) -> Vec<(f64, f64)> {
        crate::experiment::rough_body::cases(&self.hurst, &self.roughness)
    }

    /// Realisations of a case on one side: the smooth body is deterministic.
    fn realisations(&self, roughness: f64, n: u64) -> u64 {
        crate::experiment::rough_body::realisations(roughness, n)
    }

    fn body_name(&self) -> String {
        match self.body() {
            Body::Sphere(r) => format!("sphere of radius {r}"),
            Body::Punch(a) => format!("flat punch of radius {a}"),
        }
    }
}
