//! Isotropic power spectra of self-affine surfaces and their 1D images.
//!
//! Normalisation (Eq. 69): `C2D(q) = (2 pi)^-2 Int <h(x) h(0)> e^{-i q.x} d^2x`, so that
//! `<h^2> = 2 pi Int_0^inf q C2D(q) dq` (Eq. 74), `<|grad h|^2> = 2 pi Int q^3 C2D dq`,
//! `<(lap h)^2> = 2 pi Int q^5 C2D dq`. For a line, `<h^2> = 2 Int_0^inf C1D(q) dq`
//! (Eq. 75), slope and curvature with q^2 and q^4.
//!
//! The self-affine spectrum (Eq. 70) with Hurst exponent H in [-1, 3]:
//! `C2D(q) = C0 (q / q_r)^(-2H-2)` for `q_r <= q <= q_1`, a plateau `C0` for
//! `q_0 <= q < q_r` (roll-off; q_r = q_0 means none), and zero outside [q_0, q_1].
//! The 1D image is `C1D(q) = lambda(H) q C2D(q)` (Eq. 76), lambda = pi by default
//! (Eq. 73). A straight cut through an isotropic surface has
//! `lambda_cut(H) = sqrt(pi) Gamma(H + 1/2) / Gamma(H + 1)` (H > -1/2).

use crate::error::{positive, MrdError, Result};
use std::f64::consts::PI;

/// Int_a^b s^k ds, with the logarithmic case k = -1.
fn power_integral(a: f64, b: f64, k: f64) -> f64 {
    if (k + 1.0).abs() < 1e-12 {
        (b / a).ln()
    } else {
        (b.powf(k + 1.0) - a.powf(k + 1.0)) / (k + 1.0)
    }
}

/// lambda of a straight cut: `Int C2D(sqrt(q^2 + qy^2)) dqy = lambda_cut q C2D(q)` for a
/// power law C2D ~ q^(-2H-2); finite for H > -1/2.
pub fn lambda_cut(hurst: f64) -> Result<f64> {
    if hurst.is_nan() || hurst <= -0.5 || hurst.is_infinite() {
        return Err(MrdError::InvalidParameter {
            name: "hurst",
            value: hurst,
            reason: "the straight-cut lambda exists only for H > -1/2",
        });
    }
    Ok(PI.sqrt() * libm::tgamma(hurst + 0.5) / libm::tgamma(hurst + 1.0))
}

/// A calibrated table lambda(H), linearly interpolated; no extrapolation.
#[derive(Debug, Clone, PartialEq)]
pub struct LambdaTable {
    hurst: Vec<f64>,
    lambda: Vec<f64>,
}

impl LambdaTable {
    pub fn new(hurst: Vec<f64>, lambda: Vec<f64>) -> Result<Self> {
        if hurst.len() != lambda.len() || hurst.is_empty() {
            return Err(MrdError::InvalidData(
                "lambda table needs equal, non-empty columns".into(),
            ));
        }
        if hurst.iter().any(|h| h.is_nan()) || hurst.windows(2).any(|w| w[1] <= w[0]) {
            return Err(MrdError::InvalidData(
                "lambda table: H must increase strictly".into(),
            ));
        }
        if let Some(i) = lambda.iter().position(|l| !(l.is_finite() && *l > 0.0)) {
            return Err(MrdError::InvalidData(format!(
                "lambda table row {}: lambda must be > 0",
                i + 1
            )));
        }
        Ok(Self { hurst, lambda })
    }

    /// Parses CSV text with columns `hurst, lambda` (further columns ignored, `#` comments
    /// and one header line allowed).
    pub fn from_csv(text: &str) -> Result<Self> {
        let (mut h, mut l) = (Vec::new(), Vec::new());
        for (i, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let cols: Vec<&str> = line.split(',').map(str::trim).collect();
            match (
                cols.first().and_then(|c| c.parse::<f64>().ok()),
                cols.get(1).and_then(|c| c.parse::<f64>().ok()),
            ) {
                (Some(a), Some(b)) => {
                    h.push(a);
                    l.push(b);
                }
                _ if h.is_empty() && cols.first().is_some_and(|c| c.parse::<f64>().is_err()) => {}
                _ => {
                    return Err(MrdError::InvalidData(format!(
                        "lambda table line {}: `{line}`",
                        i + 1
                    )))
                }
            }
        }
        Self::new(h, l)
    }

