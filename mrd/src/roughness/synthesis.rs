//! Random-phase synthesis of periodic rough surfaces (Eq. 71) and lines (Eq. 72).
//!
//! `h(x) = sum_q B(q) exp(i (q.x + phi(q)))` with `phi(-q) = -phi(q)` so that h is real,
//! `B2D = (2 pi / sqrt(Lx Ly)) sqrt(C2D)` (Eq. 71 for Lx = Ly = L) and
//! `B1D = sqrt(2 pi C1D / L)` (Eq. 72). The sums are inverse FFTs. Mean (q = 0) and
//! Nyquist modes are not populated. Each realisation draws from its own ChaCha8 stream
//! seeded by (seed, realisation), in a fixed order, so a realisation is the same whatever
//! the thread count or the set of realisations computed alongside it.

use super::spectrum::{LineSpectrum, SelfAffine};
use crate::error::{MrdError, Result};
use fftplans::Planned;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rustfft::num_complex::Complex64;
use std::f64::consts::PI;

/// Amplitude statistics of the Fourier modes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Amplitudes {
    /// |H(q)| = B(q) exactly, random phase (Eqs. 71-72 as written).
    #[default]
    Deterministic,
    /// Complex Gaussian modes with <|H(q)|^2> = B(q)^2 (Gaussian random field).
    Gaussian,
}

/// Stream for one realisation (SplitMix64 mixing of seed and index).
pub fn realisation_rng(seed: u64, realisation: u64) -> ChaCha8Rng {
    let mix = |mut z: u64| {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    };
    ChaCha8Rng::seed_from_u64(mix(seed ^ mix(realisation.wrapping_add(1))))
}

fn mode(rng: &mut ChaCha8Rng, b: f64, amps: Amplitudes) -> Complex64 {
    match amps {
        Amplitudes::Deterministic => Complex64::from_polar(b, 2.0 * PI * rng.random::<f64>()),
        Amplitudes::Gaussian => {
            // Box-Muller: |H|^2 is exponential with mean b^2, phase uniform.
            let u: f64 = rng.random::<f64>();
            let r = b * (-(1.0 - u).ln()).sqrt();
            Complex64::from_polar(r, 2.0 * PI * rng.random::<f64>())
        }
    }
}

fn check_size(n: usize) -> Result<()> {
    if n < 4 {
        return Err(MrdError::InvalidParameter {
            name: "grid points",
            value: n as f64,
            reason: "need at least 4 points per direction",
        });
    }
    Ok(())
}

/// A periodic grid of `ny x nx` points (row-major) covering `lx x ly`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub nx: usize,
    pub ny: usize,
    pub lx: f64,
    pub ly: f64,
}

impl Grid {
    pub fn square(n: usize, l: f64) -> Self {
        Self {
            nx: n,
            ny: n,
            lx: l,
            ly: l,
        }
    }
}

/// A periodic rough surface on `grid` (Eq. 71).
pub fn surface(
    spec: &SelfAffine,
    grid: &Grid,
    seed: u64,
    realisation: u64,
    amps: Amplitudes,
) -> Result<Vec<f64>> {
    surface_from(&|q| spec.c2d(q), grid, seed, realisation, amps)
}

/// A periodic rough surface on `grid` (Eq. 71) for any isotropic 2D spectrum `c2d(q)`.
/// The modes are drawn in grid order: the same seed on another grid gives another
/// surface (see [`upsample`] for one surface on several grids).
pub fn surface_from(
    c2d: &dyn Fn(f64) -> f64,
    grid: &Grid,
    seed: u64,
    realisation: u64,
    amps: Amplitudes,
) -> Result<Vec<f64>> {
    let Grid { nx, ny, lx, ly } = *grid;
    check_size(nx)?;
    check_size(ny)?;
    crate::error::positive("lx", lx)?;
    crate::error::positive("ly", ly)?;
    if !(lx * ly).is_normal() {
        return Err(MrdError::InvalidParameter {
            name: "lx x ly",
            value: lx * ly,
            reason: "the area must be a finite, normal number (sizes within about 1e-150..1e150)",
        });
    }
    let nc = nx / 2 + 1;
    // The half spectrum and the surface are alive together.
    let what = format!("a {ny} x {nx} surface");
    let half = sysmem::bytes(&[nc, ny], 16, &what)?;
    sysmem::check(
        half.saturating_add(sysmem::bytes(&[nx, ny], 8, &what)?),
        &what,
    )?;
    let mut rng = realisation_rng(seed, realisation);
    let norm = 2.0 * PI / (lx * ly).sqrt();
    // Half spectrum S[i][j] (column i = kx >= 0, row j = ky signed), column-major for the
    // y transforms.
    let mut s = sysmem::try_vec(nc * ny, Complex64::default(), &what)?;
    let signed = |j: usize| {
        if j <= ny / 2 {
            j as f64
        } else {
            j as f64 - ny as f64
        }
    };
    for i in 0..nc {
        if nx.is_multiple_of(2) && i == nx / 2 {
            continue; // Nyquist column
        }
        for j in 0..ny {
            if ny.is_multiple_of(2) && j == ny / 2 {
                continue; // Nyquist row
            }
            if i == 0 {
                // kx = 0 column: modes (0, ky) and (0, -ky) are conjugates; draw once.
                let jn = (ny - j) % ny;
                if j == 0 || jn < j {
                    continue;
                }
                let q = 2.0 * PI * (signed(j) / ly).abs();
                let h = mode(&mut rng, norm * c2d(q).sqrt(), amps);
                s[j] = h;
                s[jn] = h.conj();
                continue;
            }
            let q = 2.0 * PI * ((i as f64 / lx).powi(2) + (signed(j) / ly).powi(2)).sqrt();
            s[i * ny + j] = mode(&mut rng, norm * c2d(q).sqrt(), amps);
        }
    }
    let ifft_y = fftplans::inverse::<f64>(ny);
    ifft_y.process(&mut s); // all nc columns, each of length ny
    rows_to_real(&s, nx, ny, &what)
}

