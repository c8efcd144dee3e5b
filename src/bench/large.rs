//! `mrdw bench large`: the 3D solver's memory and time on big periodic grids (4096^2 ..
//! 16384^2) at 0.1 %, 1 % and 20 % contact, each case in a fresh process so that its
//! peak resident memory is its own.
//!
//! The surface is the benchmark's self-affine one ([`super::reference_surface`]: H = 0.8,
//! rolled off below a quarter of the box, rms slope 0.1, E* = 1, box 1 x 1); the solve is
//! force-controlled to the tolerance 1e-10 of the solver's criterion and must also pass
//! its certificate (bem3d::solver docs). The caller's heights are dropped once the solver
//! holds its copy; before anything is allocated, the case checks the estimated peak of
//! the solve so run against the memory the process may use and refuses with the numbers. No reference solve at a tighter tolerance runs here (it would double
//! the time of the largest cases): the accuracy statement is the criterion and the
//! certificate the solve reports.

use super::common::{child_error, field, peak_memory_mib, reference_surface};
use std::io::Write;
use std::time::Instant;

/// Mean pressures of the cases (fractions of E*), with the contact fraction each gives
/// on the benchmark surface (about: the table reports the measured one).
pub const PRESSURES: [(f64, &str); 3] = [(5e-5, "0.1 %"), (5e-4, "1 %"), (1e-2, "20 %")];

/// Bytes per cell of the caller's heights (f64), counted in
/// [`bem3d::operator::BYTES_PER_CELL_PERIODIC`].
const HEIGHT_BYTES: f64 = 8.0;

/// Smallest grid side of the ladder.
const SMALLEST: usize = 4096;

/// One large case: prints `RESULT key=value ...`. `scaled`: the solver's choice for
/// its scaled direction vectors ([`bem3d::Paths::scaled_directions`]).
pub fn run_large_case(
    w: &mut dyn Write,
    n: usize,
    mean_pressure: f64,
    scaled: bem3d::Choice,
) -> Result<(), String> {
    use bem3d::*;
    if !(16..=16384).contains(&n) {
        return Err(format!("grid side n = {n} must lie in 16..=16384"));
    }
    if !(mean_pressure > 0.0 && mean_pressure < 1.0) {
        return Err(format!(
            "mean pressure {mean_pressure:e} must lie in (0, 1) (a fraction of E*)"
        ));
    }
    // Preflight: the solve's peak estimate without the caller's heights, which this
    // process drops once the solver has its copy (the synthesis' peak is smaller).
    let hs = bem3d::operator::HalfSpace {
        nx: n,
        ny: n,
        lx: 1.0,
        ly: 1.0,
        e_star: 1.0,
    };
    hs.validate().map_err(|e| e.to_string())?;
    let per_cell = bem3d::operator::BYTES_PER_CELL_PERIODIC - HEIGHT_BYTES;
    let estimate = (n * n) as f64 * per_cell + bem3d::operator::PROCESS_BYTES;
    sysmem::check_estimate(estimate, &format!("a {n} x {n} contact")).map_err(|e| e.to_string())?;
    let failed = |e: BemError| e.to_string();
    let t0 = Instant::now();
    let heights = reference_surface(n).map_err(|e| e.to_string())?;
    let synthesis = t0.elapsed().as_secs_f64();
    let synthesis_mem = peak_memory_mib().unwrap_or(0.0);
    let t1 = Instant::now();
    let op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
    let mut solver = ContactSolver::new(op, &heights, None).map_err(failed)?;
    drop(heights);
    let setup = t1.elapsed().as_secs_f64();
    let opts = SolverOptions {
        tolerance: 1e-10,
        max_iterations: 50_000,
        paths: Paths {
            scaled_directions: scaled,
            ..Default::default()
        },
        ..Default::default()
    };
    let t2 = Instant::now();
    let sol = solver
        .solve(Load::MeanPressure(mean_pressure), &opts, None)
        .map_err(failed)?;
    let solve = t2.elapsed().as_secs_f64();
    let mem = peak_memory_mib().unwrap_or(0.0);
    let cells = (n * n) as f64;
    writeln!(
        w,
        "RESULT kind=large n={n} mean_pressure={mean_pressure:e} threads={} synthesis={synthesis:e} setup={setup:e} solve={solve:e} iterations={} contact={:e} residual={:e} certificate={:e} synthesis_mem={synthesis_mem:.1} mem={mem:.1} bytes_per_cell={:.1} path={} scaled_directions={}",
        rayon::current_num_threads(),
        sol.iterations,
        sol.contact_cells as f64 / cells,
        sol.residual,
        sol.certificate,
        mem * 1024.0 * 1024.0 / cells,
        if sol.restricted() { "restricted" } else { "full" },
        sol.scaled_directions,
    )
    .map_err(|e| format!("writing to standard output: {e}"))
}

