//! Property tests (proptest) of the 3D solver's invariances on small random grids:
//! a periodic solution moves with a circular shift of the surface, and any solution is
//! transposed with the surface. Each case is an independent check of the operators'
//! index conventions and of the solver's determinism.

use crate::common;
use bem3d::*;
use common::self_affine;
use proptest::prelude::*;

fn solve<K: SolverOperator>(op: K, h: &[f64], pm: f64) -> Solution {
    let mut s = ContactSolver::new(op, h, None).unwrap();
    s.solve(
        Load::MeanPressure(pm),
        &SolverOptions::new(1e-12, 5000),
        None,
    )
    .unwrap()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, &x| m.max(x.abs()))
}

/// A random rectangular surface cut from a periodic 32^2 self-affine one.
fn surface(nx: usize, ny: usize, seed: u64) -> Vec<f64> {
    let big = self_affine(32, 0.7, seed);
    (0..nx * ny).map(|k| big[(k / nx) * 32 + k % nx]).collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn periodic_solution_follows_a_circular_shift(
        nx in 6usize..20, ny in 6usize..20, sx in 0usize..20, sy in 0usize..20,
        seed in 0u64..1000, pm in 0.002f64..0.05,
    ) {
        let h = surface(nx, ny, seed);
        let (sx, sy) = (sx % nx, sy % ny);
        let shifted: Vec<f64> = (0..nx * ny)
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                h[((j + ny - sy) % ny) * nx + (i + nx - sx) % nx]
            })
            .collect();
        let (lx, ly) = (1.0, ny as f64 / nx as f64);
        let a = solve(PeriodicHalfSpace::new(nx, ny, lx, ly, 1.0), &h, pm);
        let b = solve(PeriodicHalfSpace::new(nx, ny, lx, ly, 1.0), &shifted, pm);
        let pmax = max_abs(&a.pressure);
        for k in 0..nx * ny {
            let (i, j) = (k % nx, k / nx);
            let moved = b.pressure[((j + sy) % ny) * nx + (i + sx) % nx];
            prop_assert!((a.pressure[k] - moved).abs() <= 1e-8 * pmax);
        }
        prop_assert!((a.approach - b.approach).abs() <= 1e-9 * a.approach.abs().max(1e-6));
    }

    #[test]
    fn solution_transposes_with_the_surface(
        nx in 5usize..18, ny in 5usize..18, seed in 0u64..1000, pm in 0.002f64..0.05,
        periodic in any::<bool>(),
    ) {
        let h = surface(nx, ny, seed);
        let t: Vec<f64> = (0..nx * ny).map(|k| h[(k % ny) * nx + k / ny]).collect();
        let (lx, ly) = (1.0, ny as f64 / nx as f64);
        let (a, b) = if periodic {
            (
                solve(PeriodicHalfSpace::new(nx, ny, lx, ly, 1.0), &h, pm),
                solve(PeriodicHalfSpace::new(ny, nx, ly, lx, 1.0), &t, pm),
            )
        } else {
            (
                solve(NonPeriodicHalfSpace::new(nx, ny, lx, ly, 1.0), &h, pm),
                solve(NonPeriodicHalfSpace::new(ny, nx, ly, lx, 1.0), &t, pm),
            )
        };
        let pmax = max_abs(&a.pressure);
        for j in 0..ny {
            for i in 0..nx {
                prop_assert!((a.pressure[j * nx + i] - b.pressure[i * ny + j]).abs() <= 1e-8 * pmax);
            }
        }
    }
}
