//! `mrdw bench tangential`: the cost of a tangential load step (`bem3d::tangential`,
//! partial slip under a held pressure) against a normal solve of the same grid, on the
//! periodic and on the free half-space.

use bem3d::tangential::{CerrutiFree, CerrutiPeriodic, PartialSlip, TangentialCompliance};
use bem3d::{
    ContactSolver, Load, NonPeriodicHalfSpace, PeriodicHalfSpace, Solution, SolverOptions,
};
use std::io::Write;
use std::time::Instant;

/// Force steps of the monotonic loading to 0.9 mu P.
const STEPS: usize = 10;

/// A sphere (R = 1, E* = 1, nu = 0.5) pressed to a contact radius of a tenth of the
/// period on periodic grids, and of 0.4 of the side on free grids, 128^2 .. `max_n`^2,
/// then loaded tangentially to 0.9 mu P in 10 force steps and through one cycle of
/// amplitude 0.5 mu P (10 steps per half cycle): seconds per tangential step against
/// one cold normal solve of the same grid, and their ratio.
pub fn run_tangential(w: &mut dyn Write, max_n: usize) -> std::io::Result<()> {
    writeln!(
        w,
        "Tangential load steps (bem3d::tangential, sphere R = 1, E* = 1, nu = 0.5, mu = 0.5, contact radius = period / 10 (periodic) or side x 0.4 (free), {STEPS} steps to 0.9 mu P and a cycle of amplitude 0.5 mu P, tolerance 1e-8) against a cold normal solve of the same grid (tolerance 1e-8), {} threads, {}\n",
        rayon::current_num_threads(),
        sysmem::cpu_model()
    )?;
    writeln!(
        w,
        "{:>9} | {:>6} | {:>8} | {:>16} | {:>14} | {:>8} | {:>14}",
        "half-space", "grid", "steps", "tangential [s]", "normal [s]", "ratio", "iter./step"
    )?;
    writeln!(w, "{}", "-".repeat(92))?;
    for periodic in [true, false] {
        for n in [128usize, 256, 512, 1024, 2048] {
            if n > max_n.max(128) {
                break;
            }
            if let Err(e) = row(w, n, periodic) {
                writeln!(w, "{n:>6} | error: {e}")?;
                return Ok(());
            }
        }
    }
    Ok(())
}

/// One row: the normal solve, then the tangential steps.
fn row(w: &mut dyn Write, n: usize, periodic: bool) -> Result<(), Box<dyn std::error::Error>> {
    let r = 1.0f64;
    let a = if periodic { 0.1 } else { 0.4 };
    let heights = bem3d::mask::centred(n, 1.0, |x, y| -(x * x + y * y) / (2.0 * r));
    let apex = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let load = Load::Approach(a * a / r + apex);
    let opts = SolverOptions::new(1e-8, 100_000);
    let t0 = Instant::now();
    let sol: Solution = if periodic {
        let op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
        ContactSolver::new(op, &heights, None)?.solve(load, &opts, None)?
    } else {
        let op = NonPeriodicHalfSpace::try_new(n, n, 1.0, 1.0, 1.0)?;
        ContactSolver::new(op, &heights, None)?.solve(load, &opts, None)?
    };
    let normal = t0.elapsed().as_secs_f64();
    let t0 = Instant::now();
    let op: Box<dyn TangentialCompliance + Sync> = if periodic {
        Box::new(CerrutiPeriodic::new(n, n, 1.0, 1.0, 0.25, 0.5)?)
    } else {
        Box::new(CerrutiFree::new(n, n, 1.0, 1.0, 0.25, 0.5)?)
    };
    let mut ps = PartialSlip::new(op, &sol.pressure, 0.5)?;
    let limit = ps.friction_limit();
    let mut iterations = 0usize;
    for k in 1..=STEPS {
        iterations += ps
            .load(0.9 * limit * k as f64 / STEPS as f64, 1e-8)?
            .iterations;
    }
    ps.cycle(0.5 * limit, STEPS, 1, 1e-8)?;
    let steps = STEPS + 3 * STEPS + 1;
    let tangential = t0.elapsed().as_secs_f64() / steps as f64;
    writeln!(
        w,
        "{:>9} | {:>6} | {:>8} | {:>16.4e} | {:>14.4e} | {:>8.2} | {:>14.1}",
        if periodic { "periodic" } else { "free" },
        format!("{n}^2"),
        steps,
        tangential,
        normal,
        tangential / normal,
        iterations as f64 / STEPS as f64
    )?;
    Ok(())
}
