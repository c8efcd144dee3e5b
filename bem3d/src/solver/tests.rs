//! The solver's own checks: certificate, quantile, slope, lean large-grid handling and
//! stencil against transforms.

use super::*;
use crate::operator::{NonPeriodicHalfSpace, PeriodicHalfSpace};

/// An iterate the criterion alone accepts and the certificate refuses: every
/// pressure cell open by `tol h_rms` (complementarity at the tolerance) and a cell
/// without pressure interpenetrating by `tol h_rms` (interpenetration at the
/// tolerance): criterion tol, duality gap 2 tol.
#[test]
fn the_certificate_refuses_what_the_criterion_alone_accepts() {
    let tol = 1e-6;
    let p = [1.0, 2.0, 0.0, 0.0];
    let w = [tol, tol, -tol, 1.0];
    let mask = [1u8; 4];
    let [pg, ps, worst] = sweeps::criterion_terms(&p, &w, &mask, 0.0);
    let criterion = (pg / ps).max(worst);
    let [pg, ps, low] = sweeps::certificate_terms(&p, &w, &mask, 0.0);
    let certificate = pg / ps + low.max(0.0);
    assert!(criterion <= tol * (1.0 + 1e-12), "criterion {criterion:e}");
    assert!(
        (certificate - 2.0 * tol).abs() < 1e-18,
        "certificate {certificate:e}"
    );
}

/// The cold start's order statistic against a sort of the domain's heights, every
/// rank: many ties (heights on 7 levels), both signs of zero, a constant map, a
/// mask, and a grid of several chunks; a wrong bin or rank offset shows as a
/// different value.
#[test]
fn kth_height_matches_a_sort() {
    type Height = fn(usize) -> f64;
    let cases: [(usize, usize, Height); 5] = [
        (16, 12, |k| ((k * 7919) % 613) as f64 * 0.37 - 50.0),
        (16, 12, |k| ((k * 31) % 7) as f64),
        (8, 8, |k| if k % 2 == 0 { 0.0 } else { -0.0 }),
        (8, 8, |_| 2.5),
        (512, 40, |k| ((k * 2654435761) % 100_003) as f64 * 1e-3),
    ];
    for (nx, ny, height) in cases {
        let h: Vec<f64> = (0..nx * ny).map(height).collect();
        for masked in [false, true] {
            let mask = masked.then(|| (0..nx * ny).map(|k| k % 3 != 0).collect::<Vec<_>>());
            let op = PeriodicHalfSpace::new(nx, ny, 1.0, 1.0, 1.0);
            let s = ContactSolver::new(op, &h, mask).unwrap();
            let mut zs: Vec<f64> = (0..nx * ny)
                .filter(|&i| s.problem.mask.holds(i))
                .map(|i| s.problem.z.at(i))
                .collect();
            zs.sort_by(f64::total_cmp);
            let step = (zs.len() / 200).max(1);
            for k in (0..zs.len()).step_by(step).chain([zs.len() - 1]) {
                let got = s.problem.kth_height(k, s.chunk());
                assert_eq!(got.to_bits(), zs[k].to_bits(), "{nx}x{ny} rank {k}");
            }
        }
    }
}

/// The rms slope against closed forms: a periodic sine (every pair, the wrap-around
/// one included) and a parabola whose right half the mask leaves out (only pairs of
/// domain cells count).
#[test]
fn rms_slope_matches_closed_forms() {
    let (nx, ny, l) = (16, 6, 2.0);
    let dx = l / nx as f64;
    let sine: Vec<f64> = (0..nx * ny)
        .map(|k| (2.0 * std::f64::consts::PI * (k % nx) as f64 / nx as f64).sin())
        .collect();
    let s = ContactSolver::new(PeriodicHalfSpace::new(nx, ny, l, l, 1.0), &sine, None).unwrap();
    // (h[i+1] - h[i])^2 = 4 sin^2(pi/nx) cos^2(2 pi (i + 1/2)/nx): mean 2 sin^2(pi/nx).
    let want = 2f64.sqrt() * (std::f64::consts::PI / nx as f64).sin() / dx;
    assert!(
        (s.problem.slope_rms - want).abs() < 1e-12 * want,
        "{} {want}",
        s.problem.slope_rms
    );

    let parabola: Vec<f64> = (0..nx * ny)
        .map(|k| ((k % nx) as f64 * dx).powi(2))
        .collect();
    let mask: Vec<bool> = (0..nx * ny).map(|k| k % nx < nx / 2).collect();
    let op = NonPeriodicHalfSpace::new(nx, ny, l, l, 1.0);
    let s = ContactSolver::new(op, &parabola, Some(mask)).unwrap();
    // Pairs i, i + 1 < nx/2 along x: slope (2 i + 1) dx, mean square
    // dx^2 (4 m^2 - 1) / 3 over m = nx/2 - 1 pairs; along y the slope is zero.
    let m = (nx / 2 - 1) as f64;
    let want = dx * ((4.0 * m * m - 1.0) / 3.0).sqrt();
    assert!(
        (s.problem.slope_rms - want).abs() < 1e-12 * want,
        "{} {want}",
        s.problem.slope_rms
    );
}

