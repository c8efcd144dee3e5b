//! One adhesive loading-unloading cycle of a rough sphere, in 3D or by MRD, along the
//! same approach steps of the mean body.

use super::RoughAdhesion3d;
use crate::error::{CompareError, Context as _, Result};
use bem3d::adhesion::AdhesiveContact;
use bem3d::{Load, NonPeriodicHalfSpace};
use mrd::adhesive_row::{AdhesiveRow, EdgeRadius};

/// A cycle's curve and its measures.
#[derive(Debug, Clone, Default)]
pub struct Cycle {
    /// (approach of the mean body [length], force [force], unloading) per step in
    /// contact.
    pub curve: Vec<(f64, f64, bool)>,
    /// -(smallest force of the unloading), 0 when no tension is reached [force].
    pub pull_off: f64,
    /// Force at `depth_max` [force].
    pub force_max: f64,
    /// Work of the loading minus the work returned by the unloading: the loop's area
    /// [force x length].
    pub hysteresis: f64,
    /// Set-update rounds and conjugate-gradient iterations (3D; 0 for MRD).
    pub rounds: usize,
    pub iterations: usize,
}

/// The cycles of each case (hurst, roughness): per grid (3D) or per variant (MRD), one
/// per realisation.
pub type Cases = Vec<((f64, f64), Vec<Vec<Cycle>>)>;

/// One step of a side at the mean body's approach `d`: (force, separated).
type Step<'a> = dyn FnMut(f64) -> Result<(f64, bool)> + 'a;

/// Loads from first contact (`d = -top`, `top` the highest point above the mean
/// body's apex) to `depth_max` in steps of `dd`, then unloads by `dd` until the body
/// separates.
fn drive(spec: &RoughAdhesion3d, top: f64, step: &mut Step) -> Result<Cycle> {
    let (dd, d_max) = (spec.step(), spec.depth_max);
    // The scene's checks keep first contact within a few depth_max of the apex; a
    // realisation whose highest point lies further up is refused, not walked.
    let loading = (d_max + top) / dd;
    if loading.is_nan() || loading > (100 * spec.steps) as f64 {
        return Err(CompareError::Scene(format!(
            "rough_adhesion_3d: a surface's highest point lies {top:e} above the body's apex, {loading:.0} approach steps of depth_max / steps from depth_max (at most 100 x steps): raise depth_max or lower roughness"
        )));
    }
    let mut cycle = Cycle::default();
    let mut d = -top;
    // Loading work by the trapezoidal rule from first contact (F = 0).
    let (mut last_d, mut last_f) = (d, 0.0);
    let mut work = 0.0;
    loop {
        d = (d + dd).min(d_max);
        let (f, _) = step(d)?;
        work += 0.5 * (f + last_f) * (d - last_d);
        cycle.curve.push((d, f, false));
        (last_d, last_f) = (d, f);
        if d >= d_max {
            break;
        }
    }
    cycle.force_max = last_f;
    let guard = 100 * spec.steps + (top / dd) as usize;
    let mut min_f = f64::INFINITY;
    for k in 1..=guard {
        let d = d_max - k as f64 * dd;
        let (f, separated) = step(d)?;
        if separated {
            // The force drops to zero at the last approach in contact.
            cycle.pull_off = (-min_f).max(0.0);
            cycle.hysteresis = work;
            return Ok(cycle);
        }
        work -= 0.5 * (f + last_f) * (last_d - d);
        cycle.curve.push((d, f, true));
        min_f = min_f.min(f);
        (last_d, last_f) = (d, f);
    }
    Err(CompareError::Scene(format!(
        "rough_adhesion_3d: the body did not separate within {guard} approach steps below depth_max"
    )))
}

/// The factor that gives the MRD lines of a case the surfaces' C2D: the unit-rms
/// factor of the finest 3D grid (1 for the smooth body).
pub fn unit_rms_scale(spec: &RoughAdhesion3d, hurst: f64, roughness: f64) -> Result<f64> {
    let finest = *spec.cells.last().unwrap_or(&16);
    spec.geometry(hurst, finest).unit_rms_scale(roughness)
}

/// Realisation `r` of the case (hurst, roughness) on an `n`^2 grid in 3D.
pub fn cycle_3d(
    spec: &RoughAdhesion3d,
    hurst: f64,
    roughness: f64,
    n: usize,
    r: u64,
    e_star: f64,
) -> Result<Cycle> {
    let geometry = spec.geometry(hurst, n);
    let h = roughness * spec.adhesion_length(e_star);
    let scale = if h > 0.0 {
        geometry.unit_rms_factor()?
    } else {
        1.0
    };
    let z = geometry.heights(h, scale, r)?;
    let reach2 = spec.body().reach().powi(2);
    let mask: Vec<bool> = (0..n * n).map(|c| geometry.r2(c) < reach2).collect();
    let top = (0..n * n)
        .filter(|&c| mask[c])
        .map(|c| z[c])
        .fold(f64::NEG_INFINITY, f64::max);
    let op = NonPeriodicHalfSpace::new(n, n, spec.side, spec.side, e_star);
    let mut c = AdhesiveContact::new(op, &z, Some(&mask), spec.work).ctx("3D adhesive contact")?;
    let (mut rounds, mut iterations) = (0, 0);
    let mut step = |d: f64| {
        let s = c
            .step(Load::Approach(d + top), spec.tolerance)
            .ctx("3D adhesive step")?;
        rounds += s.rounds;
        iterations += s.iterations;
        Ok((s.force, s.separated))
    };
    let mut cycle = drive(spec, top, &mut step)?;
    (cycle.rounds, cycle.iterations) = (rounds, iterations);
    Ok(cycle)
}

/// MRD line `r` of the case with factor `lambda` and the radius `rule` of Eq. 33;
/// `scale` the case's unit-rms factor ([`unit_rms_scale`]), computed once per case.
pub fn cycle_1d(
    spec: &RoughAdhesion3d,
    (hurst, roughness, scale): (f64, f64, f64),
    (rule, lambda): (EdgeRadius, f64),
    r: u64,
    e_star: f64,
) -> Result<Cycle> {
    let geometry = spec.geometry(hurst, *spec.cells.last().unwrap_or(&16));
    let h = roughness * spec.adhesion_length(e_star);
    let n1 = spec.springs();
    let (x, w) = geometry.line(h, scale, lambda, n1, r)?;
    // The springs under the body (all of them for the sphere).
    let (x, w): (Vec<f64>, Vec<f64>) = x
        .into_iter()
        .zip(w)
        .filter(|(x, _)| x.abs() < spec.body().reach())
        .unzip();
    let top = w.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let mut row = AdhesiveRow::new(&x, &w, spec.side / n1 as f64, e_star, spec.work, rule)
        .ctx("MRD adhesive row")?;
    let mut step = |d: f64| {
        // The row's approach is from its highest spring.
        let s = row.step(d + top).ctx("MRD adhesive row")?;
        Ok((s.force, s.attached == 0))
    };
    drive(spec, top, &mut step)
}
