//! `mrdw bench adhesion`: the cost of an adhesive approach-retraction cycle
//! (`bem3d::adhesion`) against the non-adhesive solver on the same grid and approaches.

use bem3d::adhesion::AdhesiveContact;
use bem3d::{ContactSolver, Load, NonPeriodicHalfSpace, SolverOptions};
use std::f64::consts::PI;
use std::io::Write;
use std::time::Instant;

/// Approach steps of the loading (the unloading goes down by the same step).
const STEPS: usize = 100;

/// A JKR sphere (R = 1, E* = 1, w = 0.002) on free grids 128^2 .. `max_n`^2 of side 2.5
/// loaded contact radii: seconds per load step of the adhesive cycle and of warm-started
/// non-adhesive solves at the same approaches (those in contact), and their ratio.
pub fn run_adhesion(w: &mut dyn Write, max_n: usize) -> std::io::Result<()> {
    writeln!(
        w,
        "Adhesive cycle (bem3d::adhesion, JKR sphere R = 1, E* = 1, w = 0.002, loaded to 1.3 a0 in {STEPS} approach steps and unloaded by the same steps to separation, tolerance 1e-8) against the non-adhesive solver at the same approaches (warm-started, tolerance 1e-8; the two criteria differ: the adhesive one is the largest gap in contact over the length scale, the normal one a pressure-weighted mean gap), {} threads, {}\n",
        rayon::current_num_threads(),
        sysmem::cpu_model()
    )?;
    writeln!(
        w,
        "{:>6} | {:>8} | {:>14} | {:>14} | {:>10} | {:>14}",
        "grid", "steps", "adhesive [s]", "normal [s]", "ratio", "CG iter./step"
    )?;
    writeln!(w, "{}", "-".repeat(80))?;
    let (gamma, r) = (0.002, 1.0);
    let a0 = (4.5 * PI * gamma * r * r).cbrt();
    let d_max = (1.3 * a0).powi(2) / r;
    let l = 2.5 * 1.3 * a0;
    for n in [128usize, 256, 512, 1024] {
        if n > max_n.max(128) {
            break;
        }
        let heights = bem3d::mask::centred(n, l, |x, y| -(x * x + y * y) / (2.0 * r));
        let apex = heights.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        let dd = d_max / STEPS as f64;
        let mut approaches: Vec<f64> = (1..=STEPS).map(|k| dd * k as f64).collect();
        approaches.extend((0..10 * STEPS).map(|k| d_max - dd * k as f64));
        // Adhesive: until separation.
        let t0 = Instant::now();
        let op = NonPeriodicHalfSpace::new(n, n, l, l, 1.0);
        let mut c = match AdhesiveContact::new(op, &heights, None, gamma) {
            Ok(c) => c,
            Err(e) => return writeln!(w, "{n:>6} | error: {e}"),
        };
        let (mut steps, mut iterations) = (0usize, 0usize);
        for &d in &approaches {
            match c.step(Load::Approach(d + apex), 1e-8) {
                Ok(s) => {
                    steps += 1;
                    iterations += s.iterations;
                    if s.separated {
                        break;
                    }
                }
                Err(e) => return writeln!(w, "{n:>6} | error: {e}"),
            }
        }
        let adhesive = t0.elapsed().as_secs_f64() / steps as f64;
        // Non-adhesive, warm-started, at the approaches in contact.
        let t0 = Instant::now();
        let op = NonPeriodicHalfSpace::new(n, n, l, l, 1.0);
        let opts = SolverOptions::new(1e-8, 100_000);
        let mut solver = match ContactSolver::new(op, &heights, None) {
            Ok(s) => s,
            Err(e) => return writeln!(w, "{n:>6} | error: {e}"),
        };
        let mut last = None;
        let mut solves = 0usize;
        for &d in approaches.iter().filter(|d| **d > 0.0) {
            match solver.solve(Load::Approach(d), &opts, last.as_ref()) {
                Ok(s) => last = Some(s),
                Err(e) => return writeln!(w, "{n:>6} | error: {e}"),
            }
            solves += 1;
        }
        let normal = t0.elapsed().as_secs_f64() / solves as f64;
        writeln!(
            w,
            "{:>6} | {:>8} | {:>14.4e} | {:>14.4e} | {:>10.2} | {:>14.1}",
            format!("{n}^2"),
            steps,
            adhesive,
            normal,
            adhesive / normal,
            iterations as f64 / steps as f64
        )?;
    }
    Ok(())
}
