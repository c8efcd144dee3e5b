//! The adhesive references: JKR's and Maugis-Dugdale's sphere, Johnson's sinusoid.

use super::{sphere, Computed, Published, References};
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::plan::Stage;
use crate::report::{Figure, Section, Style};
use bem3d::adhesion::AdhesiveContact;
use bem3d::cohesive::CohesiveContact;
use bem3d::{Load, NonPeriodicHalfSpace, PeriodicHalfSpace};
use mrd::adhesion::Control;
use mrd::normal::AxisymmetricContact;
use mrd::reference::hertz;
use std::f64::consts::PI;

impl References {
    /// JKR's pull-off (E* = R = 1, w = 0.002). MRD with Eq. 33 is exact for the sphere
    /// (its pull-off found by a root search to 1e-15 of the radius): 1e-6. The 3D
    /// JKR-limit solve under approach control (loaded to 1.3 a0, unloaded in steps; its
    /// smallest force is force control's pull-off) converges at first order in the cell:
    /// 1.5 / (cells per pull-off radius), above the errors the `adhesion-3d` ladder
    /// measures (24, 9.3, 4.7, 1.7 % at 6.2, 12.5, 25 and 50 cells per pull-off radius).
    pub(super) fn jkr(&self, out: &mut Section) -> Result<Vec<Computed>> {
        let (e, r, w) = (1.0, 1.0, 0.002);
        let profile = sphere(r)?;
        let scale = PI * w * r;
        let depth_max = 0.155;
        let mrd = mrd_jkr_pull_off(out)?;
        let a_top = hertz::radius(r, depth_max);
        // JKR's pull-off radius under force control: (9 pi w R^2 / (8 E*))^(1/3).
        let a_pull = (9.0 * PI * w * r * r / (8.0 * e)).cbrt();
        let n = self.cells;
        let side = 1.25 * 2.0 * a_top;
        let per_radius = a_pull / (side / n as f64);
        let three = out
            .stage(Stage::Adhesion3d, || -> bem3d::Result<f64> {
                let grid = AxisymGrid {
                    cells: n,
                    side,
                    periodic: false,
                };
                let (z, _) = grid.heights(&profile);
                let apex = z.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                let op = NonPeriodicHalfSpace::try_new(n, n, side, side, e)?;
                let mut c = AdhesiveContact::new(op, &z, None, w)?;
                let pull = pull_off_cycle(depth_max, 100, |d| {
                    let s = c.step(Load::Approach(d + apex), 1e-8)?;
                    Ok((s.force, s.separated))
                })?;
                Ok(-pull / scale)
            })
            .ctx("3D adhesion (JKR limit)")?;
        Ok(vec![
            Computed {
                method: "MRD",
                value: mrd,
                tolerance: 1e-6,
                why: "the rule of Hess with Eq. 33, exact for the sphere".into(),
                diagnosis: None,
            },
            Computed {
                method: "3D",
                value: three,
                tolerance: 1.5 / per_radius,
                why: format!("{n}^2 cells, {per_radius:.1} cells per pull-off radius: first order in the cell"),
                diagnosis: None,
            },
        ])
    }

