//! Nested random-phase surfaces and lines: each Fourier mode's phase is a hash of (seed,
//! realisation, wave vector), not a draw from a sequential stream, so one realisation is
//! one continuous surface whatever the grid it is sampled on and whatever band it is
//! cut to. The surface of bandwidth B (modes with |k| <= B, wavenumbers in units of
//! 2 pi / L) contains exactly the modes of every narrower band; sampled on n x n cells
//! (n > 2 B) it is the same function at any n. Studies of bandwidth and resolution
//! then compare paired surfaces, and their differences carry no sampling noise of the
//! shared modes.
//!
//! Amplitudes as Eq. (71) (|H(q)| = 2 pi / L sqrt(C2D(q)), deterministic) and Eq. (72)
//! (sqrt(2 pi C1D(q) / L)); the mean mode is empty. [`surface_with`] and [`line_with`]
//! also draw Gaussian modes (each amplitude times a hashed Rayleigh factor): the same
//! spectrum in the mean, with the amplitude statistics of a Gaussian random field.

use super::synthesis::{Amplitudes, Grid};
use crate::error::{MrdError, Result};
use fftplans::Planned;
use rustfft::num_complex::Complex64;
use std::f64::consts::{PI, TAU};

/// SplitMix64's finaliser.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The phase in [0, 2 pi) of mode (i, j) of `realisation`.
fn phase(seed: u64, realisation: u64, i: i64, j: i64) -> f64 {
    let h = mix(mix(mix(seed ^ 0x6E65_7374_6564) ^ realisation) ^ i as u64) ^ (j as u64);
    let h = mix(h);
    TAU * (h >> 11) as f64 / (1u64 << 53) as f64
}

/// A Rayleigh factor of mean square 1 for mode (i, j) of `realisation`: sqrt(-ln(1 - u))
/// with u uniform in [0, 1) from a hash independent of the phase's, so that the mode's
/// |H|^2 is exponential with the spectrum's mean (a Gaussian random field).
fn rayleigh(seed: u64, realisation: u64, i: i64, j: i64) -> f64 {
    let h = mix(mix(mix(seed ^ 0x616D_706C_6974) ^ realisation) ^ i as u64) ^ (j as u64);
    let u = (mix(h) >> 11) as f64 / (1u64 << 53) as f64;
    (-(-u).ln_1p()).sqrt()
}

fn check(n: usize, band: usize) -> Result<()> {
    if band < 1 || n <= 2 * band {
        return Err(MrdError::InvalidParameter {
            name: "grid points",
            value: n as f64,
            reason: "must exceed twice the bandwidth (the band's modes below Nyquist)",
        });
    }
    Ok(())
}

/// Realisation `realisation` of the isotropic spectrum `c2d` on the square `grid`
/// (nx = ny = n, side L = lx = ly), cut to the wave vectors |k| <= `band` (in units of
/// 2 pi / L, k != 0).
pub fn surface(
    c2d: &dyn Fn(f64) -> f64,
    band: usize,
    grid: &Grid,
    seed: u64,
    realisation: u64,
) -> Result<Vec<f64>> {
    surface_with(
        c2d,
        band,
        grid,
        seed,
        realisation,
        Amplitudes::Deterministic,
    )
}

/// [`surface`] with the amplitude statistics `amps`: [`Amplitudes::Deterministic`] is
/// [`surface`] bit for bit; [`Amplitudes::Gaussian`] scales each mode by a Rayleigh factor
/// of mean square 1, hashed from (seed, realisation, wave vector) as the phase is, so the
/// surface stays nested.
pub fn surface_with(
    c2d: &dyn Fn(f64) -> f64,
    band: usize,
    grid: &Grid,
    seed: u64,
    realisation: u64,
    amps: Amplitudes,
) -> Result<Vec<f64>> {
    let Grid { nx, ny, lx, ly } = *grid;
    if nx != ny || lx != ly {
        return Err(MrdError::InvalidData(format!(
            "nested surfaces are square: got {ny} x {nx} over {lx} x {ly}"
        )));
    }
    let (n, l) = (nx, lx);
    check(n, band)?;
    crate::error::positive("L", l)?;
    let what = format!("a {n} x {n} surface");
    sysmem::check(sysmem::bytes(&[n, n], 24, &what)?, &what)?;
    let nc = n / 2 + 1;
    let b = band as i64;
    let norm = TAU / l;
    // Half spectrum, column-major (column i = kx >= 0, rows ky signed).
    let mut s = sysmem::try_vec(nc * n, Complex64::default(), &what)?;
    for i in 0..=b {
        for j in -b..=b {
            let k2 = i * i + j * j;
            if k2 == 0 || k2 > b * b || (i == 0 && j < 0) {
                continue;
            }
            let q = TAU / l * (k2 as f64).sqrt();
            let modulus = norm * c2d(q).sqrt();
            let modulus = match amps {
                Amplitudes::Deterministic => modulus,
                Amplitudes::Gaussian => modulus * rayleigh(seed, realisation, i, j),
            };
            let h = Complex64::from_polar(modulus, phase(seed, realisation, i, j));
            let row = j.rem_euclid(n as i64) as usize;
            s[i as usize * n + row] = h;
            if i == 0 {
                s[(n - row) % n] = h.conj();
            }
        }
    }
    fftplans::inverse::<f64>(n).process(&mut s[..(b as usize + 1) * n]);
    super::synthesis::rows_to_real(&s, n, n, &what)
}

