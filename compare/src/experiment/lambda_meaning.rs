//! The one meaning of lambda in every output, table and API: Eq. (76) as written,
//! C1D(q) = lambda q C2D(q) at the line's wavenumbers, the line synthesised from the same
//! C2D (same units, no rescaling) as the surface it stands for. `mrdw.line(lam=...)`,
//! `line_spectrum`, `LineSpectrum`, every scene's `lambda` key and the calibrated table
//! (`calibrated_lambda(H)`) all take it so.
//!
//! Several outputs compare reduced curves, each side over its own rms height (k against
//! f = F/(E* h L)). There lambda enters through the ratio of the line's rms height h1 to
//! the surface's h3 that it implies: pi h1^2 / h3^2, which [`rms_matched`] computes from
//! the spectrum alone. In the continuum it is lambda itself (Eq. 73 keeps h at
//! lambda = pi); on the discrete wavenumbers of an L x L surface and a line of length
//! L it is lambda times 1.01-1.53 (H from -1 to 3, bandwidth 32-128: the lattice and the
//! line sample the lowest wavenumbers differently), and on a punch face a little more.

use mrd::roughness::nested::{line_mean_square, surface_mean_square};
use std::f64::consts::PI;

/// Where the 3D surface's rms height is taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Face {
    /// The whole periodic L x L square.
    Square,
    /// The disc of diameter L inscribed in it (a punch face), its own mean subtracted,
    /// as the expectation over realisations.
    Disc,
}

/// pi h1^2 / h3^2 for the line with C1D = `lambda` q C2D (wavenumbers 2 pi k / L,
/// 1 <= k <= band) and the surface with C2D (wave vectors 0 < |k| <= band), both of side
/// `l` (`band`: the nested synthesis' bandwidth, or the spectrum's upper wavenumber over
/// 2 pi / L): the factor by which the line's reduced curve is shifted onto the
/// surface's (K1(f sqrt(pi / rms_matched))).
pub fn rms_matched(lambda: f64, c2d: &dyn Fn(f64) -> f64, band: f64, l: f64, face: Face) -> f64 {
    let line = line_mean_square(&|q| q * c2d(q), band, l);
    let surface = surface_mean_square(c2d, band, l, face == Face::Disc);
    PI * lambda * line / surface
}

#[cfg(test)]
mod tests {
    use super::*;
    use mrd::roughness::synthesis::{line, surface, Amplitudes, Grid};
    use mrd::roughness::SelfAffine;

    /// On the synthesis the API offers (`mrdw.line(lam=...)`, `mrdw.surface`), a line
    /// with C1D = pi q C2D is rougher than the surface by the factor the issue measured
    /// (q0 = 2 pi / L, q1 = B q0, B = 32, in mean square: H = -0.5: 1.02, 0: 1.05, 0.5:
    /// 1.15, 1: 1.25, 2: 1.40), and
    /// rms_matched(pi) predicts it to 1e-9 (deterministic amplitudes).
    #[test]
    fn the_line_is_rougher_than_the_surface_by_the_predicted_factor() {
        let (n, b) = (128, 32);
        let q0 = 2.0 * PI;
        for (hurst, seen) in [
            (-0.5, 1.02),
            (0.0, 1.05),
            (0.5, 1.15),
            (1.0, 1.25),
            (2.0, 1.40),
        ] {
            let edge = 1.0 + 1e-9;
            let s = SelfAffine::new(hurst, q0 / edge, q0 / edge, q0 * b as f64 * edge).unwrap();
            let h3 = surface(&s, &Grid::square(n, 1.0), 3, 0, Amplitudes::Deterministic).unwrap();
            let h1 = line(&s.to_line(PI), 8 * n, 1.0, 3, 0, Amplitudes::Deterministic).unwrap();
            let ms = |h: &[f64]| {
                let m = h.iter().sum::<f64>() / h.len() as f64;
                h.iter().map(|v| (v - m).powi(2)).sum::<f64>() / h.len() as f64
            };
            let ratio = ms(&h1) / ms(&h3);
            let band = b as f64 * edge;
            let predicted = rms_matched(PI, &|q| s.c2d(q), band, 1.0, Face::Square) / PI;
            assert!(
                (ratio / predicted - 1.0).abs() < 1e-9,
                "H = {hurst}: {ratio} vs {predicted}"
            );
            assert!(
                (ratio - seen).abs() < 0.01,
                "H = {hurst}: {ratio} vs {seen}"
            );
        }
    }

    /// As the lowest wavenumber falls below 2 pi / L (a roll-off at q_r = 2 pi / L with
    /// the spectrum flat below it down to q0), the discrete sums approach their
    /// integrals and the two meanings of lambda meet: pi h1^2 / h3^2 -> lambda.
    #[test]
    fn the_meanings_meet_in_the_continuum() {
        let l = 1.0;
        let mut last = f64::INFINITY;
        for down in [1.0, 4.0, 16.0, 64.0] {
            // Side L' = down L: wavenumbers 2 pi / L' below the roll-off at 2 pi / L.
            let side = down * l;
            let qr = 2.0 * PI / l;
            let band = 32.0 * down;
            let s = SelfAffine::new(1.0, 2.0 * PI / side * (1.0 - 1e-9), qr, qr * 32.5).unwrap();
            let gap = (rms_matched(PI, &|q| s.c2d(q), band, side, Face::Square) / PI - 1.0).abs();
            assert!(gap < last, "{down}: {gap} after {last}");
            last = gap;
        }
        assert!(last < 0.01, "{last}");
    }
}
