//! What the axisymmetric (exact MRD) outputs share: the scene's profile mapped by the
//! rule of Hess (Eq. 11) onto the 1D foundation.

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