    /// Maugis' pull-off of a sphere with the Dugdale law at lambda = 0.3 (E* = R = 1,
    /// w = 0.002, so sigma0 = 0.0335 and the range w / sigma0 = 0.060). MRD's Eq. 33 is the
    /// zero-range (JKR) limit: its 3/2 whatever lambda, reported and diagnosed as the
    /// method's limit, not its error. The 3D cohesive solve on the free half-space (the
    /// cycle of `tabor_3d`: a grid of 1.25 diameters of the cohesive zone at the deepest
    /// point, 100 approach steps to 0.155 R in and out; the pull-off is the most tensile
    /// force on the way out) errs at first order in the cell against the contact radius at
    /// pull-off (a = 0.49663 (3 pi w R^2 / (4 E*))^(1/3) = 0.0832 R, the data file's
    /// basis): measured +2.2, +1.2, +0.32, +0.27 % at 2.0, 4.1, 8.1 and 16.3 cells per
    /// that radius (32^2 to 256^2; the last step's gain is small, the approach steps and
    /// the grid's extent share the rest); the tolerance 0.1 / (cells per radius) lies 2x
    /// or more above each.
    pub(super) fn maugis_dugdale(&self, out: &mut Section) -> Result<Vec<Computed>> {
        let (e, radius, w, lambda) = (1.0, 1.0, 0.002, 0.3);
        let sigma0 = lambda * (2.0 * PI * w * e * e / (9.0 * radius)).cbrt();
        let scale = PI * w * radius;
        let depth_max = 0.155;
        let steps = 100;
        let a_top = hertz::radius(radius, depth_max);
        let side = 1.25 * 2.0 * (a_top * a_top + 2.0 * radius * w / sigma0).sqrt();
        let n = self.cells;
        let three = out
            .stage(Stage::Adhesion3d, || -> bem3d::Result<f64> {
                let z = bem3d::mask::centred(n, side, |x, y| -(x * x + y * y) / (2.0 * radius));
                let apex = z.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                let op = NonPeriodicHalfSpace::try_new(n, n, side, side, e)?;
                let mut c = CohesiveContact::new(op, &z, None, w, sigma0)?;
                let pull = pull_off_cycle(depth_max, steps, |d| {
                    let s = c.step(d + apex, 1e-8)?;
                    Ok((s.force, s.contact_cells == 0 && s.cohesive_cells == 0))
                })?;
                Ok(-pull / scale)
            })
            .ctx("3D cohesive contact (Maugis-Dugdale)")?;
        let a_pull = 0.49663 * (3.0 * PI * w * radius * radius / (4.0 * e)).cbrt();
        let per_radius = a_pull / (side / n as f64);
        Ok(vec![
            Computed {
                method: "MRD",
                value: mrd_jkr_pull_off(out)?,
                tolerance: 1e-6,
                why: "the rule of Hess with Eq. 33: the zero-range (JKR) limit at any lambda".into(),
                diagnosis: Some(
                    "Eq. 33 is the JKR limit of vanishing range: at lambda = 0.3 the Dugdale zone outside the contact carries a tension it does not count (MRD's pull-off is within 2 % of Maugis' from lambda = 3 on, `adhesion-tabor`)",
                ),
            },
            Computed {
                method: "3D cohesive",
                value: three,
                tolerance: 0.1 / per_radius,
                why: format!("{n}^2 cells over 1.25 cohesive-zone diameters, {per_radius:.1} cells per contact radius at pull-off, approach steps of 0.155 R / {steps}: first order in the cell"),
                diagnosis: None,
            },
        ])
    }

