//! `mrdw bench plastic`: the cost of an elastic-perfectly plastic load step
//! (`bem3d::plastic`, the pressure cap) against the elastic solve of the same rough
//! surface at the same force, on the periodic half-space.

use super::common::reference_surface;
use bem3d::plastic::PlasticContact;
use bem3d::{ContactSolver, Load, PeriodicHalfSpace, SolverOptions};
use std::io::Write;
use std::time::Instant;

/// Mean pressures of the force ladder, over E* (the reference surface's rms slope is
/// 0.1: about 2 % to 13 % of the surface in elastic contact).
const PRESSURES: [f64; 4] = [0.001, 0.002, 0.004, 0.008];

/// The periodic reference surface (self-affine H = 0.8, rms slope 0.1, as `bench bem`
/// and the Tamaas comparison) on grids 128^2 .. `max_n`^2, E* = 1, hardness H = 0.1 E*
/// (plasticity index E* h' / H = 1): the force ladder of [`PRESSURES`] loaded step by
/// step by the plastic solve (each step one solve holding the force, warm-started, or a
/// search of the approach where it stalls), and the elastic solve at each force
/// (warm-started from the last); seconds per step, their ratio, the solves per plastic
/// step, the iterations per step of each, and the saturated share of the contact at the
/// last force.
pub fn run_plastic(w: &mut dyn Write, max_n: usize) -> std::io::Result<()> {
    let hardness = 0.1;
    writeln!(
        w,
        "Plastic load steps (bem3d::plastic, pressure cap H = {hardness} E*, the periodic reference surface: self-affine H = 0.8, rms slope 0.1; mean pressures {PRESSURES:?} E*, tolerance 1e-8) against the elastic solve at each force (warm-started, tolerance 1e-8; the criteria differ: the plastic one is the box-constrained gradient's, the elastic one the normal solver's), {} threads, {}\n",
        rayon::current_num_threads(),
        sysmem::cpu_model()
    )?;
    writeln!(
        w,
        "{:>6} | {:>13} | {:>13} | {:>7} | {:>7} | {:>14} | {:>14} | {:>15}",
        "grid",
        "plastic [s]",
        "elastic [s]",
        "ratio",
        "solves",
        "plastic iter.",
        "elastic iter.",
        "saturated share"
    )?;
    writeln!(w, "{}", "-".repeat(110))?;
    for n in [128usize, 256, 512, 1024, 2048] {
        if n > max_n.max(128) {
            break;
        }
        if let Err(e) = row(w, n, hardness) {
            writeln!(w, "{n:>6} | error: {e}")?;
            return Ok(());
        }
    }
    Ok(())
}

fn row(w: &mut dyn Write, n: usize, hardness: f64) -> Result<(), Box<dyn std::error::Error>> {
    let heights = reference_surface(n)?;
    let op = PeriodicHalfSpace::try_new(n, n, 1.0, 1.0, 1.0)?;
    let mut plastic = PlasticContact::new(op, &heights, None, hardness)?;
    let t0 = Instant::now();
    let (mut solves, mut iterations, mut share) = (0usize, 0usize, 0.0);
    for p in PRESSURES {
        let s = plastic.step(Load::MeanPressure(p), 1e-8)?;
        solves += s.solves;
        iterations += s.iterations;
        share = s.plastic_cells as f64 / s.contact_cells.max(1) as f64;
    }
    let t_plastic = t0.elapsed().as_secs_f64() / PRESSURES.len() as f64;
    let op = PeriodicHalfSpace::try_new(n, n, 1.0, 1.0, 1.0)?;
    let mut elastic = ContactSolver::new(op, &heights, None)?;
    let opts = SolverOptions::new(1e-8, 100_000);
    let t0 = Instant::now();
    let mut last: Option<bem3d::Solution> = None;
    let mut elastic_iterations = 0;
    for p in PRESSURES {
        let s = elastic.solve(Load::MeanPressure(p), &opts, last.as_ref())?;
        elastic_iterations += s.iterations;
        last = Some(s);
    }
    let t_elastic = t0.elapsed().as_secs_f64() / PRESSURES.len() as f64;
    let steps = PRESSURES.len() as f64;
    writeln!(
        w,
        "{:>6} | {:>13.4e} | {:>13.4e} | {:>7.2} | {:>7.2} | {:>14.1} | {:>14.1} | {:>15.3}",
        format!("{n}^2"),
        t_plastic,
        t_elastic,
        t_plastic / t_elastic,
        solves as f64 / steps,
        iterations as f64 / steps,
        elastic_iterations as f64 / steps,
        share
    )?;
    Ok(())
}