    pub fn at(&self, hurst: f64) -> Result<f64> {
        let (h0, h1) = (self.hurst[0], *self.hurst.last().unwrap());
        if !(hurst >= h0 && hurst <= h1) {
            return Err(MrdError::OutsideTable {
                what: "hurst",
                value: hurst,
                lo: h0,
                hi: h1,
                table: "lambda table",
            });
        }
        let k = self
            .hurst
            .partition_point(|&x| x <= hurst)
            .clamp(1, self.hurst.len().max(2) - 1);
        if self.hurst.len() == 1 {
            return Ok(self.lambda[0]);
        }
        let t = (hurst - self.hurst[k - 1]) / (self.hurst[k] - self.hurst[k - 1]);
        Ok(self.lambda[k - 1] + t * (self.lambda[k] - self.lambda[k - 1]))
    }
}

/// The factor lambda of Eq. (76).
#[derive(Debug, Clone, PartialEq)]
pub enum Lambda {
    /// lambda = pi (Eq. 73).
    Pi,
    Value(f64),
    /// Straight-cut value lambda_cut(H).
    Cut,
    Table(LambdaTable),
}

impl Lambda {
    pub fn at(&self, hurst: f64) -> Result<f64> {
        match self {
            Lambda::Pi => Ok(PI),
            Lambda::Value(v) => positive("lambda", *v),
            Lambda::Cut => lambda_cut(hurst),
            Lambda::Table(t) => t.at(hurst),
        }
    }
}

/// rms height, slope and curvature from the spectral moments (Eqs. 74-75 and their
/// q^2, q^4 weighted versions).
pub trait SpectralMoments {
    /// Mean square of the k-th derivative-like moment: k = 0 height, 2 slope, 4 curvature.
    fn moment(&self, k: f64) -> f64;
    fn rms_height(&self) -> f64 {
        self.moment(0.0).sqrt()
    }
    fn rms_slope(&self) -> f64 {
        self.moment(2.0).sqrt()
    }
    fn rms_curvature(&self) -> f64 {
        self.moment(4.0).sqrt()
    }
}

/// Isotropic self-affine 2D spectrum with roll-off and cut-offs (Eq. 70).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfAffine {
    pub hurst: f64,
    /// Lower cut-off q_0: no roughness below.
    pub q0: f64,
    /// Roll-off q_r >= q_0: plateau below, power law above.
    pub qr: f64,
    /// Upper cut-off q_1.
    pub q1: f64,
    /// C2D at the plateau (q_0 <= q <= q_r).
    pub c0: f64,
}

impl SelfAffine {
    /// Spectrum with unit C0; see [`Self::with_rms_height`] and [`Self::with_rms_slope`].
    pub fn new(hurst: f64, q0: f64, qr: f64, q1: f64) -> Result<Self> {
        if !(-1.0..=3.0).contains(&hurst) {
            return Err(MrdError::InvalidParameter {
                name: "hurst",
                value: hurst,
                reason: "must lie in [-1, 3]",
            });
        }
        positive("q0", q0)?;
        positive("q1", q1)?;
        if !(qr >= q0 && q1 > qr) {
            return Err(MrdError::InvalidParameter {
                name: "qr",
                value: qr,
                reason: "need q0 <= qr < q1",
            });
        }
        Ok(Self {
            hurst,
            q0,
            qr,
            q1,
            c0: 1.0,
        })
    }

    pub fn c2d(&self, q: f64) -> f64 {
        if q < self.q0 || q > self.q1 {
            0.0
        } else if q < self.qr {
            self.c0
        } else {
            self.c0 * (q / self.qr).powf(-2.0 * self.hurst - 2.0)
        }
    }

    /// `2 pi Int q^(1+k) C2D(q) dq`: k = 0 mean square height, 2 slope, 4 curvature.
    fn moment_2d(&self, k: f64) -> f64 {
        let plateau = power_integral(self.q0, self.qr, 1.0 + k);
        // Int_qr^q1 q^(1+k) (q/qr)^(-2H-2) dq = qr^(2+k) Int_1^(q1/qr) s^(k-1-2H) ds
        let law = self.qr.powf(2.0 + k)
            * power_integral(1.0, self.q1 / self.qr, k - 1.0 - 2.0 * self.hurst);
        2.0 * PI * self.c0 * (plateau + law)
    }

    /// Rescales C0 so that the rms height is `h`.
    pub fn with_rms_height(mut self, h: f64) -> Result<Self> {
        positive("rms height", h)?;
        self.c0 *= h * h / self.moment(0.0);
        Ok(self)
    }
    /// Rescales C0 so that the rms slope is `s`.
    pub fn with_rms_slope(mut self, s: f64) -> Result<Self> {
        positive("rms slope", s)?;
        self.c0 *= s * s / self.moment(2.0);
        Ok(self)
    }

