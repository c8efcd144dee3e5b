//! A rough line pressed into the MRD foundation (Sections 9 and 10.2).
//!
//! Springs `E* dx` (Eq. 3) under a rigid rough line z_i: at approach d (from the first
//! touch of the highest point) spring i carries `E* dx (d - g_i)+` with gap
//! `g_i = max z - z_i`. One sort of the gaps plus prefix sums makes force, contact count,
//! contact length and stiffness `k = E* dx m` exact in O(log N) per query, and a
//! force-controlled state an exact inversion ([`crate::foundation`]). The mean slope in
//! contact (Eq. 86) is a prefix sum too, of the squared forward-difference slopes taken
//! in gap order. A k(F) curve of M points costs O(N log N + M log N).

use crate::error::{positive, MrdError, Result};
use crate::foundation::Foundation;
use rayon::prelude::*;

/// One state of the rough line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughState {
    pub depth: f64,
    pub force: f64,
    /// Springs in contact.
    pub contacts: usize,
    /// Contact length m dx.
    pub contact_length: f64,
    /// k = dF/dd = E* dx m.
    pub stiffness: f64,
    /// rms slope over the contacting points (Eq. 86); 0 without contact.
    pub contact_slope: f64,
}

/// A rough line of length L with N points on the foundation.
#[derive(Debug, Clone)]
pub struct RoughLine {
    foundation: Foundation,
    /// Prefix sums of squared slopes in gap order: slope2[m] = sum over the m lowest gaps.
    slope2: Vec<f64>,
    length: f64,
    e_star: f64,
    /// rms height about the mean (Eq. 87).
    pub rms_height: f64,
    /// rms forward-difference slope over the whole line (Eq. 88, as in Eq. 86).
    pub rms_slope: f64,
    /// Highest point minus mean height.
    mean_gap: f64,
}

impl RoughLine {
    /// `heights` (periodic, N points over length `length`), modulus E*.
    pub fn new(heights: &[f64], length: f64, e_star: f64) -> Result<Self> {
        positive("length", length)?;
        positive("e_star", e_star)?;
        let n = heights.len();
        if n < 2 {
            return Err(MrdError::InvalidData(
                "a rough line needs at least 2 points".into(),
            ));
        }
        if let Some((i, what)) = crate::error::bad_height(heights) {
            return Err(MrdError::InvalidData(format!(
                "rough line: {what} at index {i}"
            )));
        }
        let dx = length / n as f64;
        let zmax = heights.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
        let gaps: Vec<f64> = heights.iter().map(|z| zmax - z).collect();
        // Slopes (z_{i+1} - z_i)/dx, periodic (Eq. 86), ordered like the sorted gaps.
        let slope_sq: Vec<f64> = (0..n)
            .map(|i| ((heights[(i + 1) % n] - heights[i]) / dx).powi(2))
            .collect();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_unstable_by(|&a, &b| gaps[a].total_cmp(&gaps[b]).then(a.cmp(&b)));
        let mut slope2 = Vec::with_capacity(n + 1);
        slope2.push(0.0);
        let mut acc = 0.0;
        for &i in &order {
            acc += slope_sq[i];
            slope2.push(acc);
        }
        let mean = heights.iter().sum::<f64>() / n as f64;
        let rms_height =
            (heights.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
        let rms_slope = (acc / n as f64).sqrt();
        Ok(Self {
            foundation: Foundation::new(&gaps, dx, e_star)?,
            slope2,
            length,
            e_star,
            rms_height,
            rms_slope,
            mean_gap: zmax - mean,
        })
    }

    pub fn len(&self) -> usize {
        self.foundation.len()
    }
    pub fn is_empty(&self) -> bool {
        self.foundation.is_empty()
    }
    pub fn length(&self) -> f64 {
        self.length
    }
    /// Approach (from the first contact) at which the rigid plane reaches the mean
    /// height: the highest point minus the mean.
    pub fn mean_plane_depth(&self) -> f64 {
        self.mean_gap
    }
    /// Approach at which the contact becomes complete.
    pub fn full_contact_depth(&self) -> f64 {
        self.foundation.full_contact()
    }

    fn state(&self, s: crate::foundation::FoundationState) -> RoughState {
        let m = s.contacts;
        RoughState {
            depth: s.depth,
            force: s.force,
            contacts: m,
            contact_length: m as f64 * self.foundation.dx(),
            stiffness: s.stiffness,
            contact_slope: if m > 0 {
                (self.slope2[m] / m as f64).sqrt()
            } else {
                0.0
            },
        }
    }

    /// Exact state at approach d >= 0.
    pub fn at_depth(&self, d: f64) -> Result<RoughState> {
        crate::error::non_negative("depth", d)?;
        Ok(self.state(self.foundation.at_depth(d)?))
    }

    /// Exact force-controlled state.
    pub fn at_force(&self, f: f64) -> Result<RoughState> {
        Ok(self.state(self.foundation.at_force(f)?))
    }

    /// Dimensionless force f = F/(E* h L) (Eqs. 77, 90).
    pub fn reduced_force(&self, f: f64) -> f64 {
        f / (self.e_star * self.rms_height * self.length)
    }
    /// Dimensionless stiffness k/(E* L) (Eq. 77).
    pub fn reduced_stiffness(&self, k: f64) -> f64 {
        k / (self.e_star * self.length)
    }
}

/// Mean, standard deviation and the half-width of a 95 % confidence interval of the
/// mean (normal approximation, 1.96 s/sqrt(n)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stat {
    pub mean: f64,
    pub std: f64,
    pub ci95: f64,
    pub count: usize,
}

