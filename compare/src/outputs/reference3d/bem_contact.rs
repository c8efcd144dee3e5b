//! `bem_contact`: a 3D boundary-element contact of a height map read from a file, at a
//! list of mean pressures or approaches (load steps, warm-started where that pays), so
//! that the same surface can be run side by side with other solvers.
//!
//! A solve that does not converge is recorded, not hidden: its row carries the last
//! iterate, `converged = 0` and the residual reached, the report is written, and the run
//! fails (exit code 4). The tangent stiffness is computed only when `stiffness = true`;
//! at complete contact of a periodic surface it is infinite (written `inf`).

use crate::checks::{bad, require_positive};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use bem3d::{
    BemError, ContactSolver, Load, NonPeriodicHalfSpace, Path, PeriodicHalfSpace, Solution,
    SolverOperator, SolverOptions,
};
use mrd::topography::HeightMap;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BemContact {
    /// Height map file (peaks up), relative to the scene: `.npy`, a text matrix, an ESRI
    /// ASCII grid or an `.xyz` point list ([`HeightMap::read_with_cell`]).
    heights: String,
    /// Physical size [lx, ly] of the map (length units).
    size: [f64; 2],
    /// true: the periodic half-space; false: the free (zero-padded) half-space.
    #[serde(default = "crate::checks::default_true")]
    periodic: bool,
    /// Radius of a centred circular punch (mask); none: the whole map may touch.
    punch_radius: Option<f64>,
    /// Loads: mean pressures over the map area ...
    #[serde(default)]
    mean_pressures: Vec<f64>,
    /// ... or rigid-body approaches from first contact.
    #[serde(default)]
    approaches: Vec<f64>,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "tolerance")]
    tolerance: f64,
    /// Most iterations of one 3D solve.
    #[serde(default = "max_iterations")]
    max_iterations: usize,
    /// Also compute the tangent stiffness dF/dd (contact set fixed) at each load.
    #[serde(default)]
    stiffness: bool,
    /// Also write pressure and gap fields as .npy (one pair per load).
    #[serde(default)]
    fields: bool,
}

fn tolerance() -> f64 {
    1e-10
}
fn max_iterations() -> usize {
    20_000
}

/// One load step's result.
struct Step {
    sol: Solution,
    converged: bool,
    stiffness: Option<f64>,
}

impl BemContact {
    fn loads(&self) -> Vec<Load> {
        if self.mean_pressures.is_empty() {
            self.approaches.iter().map(|&d| Load::Approach(d)).collect()
        } else {
            self.mean_pressures
                .iter()
                .map(|&p| Load::MeanPressure(p))
                .collect()
        }
    }

    fn options(&self) -> SolverOptions {
        SolverOptions::new(self.tolerance, self.max_iterations)
    }

    /// Solves every load in turn on operator `op`.
    fn solve_all<K: SolverOperator>(
        &self,
        op: K,
        map: &HeightMap,
        out: &mut Section,
    ) -> Result<Vec<Step>> {
        let (lx, ly) = (self.size[0], self.size[1]);
        let mask = self
            .punch_radius
            .map(|r| bem3d::mask::disc(map.cols, map.rows, lx, ly, r));
        let mut solver = ContactSolver::new(op, &map.data, mask).ctx("3D solver set-up")?;
        let opts = self.options();
        let mut steps: Vec<Step> = Vec::new();
        for (k, load) in self.loads().into_iter().enumerate() {
            let warm = steps.last().filter(|s| s.converged).map(|s| &s.sol);
            let (sol, converged) = match out.stage(Stage::Bem3d, || solver.solve(load, &opts, warm))
            {
                Ok(sol) => (sol, true),
                Err(BemError::NoConvergence {
                    last,
                    iterations,
                    residual,
                    ..
                }) => {
                    out.failures.push(format!(
                        "load {}: not converged after {iterations} iterations, residual {residual:.3e} (tolerance {:.1e})",
                        k + 1,
                        self.tolerance
                    ));
                    (*last, false)
                }
                Err(e) => return Err(e).ctx(format!("load {}", k + 1)),
            };
            let stiffness = if self.stiffness {
                Some(
                    match out.stage(Stage::Bem3dStiffness, || {
                        solver.tangent_stiffness(&sol, &opts)
                    }) {
                        Ok(v) => v,
                        Err(e) if e.progress().is_some() => {
                            out.failures.push(format!("load {}: stiffness: {e}", k + 1));
                            f64::NAN
                        }
                        Err(e) => return Err(e).ctx(format!("stiffness at load {}", k + 1)),
                    },
                )
            } else {
                None
            };
            steps.push(Step {
                sol,
                converged,
                stiffness,
            });
        }
        Ok(steps)
    }
}

