//! Scene (case) files: what is modelled and which outputs are wanted.
//!
//! A scene is TOML; unknown keys are errors. It declares units, the material, the
//! indenter profile and a list of `[[outputs]]`; the run computes only the stages those
//! outputs need (see [`crate::plan`]). The format is documented with examples in
//! `cases/README.md`.

use crate::error::{CompareError, MrdContext, Result};
use mrd::{ElasticBody, Material, Profile, Shape, TabulatedProfile};
use serde::Deserialize;
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Short name; the default output folder is `reports/<name>/`.
    pub name: String,
    pub title: Option<String>,
    pub description: Option<String>,
    #[serde(default)]
    pub units: Units,
    pub material: MaterialSpec,
    pub profile: Option<ProfileSpec>,
    pub outputs: Vec<OutputSpec>,
}

/// Unit labels (the computation is unit-agnostic; labels go into headers and axes).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Units {
    #[serde(default = "default_length")]
    pub length: String,
    #[serde(default = "default_stress")]
    pub stress: String,
}

fn default_length() -> String {
    "m".into()
}
fn default_stress() -> String {
    "Pa".into()
}

impl Default for Units {
    fn default() -> Self {
        Self {
            length: default_length(),
            stress: default_stress(),
        }
    }
}

impl Units {
    /// Force unit = stress x length^2, named where the pair is a standard one.
    pub fn force(&self) -> String {
        match (self.stress.as_str(), self.length.as_str()) {
            ("Pa", "m") | ("MPa", "mm") => "N".into(),
            ("GPa", "mm") => "kN".into(),
            ("MPa", "um") => "uN".into(),
            ("GPa", "um") => "mN".into(),
            ("1", "1") => "1".into(),
            (s, l) => format!("{s}*{l}^2"),
        }
    }
    /// Energy unit = force x length.
    pub fn energy(&self) -> String {
        match (self.force().as_str(), self.length.as_str()) {
            ("N", "m") => "J".into(),
            ("N", "mm") => "mJ".into(),
            ("1", "1") => "1".into(),
            (f, l) => format!("{f}*{l}"),
        }
    }
    /// Work of adhesion unit = energy / area = stress x length.
    pub fn surface_energy(&self) -> String {
        match (self.stress.as_str(), self.length.as_str()) {
            ("Pa", "m") => "J/m^2".into(),
            ("1", "1") => "1".into(),
            (s, l) => format!("{s}*{l}"),
        }
    }
    /// Stiffness unit = force / length = stress x length.
    pub fn stiffness(&self) -> String {
        match (self.stress.as_str(), self.length.as_str()) {
            ("Pa", "m") => "N/m".into(),
            ("MPa", "mm") => "N/mm".into(),
            ("1", "1") => "1".into(),
            (s, l) => format!("{s}*{l}"),
        }
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    /// Young's modulus; `inf` for a rigid body.
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
}

/// Either effective moduli directly (`e_star`, optional `g_star`) or the two bodies.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub e_star: Option<f64>,
    pub g_star: Option<f64>,
    pub indenter: Option<BodySpec>,
    pub substrate: Option<BodySpec>,
}

