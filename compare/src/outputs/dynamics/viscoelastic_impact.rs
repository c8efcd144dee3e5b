//! `viscoelastic_impact`: a rigid sphere (mass m) striking a viscoelastic half-space at a
//! range of speeds, integrated in time with the contact evaluated at every step by MRD's
//! viscoelastic springs (the rule of Hess, each spring the hereditary integral of Eq. 63,
//! separating at zero force) and by the 3D transient boundary-element solve on the same
//! modulus E*(t) = E_inf + sum_k E_k exp(-t / tau_k) (Sections 8 and 12). The quantity of
//! interest is the coefficient of restitution e(v) (out speed over in speed), below 1
//! where the contact lasts about a relaxation time, and the contact time.
//!
//! Radok's elastic-viscoelastic correspondence ends when the contact shrinks, so the
//! rebound has no closed form: the 3D transient solve is the reference, and MRD's
//! viscoelastic springs (Section 8; the mapping rules for axisymmetric viscoelastic
//! contacts: Popov, Willert & Hess, Facta Univ. Mech. Eng. 16 (2018) 99, doi
//! 10.22190/FUME180327013P) are held against it through the whole rebound, where the
//! contact shrinks and the springs separate one by one. The limits are closed forms: a contact much shorter than every tau_k
//! is elastic at the glassy modulus E_0 = E_inf + sum E_k, one much longer elastic at
//! E_inf: restitution 1 and Hertz's contact time at that modulus (Johnson 11.4).
//!
//! Set-up as in `impact`: the mass starts 1e-3 of the relaxed Hertz approach before first
//! contact and is integrated by velocity Verlet (`dynamics::integrate`, steps rejected
//! where the force jumps by 5 % of the glassy Hertz force) until it has left the
//! contact, at most 3 relaxed Hertz contact times. Time steps and the spring row are
//! scaled on the relaxed Hertz impact (the longest contact, the widest), the 3D grid
//! spans `extent` relaxed Hertz contact diameters.

use crate::checks::{bad, default_tolerance};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::axisym_3d::AxisymGrid;
use crate::experiment::impact::{
    check_resolution, first_contact, stages as impact_stages, FirstContact, Strike,
};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Style, Table};
use bem3d::viscoelastic::Relaxation;
use bem3d::NonPeriodicHalfSpace;
use dynamics::integrate::{Sample, Stop};
use dynamics::{ContactLaw, ViscoelasticBem3d, ViscoelasticSprings};
use mrd::reference::{for_profile, hertz, hertz_impact};
use mrd::rheology::Prony;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViscoelasticImpact {
    /// The sphere's mass [mass].
    mass: f64,
    /// Impact speeds, increasing [length / time].
    speeds: Vec<f64>,
    /// Long-time (relaxed) contact modulus E*_inf, > 0.
    e_inf: f64,
    /// Prony terms [[E_k, tau_k], ...] of E*(t) = E_inf + sum E_k exp(-t / tau_k).
    prony: Vec<[f64; 2]>,
    /// MRD springs on the half line (over 1.5 relaxed Hertz contact radii).
    #[serde(default = "crate::checks::default_count::<2000>")]
    springs: usize,
    /// Time steps per relaxed Hertz contact time, MRD's finer run (its coarser run takes
    /// half of them: the convergence in the time step).
    #[serde(default = "crate::checks::default_count::<2000>")]
    steps: usize,
    /// Cells per side of the 3D grids, coarse to fine (empty: MRD alone).
    #[serde(default = "default_cells")]
    cells: Vec<usize>,
    /// Time steps per relaxed Hertz contact time of the 3D runs.
    #[serde(default = "crate::checks::default_count::<200>")]
    steps_3d: usize,
    /// Side of the 3D grid over the relaxed Hertz contact diameter.
    #[serde(default = "default_extent")]
    extent: f64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "default_tolerance")]
    tolerance: f64,
}

fn default_cells() -> Vec<usize> {
    vec![32]
}
fn default_extent() -> f64 {
    1.3
}

/// The relaxed Hertz impact of one speed: contact time, largest approach, and the glassy
/// largest force (the force scale of step rejection).
struct Scale {
    tc: f64,
    dmax: f64,
    fmax: f64,
}

/// One integrated impact.
struct Run {
    /// 0: MRD; else the 3D grid's side.
    grid: usize,
    dt: f64,
    samples: Vec<Sample>,
    outcome: Option<FirstContact>,
    accepted: usize,
    rejected: usize,
}

