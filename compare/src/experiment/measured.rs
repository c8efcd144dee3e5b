//! A measured topography made ready for the rough studies: the central square of the
//! map, its mean plane removed (instrument tilt), and its isotropic power spectrum
//! C2D(q) (radially averaged over a Hann window, so the map's non-periodic edges do not
//! leak power to high q), with what a user must know about it: the slope anisotropy the
//! isotropic average hides, and whether the spectrum shows a roll-off or still rises at
//! the scan's longest wavelength.

use crate::error::{CompareError, Result};
use mrd::roughness::stats::surface_psd;
use mrd::roughness::TabulatedSpectrum;
use std::f64::consts::PI;

/// The fewest pixels a side that a calibration accepts.
pub const MIN_PIXELS: usize = 32;

/// The slope anisotropy above which a warning says the isotropic PSD is a simplification.
pub const ANISOTROPY_WARN: f64 = 0.2;
/// The rms height, over the largest height before the plane is removed, below which a
/// map counts as flat (a tilted plane leaves about 1e-19 of it).
const FLAT: f64 = 1e-12;

/// A measured map reduced to what the studies use.
#[derive(Debug, Clone)]
pub struct Measured {
    /// Pixels a side of the square kept.
    pub n: usize,
    /// Its side L [length].
    pub side: f64,
    /// Heights of the square, row-major, mean plane removed [length].
    pub heights: Vec<f64>,
    /// Radially averaged PSD of the square (q [1/length], C2D [length^4]).
    pub psd: Vec<(f64, f64)>,
    /// (s_x^2 - s_y^2) / (s_x^2 + s_y^2), s the rms slopes along x and y by finite
    /// differences: 0 for an isotropic surface.
    pub anisotropy: f64,
    /// log-log slope of C2D over the lowest octaves against the rest; None when too few
    /// bins (fewer than three in each part).
    pub slopes: Option<(f64, f64)>,
    /// (rows, cols) of the map when only its central square was kept.
    pub cropped_from: Option<(usize, usize)>,
}

impl Measured {
    /// The map `data` (`rows x cols`, row-major, rows along y) of physical size `size`
    /// (lx, ly): its central square, detrended.
    pub fn new(data: &[f64], rows: usize, cols: usize, size: (f64, f64)) -> Result<Self> {
        let bad = |m: String| Err(CompareError::Scene(m));
        if rows < MIN_PIXELS || cols < MIN_PIXELS {
            return bad(format!(
                "topography: {rows} x {cols} pixels; a calibration needs at least {MIN_PIXELS} a side (its PSD spans half the pixels in wavenumber)"
            ));
        }
        if !(size.0.is_finite() && size.0 > 0.0 && size.1.is_finite() && size.1 > 0.0) {
            return bad(format!(
                "size = [{}, {}]: give the map's physical size [lx, ly] > 0 in the scene's length unit",
                size.0, size.1
            ));
        }
        let (dx, dy) = (size.0 / cols as f64, size.1 / rows as f64);
        if (dx / dy - 1.0).abs() > 1e-6 {
            return bad(format!(
                "size = [{}, {}] over {cols} x {rows} pixels gives pixels of {dx:.4e} x {dy:.4e}: the calibration needs square pixels",
                size.0, size.1
            ));
        }
        if let Some(i) = data.iter().position(|v| !v.is_finite()) {
            return bad(format!(
                "topography: undefined height at row {}, column {}: fill or crop the missing points first",
                i / cols + 1,
                i % cols + 1
            ));
        }
        let n = rows.min(cols);
        let (r0, c0) = ((rows - n) / 2, (cols - n) / 2);
        let mut heights: Vec<f64> = (0..n)
            .flat_map(|j| {
                data[(r0 + j) * cols + c0..(r0 + j) * cols + c0 + n]
                    .iter()
                    .copied()
            })
            .collect();
        let extent = heights.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        remove_plane(&mut heights, n);
        let rms = (heights.iter().map(|v| v * v).sum::<f64>() / (n * n) as f64).sqrt();
        // What a plane leaves in rounding: some 1e-16 of the heights' magnitude.
        if rms <= FLAT * extent || rms.is_nan() {
            return bad(format!(
                "topography: the map is flat once its mean plane is removed (rms height {rms:.3e} against heights up to {extent:.3e}): it has no roughness to calibrate"
            ));
        }
        let side = n as f64 * dx;
        let psd = windowed_psd(&heights, n, side);
        Ok(Self {
            n,
            side,
            anisotropy: anisotropy(&heights, n),
            slopes: slopes(&psd, side),
            cropped_from: (rows != cols).then_some((rows, cols)),
            heights,
            psd,
        })
    }