impl MaterialSpec {
    pub fn build(&self) -> Result<Material> {
        match (self.e_star, &self.indenter, &self.substrate) {
            (Some(e), None, None) => match self.g_star {
                Some(g) => Material::from_moduli(e, g),
                None => Material::from_e_star(e),
            }
            .ctx("material"),
            (None, Some(a), Some(b)) => {
                if self.g_star.is_some() {
                    return Err(CompareError::Scene(
                        "material: give either e_star/g_star or indenter+substrate, not both"
                            .into(),
                    ));
                }
                let a =
                    ElasticBody::new(a.youngs_modulus, a.poisson_ratio).ctx("material.indenter")?;
                let b = ElasticBody::new(b.youngs_modulus, b.poisson_ratio)
                    .ctx("material.substrate")?;
                Material::from_bodies(a, b).ctx("material")
            }
            _ => Err(CompareError::Scene(
                "material: give either e_star (and optionally g_star) or both [material.indenter] \
                 and [material.substrate]"
                    .into(),
            )),
        }
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ShapeSpec {
    /// z = c r^n (Eq. 12), any real n > 0.
    PowerLaw { c: f64, n: f64 },
    /// Sphere of radius R (paraboloid z = r^2/(2R)).
    Sphere { radius: f64 },
    /// Cone z = r tan(theta); `slope` = tan(theta).
    Cone { slope: f64 },
    /// Flattened sphere (Eq. 22): flat of radius `flat_radius`, then a paraboloid.
    FlattenedSphere { radius: f64, flat_radius: f64 },
    /// Piecewise-linear table: two-column CSV `file` (r, z; relative to the scene) or
    /// inline arrays `r` and `z`.
    Table {
        file: Option<String>,
        r: Option<Vec<f64>>,
        z: Option<Vec<f64>>,
    },
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileSpec {
    /// Shapes summed into one profile (may be empty for a flat punch).
    #[serde(default)]
    pub shapes: Vec<ShapeSpec>,
    /// Radius of the cylindrical punch carrying the profile (flat punch: no shapes).
    pub rim: Option<f64>,
}

impl ProfileSpec {
    pub fn build(&self, base_dir: Option<&Path>) -> Result<Profile> {
        let mut shapes = Vec::new();
        for (i, s) in self.shapes.iter().enumerate() {
            let ctx = format!("profile.shapes[{i}]");
            shapes.push(match s {
                ShapeSpec::PowerLaw { c, n } => Shape::power_law(*c, *n).ctx(ctx)?,
                ShapeSpec::Sphere { radius } => Shape::paraboloid(*radius).ctx(ctx)?,
                ShapeSpec::Cone { slope } => Shape::cone(*slope).ctx(ctx)?,
                ShapeSpec::FlattenedSphere {
                    radius,
                    flat_radius,
                } => Shape::flattened_paraboloid(*radius, *flat_radius).ctx(ctx)?,
                ShapeSpec::Table { file, r, z } => {
                    let (r, z) = match (file, r, z) {
                        (Some(f), None, None) => {
                            mrd::topography::read_profile_csv(&resolve(base_dir, f)?).ctx(&ctx)?
                        }
                        (None, Some(r), Some(z)) => (r.clone(), z.clone()),
                        _ => {
                            return Err(CompareError::Scene(format!(
                                "{ctx}: a table needs either `file` or both `r` and `z`"
                            )))
                        }
                    };
                    Shape::Table(TabulatedProfile::new(r, z).ctx(ctx)?)
                }
            });
        }
        Profile::new(shapes, self.rim).ctx("profile")
    }

    /// The single analytic shape with a closed-form solution, if the profile is one.
    pub fn closed_form(&self) -> Option<ClosedForm> {
        match (self.shapes.as_slice(), self.rim) {
            ([], Some(a)) => Some(ClosedForm::FlatPunch { radius: a }),
            ([ShapeSpec::Sphere { radius }], None) => Some(ClosedForm::Sphere { radius: *radius }),
            ([ShapeSpec::Cone { slope }], None) => Some(ClosedForm::Cone { slope: *slope }),
            ([ShapeSpec::PowerLaw { c, n }], None) => Some(ClosedForm::PowerLaw { c: *c, n: *n }),
            (
                [ShapeSpec::FlattenedSphere {
                    radius,
                    flat_radius,
                }],
                None,
            ) => Some(ClosedForm::FlattenedSphere {
                radius: *radius,
                flat_radius: *flat_radius,
            }),
            _ => None,
        }
    }
}

/// Profiles with a literature closed form to overlay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClosedForm {
    FlatPunch { radius: f64 },
    Sphere { radius: f64 },
    Cone { slope: f64 },
    PowerLaw { c: f64, n: f64 },
    FlattenedSphere { radius: f64, flat_radius: f64 },
}

fn resolve(base: Option<&Path>, file: &str) -> Result<PathBuf> {
    let p = Path::new(file);
    if p.is_absolute() {
        return Ok(p.to_path_buf());
    }
    match base {
        Some(b) => Ok(b.join(p)),
        None => Err(CompareError::Scene(format!(
            "table file `{file}`: embedded scenes cannot refer to files; use inline r and z"
        ))),
    }
}

/// How a force-depth curve is driven.
#[derive(Debug, Clone, Copy, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Drive {
    #[default]
    Depth,
    Force,
}

#[derive(Debug, Clone, Copy, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum ControlSpec {
    #[default]
    Force,
    Displacement,
}