/// The real `ny x nx` field (row-major) of a half spectrum `s` already transformed along
/// y: `nx / 2 + 1` columns of `ny` values, column-major; each row's inverse real
/// transform, with the imaginary parts a real row cannot carry (kx = 0 and, for even
/// `nx`, the Nyquist column) dropped. `what` names the field in an out-of-memory error.
pub(crate) fn rows_to_real(s: &[Complex64], nx: usize, ny: usize, what: &str) -> Result<Vec<f64>> {
    let nc = nx / 2 + 1;
    let c2r = f64::real_inverse(nx);
    let mut row = vec![Complex64::default(); nc];
    let mut out = sysmem::try_vec(nx * ny, 0.0, what)?;
    for j in 0..ny {
        for i in 0..nc {
            row[i] = s[i * ny + j];
        }
        row[0].im = 0.0;
        if nx.is_multiple_of(2) {
            row[nc - 1].im = 0.0;
        }
        c2r.process(&mut row, &mut out[j * nx..(j + 1) * nx])
            .map_err(|e| MrdError::InvalidData(format!("inverse FFT: {e}")))?;
    }
    Ok(out)
}

/// A periodic rough line of `n` points over length `l` (Eq. 72) for any 1D spectrum
/// `c1d(q)`, e.g. one derived from a measured PSD.
pub fn line_from(
    c1d: &dyn Fn(f64) -> f64,
    n: usize,
    l: f64,
    seed: u64,
    realisation: u64,
    amps: Amplitudes,
) -> Result<Vec<f64>> {
    check_size(n)?;
    crate::error::positive("length", l)?;
    let nc = n / 2 + 1;
    let what = format!("a line of {n} points");
    sysmem::check(sysmem::bytes(&[n], 24, &what)?, &what)?;
    let mut rng = realisation_rng(seed, realisation);
    let mut s = sysmem::try_vec(nc, Complex64::default(), &what)?;
    for (k, sk) in s.iter_mut().enumerate().skip(1) {
        if n.is_multiple_of(2) && k == n / 2 {
            break;
        }
        let q = 2.0 * PI * k as f64 / l;
        *sk = mode(&mut rng, (2.0 * PI * c1d(q) / l).sqrt(), amps); // Eq. (72)
    }
    let c2r = f64::real_inverse(n);
    let mut out = sysmem::try_vec(n, 0.0, &what)?;
    c2r.process(&mut s, &mut out)
        .map_err(|e| MrdError::InvalidData(format!("inverse FFT: {e}")))?;
    Ok(out)
}

/// A periodic rough line of `n` points over length `l` (Eq. 72).
pub fn line(
    spec: &LineSpectrum,
    n: usize,
    l: f64,
    seed: u64,
    realisation: u64,
    amps: Amplitudes,
) -> Result<Vec<f64>> {
    line_from(&|q| spec.c1d(q), n, l, seed, realisation, amps)
}

