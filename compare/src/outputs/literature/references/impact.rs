//! Hertz's impact, by MRD and in 3D in the loop of a time integration.

use super::{sphere, Computed, References};
use crate::error::{Context as _, Result};
use crate::experiment::impact::{bem3d_law, first_contact, Strike};
use crate::plan::Stage;
use crate::report::Section;
use dynamics::{ContactLaw, Springs};
use mrd::reference::{hertz, hertz_impact};

impl References {
    /// Hertz's impact (E* = R = 1, m = 1e-3, v = 0.05), integrated in time by velocity
    /// Verlet with the contact at every step. MRD (the rule of Hess, exact for the
    /// sphere) errs by the time step only, at second order: 1e-3 of the contact time at
    /// 2000 steps bounds it with room (the `impact` scene measures 3e-8 at 4000). The 3D
    /// solve in the loop errs by its grid (the highest cell below the apex, the disc of
    /// cells): 1 % at 32 cells per side or more (the `impact` scene measures 4.3e-4 at
    /// 64^2).
    pub(super) fn impact(&self, out: &mut Section) -> Result<Vec<Computed>> {
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
}