/// One requested output. Each writes one CSV and one PNG named after its kind.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum OutputSpec {
    /// The 3D profile z(r) and its MRD image z1d(x) (Eq. 11).
    #[serde(rename = "profile_1d")]
    Profile1d {
        r_max: f64,
        #[serde(default = "default_points")]
        points: usize,
    },
    /// Force, contact radius and stiffness against depth (Eqs. 20, 24, 25), optionally
    /// on a discrete foundation of `springs` springs over [-half_length, half_length],
    /// and the electrical conductance for a resistivity sum.
    ForceDepth {
        /// Largest depth (drive = "depth") or force (drive = "force").
        max: f64,
        #[serde(default)]
        drive: Drive,
        #[serde(default = "default_points")]
        points: usize,
        springs: Option<usize>,
        half_length: Option<f64>,
        resistivity_sum: Option<f64>,
    },
    /// Pressure p(r) by the Abel transform (Eq. 26) at one depth.
    Pressure {
        depth: f64,
        #[serde(default = "default_points")]
        points: usize,
    },
    /// Adhesive loading-unloading cycle (Eq. 33) to `depth_max` and pull-off.
    Adhesion {
        gamma: f64,
        depth_max: f64,
        #[serde(default)]
        control: ControlSpec,
        springs: Option<usize>,
        half_length: Option<f64>,
        #[serde(default = "default_points")]
        points: usize,
    },
    /// Tangential loading at normal force `normal_force` up to full sliding (Section 6),
    /// and the traction distribution at the fractions `traction_at` of mu F_N.
    Tangential {
        mu: f64,
        normal_force: f64,
        #[serde(default = "default_points")]
        points: usize,
        #[serde(default)]
        traction_at: Vec<f64>,
    },
    /// A 3D boundary-element contact of a height map from a file (`.npy` or text).
    BemContact {
        /// Height map file (peaks up), relative to the scene.
        heights: String,
        /// Physical size [lx, ly] of the map (length units).
        size: [f64; 2],
        #[serde(default = "yes")]
        periodic: bool,
        /// Radius of a centred circular punch (mask); none: the whole map may touch.
        punch_radius: Option<f64>,
        /// Loads: mean pressures over the map area ...
        #[serde(default)]
        mean_pressures: Vec<f64>,
        /// ... or rigid-body approaches from first contact.
        #[serde(default)]
        approaches: Vec<f64>,
        #[serde(default = "bem_tol")]
        tolerance: f64,
        #[serde(default = "bem_iters")]
        max_iterations: usize,
        /// Also write pressure and gap fields as .npy (one pair per load).
        #[serde(default)]
        fields: bool,
    },
    /// The Hurst sweep, 3D against 1D (Section 9, Fig. 6); see [`crate::sweep`].
    HurstSweep(crate::sweep::SweepSpec),
    /// Static friction from the mean slope in contact (Section 10.2, Fig. 9).
    StaticFriction {
        hurst: f64,
        points: usize,
        length: f64,
        /// rms height h; or give `contacts_at_max_force` to calibrate h.
        rms_height: Option<f64>,
        contacts_at_max_force: Option<f64>,
        #[serde(default = "default_realisations")]
        realisations: u64,
        #[serde(default)]
        seed: u64,
        force_min: f64,
        force_max: f64,
        #[serde(default = "default_force_points")]
        force_points: usize,
        /// A published fit xi = a + b ln f to draw and report alongside (optional).
        paper_a: Option<f64>,
        paper_b: Option<f64>,
    },
    /// Ensemble stiffness-force law of MRD rough lines (Eq. 77) and its exponent.
    RoughStiffness {
        hurst: f64,
        /// A measured topography whose radially averaged PSD replaces the self-affine
        /// spectrum: C1D = lambda q C2D_measured (Eq. 76).
        measured: Option<MeasuredSurface>,
        points: usize,
        length: f64,
        /// Upper cut-off as a fraction of the Nyquist wavenumber pi N / L.
        #[serde(default = "default_cutoff_ratio")]
        upper_cutoff_ratio: f64,
        #[serde(default)]
        lambda: LambdaSpec,
        #[serde(default = "default_realisations")]
        realisations: u64,
        #[serde(default)]
        seed: u64,
        f_min: f64,
        f_max: f64,
        #[serde(default = "default_force_points")]
        f_points: usize,
    },
    /// Viscoelastic indentation (Section 8, Eq. 63): a constant-rate ramp to `depth_max`
    /// over `ramp_time`, then a hold until `end_time`, against Radok's solution.
    Viscoelastic {
        /// Long-time modulus E*_inf.
        e_inf: f64,
        /// Prony terms [[E_i, tau_i], ...] of E*(t) = E_inf + sum E_i exp(-t/tau_i).
        prony: Vec<[f64; 2]>,
        depth_max: f64,
        ramp_time: f64,
        end_time: f64,
        #[serde(default = "default_springs")]
        springs: usize,
        half_length: Option<f64>,
        #[serde(default = "default_steps_visco")]
        steps: usize,
    },
    /// Oscillating tangential loading at depth `depth` (Section 7): dissipation per cycle
    /// against amplitude, up to `max_amplitude_ratio` x A_c0 (A_c0 = mu E*/G* d).
    Damping {
        mu: f64,
        depth: f64,
        #[serde(default = "default_amplitude_ratio")]
        max_amplitude_ratio: f64,
        #[serde(default = "default_points")]
        points: usize,
        #[serde(default = "default_springs")]
        springs: usize,
        half_length: Option<f64>,
        #[serde(default = "default_steps")]
        steps_per_cycle: usize,
    },
}