/// `mrdw bench large`: grids from 4096^2 (or `max_n`, if smaller) up to `max_n`, each
/// at the three [`PRESSURES`], each case in a fresh process (`mrdw bench-case large N
/// --mean-pressure P`); prints the table.
pub fn run_large(w: &mut dyn Write, max_n: usize) -> Result<(), String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut lines = Vec::new();
    let mut n = SMALLEST.min(max_n);
    while n <= max_n {
        for (p, _) in PRESSURES {
            let _ = writeln!(
                std::io::stderr(),
                "running {n}^2 at mean pressure {p:e} ..."
            );
            let out = std::process::Command::new(&exe)
                .args(["bench-case", "large", &n.to_string()])
                .args(["--mean-pressure", &p.to_string()])
                .output()
                .map_err(|e| e.to_string())?;
            let stdout = String::from_utf8_lossy(&out.stdout);
            match stdout.lines().find(|l| l.starts_with("RESULT")) {
                Some(l) if out.status.success() => lines.push(l.to_string()),
                _ => {
                    let reason = child_error(&out.stderr);
                    lines.push(format!("FAILED n={n} mean_pressure={p:e} {reason}"));
                }
            }
        }
        n *= 2;
    }
    print_large_table(w, &lines).map_err(|e| format!("writing to standard output: {e}"))?;
    every_case_failed(&lines)
}

/// An error when no case of a benchmark gave a result (the table above says why each
/// failed), so that the command's exit status shows it.
fn every_case_failed(lines: &[String]) -> Result<(), String> {
    if !lines.is_empty() && lines.iter().all(|l| l.starts_with("FAILED")) {
        return Err(format!(
            "every case of the benchmark failed ({} of {})",
            lines.len(),
            lines.len()
        ));
    }
    Ok(())
}

fn print_large_table(w: &mut dyn Write, lines: &[String]) -> std::io::Result<()> {
    writeln!(
        w,
        "{:>8} | {:>9} | {:>9} | {:>9} | {:>9} | {:>6} | {:>9} | {:>10} | {:>10} | {:>11} | {:>10}",
        "grid",
        "p / E*",
        "contact",
        "setup [s]",
        "solve [s]",
        "iters",
        "mem [MiB]",
        "B per cell",
        "residual",
        "certificate",
        "path"
    )?;
    writeln!(w, "{}", "-".repeat(126))?;
    for l in lines {
        if l.starts_with("FAILED") {
            writeln!(w, "{l}")?;
            continue;
        }
        writeln!(
            w,
            "{:>8} | {:>9.0e} | {:>8.3}% | {:>9.2} | {:>9.2} | {:>6} | {:>9.0} | {:>10.1} | {:>10.1e} | {:>11.1e} | {:>10}",
            format!("{}^2", field(l, "n")),
            field(l, "mean_pressure"),
            100.0 * field(l, "contact"),
            field(l, "setup"),
            field(l, "solve"),
            field(l, "iterations"),
            field(l, "mem"),
            field(l, "bytes_per_cell"),
            field(l, "residual"),
            field(l, "certificate"),
            l.split_whitespace()
                .find_map(|kv| kv.strip_prefix("path="))
                .unwrap_or("?"),
        )?;
    }
    writeln!(
        w,
        "\nperiodic self-affine surface H = 0.8, rms slope 0.1, E* = 1; tolerance 1e-10 and the certificate;"
    )?;
    writeln!(
        w,
        "mem = peak resident memory of the case's process (surface synthesis, solver, solution);"
    )?;
    writeln!(
        w,
        "setup = operator and solver; solve = the contact solve alone;"
    )?;
    writeln!(
        w,
        "path: full = the full-grid iteration, restricted = a candidate set (bem3d::solver docs)."
    )
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_benchmark_with_no_result_fails() {
        let ok = "RESULT n=1024".to_string();
        let failed = "FAILED n=1024 mean_pressure=1e-2 out of memory".to_string();
        assert!(super::every_case_failed(&[ok.clone(), failed.clone()]).is_ok());
        let err = super::every_case_failed(&[failed.clone(), failed]).unwrap_err();
        assert!(
            err.contains("every case of the benchmark failed (2 of 2)"),
            "{err}"
        );
    }
}