    /// The PSD as a spectrum, held flat from its lowest bin down to 2 pi / L.
    pub fn spectrum(&self) -> Result<TabulatedSpectrum> {
        TabulatedSpectrum::new(&self.psd)
            .map(|t| t.with_lowest_wavenumber(2.0 * PI / self.side))
            .map_err(|e| CompareError::Scene(format!("topography PSD: {e}")))
    }

    /// The spectrum a map of this one's spectrum could as well have given: a Gaussian
    /// random field with C2D = this map's estimate (Rayleigh amplitudes, random phases),
    /// synthesised on a periodic square half as large again so that the central n x n
    /// window cut from it is not periodic, then read by the same estimator as the map
    /// (plane removed, Hann window, radial bins), rows (q [1/length], C2D [length^4]).
    /// Below 2 pi / L the field's C2D is held at the table's first value, as the table
    /// holds it down to 2 pi / L: a measured surface extends beyond its scan, and what
    /// lies below the scan's wavenumber reaches its lowest bins through the window and
    /// the plane (with zero power there the surrogates' lowest bin reads 10-30 % less). Surrogate `s` of
    /// `seed`: the spread of these estimates around this one is the estimator's sampling
    /// uncertainty (a parametric bootstrap).
    pub fn surrogate_psd(&self, seed: u64, s: u64) -> Result<Vec<(f64, f64)>> {
        use mrd::roughness::synthesis::{surface_from, Amplitudes, Grid};
        let table = self.spectrum()?;
        let n = self.n;
        let m = (n + n / 2 + 1) & !1;
        let dx = self.side / n as f64;
        let q0 = 2.0 * PI / self.side;
        let big = surface_from(
            &|q| table.c2d(q.max(q0)),
            &Grid::square(m, m as f64 * dx),
            seed,
            s,
            Amplitudes::Gaussian,
        )
        .map_err(|e| CompareError::Scene(format!("topography: surrogate map: {e}")))?;
        let o = (m - n) / 2;
        let crop: Vec<f64> = (0..n)
            .flat_map(|j| big[(o + j) * m + o..(o + j) * m + o + n].iter().copied())
            .collect();
        Ok(Measured::new(&crop, n, n, (self.side, self.side))?.psd)
    }

    /// Whether the spectrum flattens at its longest wavelengths (a roll-off): the
    /// lowest octaves' slope less than half as steep as the rest's.
    pub fn rolloff_seen(&self) -> Option<bool> {
        self.slopes.map(|(low, rest)| low > 0.5 * rest)
    }

    /// Warnings a user must read before trusting a calibration of this map.
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        if let Some((r, c)) = self.cropped_from {
            w.push(format!(
                "topography: {r} x {c} pixels; the central {0} x {0} square is used (the punch is the disc inscribed in it)",
                self.n
            ));
        }
        if self.anisotropy.abs() > ANISOTROPY_WARN {
            w.push(format!(
                "topography: the mean square slopes along x and y differ by {:.0} % of their sum ((s_x^2 - s_y^2)/(s_x^2 + s_y^2) = {:.2}): the calibration uses the radially averaged, isotropic PSD and MRD lines of any direction; lambda describes an isotropic surface of that PSD",
                100.0 * self.anisotropy.abs(),
                self.anisotropy
            ));
        }
        match (self.slopes, self.rolloff_seen()) {
            (Some((low, rest)), Some(false)) => w.push(format!(
                "topography: no roll-off in the PSD (log-log slope {low:.2} over the lowest two octaves against {rest:.2} above): the spectrum still rises at the scan's longest wavelength, so the punch of diameter L = {:.4e} (the scan) sets q0 = 2 pi / L and lambda holds for that diameter; a larger contact sees a spectrum the map does not show",
                self.side
            )),
            (None, _) => w.push(
                "topography: too few PSD bins to tell whether the spectrum rolls off; lambda holds for a punch of the scan's diameter".into(),
            ),
            _ => {}
        }
        w
    }
}

/// Removes the least-squares plane a + b x + c y of an `n x n` map (pixel coordinates
/// centred, so the three normal equations decouple).
fn remove_plane(h: &mut [f64], n: usize) {
    let c = (n as f64 - 1.0) / 2.0;
    let (mut s0, mut sx, mut sy, mut xx) = (0.0, 0.0, 0.0, 0.0);
    for j in 0..n {
        for i in 0..n {
            let v = h[j * n + i];
            let (x, y) = (i as f64 - c, j as f64 - c);
            s0 += v;
            sx += v * x;
            sy += v * y;
            xx += x * x;
        }
    }
    let cells = (n * n) as f64;
    let (a, b, cy) = (s0 / cells, sx / xx, sy / xx);
    for j in 0..n {
        for i in 0..n {
            h[j * n + i] -= a + b * (i as f64 - c) + cy * (j as f64 - c);
        }
    }
}