/// A height map on disk and its physical size.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MeasuredSurface {
    /// `.npy` or text matrix, relative to the scene.
    pub heights: String,
    /// [lx, ly] in length units.
    pub size: [f64; 2],
}

/// lambda of Eq. (76): a number, "pi" (Eq. 73), "cut" (straight cut), "calibrated" (the
/// embedded table from the `fig6` scene), or the path of a CSV table `hurst, lambda`
/// (relative to the scene), e.g. a sweep's `<label>_lambda_table.csv`.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum LambdaSpec {
    Value(f64),
    Named(String),
}

impl Default for LambdaSpec {
    fn default() -> Self {
        LambdaSpec::Named("pi".into())
    }
}

fn default_points() -> usize {
    60
}
fn yes() -> bool {
    true
}
fn bem_tol() -> f64 {
    1e-10
}
fn bem_iters() -> usize {
    20_000
}
fn default_realisations() -> u64 {
    100
}
fn default_force_points() -> usize {
    30
}
fn default_cutoff_ratio() -> f64 {
    0.5
}
fn default_amplitude_ratio() -> f64 {
    1.0
}
fn default_springs() -> usize {
    20_000
}
fn default_steps_visco() -> usize {
    400
}
fn default_steps() -> usize {
    8
}

impl OutputSpec {
    pub fn kind(&self) -> &'static str {
        match self {
            OutputSpec::Profile1d { .. } => "profile_1d",
            OutputSpec::ForceDepth { .. } => "force_depth",
            OutputSpec::Pressure { .. } => "pressure",
            OutputSpec::Adhesion { .. } => "adhesion",
            OutputSpec::Tangential { .. } => "tangential",
            OutputSpec::Damping { .. } => "damping",
            OutputSpec::Viscoelastic { .. } => "viscoelastic",
            OutputSpec::StaticFriction { .. } => "static_friction",
            OutputSpec::RoughStiffness { .. } => "rough_stiffness",
            OutputSpec::HurstSweep(_) => "hurst_sweep",
            OutputSpec::BemContact { .. } => "bem_contact",
        }
    }

    /// The module that runs this output: the one place that sorts output kinds.
    pub fn executor(&self) -> Executor {
        match self {
            OutputSpec::Profile1d { .. }
            | OutputSpec::ForceDepth { .. }
            | OutputSpec::Pressure { .. }
            | OutputSpec::Adhesion { .. }
            | OutputSpec::Tangential { .. }
            | OutputSpec::Damping { .. }
            | OutputSpec::Viscoelastic { .. } => Executor::Axisymmetric,
            OutputSpec::StaticFriction { .. } | OutputSpec::RoughStiffness { .. } => {
                Executor::RoughLines
            }
            OutputSpec::HurstSweep(_) => Executor::Sweep,
            OutputSpec::BemContact { .. } => Executor::Bem,
        }
    }

    /// Axisymmetric outputs need the scene's `[profile]`; the others do not.
    pub fn needs_profile(&self) -> bool {
        self.executor() == Executor::Axisymmetric
    }
}

