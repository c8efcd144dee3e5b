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