    /// The 1D image with factor `lambda` (Eq. 76).
    pub fn to_line(&self, lambda: f64) -> LineSpectrum {
        LineSpectrum {
            surface: *self,
            lambda,
        }
    }
}

/// A 2D spectrum tabulated at wavenumbers (e.g. a measured, radially averaged PSD),
/// interpolated log-log between points and zero outside their range.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedSpectrum {
    q: Vec<f64>,
    c2d: Vec<f64>,
    /// Lowest wavenumber the data represent (2 pi / L of the map); C2D is held at its
    /// first tabulated value between here and the first bin centre.
    q_min: f64,
}

impl TabulatedSpectrum {
    /// From (q, C2D) pairs with q increasing. Bins more than 12 decades below the peak
    /// (rounding-level power beyond a band limit, zeros) are dropped.
    pub fn new(points: &[(f64, f64)]) -> Result<Self> {
        let peak = points
            .iter()
            .map(|p| p.1)
            .filter(|c| c.is_finite())
            .fold(0.0f64, f64::max);
        let pts: Vec<(f64, f64)> = points
            .iter()
            .copied()
            .filter(|p| p.1.is_finite() && p.1 > 1e-12 * peak)
            .collect();
        if pts.len() < 2
            || pts.windows(2).any(|w| w[1].0 <= w[0].0)
            || pts.iter().any(|p| p.0.is_nan() || p.0 <= 0.0)
        {
            return Err(MrdError::InvalidData(
                "a tabulated spectrum needs >= 2 points with increasing q > 0".into(),
            ));
        }
        let q_min = pts[0].0;
        Ok(Self {
            q: pts.iter().map(|p| p.0).collect(),
            c2d: pts.iter().map(|p| p.1).collect(),
            q_min,
        })
    }

    /// Extends the table down to `q_min` (e.g. 2 pi / L of the measured map), holding
    /// the first value: the lowest radial bin's mean |q| lies above the lowest mode.
    pub fn with_lowest_wavenumber(mut self, q_min: f64) -> Self {
        if q_min > 0.0 && q_min < self.q[0] {
            self.q_min = q_min;
        }
        self
    }

    pub fn c2d(&self, q: f64) -> f64 {
        let (q0, q1) = (self.q[0], *self.q.last().unwrap());
        if q >= self.q_min * (1.0 - 1e-12) && q < q0 {
            return self.c2d[0];
        }
        if !(q >= q0 && q <= q1) {
            return 0.0;
        }
        let k = self
            .q
            .partition_point(|&x| x <= q)
            .clamp(1, self.q.len() - 1);
        let t = (q / self.q[k - 1]).ln() / (self.q[k] / self.q[k - 1]).ln();
        (self.c2d[k - 1].ln() + t * (self.c2d[k] / self.c2d[k - 1]).ln()).exp()
    }

    /// Number of tabulated bins and the ratio of the highest to the lowest bin's q: how
    /// much of a spectrum a fit of its exponent sees.
    pub fn extent(&self) -> (usize, f64) {
        (self.q.len(), self.q[self.q.len() - 1] / self.q[0])
    }

    /// Hurst exponent from a least-squares fit C2D ~ q^(-2H-2) over the table.
    pub fn fitted_hurst(&self) -> f64 {
        let x: Vec<f64> = self.q.iter().map(|q| q.ln()).collect();
        let y: Vec<f64> = self.c2d.iter().map(|c| c.ln()).collect();
        let n = x.len() as f64;
        let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
        let slope = x
            .iter()
            .zip(&y)
            .map(|(a, b)| (a - mx) * (b - my))
            .sum::<f64>()
            / x.iter().map(|a| (a - mx).powi(2)).sum::<f64>();
        -(slope + 2.0) / 2.0
    }
}

/// A 1D spectrum `C1D(q) = lambda q C2D(q)` (Eq. 76). A line defined directly by its own
/// power law C1D ~ q^(-2H-1) is the same object with lambda = 1 and C0 rescaled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineSpectrum {
    pub surface: SelfAffine,
    pub lambda: f64,
}

impl LineSpectrum {
    pub fn c1d(&self, q: f64) -> f64 {
        self.lambda * q.abs() * self.surface.c2d(q.abs()) // Eq. (76)
    }
}

impl SpectralMoments for SelfAffine {
    fn moment(&self, k: f64) -> f64 {
        self.moment_2d(k)
    }
}

