//! `calibrate`: lambda of Eq. (76) for the user's own surface. From a measured height
//! map, an isotropic PSD table or a self-affine spectrum with a roll-off, it presses 3D
//! rough punches whose faces carry that spectrum and MRD lines with C1D = lambda q C2D of
//! the same spectrum, and returns the lambda that makes MRD's stiffness-force curve
//! k(F) match the 3D ensemble's, with its 95 % interval, the misfit left over the force
//! range, the exponents alpha_3D and alpha_MRD (Eq. 77) and both curves. A measured map
//! is also solved itself, in 3D at its full resolution, against MRD lines of its whole
//! spectrum with the calibrated lambda.
//!
//! The set-up is the lambda study's (`lambda_study`), in units of the punch diameter L
//! (the map's side) and E* = 1: a rigid circular punch of diameter L whose face is a
//! nested random-phase surface with the spectrum's C2D on the wave vectors 0 < |k| <= B
//! (units of 2 pi / L; B = `bandwidth`, or the map's Nyquist wavenumber if lower),
//! sampled with `cells` cells per shortest wavelength; the load ladder runs from 1e-3 of
//! the full-contact approach to full contact; k = dF/dd at fixed contact set. MRD lines
//! are nested the same way (C1D = pi q C2D, `points_1d_per_cell` points per 3D cell).
//! Each curve is reduced by its own rms height (f = F/(E* h L)); lambda only rescales the
//! line's heights, so MRD at lambda is K1(f sqrt(pi / l)) with l = lambda times the
//! case's rms factor (`experiment::lambda_meaning`), and l minimises the log-space misfit
//! to the 3D ensemble mean wherever that mean lies in `window` (k/(E* L)). Intervals:
//! 95 % bootstrap over the 3D realisations (200 resamples, on the full sample's points).
//!
//! A measured map's spectrum is itself an estimate: its lowest annuli hold a few lattice
//! points each and carry most of the variance. [`spectrum`] propagates that uncertainty
//! by a parametric bootstrap (surrogate maps of the estimated spectrum, read by the same
//! estimator, each calibrated on the main sample's first punches with the same phases)
//! and reports it beside the punches' interval, and both combined; where the punches'
//! noise hides it, at its upper bound.
//!
//! Realisations: `realisations.min`, then batches of `realisations.batch` (up to
//! `realisations.max`) while lambda's interval is wider than +/- `target`; decisions use
//! complete batches only, so the result does not depend on threads, shards or
//! interruptions (a sharded run computes every realisation up to `max`).
//!
//! Files: [`tasks`] (the source's spectrum, the checkpointed solves), [`analysis`]
//! (curves, lambda, intervals), [`spectrum`] (the spectrum's part of the interval),
//! [`report`] (tables and figures), [`kind`] (the output).

pub mod analysis;
mod kind;
mod psd;
mod report;
pub mod spectrum;
pub mod tasks;

use crate::experiment::tasks::Realisations;
use serde::Deserialize;

