//! The MRD side of the sliding-friction outputs (Section 10.1): the rigid rough line
//! ([`LineSpec`]: a band-limited or self-affine spectrum with C1D = pi q C2D, or a
//! sinusoid), the settings of an ensemble of steady-state slides on the viscoelastic
//! foundation ([`MrdSliding`]), its runs per velocity ([`AtVelocity`]) and the check
//! that the two routes to mu agree ([`routes_rel_diff`]). `sliding_friction` reports
//! them alone; `sliding_friction_3d` runs them beside its 3D answer.

use super::elastomer::{self, Material};
use crate::checks::{bad, positive, require_positive};
use crate::error::{Context as _, Result};
use crate::plan::Stage;
use crate::report::Section;
use mrd::rheology::Prony;
use mrd::roughness::synthesis::{line_from, Amplitudes};
use mrd::sliding::{slide, Line, Sliding, SlidingResult};
use rand::RngExt;
use rayon::prelude::*;

/// The MRD lines' steady state, unless the scene says otherwise: mu and the mean
/// approach change by less than this between passes.
pub(crate) fn default_line_tolerance() -> f64 {
    1e-4
}

/// Passes over a line at most before its steady state counts as not reached.
pub(crate) fn default_max_passes() -> usize {
    400
}

/// A velocity is resolved where the two routes to mu agree within this, relatively.
pub(crate) fn default_error_limit() -> f64 {
    0.1
}
use serde::Deserialize;
use std::f64::consts::{PI, TAU};

/// The rigid line.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub(crate) enum LineSpec {
    /// Flat C2D for q in [k/band, k band] (non-fractal), `waves` = k L / (2 pi).
    Band { waves: f64, band: f64 },
    /// Self-affine C2D ~ q^(-2H-2) for q from `min_waves` 2 pi / L (default 1) to
    /// `waves` 2 pi / L.
    SelfAffine {
        hurst: f64,
        waves: f64,
        #[serde(default = "one_f")]
        min_waves: f64,
    },
    /// h0 cos(k x + phase), `waves` whole waves over L.
    Sinusoid { waves: usize },
}

impl LineSpec {
    /// The isotropic 2D spectrum C2D(q) of a surface of size `l` (up to a factor), whose
    /// MRD line has C1D = pi q C2D (Eq. 76 with lambda = pi); None for the sinusoid.
    pub(crate) fn c2d(&self, l: f64) -> Option<Box<dyn Fn(f64) -> f64 + Send + Sync>> {
        match *self {
            LineSpec::Band { waves, band } => {
                let k = TAU * waves / l;
                let (lo, hi) = (k / band, k * band);
                Some(Box::new(
                    move |q| if (lo..=hi).contains(&q) { 1.0 } else { 0.0 },
                ))
            }
            LineSpec::SelfAffine {
                hurst,
                waves,
                min_waves,
            } => {
                let (q0, q1) = (TAU * min_waves / l, TAU * waves / l);
                Some(Box::new(move |q| {
                    if (q0..=q1).contains(&q) {
                        q.powf(-2.0 * hurst - 2.0)
                    } else {
                        0.0
                    }
                }))
            }
            LineSpec::Sinusoid { .. } => None,
        }
    }

    /// The lowest and highest wavenumber q of the spectrum on a line of length `l`.
    pub(crate) fn q_range(&self, l: f64) -> (f64, f64) {
        let q = |waves: f64| TAU * waves / l;
        match *self {
            LineSpec::Band { waves, band } => (q(waves / band), q(waves * band)),
            LineSpec::SelfAffine {
                waves, min_waves, ..
            } => (q(min_waves), q(waves)),
            LineSpec::Sinusoid { waves } => (q(waves as f64), q(waves as f64)),
        }
    }

    /// The highest wave number (waves over L) of the spectrum.
    pub(crate) fn max_waves(&self) -> f64 {
        match *self {
            LineSpec::Band { waves, band } => waves * band,
            LineSpec::SelfAffine { waves, .. } => waves,
            LineSpec::Sinusoid { waves } => waves as f64,
        }
    }

    /// `key`: the scene key, named in messages.
    pub(crate) fn validate(&self, key: &str) -> Result<()> {
        match *self {
            LineSpec::Band { waves, band } => {
                if !(positive(waves) && band > 1.0 && band.is_finite()) {
                    return bad(format!("{key}: waves must be > 0 and band > 1"));
                }
            }
            LineSpec::SelfAffine {
                hurst,
                waves,
                min_waves,
            } => {
                let ok = (-1.0..=3.0).contains(&hurst)
                    && min_waves >= 1.0
                    && waves >= 2.0 * min_waves
                    && waves.is_finite();
                if !ok {
                    return bad(format!(
                        "{key}: hurst must lie in [-1, 3], min_waves >= 1 and waves >= 2 min_waves"
                    ));
                }
            }
            LineSpec::Sinusoid { waves } => {
                if waves == 0 {
                    return bad(format!("{key}: waves must be >= 1"));
                }
            }
        }
        Ok(())
    }
}

fn one_f() -> f64 {
    1.0
}

/// An ensemble of steady-state slides of rough lines on the MRD foundation: the scene
/// keys of `sliding_friction` (its docs give their meaning) but the error limit.
#[derive(Debug, Clone)]
pub(crate) struct MrdSliding {
    pub material: Material,
    pub line: LineSpec,
    /// Line length L and rms height h (length units).
    pub length: f64,
    pub rms_height: f64,
    /// Springs along L, line points per spring, line points moved per time step.
    pub springs: usize,
    pub refine: usize,
    pub stride: usize,
    /// Normal force as F / (4 G(inf) h L) (Eq. 77).
    pub reduced_force: f64,
    /// `velocities` values log-spaced from `velocity_min` to `velocity_max`.
    pub velocity_min: f64,
    pub velocity_max: f64,
    pub velocities: usize,
    pub realisations: u64,
    pub seed: u64,
    /// Steady state: mu and the mean approach change by less than this between passes.
    pub tolerance: f64,
    pub max_passes: usize,
}

