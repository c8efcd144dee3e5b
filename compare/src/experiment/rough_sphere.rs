//! The rough sphere of the 3D studies (Section 9: "a rough parabolic indenter") and its
//! MRD line: a sphere of radius R with nested self-affine roughness superposed on a
//! square of side `side`, centred on the axis.
//!
//! - Roughness: C2D ~ q^(-2H-2) with modes |k| <= `bandwidth` (units of 2 pi / side),
//!   realisation `r` of the nested family of `seed` (the same phases on every grid);
//!   scaled by one factor ([`RoughSphereGeometry::unit_rms_factor`]) to unit rms height
//!   over the square, then by the case's rms height h.
//! - 3D heights (peaks up): -r^2 / (2R) + h s z(x, y) on `grid`^2 cell centres.
//! - MRD line: -x^2 / R (the rule of Hess for the sphere, Eq. 11) + h s z1(x), with z1 a
//!   line of C1D = lambda q C2D (Eq. 76, the same factor s: both sides carry the same
//!   C2D), on `n1` spring centres across the same side.

use crate::error::{CompareError, Context as _, Result};
use mrd::roughness::synthesis::Grid;
use mrd::roughness::{nested, SelfAffine};
use std::f64::consts::PI;

/// A rough sphere's geometry (lengths in the scene's unit).
#[derive(Debug, Clone, Copy)]
pub struct RoughSphereGeometry {
    pub radius: f64,
    pub hurst: f64,
    /// Side of the square map and of the MRD row.
    pub side: f64,
    pub grid: usize,
    pub bandwidth: usize,
    pub seed: u64,
}

/// MRD springs per 3D cell, unless the scene gives `points_1d_factor`.
pub fn default_points_1d_factor() -> usize {
    4
}

/// Cell-centre coordinate of index i of `n` across `side`, centred on the axis.
pub fn centre(i: usize, n: usize, side: f64) -> f64 {
    (i as f64 + 0.5) * side / n as f64 - 0.5 * side
}

impl RoughSphereGeometry {
    pub fn spectrum(&self) -> Result<SelfAffine> {
        let q0 = 2.0 * PI / self.side;
        SelfAffine::new(self.hurst, q0, q0, q0 * (self.bandwidth as f64 + 1.0)).ctx("spectrum")
    }

    /// Realisation `r` of the roughness on the `grid`^2 map, not scaled.
    pub fn surface(&self, r: u64) -> Result<Vec<f64>> {
        let sa = self.spectrum()?;
        let grid = Grid::square(self.grid, self.side);
        nested::surface(&|q| sa.c2d(q), self.bandwidth, &grid, self.seed, r).ctx("3D roughness")
    }

    /// The factor that gives the surfaces unit rms height over the square (the same for
    /// every realisation: their mode amplitudes are fixed, only the phases are random).
    pub fn unit_rms_factor(&self) -> Result<f64> {
        let z = self.surface(0)?;
        let n = z.len() as f64;
        let mean = z.iter().sum::<f64>() / n;
        let rms = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
        if rms.is_nan() || rms <= 0.0 {
            return Err(CompareError::Scene("the roughness band is empty".into()));
        }
        Ok(1.0 / rms)
    }

    /// The factor that gives a case's surfaces unit rms height: [`Self::unit_rms_factor`]
    /// of this grid (the case's finest, whose factor its MRD lines take too), 1 for the
    /// smooth body (`roughness` 0).
    pub fn unit_rms_scale(&self, roughness: f64) -> Result<f64> {
        if roughness > 0.0 {
            self.unit_rms_factor()
        } else {
            Ok(1.0)
        }
    }

    /// Squared distance from the axis of cell `c` of the map.
    pub fn r2(&self, c: usize) -> f64 {
        let n = self.grid;
        centre(c % n, n, self.side).powi(2) + centre(c / n, n, self.side).powi(2)
    }

    /// The 3D heights of realisation `r` with rms height `h` (`scale` from
    /// [`Self::unit_rms_factor`]); `h = 0` is the smooth sphere.
    pub fn heights(&self, h: f64, scale: f64, r: u64) -> Result<Vec<f64>> {
        let n = self.grid;
        let rough = if h > 0.0 {
            self.surface(r)?
        } else {
            vec![0.0; n * n]
        };
        Ok((0..n * n)
            .map(|c| -self.r2(c) / (2.0 * self.radius) + h * scale * rough[c])
            .collect())
    }

    /// MRD line `r` on `n1` springs with rms height `h` of the surface and factor
    /// `lambda`: (spring centres x, heights -x^2 / R + line).
    pub fn line(
        &self,
        h: f64,
        scale: f64,
        lambda: f64,
        n1: usize,
        r: u64,
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let rough = if h > 0.0 {
            let line = self.spectrum()?.to_line(lambda); // Eq. (76)
            nested::line(
                &|q| line.c1d(q),
                self.bandwidth,
                n1,
                self.side,
                self.seed,
                r,
            )
            .ctx("1D line")?
        } else {
            vec![0.0; n1]
        };
        let x: Vec<f64> = (0..n1).map(|i| centre(i, n1, self.side)).collect();
        let w = (0..n1)
            .map(|i| -x[i] * x[i] / self.radius + h * scale * rough[i])
            .collect();
        Ok((x, w))
    }
}
