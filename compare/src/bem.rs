//! The `bem_contact` output: a 3D boundary-element contact of a height map read from a
//! file, at a list of mean pressures or approaches (warm-started load steps), so that the
//! same surface can be run side by side with other solvers.

use crate::error::{CompareError, MrdContext, Result};
use crate::plan::Stage;
use crate::report::{Figure, Report, Series, Style, Table};
use crate::scene::{OutputSpec, Scene};
use bem3d::{
    Compliance, ContactSolver, Load, NonPeriodicHalfSpace, PeriodicHalfSpace, SolverOptions,
};
use mrd::topography::HeightMap;
use std::time::Instant;

pub fn run_output(scene: &Scene, index: usize, report: &mut Report) -> Result<()> {
    let OutputSpec::BemContact {
        heights,
        size,
        periodic,
        punch_radius,
        mean_pressures,
        approaches,
        tolerance,
        max_iterations,
        fields,
    } = &scene.file.outputs[index]
    else {
        unreachable!("not a bem_contact output")
    };
    let ctx = format!("outputs[{index}] (bem_contact)");
    report.ran(Stage::Bem3d);
    let path = match &scene.base_dir {
        Some(b) => b.join(heights),
        None => std::path::PathBuf::from(heights),
    };
    let map = HeightMap::read(&path).ctx(&ctx)?;
    let (nx, ny) = (map.cols, map.rows);
    if nx < 4 || ny < 4 {
        return Err(CompareError::Scene(format!(
            "{ctx}: height map {ny} x {nx} is too small (need >= 4 x 4)"
        )));
    }
    let (lx, ly) = (size[0], size[1]);
    let e = scene.material.e_star;
    let mask = punch_radius.map(|r| {
        (0..nx * ny)
            .map(|k| {
                let x = ((k % nx) as f64 + 0.5) * lx / nx as f64 - 0.5 * lx;
                let y = ((k / nx) as f64 + 0.5) * ly / ny as f64 - 0.5 * ly;
                x * x + y * y <= r * r
            })
            .collect::<Vec<bool>>()
    });
    let opts = SolverOptions {
        tolerance: *tolerance,
        max_iterations: *max_iterations,
    };
    let loads: Vec<Load> = if mean_pressures.is_empty() {
        approaches.iter().map(|&d| Load::Approach(d)).collect()
    } else {
        mean_pressures
            .iter()
            .map(|&p| Load::MeanPressure(p))
            .collect()
    };
    let rows = if *periodic {
        let op = PeriodicHalfSpace::new(nx, ny, lx, ly, e);
        solve_all(op, &map.data, mask, &loads, &opts, &ctx, *fields, report)?
    } else {
        let op = NonPeriodicHalfSpace::new(nx, ny, lx, ly, e);
        solve_all(op, &map.data, mask, &loads, &opts, &ctx, *fields, report)?
    };
    let u = &scene.file.units;
    let mut t = Table::new(
        "bem_contact",
        &[
            format!("mean_pressure [{}]", u.stress),
            format!("force [{}]", u.force()),
            format!("approach [{}]", u.length),
            "relative_contact_area [1]".into(),
            format!("mean_gap [{}]", u.length),
            format!("stiffness [{}]", u.stiffness()),
            "iterations [1]".into(),
            "residual [1]".into(),
            "wall_time [s]".into(),
        ],
    );
    t.notes.push(format!(
        "{} {ny} x {nx} map from {} over {lx} x {ly}; E* = {e}; tolerance {tolerance:e} (criterion: bem3d::solver docs); stiffness dF/dd with the contact set fixed",
        if *periodic { "periodic" } else { "non-periodic" },
        path.display()
    ));
    for r in &rows {
        t.push(r.clone());
    }
    let last = rows.last().unwrap();
    report.scalar("bem_contact.relative_contact_area", last[3]);
    report.scalar("bem_contact.mean_gap", last[4]);
    report.scalar("bem_contact.stiffness", last[5]);
    report.scalar(
        "bem_contact.iterations_total",
        rows.iter().map(|r| r[6]).sum(),
    );
    let mut fig = Figure::new(
        "bem_contact",
        "Real contact area against load (3D boundary elements)",
        &format!("mean pressure [{}]", u.stress),
        "relative contact area [1]",
    )
    .with(Series::new(
        "bem3d",
        rows.iter().map(|r| (r[0], r[3])).collect(),
        Style::Markers,
    ));
    fig.log_x = rows.iter().all(|r| r[0] > 0.0) && rows.len() > 2;
    fig.log_y = rows.iter().all(|r| r[3] > 0.0) && rows.len() > 2;
    report.tables.push(t);
    report.figures.push(fig);
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn solve_all<K: Compliance>(
    op: K,
    heights: &[f64],
    mask: Option<Vec<bool>>,
    loads: &[Load],
    opts: &SolverOptions,
    ctx: &str,
    fields: bool,
    report: &mut Report,
) -> Result<Vec<Vec<f64>>> {
    let (nx, ny, area) = (op.nx(), op.ny(), op.lx() * op.ly());
    let n_domain = mask
        .as_ref()
        .map_or(nx * ny, |m| m.iter().filter(|&&v| v).count()) as f64;
    let mut solver = ContactSolver::new(op, heights, mask)
        .map_err(|e| CompareError::Scene(format!("{ctx}: {e}")))?;
    let mut warm: Option<bem3d::Solution> = None;
    let mut rows = Vec::new();
    for (k, &load) in loads.iter().enumerate() {
        let t0 = Instant::now();
        let sol = solver
            .solve(load, opts, warm.as_ref())
            .map_err(|e| CompareError::Scene(format!("{ctx}: load {}: {e}", k + 1)))?;
        let kk = solver
            .tangent_stiffness(&sol, opts)
            .map_err(|e| CompareError::Scene(format!("{ctx}: stiffness at load {}: {e}", k + 1)))?;
        let secs = t0.elapsed().as_secs_f64();
        rows.push(vec![
            sol.force / area,
            sol.force,
            sol.approach,
            sol.contact_cells as f64 / n_domain,
            sol.mean_gap,
            kk,
            sol.iterations as f64,
            sol.residual,
            secs,
        ]);
        if fields {
            for (what, data) in [("pressure", &sol.pressure), ("gap", &sol.gap)] {
                let bytes = HeightMap {
                    rows: ny,
                    cols: nx,
                    data: data.clone(),
                }
                .to_npy_bytes();
                report
                    .files
                    .push((format!("bem_contact_{what}_{}.npy", k + 1), bytes));
            }
        }
        warm = Some(sol);
    }
    Ok(rows)
}