impl MrdSliding {
    /// The settings' checks, naming the scene keys.
    pub(crate) fn validate(&self) -> Result<()> {
        let shear = self.material.validate()?;
        self.line.validate("line")?;
        require_positive("length", self.length)?;
        require_positive("rms_height", self.rms_height)?;
        if !(16..=1 << 20).contains(&self.springs) || self.refine == 0 || self.stride == 0 {
            return bad("springs must lie in 16..=1048576, refine and stride >= 1");
        }
        if !self.points().is_multiple_of(self.stride) {
            return bad(format!(
                "stride = {} must divide springs x refine = {}",
                self.stride,
                self.points()
            ));
        }
        if self.points() > 1 << 22 {
            return bad("springs x refine must be <= 4194304");
        }
        crate::checks::check_memory_per_thread(
            self.springs as f64 * (shear.terms.len() as f64 + 4.0) * 16.0,
            &format!("springs = {}", self.springs),
        )?;
        require_positive("reduced_force", self.reduced_force)?;
        elastomer::velocities(
            self.velocity_min,
            self.velocity_max,
            self.velocities,
            &shear,
            self.line.q_range(self.length),
        )?;
        if !(2..=10_000).contains(&self.realisations) {
            return bad("realisations must lie in 2..=10000 (for intervals)");
        }
        if !(self.tolerance > 0.0 && self.tolerance < 0.1) || self.max_passes < 2 {
            return bad("tolerance must lie in (0, 0.1) and max_passes be >= 2");
        }
        Ok(())
    }
}

/// Runs of one velocity, over the lines.
pub(crate) struct AtVelocity {
    pub velocity: f64,
    pub runs: Vec<SlidingResult>,
}

impl MrdSliding {
    pub(crate) fn points(&self) -> usize {
        self.springs * self.refine
    }

    pub(crate) fn velocity_grid(&self) -> Vec<f64> {
        mrd::friction::log_space(self.velocity_min, self.velocity_max, self.velocities)
    }

    /// Line `r`, scaled to the rms height.
    pub(crate) fn line(&self, r: u64) -> mrd::Result<Line> {
        let (n, l) = (self.points(), self.length);
        let z = if let LineSpec::Sinusoid { waves } = self.line {
            let phase =
                TAU * mrd::roughness::synthesis::realisation_rng(self.seed, r).random::<f64>();
            (0..n)
                .map(|i| (TAU * waves as f64 * i as f64 / n as f64 + phase).cos())
                .collect()
        } else {
            let c2d = self.line.c2d(l);
            line_from(
                &|q: f64| PI * q * c2d.as_ref().map_or(0.0, |c| c(q)),
                n,
                l,
                self.seed,
                r,
                Amplitudes::Deterministic,
            )?
        };
        let h = Line::new(&z, l)?.rms_height;
        let z: Vec<f64> = z.iter().map(|v| v * self.rms_height / h).collect();
        Line::new(&z, l)
    }

    pub(crate) fn setup(&self, shear: &Prony, velocity: f64) -> Sliding {
        let f = self.reduced_force * 4.0 * shear.relaxed * self.rms_height * self.length;
        Sliding {
            modulus: shear.scaled(4.0),
            springs: self.springs,
            stride: self.stride,
            normal_force: f,
            velocity,
            tolerance: self.tolerance,
            max_passes: self.max_passes,
            accelerate: true,
        }
    }
}

impl MrdSliding {
    /// The lines and every (velocity, line) run, stages recorded in `out`.
    pub(crate) fn simulate(&self, out: &mut Section) -> Result<(Vec<Line>, Vec<AtVelocity>)> {
        let shear = self.material.shear().ctx("material")?;
        let lines: Vec<Line> = out
            .stage(Stage::RoughSynthesis, || {
                (0..self.realisations)
                    .map(|r| self.line(r))
                    .collect::<mrd::Result<_>>()
            })
            .ctx("lines")?;
        let vs = self.velocity_grid();
        let jobs: Vec<(usize, usize)> = (0..vs.len())
            .flat_map(|i| (0..lines.len()).map(move |r| (i, r)))
            .collect();
        let runs: Vec<SlidingResult> = out
            .stage(Stage::ViscoelasticSliding, || {
                jobs.par_iter()
                    .with_max_len(1)
                    .map(|&(i, r)| slide(&lines[r], &self.setup(&shear, vs[i])))
                    .collect::<mrd::Result<_>>()
            })
            .ctx("sliding")?;
        let per_v: Vec<AtVelocity> = vs
            .iter()
            .enumerate()
            .map(|(i, &velocity)| AtVelocity {
                velocity,
                runs: runs[i * lines.len()..(i + 1) * lines.len()].to_vec(),
            })
            .collect();
        Ok((lines, per_v))
    }
}

/// Largest |mu - mu_energy| / |mu| over the runs of one velocity: how far the friction
/// force and the dissipated energy per unit distance, equal in the continuum, differ
/// on these springs (NaN counts as unresolved).
pub(crate) fn routes_rel_diff(runs: &[SlidingResult]) -> f64 {
    runs.iter()
        .map(|x| ((x.mu - x.mu_energy) / x.mu).abs())
        .fold(0.0, |a: f64, d| {
            if d.is_nan() || a.is_nan() {
                f64::NAN
            } else {
                a.max(d)
            }
        })
}