/// The memory-lean handling of large grids (coarse solver released after a nested
/// start, the gap written over w, the update apart from a fresh double-precision
/// K p, the operator's symbols computed and its double-precision spectra held in w)
/// against the default on a grid where both run: the same bits through cold,
/// repeated and warm solves, under force and approach, and K's row buffer stays
/// sized for single precision.
#[test]
fn lean_large_grid_handling_changes_no_bit() {
    let n = 512;
    let h = crate::testing::on_unit_cell(n, |x, y| {
        let phase =
            |a: f64, b: f64, c: f64| (2.0 * std::f64::consts::PI * (a * x + b * y) + c).cos();
        0.01 * (phase(1.0, 2.0, 0.3) + 0.5 * phase(5.0, -3.0, 1.0) + 0.2 * phase(-11.0, 17.0, 2.0))
    });
    // Without the single-precision phase, every fresh K p is in double precision
    // (the early ones, while the contact set changes, too), and K t's double-precision
    // transform grows K's row buffer to its own size.
    for single_precision in [Choice::Allow, Choice::Forbid] {
        lean_against_default(n, &h, single_precision);
    }
}

fn lean_against_default(n: usize, h: &[f64], single_precision: Choice) {
    let opts = SolverOptions {
        tolerance: 1e-10,
        // The same iterates with and without the lean layout: directions in single
        // precision on both (scaled ones: their own test).
        paths: Paths {
            single_precision,
            scaled_directions: Choice::Forbid,
            ..Default::default()
        },
        ..Default::default()
    };
    let run = |large: usize| {
        let op = PeriodicHalfSpace::with_symbols(n, n, (1.0, 1.0), 1.0, large == 0);
        let mut s = ContactSolver::new(op, h, None).unwrap();
        s.tuning.large_grid_cells = large;
        let first = s.solve(Load::MeanPressure(2e-3), &opts, None).unwrap();
        let kept = s.coarse.is_some();
        let again = s.solve(Load::MeanPressure(2e-3), &opts, None).unwrap();
        let warm = s
            .solve(Load::MeanPressure(3e-3), &opts, Some(&again))
            .unwrap();
        let approach = s.solve(Load::Approach(warm.approach), &opts, None).unwrap();
        // Single-precision spectra: 8 bytes per complex value, n/2 + 1 per row.
        let single = 8 * n * (n / 2 + 1);
        let lean = large == 0 && single_precision == Choice::Allow;
        assert_eq!(s.op.row_buffer_bytes() == single, lean, "row buffer");
        (kept, [first, again, warm, approach])
    };
    let (kept, default) = run(LARGE_GRID_CELLS);
    let (kept_lean, lean) = run(0);
    assert!(
        kept && !kept_lean,
        "coarse solver kept: {kept}, {kept_lean}"
    );
    assert!(default[0].nested_start && lean[0].nested_start);
    for (a, b) in default.iter().zip(&lean) {
        assert!(a.gap.iter().any(|&g| g > 0.0) && a.contact_cells > 0);
        assert_eq!(
            (a.iterations, a.approach.to_bits()),
            (b.iterations, b.approach.to_bits())
        );
        let same = |x: &[f64], y: &[f64]| x.iter().zip(y).all(|(u, v)| u.to_bits() == v.to_bits());
        assert!(same(&a.pressure, &b.pressure) && same(&a.gap, &b.gap));
    }
}

