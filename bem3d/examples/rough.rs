use bem3d::*;
use mrd::roughness::synthesis::{surface, Amplitudes, Grid};
use mrd::roughness::SelfAffine;
use std::f64::consts::PI;
fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    for n in sizes {
        let spec = SelfAffine::new(0.8, 2.0 * PI, 4.0 * PI, 2.0 * PI * (n / 4) as f64).unwrap();
        let mut h = surface(
            &spec,
            &Grid::square(n, 1.0),
            1,
            0,
            Amplitudes::Deterministic,
        )
        .unwrap();
        let m = mrd::roughness::stats::surface_moments(&h, n, n, 1.0, 1.0);
        h.iter_mut().for_each(|v| *v *= 0.1 / m.rms_slope);
        let t = std::time::Instant::now();
        let mut s =
            ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None).unwrap();
        let sol = s
            .solve(
                Load::MeanPressure(0.01),
                &SolverOptions {
                    tolerance: 1e-10,
                    max_iterations: 20000,
                },
                None,
            )
            .unwrap();
        let el = t.elapsed().as_secs_f64();
        // FFT pair time
        let mut f = bem3d::fft::Fft2::new(n, n);
        let mut spec_buf = vec![rustfft::num_complex::Complex64::default(); f.spectrum_len()];
        let x = h.clone();
        let mut y = vec![0.0; n * n];
        let t2 = std::time::Instant::now();
        for _ in 0..10 {
            f.forward(&x, &mut spec_buf);
            f.inverse(&mut spec_buf, &mut y);
        }
        let pair = t2.elapsed().as_secs_f64() / 10.0;
        println!(
            "n={n} it={} t={el:.3}s per_it={:.2e} pairs/it={:.2} area={:.4} res={:.1e}",
            sol.iterations,
            el / sol.iterations as f64,
            el / sol.iterations as f64 / pair,
            sol.contact_area,
            sol.residual
        );
    }
}
