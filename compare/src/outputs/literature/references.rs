//! `references`: published reference results (`compare/data/references.toml`: each with
//! its citation, units, uncertainty and the problem's statement), each reproduced by MRD
//! and by the 3D solvers on the problem as the source states it, with the deviation and
//! a verdict against a tolerance the workbench justifies for its own discretisation.
//!
//! A computation holds when `|workbench - published| <= k u + tolerance |published|`,
//! with u the published uncertainty (k = 1 for a bound such as the rounding of printed
//! digits, 2 for a standard uncertainty, u = 0 for an exact result) and the tolerance
//! the workbench's discretisation error at the resolution the scene gives, stated beside
//! each computation below. A computation that does not hold is a failure of the run
//! (exit status 4), reported with its numbers.
//!
//! The problems are the references' own, dimensionless (E* = R = 1): the kind reads no
//! profile, and the scene's material must be `e_star = 1` alone (no G*: the tangential
//! reference takes nu = 0.3).

use crate::checks::{bad, count_in};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::{equivalent_body, AxisymGrid};
use crate::experiment::impact::{bem3d_law, first_contact, Strike};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use bem3d::adhesion::AdhesiveContact;
use bem3d::cohesive::CohesiveContact;
use bem3d::tangential::{CerrutiFree, PartialSlip};
use bem3d::viscoelastic::{Relaxation, TransientContact};
use bem3d::{Load, NonPeriodicHalfSpace, PeriodicHalfSpace, SlidingContact, SolverOptions};
use dynamics::{ContactLaw, Springs};
use mrd::adhesion::Control;
use mrd::normal::AxisymmetricContact;
use mrd::oscillation::dissipation_semi_analytic;
use mrd::reference::{hertz, hertz_impact};
use mrd::tangential::TangentialContact;
use mrd::viscoelastic::{Prony, RowLoad, SpringRow};
use mrd::{Profile, Shape};
use serde::Deserialize;
use std::f64::consts::PI;

/// The published results, embedded: the data file is their one owner.
const DATA: &str = include_str!("../../../data/references.toml");

/// One published result (the data file's header documents each key).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Published {
    pub id: String,
    pub quantity: String,
    pub units: String,
    pub value: f64,
    pub uncertainty: f64,
    pub uncertainty_kind: String,
    pub uncertainty_basis: String,
    pub citation: String,
    pub doi: String,
    pub location: String,
    pub problem: String,
}