impl Run {
    /// How long the contact carries a force: from the first step with a force to the
    /// last (a viscoelastic surface recovers behind the rebounding body, which leaves it
    /// before its own position returns to first contact).
    fn pressed_for(&self) -> f64 {
        let pressed = |s: &&Sample| s.force > 0.0;
        match (
            self.samples.iter().find(pressed),
            self.samples.iter().rfind(pressed),
        ) {
            (Some(a), Some(b)) => b.t - a.t,
            _ => 0.0,
        }
    }
}

impl ViscoelasticImpact {
    fn glassy(&self) -> f64 {
        self.e_inf + self.prony.iter().map(|t| t[0]).sum::<f64>()
    }

    fn scale(&self, r: f64, v: f64) -> Scale {
        let m = self.mass;
        Scale {
            tc: hertz_impact::duration(self.e_inf, r, m, v),
            dmax: hertz_impact::max_approach(self.e_inf, r, m, v),
            fmax: hertz_impact::max_force(self.glassy(), r, m, v),
        }
    }

    fn tau_min(&self) -> f64 {
        self.prony
            .iter()
            .map(|t| t[1])
            .fold(f64::INFINITY, f64::min)
    }

    fn terms(&self) -> Vec<(f64, f64)> {
        self.prony.iter().map(|t| (t[0], t[1])).collect()
    }

    /// The impact at `speed` through `law` at `steps` per relaxed contact time.
    fn integrate(
        &self,
        law: &mut dyn ContactLaw,
        grid: usize,
        speed: f64,
        s: &Scale,
        steps: usize,
    ) -> dynamics::Result<Run> {
        let strike = Strike {
            mass: self.mass,
            speed,
            tc: s.tc,
            fmax: s.fmax,
            dmax: s.dmax,
        };
        // Until the mass has been in contact and is apart again, moving away.
        let left = |x: &Sample| x.x < 0.0 && x.v < 0.0;
        let stop = Stop::When {
            until: &left,
            t_max: 3.0 * s.tc,
        };
        let (samples, counts, dt) = strike.run_until(law, steps, stop)?;
        Ok(Run {
            grid,
            dt,
            outcome: first_contact(&samples),
            samples,
            accepted: counts.accepted,
            rejected: counts.rejected,
        })
    }
}

impl Output for ViscoelasticImpact {
    fn validate(&self, ctx: &Context) -> Result<()> {
        let Some(r) = for_profile::sphere_radius(ctx.profile()?) else {
            return bad("viscoelastic_impact needs a sphere (profile = paraboloid): Hertz's impact gives its scales and limits");
        };
        if !(self.mass.is_finite() && self.mass > 0.0) {
            return bad(format!("mass = {} must be finite and > 0", self.mass));
        }
        if self.speeds.is_empty()
            || self.speeds.len() > 40
            || self.speeds.iter().any(|v| !(v.is_finite() && *v > 0.0))
            || self.speeds.windows(2).any(|w| w[1] <= w[0])
        {
            return bad(format!(
                "speeds = {:?}: give 1 to 40 increasing speeds, each finite and > 0",
                self.speeds
            ));
        }
        if !self.e_inf.is_finite() || self.e_inf <= 0.0 || self.prony.is_empty() {
            return bad(format!(
                "e_inf = {} must be finite and > 0 and prony hold at least one [E_k, tau_k] term (without one the contact is elastic: use `impact`)",
                self.e_inf
            ));
        }
        Prony::new(self.e_inf, self.terms()).ctx("e_inf, prony")?;
        check_resolution(
            self.springs,
            (self.steps, self.steps_3d),
            &self.cells,
            512,
            self.extent,
            self.tolerance,
        )?;
        let fastest = self.speeds[self.speeds.len() - 1];
        let dmax = self.scale(r, fastest).dmax;
        if dmax > 0.1 * r {
            return bad(format!(
                "mass and speed {fastest} press the sphere to {dmax:.3e} on the relaxed modulus, beyond a tenth of its radius {r}: the small-strain half-space no longer holds"
            ));
        }
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        impact_stages(!self.cells.is_empty())
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let profile = env.ctx.profile()?.clone();
        let r = for_profile::sphere_radius(&profile).unwrap_or(1.0);
        out.stage(Stage::HessTransform, || profile.z1d(0.0));
        let scales: Vec<Scale> = out.stage(Stage::ClosedForm, || {
            self.speeds.iter().map(|&v| self.scale(r, v)).collect()
        });
        let prony = Prony::new(self.e_inf, self.terms()).ctx("e_inf, prony")?;
        let mrd = out
            .stage(Stage::Dynamics, || -> dynamics::Result<Vec<[Run; 2]>> {
                self.speeds
                    .iter()
                    .zip(&scales)
                    .map(|(&v, s)| {
                        let a = hertz::radius(r, s.dmax);
                        let run = |steps: usize| {
                            let mut law =
                                ViscoelasticSprings::body(&profile, &prony, self.springs, 1.5 * a)?;
                            self.integrate(&mut law, 0, v, s, steps)
                        };
                        Ok([run(self.steps / 2)?, run(self.steps)?])
                    })
                    .collect()
            })
            .ctx("MRD in the loop")?;
        let three = out
            .stage(Stage::Dynamics3d, || -> dynamics::Result<Vec<Vec<Run>>> {
                let relaxation = Relaxation::new(self.e_inf, self.terms())?;
                self.speeds
                    .iter()
                    .zip(&scales)
                    .map(|(&v, s)| {
                        let side = 2.0 * self.extent * hertz::radius(r, s.dmax);
                        self.cells
                            .iter()
                            .map(|&n| {
                                let grid = AxisymGrid {
                                    cells: n,
                                    side,
                                    periodic: false,
                                };
                                let (z, _) = grid.heights(&profile);
                                let op = NonPeriodicHalfSpace::try_new(n, n, side, side, 1.0)?;
                                let mut law = ViscoelasticBem3d::new(
                                    op,
                                    &z,
                                    None,
                                    relaxation.clone(),
                                    self.tolerance,
                                    10_000,
                                )?;
                                self.integrate(&mut law, n, v, s, self.steps_3d)
                            })
                            .collect()
                    })
                    .collect()
            })
            .ctx("3D in the loop")?;
        self.report(out, r, &scales, &mrd, &three)
    }
}