/// Radially averaged PSD of the map under a separable Hann window, normalised by the
/// window's mean square so that a stationary surface keeps its power.
fn windowed_psd(h: &[f64], n: usize, side: f64) -> Vec<(f64, f64)> {
    let w: Vec<f64> = (0..n)
        .map(|i| (PI * (i as f64 + 0.5) / n as f64).sin().powi(2))
        .collect();
    let ms = w.iter().map(|v| v * v).sum::<f64>() / n as f64;
    let norm = 1.0 / ms; // the 2D window's mean square is ms^2; amplitude 1/ms
    let hw: Vec<f64> = (0..n * n)
        .map(|k| h[k] * w[k % n] * w[k / n] * norm)
        .collect();
    let bins = (n / 8).clamp(16, 64);
    surface_psd(&hw, n, n, side, side, bins)
}

/// Slope anisotropy from finite differences along x and y.
fn anisotropy(h: &[f64], n: usize) -> f64 {
    let (mut sx, mut sy) = (0.0, 0.0);
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let v = h[j * n + i];
            sx += (h[j * n + i + 1] - v).powi(2);
            sy += (h[(j + 1) * n + i] - v).powi(2);
        }
    }
    if sx + sy > 0.0 {
        (sx - sy) / (sx + sy)
    } else {
        0.0
    }
}

/// log-log slopes of the PSD over q < 4 (2 pi / L) (the lowest two octaves above the
/// window-smeared first mode) and over the rest.
fn slopes(psd: &[(f64, f64)], side: f64) -> Option<(f64, f64)> {
    let q1 = 2.0 * PI / side;
    let fit = |pts: Vec<&(f64, f64)>| -> Option<f64> {
        if pts.len() < 3 {
            return None;
        }
        let x: Vec<f64> = pts.iter().map(|p| p.0.ln()).collect();
        let y: Vec<f64> = pts.iter().map(|p| p.1.ln()).collect();
        mrd::rough_contact::fit_line(&x, &y).ok().map(|l| l.b)
    };
    let usable = psd.iter().filter(|p| p.0 >= 1.5 * q1 && p.1 > 0.0);
    let low = fit(usable.clone().filter(|p| p.0 < 4.0 * q1).collect())?;
    let rest = fit(usable.filter(|p| p.0 >= 4.0 * q1).collect())?;
    Some((low, rest))
}

#[cfg(test)]
mod tests {
    use super::*;
    use mrd::roughness::synthesis::{surface, Amplitudes, Grid};
    use mrd::roughness::SelfAffine;

    /// A periodic self-affine map with a roll-off at 4 (2 pi / L), tilted: the plane is
    /// removed to rounding, the PSD follows the spectrum (within 20 % in bins of many
    /// modes, 10 % in the mean over the bins from the roll-off to half the Nyquist
    /// wavenumber; one realisation), the roll-off is seen, and without one it is not.
    #[test]
    fn surrogates_scatter_as_their_bins_count_modes() {
        let (n, side) = (128, 1.0);
        let q0 = 2.0 * PI / side;
        let s = SelfAffine::new(0.8, q0, 4.0 * q0, PI * n as f64 / side).unwrap();
        let h = surface(&s, &Grid::square(n, side), 7, 0, Amplitudes::Gaussian).unwrap();
        let m = Measured::new(&h, n, n, (side, side)).unwrap();
        let draws: Vec<Vec<(f64, f64)>> = (0..48).map(|k| m.surrogate_psd(1, k).unwrap()).collect();
        assert_eq!(draws[5], m.surrogate_psd(1, 5).unwrap());
        // The same estimator, the same bins (at the same mean |q|).
        for d in &draws {
            assert_eq!(d.len(), m.psd.len());
            assert!(d.iter().zip(&m.psd).all(|(a, b)| a.0 == b.0));
        }
        let spread = |b: usize| {
            let r: Vec<f64> = draws.iter().map(|d| d[b].1 / m.psd[b].1).collect();
            let mean = r.iter().sum::<f64>() / r.len() as f64;
            let sd =
                (r.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (r.len() - 1) as f64).sqrt();
            (mean, sd / mean)
        };
        // The lowest bin (a few lattice points, mixed by the window) scatters by tens of
        // per cent; a bin of hundreds of modes by a few; on average the surrogates
        // reproduce the map's estimate above the roll-off (to 48 draws' resolution).
        // The lowest bin (the first annulus, mixed by the window) scatters by 90 %, and
        // its surrogates read two thirds of the power they were given (the plane and the
        // window take part of the longest wavelength): the estimator's own loss there,
        // which the surrogates repeat on the map's estimate. Bins of hundreds of modes
        // (above 20 x 2 pi / L) scatter by 10 % or less, and between 5 x 2 pi / L and
        // the last bin (whose upper half the table leaves empty) the surrogates
        // reproduce the map's estimate within 15 % (leakage of the red spectrum through
        // the window counted twice: the map's estimate is their input).
        let (mean_low, low) = spread(0);
        assert!(
            low > 0.5 && mean_low < 0.85,
            "lowest bin: {mean_low} +/- {low}"
        );
        let last = m.psd.len() - 1;
        for b in 0..last {
            let (mean, sd) = spread(b);
            if m.psd[b].0 > 20.0 * q0 {
                assert!(sd < 0.12, "bin {b}: relative sd {sd}");
            }
            if m.psd[b].0 > 5.0 * q0 {
                assert!((mean - 1.0).abs() < 0.15, "bin {b}: mean ratio {mean}");
            }
        }
    }

