//! The plan: which computation stages a scene's outputs need.
//!
//! A stage is a named unit of work. The plan is derived from the requested outputs only,
//! so a force-depth request never reconstructs pressure fields and an MRD-only scene
//! never touches the 3D solver; `summary.json` lists the stages that actually ran.

use crate::scene::{Executor, OutputSpec, Scene};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stage {
    /// Rule of Hess (Eq. 11): closed form per shape and by quadrature.
    HessTransform,
    /// Depth/force/radius/stiffness by quadrature and root finding (Eqs. 20, 24, 25).
    NormalSemiAnalytic,
    /// The same on a discretised foundation of springs.
    NormalDiscrete,
    /// Pressure field by the Abel transform (Eq. 26).
    AbelPressure,
    /// Adhesive branch and pull-off (Eqs. 33-37).
    AdhesionSemiAnalytic,
    /// Event-driven loading-unloading of the adhesive spring row.
    AdhesionDiscrete,
    /// Cattaneo-Mindlin/Jager tangential contact (Eqs. 41-50).
    Tangential,
    /// Tangential traction by the Abel transform of Eq. (51).
    AbelTraction,
    /// Time-stepped oscillating contact with Coulomb friction (Section 7).
    OscillationDiscrete,
    /// Literature closed forms for overlay and error measures.
    ClosedForm,
    /// Hereditary (Prony) springs of Eq. (63).
    Viscoelastic,
    /// Random rough lines or surfaces (Eqs. 70-72).
    RoughSynthesis,
    /// Rough line on the MRD foundation (sorted gaps, exact queries).
    RoughContact,
    /// 3D boundary-element contact (bem3d).
    Bem3d,
    /// Power spectrum of a measured topography.
    Psd,
    /// Fits of Eq. (77), bootstrap intervals, lambda calibration.
    SweepFit,
}

impl Stage {
    pub fn name(self) -> &'static str {
        match self {
            Stage::HessTransform => "hess_transform",
            Stage::NormalSemiAnalytic => "normal_semi_analytic",
            Stage::NormalDiscrete => "normal_discrete",
            Stage::AbelPressure => "abel_pressure",
            Stage::AdhesionSemiAnalytic => "adhesion_semi_analytic",
            Stage::AdhesionDiscrete => "adhesion_discrete",
            Stage::Tangential => "tangential",
            Stage::AbelTraction => "abel_traction",
            Stage::OscillationDiscrete => "oscillation_discrete",
            Stage::ClosedForm => "closed_form",
            Stage::Viscoelastic => "viscoelastic_springs",
            Stage::RoughSynthesis => "rough_synthesis",
            Stage::RoughContact => "rough_contact_mrd",
            Stage::Bem3d => "bem3d",
            Stage::Psd => "measured_psd",
            Stage::SweepFit => "sweep_fit",
        }
    }
}

/// Stages needed by one output (in execution order).
pub fn stages_for(output: &OutputSpec, has_closed_form: bool) -> Vec<Stage> {
    use Stage::*;
    match output.executor() {
        Executor::Sweep => return vec![RoughSynthesis, Bem3d, RoughContact, SweepFit],
        Executor::Bem => return vec![Bem3d],
        Executor::RoughLines => return vec![RoughSynthesis, RoughContact],
        Executor::Axisymmetric => {}
    }
    let mut s = vec![HessTransform];
    match output {
        OutputSpec::Profile1d { .. } => {}
        OutputSpec::ForceDepth { springs, .. } => {
            s.push(NormalSemiAnalytic);
            if springs.is_some() {
                s.push(NormalDiscrete);
            }
        }
        OutputSpec::Pressure { .. } => s.extend([NormalSemiAnalytic, AbelPressure]),
        OutputSpec::Adhesion { springs, .. } => {
            s.push(AdhesionSemiAnalytic);
            if springs.is_some() {
                s.push(AdhesionDiscrete);
            }
        }
        OutputSpec::Tangential { traction_at, .. } => {
            s.extend([NormalSemiAnalytic, Tangential]);
            if !traction_at.is_empty() {
                s.push(AbelTraction);
            }
        }
        OutputSpec::Damping { .. } => s.extend([NormalSemiAnalytic, OscillationDiscrete]),
        OutputSpec::Viscoelastic { .. } => s.extend([Viscoelastic, ClosedForm]),
        OutputSpec::StaticFriction { .. }
        | OutputSpec::RoughStiffness { .. }
        | OutputSpec::HurstSweep(_)
        | OutputSpec::BemContact { .. } => unreachable!(),
    }
    if has_closed_form && !matches!(output, OutputSpec::Profile1d { .. }) {
        s.push(ClosedForm);
    }
    s
}

/// The union of all outputs' stages, each once, in first-use order.
pub fn plan(scene: &Scene) -> Vec<Stage> {
    let cf = scene
        .file
        .profile
        .as_ref()
        .and_then(|p| p.closed_form())
        .is_some();
    let mut all = Vec::new();
    for o in &scene.file.outputs {
        for st in stages_for(o, cf) {
            if !all.contains(&st) {
                all.push(st);
            }
        }
    }
    all
}