impl ViscoelasticImpact {
    fn report(
        &self,
        out: &mut Section,
        r: f64,
        scales: &[Scale],
        mrd: &[[Run; 2]],
        three: &[Vec<Run>],
    ) -> Result<()> {
        let mut t = Table::new(
            "restitution",
            &[
                "speed [length/time]",
                "method [0 MRD, 1 3D]",
                "grid [cells]",
                "relaxed Hertz t_c over the shortest tau [1]",
                "time step over the relaxed t_c [1]",
                "restitution [1]",
                "contact_time (force > 0) over the relaxed Hertz t_c [1]",
                "peak_force over the glassy Hertz F_max [1]",
                "accepted_steps [count]",
                "rejected_steps [count]",
            ],
        );
        let (e0, m) = (self.glassy(), self.mass);
        t.notes.push(format!(
            "rigid sphere R = {r}, mass {m}, on E*(t) = {} + sum E_k exp(-t/tau_k), [E_k, tau_k] = {:?} (glassy E_0 = {e0}); MRD: {} springs on the half line over 1.5 relaxed Hertz radii, Eq. (63), at t_c/{} and t_c/{}; 3D: transient solve on free grids of {} relaxed Hertz diameters, tolerance {:e}, t_c/{}; velocity Verlet, steps rejected where the force jumps by 5 % of the glassy F_max; the elastic limits: restitution 1, t_c(E_0)/t_c(E_inf) = {:.6}",
            self.e_inf,
            self.prony,
            self.springs,
            self.steps / 2,
            self.steps,
            self.extent,
            self.tolerance,
            self.steps_3d,
            (self.e_inf / e0).powf(0.4),
        ));
        let mut rows = |v: f64, s: &Scale, run: &Run, out: &mut Section| {
            let Some(o) = &run.outcome else {
                out.failures.push(format!(
                    "speed {v}, {}: the contact did not end within 3 relaxed contact times",
                    if run.grid == 0 {
                        "MRD".to_string()
                    } else {
                        format!("3D {}^2", run.grid)
                    }
                ));
                return;
            };
            t.push(vec![
                v,
                (run.grid > 0) as u8 as f64,
                run.grid as f64,
                s.tc / self.tau_min(),
                run.dt / s.tc,
                o.restitution,
                run.pressed_for() / s.tc,
                o.peak_force / s.fmax,
                run.accepted as f64,
                run.rejected as f64,
            ]);
        };
        for (k, (&v, s)) in self.speeds.iter().zip(scales).enumerate() {
            for run in mrd[k].iter() {
                rows(v, s, run, out);
            }
            if let Some(runs) = three.get(k) {
                for run in runs {
                    rows(v, s, run, out);
                }
            }
        }
        out.tables.push(t);
        // Scalars: MRD's restitution at each speed, its change between the two time
        // steps, and the finest 3D grid's deviation from it.
        let (mut dt_change, mut dev, mut lowest) = (0.0f64, 0.0f64, f64::INFINITY);
        for (k, runs) in mrd.iter().enumerate() {
            let (Some(coarse), Some(fine)) = (&runs[0].outcome, &runs[1].outcome) else {
                continue;
            };
            out.scalar(format!("restitution_mrd_{k}"), fine.restitution);
            lowest = lowest.min(fine.restitution);
            dt_change = dt_change.max((coarse.restitution - fine.restitution).abs());
            if let Some(o) = three
                .get(k)
                .and_then(|r| r.last())
                .and_then(|r| r.outcome.as_ref())
            {
                out.scalar(format!("restitution_3d_{k}"), o.restitution);
                dev = dev.max((o.restitution - fine.restitution).abs());
            }
        }
        out.scalar("restitution_mrd_lowest", lowest);
        out.scalar("restitution_mrd_dt_change_max", dt_change);
        if three.iter().any(|r| !r.is_empty()) {
            out.scalar("restitution_3d_vs_mrd_max_abs_dev", dev);
        }
        self.figures(out, scales, mrd, three);
        Ok(())
    }