/// Which module runs an output (and so which stages it can need).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Executor {
    /// `crate::axisym`: exact MRD of an axisymmetric profile.
    Axisymmetric,
    /// `crate::rough`: MRD rough lines.
    RoughLines,
    /// `crate::sweep`: the Hurst sweep, 3D against 1D.
    Sweep,
    /// `crate::bem`: 3D contact of a height map.
    Bem,
}

/// A parsed and validated scene, with its source text for provenance.
#[derive(Debug, Clone)]
pub struct Scene {
    pub file: SceneFile,
    pub source: String,
    pub origin: String,
    pub material: Material,
    pub profile: Option<Profile>,
    /// Folder of the scene file (None for embedded scenes).
    pub base_dir: Option<std::path::PathBuf>,
}

impl Scene {
    /// Parses TOML text; `base_dir` resolves relative table files (None for embedded).
    pub fn parse(source: &str, origin: &str, base_dir: Option<&Path>) -> Result<Self> {
        let file: SceneFile = toml::from_str(source).map_err(|e| {
            let (line, col) = e
                .span()
                .map(|s| line_col(source, s.start))
                .unwrap_or((0, 0));
            CompareError::Scene(format!(
                "{origin}:{line}:{col}: {}",
                e.message().lines().next().unwrap_or("invalid TOML").trim()
            ))
        })?;
        if file.name.trim().is_empty()
            || !file
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        {
            return Err(CompareError::Scene(format!(
                "{origin}: name `{}` must be non-empty and use only letters, digits, '-' and '_'",
                file.name
            )));
        }
        if file.outputs.is_empty() {
            return Err(CompareError::Scene(format!(
                "{origin}: no [[outputs]] requested: nothing to compute"
            )));
        }
        let material = file.material.build()?;
        let profile = file
            .profile
            .as_ref()
            .map(|p| p.build(base_dir))
            .transpose()?;
        let scene = Self {
            file,
            source: source.to_string(),
            origin: origin.to_string(),
            material,
            profile,
            base_dir: base_dir.map(Path::to_path_buf),
        };
        scene.validate_outputs()?;
        Ok(scene)
    }

