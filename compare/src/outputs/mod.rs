//! Output kinds: one file (or folder) per kind, each implementing [`Output`]. This file
//! holds the trait, what a running output may use ([`Env`]), and the registry
//! ([`KINDS`]): the one place that lists the kinds. Adding a kind is a new file here
//! plus one line in [`KINDS`].
//!
//! The life of an output: the scene parser looks its `kind` up in [`KINDS`] and
//! deserialises the rest of its `[[outputs]]` table into the kind's struct (unknown keys
//! are errors); [`Output::validate`] checks it against the scene's [`Context`];
//! [`Output::stages`] declares what it will run; [`Output::run`] computes those stages
//! (each through [`Section::stage`], which records it) and fills its [`Section`] with
//! named tables, figures and results.

use crate::context::Context;
use crate::error::{CompareError, Result};
use crate::plan::Stage;
use crate::report::Section;
use serde::de::DeserializeOwned;
use std::path::Path;

mod adhesion;
mod axisym;
mod bem_contact;
mod contact_area;
mod damping;
mod elastomer;
mod force_depth;
pub mod hurst_sweep;
pub mod lambda_meaning;
pub mod lambda_study;
mod pressure;
mod profile_1d;
mod rough_sphere;
pub mod rough_stiffness;
mod sliding_friction;
mod sliding_friction_3d;
mod static_friction;
mod static_friction_3d;
mod tangential;
mod tangential_viscoelastic;
mod viscoelastic;
mod viscoelastic_rough;

/// One requested output.
pub trait Output: std::fmt::Debug + Send + Sync {
    /// Checks the request against the scene before anything runs (ranges, material
    /// constants, files); messages name the key and its valid range.
    fn validate(&self, ctx: &Context) -> Result<()>;
    /// The stages [`Self::run`] will execute, in order.
    fn stages(&self, ctx: &Context) -> Vec<Stage>;
    /// Computes the declared stages and fills `out`.
    fn run(&self, env: &Env, out: &mut Section) -> Result<()>;
    /// The random seed, if the output draws random surfaces.
    fn seed(&self) -> Option<u64> {
        None
    }
    /// Outputs whose work is split into checkpointed tasks (resumable, shardable).
    fn checkpointed(&self) -> Option<&dyn Checkpointed> {
        None
    }
}

/// Work split into tasks, each saved to its own checkpoint file when done.
/// A checkpoint folder's name from the text of the parameters its tasks depend on:
/// FNV-1a, 16 hex digits.
pub(crate) fn checkpoint_key(text: &str) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

pub trait Checkpointed {
    /// A hash of the output's parameters: its checkpoints live in `<work root>/<key>/`.
    fn key(&self) -> String;
    /// The checkpoint file names of all tasks, in their fixed global order (shard K of N
    /// computes every N-th from K).
    fn task_files(&self) -> Vec<String>;
    /// Computes the missing tasks (of the shard in `control`) into `dir`.
    fn compute(&self, dir: &Path, control: &RunControl) -> Result<()>;
}

/// How a run divides and limits its work.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunControl {
    /// (K, N): compute only tasks with index % N == K.
    pub shard: Option<(usize, usize)>,
    /// Stop (with [`CompareError::Stopped`]) after computing this many new tasks
    /// (tests of interruption and resume).
    pub stop_after: Option<usize>,
    /// Show progress bars on long work.
    pub progress: bool,
    /// Compute nothing: outputs that can report what their checkpoints hold do so.
    pub report_only: bool,
}

