//! Static friction from the mean slope in contact (Section 10.2, Eqs. 85-93).
//!
//! Rough lines of N points over length L with `C1D ~ q^(-2H-1)` (Eq. 70) on the band
//! `pi/L < |q| < 0.1 pi/dx` (Eq. 85) are pressed with force F; the rms slope over the
//! contacting points (Eq. 86) over the rms slope of the whole line (Eq. 88) gives
//! `xi = grad z_cont / grad z` (Eq. 89) as a function of `f = F/(E* h L)` (Eq. 90),
//! averaged over realisations and fitted by `xi = a + b ln f` (Eq. 91).

use crate::error::{positive, Result};
use crate::rough_contact::{ensemble, fit_line, LineFit, RoughLine, Stat};
use crate::roughness::synthesis::{line, Amplitudes};
use crate::roughness::SelfAffine;
use std::f64::consts::PI;

/// Set-up of the experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionSetup {
    pub hurst: f64,
    pub points: usize,
    pub length: f64,
    pub e_star: f64,
    /// rms height h of every line (deterministic amplitudes give it exactly).
    pub rms_height: f64,
    pub realisations: u64,
    pub seed: u64,
    /// Forces F at which xi is evaluated.
    pub forces: Vec<f64>,
}

/// Ensemble result at one force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionPoint {
    pub force: f64,
    /// f = F/(E* h L) (Eq. 90).
    pub reduced_force: f64,
    /// xi (Eq. 89) over the ensemble.
    pub xi: Stat,
    /// Number of contacting points over the ensemble.
    pub contacts: Stat,
}

#[derive(Debug, Clone, PartialEq)]
pub struct FrictionResult {
    pub points: Vec<FrictionPoint>,
    /// xi = a + b ln f (Eq. 91), least squares on the ensemble means (needs >= 3 forces).
    pub fit: Option<LineFit>,
}

/// The line spectrum of Eq. (85): C1D ~ q^(-2H-1) on pi/L < q < 0.1 pi/dx.
pub fn band_spectrum(
    hurst: f64,
    points: usize,
    length: f64,
    rms_height: f64,
) -> Result<crate::roughness::LineSpectrum> {
    let dx = length / points as f64;
    // Lowest populated mode 2 pi/L > pi/L; upper cut-off 0.1 pi/dx (Eq. 85).
    let q_lo = 2.0 * PI / length;
    let q_hi = 0.1 * PI / dx;
    SelfAffine::new(hurst, q_lo, q_lo, q_hi * (1.0 - 1e-12))?
        .to_line(1.0)
        .with_rms_height(rms_height)
}

/// Line `r` of the experiment with rms height `h`.
fn rough_line(
    setup: &FrictionSetup,
    spec: &crate::roughness::LineSpectrum,
    r: u64,
) -> Result<RoughLine> {
    let z = line(
        spec,
        setup.points,
        setup.length,
        setup.seed,
        r,
        Amplitudes::Deterministic,
    )?;
    RoughLine::new(&z, setup.length, setup.e_star)
}

pub fn static_friction(setup: &FrictionSetup) -> Result<FrictionResult> {
    positive("rms height", setup.rms_height)?;
    let spec = band_spectrum(setup.hurst, setup.points, setup.length, setup.rms_height)?;
    let per: Vec<Vec<(f64, f64)>> = ensemble(setup.realisations, |r| {
        let rl = rough_line(setup, &spec, r)?;
        setup
            .forces
            .iter()
            .map(|&f| {
                let s = rl.at_force(f)?;
                Ok((s.contact_slope / rl.rms_slope, s.contacts as f64)) // Eq. (89)
            })
            .collect()
    })?;
    let mut points = Vec::new();
    for (k, &f) in setup.forces.iter().enumerate() {
        let xi: Vec<f64> = per.iter().map(|v| v[k].0).collect();
        let m: Vec<f64> = per.iter().map(|v| v[k].1).collect();
        points.push(FrictionPoint {
            force: f,
            reduced_force: f / (setup.e_star * setup.rms_height * setup.length), // Eq. (90)
            xi: Stat::of(&xi),
            contacts: Stat::of(&m),
        });
    }
    let x: Vec<f64> = points.iter().map(|p| p.reduced_force.ln()).collect();
    let y: Vec<f64> = points.iter().map(|p| p.xi.mean).collect();
    let fit = if points.len() >= 3 {
        Some(fit_line(&x, &y)?)
    } else {
        None
    };
    Ok(FrictionResult { fit, points })
}

/// The rms height for which the mean number of contacting points at force
/// `setup.forces.last()` equals `target`, from `probe` realisations. Uses the exact
/// scaling of the foundation: the count at force F for height h equals the count at
/// force F/h for unit height, so the unit-height lines are built once and the force is
/// bisected.
pub fn calibrate_rms_height(setup: &FrictionSetup, target: f64, probe: u64) -> Result<f64> {
    let spec = band_spectrum(setup.hurst, setup.points, setup.length, 1.0)?;
    let lines: Vec<RoughLine> = ensemble(probe.max(1), |r| rough_line(setup, &spec, r))?;
    let mean_contacts = |f: f64| -> Result<f64> {
        let mut s = 0.0;
        for l in &lines {
            s += l.at_force(f)?.contacts as f64;
        }
        Ok(s / lines.len() as f64)
    };
    let f_max = *setup
        .forces
        .last()
        .ok_or(crate::error::MrdError::InvalidData("no forces".into()))?;
    let (mut lo, mut hi) = (
        1e-12 * setup.e_star * setup.length,
        setup.e_star * setup.length,
    );
    if mean_contacts(hi)? < target {
        return Err(crate::error::MrdError::ImpossibleLoad(format!(
            "{target} contacts cannot be reached"
        )));
    }
    for _ in 0..100 {
        let mid = (lo * hi).sqrt();
        if mean_contacts(mid)? >= target {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi / lo < 1.0 + 1e-10 {
            break;
        }
    }
    // F_max at height h corresponds to F_max / h at unit height.
    Ok(f_max / hi)
}

/// `count` forces spaced logarithmically over [lo, hi].
pub fn log_space(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| lo * (hi / lo).powf(k as f64 / (count - 1).max(1) as f64))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::roughness::SpectralMoments;

    #[test]
    fn xi_is_invariant_under_height_scaling() {
        // Scaling h and F together leaves xi(f) unchanged (Section 10.2).
        let mk = |h: f64| FrictionSetup {
            hurst: 0.7,
            points: 4096,
            length: 4096.0,
            e_star: 1.0,
            rms_height: h,
            realisations: 4,
            seed: 1,
            forces: log_space(1.0 * h, 100.0 * h, 5),
        };
        let a = static_friction(&mk(1.0)).unwrap();
        let b = static_friction(&mk(7.0)).unwrap();
        for (p, q) in a.points.iter().zip(&b.points) {
            assert!((p.xi.mean - q.xi.mean).abs() < 1e-9);
            assert!((p.reduced_force - q.reduced_force).abs() < 1e-15);
        }
    }

    #[test]
    fn band_spectrum_has_the_requested_height() {
        let s = band_spectrum(0.7, 1000, 1000.0, 2.0).unwrap();
        assert!((s.rms_height() - 2.0).abs() < 1e-12);
    }
}