/// M by its stencil (small contact sets) against M by its transforms: the same
/// solution at a tight tolerance, not the same iterates (the stencil path ran),
/// and the same bits on one and three threads. Periodic and free, square and not,
/// a few per cent of contact, the stencil forced (every contact set counts as
/// small) or off.
#[test]
fn stencil_and_transforms_reach_the_same_solution() {
    let rough = |nx: usize, ny: usize| -> Vec<f64> {
        (0..nx * ny)
            .map(|k| {
                let (x, y) = ((k % nx) as f64 / nx as f64, (k / nx) as f64 / ny as f64);
                (1..=6)
                    .map(|m| {
                        let (a, b) = ((m * 5 % 7) as f64, (m * 3 % 5) as f64 - 2.0);
                        let phase = 2.0 * std::f64::consts::PI * (a * x + b * y) + m as f64;
                        phase.cos() / m as f64
                    })
                    .sum::<f64>()
                    * 0.01
            })
            .collect()
    };
    fn run<K: crate::SolverOperator>(op: K, h: &[f64], fraction: f64, threads: usize) -> Solution {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut s = ContactSolver::new(op, h, None).unwrap();
            s.tuning.local_max_fraction = fraction;
            let opts = SolverOptions {
                tolerance: 1e-12,
                max_iterations: 5_000,
                ..Default::default()
            };
            s.solve(Load::MeanPressure(6e-3), &opts, None).unwrap()
        })
    }
    for (nx, ny, periodic) in [(64, 64, true), (48, 40, false), (40, 56, true)] {
        let h = rough(nx, ny);
        let solve = |fraction: f64, threads: usize| {
            if periodic {
                run(
                    PeriodicHalfSpace::new(nx, ny, 1.0, 1.0, 1.0),
                    &h,
                    fraction,
                    threads,
                )
            } else {
                run(
                    NonPeriodicHalfSpace::new(nx, ny, 1.0, 1.0, 1.0),
                    &h,
                    fraction,
                    threads,
                )
            }
        };
        let (by_transforms, by_stencil) = (solve(0.0, 2), solve(1.0, 2));
        let share = by_stencil.contact_cells as f64 / (nx * ny) as f64;
        assert!((0.01..0.3).contains(&share), "{nx}x{ny}: contact {share}");
        assert!(
            !by_stencil.restricted() && !by_transforms.restricted(),
            "{nx}x{ny}: {share}"
        );
        let peak = by_transforms.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
        let worst = by_transforms
            .pressure
            .iter()
            .zip(&by_stencil.pressure)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(worst <= 1e-9 * peak, "{nx}x{ny}: {worst:e} of {peak:e}");
        assert_ne!(
            by_transforms.pressure, by_stencil.pressure,
            "{nx}x{ny}: the stencil path did not run"
        );
        let one = solve(1.0, 1);
        let three = solve(1.0, 3);
        assert!(one
            .pressure
            .iter()
            .zip(&three.pressure)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
        assert!(one
            .pressure
            .iter()
            .zip(&by_stencil.pressure)
            .all(|(a, b)| a.to_bits() == b.to_bits()));
    }
}

/// The caller's heights read in place give the solve of a copy bit for bit: periodic
/// and free, force and approach, a mask, and a contact small enough for the window and
/// candidate-set paths (whose parts gather z from the heights).
#[test]
fn shared_heights_solve_as_a_copy_does() {
    let n = 96;
    let h = crate::testing::on_unit_cell(n, |x, y| {
        let bump = -((x - 0.5).powi(2) + (y - 0.5).powi(2));
        bump + 0.004 * (23.0 * x).sin() * (17.0 * y).cos() + 0.002 * (41.0 * y).sin()
    });
    let shared: SharedHeights = std::sync::Arc::new(h.clone());
    let mask: Vec<bool> = (0..n * n).map(|k| k % 7 != 3).collect();
    let opts = SolverOptions::new(1e-10, 10_000);
    let mut paths = Vec::new();
    for load in [Load::Force(1e-4), Load::Force(3e-3), Load::Approach(2e-3)] {
        for m in [None, Some(mask.clone())] {
            let periodic = || PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
            let a = ContactSolver::new(periodic(), &h, m.clone())
                .unwrap()
                .solve(load, &opts, None)
                .unwrap();
            let b = ContactSolver::new_shared(periodic(), shared.clone(), m.clone())
                .unwrap()
                .solve(load, &opts, None)
                .unwrap();
            let free = || NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
            let c = ContactSolver::new(free(), &h, m.clone())
                .unwrap()
                .solve(load, &opts, None)
                .unwrap();
            let d = ContactSolver::new_shared(free(), shared.clone(), m)
                .unwrap()
                .solve(load, &opts, None)
                .unwrap();
            for (x, y) in [(&a, &b), (&c, &d)] {
                let bits =
                    |s: &Solution| s.pressure.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(x), bits(y), "{load:?}");
                assert_eq!((x.iterations, x.path), (y.iterations, y.path), "{load:?}");
                paths.push(format!("{:?}", x.path));
            }
        }
    }
    paths.sort();
    paths.dedup();
    // Measured: the candidate set, the full grid and the window all ran.
    assert_eq!(paths, ["CandidateSet", "FullGrid", "Window"]);
}
