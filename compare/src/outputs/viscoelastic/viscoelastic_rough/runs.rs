//! One realisation of each side through the load history: the rough punch in 3D on the
//! viscoelastic half-space (`bem3d::viscoelastic`) and an MRD line on viscoelastic
//! springs that separate (`mrd::viscoelastic::SpringRow`, Eq. 63), each with the
//! elastic contact set at the same approach beside it (Radok's prediction).

use super::ViscoelasticRough;
use crate::checks::MIN_CONTACT_CELLS;
use crate::error::{Context as _, Result};
use bem3d::viscoelastic::{Relaxation, TransientContact};
use bem3d::{ContactSolver, Load, NonPeriodicHalfSpace, SolverOptions};
use mrd::foundation::Foundation;
use mrd::roughness::synthesis::Grid;
use mrd::roughness::{nested, SelfAffine};
use mrd::viscoelastic::{Prony, RowLoad, SpringRow};
use std::f64::consts::TAU;

/// One time step of one realisation, in units of its own rms height h (E_inf = 1, L = 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Approach / h, from the first contact of the undeformed face.
    pub approach: f64,
    /// Contact fraction of the face (3D: cells; MRD: springs).
    pub area: f64,
    /// The elastic contact fraction at the same approach.
    pub area_elastic: f64,
    /// f = F / (E_inf h L).
    pub force: f64,
    /// The same of the elastic contact at the same approach, modulus E_inf.
    pub force_elastic: f64,
}

/// What a scene solved: the 3D realisations, and per lambda of Eq. (76) the MRD lines'.
pub struct Runs {
    pub lambdas: Vec<f64>,
    pub d3: Vec<Run>,
    pub d1: Vec<Vec<Run>>,
}

/// A realisation's history; `unconverged` steps are recorded as failures of the run.
#[derive(Debug, Clone)]
pub struct Run {
    pub points: Vec<Point>,
    pub iterations: usize,
}

fn spectrum(spec: &ViscoelasticRough) -> Result<SelfAffine> {
    // Modes |k| in 1..=B (units 2 pi / L), as the lambda study's punch.
    let q0 = TAU * (1.0 - 1e-9);
    SelfAffine::new(spec.hurst, q0, q0, TAU * (spec.bandwidth as f64 + 0.5)).ctx("spectrum")
}

/// The 3D face of realisation `r`: heights on the grid and the disc mask.
fn face(spec: &ViscoelasticRough, r: u64) -> Result<(Vec<f64>, Vec<bool>, f64)> {
    let g = spec.grid();
    let sa = spectrum(spec)?;
    let z = nested::surface(
        &|q| sa.c2d(q),
        spec.bandwidth,
        &Grid::square(g, 1.0),
        spec.seed,
        r,
    )
    .ctx("3D surface")?;
    let mask = bem3d::mask::disc(g, g, 1.0, 1.0, 0.5);
    let on: Vec<f64> = z.iter().zip(&mask).filter(|p| *p.1).map(|p| *p.0).collect();
    let mean = on.iter().sum::<f64>() / on.len() as f64;
    let rms = (on.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / on.len() as f64).sqrt();
    Ok((z, mask, rms))
}

