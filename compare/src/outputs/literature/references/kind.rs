//! `references`' run: every reference computed, then the report.

use super::{published, Computed, References};
use crate::checks::{bad, count_in};
use crate::context::Context;
use crate::error::Result;
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::Section;

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
