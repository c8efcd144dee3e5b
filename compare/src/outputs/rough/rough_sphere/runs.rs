//! One realisation of each side: the rough sphere in 3D and its MRD row of springs,
//! each pressed at the output's forces.

use super::RoughSphere;
use crate::error::{Context as _, Result};
use bem3d::{BemError, ContactSolver, Load, NonPeriodicHalfSpace, SolverOptions};
use mrd::foundation::Foundation;

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

/// The factor that gives the surfaces unit rms height over the square; the MRD lines
/// take the same factor, so both sides carry the same C2D.
pub fn roughness_scale(spec: &RoughSphere) -> Result<f64> {
    spec.geometry().unit_rms_factor()
}

/// Realisation `r` of the rough sphere with alpha `alpha` in 3D.
pub fn press_3d(spec: &RoughSphere, alpha: f64, scale: f64, r: u64) -> Result<Run> {
    let (n, side) = (spec.grid, spec.side_length());
    let geometry = spec.geometry();
    let z = geometry.heights(spec.rms_height(alpha), scale, r)?;
    let r2 = |c: usize| geometry.r2(c);
    let top = z.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let op = NonPeriodicHalfSpace::new(n, n, side, side, 1.0);
    let mut solver = ContactSolver::new(op, &z, None).ctx("3D solver set-up")?;
    let opts = crate::experiment::solve_options(spec.tolerance, n);
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
    let (x, w) = spec
        .geometry()
        .line(spec.rms_height(alpha), scale, lambda, n1, r)?;
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
