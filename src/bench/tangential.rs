//! `mrdw bench tangential`: the cost of a tangential load step (`bem3d::tangential`,
//! partial slip under a held pressure) against a normal solve of the same grid.

use bem3d::tangential::{CerrutiPeriodic, PartialSlip};
use bem3d::{ContactSolver, Load, PeriodicHalfSpace, SolverOptions};
use std::io::Write;
use std::time::Instant;

/// Force steps of the monotonic loading to 0.9 mu P.
const STEPS: usize = 10;

/// A sphere (R = 1, E* = 1, nu = 0.5) pressed to a contact radius of a tenth of the
/// period on periodic grids 128^2 .. `max_n`^2 (12.8 .. cells per contact radius), then
/// loaded tangentially to 0.9 mu P in 10 force steps and through one cycle of amplitude
/// 0.5 mu P (10 steps per half cycle): seconds per tangential step against one cold
/// normal solve of the same grid, and their ratio.
pub fn run_tangential(w: &mut dyn Write, max_n: usize) -> std::io::Result<()> {
    writeln!(
        w,
        "Tangential load steps (bem3d::tangential, sphere R = 1, E* = 1, nu = 0.5, mu = 0.5, contact radius = period / 10, {STEPS} steps to 0.9 mu P and a cycle of amplitude 0.5 mu P, tolerance 1e-8) against a cold normal solve of the same grid (tolerance 1e-8), {} threads, {}\n",
        rayon::current_num_threads(),
        sysmem::cpu_model()
    )?;
    writeln!(
        w,
        "{:>6} | {:>8} | {:>16} | {:>14} | {:>8} | {:>14}",
        "grid", "steps", "tangential [s]", "normal [s]", "ratio", "iter./step"
    )?;
    writeln!(w, "{}", "-".repeat(80))?;
    let (r, a) = (1.0f64, 0.1f64);
    let d = a * a / r;
    for n in [128usize, 256, 512, 1024, 2048] {
        if n > max_n.max(128) {
            break;
        }
        let heights = bem3d::mask::centred(n, 1.0, |x, y| -(x * x + y * y) / (2.0 * r));
        let apex = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let t0 = Instant::now();
        let op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
        let sol = ContactSolver::new(op, &heights, None).and_then(|mut s| {
            s.solve(
                Load::Approach(d + apex),
                &SolverOptions::new(1e-8, 100_000),
                None,
            )
        });
        let sol = match sol {
            Ok(s) => s,
            Err(e) => return writeln!(w, "{n:>6} | error: {e}"),
        };
        let normal = t0.elapsed().as_secs_f64();
        let t0 = Instant::now();
        let slip = CerrutiPeriodic::new(n, n, 1.0, 1.0, 0.25, 0.5)
            .and_then(|op| PartialSlip::new(op, &sol.pressure, 0.5));
        let mut ps = match slip {
            Ok(p) => p,
            Err(e) => return writeln!(w, "{n:>6} | error: {e}"),
        };
        let limit = ps.friction_limit();
        let (mut steps, mut iterations) = (0usize, 0usize);
        for k in 1..=STEPS {
            match ps.load(0.9 * limit * k as f64 / STEPS as f64, 1e-8) {
                Ok(s) => iterations += s.iterations,
                Err(e) => return writeln!(w, "{n:>6} | error: {e}"),
            }
            steps += 1;
        }
        if let Err(e) = ps.cycle(0.5 * limit, STEPS, 1, 1e-8) {
            return writeln!(w, "{n:>6} | error: {e}");
        }
        steps += 3 * STEPS + 1;
        let tangential = t0.elapsed().as_secs_f64() / steps as f64;
        writeln!(
            w,
            "{:>6} | {:>8} | {:>16.4e} | {:>14.4e} | {:>8.2} | {:>14.1}",
            format!("{n}^2"),
            steps,
            tangential,
            normal,
            tangential / normal,
            iterations as f64 / STEPS as f64
        )?;
    }
    Ok(())
}
