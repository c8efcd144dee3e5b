//! The rough punch of the Hurst sweep and the lambda study (Section 9, Pohrt & Popov):
//! a rigid circular punch with a rough face pressed on the free half-space along a
//! ladder of approaches, its k(F) curve with every solve's record, and the k(f) of an
//! ensemble of MRD lines on the same f grid, as the studies checkpoint them.

use crate::error::{Context as _, Result};
use crate::output::{Checkpointed, Env};
use crate::plan::Stage;
use crate::report::{clock, Section};
use bem3d::{BemError, ContactSolver, Load, NonPeriodicHalfSpace, SolverOptions};
use serde::{Deserialize, Serialize};

/// The stages of a rough-punch study's checkpointed work, which run interleaved: a 3D
/// task synthesises a face and solves it and its stiffness at every load, a 1D task
/// synthesises and loads its lines.
pub const STAGES: [Stage; 4] = [
    Stage::RoughSynthesis,
    Stage::Bem3d,
    Stage::Bem3dStiffness,
    Stage::RoughContact,
];

/// The stages of a checkpointed study of rough punches: the spectrum of its measured
/// source where it has one (`psd`), the punches' [`STAGES`], then the fit.
pub fn study_stages(psd: bool) -> Vec<Stage> {
    let mut s = Vec::new();
    if psd {
        s.push(Stage::Psd);
    }
    s.extend(STAGES);
    s.push(Stage::SweepFit);
    s
}

/// Runs a study's checkpointed tasks `compute`, recorded as the [`STAGES`] they
/// interleave.
pub fn run_tasks<T>(out: &mut Section, compute: impl FnOnce() -> T) -> T {
    out.stages_together(&STAGES, compute)
}

/// Computes the missing tasks of `study` in its checkpoint folder under the run's work
/// root, recorded as the [`STAGES`]; returns the folder.
pub fn compute_study(
    study: &dyn Checkpointed,
    env: &Env,
    out: &mut Section,
) -> Result<std::path::PathBuf> {
    let work = env.work_root.join(study.key());
    run_tasks(out, || study.compute(env.ctx, &work, env.control))?;
    Ok(work)
}

/// One 3D solve of a realisation's load ladder, as recorded in the solves table.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct SolveRecord {
    pub approach: f64,
    pub force: f64,
    pub iterations: usize,
    pub residual: f64,
    pub converged: bool,
    pub stiffness_converged: bool,
}

/// Result of one 3D realisation: F and k at each approach where both converged (E* = 1,
/// L = 1), and every solve's record.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct BemCurve {
    pub rms_height: f64,
    pub force: Vec<f64>,
    pub stiffness: Vec<f64>,
    pub solves: Vec<SolveRecord>,
    pub iterations: usize,
    /// Largest residual reached; above the tolerance when a solve did not converge.
    pub max_residual: f64,
    pub unconverged: usize,
    pub seconds: f64,
}

/// The 3D solves of a study that did not converge, counted over its punches' records.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolveTally {
    pub solves: usize,
    pub unconverged: usize,
    /// Converged solves whose tangent-stiffness solve did not converge.
    pub stiffness_failed: usize,
    /// The largest residual of the unconverged solves.
    pub worst: f64,
}

impl SolveTally {
    pub fn add(&mut self, s: &SolveRecord) {
        self.solves += 1;
        if !s.converged {
            self.unconverged += 1;
            self.worst = self.worst.max(s.residual);
        } else if !s.stiffness_converged {
            self.stiffness_failed += 1;
        }
    }

    pub fn add_curve(&mut self, c: &BemCurve) {
        c.solves.iter().for_each(|s| self.add(s));
    }

    /// Makes unconverged solves fail the run visibly (the report is still written, the
    /// exit code is 4) and records their count as `unconverged_3d_solves`.
    pub fn report(&self, tolerance: f64, out: &mut Section) {
        if self.unconverged > 0 {
            out.failures.push(format!(
                "{} of {} 3D solves did not converge (largest residual {:.2e}, tolerance {tolerance:.1e}); left out of the curves, listed in the solves table",
                self.unconverged, self.solves, self.worst
            ));
        }
        if self.stiffness_failed > 0 {
            out.failures.push(format!(
                "{} 3D stiffness solves did not converge; left out of the curves",
                self.stiffness_failed
            ));
        }
        out.value("unconverged_3d_solves", serde_json::json!(self.unconverged));
    }
}