/// What a running output may use.
pub struct Env<'a> {
    pub ctx: &'a Context,
    /// Checkpoints of resumable outputs go to `work_root/<key>/`.
    pub work_root: &'a Path,
    pub control: &'a RunControl,
}

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
    Kind::of::<profile_1d::Profile1d>(
        "profile_1d",
        "the 3D profile z(r) and its MRD image z1d(x) (Eq. 11)",
    ),
    Kind::of::<force_depth::ForceDepth>(
        "force_depth",
        "force, contact radius and stiffness against depth (Eqs. 20, 24, 25)",
    ),
    Kind::of::<pressure::Pressure>("pressure", "pressure p(r) by the Abel transform (Eq. 26)"),
    Kind::of::<adhesion::Adhesion>(
        "adhesion",
        "adhesive loading-unloading and pull-off (Eqs. 33-37)",
    ),
    Kind::of::<tangential::Tangential>(
        "tangential",
        "Cattaneo-Mindlin tangential loading and tractions (Eqs. 41-51)",
    ),
    Kind::of::<damping::Damping>(
        "damping",
        "energy dissipated per cycle of an oscillating contact (Section 7)",
    ),
    Kind::of::<viscoelastic::Viscoelastic>(
        "viscoelastic",
        "viscoelastic ramp-and-hold indentation against Radok (Eq. 63)",
    ),
    Kind::of::<static_friction::StaticFriction>(
        "static_friction",
        "static friction from the mean slope in contact (Section 10.2, Fig. 9)",
    ),
    Kind::of::<static_friction_3d::StaticFriction3d>(
        "static_friction_3d",
        "the mean slope in contact in 3D against MRD, Eq. (93) (Section 10.2)",
    ),
    Kind::of::<rough_stiffness::RoughStiffness>(
        "rough_stiffness",
        "ensemble stiffness-force law of MRD rough lines (Eq. 77)",
    ),
    Kind::of::<sliding_friction::SlidingFriction>(
        "sliding_friction",
        "elastomer friction mu(v) of rough lines on viscoelastic springs, Eq. 82 (Fig. 7)",
    ),
    Kind::of::<sliding_friction_3d::SlidingFriction3d>(
        "sliding_friction_3d",
        "steady viscoelastic sliding of rough surfaces in 3D against MRD and Eq. 82 (Fig. 7 in 3D)",
    ),
    Kind::of::<bem_contact::BemContact>(
        "bem_contact",
        "3D boundary-element contact of a height map from a file (.npy, text matrix, ESRI ASCII grid, .xyz point list)",
    ),
    Kind::of::<contact_area::ContactArea>(
        "contact_area",
        "real contact area and mean gap against force, 3D against MRD (Section 11)",
    ),
    Kind::of::<rough_sphere::RoughSphere>(
        "rough_sphere",
        "a sphere with self-affine roughness, 3D against MRD (Hess + Eq. 76), smooth to rough (Section 9)",
    ),
    Kind::of::<tangential_viscoelastic::TangentialViscoelastic>(
        "tangential_viscoelastic",
        "Cattaneo-Mindlin on viscoelastic tangential springs: ramp, hold, cycle, stick zone and energy (Eqs. 64-65)",
    ),
    Kind::of::<viscoelastic_rough::ViscoelasticRough>(
        "viscoelastic_rough",
        "a rough punch on a viscoelastic half-space through ramp, hold, unload and reload, 3D against MRD springs (Eq. 63, Section 8)",
    ),
    Kind::of::<hurst_sweep::HurstSweep>(
        "hurst_sweep",
        "the Hurst sweep, 3D against MRD: alpha(H), zeta(H), lambda(H) (Fig. 6)",
    ),
    Kind::of::<lambda_study::LambdaStudy>(
        "lambda_study",
        "lambda(H) and alpha(H) converged in bandwidth, resolution and realisations (calibration of Eq. 76)",
    ),
];

/// The registered kind called `name`.
pub fn kind(name: &str) -> Option<&'static Kind> {
    KINDS.iter().find(|k| k.name == name)
}

/// A scene error (the caller adds which output it is).
pub(crate) fn bad<T>(what: impl Into<String>) -> Result<T> {
    Err(CompareError::Scene(what.into()))
}

pub(crate) fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

/// A count key (`realisations`, `loads`, `f_points`, ...) within `range`: the bounds keep
/// a run's size (tasks, table rows) within what a machine can hold and finish.
pub(crate) fn count_in(key: &str, value: u64, range: std::ops::RangeInclusive<u64>) -> Result<()> {
    if range.contains(&value) {
        Ok(())
    } else {
        bad(format!(
            "{key} = {value} must lie in {}..={}",
            range.start(),
            range.end()
        ))
    }
}

/// A 3D solver tolerance from a scene: the solver's own range and message
/// ([`bem3d::SolverOptions::validate`]).
pub(crate) fn check_tolerance(tolerance: f64) -> Result<()> {
    bem3d::SolverOptions::new(tolerance, 1)
        .validate()
        .or_else(|e| bad(e.to_string()))
}

/// The 3D and MRD ensemble sizes of a comparison: at least 2 each, for intervals.
pub(crate) fn check_ensembles(realisations_3d: u64, realisations_1d: u64) -> Result<()> {
    count_in("realisations_3d", realisations_3d, 2..=MAX_REALISATIONS)?;
    count_in("realisations_1d", realisations_1d, 2..=MAX_REALISATIONS)
}

