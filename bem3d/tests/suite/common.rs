//! Surfaces and measures shared by the solver's tests.
#![allow(dead_code, clippy::needless_range_loop)]

use std::f64::consts::PI;

pub fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Heights of a sphere of radius r (peaks up) on an n x n grid of side l, its apex on
/// the centre of cell (n/2, n/2) (as in the peer codes' Hertz benchmark).
pub fn sphere(n: usize, l: f64, r: f64) -> Vec<f64> {
    let h = l / n as f64;
    let mut z = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (
                (i as f64 - (n / 2) as f64) * h,
                (j as f64 - (n / 2) as f64) * h,
            );
            z.push(-(x * x + y * y) / (2.0 * r));
        }
    }
    z
}

pub fn rough(nx: usize, ny: usize, seed: u64) -> Vec<f64> {
    // Deterministic smooth random-ish surface: a few sines with hashed phases.
    let mut h = vec![0.0; nx * ny];
    let mut state = seed;
    for m in 1..6 {
        for k in 0..3 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let ph = (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * PI;
            let (fx, fy) = (m as f64, (k as f64) - 1.0);
            for j in 0..ny {
                for i in 0..nx {
                    let arg =
                        2.0 * PI * (fx * i as f64 / nx as f64 + fy * j as f64 / ny as f64) + ph;
                    h[j * nx + i] += arg.cos() / (m * m) as f64;
                }
            }
        }
    }
    h
}

/// A periodic random self-affine surface on an `n x n` grid of side 1: spectral
/// amplitudes |k|^(-1-H) from the lowest wavenumber to n/4, phases from a fixed LCG,
/// scaled to rms height 0.01 (deterministic for a seed).
pub fn self_affine(n: usize, hurst: f64, seed: u64) -> Vec<f64> {
    use bem3d::fft::Fft2;
    use rustfft::num_complex::Complex64;
    let mut fft = Fft2::new(n, n);
    let nc = fft.nc();
    let mut spec = vec![Complex64::default(); fft.spectrum_len()];
    let mut state = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
    for c in 0..nc {
        for r in 0..n {
            let ky = if r <= n / 2 {
                r as f64
            } else {
                r as f64 - n as f64
            };
            let k = (c as f64 * c as f64 + ky * ky).sqrt();
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let ph = (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * PI;
            if k >= 1.0 && k <= n as f64 / 4.0 {
                spec[c * n + r] = Complex64::from_polar(k.powf(-1.0 - hurst), ph);
            }
        }
    }
    let mut h = vec![0.0; n * n];
    fft.inverse(&mut spec, &mut h);
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    let rms = (h.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / h.len() as f64).sqrt();
    h.iter_mut().for_each(|v| *v = 0.01 * (*v - mean) / rms);
    h
}

/// Solves the dense system `a x = b` (`a` row-major, n x n) by Gaussian elimination with
/// partial pivoting, and checks the result: the residual |a x - b| must be within 1e-9 of
/// |a| |x| + |b| (max norms), so a singular or ill-conditioned system fails loudly
/// instead of returning a wrong reference.
///
/// Written out here rather than taken from a linear-algebra crate: such a crate, as a
/// test dependency, changes the features of crates the solver itself uses (integer
/// support of `num-integer` below `rustfft`), and `cargo test` would then rebuild the
/// whole workspace after `cargo build`.
pub fn dense_solve(a: &[f64], b: &[f64]) -> Vec<f64> {
    let n = b.len();
    assert_eq!(a.len(), n * n);
    let (mut m, mut x) = (a.to_vec(), b.to_vec());
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| m[i * n + col].abs().total_cmp(&m[j * n + col].abs()))
            .unwrap();
        assert!(m[piv * n + col] != 0.0, "singular system at column {col}");
        if piv != col {
            for k in 0..n {
                m.swap(piv * n + k, col * n + k);
            }
            x.swap(piv, col);
        }
        for r in col + 1..n {
            let f = m[r * n + col] / m[col * n + col];
            if f != 0.0 {
                for k in col..n {
                    m[r * n + k] -= f * m[col * n + k];
                }
                x[r] -= f * x[col];
            }
        }
    }
    for r in (0..n).rev() {
        let s: f64 = (r + 1..n).map(|k| m[r * n + k] * x[k]).sum();
        x[r] = (x[r] - s) / m[r * n + r];
    }
    let max = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |a, b| a.max(b.abs()));
    let residual =
        max(&mut (0..n).map(|r| (0..n).map(|k| a[r * n + k] * x[k]).sum::<f64>() - b[r]));
    let scale = max(&mut a.iter().copied()) * max(&mut x.iter().copied()) * n as f64
        + max(&mut b.iter().copied());
    assert!(
        residual <= 1e-9 * scale,
        "dense solve: residual {residual:e} of {scale:e}"
    );
    x
}

