//! `oblique_impact`: a sphere striking the half-space obliquely, with friction, the
//! normal and the tangential force both evaluated at every time step (Sections 6-7 and
//! 12: the varying normal force with a tangential one). The sphere translates without
//! turning, or (`gyration`, its moment of inertia over m R^2) turns freely: then its
//! contact point moves tangentially as the mass `m / (1 + 1 / gyration)` would (the
//! case of Maw, Barber & Fawcett, Wear 38 (1976) 101), and the tangential speeds are
//! the contact point's. By MRD's springs (the rule
//! of Hess, tangential springs `G* dx` with Coulomb slip: exact for the sphere) and by
//! the 3D contact in the loop (`dynamics::ObliqueBem3d`: the normal solve and the
//! partial slip under the step's pressure, the slip carried from step to step), at a
//! range of incidences, the tangential speed over mu times the normal one.
//!
//! Closed forms: the normal restitution is 1 (Hertz); where the sphere slides
//! throughout (checked from a tangential speed of `2 mu m / m_t` times the normal one
//! on, where the contact point just comes to rest), the tangential impulse is mu times
//! the normal one, `v_t' = v_t - 2 mu v_n m / m_t`; without turning, for nu = 0
//! (G* = E*) below mu the tangential motion is the normal one scaled, nothing slips
//! and `v_t' = -v_t`. In between, stick and slip share the impact: MRD against 3D.
//! The slip energy closes the kinetic energy's balance (the elastic energy is
//! returned).
//!
//! Set-up: as `impact`, from 1e-3 of the largest approach before first contact, until
//! the sphere has left the surface; the 3D grid free, of side `extent` times the
//! largest Hertz contact diameter.