    /// Loads a scene from a path.
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(crate::error::io_err(format!(
            "reading scene {}",
            path.display()
        )))?;
        Self::parse(&text, &path.display().to_string(), path.parent())
    }

    pub fn profile(&self) -> Result<&Profile> {
        self.profile.as_ref().ok_or_else(|| {
            CompareError::Scene(format!("{}: this output needs a [profile]", self.origin))
        })
    }

    fn validate_outputs(&self) -> Result<()> {
        let bad = |i: usize, what: &str| {
            Err(CompareError::Scene(format!(
                "{}: outputs[{i}]: {what}",
                self.origin
            )))
        };
        let positive = |x: f64| x.is_finite() && x > 0.0;
        for (i, o) in self.file.outputs.iter().enumerate() {
            if !o.needs_profile() {
                self.validate_rough(i, o)?;
                continue;
            }
            self.profile()?;
            let points = match o {
                OutputSpec::Profile1d { points, .. }
                | OutputSpec::ForceDepth { points, .. }
                | OutputSpec::Pressure { points, .. }
                | OutputSpec::Adhesion { points, .. }
                | OutputSpec::Tangential { points, .. }
                | OutputSpec::Damping { points, .. } => *points,
                OutputSpec::Viscoelastic { steps, .. } => *steps,
                OutputSpec::StaticFriction { .. }
                | OutputSpec::RoughStiffness { .. }
                | OutputSpec::HurstSweep(_)
                | OutputSpec::BemContact { .. } => {
                    unreachable!()
                }
            };
            if !(2..=100_000).contains(&points) {
                return bad(i, "points must lie in 2..=100000");
            }
            match o {
                OutputSpec::Profile1d { r_max, .. } if !positive(*r_max) => {
                    return bad(i, "r_max must be > 0")
                }
                OutputSpec::ForceDepth { max, springs, .. } => {
                    if !positive(*max) {
                        return bad(i, "max must be > 0");
                    }
                    if springs.is_some_and(|n| n < 2) {
                        return bad(i, "springs must be >= 2");
                    }
                }
                OutputSpec::Pressure { depth, .. } if !positive(*depth) => {
                    return bad(i, "depth must be > 0")
                }
                OutputSpec::Adhesion {
                    gamma, depth_max, ..
                } => {
                    if !positive(*gamma) {
                        return bad(i, "gamma (work of adhesion) must be > 0");
                    }
                    if !positive(*depth_max) {
                        return bad(i, "depth_max must be > 0");
                    }
                }
                OutputSpec::Tangential {
                    mu,
                    normal_force,
                    traction_at,
                    ..
                } => {
                    if !positive(*mu) {
                        return bad(i, "friction coefficient mu must be > 0");
                    }
                    if !positive(*normal_force) {
                        return bad(i, "normal_force must be > 0");
                    }
                    if traction_at.iter().any(|f| !(0.0..1.0).contains(f)) {
                        return bad(i, "traction_at fractions of mu F_N must lie in [0, 1)");
                    }
                    self.material.g_star().ctx("tangential output")?;
                }
                OutputSpec::Damping {
                    mu,
                    depth,
                    max_amplitude_ratio,
                    springs,
                    ..
                } => {
                    if !positive(*mu) {
                        return bad(i, "friction coefficient mu must be > 0");
                    }
                    if !positive(*depth) || !positive(*max_amplitude_ratio) {
                        return bad(i, "depth and max_amplitude_ratio must be > 0");
                    }
                    if *springs < 2 {
                        return bad(i, "springs must be >= 2");
                    }
                    self.material.g_star().ctx("damping output")?;
                }
                _ => {}
            }
        }
        Ok(())
    }
}

impl Scene {
    /// Seed recorded in the provenance: the first output that has one.
    pub fn seed(&self) -> Option<u64> {
        self.file.outputs.iter().find_map(|o| match o {
            OutputSpec::HurstSweep(s) => Some(s.seed),
            OutputSpec::StaticFriction { seed, .. } | OutputSpec::RoughStiffness { seed, .. } => {
                Some(*seed)
            }
            _ => None,
        })
    }