/// Realisation `realisation` of the 1D spectrum `c1d` on `n` points over length `l`,
/// cut to the wavenumbers k <= `band` (units of 2 pi / L, k >= 1).
pub fn line(
    c1d: &dyn Fn(f64) -> f64,
    band: usize,
    n: usize,
    l: f64,
    seed: u64,
    realisation: u64,
) -> Result<Vec<f64>> {
    line_with(
        c1d,
        band,
        n,
        l,
        seed,
        realisation,
        Amplitudes::Deterministic,
    )
}

/// [`line`] with the amplitude statistics `amps` (as [`surface_with`]: deterministic is
/// [`line`] bit for bit, Gaussian a hashed Rayleigh factor of mean square 1 per mode).
pub fn line_with(
    c1d: &dyn Fn(f64) -> f64,
    band: usize,
    n: usize,
    l: f64,
    seed: u64,
    realisation: u64,
    amps: Amplitudes,
) -> Result<Vec<f64>> {
    check(n, band)?;
    crate::error::positive("L", l)?;
    let what = format!("a line of {n} points");
    sysmem::check(sysmem::bytes(&[n], 24, &what)?, &what)?;
    let mut s = sysmem::try_vec(n / 2 + 1, Complex64::default(), &what)?;
    for (k, sk) in s.iter_mut().enumerate().take(band + 1).skip(1) {
        let q = TAU * k as f64 / l;
        let b = (2.0 * PI * c1d(q) / l).sqrt(); // Eq. (72)
        let b = match amps {
            Amplitudes::Deterministic => b,
            Amplitudes::Gaussian => b * rayleigh(seed ^ 0x4C49_4E45, realisation, k as i64, 0),
        };
        *sk = Complex64::from_polar(b, phase(seed ^ 0x4C49_4E45, realisation, k as i64, 0));
    }
    let mut out = sysmem::try_vec(n, 0.0, &what)?;
    f64::real_inverse(n)
        .process(&mut s, &mut out)
        .map_err(|e| MrdError::InvalidData(format!("inverse FFT: {e}")))?;
    Ok(out)
}

/// The mean square height of every realisation of [`line`] with `c1d`, `band` and length
/// `l` (Parseval: deterministic amplitudes, so the same for every realisation): the sum
/// over 1 <= k <= band of 2 (2 pi / L) C1D(2 pi k / L). The same holds for the lines of
/// [`super::synthesis`] with deterministic amplitudes, `band` then the spectrum's upper
/// wavenumber over 2 pi / L (the spectrum is zero beyond it).
pub fn line_mean_square(c1d: &dyn Fn(f64) -> f64, band: f64, l: f64) -> f64 {
    (1..=band.floor() as usize)
        .map(|k| 2.0 * TAU / l * c1d(TAU * k as f64 / l))
        .sum()
}

