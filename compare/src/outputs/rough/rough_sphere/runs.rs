//! One realisation of each side: the rough sphere in 3D and its MRD row of springs,
//! each pressed at the output's forces.

use super::RoughSphere;
use crate::error::{Context as _, Result};
use bem3d::{BemError, ContactSolver, Load, NonPeriodicHalfSpace, SolverOptions};
use mrd::foundation::Foundation;
use mrd::roughness::synthesis::Grid;
use mrd::roughness::{nested, SelfAffine};
use std::f64::consts::PI;

/// The contact at one force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    pub force: f64,
    /// Approach of the mean sphere, from the apex of the smooth sphere.
    pub approach: f64,
    /// k = dF/dd (contact set fixed).
    pub stiffness: f64,
    /// sqrt(5/2 <r^2>_p) (3D), sqrt(5 <x^2>_q) (MRD): the Hertz radius when smooth.
    pub radius: f64,
    /// Distance of the farthest contact from the axis.
    pub outermost: f64,
    /// Whether a contact lies farther from the axis than 0.9 of the half-side (then
    /// the map or row, not the sphere, bounds the contact).
    pub edge: bool,
}

/// A contact farther from the axis than this fraction of the side (0.9 of the
/// half-side) is bounded by the map, not by the sphere.
const EDGE: f64 = 0.45;

/// A realisation's states at each force (None: not converged; counted).
#[derive(Debug, Clone)]
pub struct Run {
    pub states: Vec<Option<State>>,
    pub unconverged: usize,
}

fn spectrum(spec: &RoughSphere) -> Result<SelfAffine> {
    let q0 = 2.0 * PI / spec.side_length();
    SelfAffine::new(spec.hurst, q0, q0, q0 * (spec.bandwidth as f64 + 1.0)).ctx("spectrum")
}

fn surface(spec: &RoughSphere, r: u64) -> Result<Vec<f64>> {
    let sa = spectrum(spec)?;
    let grid = Grid::square(spec.grid, spec.side_length());
    nested::surface(&|q| sa.c2d(q), spec.bandwidth, &grid, spec.seed, r).ctx("3D roughness")
}

/// The factor that gives the surfaces unit rms height over the square (the same for
/// every realisation: their mode amplitudes are fixed, only the phases are random). The
/// MRD lines take the same factor, so both sides carry the same C2D.
pub fn roughness_scale(spec: &RoughSphere) -> Result<f64> {
    let z = surface(spec, 0)?;
    let n = z.len() as f64;
    let mean = z.iter().sum::<f64>() / n;
    let rms = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    if rms.is_nan() || rms <= 0.0 {
        return Err(crate::error::CompareError::Scene(
            "rough_sphere: the roughness band is empty".into(),
        ));
    }
    Ok(1.0 / rms)
}

/// Cell-centre coordinate of index i of `n` across `side`, centred on the axis.
fn centre(i: usize, n: usize, side: f64) -> f64 {
    (i as f64 + 0.5) * side / n as f64 - 0.5 * side
}

/// Realisation `r` of the rough sphere with alpha `alpha` in 3D.
pub fn press_3d(spec: &RoughSphere, alpha: f64, scale: f64, r: u64) -> Result<Run> {
    let (n, side) = (spec.grid, spec.side_length());
    let h = spec.rms_height(alpha);
    let rough = if alpha > 0.0 {
        surface(spec, r)?
    } else {
        vec![0.0; n * n]
    };
    let r2 = |c: usize| centre(c % n, n, side).powi(2) + centre(c / n, n, side).powi(2);
    let z: Vec<f64> = (0..n * n)
        .map(|c| -r2(c) / (2.0 * spec.radius) + h * scale * rough[c])
        .collect();
    let top = z.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let op = NonPeriodicHalfSpace::new(n, n, side, side, 1.0);
    let mut solver = ContactSolver::new(op, &z, None).ctx("3D solver set-up")?;
    let opts = SolverOptions {
        tolerance: spec.tolerance,
        max_iterations: 20 * n + 2000,
        ..Default::default()
    };
    let stiffness_opts = SolverOptions {
        tolerance: 1e-9,
        ..opts.clone()
    };
    let mut run = Run {
        states: Vec::new(),
        unconverged: 0,
    };
    let mut warm: Option<bem3d::Solution> = None;
    for force in spec.forces() {
        let sol = match solver.solve(Load::Force(force), &opts, warm.as_ref()) {
            Ok(s) => s,
            Err(BemError::NoConvergence { .. }) => {
                run.unconverged += 1;
                run.states.push(None);
                continue;
            }
            Err(e) => return Err(e).ctx("3D solve"),
        };
        let stiffness = match solver.tangent_stiffness(&sol, &stiffness_opts) {
            Ok(k) => k,
            Err(e) if e.progress().is_some() => {
                run.unconverged += 1;
                run.states.push(None);
                continue;
            }
            Err(e) => return Err(e).ctx("3D stiffness"),
        };
        let (mut pr2, mut p, mut outermost) = (0.0, 0.0, 0.0f64);
        for (c, &pc) in sol.pressure.iter().enumerate() {
            if pc > 0.0 {
                pr2 += pc * r2(c);
                p += pc;
                outermost = outermost.max(r2(c).sqrt());
            }
        }
        run.states.push(Some(State {
            force: sol.force,
            approach: sol.approach - top,
            stiffness,
            radius: (2.5 * pr2 / p).sqrt(),
            outermost,
            edge: outermost > EDGE * side,
        }));
        warm = Some(sol);
    }
    Ok(run)
}

/// MRD line `r` of the rough sphere with alpha `alpha` and factor `lambda`: springs E* dx
/// across the map's side with the gap x^2 / R (Eq. 11 for the sphere) minus the line.
pub fn press_1d(spec: &RoughSphere, alpha: f64, scale: f64, lambda: f64, r: u64) -> Result<Run> {
    let side = spec.side_length();
    let n1 = spec.points_1d_factor * spec.grid;
    let h = spec.rms_height(alpha);
    let rough = if alpha > 0.0 {
        let line = spectrum(spec)?.to_line(lambda); // Eq. (76)
        nested::line(&|q| line.c1d(q), spec.bandwidth, n1, side, spec.seed, r).ctx("1D line")?
    } else {
        vec![0.0; n1]
    };
    let x: Vec<f64> = (0..n1).map(|i| centre(i, n1, side)).collect();
    let w: Vec<f64> = (0..n1)
        .map(|i| -x[i] * x[i] / spec.radius + h * scale * rough[i])
        .collect();
    let top = w.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let gaps: Vec<f64> = w.iter().map(|v| top - v).collect();
    let dx = side / n1 as f64;
    let row = Foundation::new(&gaps, dx, 1.0).ctx("MRD springs")?;
    let mut states = Vec::new();
    for force in spec.forces() {
        let s = row.at_force(force).ctx("MRD")?;
        let (mut qx2, mut q, mut outermost) = (0.0, 0.0, 0.0f64);
        for i in 0..n1 {
            let qi = s.depth - gaps[i];
            if qi > 0.0 {
                qx2 += qi * x[i] * x[i];
                q += qi;
                outermost = outermost.max(x[i].abs());
            }
        }
        states.push(Some(State {
            force: s.force,
            approach: s.depth - top,
            stiffness: s.stiffness,
            radius: (5.0 * qx2 / q).sqrt(),
            outermost,
            edge: outermost > EDGE * side,
        }));
    }
    Ok(Run {
        states,
        unconverged: 0,
    })
}
