//! `rough_adhesion_3d`: adhesion of rough spheres and rough flat punches in 3D against
//! MRD (Section 5 on rough surfaces; the review's "adhesion maps").
//!
//! A sphere of radius R, or a flat punch of radius a, with self-affine roughness of rms
//! height h ([`crate::experiment::rough_sphere`]; the punch is the sphere with R
//! infinite, cut to the disc r < a) is pressed to the approach `depth_max` of the mean
//! body and pulled back until it separates, in zero-range (JKR-limit) adhesion with
//! work of adhesion w, on both sides:
//!
//! - 3D: `bem3d::adhesion` on the free half-space (Pohrt & Popov's mesh-dependent
//!   detachment criterion, the 3D counterpart of Eq. 33), on a ladder of grids that
//!   sample the same surfaces (nested synthesis).
//! - MRD: the body's 1D profile (x^2 / R for the sphere, flat on |x| < a for the punch,
//!   Eq. 11) plus a rough line of C1D = lambda q C2D (Eq. 76), its springs detaching by
//!   the rule of Hess with, as the radius of Eq. 33, either the contact's outer radius
//!   or the half-length of each spring's cluster ([`mrd::adhesive_row`], which states
//!   why these two rules for a rough line).
//!
//! Both load without adhesion at a distance (cells and springs join on touching) along
//! the same approach steps of the mean body and unload until the body separates.
//! Per case: the pull-off force under force control (the smallest force of the
//! approach-controlled unloading, as for JKR's sphere), over the smooth body's closed
//! form (JKR's 3/2 pi R w; Kendall's sqrt(8 pi a^3 E* w), Eq. 34); the adhesion
//! coefficient (pull-off over the force at `depth_max`); the energy lost in the cycle
//! (the loop's area). Roughness is given as h over the body's adhesion length: JKR's
//! (pi^2 w^2 R / E*^2)^(1/3) for the sphere, the punch's critical opening
//! sqrt(2 pi a w / E*) (Eq. 33 at its rim); each case also states the rms slope and a
//! Johnson-type parameter sqrt(w / (2 pi U)), U the elastic energy per area that
//! flattens the roughness (for one sinusoid this is Johnson's alpha; Ciavarella & Papangelo's
//! generalised Johnson parameter for multiscale roughness is of this kind).

mod cycles;
mod kind;
mod report;

use crate::experiment::lambda::LambdaSpec;
use crate::experiment::rough_body::Body;
use crate::experiment::rough_sphere::RoughSphereGeometry;
use serde::Deserialize;
use std::f64::consts::PI;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughAdhesion3d {
    /// Sphere radius R [length]; or
    radius: Option<f64>,
    /// the radius a of a flat punch [length] (give one of the two).
    punch_radius: Option<f64>,
    /// Work of adhesion w [energy / length^2].
    work: f64,
    /// Approach of the mean body at the end of loading, from its apex [length].
    depth_max: f64,
    /// Hurst exponents of the roughness.
    hurst: Vec<f64>,
    /// rms heights over the body's adhesion length (module docs), each > 0; the smooth
    /// body is always run as the reference.
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
    /// Approach steps from the smooth body's first contact to `depth_max`; the loading
    /// starts at each body's own first contact and the unloading goes down by the same
    /// step until the body separates.
    #[serde(default = "crate::checks::default_count::<60>")]
    steps: usize,
    /// lambda of Eq. 76, one MRD curve per entry: a number, "pi" (Eq. 73), "cut",
    /// "calibrated" (the shipped lambda(H) table) or a CSV table's path; default ["pi"].
    #[serde(default = "crate::experiment::lambda::default_lambdas")]
    lambda: Vec<LambdaSpec>,
    /// The radii of Eq. 33 that MRD is run with: "outer", "cluster" (both by default).
    #[serde(default = "both_rules")]
    mrd_rule: Vec<String>,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "crate::checks::default_tolerance")]
    tolerance: f64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
}

/// The radius of Eq. 33 for a rough line ([`mrd::adhesive_row::EdgeRadius`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    Outer,
    Cluster,
}

