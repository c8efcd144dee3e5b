//! Stages and the plan: which computation stages each requested output will run.
//!
//! Each output declares its stages before running ([`crate::output::Output::stages`]),
//! so a force-depth request never reconstructs pressure fields and an MRD-only scene never
//! touches the 3D solver. The run records the stages each output actually executed
//! ([`crate::report::Section::stage`]); `summary.json` lists them, and the test suite
//! checks that they equal the declared plan for every embedded scene.

use std::fmt;

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
    /// 3D adhesive contact in the JKR limit (`bem3d::adhesion`).
    Adhesion3d,
    /// Cattaneo-Mindlin/Jager tangential contact (Eqs. 41-50).
    Tangential,
    /// Tangential traction by the Abel transform of Eq. (51).
    AbelTraction,
    /// 3D partial slip with Coulomb friction under a held pressure (`bem3d::tangential`).
    Tangential3d,
    /// Time-stepped oscillating contact with Coulomb friction (Section 7).
    OscillationDiscrete,
    /// Literature closed forms for overlay and error measures.
    ClosedForm,
    /// Hereditary (Prony) springs of Eq. (63).
    Viscoelastic,
    /// Steady sliding of rough lines over viscoelastic springs (Section 10.1).
    ViscoelasticSliding,
    /// Steady sliding of rough surfaces over a viscoelastic half-space (bem3d).
    ViscoelasticSliding3d,
    /// Transient contact of rough surfaces on a viscoelastic half-space (bem3d).
    Viscoelastic3d,
    /// Random rough lines or surfaces (Eqs. 70-72).
    RoughSynthesis,
    /// Rough line on the MRD foundation (sorted gaps, exact queries).
    RoughContact,
    /// 3D boundary-element contact (bem3d).
    Bem3d,
    /// Tangent normal stiffness of 3D contacts (bem3d, contact set fixed).
    Bem3dStiffness,
    /// Power spectrum of a measured topography.
    Psd,
    /// Fits of Eq. (77), bootstrap intervals, lambda calibration.
    SweepFit,
    /// Elastic-perfectly plastic contact by MRD in incremental form (`mrd::plasticity`).
    PlasticMrd,
    /// Elastic-perfectly plastic contact in 3D, the pressure cap (`bem3d::plastic`).
    Plastic3d,
    /// A time integration with MRD's contact at every step (`dynamics`).
    Dynamics,
    /// A time integration with the 3D contact at every step (`dynamics`, `bem3d`).
    Dynamics3d,
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
            Stage::Adhesion3d => "adhesion_3d",
            Stage::Tangential => "tangential",
            Stage::AbelTraction => "abel_traction",
            Stage::Tangential3d => "tangential_3d",
            Stage::OscillationDiscrete => "oscillation_discrete",
            Stage::ClosedForm => "closed_form",
            Stage::Viscoelastic => "viscoelastic_springs",
            Stage::ViscoelasticSliding => "viscoelastic_sliding",
            Stage::ViscoelasticSliding3d => "viscoelastic_sliding_3d",
            Stage::Viscoelastic3d => "viscoelastic_3d",
            Stage::RoughSynthesis => "rough_synthesis",
            Stage::RoughContact => "rough_contact_mrd",
            Stage::Bem3d => "bem3d",
            Stage::Bem3dStiffness => "bem3d_stiffness",
            Stage::Psd => "measured_psd",
            Stage::SweepFit => "sweep_fit",
            Stage::PlasticMrd => "plastic_mrd",
            Stage::Plastic3d => "plastic_3d",
            Stage::Dynamics => "dynamics_mrd",
            Stage::Dynamics3d => "dynamics_3d",
        }
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The stages of each output of a scene, in run order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Plan {
    /// (output label, stages).
    pub outputs: Vec<(String, Vec<Stage>)>,
}

impl Plan {
    /// Every stage once, in first-use order.
    pub fn stages(&self) -> Vec<Stage> {
        let mut all = Vec::new();
        for (_, stages) in &self.outputs {
            for &s in stages {
                if !all.contains(&s) {
                    all.push(s);
                }
            }
        }
        all
    }
}

impl fmt::Display for Plan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (label, stages) in &self.outputs {
            let names: Vec<&str> = stages.iter().map(|s| s.name()).collect();
            writeln!(f, "  {label}: {}", names.join(" -> "))?;
        }
        Ok(())
    }
}
