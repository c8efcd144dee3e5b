//! `Calibrate` as an output kind: its checks, stages and run (the realisation plan and
//! the analysis of what the checkpoints hold).

use super::analysis::{self, Calibration};
use super::spectrum::SpectrumPart;
use super::tasks::{self, Case, Lines, Task};
use super::{report, Calibrate};
use crate::checks::{bad, count_in, MAX_LOADS, MAX_REALISATIONS};
use crate::context::Context;
use crate::error::{CompareError, Result};
use crate::experiment::rough_punch::{self, BemCurve};
use crate::output::{Checkpointed, Env, Output, RunControl};
use crate::plan::Stage;
use crate::report::Section;
use std::path::Path;

impl Output for Calibrate {
    fn validate(&self, ctx: &Context) -> Result<()> {
        self.realisations.validate()?;
        count_in("bandwidth", self.bandwidth as u64, 8..=512)?;
        count_in("cells", self.cells as u64, 3..=32)?;
        count_in("loads", self.loads as u64, 6..=MAX_LOADS)?;
        count_in("lines", self.lines, 2..=MAX_REALISATIONS)?;
        count_in("points_1d_per_cell", self.points_1d_per_cell as u64, 2..=64)?;
        crate::checks::check_tolerance(self.tolerance)?;
        let [lo, hi] = self.window;
        if !(lo > 0.0 && lo < hi && hi <= 1.0) {
            return bad("window must satisfy 0 < window[0] < window[1] <= 1 (k/(E* L))");
        }
        if let Some(u) = self.spectrum_uncertainty {
            if self.topography.is_none() {
                return bad("spectrum_uncertainty applies to a topography (a measured map) only: a self-affine or tabulated spectrum is taken as exact");
            }
            // resamples = 0 leaves the spectrum's part out (punches then unused).
            if u.resamples != 0 {
                count_in("spectrum_uncertainty.resamples", u.resamples, 4..=256)?;
                count_in("spectrum_uncertainty.punches", u.punches, 4..=256)?;
            }
        }
        if let Some(u) = self.spectrum_resamples() {
            if u.punches > self.realisations.max || u.punches < 4 {
                return bad(format!(
                    "spectrum_uncertainty.punches = {} must lie in 4..=realisations.max = {} (the surrogates' punches are the main sample's first ones); resamples = 0 leaves the spectrum's part out",
                    u.punches, self.realisations.max
                ));
            }
        }
        if !(self.target > 0.0 && self.target < 1.0) {
            return bad(format!("target = {} must lie in (0, 1)", self.target));
        }
        let case = self.case(ctx)?;
        let g = case.grid.max(case.map.as_ref().map_or(0, |m| m.n));
        if g > 4096 {
            return bad(format!(
                "the 3D grid would be {g} cells a side (cells x bandwidth, or the map): at most 4096"
            ));
        }
        crate::checks::check_memory_per_thread(
            (g * g) as f64 * crate::checks::cell_bytes::ROUGH_FREE,
            &format!("a {g} x {g} punch per thread"),
        )
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        rough_punch::study_stages(self.topography.is_some() || self.psd.is_some())
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn checkpointed(&self) -> Option<&dyn Checkpointed> {
        Some(self)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        // The source was read and its spectrum computed when the scene was validated:
        // the stage takes them from the scene's memo.
        let make = || self.case(env.ctx);
        let case = if self.topography.is_some() || self.psd.is_some() {
            out.stage(Stage::Psd, make)?
        } else {
            make()?
        };
        for w in &case.warnings {
            out.warn(w.clone());
        }
        let work = env.work_root.join(self.key());
        let (plan, mut solves, part) =
            rough_punch::run_tasks(out, || self.realise(&case, &work, env.control))?;
        let (cal, map) = out.stage(Stage::SweepFit, || -> Result<_> {
            let map = match (&case.map, self.solves_map()) {
                (Some(_), true) => Some(report::MapCurves {
                    bem: tasks::load(&work, Task::MapBem)?,
                    lines: tasks::load(&work, Task::MapMrd)?,
                    rms_factor: case.rms_factor(case.source_band),
                }),
                _ => None,
            };
            Ok((plan, map))
        })?;
        if let Some(m) = &map {
            solves.push((None, m.bem.solves.clone()));
        }
        report::report(
            self,
            &case,
            &cal,
            part.as_ref(),
            map.as_ref(),
            &env.ctx.units.length,
            out,
        )?;
        let surrogates = part.iter().flat_map(|p| p.curves.iter());
        report::solves(self, &solves, surrogates, out);
        Ok(())
    }
}

impl Calibrate {
    /// The source read and checked once per scene (validation and run share it), keyed
    /// by every field `Case::new` reads.
    fn case(&self, ctx: &Context) -> Result<std::sync::Arc<Case>> {
        let key = format!("calibrate {} solve_map={:?}", self.key(), self.solve_map);
        ctx.memo(&key, || Case::new(self, ctx))
    }

