//! `static_friction_3d`: Eq. (93) computed in 3D. Section 10.2 closes with the claim
//! that the MRD law xi(f) of Eqs. (89)-(92) holds for three-dimensional systems "provided
//! the length of the system is replaced by L = 2 sqrt(A) / sqrt(pi)". This output puts
//! the 3D answer next to MRD's:
//!
//! - 3D: rigid self-affine surfaces with the band of Eq. (85) (no lower cut-off but the
//!   system size, upper cut-off 1/10 of the Nyquist wavenumber: `cells` = 20 cells per
//!   shortest wavelength) pressed on the elastic half-space, periodic square (A = L^2)
//!   or free half-space disc (the punch of the Hurst sweep, A = pi L^2 / 4), force
//!   controlled. xi_3D = rms |grad z| over the cells in contact / rms |grad z| over A
//!   (Eqs. 86, 88, 89 with forward differences in x and y: the same stencil as the 1D
//!   lines, Eq. 86), against f = sqrt(pi) F / (2 E* h sqrt(A)) (Eq. 93), h the rms
//!   height over A of each realisation; each realisation's forces are set to land on
//!   the f grid.
//! - MRD: lines of length L1 = 2 sqrt(A / pi) with C1D = lambda q C2D (Eq. 76) of the
//!   same spectrum and the same shortest wavelength and sampling, pressed with the same
//!   force F the 3D system carries at f (h the 3D ensemble's mean rms height). xi as a
//!   function of a line's own f = F/(E* h1 L1) does not depend on lambda (the line
//!   scales as sqrt(lambda): Section 10.2's scaling); lambda shifts the MRD curve along
//!   f by h1 / h = sqrt(lambda / pi).
//!
//! Both curves get the fit xi = a + b ln f (Eq. 91) with bootstrap intervals over
//! realisations, and an optional grid refinement of the 3D side at one point: the same
//! surfaces (nested synthesis) sampled with twice the cells per shortest wavelength.

mod kind;
mod report;
pub mod runs;

use crate::experiment::lambda::LambdaSpec;
use serde::Deserialize;
use std::f64::consts::PI;

/// The apparent contact area of the 3D system.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Geometry {
    /// The periodic half-space: A = L^2, so L1 = 2 L / sqrt(pi).
    Periodic,
    /// The disc of diameter L inscribed in the map, on the free half-space: L1 = L.
    Disc,
}

impl Geometry {
    fn name(self) -> &'static str {
        match self {
            Geometry::Periodic => "periodic square",
            Geometry::Disc => "disc",
        }
    }
    /// Code in the CSV tables.
    fn code(self) -> f64 {
        match self {
            Geometry::Periodic => 0.0,
            Geometry::Disc => 1.0,
        }
    }
    /// Apparent area A for the map side L = 1.
    fn area(self) -> f64 {
        match self {
            Geometry::Periodic => 1.0,
            Geometry::Disc => PI / 4.0,
        }
    }
    /// MRD line length L1 = 2 sqrt(A / pi) (Eq. 93).
    fn line_length(self) -> f64 {
        2.0 * (self.area() / PI).sqrt()
    }
}

/// A grid refinement of the 3D side at one point.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Refinement {
    hurst: f64,
    geometry: Geometry,
    /// The reduced force of the check (one of the f grid's values is taken: the nearest).
    f: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StaticFriction3d {
    /// Hurst exponents, each in [0, 1] (the self-affine range of Section 10.2).
    hurst: Vec<f64>,
    /// Shortest wavelength L / bandwidth; the map side L is 1.
    bandwidth: usize,
    /// Cells per shortest wavelength; 20 is Eq. (85)'s cut-off at 1/10 of Nyquist.
    #[serde(default = "crate::checks::default_count::<20>")]
    cells: usize,
    /// The 3D geometries, "periodic" and/or "disc" (default both).
    #[serde(default = "both")]
    geometry: Vec<Geometry>,
    /// Rough surfaces solved in 3D (independent realisations of the spectrum).
    realisations_3d: u64,
    /// MRD rough lines (independent realisations, C1D = lambda q C2D) behind each MRD
    /// curve.
    realisations_1d: u64,
    /// Reduced forces f = sqrt(pi) F / (2 E* h sqrt(A)) (Eq. 93), log-spaced.
    f_min: f64,
    /// Largest dimensionless force f.
    f_max: f64,
    /// Forces, log-spaced from f_min to f_max.
    #[serde(default = "crate::checks::default_count::<12>")]
    f_points: usize,
    /// The fits of Eq. (91) use the f points whose 3D contact fraction is below this
    /// (the paper's law is one of sparse contact; xi -> 1 at complete contact).
    #[serde(default = "tenth")]
    fit_max_area: f64,
    /// lambda of Eq. (76) for the MRD lines: one curve per entry (a number, "pi", "cut",
    /// "calibrated" or a table's path); default ["pi"].
    #[serde(default = "crate::experiment::lambda::default_lambdas")]
    lambda: Vec<LambdaSpec>,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "crate::checks::default_tolerance")]
    tolerance: f64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
    /// The paper's fit xi = a + b ln f to draw at `paper_hurst` (Eq. 92: 2.9, 0.14, 0.7).
    paper: Option<[f64; 3]>,
    /// Optional: one point solved again on twice the cells, e.g. { hurst = 0.7, geometry =
    /// "periodic", f = 0.01 }.
    refine: Option<Refinement>,
}

fn both() -> Vec<Geometry> {
    vec![Geometry::Periodic, Geometry::Disc]
}
fn tenth() -> f64 {
    0.1
}

/// Bootstrap resamples of the fits.
const RESAMPLES: usize = 400;

impl StaticFriction3d {
    fn grid(&self, cells: usize) -> usize {
        cells * self.bandwidth
    }
    fn f_grid(&self) -> Vec<f64> {
        mrd::friction::log_space(self.f_min, self.f_max, self.f_points)
    }
    fn refine_index(&self, r: &Refinement) -> usize {
        let fs = self.f_grid();
        let d = |k: usize| (fs[k].ln() - r.f.ln()).abs();
        (0..fs.len())
            .min_by(|&a, &b| d(a).total_cmp(&d(b)))
            .unwrap_or(0)
    }
}
