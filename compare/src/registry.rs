//! The registry: the one place that lists the output kinds, in the order `mrdw kinds`
//! prints them. A new kind is a file (or a folder, for a study) in its group under
//! `outputs/` plus one line here; no kind imports this module.

use crate::output::Output;
use crate::outputs::{axisym, dynamics, friction, literature, reference3d, rough, viscoelastic};
use serde::de::DeserializeOwned;

/// A registered output kind.
pub struct Kind {
    pub name: &'static str,
    /// One line: what the output computes.
    pub about: &'static str,
    parse: fn(toml::Value) -> std::result::Result<Box<dyn Output>, String>,
}

impl Kind {
    const fn of<T: Output + DeserializeOwned + 'static>(
        name: &'static str,
        about: &'static str,
    ) -> Self {
        Self {
            name,
            about,
            parse: parse_as::<T>,
        }
    }

    /// Builds the output from its `[[outputs]]` table (without `kind`).
    pub fn parse(&self, table: toml::Value) -> std::result::Result<Box<dyn Output>, String> {
        (self.parse)(table)
    }
}

fn parse_as<T: Output + DeserializeOwned + 'static>(
    v: toml::Value,
) -> std::result::Result<Box<dyn Output>, String> {
    v.try_into::<T>()
        .map(|t| Box::new(t) as Box<dyn Output>)
        .map_err(|e| e.message().lines().next().unwrap_or("invalid").to_string())
}