impl SpectralMoments for LineSpectrum {
    /// `2 Int_0^inf q^k C1D dq = (lambda/pi) 2 pi Int q^(1+k) C2D dq`.
    fn moment(&self, k: f64) -> f64 {
        self.lambda / PI * self.surface.moment_2d(k)
    }
}

impl LineSpectrum {
    /// Rescales to rms height `h`.
    pub fn with_rms_height(mut self, h: f64) -> Result<Self> {
        positive("rms height", h)?;
        self.surface.c0 *= h * h / self.moment(0.0);
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::quad::tanh_sinh;

    #[test]
    fn lambda_cut_matches_quadrature_of_the_cut() {
        // Int_-inf^inf (1 + t^2)^(-H-1) dt, by t = cot(u) (singular end at u = 0).
        for &h in &[-0.4, 0.0, 0.3, 0.8, 1.0, 2.0, 3.0] {
            let num =
                2.0 * tanh_sinh(|u: f64| u.sin().powf(2.0 * h), 0.0, PI / 2.0, 1e-13).unwrap();
            assert!((num / lambda_cut(h).unwrap() - 1.0).abs() < 1e-10, "H={h}");
        }
        assert!((lambda_cut(0.5).unwrap() - 2.0).abs() < 1e-14); // sqrt(pi) Gamma(1)/Gamma(3/2)
        assert!(lambda_cut(-0.6).is_err());
    }

    #[test]
    fn moments_match_quadrature_for_all_hurst() {
        for &h in &[-1.0, -0.5, 0.0, 0.5, 1.0, 2.0, 3.0] {
            let s = SelfAffine::new(h, 1.0, 2.0, 50.0).unwrap();
            for &k in &[0.0, 2.0, 4.0] {
                let f = |q: f64| 2.0 * PI * q.powf(1.0 + k) * s.c2d(q);
                let num = tanh_sinh(f, 1.0, 2.0, 1e-13).unwrap()
                    + tanh_sinh(f, 2.0, 50.0, 1e-13).unwrap();
                assert!((s.moment(k) / num - 1.0).abs() < 1e-10, "H={h} k={k}");
            }
        }
    }

    #[test]
    fn eq73_preserves_rms_height_slope_and_curvature() {
        let s = SelfAffine::new(0.7, 1.0, 1.0, 100.0)
            .unwrap()
            .with_rms_height(0.3)
            .unwrap();
        let line = s.to_line(PI);
        assert!((line.rms_height() / s.rms_height() - 1.0).abs() < 1e-14);
        assert!((line.rms_slope() / s.rms_slope() - 1.0).abs() < 1e-14);
        assert!((line.rms_curvature() / s.rms_curvature() - 1.0).abs() < 1e-14);
        assert!((s.rms_height() - 0.3).abs() < 1e-15);
    }

    #[test]
    fn tabulated_spectrum_recovers_a_power_law() {
        let s = SelfAffine::new(0.6, 1.0, 1.0, 100.0).unwrap();
        let pts: Vec<(f64, f64)> = (0..20)
            .map(|i| 1.5 * 1.25f64.powi(i))
            .map(|q| (q, s.c2d(q)))
            .collect();
        let t = TabulatedSpectrum::new(&pts).unwrap();
        assert!((t.fitted_hurst() - 0.6).abs() < 1e-10);
        assert!((t.c2d(7.3) / s.c2d(7.3) - 1.0).abs() < 1e-12);
        assert_eq!(t.c2d(0.5), 0.0);
        assert!(TabulatedSpectrum::new(&[(1.0, 1.0)]).is_err());
        // Rounding-level bins beyond a cut-off do not enter the fit.
        let mut noisy = pts.clone();
        noisy.extend([(200.0, 1e-35), (300.0, 3e-36)]);
        assert!((TabulatedSpectrum::new(&noisy).unwrap().fitted_hurst() - 0.6).abs() < 1e-10);
    }

    #[test]
    fn lambda_tables() {
        let t = LambdaTable::from_csv("# calibrated\nhurst,lambda\n0.0,2.0\n1.0,3.0\n").unwrap();
        assert!((t.at(0.25).unwrap() - 2.25).abs() < 1e-14);
        assert!(t.at(1.5).is_err());
        assert!(LambdaTable::from_csv("h,l\n0,1\n0,2\n").is_err());
        assert!(LambdaTable::from_csv("h,l\n0,-1\n").is_err());
        assert!(SelfAffine::new(3.5, 1.0, 1.0, 2.0).is_err());
        assert!(SelfAffine::new(0.5, 1.0, 3.0, 2.0).is_err());
    }
}
