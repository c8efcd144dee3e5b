//! `rough_plastic_3d`'s runs: the spectrum and its moments, the load history, the 3D
//! elastic-plastic punch and MRD's plastic lines along it.

use super::*;
use crate::error::{Context as _, Result};
use crate::experiment::rough_punch::punch_face;
use bem3d::plastic::PlasticContact;
use bem3d::{Load, NonPeriodicHalfSpace};
use mrd::plastic_line::PlasticLine;
use mrd::roughness::nested;
use mrd::roughness::SelfAffine;
use std::f64::consts::TAU;

impl RoughPlastic3d {
    /// The face's spectrum: self-affine from 2 pi / L to B 2 pi / L, rms slope SLOPE.
    pub(super) fn spectrum(&self) -> Result<SelfAffine> {
        let q0 = TAU;
        SelfAffine::new(self.hurst, q0, q0, q0 * self.bandwidth as f64)
            .and_then(|s| s.with_rms_slope(SLOPE))
            .ctx("the face's spectrum")
    }

    /// The rms height h and rms slope h' of the face's modes on the square lattice
    /// (every realisation's, the amplitudes being fixed).
    pub(super) fn moments(&self) -> Result<(f64, f64)> {
        let s = self.spectrum()?;
        let c2d = |q: f64| s.c2d(q);
        let b = self.bandwidth as f64;
        let h2 = nested::surface_mean_square(&c2d, b, 1.0, false);
        let s2 = nested::surface_mean_square(&|q| q * q * c2d(q), b, 1.0, false);
        Ok((h2.sqrt(), s2.sqrt()))
    }

    /// The reduced forces of the history: the first loading, the unloading, the reloading.
    pub(super) fn history(&self) -> Vec<f64> {
        let mut f = mrd::friction::log_space(self.f_min, self.f_max, self.loads);
        f.extend(UNLOAD.iter().chain(&RELOAD).map(|u| u * self.f_max));
        f
    }

    pub(super) fn run_3d(
        &self,
        z: &[f64],
        n: usize,
        hardness: f64,
        h: f64,
        forces: &[f64],
    ) -> Result<Reading> {
        let (mask, _) = punch_face(z, n);
        let disc = mask.iter().filter(|&&m| m).count() as f64 / (n * n) as f64;
        let op = NonPeriodicHalfSpace::try_new(n, n, 1.0, 1.0, 1.0).ctx("3D operator")?;
        let mut c = PlasticContact::new(op, z, Some(&mask), hardness).ctx("3D plastic contact")?;
        let mut points = Vec::with_capacity(forces.len());
        for &f in forces {
            let s = c
                .step(Load::Force(f * h), self.tolerance)
                .ctx(format!("3D step to f = {f:.4e} on {n}^2 cells"))?;
            points.push(Point {
                approach: s.approach,
                force: s.force,
                contact: s.contact_area / disc,
                plastic: if s.contact_area > 0.0 {
                    s.plastic_area / s.contact_area
                } else {
                    0.0
                },
            });
        }
        Ok(self.reading(points))
    }

    pub(super) fn run_mrd(
        &self,
        z: &[f64],
        hardness: f64,
        h: f64,
        forces: &[f64],
    ) -> Result<Reading> {
        let mut line = PlasticLine::new(z, 1.0, 1.0, hardness).ctx("MRD line")?;
        let mut points = Vec::with_capacity(forces.len());
        for &f in forces {
            let s = line.step_to_force(f * h, self.tolerance).ctx("MRD step")?;
            points.push(Point {
                approach: s.approach,
                force: s.force,
                contact: s.contacts as f64 / self.springs as f64,
                plastic: if s.contacts > 0 {
                    s.capped as f64 / s.contacts as f64
                } else {
                    0.0
                },
            });
        }
        Ok(self.reading(points))
    }

    fn reading(&self, points: Vec<Point>) -> Reading {
        let secant = |a: &Point, b: &Point| ((b.force - a.force) / (b.approach - a.approach)).ln();
        let first = &points[..self.loads];
        let peak = points[self.loads - 1];
        let unload = points[self.loads];
        let lowest = points[self.loads + UNLOAD.len() - 1];
        let reloaded = points[points.len() - 1];
        Reading {
            ln_k: first.windows(2).map(|w| secant(&w[0], &w[1])).collect(),
            ln_k_unload: secant(&unload, &peak),
            ln_recovery: (peak.approach - lowest.approach).ln(),
            ln_peak: peak.approach.ln(),
            retrace: ((reloaded.approach - peak.approach) / peak.approach).abs(),
            points,
        }
    }

    /// The mean over a case's runs of the mean over the loading intervals of ln k, and
    /// its interval: one number per run, so the interval is the runs' spread.
    pub(super) fn loading(runs: &[Reading]) -> (f64, f64) {
        let per: Vec<f64> = runs
            .iter()
            .map(|r| r.ln_k.iter().sum::<f64>() / r.ln_k.len() as f64)
            .collect();
        mean_ci(&per)
    }
}