    /// Johnson's (1995) pull-off of a sinusoidal surface in JKR adhesion at alpha = 0.3
    /// (E* = lambda = 1, Delta = 0.01): a y-invariant strip of 4 rows on the periodic
    /// half-space, whose response to a y-invariant load is the plane-strain one exactly,
    /// so the grid's error is the cell along x alone. The periodic half-space takes the
    /// load as a mean pressure: loaded to 0.2 p* in steps of 0.01 p*, unloaded in steps
    /// of 0.001 p* until the contact separates; the last mean pressure in contact is the
    /// pull-off (to 0.001 p*). MRD does not apply (the surface is not a body of
    /// revolution). A first-order criterion would err by about 1.5 / (cells per contact
    /// half-width at pull-off), as for the sphere.
    ///
    /// It does not hold, and the cause is measured: along the whole receding branch the
    /// 3D mean pressure follows Johnson's curve with alpha multiplied by 1.36 (grid-aligned
    /// front) or 1.15 (a wave along the grid's diagonal), at 256 and 512 cells per
    /// wavelength alike. Pohrt and Popov's one-cell criterion reads the compliance of one
    /// cell, which against the sampling along a straight front's normal sets its
    /// toughness (a diagonal wave is sampled h / sqrt(2) apart: 1.36 / 2^(1/4)), and does
    /// not converge to JKR's there; the sphere's staircase rim does (the `jkr-pull-off`
    /// row). docs/verification.md states what this means for rough surfaces.
    ///
    /// The cohesive solver (Maugis-Dugdale law, finite range) on the same strip does
    /// converge to Johnson's value: its error is set by the cells per Dugdale length
    /// `l_D = E* w / sigma0^2` (here `l_D = 0.4 a` at pull-off, whose own finite-range
    /// effect is 5e-5 p* between 0.4 a and 0.2 a). Measured on this strip: +9.8, +5.4,
    /// +2.9, +1.5 % at 12, 24, 48 and 96 cells per `l_D` (observed order 0.79;
    /// extrapolated -0.5 %); the tolerance `n^-0.75` (n cells per `l_D`) lies above every
    /// rung. Approach control (the mean gap, module `bem3d::cohesive`), loaded to 0.2 p*
    /// and unloaded in steps of Delta / 400; the smallest force on the way is the pull-off.
    pub(super) fn sinusoid(&self, out: &mut Section, r: &Published) -> Result<Vec<Computed>> {
        let (e, lambda, delta, alpha) = (1.0, 1.0, 0.01, 0.3);
        let p_star = PI * e * delta / lambda;
        let w = alpha * alpha * PI * PI * e * delta * delta / (2.0 * lambda);
        // The contact half-width at pull-off, a / lambda (the data file's basis).
        let a_pull = 0.058569 * lambda;
        let (nx, ny) = (8 * self.cells, 4);
        let h = lambda / nx as f64;
        let per_half_width = a_pull / h;
        // The strip: the sinusoid's row, repeated over the rows, and its half-space.
        let z = (0..nx)
            .map(|i| -delta * (1.0 - (2.0 * PI * i as f64 / nx as f64).cos()))
            .collect::<Vec<f64>>()
            .repeat(ny);
        let area = lambda * ny as f64 * h;
        let strip = || PeriodicHalfSpace::try_new(nx, ny, lambda, ny as f64 * h, e);
        let (three, branch) = out
            .stage(
                Stage::Adhesion3d,
                || -> bem3d::Result<(f64, Vec<(f64, f64)>)> {
                    let mut c = AdhesiveContact::new(strip()?, &z, None, w)?;
                    for k in 1..=20 {
                        c.step(Load::MeanPressure(0.01 * k as f64 * p_star), 1e-10)?;
                    }
                    // The unloading branch: (contact half-width / lambda, p / p*).
                    let mut branch = Vec::new();
                    for k in (-1000..200).rev() {
                        let p = 0.001 * k as f64;
                        let s = c.step(Load::MeanPressure(p * p_star), 1e-10)?;
                        if s.separated {
                            return Ok((-(p + 0.001), branch));
                        }
                        let half_width = s.contact_cells as f64 / ny as f64 * h / 2.0;
                        branch.push((half_width / lambda, p));
                    }
                    Err(bem3d::BemError::Infeasible(
                        "the sinusoid did not separate at a mean tension of p*".into(),
                    ))
                },
            )
            .ctx("3D adhesion of a sinusoid (JKR limit)")?;
        let sigma0 = (e * w / (0.4 * a_pull)).sqrt();
        let per_dugdale = 0.4 * a_pull / h;
        let (cohesive, cohesive_branch) = out
            .stage(
                Stage::Adhesion3d,
                || -> bem3d::Result<(f64, Vec<(f64, f64)>)> {
                    let mut c = CohesiveContact::new(strip()?, &z, None, w, sigma0)?;
                    let dd = delta / 400.0;
                    let mut d = 0.0;
                    for _ in 0..400 {
                        d += dd;
                        if c.step(d, 1e-10)?.force / area >= 0.2 * p_star {
                            break;
                        }
                    }
                    let (mut smallest, mut branch) = (f64::INFINITY, Vec::new());
                    for _ in 0..8000 {
                        d -= dd;
                        let s = c.step(d, 1e-10)?;
                        if s.contact_cells == 0 && s.cohesive_cells == 0 {
                            return Ok((-smallest / area / p_star, branch));
                        }
                        smallest = smallest.min(s.force);
                        let half_width = s.contact_cells as f64 / ny as f64 * h / 2.0;
                        branch.push((half_width / lambda, s.force / area / p_star));
                    }
                    Err(bem3d::BemError::Infeasible(
                        "the sinusoid did not separate while unloading (cohesive)".into(),
                    ))
                },
            )
            .ctx("3D adhesion of a sinusoid (cohesive, Maugis-Dugdale)")?;
        let top = branch
            .iter()
            .chain(&cohesive_branch)
            .map(|b| b.0)
            .fold(0.0, f64::max);
        // Johnson's mean pressure at the contact half-width a, for a Johnson parameter.
        let johnson = |alpha: f64| -> Vec<(f64, f64)> {
            (1..=200)
                .map(|k| {
                    let a = top * k as f64 / 200.0;
                    let psi = PI * a / lambda;
                    (a, psi.sin().powi(2) - alpha * psi.tan().sqrt())
                })
                .collect()
        };
        out.figures.push(
            Figure::new(
                "johnson_sinusoid",
                "JKR adhesion of a sinusoid (Johnson 1995, alpha = 0.3), unloading",
                "contact half-width over wavelength a / lambda [1]",
                "mean pressure over full-contact pressure p / p* [1]",
            )
            .plot("Johnson (1995), closed form", johnson(alpha), Style::Line)
            .plot(
                "closed form at 1.36 alpha (the diagnosis)",
                johnson(1.36 * alpha),
                Style::Dashed,
            )
            .plot(
                format!("3D, JKR limit (one-cell criterion), {nx} cells per wavelength"),
                branch,
                Style::Markers,
            )
            .plot(
                format!("3D, cohesive (Maugis-Dugdale, Dugdale length 0.4 a), {nx} cells per wavelength"),
                cohesive_branch,
                Style::Crosses,
            )
            .plot(
                "pull-off: Johnson (1995)",
                vec![(a_pull / lambda, -r.value)],
                Style::Crosses,
            ),
        );
        Ok(vec![Computed {
            method: "3D",
            value: three,
            tolerance: 1.5 / per_half_width,
            why: format!(
                "{nx} x {ny} cells per wavelength (y-invariant), {per_half_width:.1} cells per contact half-width at pull-off, pull-off to 0.001 p*"
            ),
            diagnosis: Some(
                "the one-cell criterion (Pohrt & Popov) gives a straight front a toughness set by the cells' orientation: Johnson's curve is followed with alpha x 1.36 (aligned front), x 1.15 (diagonal), at 256 to 2048 cells per wavelength alike; it converges on curved fronts only",
            ),
        },
        Computed {
            method: "3D cohesive",
            value: cohesive,
            tolerance: per_dugdale.powf(-0.75),
            why: format!(
                "Maugis-Dugdale, Dugdale length 0.4 a, {nx} x {ny} cells per wavelength, {per_dugdale:.1} cells per Dugdale length: measured order 0.79"
            ),
            diagnosis: None,
        }])
    }
}

