//! The rule of Hess by quadrature, for any profile (Eq. 11), and its inverse.
//!
//! Forward (Eq. 11): with r = x sin t the kernel's singularity disappears,
//! `z1d(x) = x * Int_0^{pi/2} z'(x sin t) dt`; what remains (e.g. z' ~ r^{n-1} for n < 1)
//! is an end-point singularity that tanh-sinh quadrature integrates to full precision.
//!
//! Inverse (1D -> 3D): `z(r) = (2/pi) Int_0^r z1d(x) / sqrt(r^2 - x^2) dx`
//! `= (2/pi) Int_0^{pi/2} z1d(r sin t) dt`.

use crate::error::Result;
use crate::numerics::quad::{tanh_sinh_split, DEFAULT_TOL};
use crate::profile::Profile;
use std::f64::consts::{FRAC_2_PI, FRAC_PI_2};

/// Eq. (11) for a slope function `dz` with break points `breaks` (radii where `dz` is
/// not smooth).
pub fn transform<F: Fn(f64) -> f64>(dz: F, breaks: &[f64], x: f64) -> Result<f64> {
    if x == 0.0 {
        return Ok(0.0);
    }
    let x = x.abs();
    Ok(x * quarter_integral(dz, breaks, x)?) // Eq. (11)
}

/// Inverse of Eq. (11): the 3D profile z(r) whose MRD image is `z1d`.
pub fn inverse<F: Fn(f64) -> f64>(z1d: F, breaks: &[f64], r: f64) -> Result<f64> {
    if r == 0.0 {
        return Ok(0.0);
    }
    let r = r.abs();
    Ok(FRAC_2_PI * quarter_integral(z1d, breaks, r)?)
}

/// `Int_0^{pi/2} g(r sin t) dt` (r > 0), split where `r sin t` crosses a break point of
/// `g` (the `breaks` inside (0, r)).
fn quarter_integral<F: Fn(f64) -> f64>(g: F, breaks: &[f64], r: f64) -> Result<f64> {
    let t_breaks: Vec<f64> = breaks
        .iter()
        .filter(|&&b| b > 0.0 && b < r)
        .map(|&b| (b / r).asin())
        .collect();
    tanh_sinh_split(|t| g(r * t.sin()), 0.0, FRAC_PI_2, &t_breaks, DEFAULT_TOL)
}

impl Profile {
    /// z1d(x) by quadrature of Eq. (11) (independent of the per-shape closed forms).
    pub fn z1d_numeric(&self, x: f64) -> Result<f64> {
        transform(|r| self.dz(r), &self.breaks(), x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::{Shape, TabulatedProfile};

    #[test]
    fn power_laws_match_eq15_to_1e9() {
        for &n in &[0.5, 1.0, 2.0, 3.0, 4.5] {
            let p = Profile::single(Shape::power_law(0.7, n).unwrap());
            for &x in &[1e-3, 0.1, 0.5, 1.0, 3.7] {
                let exact = crate::profile::kappa(n) * 0.7 * f64::powf(x, n); // Eq. (14)-(15)
                let num = p.z1d_numeric(x).unwrap();
                assert!(
                    ((num - exact) / exact).abs() <= 1e-9,
                    "n={n} x={x}: {num} vs {exact}"
                );
                assert!(((p.z1d(x) - exact) / exact).abs() <= 1e-13);
            }
        }
    }

    #[test]
    fn flattened_paraboloid_matches_eq23() {
        let p = Profile::single(Shape::flattened_paraboloid(2.0, 0.3).unwrap());
        for &x in &[0.31, 0.5, 1.0, 2.0] {
            let exact = x * (x * x - 0.09f64).sqrt() / 2.0; // Eq. (23)
            let num = p.z1d_numeric(x).unwrap();
            assert!(
                ((num - exact) / exact).abs() <= 1e-9,
                "x={x}: {num} vs {exact}"
            );
        }
        assert_eq!(p.z1d(0.2), 0.0);
    }

    #[test]
    fn tables_match_quadrature() {
        let r: Vec<f64> = (0..30).map(|i| (i as f64 / 29.0).powf(1.3)).collect();
        let z: Vec<f64> = r.iter().map(|&r| r * r + 0.2 * r.powi(4)).collect();
        let p = Profile::single(Shape::Table(TabulatedProfile::new(r, z).unwrap()));
        for &x in &[0.05, 0.33, 0.7, 1.0] {
            let num = p.z1d_numeric(x).unwrap();
            assert!(((num - p.z1d(x)) / num).abs() <= 1e-9, "x={x}");
        }
    }

    #[test]
    fn inverse_round_trip() {
        for &n in &[0.5, 1.0, 2.0, 3.0, 4.5] {
            let p = Profile::single(Shape::power_law(1.3, n).unwrap());
            for &r in &[0.01, 0.4, 1.0, 2.5] {
                let z = inverse(|x| p.z1d(x), &[], r).unwrap();
                let exact = 1.3 * f64::powf(r, n);
                assert!(
                    ((z - exact) / exact).abs() <= 1e-9,
                    "n={n} r={r}: {z} vs {exact}"
                );
            }
        }
        let p = Profile::single(Shape::flattened_paraboloid(1.0, 0.5).unwrap());
        for &r in &[0.3, 0.6, 1.2] {
            let z = inverse(|x| p.z1d(x), &p.breaks(), r).unwrap();
            assert!(
                (z - p.z(r)).abs() <= 1e-9 * p.z(1.2),
                "r={r}: {z} vs {}",
                p.z(r)
            );
        }
    }
}