/// Dense reference: the same discrete LCP solved by an active-set method with direct
/// solves ([`dense_solve`]) on the contact set, force-controlled.
/// `matrix`: row-major n x n influence matrix (need not be symmetric).
pub fn dense_reference(matrix: &[f64], z: &[f64], force: f64, area: f64) -> (Vec<f64>, f64) {
    let n = z.len();
    let mut active: Vec<bool> = vec![true; n];
    for _ in 0..200 {
        let idx: Vec<usize> = (0..n).filter(|&i| active[i]).collect();
        let m = idx.len();
        // [K_CC  -1] [p]   [-z_C]
        // [A 1^T  0] [d] = [ W  ]
        let mut a = vec![0.0; (m + 1) * (m + 1)];
        for r in 0..=m {
            for c in 0..=m {
                a[r * (m + 1) + c] = if r < m && c < m {
                    matrix[idx[r] * n + idx[c]]
                } else if r < m {
                    -1.0
                } else if c < m {
                    area
                } else {
                    0.0
                };
            }
        }
        let b: Vec<f64> = (0..=m)
            .map(|r| if r < m { -z[idx[r]] } else { force })
            .collect();
        let x = dense_solve(&a, &b);
        let mut p = vec![0.0; n];
        for (k, &i) in idx.iter().enumerate() {
            p[i] = x[k];
        }
        let d = x[m];
        let mut u = vec![0.0; n];
        for i in 0..n {
            u[i] = (0..n).map(|j| matrix[i * n + j] * p[j]).sum();
        }
        let mut changed = false;
        for i in 0..n {
            if active[i] && p[i] < 0.0 {
                active[i] = false;
                changed = true;
            }
        }
        if !changed {
            for i in 0..n {
                if !active[i] && u[i] + z[i] - d < -1e-15 {
                    active[i] = true;
                    changed = true;
                }
            }
        }
        if !changed {
            return (p, d);
        }
    }
    panic!("active set did not settle");
}

/// Rms gradient of a periodic `n x n` surface of side `l` (spectral derivatives).
pub fn rms_slope(h: &[f64], n: usize, l: f64) -> f64 {
    use bem3d::fft::Fft2;
    use rustfft::num_complex::Complex64;
    let mut fft = Fft2::new(n, n);
    let mut spec = vec![Complex64::default(); fft.spectrum_len()];
    fft.forward(h, &mut spec);
    let nc = fft.nc();
    let mut sum = 0.0;
    for c in 0..nc {
        for r in 0..n {
            if n.is_multiple_of(2) && c == n / 2 {
                continue;
            }
            let ky = if r <= n / 2 {
                r as f64
            } else {
                r as f64 - n as f64
            };
            let k2 = (2.0 * PI / l).powi(2) * ((c * c) as f64 + ky * ky);
            let w = if c == 0 { 1.0 } else { 2.0 };
            sum += w * k2 * spec[c * n + r].norm_sqr();
        }
    }
    (sum / (n * n) as f64 / (n * n) as f64).sqrt()
}

/// Largest absolute difference between two fields.
#[allow(dead_code)]
pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Asserts that `f` gives the same result, bit for bit, on a pool of one thread and on
/// a pool of three (sums whose order followed the thread count would differ).
pub fn same_on_1_and_3_threads<R: Send + PartialEq + std::fmt::Debug>(
    f: impl Fn() -> R + Send + Sync,
) {
    assert_eq!(on_threads(1, &f), on_threads(3, &f));
}

/// `f` on a rayon pool of `threads` threads (for the thread-count determinism tests).
pub fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
        .install(f)
}