use crate::checks::{bad, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::experiment::impact::{check_resolution, check_strike, stages as impact_stages};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use dynamics::integrate::{Planar, PlanarSample};
use dynamics::{ContactLaw, ObliqueBem3d, Springs};
use mrd::reference::{for_profile, hertz, hertz_impact};
use serde::Deserialize;
use std::time::Instant;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObliqueImpact {
    /// The sphere's mass [mass].
    mass: f64,
    /// Its normal speed at first contact [length / time].
    speed: f64,
    /// Coulomb's friction coefficient.
    mu: f64,
    /// The sphere's moment of inertia about its centre over m R^2 when it turns freely
    /// (0.4: a solid sphere; the contact point then moves tangentially as the mass
    /// m / (1 + 1 / gyration)); none: it does not turn.
    #[serde(default)]
    gyration: Option<f64>,
    /// The incidences: tangential speed at first contact over mu times the normal one,
    /// each > 0, increasing.
    #[serde(default = "default_ratios")]
    ratios: Vec<f64>,
    /// MRD springs on the half line (over 1.5 Hertz contact radii).
    #[serde(default = "default_springs")]
    springs: usize,
    /// Time steps per Hertz contact time of the MRD runs.
    #[serde(default = "default_steps")]
    steps: usize,
    /// Cells per side of the 3D grids, coarse to fine (empty: MRD alone).
    #[serde(default = "default_cells")]
    cells: Vec<usize>,
    /// Time steps per contact time of the 3D runs.
    #[serde(default = "default_steps_3d")]
    steps_3d: usize,
    /// Side of the 3D grid over the largest Hertz contact diameter.
    #[serde(default = "default_extent")]
    extent: f64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn default_ratios() -> Vec<f64> {
    vec![0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0, 3.0, 4.0, 6.0, 10.0]
}
fn default_springs() -> usize {
    4000
}
fn default_steps() -> usize {
    2000
}
fn default_cells() -> Vec<usize> {
    vec![32]
}
fn default_steps_3d() -> usize {
    400
}
fn default_extent() -> f64 {
    1.25
}

/// One impact's outcome.
struct Outcome {
    /// Exit normal speed over the incoming one.
    normal: f64,
    /// Exit tangential speed over the incoming one (negative: reversed).
    tangential: f64,
    /// Slip energy and kinetic energy lost, over the incoming kinetic energy.
    slip_energy: f64,
    kinetic_loss: f64,
    steps: usize,
    iterations: usize,
    seconds: f64,
}

/// The runs of one method: its label and an outcome per ratio.
struct Method {
    label: String,
    cells: usize,
    outcomes: Vec<Outcome>,
}

impl Output for ObliqueImpact {
    fn validate(&self, ctx: &Context) -> Result<()> {
        if for_profile::sphere_radius(ctx.profile()?).is_none() {
            return bad("oblique_impact needs a sphere (profile = paraboloid): Hertz's impact scales the run");
        }
        let g = ctx.material.g_star().ctx("oblique_impact")?;
        let r = for_profile::sphere_radius(ctx.profile()?).unwrap_or(1.0);
        check_strike(ctx.material.e_star, r, self.mass, self.speed)?;
        if let Some(k) = self.gyration {
            if !(k.is_finite() && k > 0.0 && k <= 100.0) {
                return bad(format!(
                    "gyration = {k} must lie in (0, 100] (the moment of inertia over m R^2; 0.4 for a solid sphere)"
                ));
            }
        }
        if !(self.mu.is_finite() && self.mu > 0.0 && self.mu <= 10.0) {
            return bad(format!("mu = {} must lie in (0, 10]", self.mu));
        }
        if self.ratios.is_empty()
            || self.ratios.len() > 100
            || self
                .ratios
                .iter()
                .any(|r| !(r.is_finite() && *r > 0.0 && *r <= 100.0))
            || self.ratios.windows(2).any(|w| w[1] <= w[0])
        {
            return bad(format!(
                "ratios = {:?}: give 1 to 100 increasing incidences in (0, 100] (tangential speed over mu times the normal one)",
                self.ratios
            ));
        }
        let ratio = g / ctx.material.e_star;
        if !self.cells.is_empty() && !(2.0 / 3.0..=1.0).contains(&ratio) {
            return bad(format!(
                "G* / E* = {ratio}: the 3D runs (cells = {:?}) take one elastic body, G* / E* in [2/3, 1] (Poisson's ratio in [0, 0.5]); or set cells = []",
                self.cells
            ));
        }
        check_resolution(
            self.springs,
            (self.steps, self.steps_3d),
            &self.cells,
            256,
            self.extent,
            self.tolerance,
        )?;
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        impact_stages(!self.cells.is_empty())
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let ctx = env.ctx;
        let profile = ctx.profile()?.clone();
        let (e, g) = (
            ctx.material.e_star,
            ctx.material.g_star().ctx("oblique_impact")?,
        );
        let r = for_profile::sphere_radius(&profile).unwrap_or(1.0);
        let (m, v) = (self.mass, self.speed);
        out.stage(Stage::HessTransform, || profile.z1d(0.0));
        let (tc, fmax, dmax) = out.stage(Stage::ClosedForm, || {
            (
                hertz_impact::duration(e, r, m, v),
                hertz_impact::max_force(e, r, m, v),
                hertz_impact::max_approach(e, r, m, v),
            )
        });
        let a = hertz::radius(r, dmax);
        let scale = (tc, fmax, dmax);
        let mrd = out
            .stage(Stage::Dynamics, || -> dynamics::Result<Method> {
                let outcomes = self
                    .ratios
                    .iter()
                    .map(|&k| {
                        let mut law = Springs::body(&profile, e, self.springs, 1.5 * a)?
                            .with_friction(g, self.mu)?;
                        self.strike(&mut law, k, self.steps, scale)
                    })
                    .collect::<dynamics::Result<_>>()?;
                Ok(Method {
                    label: format!("MRD, {} springs", self.springs),
                    cells: 0,
                    outcomes,
                })
            })
            .ctx("MRD in the loop")?;
        let three = out
            .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Method>> {
                self.cells
                    .iter()
                    .map(|&n| {
                        let side = 2.0 * self.extent * a;
                        let grid = AxisymGrid {
                            cells: n,
                            side,
                            periodic: false,
                        };
                        let (z, _) = grid.heights(&profile);
                        let outcomes = self
                            .ratios
                            .iter()
                            .map(|&k| {
                                let mut law = ObliqueBem3d::new(
                                    &z,
                                    (n, n),
                                    (side, side),
                                    (e, g),
                                    self.mu,
                                    self.tolerance,
                                )?;
                                self.strike(&mut law, k, self.steps_3d, scale)
                            })
                            .collect::<dynamics::Result<_>>()?;
                        Ok(Method {
                            label: format!("3D, {n}^2 cells"),
                            cells: n,
                            outcomes,
                        })
                    })
                    .collect()
            })
            .ctx("3D in the loop")?;
        self.report(out, &mrd, &three, g / e)
    }
}

impl ObliqueImpact {
    /// The contact point's tangential mass: the sphere's, or `m / (1 + 1 / gyration)`
    /// when it turns freely.
    fn tangential_mass(&self) -> f64 {
        match self.gyration {
            Some(k) => self.mass / (1.0 + 1.0 / k),
            None => self.mass,
        }
    }

    /// The tangential impulse's factor on the contact point's speed: `m / m_t`
    /// (sliding throughout, `v_t' = v_t - 2 mu v_n m / m_t`).
    fn impulse_factor(&self) -> f64 {
        self.mass / self.tangential_mass()
    }

    /// One impact at the incidence `ratio` on `law`, `steps` per Hertz contact time.
    fn strike(
        &self,
        law: &mut dyn ContactLaw,
        ratio: f64,
        steps: usize,
        (tc, fmax, dmax): (f64, f64, f64),
    ) -> dynamics::Result<Outcome> {
        let planar = Planar {
            mass: [self.mass, self.tangential_mass()],
            dt: tc / steps as f64,
            dt_min: tc / (1000.0 * steps as f64),
            max_jump: 0.05,
            force_scale: fmax,
        };
        let (vn, vt) = (self.speed, ratio * self.mu * self.speed);
        let x0 = -1e-3 * dmax;
        // Off the surface again, moving away: no force acts any more.
        let left = |s: &PlanarSample| s.x[0] < 0.0 && s.v[0] < 0.0;
        let t0 = Instant::now();
        let (samples, counts) = planar.run(law, ([x0, 0.0], [vn, vt]), &left, 3.0 * tc)?;
        let seconds = t0.elapsed().as_secs_f64();
        let last = samples.last().expect("a run keeps its start");
        // Starting without spin, the kinetic energy the impulses change is the normal
        // mass's and the contact point's tangential mass's.
        let mt = self.tangential_mass();
        let kinetic = |v: [f64; 2]| 0.5 * (self.mass * v[0] * v[0] + mt * v[1] * v[1]);
        let k_in = kinetic([vn, vt]);
        Ok(Outcome {
            normal: if left(last) {
                -last.v[0] / vn
            } else {
                f64::NAN
            },
            tangential: if left(last) { last.v[1] / vt } else { f64::NAN },
            slip_energy: samples.iter().map(|s| s.forces.dissipated).sum::<f64>() / k_in,
            kinetic_loss: (k_in - kinetic(last.v)) / k_in,
            steps: counts.accepted,
            iterations: samples.iter().map(|s| s.forces.iterations).sum(),
            seconds,
        })
    }

    fn report(
        &self,
        out: &mut Section,
        mrd: &Method,
        three: &[Method],
        g_over_e: f64,
    ) -> Result<()> {
        let methods: Vec<&Method> = std::iter::once(mrd).chain(three).collect();
        let f = self.impulse_factor();
        let mut t = Table::new(
            "oblique",
            &[
                "method [0 MRD, else 3D cells a side]",
                "incidence v_t / (mu v_n) [1]",
                "tangential exit over entry v_t' / v_t [1]",
                "sliding throughout 1 - 2 m / (m_t incidence) [1]",
                "normal restitution [1]",
                "slip energy over entry kinetic energy [1]",
                "kinetic energy lost over entry [1]",
                "accepted_steps [count]",
                "iterations_per_step, mean [1]",
                "seconds_per_step [s]",
            ],
        );
        t.notes.push(format!(
            "a sphere {} (mass {}, normal speed {}, mu = {}, G*/E* = {g_over_e:.6}) from 1e-3 of Hertz's largest approach before contact until it leaves; velocity Verlet, steps rejected where the force jumps by 5 % of Hertz's largest; MRD at t_c/{}, 3D at t_c/{} (grids free, side {} Hertz contact diameters, solves to {:e}); iterations: the 3D normal solve's conjugate-gradient iterations and the partial-slip solves per step",
            match self.gyration {
                Some(k) => format!("turning freely, I = {k} m R^2 (the tangential speeds the contact point's, its mass m / (1 + 1 / {k}))"),
                None => "translating without turning".into(),
            },
            self.mass, self.speed, self.mu, self.steps, self.steps_3d, self.extent, self.tolerance
        ));
        for m in &methods {
            for (k, o) in self.ratios.iter().zip(&m.outcomes) {
                if !o.tangential.is_finite() {
                    out.failures.push(format!(
                        "{}: at incidence {k} the sphere had not left the surface after 3 contact times",
                        m.label
                    ));
                }
                let steps = o.steps.max(1) as f64;
                t.push(vec![
                    m.cells as f64,
                    *k,
                    o.tangential,
                    1.0 - 2.0 * f / k,
                    o.normal,
                    o.slip_energy,
                    o.kinetic_loss,
                    o.steps as f64,
                    o.iterations as f64 / steps,
                    o.seconds / steps,
                ]);
            }
        }
        out.tables.push(t);
        let worst = |m: &Method, f: &dyn Fn(f64, &Outcome) -> Option<f64>| {
            self.ratios
                .iter()
                .zip(&m.outcomes)
                .filter_map(|(k, o)| f(*k, o))
                .fold(0.0f64, f64::max)
        };
        let sliding = |k: f64, o: &Outcome| {
            (k >= 2.0 * f).then(|| (o.tangential - (1.0 - 2.0 * f / k)).abs())
        };
        let balance = |_: f64, o: &Outcome| Some((o.kinetic_loss - o.slip_energy).abs());
        let normal = |_: f64, o: &Outcome| Some((o.normal - 1.0).abs());
        out.scalar("mrd_normal_restitution_max_dev", worst(mrd, &normal));
        out.scalar("mrd_energy_balance_max_dev", worst(mrd, &balance));
        if self.ratios.iter().any(|k| *k >= 2.0 * f) {
            out.scalar("mrd_sliding_closed_form_max_dev", worst(mrd, &sliding));
        }
        // nu = 0: below mu nothing slips and the tangential speed reverses.
        let stick = |k: f64, o: &Outcome| (k < 1.0).then(|| (o.tangential + 1.0).abs());
        let no_slip =
            g_over_e == 1.0 && self.gyration.is_none() && self.ratios.iter().any(|k| *k < 1.0);
        if no_slip {
            out.scalar("mrd_no_slip_closed_form_max_dev", worst(mrd, &stick));
        }
        if let Some(fine) = three.last() {
            out.scalar("bem3d_normal_restitution_max_dev", worst(fine, &normal));
            out.scalar("bem3d_energy_balance_max_dev", worst(fine, &balance));
            if self.ratios.iter().any(|k| *k >= 2.0 * f) {
                out.scalar("bem3d_sliding_closed_form_max_dev", worst(fine, &sliding));
            }
            if no_slip {
                out.scalar("bem3d_no_slip_closed_form_max_dev", worst(fine, &stick));
            }
            let vs_mrd = self
                .ratios
                .iter()
                .enumerate()
                .map(|(i, _)| (fine.outcomes[i].tangential - mrd.outcomes[i].tangential).abs())
                .fold(0.0f64, f64::max);
            out.scalar("tangential_exit_max_abs_dev_3d_vs_mrd", vs_mrd);
            let per = |m: &Method| {
                let s: f64 = m.outcomes.iter().map(|o| o.seconds).sum();
                let n: usize = m.outcomes.iter().map(|o| o.steps).sum();
                s / n.max(1) as f64
            };
            out.scalar("cost_per_step_3d_over_mrd", per(fine) / per(mrd));
        }
        self.figures(out, &methods, no_slip);
        Ok(())
    }

    /// The tangential rebound and the slip energy against the incidence, each method
    /// beside the closed forms.
    fn figures(&self, out: &mut Section, methods: &[&Method], no_slip: bool) {
        let f = self.impulse_factor();
        let title = match self.gyration {
            Some(k) => format!(
                "Oblique impact, the sphere turning freely (I = {k} m R^2): tangential rebound"
            ),
            None => "Oblique impact of a translating sphere: tangential rebound against incidence"
                .into(),
        };
        let mut fig = Figure::new(
            "oblique_rebound",
            &title,
            "incidence: tangential over mu times normal speed v_t / (mu v_n) [1]",
            "tangential exit over entry speed v_t' / v_t (contact point) [1]",
        );
        let top = self.ratios.last().copied().unwrap_or(1.0);
        let lo = self.ratios[0].max(f);
        let line: Vec<(f64, f64)> = (0..=100)
            .map(|i| {
                let k = lo * (top / lo).powf(i as f64 / 100.0);
                (k, 1.0 - 2.0 * f / k)
            })
            .collect();
        fig = fig.plot(
            format!("sliding throughout: 1 - 2 m / (m_t incidence), m / m_t = {f:.4}"),
            line.clone(),
            Style::Dashed,
        );
        if no_slip {
            fig = fig.plot(
                "no slip (nu = 0): -1",
                vec![(self.ratios[0], -1.0), (1.0, -1.0)],
                Style::Dashed,
            );
        }
        let mut energy = Figure::new(
            "oblique_slip_energy",
            "Oblique impact: energy dissipated by slip against incidence",
            "incidence: tangential over mu times normal speed v_t / (mu v_n) [1]",
            "slip energy over entry kinetic energy [1]",
        );
        // Sliding throughout, the kinetic energy lost is the slip energy:
        // (v_t^2 - (v_t - 2 mu v_n)^2) / (v_n^2 + v_t^2) at v_t = k mu v_n.
        let mu2 = self.mu * self.mu;
        let slid: Vec<(f64, f64)> = line
            .iter()
            .map(|(k, _)| (*k, 4.0 * mu2 * (k - f) / (1.0 + k * k * mu2 / f)))
            .filter(|p| p.1 > 0.0)
            .collect();
        energy = energy.plot(
            "sliding throughout: 4 mu^2 (k - m/m_t) / (1 + k^2 mu^2 m_t/m), k the incidence",
            slid,
            Style::Dashed,
        );
        fig.log_x = true;
        energy = energy.log_log();
        for (i, m) in methods.iter().enumerate() {
            // MRD the line, the finest grid markers, coarser grids crosses (each visible
            // where the grids agree).
            let style = match i {
                0 => Style::Line,
                _ if i + 1 == methods.len() => Style::Markers,
                _ => Style::Crosses,
            };
            let pts = |f: &dyn Fn(&Outcome) -> f64| -> Vec<(f64, f64)> {
                self.ratios
                    .iter()
                    .zip(&m.outcomes)
                    .map(|(k, o)| (*k, f(o)))
                    .collect()
            };
            fig = fig.plot(m.label.clone(), pts(&|o| o.tangential), style);
            energy = energy.plot(m.label.clone(), pts(&|o| o.slip_energy), style);
        }
        out.figures.push(fig);
        out.figures.push(energy);
    }
}
