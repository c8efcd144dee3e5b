//! What the axisymmetric (exact MRD) outputs share: the scene's profile mapped by the
//! rule of Hess (Eq. 11) onto the 1D foundation.

use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::output::Env;
use crate::plan::Stage;
use crate::report::Section;
use mrd::normal::AxisymmetricContact;

/// The rule-of-Hess stage: the profile's 1D contact (E* springs).
pub fn hess(env: &Env, out: &mut Section) -> Result<AxisymmetricContact> {
    let profile = env.ctx.profile()?.clone();
    let e = env.ctx.material.e_star;
    out.stage(Stage::HessTransform, || {
        AxisymmetricContact::new(profile, e)
    })
    .ctx("rule of Hess")
}

/// The stages of an axisymmetric output: the rule of Hess, the semi-analytic normal
/// solve, the output's own stage `then`, and the closed form where the scene has one.
pub fn stages(then: Stage, closed_form: bool) -> Vec<Stage> {
    let mut s = vec![Stage::HessTransform, Stage::NormalSemiAnalytic, then];
    if closed_form {
        s.push(Stage::ClosedForm);
    }
    s
}

/// Whether the scene's profile is a sphere (a paraboloid), whose closed forms the
/// tangential and damping outputs compare against.
pub fn is_sphere(ctx: &Context) -> bool {
    ctx.profile
        .as_ref()
        .and_then(mrd::reference::for_profile::sphere_radius)
        .is_some()
}

/// What every axisymmetric output checks first: the scene has a profile, and `points`
/// samples lie in the range the tables take.
pub fn check_scene(ctx: &Context, points: usize) -> Result<()> {
    ctx.profile()?;
    crate::checks::check_points(points)
}

/// G* of the scene's material for the tangential output `what`, with a warning in `out`
/// where the bodies are not elastically similar (Eq. 7: MRD's decoupled tangential
/// solution is then an approximation).
pub fn shear_modulus(env: &Env, out: &mut Section, what: &str) -> Result<f64> {
    let g = env.ctx.material.g_star().ctx(what)?;
    if let Some(w) = env.ctx.material.similarity_warning() {
        out.warn(w);
    }
    Ok(g)
}