/// Result of the 1D ensemble at one H: k/(E* L) per realisation on the f grid.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct MrdEnsemble {
    pub stiffness: Vec<Vec<f64>>,
    pub seconds: f64,
    pub points: usize,
}

/// The punch's face on the `g x g` map `heights` (side L = 1): the disc inscribed in
/// it, and the approach of full contact over that disc (its highest minus its lowest
/// height).
pub fn punch_face(heights: &[f64], g: usize) -> (Vec<bool>, f64) {
    let mask = bem3d::mask::disc(g, g, 1.0, 1.0, 0.5);
    let (top, bottom) = heights
        .iter()
        .zip(&mask)
        .filter(|(_, &m)| m)
        .fold((f64::NEG_INFINITY, f64::INFINITY), |(t, b), (&v, _)| {
            (t.max(v), b.min(v))
        });
    (mask, top - bottom)
}

/// The rough punch of the studies: the disc inscribed in the `g x g` map `heights` (side
/// L = 1, E* = 1) pressed on the free half-space at `loads` approaches, log-spaced from
/// 1e-3 of the full-contact approach to full contact, warm-started; F and the tangent
/// stiffness k = dF/dd (contact set fixed) at each. `seconds` is left 0 for the caller.
pub fn punch_curve(heights: &[f64], g: usize, loads: usize, tolerance: f64) -> Result<BemCurve> {
    let (mask, full) = punch_face(heights, g);
    let mut solver = ContactSolver::new(
        NonPeriodicHalfSpace::new(g, g, 1.0, 1.0, 1.0),
        heights,
        Some(mask),
    )
    .ctx("3D solver set-up")?;
    let opts = SolverOptions {
        tolerance,
        max_iterations: 20 * g + 2000,
        ..Default::default()
    };
    let stiffness_opts = SolverOptions {
        tolerance: 1e-9,
        ..opts.clone()
    };
    let mut out = BemCurve {
        rms_height: solver.h_rms(),
        force: vec![],
        stiffness: vec![],
        solves: vec![],
        iterations: 0,
        max_residual: 0.0,
        unconverged: 0,
        seconds: 0.0,
    };
    let mut warm: Option<bem3d::Solution> = None;
    for k in 0..loads {
        let d = full * 10f64.powf(-3.0 * (1.0 - k as f64 / (loads - 1) as f64));
        let solved = clock::time(Stage::Bem3d, || {
            solver.solve(Load::Approach(d), &opts, warm.as_ref())
        });
        let (sol, converged) = match solved {
            Ok(s) => (s, true),
            Err(BemError::NoConvergence { last, .. }) => {
                out.unconverged += 1;
                (*last, false)
            }
            Err(e) => return Err(e).ctx("3D solve"),
        };
        out.iterations += sol.iterations;
        out.max_residual = out.max_residual.max(sol.residual);
        // Unconverged iterates are recorded, not used.
        let kk = match converged.then(|| {
            clock::time(Stage::Bem3dStiffness, || {
                solver.tangent_stiffness(&sol, &stiffness_opts)
            })
        }) {
            Some(Ok(v)) => v,
            Some(Err(e)) if e.progress().is_none() => return Err(e).ctx("3D stiffness"),
            _ => f64::NAN,
        };
        out.solves.push(SolveRecord {
            approach: d,
            force: sol.force,
            iterations: sol.iterations,
            residual: sol.residual,
            converged,
            stiffness_converged: kk.is_finite(),
        });
        if sol.force > 0.0 && kk.is_finite() && kk > 0.0 {
            out.force.push(sol.force);
            out.stiffness.push(kk);
        }
        if converged {
            warm = Some(sol);
        }
    }
    Ok(out)
}

/// k/(E* L) of one MRD line on the foundation E* = 1, L = 1 at each reduced force
/// f = F/(E* h L) of `fs`, h the line's own rms height; past complete contact k = E* L.
pub fn line_stiffness(rl: &mrd::rough_contact::RoughLine, fs: &[f64]) -> Result<Vec<f64>> {
    clock::time(Stage::RoughContact, || {
        let full_force = rl.at_depth(rl.full_contact_depth()).ctx("1D")?.force;
        fs.iter()
            .map(|&f| {
                let force = f * rl.rms_height;
                if full_force <= force {
                    return Ok(1.0);
                }
                Ok(rl.at_force(force).ctx("1D")?.stiffness)
            })
            .collect()
    })
}