/// The mean square height of [`surface`] with `c2d` and `band` on the square of side `l`:
/// over the whole square (`disc` false: the sum over wave vectors 0 < |k| <= band of
/// (2 pi / L)^2 C2D(q), the same for every realisation), or over the inscribed disc with
/// the disc's mean subtracted (`disc` true), as its expectation over realisations:
/// each mode loses the square of its disc average 2 J1(q a) / (q a), a = L / 2 (random
/// phases make the modes' disc averages uncorrelated). As for [`line_mean_square`], the
/// surfaces of [`super::synthesis`] too, `band` the spectrum's upper wavenumber over
/// 2 pi / L.
pub fn surface_mean_square(c2d: &dyn Fn(f64) -> f64, band: f64, l: f64, disc: bool) -> f64 {
    let b = band.floor() as i64;
    let mut sum = 0.0;
    for i in -b..=b {
        for j in -b..=b {
            let k2 = i * i + j * j;
            if k2 == 0 || (k2 as f64) > band * band {
                continue;
            }
            let q = TAU / l * (k2 as f64).sqrt();
            let kept = if disc {
                let x = 0.5 * q * l;
                1.0 - (2.0 * libm::j1(x) / x).powi(2)
            } else {
                1.0
            };
            sum += (TAU / l).powi(2) * c2d(q) * kept;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::roughness::stats::{line_moments, surface_moments};

    fn at(h: &[f64], n: usize, x: f64, y: f64) -> f64 {
        h[(y * n as f64).round() as usize * n + (x * n as f64).round() as usize]
    }

    /// The mean squares of lines and surfaces from the spectrum alone: exact for every
    /// line and for the whole square, the disc's within the spread of 400 realisations.
    #[test]
    fn mean_squares_from_the_spectrum() {
        let c2d = |q: f64| q.powf(-2.0 * 0.7 - 2.0);
        let c1d = |q: f64| PI * q * c2d(q);
        let (band, n) = (12, 64);
        let line_ms = line_mean_square(&c1d, band as f64, 2.0);
        for r in 0..3 {
            let z = line(&c1d, band, 8 * band, 2.0, 5, r).unwrap();
            let mean = z.iter().sum::<f64>() / z.len() as f64;
            let m = z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / z.len() as f64;
            assert!((m / line_ms - 1.0).abs() < 1e-12, "{m} {line_ms}");
        }
        let g = Grid::square(n, 1.0);
        let square = surface_mean_square(&c2d, band as f64, 1.0, false);
        let disc = surface_mean_square(&c2d, band as f64, 1.0, true);
        let mask = bem3d_free_disc(n);
        let cells = mask.iter().filter(|&&m| m).count() as f64;
        let mut on_disc = Vec::new();
        for r in 0..400 {
            let h = surface(&c2d, band, &g, 7, r).unwrap();
            let m = surface_moments(&h, n, n, 1.0, 1.0).rms_height.powi(2);
            assert!((m / square - 1.0).abs() < 1e-12, "{m} {square}");
            let mean = h
                .iter()
                .zip(&mask)
                .filter(|p| *p.1)
                .map(|p| p.0)
                .sum::<f64>()
                / cells;
            let var = h
                .iter()
                .zip(&mask)
                .filter(|p| *p.1)
                .map(|p| (p.0 - mean).powi(2))
                .sum::<f64>()
                / cells;
            on_disc.push(var);
        }
        let k = on_disc.len() as f64;
        let mean = on_disc.iter().sum::<f64>() / k;
        let se = (on_disc.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (k - 1.0) / k).sqrt();
        assert!(
            (mean - disc).abs() < 4.0 * se + 1e-3 * disc,
            "{mean} +/- {se} vs {disc}"
        );
        // The disc keeps less of the long waves than the square.
        assert!(disc < square, "{disc} {square}");
    }

    /// The inscribed disc of an n x n map of side 1 (cell centres within 1/2 of the
    /// centre), as the punch faces use it.
    fn bem3d_free_disc(n: usize) -> Vec<bool> {
        let h = 1.0 / n as f64;
        (0..n * n)
            .map(|k| {
                let x = ((k % n) as f64 + 0.5) * h - 0.5;
                let y = ((k / n) as f64 + 0.5) * h - 0.5;
                x * x + y * y <= 0.25
            })
            .collect()
    }

    #[test]
    fn one_realisation_is_one_surface_on_every_grid() {
        // Band 6 on 16^2 and on 64^2: equal at the shared points to rounding.
        let c = |q: f64| q.powf(-3.0);
        let g = |n| Grid::square(n, 1.0);
        let coarse = surface(&c, 6, &g(16), 9, 4).unwrap();
        let fine = surface(&c, 6, &g(64), 9, 4).unwrap();
        let rms = surface_moments(&coarse, 16, 16, 1.0, 1.0).rms_height;
        for j in 0..16 {
            for i in 0..16 {
                let (x, y) = (i as f64 / 16.0, j as f64 / 16.0);
                assert!((at(&coarse, 16, x, y) - at(&fine, 64, x, y)).abs() < 1e-12 * rms);
            }
        }
    }

    #[test]
    fn a_wider_band_adds_modes_and_keeps_the_narrower_ones() {
        // h(band 12) - h(band 6) holds only modes 6 < |k| <= 12: its power is the
        // spectrum's over that annulus, and the variances add (orthogonal modes).
        let c = |q: f64| q.powf(-3.0);
        let g = Grid::square(32, 1.0);
        let narrow = surface(&c, 6, &g, 1, 0).unwrap();
        let wide = surface(&c, 12, &g, 1, 0).unwrap();
        let diff: Vec<f64> = wide.iter().zip(&narrow).map(|(a, b)| a - b).collect();
        let m = |h: &[f64]| surface_moments(h, 32, 32, 1.0, 1.0).rms_height.powi(2);
        let (vn, vw, vd) = (m(&narrow), m(&wide), m(&diff));
        assert!((vw - vn - vd).abs() < 1e-12 * vw, "{vw} {vn} {vd}");
        // Exact variance: sum over the annulus of |H|^2 = (2 pi / L)^2 C2D(q).
        let mut want = 0.0;
        for i in -12i64..=12 {
            for j in -12i64..=12 {
                let k2 = (i * i + j * j) as f64;
                if k2 > 36.0 && k2 <= 144.0 {
                    want += TAU * TAU * c(TAU * k2.sqrt());
                }
            }
        }
        assert!((vd / want - 1.0).abs() < 1e-12, "{vd} {want}");
        // Realisations and seeds differ.
        assert_ne!(surface(&c, 6, &g, 1, 1).unwrap(), narrow);
        assert_ne!(surface(&c, 6, &g, 2, 0).unwrap(), narrow);
    }

    #[test]
    fn lines_nest_and_carry_the_spectrums_variance() {
        let c = |q: f64| q.powf(-2.0);
        let (a, b) = (
            line(&c, 8, 64, 2.0, 5, 3).unwrap(),
            line(&c, 8, 256, 2.0, 5, 3).unwrap(),
        );
        for k in 0..64 {
            assert!((a[k] - b[4 * k]).abs() < 1e-12);
        }
        // Variance sum_k |H_k|^2 (two-sided: each k and -k).
        let want: f64 = (1..=8)
            .map(|k| 2.0 * TAU * c(TAU * k as f64 / 2.0) / 2.0)
            .sum();
        let got = line_moments(&b, 2.0).rms_height.powi(2);
        assert!((got / want - 1.0).abs() < 1e-12, "{got} {want}");
        assert!(line(&c, 8, 16, 1.0, 0, 0).is_err());
    }

    /// Gaussian amplitudes: the mean square over realisations is the spectrum's (within
    /// three standard errors of 2000 surfaces and lines, whose single realisations now
    /// scatter), a surface is still one function on every grid, and the deterministic
    /// choice is `surface` bit for bit.
    #[test]
    fn gaussian_amplitudes_keep_the_mean_spectrum_and_the_nesting() {
        let c2d = |q: f64| q.powf(-2.0 * 0.7 - 2.0);
        let c1d = |q: f64| PI * q * c2d(q);
        let band = 4;
        let g = Grid::square(16, 1.0);
        let square = surface_mean_square(&c2d, band as f64, 1.0, false);
        let line_ms = line_mean_square(&c1d, band as f64, 1.0);
        let (mut s, mut s2, mut l, mut l2) = (0.0, 0.0, 0.0, 0.0);
        let count = 2000;
        for r in 0..count {
            let h = surface_with(&c2d, band, &g, 3, r, Amplitudes::Gaussian).unwrap();
            let m = surface_moments(&h, 16, 16, 1.0, 1.0).rms_height.powi(2) / square;
            s += m;
            s2 += m * m;
            let z = line_with(&c1d, band, 16, 1.0, 3, r, Amplitudes::Gaussian).unwrap();
            let m = z.iter().map(|v| v * v).sum::<f64>() / 16.0 / line_ms;
            l += m;
            l2 += m * m;
        }
        let n = count as f64;
        for (sum, sq, what) in [(s, s2, "surfaces"), (l, l2, "lines")] {
            let mean = sum / n;
            let se = ((sq / n - mean * mean) / n).sqrt();
            assert!(se > 1e-3, "{what}: Gaussian realisations must scatter");
            assert!((mean - 1.0).abs() < 3.0 * se, "{what}: {mean} +/- {se}");
        }
        let fine = surface_with(
            &c2d,
            band,
            &Grid::square(32, 1.0),
            3,
            5,
            Amplitudes::Gaussian,
        )
        .unwrap();
        let coarse = surface_with(&c2d, band, &g, 3, 5, Amplitudes::Gaussian).unwrap();
        for (x, y) in [(0.25, 0.5), (0.5, 0.75), (0.0, 0.125)] {
            assert!((at(&fine, 32, x, y) - at(&coarse, 16, x, y)).abs() < 1e-12);
        }
        assert_eq!(
            surface_with(&c2d, band, &g, 3, 5, Amplitudes::Deterministic).unwrap(),
            surface(&c2d, band, &g, 3, 5).unwrap()
        );
    }
}
