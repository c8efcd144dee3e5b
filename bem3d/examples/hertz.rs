use bem3d::*;
use std::f64::consts::PI;
fn main() {
    for n in [32usize, 64, 128, 256, 512] {
        let (l, r, e) = (1.0f64, 1.0f64, 1.0f64);
        let a = l / 4.0;
        let f = 4.0 * e * a.powi(3) / (3.0 * r);
        let h = l / n as f64;
        let z: Vec<f64> = (0..n * n)
            .map(|k| {
                let (x, y) = (
                    ((k % n) as f64 - (n / 2) as f64) * h,
                    ((k / n) as f64 - (n / 2) as f64) * h,
                );
                -(x * x + y * y) / 2.0
            })
            .collect();
        let t = std::time::Instant::now();
        let mut s = ContactSolver::new(NonPeriodicHalfSpace::new(n, n, l, l, e), &z, None).unwrap();
        let sol = s
            .solve(
                Load::Force(f),
                &SolverOptions {
                    tolerance: 1e-10,
                    max_iterations: 5000,
                },
                None,
            )
            .unwrap();
        let pmax = sol.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
        println!(
            "n={n} it={} t={:.3}s d_err={:.2e} p0_err={:.2e} a_area_err={:.2e} res={:.1e}",
            sol.iterations,
            t.elapsed().as_secs_f64(),
            (sol.approach / (a * a) - 1.0).abs(),
            (pmax / (2.0 * a / PI) - 1.0).abs(),
            ((sol.contact_area / PI).sqrt() / a - 1.0).abs(),
            sol.residual
        );
    }
}