/// Parameters of a calibration (an `[[outputs]]` entry of kind `calibrate`).
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Calibrate {
    /// A measured height map (`.npy`, text matrix, ESRI ASCII grid, `.xyz` list),
    /// relative to the scene; heights in the scene's length unit.
    pub topography: Option<String>,
    /// An isotropic PSD table, relative to the scene: two columns q [1/length] and C2D
    /// [length^4] (`#` comments and a header line allowed).
    pub psd: Option<String>,
    /// A self-affine spectrum with a roll-off (C2D flat below q_r = `rolloff` 2 pi / L),
    /// for the verification against the lambda table.
    pub self_affine: Option<SelfAffineSource>,
    /// [lx, ly] [length]: the map's physical size (needed unless the file states its
    /// cell size), or for `psd` the punch diameter L as [L, L].
    pub size: Option<[f64; 2]>,
    /// Bandwidth B = L / lambda_min of the calibration punches (the spectrum is cut
    /// there, or at the map's Nyquist wavenumber if that is lower).
    #[serde(default = "crate::checks::default_count::<32>")]
    pub bandwidth: usize,
    /// Cells per shortest wavelength of the 3D punches.
    #[serde(default = "crate::checks::default_count::<8>")]
    pub cells: usize,
    /// Realisations of the MRD punches: { min, max, batch } (default { min = 16, max = 400,
    /// batch = 16 }): batches while the interval is wider than its target.
    #[serde(default = "realisations")]
    pub realisations: Realisations,
    /// Relative half-width of lambda's 95 % interval at which realisations stop.
    #[serde(default = "ten_percent")]
    pub target: f64,
    /// The calibration range in k/(E* L).
    #[serde(default = "window")]
    pub window: [f64; 2],
    /// Approaches per 3D punch.
    #[serde(default = "crate::checks::default_count::<16>")]
    pub loads: usize,
    /// 3D solver tolerance.
    #[serde(default = "tolerance")]
    pub tolerance: f64,
    /// MRD lines.
    #[serde(default = "crate::checks::default_count_u64::<1000>")]
    pub lines: u64,
    /// MRD points per 3D cell across.
    #[serde(default = "crate::checks::default_count::<16>")]
    pub points_1d_per_cell: usize,
    /// Solve the measured map itself in 3D (a topography only; default true).
    pub solve_map: Option<bool>,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    pub seed: u64,
    /// Amplitude statistics of the 3D punches' faces, the surface being calibrated for:
    /// "fixed" (default: each mode's |H(q)| as Eq. 71 writes it, random phase: the
    /// shipped lambda table's) or "gaussian" (a Gaussian random field of the same mean
    /// spectrum: Rayleigh-distributed amplitudes). The MRD lines keep the method's own
    /// recipe (Eq. 72, fixed amplitudes) either way; lambda depends on the faces' choice,
    /// so a surface is calibrated with the statistics it has.
    #[serde(default)]
    pub amplitudes: AmplitudeStatistics,
    /// The map's spectrum's own uncertainty in lambda's interval (a topography only):
    /// { resamples, punches } surrogate spectra of the map's estimate, each calibrated on
    /// the main sample's first `punches` punches (the main sample then has at least
    /// that many); default { resamples = 12, punches = 32 } (at most realisations.max);
    /// resamples = 0 leaves it out.
    pub spectrum_uncertainty: Option<SpectrumUncertainty>,
}

/// How the spectrum's sampling uncertainty is propagated to lambda (key
/// `spectrum_uncertainty`).
#[derive(Debug, Clone, Copy, Deserialize, PartialEq, Eq)]
#[serde(deny_unknown_fields)]
pub struct SpectrumUncertainty {
    /// Surrogate spectra, each estimated from its own surrogate map.
    pub resamples: u64,
    /// Punches per surrogate spectrum: the main sample's first ones, with the same
    /// phases (at most `realisations.min`).
    pub punches: u64,
}

/// The amplitude statistics of synthesised faces and lines (key `amplitudes`).
#[derive(Debug, Clone, Copy, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum AmplitudeStatistics {
    #[default]
    Fixed,
    Gaussian,
}

impl AmplitudeStatistics {
    /// The synthesis' choice.
    pub fn synthesis(self) -> mrd::roughness::synthesis::Amplitudes {
        match self {
            Self::Fixed => mrd::roughness::synthesis::Amplitudes::Deterministic,
            Self::Gaussian => mrd::roughness::synthesis::Amplitudes::Gaussian,
        }
    }

    /// How the report names it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Fixed => "fixed (|H(q)| as Eq. 71 writes it, random phases)",
            Self::Gaussian => "Gaussian (Rayleigh amplitudes, random phases)",
        }
    }
}

#[derive(Debug, Clone, Copy, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SelfAffineSource {
    pub hurst: f64,
    /// q_r / q0 (1: no roll-off).
    #[serde(default = "one")]
    pub rolloff: f64,
}

/// The default plan: 16 punches, then 16 at a time up to 400.
fn realisations() -> Realisations {
    Realisations {
        min: 16,
        max: 400,
        batch: 16,
    }
}

fn ten_percent() -> f64 {
    0.10
}
fn window() -> [f64; 2] {
    [0.02, 0.5]
}
fn tolerance() -> f64 {
    1e-8
}
fn one() -> f64 {
    1.0
}

impl Calibrate {
    /// Whether the measured map itself is solved.
    pub fn solves_map(&self) -> bool {
        self.topography.is_some() && self.solve_map.unwrap_or(true)
    }

    /// The punches per surrogate spectrum (0 without them): the main sample's first
    /// ones, which it therefore has.
    pub fn spectrum_punches(&self) -> u64 {
        self.spectrum_resamples().map_or(0, |u| u.punches)
    }

    /// The spectrum's resamples and punches per resample; None without a map or with
    /// resamples = 0.
    pub fn spectrum_resamples(&self) -> Option<SpectrumUncertainty> {
        self.topography.as_ref()?;
        // The default's punches stay within the plan's realisations.
        let u = self.spectrum_uncertainty.unwrap_or(SpectrumUncertainty {
            resamples: 12,
            punches: 32.min(self.realisations.max),
        });
        (u.resamples > 0).then_some(u)
    }
}