    fn figures(&self, out: &mut Section, scales: &[Scale], mrd: &[[Run; 2]], three: &[Vec<Run>]) {
        let (first, last) = (&scales[0], &scales[scales.len() - 1]);
        let mut fig = Figure::new(
            "restitution",
            "Viscoelastic impact: coefficient of restitution against speed, MRD and 3D in the loop",
            &format!(
                "impact speed v [length/time] (relaxed Hertz t_c / tau_min from {:.3} to {:.3})",
                first.tc / self.tau_min(),
                last.tc / self.tau_min()
            ),
            "restitution e = v_out / v_in [1]",
        );
        fig.log_x = true;
        let pick = |runs: Vec<&Run>| -> Vec<(f64, f64)> {
            self.speeds
                .iter()
                .zip(runs)
                .filter_map(|(&v, r)| r.outcome.as_ref().map(|o| (v, o.restitution)))
                .collect()
        };
        let fine = pick(mrd.iter().map(|r| &r[1]).collect());
        fig = fig.plot(
            format!("MRD, {} springs, dt = t_c/{}", self.springs, self.steps),
            fine.clone(),
            Style::Line,
        );
        // The 3D restitution less MRD's at the same speed, per grid (the agreement is
        // below the markers' size on the first figure).
        let mut dev = Figure::new(
            "restitution_3d_minus_mrd",
            "Viscoelastic impact: the 3D restitution less MRD's, per grid",
            "impact speed v [length/time]",
            "e_3D - e_MRD [1]",
        );
        dev.log_x = true;
        for (g, &n) in self.cells.iter().enumerate() {
            let runs: Vec<&Run> = three.iter().filter_map(|r| r.get(g)).collect();
            let points = pick(runs);
            let label = format!("3D transient, {n}^2 cells, dt = t_c/{}", self.steps_3d);
            let diff: Vec<(f64, f64)> = points
                .iter()
                .filter_map(|&(v, e)| fine.iter().find(|p| p.0 == v).map(|p| (v, e - p.1)))
                .collect();
            fig = fig.plot(label.clone(), points, Style::Markers);
            dev = dev.plot(label, diff, Style::Markers);
        }
        dev = dev.plot(
            "zero",
            vec![
                (self.speeds[0], 0.0),
                (self.speeds[self.speeds.len() - 1], 0.0),
            ],
            Style::Dashed,
        );
        let ends = (self.speeds[0], self.speeds[self.speeds.len() - 1]);
        fig = fig.plot(
            "elastic limits (glassy and relaxed): e = 1",
            vec![(ends.0, 1.0), (ends.1, 1.0)],
            Style::Dashed,
        );
        out.figures.push(fig);
        if !self.cells.is_empty() {
            out.figures.push(dev);
        }
        // The force against time at the speed of MRD's lowest restitution.
        let k = mrd
            .iter()
            .enumerate()
            .filter_map(|(k, r)| r[1].outcome.as_ref().map(|o| (k, o.restitution)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(0, |p| p.0);
        let s = &scales[k];
        let mut ft = Figure::new(
            "force_time",
            &format!(
                "Viscoelastic impact at v = {:e}: contact force against time",
                self.speeds[k]
            ),
            "time over the relaxed Hertz contact time t / t_c [1]",
            "contact force over the glassy Hertz largest F / F_max [1]",
        );
        let curve = |r: &Run, points: usize| -> Vec<(f64, f64)> {
            let every = (r.samples.len() / points).max(1);
            r.samples
                .iter()
                .step_by(every)
                .map(|x| (x.t / s.tc, x.force / s.fmax))
                .collect()
        };
        ft = ft.plot("MRD", curve(&mrd[k][1], 300), Style::Line);
        if let Some(runs) = three.get(k) {
            for r in runs {
                ft = ft.plot(format!("3D {}^2", r.grid), curve(r, 60), Style::Markers);
            }
        }
        out.figures.push(ft);
    }
}