/// Most realisations any output computes (tasks are listed before they run).
pub(crate) const MAX_REALISATIONS: u64 = 100_000;
/// Most load points of a force-controlled curve.
pub(crate) const MAX_LOADS: u64 = 10_000;

/// The half-length of a spring row: `given` if it covers the largest contact radius
/// `a_max` the output reaches (springs beyond the row cannot touch), else an error
/// naming both; without it `default_factor x a_max`.
pub(crate) fn row_half_length(given: Option<f64>, a_max: f64, default_factor: f64) -> Result<f64> {
    match given {
        None if positive(default_factor * a_max) => Ok(default_factor * a_max),
        None => bad(format!(
            "springs: the largest contact radius is {a_max:e}, so the default half_length ({default_factor} x it) is unusable; give half_length > 0 or a larger max"
        )),
        Some(l) if positive(l) && l > a_max => Ok(l),
        Some(l) => bad(format!(
            "half_length = {l:e} does not cover the largest contact radius this output reaches, {a_max:e}: give half_length > {a_max:e}, or leave it out ({default_factor} x that radius)"
        )),
    }
}

/// `points` of an axisymmetric output.
pub(crate) fn check_points(points: usize) -> Result<()> {
    if !(2..=100_000).contains(&points) {
        return bad(format!("points = {points} must lie in 2..=100000"));
    }
    Ok(())
}

/// Peak bytes per spring of the 1D outputs, for their memory checks: the growth of the
/// peak resident memory of `mrdw run` per spring, raised by about a quarter (measured
/// between 1e6 and 2e6 springs on one thread: force_depth 22, adhesion 196, damping 14,
/// viscoelastic with one Prony term 22, tangential_viscoelastic with one 56, a rough line
/// 60; per further term 8 and 8.3, per further thread 36-37 bytes, between 1e3 and
/// 2e6-4e6 springs; `spring_memory_estimates_hold` in tests/suite/robustness.rs measures
/// the one-term, one-thread figures again). Per grid cell of the 3D solvers:
/// [`bem3d::operator::BYTES_PER_CELL_PERIODIC`] and
/// [`bem3d::operator::BYTES_PER_CELL_NON_PERIODIC`].
pub mod spring_bytes {
    pub const FORCE_DEPTH: f64 = 30.0;
    pub const ADHESION: f64 = 250.0;
    pub const DAMPING: f64 = 18.0;
    pub fn viscoelastic(terms: usize) -> f64 {
        18.0 + 10.0 * terms as f64
    }
    pub fn tangential_viscoelastic(terms: usize) -> f64 {
        56.0 + 11.0 * terms as f64
    }
    /// A rough line's point, with one line per worker thread at a time.
    pub fn rough_line(threads: usize) -> f64 {
        55.0 + 45.0 * threads as f64
    }
}
pub(crate) use bem3d::operator::{BYTES_PER_CELL_NON_PERIODIC, BYTES_PER_CELL_PERIODIC};

/// Refuses work whose memory estimate exceeds what this process may allocate
/// ([`sysmem::check_estimate`]: free memory, rlimits, cgroup).
pub fn check_memory(bytes: f64, what: &str) -> Result<()> {
    sysmem::check_estimate(bytes, what).map_err(CompareError::from)
}

/// A spring count: at least 2, and within memory at `bytes` per spring
/// ([`spring_bytes`]).
pub(crate) fn check_springs(springs: usize, bytes: f64) -> Result<()> {
    if springs < 2 {
        return bad(format!("springs = {springs} must be >= 2"));
    }
    check_memory(springs as f64 * bytes, &format!("springs = {springs}"))
}

pub(crate) fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

pub(crate) fn default_points() -> usize {
    60
}
pub(crate) fn default_springs() -> usize {
    20_000
}
pub(crate) fn default_realisations() -> u64 {
    100
}
/// lambda = pi alone, the default of the kinds that take a list of lambdas.
pub(crate) fn default_lambdas() -> Vec<rough_stiffness::LambdaSpec> {
    vec![rough_stiffness::LambdaSpec::default()]
}
/// The 3D solver tolerance of the comparison kinds.
pub(crate) fn default_tolerance() -> f64 {
    1e-8
}
pub(crate) fn default_force_points() -> usize {
    30
}