    /// Computes (unless `report_only`) and calibrates on `min` realisations, then on
    /// batches more while lambda's interval is wider than the target; a sharded run
    /// computes every realisation up to `max` and reports nothing. Each punch's curve is
    /// read and reduced once, when its batch is first calibrated; its solves' records
    /// are returned beside the calibration, and the spectrum's part of the interval
    /// (a measured map's) after it.
    fn realise(
        &self,
        case: &Case,
        work: &Path,
        control: &RunControl,
    ) -> Result<(Calibration, Vec<report::Solves>, Option<SpectrumPart>)> {
        let r = self.realisations;
        let head = tasks::all(self).len() - r.max as usize;
        let fs = tasks::f_grid();
        let (mut k1, mut k3): (Option<Vec<Option<f64>>>, _) = (None, Vec::new());
        let mut solves = Vec::new();
        // The surrogates' punches are the main sample's first ones: it has them all.
        let first = r.min.max(self.spectrum_punches());
        let mut n = first;
        loop {
            if !control.report_only {
                tasks::compute(self, case, work, head + n as usize, n == first, control)?;
            }
            if k1.is_none() {
                k1 = Some(tasks::load::<Lines>(work, Task::Mrd)?.mean());
            }
            for r in k3.len() as u64..n {
                let curve = tasks::load::<BemCurve>(work, Task::Bem(r))?;
                k3.push(analysis::reduce(&curve, &fs));
                solves.push((Some(r), curve.solves));
            }
            let c = self.calibrate(case, &fs, &k3, k1.as_deref().unwrap_or_default())?;
            let met = c.lambda.relative_half_width() <= self.target;
            if met || n >= r.max {
                let k1 = k1.as_deref().unwrap_or_default();
                let part = super::spectrum::analyse(
                    self,
                    case,
                    work,
                    &k3,
                    k1,
                    case.rms_factor(case.band),
                    &c.lambda,
                )?;
                return Ok((c, solves, part));
            }
            n = (n + r.batch).min(r.max);
        }
    }

    /// The calibration on the reduced 3D curves `k3` against the mean MRD curve `k1`.
    fn calibrate(
        &self,
        case: &Case,
        fs: &[f64],
        k3: &[Vec<Option<f64>>],
        k1: &[Option<f64>],
    ) -> Result<Calibration> {
        let mut rng = mrd::roughness::synthesis::realisation_rng(self.seed, 0x6361_6c69);
        analysis::calibrate(fs, k3, k1, self.window, case.rms_factor(case.band), &mut rng)
            .ok_or_else(|| {
                CompareError::Scene(format!(
                    "fewer than 3 points of the 3D mean k/(E* L) lie in window = {:?} after {} punches: widen the window or raise loads",
                    self.window,
                    k3.len()
                ))
            })
    }
}

impl Checkpointed for Calibrate {
    /// Every parameter the tasks depend on (the source's data are checked separately,
    /// by the fingerprint in the folder).
    fn key(&self) -> String {
        let text = format!(
            "calibrate v1 {:?} {:?} {:?} size={:?} bandwidth={} cells={} loads={} tolerance={} lines={} points={} seed={}",
            self.topography,
            self.psd,
            self.self_affine,
            self.size,
            self.bandwidth,
            self.cells,
            self.loads,
            self.tolerance,
            self.lines,
            self.points_1d_per_cell,
            self.seed
        );
        crate::output::checkpoint_key(&text)
    }

    fn task_files(&self) -> Vec<String> {
        tasks::all(self).iter().map(Task::file_name).collect()
    }

    fn compute(&self, ctx: &Context, dir: &Path, control: &RunControl) -> Result<()> {
        let case = self.case(ctx)?;
        tasks::compute(self, &case, dir, tasks::all(self).len(), true, control)
    }
}