    fn validate_rough(&self, i: usize, o: &OutputSpec) -> Result<()> {
        let bad = |what: String| {
            Err(CompareError::Scene(format!(
                "{}: outputs[{i}]: {what}",
                self.origin
            )))
        };
        let pos = |x: f64| x.is_finite() && x > 0.0;
        if let OutputSpec::HurstSweep(spec) = o {
            return spec.validate().or_else(&bad);
        }
        if let OutputSpec::BemContact {
            size,
            punch_radius,
            mean_pressures,
            approaches,
            tolerance,
            max_iterations,
            ..
        } = o
        {
            if !size.iter().all(|v| pos(*v)) {
                return bad("size [lx, ly] must be > 0".into());
            }
            if mean_pressures.is_empty() == approaches.is_empty() {
                return bad(
                    "give exactly one of mean_pressures and approaches (a non-empty list)".into(),
                );
            }
            if mean_pressures
                .iter()
                .chain(approaches)
                .any(|v| !(v.is_finite() && *v >= 0.0))
            {
                return bad("loads must be finite and >= 0".into());
            }
            if punch_radius.is_some_and(|r| !pos(r)) {
                return bad("punch_radius must be > 0".into());
            }
            if !(*tolerance > 0.0 && *tolerance < 1e-2) || *max_iterations == 0 {
                return bad("tolerance must lie in (0, 1e-2) and max_iterations be > 0".into());
            }
            return Ok(());
        }
        let (hurst, points, length, realisations) = match o {
            OutputSpec::StaticFriction {
                hurst,
                points,
                length,
                realisations,
                ..
            }
            | OutputSpec::RoughStiffness {
                hurst,
                points,
                length,
                realisations,
                ..
            } => (*hurst, *points, *length, *realisations),
            _ => unreachable!(),
        };
        if !(-1.0..=3.0).contains(&hurst) {
            return bad(format!("hurst = {hurst} must lie in [-1, 3]"));
        }
        if !(64..=50_000_000).contains(&points) {
            return bad(format!("points = {points} must lie in 64..=5e7"));
        }
        if !pos(length) {
            return bad("length must be > 0".into());
        }
        if realisations == 0 || realisations > 1_000_000 {
            return bad("realisations must lie in 1..=1e6".into());
        }
        match o {
            OutputSpec::StaticFriction {
                rms_height,
                contacts_at_max_force,
                force_min,
                force_max,
                force_points,
                ..
            } => {
                if rms_height.is_some() == contacts_at_max_force.is_some() {
                    return bad("give exactly one of rms_height and contacts_at_max_force".into());
                }
                if rms_height.is_some_and(|h| !pos(h))
                    || contacts_at_max_force.is_some_and(|c| !(c >= 1.0 && c < points as f64))
                {
                    return bad(
                        "rms_height must be > 0; contacts_at_max_force in [1, points)".into(),
                    );
                }
                if !(pos(*force_min) && pos(*force_max) && force_max > force_min)
                    || *force_points < 3
                {
                    return bad("need 0 < force_min < force_max and force_points >= 3".into());
                }
            }
            OutputSpec::RoughStiffness {
                upper_cutoff_ratio,
                f_min,
                f_max,
                f_points,
                lambda,
                ..
            } => {
                if !(*upper_cutoff_ratio > 0.0 && *upper_cutoff_ratio <= 1.0) {
                    return bad("upper_cutoff_ratio must lie in (0, 1]".into());
                }
                if !(pos(*f_min) && pos(*f_max) && f_max > f_min) || *f_points < 3 {
                    return bad("need 0 < f_min < f_max and f_points >= 3".into());
                }
                if let LambdaSpec::Value(v) = lambda {
                    if !pos(*v) {
                        return bad(format!("lambda = {v} must be > 0"));
                    }
                }
                crate::rough::lambda_of(lambda, self.base_dir.as_deref())?
                    .at(hurst)
                    .ctx(format!("outputs[{i}] lambda"))?;
            }
            _ => {}
        }
        Ok(())
    }
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.len() - before.rfind('\n').map_or(0, |p| p + 1) + 1;
    (line, col)
}