impl Published {
    /// How many published uncertainties the verdict allows (module docs).
    fn coverage(&self) -> f64 {
        match self.uncertainty_kind.as_str() {
            "standard" => 2.0,
            _ => 1.0,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    reference: Vec<Published>,
}

/// Parses and checks a references file: every key present (serde), every text
/// non-empty (the DOI may be empty for a book), the value finite, the uncertainty finite
/// and >= 0 and of a known kind (0 exactly when the result is exact), the ids unique.
pub fn parse(text: &str) -> std::result::Result<Vec<Published>, String> {
    let file: File = toml::from_str(text).map_err(|e| format!("references: {e}"))?;
    let mut seen = Vec::new();
    for r in &file.reference {
        let id = &r.id;
        for (key, v) in [
            ("id", &r.id),
            ("quantity", &r.quantity),
            ("units", &r.units),
            ("uncertainty_basis", &r.uncertainty_basis),
            ("citation", &r.citation),
            ("location", &r.location),
            ("problem", &r.problem),
        ] {
            if v.trim().is_empty() {
                return Err(format!("reference '{id}': {key} is empty"));
            }
        }
        if !r.value.is_finite() {
            return Err(format!("reference '{id}': value {} is not finite", r.value));
        }
        let exact = r.uncertainty_kind == "exact";
        let known = ["exact", "bound", "standard"].contains(&r.uncertainty_kind.as_str());
        let sound = known && r.uncertainty.is_finite() && r.uncertainty >= 0.0;
        if !sound || exact != (r.uncertainty == 0.0) {
            return Err(format!(
                "reference '{id}': uncertainty {} of kind '{}': give a finite uncertainty >= 0 of kind exact (0), bound or standard (> 0)",
                r.uncertainty, r.uncertainty_kind
            ));
        }
        if seen.contains(id) {
            return Err(format!("reference '{id}' is listed twice"));
        }
        seen.push(id.clone());
    }
    if file.reference.is_empty() {
        return Err("references: the file lists no [[reference]]".into());
    }
    Ok(file.reference)
}

/// The embedded published results.
pub fn published() -> std::result::Result<Vec<Published>, String> {
    parse(DATA)
}

/// The references this kind computes, in the data file's order of ids.
pub const COMPUTED: &[&str] = &[
    "hertz-impact-duration",
    "jkr-pull-off",
    "cattaneo-stick-radius",
    "johnson-sinusoid-pull-off",
    "mindlin-deresiewicz-energy",
    "viscoelastic-sinusoid-friction",
    "lee-radok-sphere",
    "ting-sphere-unloading",
    "maugis-dugdale-pull-off",
];

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct References {
    /// Cells per side of the 3D grids (the tolerances of the 3D computations follow
    /// from it, module docs).
    #[serde(default = "default_cells")]
    cells: usize,
    /// MRD springs on the half line.
    #[serde(default = "default_springs")]
    springs: usize,
    /// Time steps per contact time of the impacts (MRD's; the 3D run takes a tenth).
    #[serde(default = "default_steps")]
    steps: usize,
}

fn default_cells() -> usize {
    64
}
fn default_springs() -> usize {
    2000
}
fn default_steps() -> usize {
    2000
}

/// One computation of a reference: the method, its value, and the tolerance of its
/// discretisation with the reason.
#[derive(Clone)]
struct Computed {
    method: &'static str,
    value: f64,
    tolerance: f64,
    why: String,
    /// Why a computation known not to reproduce the reference does not (its measured
    /// cause): reported as "does not hold (diagnosed)" without failing the run, and
    /// pinned by the CLI test, so a change that makes it hold is seen.
    diagnosis: Option<&'static str>,
}

impl Output for References {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if ctx.profile.is_some() {
            return bad(
                "references solve the published problems on their own bodies: remove [profile]",
            );
        }
        if ctx.material.g_star.is_some() {
            return bad("references solve the published problems with their own materials (Cattaneo-Mindlin's at nu = 0.3): remove g_star or the bodies from [material], keep e_star = 1");
        }
        if ctx.material.e_star != 1.0 {
            return bad(format!(
                "references solve the published problems in their own dimensionless units: set e_star = 1 (the scene gives {})",
                ctx.material.e_star
            ));
        }
        count_in("cells", self.cells as u64, 32..=512)?;
        count_in("springs", self.springs as u64, 200..=1_000_000)?;
        count_in("steps", self.steps as u64, 500..=1_000_000)?;
        published().map_err(crate::error::CompareError::Scene)?;
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        vec![
            Stage::Dynamics,
            Stage::Dynamics3d,
            Stage::AdhesionSemiAnalytic,
            Stage::Adhesion3d,
            Stage::Tangential,
            Stage::Tangential3d,
            Stage::ViscoelasticSliding3d,
            Stage::Viscoelastic,
            Stage::Viscoelastic3d,
        ]
    }

    fn run(&self, _: &Env, out: &mut Section) -> Result<()> {
        let refs = published().map_err(crate::error::CompareError::Scene)?;
        let mut rows = Vec::new();
        // Lee-Radok's loading and Ting's withdrawal are two instants of one history.
        let mut indentation: Option<[Vec<Computed>; 2]> = None;
        for (k, r) in refs.iter().enumerate() {
            let computed = match r.id.as_str() {
                "hertz-impact-duration" => self.impact(out)?,
                "jkr-pull-off" => self.jkr(out)?,
                "cattaneo-stick-radius" => self.cattaneo(out)?,
                "johnson-sinusoid-pull-off" => self.sinusoid(out, r)?,
                "mindlin-deresiewicz-energy" => self.mindlin_deresiewicz(out)?,
                "viscoelastic-sinusoid-friction" => self.sliding_sinusoid(out)?,
                "maugis-dugdale-pull-off" => self.maugis_dugdale(out)?,
                id @ ("lee-radok-sphere" | "ting-sphere-unloading") => {
                    if indentation.is_none() {
                        indentation = Some(self.viscoelastic_sphere(out)?);
                    }
                    let [lee_radok, ting] = indentation.as_ref().expect("computed above");
                    if id == "lee-radok-sphere" {
                        lee_radok.clone()
                    } else {
                        ting.clone()
                    }
                }
                other => {
                    out.failures
                        .push(format!("reference '{other}' has no computation"));
                    continue;
                }
            };
            for c in computed {
                rows.push((k, r, c));
            }
        }
        self.report(out, &rows);
        Ok(())
    }
}

impl References {
    /// Hertz's impact (E* = R = 1, m = 1e-3, v = 0.05), integrated in time by velocity
    /// Verlet with the contact at every step. MRD (the rule of Hess, exact for the
    /// sphere) errs by the time step only, at second order: 1e-3 of the contact time at
    /// 2000 steps bounds it with room (the `impact` scene measures 3e-8 at 4000). The 3D
    /// solve in the loop errs by its grid (the highest cell below the apex, the disc of
    /// cells): 1 % at 32 cells per side or more (the `impact` scene measures 4.3e-4 at
    /// 64^2).
    fn impact(&self, out: &mut Section) -> Result<Vec<Computed>> {
        let (e, r, m, v) = (1.0, 1.0, 1e-3, 0.05);
        let profile = sphere(r)?;
        let tc = hertz_impact::duration(e, r, m, v);
        let dmax = hertz_impact::max_approach(e, r, m, v);
        let fmax = hertz_impact::max_force(e, r, m, v);
        let a = hertz::radius(r, dmax);
        // t_c / (m^2 / (R E*^2 v))^(1/5): the published coefficient.
        let scale = (m * m / (r * e * e * v)).powf(0.2);
        let strike = Strike {
            mass: m,
            speed: v,
            tc,
            fmax,
            dmax,
        };
        let run = |law: &mut dyn ContactLaw, steps: usize| -> dynamics::Result<f64> {
            let (samples, _, _) = strike.run(law, steps)?;
            Ok(first_contact(&samples).map_or(f64::NAN, |c| c.duration) / scale)
        };
        let mrd = out
            .stage(Stage::Dynamics, || {
                let mut law = Springs::body(&profile, e, self.springs, 2.0 * a)?;
                run(&mut law, self.steps)
            })
            .ctx("MRD in the loop")?;
        let n = self.cells;
        let three = out
            .stage(Stage::Dynamics3d, || -> dynamics::Result<f64> {
                let mut law = bem3d_law(&profile, e, n, 2.0 * 1.5 * a, 1e-8)?;
                run(&mut law, (self.steps / 10).max(100))
            })
            .ctx("3D in the loop")?;
        Ok(vec![
            Computed {
                method: "MRD",
                value: mrd,
                tolerance: 1e-3,
                why: format!(
                    "{} springs, {} steps per contact time: second order in the step",
                    self.springs, self.steps
                ),
                diagnosis: None,
            },
            Computed {
                method: "3D",
                value: three,
                tolerance: 1e-2,
                why: format!(
                    "{n}^2 cells over 1.5 contact diameters: the grid's apex and disc of cells"
                ),
                diagnosis: None,
            },
        ])
    }