/// An adhesive sphere's approach cycle: `step(d)` to the approach `d` (from the apex)
/// in `steps` equal steps to `depth_max`, then out in the same steps until `step` reports
/// the body apart; returns the most tensile force on the way out before that (the
/// force-controlled pull-off where the steps resolve it).
fn pull_off_cycle(
    depth_max: f64,
    steps: usize,
    mut step: impl FnMut(f64) -> bem3d::Result<(f64, bool)>,
) -> bem3d::Result<f64> {
    let dd = depth_max / steps as f64;
    for k in 1..=steps {
        step(dd * k as f64)?;
    }
    let mut smallest = f64::INFINITY;
    for k in 0..100 * steps {
        let (force, apart) = step(depth_max - dd * k as f64)?;
        if apart {
            return Ok(smallest);
        }
        smallest = smallest.min(force);
    }
    Err(bem3d::BemError::Infeasible(
        "the sphere did not come apart while unloading".into(),
    ))
}

/// MRD's pull-off of a sphere by the rule of Hess with Eq. 33 (E* = R = 1, w = 0.002,
/// loaded to 0.155 R), over pi w R: a root search, exact for JKR's sphere.
fn mrd_jkr_pull_off(out: &mut Section) -> Result<f64> {
    let (e, r, w, depth_max) = (1.0, 1.0, 0.002, 0.155);
    let profile = sphere(r)?;
    out.stage(Stage::AdhesionSemiAnalytic, || -> mrd::Result<f64> {
        let contact = AxisymmetricContact::new(profile.clone(), e)?;
        let a_max = contact.state_at_depth(depth_max)?.radius;
        let ad = mrd::adhesion::AdhesiveContact::new(contact, w)?;
        Ok(-ad.pull_off(a_max, Control::Force)?.force / (PI * w * r))
    })
    .ctx("MRD adhesion (Eq. 33)")
}