impl Stat {
    pub fn of(values: &[f64]) -> Self {
        let n = values.len();
        if n == 0 {
            return Self {
                mean: f64::NAN,
                std: f64::NAN,
                ci95: f64::NAN,
                count: 0,
            };
        }
        let mean = values.iter().sum::<f64>() / n as f64;
        let var = if n > 1 {
            values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64
        } else {
            0.0
        };
        Self {
            mean,
            std: var.sqrt(),
            ci95: 1.96 * var.sqrt() / (n as f64).sqrt(),
            count: n,
        }
    }
}

/// Runs `f(realisation)` for realisations `0..count` in parallel; results in order
/// (deterministic whatever the thread count).
pub fn ensemble<T: Send, F: Fn(u64) -> Result<T> + Sync + Send>(
    count: u64,
    f: F,
) -> Result<Vec<T>> {
    (0..count).into_par_iter().map(f).collect()
}

/// Least-squares line y = a + b x with standard errors of a and b.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineFit {
    pub a: f64,
    pub b: f64,
    pub se_a: f64,
    pub se_b: f64,
}

pub fn fit_line(x: &[f64], y: &[f64]) -> Result<LineFit> {
    let n = x.len();
    if y.len() != n {
        return Err(MrdError::InvalidData(format!(
            "a line fit needs as many y as x: {} x and {} y",
            n,
            y.len()
        )));
    }
    if n < 3 {
        return Err(MrdError::InvalidData(format!(
            "a line fit needs at least 3 points, got {n}"
        )));
    }
    for (name, v) in [("x", x), ("y", y)] {
        if let Some(i) = v.iter().position(|v| !v.is_finite()) {
            return Err(MrdError::InvalidData(format!(
                "a line fit needs finite points: {name}[{i}] = {}",
                v[i]
            )));
        }
    }
    let nf = n as f64;
    let (mx, my) = (x.iter().sum::<f64>() / nf, y.iter().sum::<f64>() / nf);
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    if sxx <= 0.0 {
        return Err(MrdError::InvalidData("a line fit needs distinct x".into()));
    }
    let b = sxy / sxx;
    let a = my - b * mx;
    let rss: f64 = x.iter().zip(y).map(|(u, v)| (v - a - b * u).powi(2)).sum();
    let s2 = rss / (nf - 2.0);
    Ok(LineFit {
        a,
        b,
        se_b: (s2 / sxx).sqrt(),
        se_a: (s2 * (1.0 / nf + mx * mx / sxx)).sqrt(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn force_stiffness_and_slope_match_brute_force() {
        let n = 2000;
        let l = 3.0;
        let h: Vec<f64> = (0..n)
            .map(|i| {
                let x = i as f64 / n as f64 * 2.0 * std::f64::consts::PI;
                (3.0 * x).sin() + 0.4 * (17.0 * x + 1.0).cos() + 0.1 * (91.0 * x).sin()
            })
            .collect();
        let line = RoughLine::new(&h, l, 2.0).unwrap();
        let dx = l / n as f64;
        let zmax = h.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
        for &d in &[0.01, 0.2, 0.9, 1.7] {
            let s = line.at_depth(d).unwrap();
            let (mut f, mut m, mut s2) = (0.0, 0, 0.0);
            for i in 0..n {
                let pen = d - (zmax - h[i]);
                if pen >= 0.0 {
                    f += 2.0 * dx * pen;
                    m += 1;
                    s2 += ((h[(i + 1) % n] - h[i]) / dx).powi(2);
                }
            }
            assert!((s.force - f).abs() < 1e-10 * f.max(1.0));
            assert_eq!(s.contacts, m);
            assert!((s.stiffness - 2.0 * dx * m as f64).abs() < 1e-12);
            assert!((s.contact_slope - (s2 / m as f64).sqrt()).abs() < 1e-9);
            let back = line.at_force(s.force).unwrap();
            assert!((back.depth - d).abs() < 1e-10);
        }
    }

    #[test]
    fn stats_fit_and_errors() {
        let s = Stat::of(&[1.0, 2.0, 3.0, 4.0]);
        assert!((s.mean - 2.5).abs() < 1e-15 && (s.std - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
        let x = [0.0, 1.0, 2.0, 3.0];
        let f = fit_line(&x, &[1.0, 3.0, 5.0, 7.0]).unwrap();
        assert!((f.a - 1.0).abs() < 1e-14 && (f.b - 2.0).abs() < 1e-14 && f.se_b < 1e-12);
        assert!(RoughLine::new(&[0.0, f64::NAN], 1.0, 1.0).is_err());
        assert!(RoughLine::new(&[0.0, 1.0], -1.0, 1.0).is_err());
    }

    #[test]
    fn ensemble_is_ordered_and_deterministic() {
        let a = ensemble(50, |r| Ok(r * r)).unwrap();
        assert_eq!(a, (0..50u64).map(|r| r * r).collect::<Vec<_>>());
    }
}