    /// JKR's pull-off (E* = R = 1, w = 0.002). MRD with Eq. 33 is exact for the sphere
    /// (its pull-off found by a root search to 1e-15 of the radius): 1e-6. The 3D
    /// JKR-limit solve under approach control (loaded to 1.3 a0, unloaded in steps; its
    /// smallest force is force control's pull-off) converges at first order in the cell:
    /// 1.5 / (cells per pull-off radius), above the errors the `adhesion-3d` ladder
    /// measures (24, 9.3, 4.7, 1.7 % at 6.2, 12.5, 25 and 50 cells per pull-off radius).
    fn jkr(&self, out: &mut Section) -> Result<Vec<Computed>> {
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

    /// Cattaneo-Mindlin's stick radius at Q = mu P / 2 on [`SlipSphere`]. MRD's
    /// tangential springs are exact for the sphere: 1e-9. The 3D partial slip under the
    /// 3D Hertz pressure counts its stick cells (c = sqrt(cells x area / pi)): a rim of
    /// cells, one cell per contact radius at most.
    fn cattaneo(&self, out: &mut Section) -> Result<Vec<Computed>> {
        let sphere = SlipSphere::new()?;
        let q = 0.5 * sphere.mu * sphere.p;
        let mrd = out
            .stage(Stage::Tangential, || -> mrd::Result<f64> {
                Ok(sphere.springs.at_force(q)?.stick_radius / sphere.a)
            })
            .ctx("MRD tangential springs")?;
        let n = self.cells;
        let (side, a) = (sphere.side(), sphere.a);
        let h = side / n as f64;
        let three = out
            .stage(Stage::Tangential3d, || -> bem3d::Result<f64> {
                let s = sphere.slip_3d(n)?.load(q, 1e-10)?;
                Ok((s.stick_cells as f64 * h * h / PI).sqrt() / a)
            })
            .ctx("3D partial slip")?;
        Ok(vec![
            Computed {
                method: "MRD",
                value: mrd,
                tolerance: 1e-9,
                why: "MRD's tangential springs (G*), exact for the sphere".into(),
                diagnosis: None,
            },
            Computed {
                method: "3D",
                value: three,
                tolerance: h / a,
                why: format!(
                    "{n}^2 cells, {:.1} cells per contact radius: the stick zone counted in cells",
                    a / h
                ),
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
    fn maugis_dugdale(&self, out: &mut Section) -> Result<Vec<Computed>> {
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

    /// Mindlin and Deresiewicz's energy per cycle of a tangential force between -F* and
    /// F* = mu P / 2 on [`SlipSphere`], over (mu P)^2 / (G* a). MRD's springs dissipate
    /// the sphere's energy exactly (`mrd::oscillation::dissipation_semi_analytic` at the
    /// springs' displacement amplitude of F*, a quadrature to 1e-12): 1e-9. The 3D
    /// partial slip raises the force to F* and cycles it twice in
    /// [`CYCLE_STEPS`] force steps per half cycle, the energy summed over the second
    /// cycle's slip. Its error is set by the slip annulus (0.21 a wide) counted in cells,
    /// first order and of either sign: measured +1.2 %, -0.25 %, +0.016 %, -0.010 % at
    /// 12.8, 25.6, 51.2 and 102.4 cells per contact radius; the tolerance 0.3 / (cells per
    /// radius) lies above each by 2x or more (the steps' share is within the last: 1e-4).
    fn mindlin_deresiewicz(&self, out: &mut Section) -> Result<Vec<Computed>> {
        let sphere = SlipSphere::new()?;
        let (mu, p, a) = (sphere.mu, sphere.p, sphere.a);
        let amplitude = 0.5 * mu * p;
        let scale = (mu * p).powi(2) / (sphere.g_star * a);
        let mrd = out
            .stage(Stage::Tangential, || -> mrd::Result<f64> {
                let normal = &sphere.springs.normal;
                let shift = sphere.springs.at_force(amplitude)?.displacement;
                let w = dissipation_semi_analytic(
                    &sphere.profile,
                    sphere.e,
                    sphere.g_star,
                    mu,
                    normal.depth,
                    shift,
                )?;
                Ok(w / scale)
            })
            .ctx("MRD tangential springs")?;
        let n = self.cells;
        let per_radius = a / (sphere.side() / n as f64);
        let three = out
            .stage(Stage::Tangential3d, || -> bem3d::Result<f64> {
                let cycle = sphere.slip_3d(n)?.cycle(amplitude, CYCLE_STEPS, 2, 1e-10)?;
                Ok(cycle.dissipated / scale)
            })
            .ctx("3D partial slip")?;
        Ok(vec![
            Computed {
                method: "MRD",
                value: mrd,
                tolerance: 1e-9,
                why: "MRD's tangential springs (G*), the dissipation integral in closed form for the sphere".into(),
                diagnosis: None,
            },
            Computed {
                method: "3D",
                value: three,
                tolerance: 0.3 / per_radius,
                why: format!(
                    "{n}^2 cells, {per_radius:.1} cells per contact radius, {CYCLE_STEPS} force steps per half cycle: the slip annulus in cells"
                ),
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
    fn sinusoid(&self, out: &mut Section, r: &Published) -> Result<Vec<Computed>> {
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

    /// The friction of a sinusoid in full contact sliding over a standard linear solid
    /// (the data file's problem: lambda = E_inf = tau = 1, h0 = 0.01, p = 0.5, E_1 = 9, k v
    /// tau = 1). The 3D steady-sliding solver on a y-invariant strip of `cells` x 4
    /// cells: the surface is one Fourier mode, which every grid carries exactly, so the
    /// error is the solver's (its tolerance 1e-10 on the gap, the friction read from the
    /// pressure on the spectral slope): 1e-6. MRD does not apply: the surface is neither
    /// a body of revolution nor an isotropic random surface (Eq. 82's xi is for those).
    fn sliding_sinusoid(&self, out: &mut Section) -> Result<Vec<Computed>> {
        let (lambda, h0, tau, e_inf, e_1, p) = (1.0, 0.01, 1.0, 1.0, 9.0, 0.5);
        let k = 2.0 * PI / lambda;
        let v = 1.0 / (k * tau);
        let (nx, ny) = (self.cells, 4);
        let h = lambda / nx as f64;
        let z = (0..nx)
            .map(|i| h0 * (k * i as f64 * h).cos())
            .collect::<Vec<f64>>()
            .repeat(ny);
        // E*(omega) of the standard linear solid: (E', E'').
        let modulus = |omega: f64| {
            let x = omega * tau;
            let d = 1.0 + x * x;
            (e_inf + e_1 * x * x / d, e_1 * x / d)
        };
        let mu = out
            .stage(Stage::ViscoelasticSliding3d, || -> bem3d::Result<f64> {
                let mut s = SlidingContact::new(nx, ny, lambda, ny as f64 * h, &z, v, &modulus)?;
                let sol = s.solve(p, &SolverOptions::new(1e-10, 1000), None)?;
                if sol.contact.contact_cells != nx * ny {
                    return Err(bem3d::BemError::Infeasible(format!(
                        "the sinusoid is not in full contact ({} of {} cells)",
                        sol.contact.contact_cells,
                        nx * ny
                    )));
                }
                Ok(sol.mu)
            })
            .ctx("3D steady sliding of a sinusoid")?;
        Ok(vec![Computed {
            method: "3D",
            value: mu,
            tolerance: 1e-6,
            why: format!("{nx} x {ny} cells per wavelength (y-invariant): one Fourier mode, exact on the grid; solver tolerance 1e-10"),
            diagnosis: None,
        }])
    }

    /// Lee and Radok's force at the end of a constant-rate indentation (t = t_m) and
    /// Ting's during the withdrawal at the same rate (t = 1.25 t_m), one history: a sphere
    /// (R = 1, depth rate v = 0.01, t_m = tau = 1) on a standard linear solid (E_inf = 1,
    /// E_1 = 9). MRD: the viscoelastic springs of Eq. 63 that leave the contact at zero
    /// force (`mrd::viscoelastic::SpringRow`, Ting's problem in one dimension, where the
    /// rule of Hess gives Ting's force exactly), `springs` on 1.2 contact radii, `steps`
    /// per t_m. 3D: `bem3d::viscoelastic::TransientContact` on the free half-space,
    /// `cells`^2 over 2.5 contact radii, a tenth of the steps. Their tolerances (measured
    /// errors in the comments below) and a figure of the whole force history, to after
    /// the contact has ended, against the closed form ([`Indentation::ting_force`]).
    fn viscoelastic_sphere(&self, out: &mut Section) -> Result<[Vec<Computed>; 2]> {
        let law = Indentation::REFERENCE;
        let profile = sphere(law.r)?;
        let a_max = (law.r * law.v * law.tm).sqrt();
        let scale = law.hertz_relaxed();
        // Steps per t_m: a multiple of 20, so that 1.25 t_m and the end of the run, 1.6
        // t_m (after the contact has ended, at 1.542 t_m), are steps' ends.
        let mrd_steps = 20 * self.steps.div_ceil(20);
        let bem_steps = 20 * (self.steps / 10).div_ceil(20);
        let n = self.springs;
        let dx = 1.2 * a_max / n as f64;
        let mrd = out
            .stage(Stage::Viscoelastic, || -> mrd::Result<Vec<(f64, f64)>> {
                let prony = Prony::new(law.e_inf, vec![(law.e_1, law.tau)])?;
                let gaps: Vec<f64> = (0..n).map(|i| profile.z1d((i as f64 + 0.5) * dx)).collect();
                let mut row = SpringRow::new(&gaps, dx, &prony)?;
                let dt = law.tm / mrd_steps as f64;
                let mut history = Vec::new();
                for k in 1..=mrd_steps * 8 / 5 {
                    let t = k as f64 * dt;
                    // The row is the half line: its mirror doubles the force.
                    let s = row.step(dt, RowLoad::Depth(law.depth(t)))?;
                    history.push((t / law.tm, 2.0 * s.force / scale));
                }
                Ok(history)
            })
            .ctx("MRD viscoelastic springs")?;
        let cells = self.cells;
        let side = 2.5 * a_max;
        let three = out
            .stage(
                Stage::Viscoelastic3d,
                || -> bem3d::Result<Vec<(f64, f64)>> {
                    let grid = AxisymGrid {
                        cells,
                        side,
                        periodic: false,
                    };
                    let (z, _) = grid.heights(&profile);
                    let apex = z.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                    let op = NonPeriodicHalfSpace::try_new(cells, cells, side, side, law.e_inf)?;
                    let relaxation = Relaxation::new(law.e_inf, vec![(law.e_1, law.tau)])?;
                    let mut c = TransientContact::new(op, &z, None, relaxation)?;
                    let opts = SolverOptions::new(1e-10, 10_000);
                    let dt = law.tm / bem_steps as f64;
                    let mut history = Vec::new();
                    for k in 1..=bem_steps * 8 / 5 {
                        let t = k as f64 * dt;
                        // The approach counts from the highest cell, below the apex by -apex.
                        let s = c.step(dt, Load::Approach(law.depth(t) + apex), &opts)?;
                        history.push((t / law.tm, s.force / scale));
                    }
                    Ok(history)
                },
            )
            .ctx("3D viscoelastic indentation")?;
        let at = |h: &[(f64, f64)], steps: usize, quarters: usize| h[steps * quarters / 4 - 1].1;
        let per_radius = a_max / (side / cells as f64);
        let computed = |quarters: usize, mrd_tol: f64, bem_tol: f64| {
            vec![
                Computed {
                    method: "MRD",
                    value: at(&mrd, mrd_steps, quarters),
                    tolerance: mrd_tol,
                    why: format!("{n} springs on 1.2 contact radii, {mrd_steps} steps per t_m"),
                    diagnosis: None,
                },
                Computed {
                    method: "3D",
                    value: at(&three, bem_steps, quarters),
                    tolerance: bem_tol,
                    why: format!(
                        "{cells}^2 cells, {per_radius:.1} cells per largest contact radius, {bem_steps} steps per t_m"
                    ),
                    diagnosis: None,
                },
            ]
        };
        let closed: Vec<(f64, f64)> = (0..=320)
            .map(|k| {
                let t = 1.6 * law.tm * k as f64 / 320.0;
                (t / law.tm, law.ting_force(t) / scale)
            })
            .collect();
        out.figures.push(
            Figure::new(
                "viscoelastic_sphere",
                "A sphere pressed into a standard linear solid and withdrawn (Lee & Radok 1960, Ting 1966)",
                "time over the end of loading t / t_m [1]",
                "force over the relaxed Hertz force at the deepest point F / F_H [1]",
            )
            .plot("Lee-Radok (loading), Ting (withdrawal): closed form", closed, Style::Line)
            .plot(format!("MRD, {n} springs, {mrd_steps} steps per t_m"), mrd.clone(), Style::Dashed)
            .plot(
                format!("3D, {cells}^2 cells, {bem_steps} steps per t_m (every 5th step)"),
                three.iter().skip(4).step_by(5).cloned().collect(),
                Style::Markers,
            )
            .plot(
                "published values (t = t_m: Lee-Radok; 1.25 t_m: Ting)",
                [4, 5].map(|q| (0.25 * q as f64, law.ting_force(0.25 * q as f64 * law.tm) / scale)).to_vec(),
                Style::Crosses,
            ),
        );
        // MRD: second order in the spring width and the step (measured at 500, 1000,
        // 2000 and 4000 springs and steps: Lee-Radok -6.5e-7, -1.7e-7, -4.2e-8, -1.0e-8;
        // Ting -2.6e-6, +1.8e-7, +2.9e-8, -9.4e-9, its contact edge crossing springs).
        let mrd_tol = 1e-6 * (2000.0 / n.min(mrd_steps) as f64).powi(2);
        // 3D: about second order in the cell, not monotone (measured at 12.8, 25.6, 51.2
        // and 102.4 cells per largest contact radius, 200 steps per t_m: Lee-Radok
        // +3.4e-4, +4.0e-5, +1.8e-5, +7.9e-7; Ting +1.1e-4, +1.1e-4, +2.5e-5, +3.1e-6);
        // the step's share is under 1e-5 (Ting at 25.6 cells per radius: +0.97, +1.06,
        // +1.09, +1.10e-4 at 100, 200, 400, 800 steps per t_m). 0.2 / (cells per radius)^2
        // lies 2.5x or more above each.
        let bem_tol = 0.2 / per_radius.powi(2);
        Ok([computed(4, mrd_tol, bem_tol), computed(5, mrd_tol, bem_tol)])
    }

    /// The table (one row per computation), its Markdown twin with the citations, the
    /// scalars, and a failure per computation that does not hold.
    fn report(&self, out: &mut Section, rows: &[(usize, &Published, Computed)]) {
        let mut t = Table::new(
            "references",
            &[
                "reference [1]",
                "method [0 MRD, 1 3D, 2 3D cohesive]",
                "published [1]",
                "uncertainty [1]",
                "workbench [1]",
                "deviation_rel [1]",
                "allowed_rel [1]",
                "holds [0/1]",
            ],
        );
        t.notes.push(
            "reference: the row of compare/data/references.toml (from 1); holds when |workbench - published| <= k u + tolerance |published| (k = 1 for a bound, 2 for a standard uncertainty); a computation that does not hold fails the run unless its cause is diagnosed (references.md gives it)".into(),
        );
        let mut md = String::from(
            "| reference | quantity | published | method | workbench | deviation | allowed | verdict | resolution | source |\n|---|---|---|---|---|---|---|---|---|---|\n",
        );
        for (k, r, c) in rows {
            let allowed = r.coverage() * r.uncertainty + c.tolerance * r.value.abs();
            let dev = c.value - r.value;
            let holds = dev.abs() <= allowed;
            t.push(vec![
                (*k + 1) as f64,
                match c.method {
                    "MRD" => 0.0,
                    "3D" => 1.0,
                    _ => 2.0,
                },
                r.value,
                r.uncertainty,
                c.value,
                dev / r.value,
                allowed / r.value.abs(),
                holds as u8 as f64,
            ]);
            let key = format!(
                "{}_{}",
                r.id.replace('-', "_"),
                c.method.to_lowercase().replace(' ', "_")
            );
            out.scalar(key.clone(), c.value);
            out.scalar(format!("{key}_holds"), holds as u8 as f64);
            let published = if r.uncertainty > 0.0 {
                format!("{} +/- {} ({})", r.value, r.uncertainty, r.uncertainty_kind)
            } else {
                format!("{} (exact)", r.value)
            };
            let doi = if r.doi.is_empty() {
                String::new()
            } else {
                format!(", doi:{}", r.doi)
            };
            md.push_str(&format!(
                "| {} | {} | {published} | {} | {:.6} | {:+.2e} | {:.1e} | {} | {} | {}{doi}, {} |\n",
                r.id,
                r.quantity,
                c.method,
                c.value,
                dev / r.value,
                allowed / r.value.abs(),
                match (holds, c.diagnosis) {
                    (true, _) => "holds".to_string(),
                    (false, None) => "does not hold".to_string(),
                    (false, Some(why)) => format!("does not hold (diagnosed: {why})"),
                },
                c.why,
                r.citation,
                r.location,
            ));
            if !holds && c.diagnosis.is_none() {
                out.failures.push(format!(
                    "{} by {}: {} against the published {published}, outside the allowed {allowed:.2e} ({})",
                    r.id, c.method, c.value, c.why
                ));
            }
        }
        out.files.push(("references.md".into(), md.into_bytes()));
        out.tables.push(t);
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

/// A sphere of radius `r` (a paraboloid), the references' body.
fn sphere(r: f64) -> Result<Profile> {
    Profile::new(vec![Shape::paraboloid(r).ctx("sphere")?], None).ctx("sphere")
}

/// The viscoelastic references' indentation: a sphere of radius `r` pressed at depth
/// rate `v` until `tm` and withdrawn at the same rate, on a standard linear solid
/// E*(t) = e_inf + e_1 exp(-t / tau).
#[derive(Clone, Copy)]
struct Indentation {
    r: f64,
    v: f64,
    tm: f64,
    e_inf: f64,
    e_1: f64,
    tau: f64,
}

impl Indentation {
    /// The data file's problem (lee-radok-sphere, ting-sphere-unloading).
    const REFERENCE: Self = Self {
        r: 1.0,
        v: 0.01,
        tm: 1.0,
        e_inf: 1.0,
        e_1: 9.0,
        tau: 1.0,
    };

    fn depth(&self, t: f64) -> f64 {
        self.v * if t <= self.tm { t } else { 2.0 * self.tm - t }
    }

    /// The relaxed Hertz force at the deepest point, the forces' scale.
    fn hertz_relaxed(&self) -> f64 {
        4.0 / 3.0 * self.e_inf * self.r.sqrt() * (self.v * self.tm).powf(1.5)
    }

    /// Int_0^t E*(t - s) ds.
    fn phi(&self, t: f64) -> f64 {
        self.e_inf * t - self.e_1 * self.tau * (-t / self.tau).exp_m1()
    }

    /// Lee and Radok's force while the contact grows, Ting's while it shrinks:
    /// F(t) = 2 R^(1/2) v^(3/2) Int_0^t1 E*(t - s) s^(1/2) ds, with t1 = t while loading
    /// and, after t_m, the earlier time at which the contact had the present radius: the
    /// root of Int_t1^t E*(t - s) d'(s) ds = 0, i.e. phi(t - t1) = 2 phi(t - t_m). Zero
    /// once t1 reaches 0 (the contact ends). The integral in closed form: E_inf (2/3)
    /// t1^(3/2) + E_1 tau^(3/2) exp(-t / tau) I(t1 / tau), I(T) = Int_0^T e^u u^(1/2) du =
    /// sum_k T^(k + 3/2) / (k! (k + 3/2)).
    fn ting_force(&self, t: f64) -> f64 {
        let t1 = if t <= self.tm {
            t
        } else {
            let target = 2.0 * self.phi(t - self.tm);
            if self.phi(t) <= target {
                return 0.0;
            }
            // phi(t - t1) falls from phi(t) to phi(t - t_m) as t1 goes from 0 to t_m.
            let (mut lo, mut hi) = (0.0, self.tm);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if self.phi(t - mid) > target {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            0.5 * (lo + hi)
        };
        let big_t = t1 / self.tau;
        let (mut term, mut sum) = (big_t.powf(1.5), 0.0);
        for k in 0..200 {
            let add = term / (k as f64 + 1.5);
            if sum + add == sum {
                break;
            }
            sum += add;
            term *= big_t / (k + 1) as f64;
        }
        let integral = self.e_inf * 2.0 / 3.0 * t1.powf(1.5)
            + self.e_1 * self.tau.powf(1.5) * (-t / self.tau).exp() * sum;
        2.0 * self.r.sqrt() * self.v.powf(1.5) * integral
    }
}

/// Force steps per half cycle of the 3D oscillation of `mindlin-deresiewicz-energy`.
const CYCLE_STEPS: usize = 20;

/// The tangential references' problem: a rigid sphere (E* = R = 1, nu = 0.3) pressed by
/// P = 1e-3 with friction mu = 0.3, MRD's tangential springs on it, and its 3D partial
/// slip on the free half-space (a grid of 2.5 contact radii) under the 3D Hertz pressure.
struct SlipSphere {
    e: f64,
    nu: f64,
    /// The shear modulus of the one elastic body, and its G* = 4 G / (2 - nu).
    g: f64,
    g_star: f64,
    mu: f64,
    p: f64,
    profile: Profile,
    springs: TangentialContact,
    /// Hertz's contact radius.
    a: f64,
}

impl SlipSphere {
    fn new() -> Result<Self> {
        let (e, r, nu, mu, p) = (1.0, 1.0, 0.3, 0.3, 1e-3);
        let g = e * (1.0 - nu) / 2.0;
        let g_star = 4.0 * g / (2.0 - nu);
        debug_assert!((equivalent_body(e, g_star).0 - nu).abs() < 1e-12);
        let profile = sphere(r)?;
        let springs = AxisymmetricContact::new(profile.clone(), e)
            .and_then(|c| TangentialContact::new(c, g_star, mu, p))
            .ctx("MRD tangential springs")?;
        let a = springs.normal.radius;
        Ok(Self {
            e,
            nu,
            g,
            g_star,
            mu,
            p,
            profile,
            springs,
            a,
        })
    }

    /// The side of the 3D grid.
    fn side(&self) -> f64 {
        2.5 * self.a
    }

    /// The 3D partial slip on `n^2` cells under the sphere's 3D pressure at P.
    fn slip_3d(&self, n: usize) -> bem3d::Result<PartialSlip<CerrutiFree>> {
        let side = self.side();
        let grid = AxisymGrid {
            cells: n,
            side,
            periodic: false,
        };
        let sol = grid.press(
            &self.profile,
            self.e,
            self.p,
            &SolverOptions::new(1e-10, 10_000),
        )?;
        let op = CerrutiFree::new(n, n, side, side, self.g, self.nu)?;
        PartialSlip::new(op, &sol.pressure, self.mu)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The embedded file parses, lists every computed reference and nothing else.
    #[test]
    fn every_reference_is_complete_and_computed() {
        let refs = published().unwrap();
        let ids: Vec<&str> = refs.iter().map(|r| r.id.as_str()).collect();
        assert_eq!(ids, COMPUTED);
    }

    /// The closed form the figure draws reproduces the data file's transcribed values
    /// (evaluated independently to 30 digits), and the contact ends at 1.5421 t_m.
    #[test]
    fn lee_radok_and_ting_in_closed_form() {
        let law = Indentation::REFERENCE;
        let value = |id: &str| {
            published()
                .unwrap()
                .into_iter()
                .find(|r| r.id == id)
                .unwrap()
                .value
        };
        let f = |t: f64| law.ting_force(t) / law.hertz_relaxed();
        assert!((f(1.0) / value("lee-radok-sphere") - 1.0).abs() < 1e-12);
        assert!((f(1.25) / value("ting-sphere-unloading") - 1.0).abs() < 1e-12);
        assert!(f(1.5420) > 0.0 && f(1.5422) == 0.0);
        // Continuous at t_m, where Ting's t1 leaves t.
        assert!((f(1.0 + 1e-9) - f(1.0)).abs() < 1e-6);
    }

    /// An entry without a citation, units, an uncertainty or with an empty text is
    /// refused, naming the reference and the key.
    #[test]
    fn an_incomplete_reference_is_refused() {
        let one = DATA.split("\n[[reference]]\n").nth(1).unwrap();
        let whole = format!("[[reference]]\n{one}");
        assert!(parse(&whole).is_ok());
        for key in [
            "citation",
            "units",
            "uncertainty",
            "uncertainty_kind",
            "problem",
            "doi",
        ] {
            let without: String = whole
                .lines()
                .filter(|l| !l.starts_with(&format!("{key} =")))
                .map(|l| format!("{l}\n"))
                .collect();
            let e = parse(&without).unwrap_err();
            assert!(e.contains(key), "{key}: {e}");
        }
        let blank = whole.replace(
            &whole
                .lines()
                .find(|l| l.starts_with("citation ="))
                .unwrap()
                .to_string(),
            "citation = \"\"",
        );
        assert!(parse(&blank).unwrap_err().contains("citation is empty"));
        let twice = format!("{whole}\n{whole}");
        assert!(parse(&twice).unwrap_err().contains("listed twice"));
        let loose = whole.replace(
            "uncertainty_kind = \"bound\"",
            "uncertainty_kind = \"exact\"",
        );
        assert!(parse(&loose).unwrap_err().contains("uncertainty"));
    }
}