impl Rule {
    /// The rule a scene names, if any.
    fn parse(name: &str) -> Option<Self> {
        match name {
            "outer" => Some(Rule::Outer),
            "cluster" => Some(Rule::Cluster),
            _ => None,
        }
    }
    fn edge(self) -> mrd::adhesive_row::EdgeRadius {
        match self {
            Rule::Outer => mrd::adhesive_row::EdgeRadius::Outer,
            Rule::Cluster => mrd::adhesive_row::EdgeRadius::Cluster,
        }
    }
    /// The code of the tables' `mrd_rule` column (0 is 3D).
    fn code(self) -> f64 {
        match self {
            Rule::Outer => 1.0,
            Rule::Cluster => 2.0,
        }
    }
    fn name(self) -> &'static str {
        match self {
            Rule::Outer => "outer radius",
            Rule::Cluster => "cluster half-length",
        }
    }
}

/// One MRD variant: a rule and lambda per Hurst exponent (in the order of `hurst`).
#[derive(Debug, Clone)]
pub struct Variant {
    rule: Rule,
    lambda: Vec<f64>,
}

fn both_rules() -> Vec<String> {
    vec!["outer".into(), "cluster".into()]
}

impl RoughAdhesion3d {
    /// The body (validation checks that exactly one radius is given).
    fn body(&self) -> Body {
        Body::of(self.radius, self.punch_radius)
    }

    /// The body's adhesion length: JKR's (pi^2 w^2 R / E*^2)^(1/3), the punch's
    /// critical opening sqrt(2 pi a w / E*).
    fn adhesion_length(&self, e_star: f64) -> f64 {
        let w = self.work;
        match self.body() {
            Body::Sphere(r) => (PI * PI * w * w * r / (e_star * e_star)).cbrt(),
            Body::Punch(a) => (2.0 * PI * a * w / e_star).sqrt(),
        }
    }

    /// The smooth body's pull-off under force control: 3/2 pi R w (JKR),
    /// sqrt(8 pi a^3 E* w) (Kendall, Eq. 34).
    fn smooth_pull_off(&self, e_star: f64) -> f64 {
        match self.body() {
            Body::Sphere(r) => 1.5 * PI * r * self.work,
            Body::Punch(a) => (8.0 * PI * a.powi(3) * e_star * self.work).sqrt(),
        }
    }

    fn step(&self) -> f64 {
        self.depth_max / self.steps as f64
    }

    fn geometry(&self, hurst: f64, grid: usize) -> RoughSphereGeometry {
        RoughSphereGeometry {
            // The punch: no curvature.
            radius: self.body().curvature(),
            hurst,
            side: self.side,
            grid,
            bandwidth: self.bandwidth,
            seed: self.seed,
        }
    }

    /// The MRD rules of the scene (validation checks every name).
    fn rules(&self) -> Vec<Rule> {
        self.mrd_rule
            .iter()
            .filter_map(|r| Rule::parse(r))
            .collect()
    }

    fn springs(&self) -> usize {
        self.points_1d_factor * self.cells.last().copied().unwrap_or(0)
    }

    /// The cases: (hurst, rms height over the adhesion length), the smooth body (0, 0) first.
    fn cases(&self) -> Vec<(f64, f64)> {
        crate::experiment::rough_body::cases(&self.hurst, &self.roughness)
    }
}

/// Spectral moments of the band of `geometry` (disc of modes 1 <= |k| <= bandwidth,
/// weighted by C2D as the synthesis weights them): (<q>, <q^2>), so that a surface of
/// rms height h has rms slope h sqrt(<q^2>) and costs E* h^2 <q> / 4 per area to
/// flatten on the half-space.
fn band_moments(geometry: &RoughSphereGeometry) -> crate::error::Result<(f64, f64)> {
    let sa = geometry.spectrum()?;
    let b = geometry.bandwidth as i64;
    let (mut c, mut cq, mut cq2) = (0.0, 0.0, 0.0);
    for i in -b..=b {
        for j in -b..=b {
            let k2 = i * i + j * j;
            if k2 == 0 || k2 > b * b {
                continue;
            }
            let q = 2.0 * PI / geometry.side * (k2 as f64).sqrt();
            let w = sa.c2d(q);
            c += w;
            cq += w * q;
            cq2 += w * q * q;
        }
    }
    if c.is_nan() || c <= 0.0 {
        return Err(crate::error::CompareError::Scene(
            "rough_adhesion_3d: the roughness band is empty".into(),
        ));
    }
    Ok((cq / c, cq2 / c))
}