/// The registry: every output kind, in the order `mrdw kinds` lists them.
pub const KINDS: &[Kind] = &[
    Kind::of::<axisym::profile_1d::Profile1d>(
        "profile_1d",
        "the 3D profile z(r) and its MRD image z1d(x) (Eq. 11)",
    ),
    Kind::of::<axisym::force_depth::ForceDepth>(
        "force_depth",
        "force, contact radius and stiffness against depth (Eqs. 20, 24, 25)",
    ),
    Kind::of::<axisym::pressure::Pressure>("pressure", "pressure p(r) by the Abel transform (Eq. 26)"),
    Kind::of::<axisym::adhesion::Adhesion>(
        "adhesion",
        "adhesive loading-unloading and pull-off (Eqs. 33-37)",
    ),
    Kind::of::<axisym::adhesion_3d::Adhesion3d>(
        "adhesion_3d",
        "an adhesive loading-unloading cycle in 3D beside MRD: loop, pull-off and jump-out on a ladder of grids against Eq. 33 and JKR, Kendall or the cone (Section 5)",
    ),
    Kind::of::<axisym::tabor_3d::Tabor3d>(
        "tabor_3d",
        "a sphere's pull-off against the Tabor-Maugis parameter: 3D Maugis-Dugdale, Maugis' closed form and MRD's JKR limit (Section 5)",
    ),
    Kind::of::<axisym::plastic_3d::Plastic3d>(
        "plastic_3d",
        "elastic-perfectly plastic contact of a body of revolution (pressure cap H) along a force history, in 3D beside MRD in incremental form: loops, imprint, grid convergence; a sphere against Kogut-Etsion's finite elements (Section 11)",
    ),
    Kind::of::<rough::rough_plastic_3d::RoughPlastic3d>(
        "rough_plastic_3d",
        "a rough punch loaded, unloaded and reloaded on an elastic-perfectly plastic half-space (pressure cap H) in 3D beside MRD's rough lines with patch-capped springs, across the plasticity index: stiffness ratios, recovered approach, lambda refitted (Section 11 on rough surfaces)",
    ),
    Kind::of::<dynamics::friction_forced::FrictionForced>(
        "friction_forced",
        "a mass on a sphere driven tangentially by a harmonic force, damped by partial slip: the frequency response by MRD's Coulomb springs and the 3D partial slip in the loop, each steady period's slip energy against Mindlin-Deresiewicz's at its force amplitude (Sections 7 and 12)",
    ),
    Kind::of::<dynamics::impact::Impact>(
        "impact",
        "a sphere's impact integrated in time with the contact at every step, MRD's springs and the 3D solve in the loop, against Hertz's impact (Section 12)",
    ),
    Kind::of::<dynamics::viscoelastic_impact::ViscoelasticImpact>(
        "viscoelastic_impact",
        "a sphere striking a viscoelastic half-space at a range of speeds, MRD's viscoelastic springs and the 3D transient solve in the loop: restitution and contact time against speed (Sections 8 and 12)",
    ),
    Kind::of::<dynamics::adhesive_impact::AdhesiveImpact>(
        "adhesive_impact",
        "a sphere striking a half-space with zero-range adhesion (JKR limit) at a range of speeds, MRD's adhesive springs (Eq. 33) and the 3D adhesive solve in the loop: capture and restitution against the closed form of the adhesive hysteresis (Sections 5 and 12)",
    ),
    Kind::of::<dynamics::resonance::ContactResonance>(
        "contact_resonance",
        "free normal vibration on a rough contact with the contact at every step, MRD's rough lines and the 3D punch in the loop: frequency against k(F0), backbone and contact loss; the cost of a step against the grid (Section 12)",
    ),
    Kind::of::<dynamics::forced::ForcedResonance>(
        "forced_resonance",
        "a rough contact driven through its resonance by a harmonic normal force, MRD's rough lines and the 3D punch in the loop: steady amplitude against frequency up and down, the linear oscillator at small forcing, softening and the jump at large forcing (Section 12)",
    ),
    Kind::of::<dynamics::oblique_impact::ObliqueImpact>(
        "oblique_impact",
        "a translating sphere striking the half-space obliquely with friction, the normal and the tangential force at every step, MRD's Coulomb springs and the 3D contact (normal solve and partial slip under the step's pressure) in the loop: tangential rebound and slip energy against incidence, the sliding and no-slip closed forms (Sections 6-7 and 12)",
    ),
    Kind::of::<dynamics::oblique_cycle::ObliqueCycle>(
        "oblique_cycle",
        "a sphere's normal and tangential motion oscillating in phase, MRD's Coulomb springs and the 3D contact (normal solve and partial slip under each step's pressure): slip energy per cycle against the tangential amplitude beside the held normal's Mindlin-Deresiewicz, and the shakedown (Section 7 with the normal force oscillating too)",
    ),
    Kind::of::<dynamics::ring_down::RingDown>(
        "ring_down",
        "a mass ringing down on a sphere's frictional contact, MRD's Coulomb springs at every step, against Mindlin-Deresiewicz's loss per cycle (Sections 7 and 12)",
    ),
    Kind::of::<dynamics::rough_ring_down::RoughRingDown>(
        "rough_ring_down",
        "a mass ringing down on a rough punch's frictional contact, MRD's rough lines with Coulomb springs and the 3D partial slip in the loop: each cycle's loss against the closed form of its own normal curve (Ciavarella-Jaeger with Masing's rule), MRD's damping ratio against the 3D one (Sections 7 and 12)",
    ),
    Kind::of::<literature::references::References>(
        "references",
        "published reference results (compare/data/references.toml: Hertz's impact time, JKR's pull-off, Cattaneo-Mindlin's stick radius), each by MRD and in 3D, with its deviation and verdict",
    ),
    Kind::of::<axisym::tangential::Tangential>(
        "tangential",
        "Cattaneo-Mindlin tangential loading and tractions (Eqs. 41-51)",
    ),
    Kind::of::<axisym::tangential_3d::Tangential3d>(
        "tangential_3d",
        "a body of revolution loaded tangentially in 3D beside MRD: stick radius and dissipation per cycle, against Cattaneo-Mindlin and Mindlin-Deresiewicz for a sphere, Jaeger (MRD) for a cone or power law, Sections 6-7",
    ),
    Kind::of::<axisym::damping::Damping>(
        "damping",
        "energy dissipated per cycle of an oscillating contact (Section 7)",
    ),
    Kind::of::<viscoelastic::viscoelastic::Viscoelastic>(
        "viscoelastic",
        "viscoelastic ramp-and-hold indentation against Radok (Eq. 63)",
    ),
    Kind::of::<friction::static_friction::StaticFriction>(
        "static_friction",
        "static friction from the mean slope in contact (Section 10.2, Fig. 9)",
    ),
    Kind::of::<friction::static_friction_3d::StaticFriction3d>(
        "static_friction_3d",
        "the mean slope in contact in 3D against MRD, Eq. (93) (Section 10.2)",
    ),
    Kind::of::<rough::tangential_stiffness_3d::TangentialStiffness3d>(
        "tangential_stiffness_3d",
        "tangential over normal stiffness of rough contacts held in stick, 3D (Cerruti's tensor) against MRD's G*/E* (Section 6 on rough surfaces)",
    ),
    Kind::of::<rough::rough_partial_slip_3d::RoughPartialSlip3d>(
        "rough_partial_slip_3d",
        "partial slip of rough contacts: the 3D shift against the force and the energy per cycle against MRD's tangential mapping of each surface's normal curve (Ciavarella-Jaeger, Masing; Sections 6-7 on rough surfaces)",
    ),
    Kind::of::<rough::rough_slip_3d::RoughSlip3d>(
        "rough_slip_3d",
        "partial slip of a rough sphere or rough flat punch on the free half-space, 3D against MRD's rough line (lambda) and against MRD's law on the 3D normal curve: force-shift to gross slip, energy per cycle, k_t / k_n (Sections 6-7 on rough bodies)",
    ),
    Kind::of::<rough::calibrate::Calibrate>(
        "calibrate",
        "lambda of Eq. (76) for the user's own surface (a measured map, a PSD table or a self-affine spectrum with roll-off): 3D rough punches of its spectrum against MRD lines, with interval, misfit, alpha_3D and alpha_MRD, and the map itself solved in 3D (Section 9)",
    ),
    Kind::of::<rough::rough_stiffness::RoughStiffness>(
        "rough_stiffness",
        "ensemble stiffness-force law of MRD rough lines (Eq. 77)",
    ),
    Kind::of::<friction::sliding_friction::SlidingFriction>(
        "sliding_friction",
        "elastomer friction mu(v) of rough lines on viscoelastic springs, Eq. 82 (Fig. 7)",
    ),
    Kind::of::<friction::sliding_friction_3d::SlidingFriction3d>(
        "sliding_friction_3d",
        "steady viscoelastic sliding of rough surfaces in 3D against MRD and Eq. 82 (Fig. 7 in 3D)",
    ),
    Kind::of::<reference3d::bem_contact::BemContact>(
        "bem_contact",
        "3D boundary-element contact of a height map from a file (.npy, text matrix, ESRI ASCII grid, .xyz point list)",
    ),
    Kind::of::<rough::contact_area::ContactArea>(
        "contact_area",
        "real contact area and mean gap against force, 3D against MRD (Section 11)",
    ),
    Kind::of::<rough::rough_adhesion_3d::RoughAdhesion3d>(
        "rough_adhesion_3d",
        "adhesion of rough spheres, 3D (Pohrt-Popov) against MRD's rule of Hess on a rough line: pull-off, adhesion coefficient and loop energy against roughness (Section 5 on rough surfaces)",
    ),
    Kind::of::<rough::rough_sphere::RoughSphere>(
        "rough_sphere",
        "a sphere with self-affine roughness, 3D against MRD (Hess + Eq. 76), smooth to rough (Section 9)",
    ),
    Kind::of::<viscoelastic::tangential_viscoelastic::TangentialViscoelastic>(
        "tangential_viscoelastic",
        "Cattaneo-Mindlin on viscoelastic tangential springs: ramp, hold, cycle, stick zone and energy (Eqs. 64-65)",
    ),
    Kind::of::<viscoelastic::viscoelastic_rough::ViscoelasticRough>(
        "viscoelastic_rough",
        "a rough punch on a viscoelastic half-space through ramp, hold, unload and reload, 3D against MRD springs (Eq. 63, Section 8)",
    ),
    Kind::of::<rough::hurst_sweep::HurstSweep>(
        "hurst_sweep",
        "the Hurst sweep, 3D against MRD: alpha(H), zeta(H), lambda(H) (Fig. 6)",
    ),
    Kind::of::<rough::lambda_study::LambdaStudy>(
        "lambda_study",
        "lambda(H) and alpha(H) converged in bandwidth, resolution and realisations (calibration of Eq. 76)",
    ),
];

/// The registered kind called `name`.
pub fn kind(name: &str) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.name == name)
}