/// Band-limited (spectral) interpolation of a periodic surface of `from` points onto the
/// finer grid `to` of the same size: the same Fourier modes, evaluated at more points.
/// The coarse grid's Nyquist modes, which [`surface_from`] never populates, are dropped.
/// Lets one random surface be solved on several grids (grid refinement).
pub fn upsample(h: &[f64], from: &Grid, to: &Grid) -> Result<Vec<f64>> {
    let (nx0, ny0, nx, ny) = (from.nx, from.ny, to.nx, to.ny);
    if h.len() != nx0 * ny0 || nx < nx0 || ny < ny0 || from.lx != to.lx || from.ly != to.ly {
        return Err(MrdError::InvalidData(format!(
            "upsample: {} values from a {ny0} x {nx0} grid onto {ny} x {nx} of the same size",
            h.len()
        )));
    }
    let transform_2d = |data: &mut [Complex64], nx: usize, ny: usize, inverse: bool| {
        let (fx, fy) = if inverse {
            (fftplans::inverse::<f64>(nx), fftplans::inverse::<f64>(ny))
        } else {
            (fftplans::forward::<f64>(nx), fftplans::forward::<f64>(ny))
        };
        fx.process(data); // rows
        let mut col = vec![Complex64::default(); ny];
        for i in 0..nx {
            for j in 0..ny {
                col[j] = data[j * nx + i];
            }
            fy.process(&mut col);
            for j in 0..ny {
                data[j * nx + i] = col[j];
            }
        }
    };
    let mut a: Vec<Complex64> = h.iter().map(|&v| Complex64::new(v, 0.0)).collect();
    transform_2d(&mut a, nx0, ny0, false);
    let signed = |m: usize, n: usize| m as i64 - if m > n / 2 { n as i64 } else { 0 };
    let nyquist = |m: usize, n: usize| n.is_multiple_of(2) && m == n / 2;
    let mut b = vec![Complex64::default(); nx * ny];
    let scale = 1.0 / (nx0 * ny0) as f64;
    for j in 0..ny0 {
        for i in 0..nx0 {
            if nyquist(i, nx0) || nyquist(j, ny0) {
                continue;
            }
            let (si, sj) = (signed(i, nx0), signed(j, ny0));
            let (ti, tj) = (
                si.rem_euclid(nx as i64) as usize,
                sj.rem_euclid(ny as i64) as usize,
            );
            b[tj * nx + ti] = a[j * nx0 + i] * scale;
        }
    }
    transform_2d(&mut b, nx, ny, true);
    Ok(b.iter().map(|c| c.re).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn upsampling_keeps_the_surface_and_its_modes() {
        // Band-limited: the fine surface passes through the coarse points, keeps the
        // moments, and equals a direct evaluation of the mode sum between them.
        let band = |q: f64| if (10.0..=40.0).contains(&q) { 1.0 } else { 0.0 };
        let (coarse, fine) = (
            Grid {
                nx: 16,
                ny: 8,
                lx: 1.0,
                ly: 0.5,
            },
            Grid {
                nx: 64,
                ny: 32,
                lx: 1.0,
                ly: 0.5,
            },
        );
        let h = surface_from(&band, &coarse, 3, 0, Amplitudes::Deterministic).unwrap();
        let f = upsample(&h, &coarse, &fine).unwrap();
        let m0 = crate::roughness::stats::surface_moments(&h, 16, 8, 1.0, 0.5);
        let tol = 1e-14 * m0.rms_height;
        for j in 0..8 {
            for i in 0..16 {
                assert!((f[4 * j * 64 + 4 * i] - h[j * 16 + i]).abs() < tol);
            }
        }
        let m1 = crate::roughness::stats::surface_moments(&f, 64, 32, 1.0, 0.5);
        assert!((m0.rms_height / m1.rms_height - 1.0).abs() < 1e-12);
        assert!((m0.rms_slope / m1.rms_slope - 1.0).abs() < 1e-12);
        // Midpoint of a cell from the coarse spectrum directly.
        let (x, y) = (0.5 * (1.0 / 16.0) * 3.0, 0.5 * (0.5 / 8.0) * 5.0);
        let mut direct = 0.0;
        for j in 0..8usize {
            for i in 0..16usize {
                let s = |m: usize, n: usize| m as f64 - if m > n / 2 { n as f64 } else { 0.0 };
                let (kx, ky) = (2.0 * PI * s(i, 16), 2.0 * PI * s(j, 8) / 0.5);
                let mut c = Complex64::default();
                for b in 0..8 {
                    for a in 0..16 {
                        let arg = -(kx * a as f64 / 16.0 + ky * b as f64 * 0.5 / 8.0);
                        c += h[b * 16 + a] * Complex64::from_polar(1.0, arg);
                    }
                }
                if i == 8 || j == 4 {
                    continue;
                }
                direct += (c * Complex64::from_polar(1.0, kx * x + ky * y)).re / 128.0;
            }
        }
        let (fi, fj) = (
            (x * 64.0).round() as usize,
            (y / 0.5 * 32.0).round() as usize,
        );
        assert!((f[fj * 64 + fi] - direct).abs() < tol);
        assert!(upsample(&h, &fine, &coarse).is_err());
    }
}