/// Realisation `r` in 3D: steps through the history (force or approach controlled),
/// each beside the elastic solve at the same approach (its contact set does not depend
/// on the modulus).
pub fn run_3d(spec: &ViscoelasticRough, modulus: &Relaxation, r: u64) -> Result<Run> {
    let g = spec.grid();
    let (z, mask, h) = face(spec, r)?;
    let domain = mask.iter().filter(|&&m| m).count() as f64;
    let op = || NonPeriodicHalfSpace::new(g, g, 1.0, 1.0, 1.0);
    let mut ve = TransientContact::new(op(), &z, Some(mask.clone()), modulus.clone())
        .ctx("3D viscoelastic set-up")?;
    let mut el = ContactSolver::new(op(), &z, Some(mask)).ctx("3D elastic set-up")?;
    let opts = SolverOptions::new(spec.tolerance, 20 * g + 2000);
    let mut run = Run {
        points: Vec::new(),
        iterations: 0,
    };
    let mut warm: Option<bem3d::Solution> = None;
    let mut most = 0;
    for (dt, v) in spec.history() {
        let load = if spec.by_approach() {
            Load::Approach(v * h)
        } else {
            Load::Force(v * h * modulus.relaxed)
        };
        let s = ve.step(dt, load, &opts).ctx("3D viscoelastic step")?;
        // The elastic solver has unit modulus: its force over h is f at E_inf.
        let (area_elastic, force_elastic) = if s.approach > 0.0 {
            let e = el
                .solve(Load::Approach(s.approach), &opts, warm.as_ref())
                .ctx("3D elastic solve")?;
            run.iterations += e.iterations;
            let a = (e.contact_cells as f64 / domain, e.force / h);
            warm = Some(e);
            a
        } else {
            (0.0, 0.0)
        };
        run.iterations += s.solve.as_ref().map_or(0, |x| x.iterations);
        run.points.push(Point {
            approach: s.approach / h,
            area: s.contact_cells as f64 / domain,
            area_elastic,
            force: s.force / (h * modulus.relaxed),
            force_elastic,
        });
        most = most.max(s.contact_cells);
    }
    if most < MIN_CONTACT_CELLS {
        let what = if spec.by_approach() {
            "approach"
        } else {
            "force"
        };
        return Err(crate::error::CompareError::Scene(format!(
            "the history's {what} brings at most {most} cells into contact on the {g}^2 grid (realisation {r}), fewer than {MIN_CONTACT_CELLS}: a contact of a few cells does not test MRD's rough contact; raise {what} or cells"
        )));
    }
    Ok(run)
}

/// MRD line `r` (C1D = lambda q C2D, Eq. 76; length L = 1) through the same history:
/// the force F = f E_inf h3 L (or the approach d = (d/h) h3) with h3 the surface's rms
/// height, which the line carries as sqrt(pi / l) of its own, l = pi h1^2 / h3^2 the
/// shift that lambda implies on the line and the punch face
/// ([`crate::experiment::lambda_meaning`]; approach and force reported over h3).
pub fn run_1d(spec: &ViscoelasticRough, modulus: &Prony, lambda: f64, r: u64) -> Result<Run> {
    use crate::experiment::lambda_meaning::{rms_matched, Face};
    let n1 = spec.points_1d_per_cell * spec.cells * spec.bandwidth;
    let sa = spectrum(spec)?;
    let shift = rms_matched(
        lambda,
        &|q| sa.c2d(q),
        spec.bandwidth as f64,
        1.0,
        Face::Disc,
    );
    let line = sa.to_line(lambda);
    let z = nested::line(&|q| line.c1d(q), spec.bandwidth, n1, 1.0, spec.seed, r).ctx("1D line")?;
    let n = n1 as f64;
    let mean = z.iter().sum::<f64>() / n;
    let h1 = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    let h3 = h1 * (std::f64::consts::PI / shift).sqrt();
    let top = z.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let gaps: Vec<f64> = z.iter().map(|v| top - v).collect();
    let dx = 1.0 / n;
    let mut row = SpringRow::new(&gaps, dx, modulus).ctx("MRD springs")?;
    let elastic = Foundation::new(&gaps, dx, modulus.relaxed).ctx("MRD springs")?;
    let mut points = Vec::new();
    let unit = h3 * modulus.relaxed;
    for (dt, v) in spec.history() {
        let load = if spec.by_approach() {
            RowLoad::Depth(v * h3)
        } else {
            RowLoad::Force(v * unit)
        };
        let s = row.step(dt, load).ctx("MRD step")?;
        let e = elastic.at_depth(s.depth.max(0.0)).ctx("MRD elastic")?;
        points.push(Point {
            approach: s.depth / h3,
            area: s.contacts as f64 / n,
            area_elastic: e.contacts as f64 / n,
            force: s.force / unit,
            force_elastic: e.force / unit,
        });
    }
    Ok(Run {
        points,
        iterations: 0,
    })
}