impl Output for BemContact {
    fn validate(&self, ctx: &Context) -> Result<()> {
        bem3d::operator::check_scales(self.size[0], self.size[1], ctx.material.e_star)
            .map_err(|e| crate::error::CompareError::Scene(format!("size: {e}")))?;
        if self.mean_pressures.is_empty() == self.approaches.is_empty() {
            return bad("give exactly one of mean_pressures and approaches (a non-empty list)");
        }
        if let Some(v) = self
            .mean_pressures
            .iter()
            .chain(&self.approaches)
            .find(|v| !(v.is_finite() && **v >= 0.0))
        {
            return bad(format!("load {v}: loads must be finite and >= 0"));
        }
        if let Some(r) = self.punch_radius {
            require_positive("punch_radius", r)?;
        }
        self.options()
            .validate()
            .map_err(|e| crate::error::CompareError::Scene(e.to_string()))?;
        let path = ctx.resolve(&self.heights);
        if let Some(why) = mrd::topography::unreadable(&path) {
            return bad(format!("heights: {why}"));
        }
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        let mut s = vec![Stage::Bem3d];
        if self.stiffness {
            s.push(Stage::Bem3dStiffness);
        }
        s
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let path = env.ctx.resolve(&self.heights);
        let (map, cell) = HeightMap::read_with_cell(&path).ctx("heights")?;
        let (nx, ny) = (map.cols, map.rows);
        let (lx, ly) = (self.size[0], self.size[1]);
        if let Some((dx, dy)) = cell {
            let (fx, fy) = (dx * nx as f64, dy * ny as f64);
            if (fx - lx).abs() > 1e-6 * lx || (fy - ly).abs() > 1e-6 * ly {
                out.warn(format!(
                    "{}: its cells of {dx} x {dy} make the map {fx} x {fy}, but the scene's size is {lx} x {ly} (used)",
                    path.display()
                ));
            }
        }
        let e = env.ctx.material.e_star;
        let steps = if self.periodic {
            let op = PeriodicHalfSpace::try_new(nx, ny, lx, ly, e).ctx("heights")?;
            self.solve_all(op, &map, out)?
        } else {
            let op = NonPeriodicHalfSpace::try_new(nx, ny, lx, ly, e).ctx("heights")?;
            self.solve_all(op, &map, out)?
        };
        let u = &env.ctx.units;
        let mut cols = vec![
            format!("mean_pressure [{}]", u.stress),
            format!("force [{}]", u.force()),
            format!("approach [{}]", u.length),
            "relative_contact_area [1]".into(),
            format!("mean_gap [{}]", u.length),
        ];
        if self.stiffness {
            cols.push(format!("stiffness [{}]", u.stiffness()));
        }
        cols.extend([
            "iterations [count]".into(),
            "residual [1]".into(),
            "certificate [1]".into(),
            "converged [0/1]".into(),
            "path [0 full grid/1 window/2 candidate set]".into(),
            "nested_start [0/1]".into(),
            "single_precision_iterations [count]".into(),
            "stencil_iterations [count]".into(),
        ]);
        let mut t = Table::new("bem_contact", &cols);
        t.missing_ok = true;
        t.infinite_ok = true;
        t.notes.push(format!(
            "{} {ny} x {nx} map from {} over {lx} x {ly}; E* = {e}; tolerance {:e} (criterion: bem3d::solver docs){}; certificate: bound of the energy's duality gap over F h_rms, at most the tolerance when converged away from complete contact (then the pressure error in the norm of K, (p - p*).K(p - p*), is at most 2 x tolerance x F x h_rms; bem3d::solver docs); converged = 1: the criterion reached the tolerance, or in complete contact the floor of rounding it can reach (the residual then above the tolerance; bem3d::solver docs, Complete contact); converged = 0: the last iterate at max_iterations; iterations of restricted solves count iterations on a window around a compact contact (non-periodic) or applications of a dense K between a small candidate set (few contact cells; bem3d::solver docs); path, nested_start, single_precision_iterations (of iterations, those with K p carried in single precision) and stencil_iterations (those with the preconditioner applied by its stencil): the strategies the solve took (bem3d::Solution)",
            if self.periodic { "periodic" } else { "non-periodic" },
            path.display(),
            self.tolerance,
            if self.stiffness { "; stiffness dF/dd with the contact set fixed (inf at complete contact of a periodic map)" } else { "" },
        ));
        let area = lx * ly;
        for (k, s) in steps.iter().enumerate() {
            let sol = &s.sol;
            let mut row = vec![
                sol.force / area,
                sol.force,
                sol.approach,
                sol.contact_cells as f64 / sol.domain_cells as f64,
                sol.mean_gap,
            ];
            row.extend(s.stiffness);
            row.extend([
                sol.iterations as f64,
                sol.residual,
                sol.certificate,
                s.converged as u8 as f64,
                match sol.path {
                    Path::FullGrid => 0.0,
                    Path::Window => 1.0,
                    Path::CandidateSet => 2.0,
                },
                sol.nested_start as u8 as f64,
                sol.single_iterations as f64,
                sol.stencil_iterations as f64,
            ]);
            t.push(row);
            if self.fields {
                for (what, data) in [("pressure", &sol.pressure), ("gap", &sol.gap)] {
                    let bytes = HeightMap {
                        rows: ny,
                        cols: nx,
                        data: data.clone(),
                    }
                    .to_npy_bytes();
                    out.files
                        .push((format!("{}_{what}_{}.npy", out.label, k + 1), bytes));
                }
            }
        }
        let last = steps.last().expect("at least one load");
        out.scalar(
            "relative_contact_area",
            last.sol.contact_cells as f64 / last.sol.domain_cells as f64,
        );
        out.scalar("mean_gap", last.sol.mean_gap);
        if let Some(k) = last.stiffness.filter(|k| k.is_finite()) {
            out.scalar("stiffness", k);
        }
        out.scalar(
            "iterations_total",
            steps.iter().map(|s| s.sol.iterations as f64).sum(),
        );
        out.value(
            "unconverged_solves",
            serde_json::json!(steps.iter().filter(|s| !s.converged).count()),
        );
        let pts = t.xy("mean_pressure", "relative_contact_area");
        let mut fig = Figure::new(
            "bem_contact",
            "Real contact area against load (3D boundary elements)",
            &format!("mean pressure [{}]", u.stress),
            "relative contact area [1]",
        )
        .plot("bem3d", pts.clone(), Style::Markers);
        fig.log_x = pts.iter().all(|p| p.0 > 0.0) && pts.len() > 2;
        fig.log_y = pts.iter().all(|p| p.1 > 0.0) && pts.len() > 2;
        out.tables.push(t);
        out.figures.push(fig);
        Ok(())
    }
}
