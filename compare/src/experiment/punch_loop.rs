//! A mass on a rough circular punch in the loop of a time integration (Section 12): the
//! faces and MRD lines of the `contact_resonance` and `forced_resonance` kinds, their
//! contact laws, and what a run is measured by (the static stiffness at the preload).
//!
//! Set-up (units of the punch diameter L and E* = 1, as the lambda study): a self-affine
//! face without roll-off (Hurst exponent, bandwidth B: wave vectors 2 pi / L to
//! 2 pi B / L, [`CELLS`] cells per shortest wavelength: a grid of 8 B cells), the disc
//! inscribed in it; MRD lines of [`POINTS`] points per 3D cell with C1D = lambda q C2D
//! (Eq. 76), each in its own loop.

use super::lambda::LambdaSpec;
use super::rough_punch::punch_face;
use bem3d::NonPeriodicHalfSpace;
use dynamics::{Bem3d, ContactLaw, Springs};
use mrd::roughness::synthesis::{line, surface, Amplitudes, Grid};
use mrd::roughness::SelfAffine;
use std::f64::consts::PI;

/// Cells per shortest wavelength of the faces.
pub const CELLS: usize = 8;
/// MRD points per 3D cell across.
pub const POINTS: usize = 16;

/// The preload's default, over the force of full contact (key `preload` of both kinds).
pub fn default_preload() -> f64 {
    0.3
}

/// MRD lines per run's default (key `lines` of both kinds).
pub fn default_lines() -> usize {
    16
}

/// lambda's default: the shipped calibrated table (key `lambda` of both kinds).
pub fn calibrated() -> LambdaSpec {
    LambdaSpec::Named("calibrated".into())
}

/// A punch face: heights, the disc's mask, the approach of full contact.
pub type Face = (Vec<f64>, Vec<bool>, f64);

/// `faces` punch faces at bandwidth `band` and `lines` MRD lines of their spectrum with
/// C1D = lambda q C2D, fixed amplitudes, from `seed` (face r of bandwidth B is
/// realisation `B << 20 ^ r`, line r realisation `1 << 40 ^ r`).
pub fn synthesise(
    hurst: f64,
    band: usize,
    lambda: f64,
    (faces, lines): (usize, usize),
    seed: u64,
) -> mrd::Result<(Vec<Face>, Vec<Vec<f64>>)> {
    let g = CELLS * band;
    let q0 = 2.0 * PI;
    let sa = SelfAffine::new(hurst, q0, q0, q0 * band as f64)?;
    let faces = (0..faces as u64)
        .map(|r| {
            let id = ((band as u64) << 20) ^ r;
            let h = surface(
                &sa,
                &Grid::square(g, 1.0),
                seed,
                id,
                Amplitudes::Deterministic,
            )?;
            let (mask, full) = punch_face(&h, g);
            Ok((h, mask, full))
        })
        .collect::<mrd::Result<Vec<_>>>()?;
    let spec = sa.to_line(lambda);
    let lines = (0..lines as u64)
        .map(|r| {
            line(
                &spec,
                POINTS * g,
                1.0,
                seed,
                (1u64 << 40) ^ r,
                Amplitudes::Deterministic,
            )
        })
        .collect::<mrd::Result<Vec<_>>>()?;
    Ok((faces, lines))
}

/// A scene's lambda, faces, lines and the faces' mean rms height.
pub type Ensemble = (f64, Vec<Face>, Vec<Vec<f64>>, f64);

/// The faces and lines of a scene: lambda at `hurst` as the scene gives it, the
/// synthesis ([`synthesise`]) as the scene's rough-synthesis stage, and the faces' mean
/// rms height over their discs (the unit of every preload F0 / (E* h L)). Returns
/// (lambda, faces, lines, mean rms height).
pub fn ensemble(
    out: &mut crate::report::Section,
    ctx: &crate::context::Context,
    (spec, hurst): (&LambdaSpec, f64),
    band: usize,
    counts: (usize, usize),
    seed: u64,
) -> crate::error::Result<Ensemble> {
    use crate::error::Context as _;
    let lambda = LambdaSpec::at_hurst(std::slice::from_ref(spec), ctx, hurst)?[0];
    let (faces, lines) = out
        .stage(crate::plan::Stage::RoughSynthesis, || {
            synthesise(hurst, band, lambda, counts, seed)
        })
        .ctx("rough surfaces")?;
    let rms = faces.iter().map(|f| rms_on(&f.0, &f.1)).sum::<f64>() / faces.len() as f64;
    Ok((lambda, faces, lines, rms))
}

/// The preload's range, as a reduced force F0 / (E* h L): (1e-4, 10).
pub fn check_preload(preload: f64) -> crate::error::Result<()> {
    if !(preload.is_finite() && preload > 1e-4 && preload < 10.0) {
        return crate::checks::bad(format!(
            "preload = {preload} must lie in (1e-4, 10) (F0 / (E* h L))"
        ));
    }
    Ok(())
}

/// The memory of a free `g x g` punch's 3D solve, checked before computing.
pub fn check_punch_memory(g: usize) -> crate::error::Result<()> {
    crate::checks::check_memory(
        (g * g) as f64 * crate::checks::cell_bytes::ROUGH_FREE,
        &format!("a {g} x {g} punch"),
    )
}

/// The rms height over the cells of `mask`.
pub fn rms_on(h: &[f64], mask: &[bool]) -> f64 {
    let v: Vec<f64> = h.iter().zip(mask).filter(|p| *p.1).map(|p| *p.0).collect();
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
}

/// The 3D law of a face of `g` cells a side (the free half-space, E* = 1, L = 1),
/// warm-started from step to step, solved to `tolerance`.
pub fn face_law(
    (h, mask): (&[f64], &[bool]),
    g: usize,
    tolerance: f64,
) -> dynamics::Result<Bem3d<NonPeriodicHalfSpace>> {
    let op = NonPeriodicHalfSpace::try_new(g, g, 1.0, 1.0, 1.0)?;
    Bem3d::new(op, h, Some(mask.to_vec()), tolerance, 20 * g + 2000)
}

/// MRD's law of a line (E* = 1, on a line of length L, mapped on the disc's area).
pub fn line_law(z: &[f64]) -> dynamics::Result<Springs> {
    Springs::rough_line(z, 1.0, 1.0, PI / 4.0)
}

/// The normal stiffness at the approach `d0` with the history held: a centred difference
/// of two trials 1e-4 of the approach apart (both rolled back).
pub fn static_stiffness(law: &mut dyn ContactLaw, d0: f64) -> dynamics::Result<f64> {
    let h = 1e-4 * d0;
    let mut force_at = |d: f64| -> dynamics::Result<f64> {
        let f = law
            .trial(dynamics::Motion {
                normal: d,
                tangential: 0.0,
                dt: 1.0,
            })?
            .normal;
        law.rollback();
        Ok(f)
    };
    Ok((force_at(d0 + h)? - force_at(d0 - h)?) / (2.0 * h))
}