    #[test]
    fn a_tilted_synthetic_map_gives_back_its_spectrum() {
        let (n, side) = (256, 2.0);
        let q0 = 2.0 * PI / side;
        for (rolloff, seen) in [(4.0, true), (1.0, false)] {
            let s = SelfAffine::new(0.8, q0, rolloff * q0, PI * n as f64 / side).unwrap();
            let mut h =
                surface(&s, &Grid::square(n, side), 3, 0, Amplitudes::Deterministic).unwrap();
            let flat = h.clone();
            for j in 0..n {
                for i in 0..n {
                    h[j * n + i] += 0.3 + 1e-3 * i as f64 - 2e-3 * j as f64;
                }
            }
            let m = Measured::new(&h, n, n, (side, side)).unwrap();
            let mean = flat.iter().sum::<f64>() / flat.len() as f64;
            let mut check = flat.iter().map(|v| v - mean).collect::<Vec<_>>();
            remove_plane(&mut check, n);
            let worst = m
                .heights
                .iter()
                .zip(&check)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-12, "{worst}");
            // A bin of few modes scatters (the window mixes neighbouring modes, whose
            // phases are random): bins above 30 / L hold hundreds of modes.
            let (mut sum, mut bins) = (0.0, 0.0);
            for &(q, c) in &m.psd {
                if q > 1.2 * rolloff * q0 && q < 0.5 * PI * n as f64 / side {
                    let r = c / s.c2d(q);
                    sum += r;
                    bins += 1.0;
                    assert!(q < 30.0 || (r - 1.0).abs() < 0.2, "q = {q}: {r}");
                }
            }
            assert!((sum / bins - 1.0).abs() < 0.1, "mean ratio {}", sum / bins);
            assert_eq!(m.rolloff_seen(), Some(seen), "{:?}", m.slopes);
            assert!(m.anisotropy.abs() < 0.05, "{}", m.anisotropy);
        }
    }

    /// Bad maps are refused, each naming what is wrong.
    #[test]
    fn bad_maps_are_refused_by_name() {
        let ok = vec![0.0; 64 * 64];
        let err = |d: &[f64], r, c, s| Measured::new(d, r, c, s).unwrap_err().to_string();
        assert!(err(&ok[..16 * 64], 16, 64, (1.0, 1.0)).contains("16 x 64 pixels"));
        assert!(err(&ok, 64, 64, (1.0, 0.0)).contains("size"));
        assert!(err(&ok, 64, 64, (1.0, 2.0)).contains("square pixels"));
        let mut nan = ok.clone();
        nan[65] = f64::NAN;
        assert!(err(&nan, 64, 64, (1.0, 1.0)).contains("row 2, column 2"));
        // Streaks along x: slopes along y only.
        let streaks: Vec<f64> = (0..64 * 64)
            .map(|k| ((k / 64) as f64 * 0.7).sin())
            .collect();
        let m = Measured::new(&streaks, 64, 64, (1.0, 1.0)).unwrap();
        assert!(m.anisotropy < -0.9, "{}", m.anisotropy);
        assert!(m.warnings().iter().any(|w| w.contains("along x and y")));
    }
}
