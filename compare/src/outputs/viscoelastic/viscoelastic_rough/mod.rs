//! `viscoelastic_rough`: Section 8 says MRD springs with the time-dependent modulus of
//! Eq. (63) reproduce a viscoelastic contact, and (Radok) that "at the given indentation
//! depth, the configurations of an elastic and of a viscous medium are strictly
//! identical ... only during the indentation phase". This output puts it next to 3D:
//! the rough punch of the Hurst sweep (a rigid disc of diameter L with a self-affine
//! face, modes |k| <= `bandwidth` in units of 2 pi / L, on the free half-space) pressed
//! into a generalised-Maxwell half-space, E*(t) = E_inf + sum_k E_k exp(-t / tau_k),
//! under a force history: a ramp to f = F / (E_inf h L) over `ramp`, a hold, an unload
//! to `unload` of that force over `ramp`, a reload over `ramp` (or the same history of
//! the approach d / h, `approach` instead of `force`). Against it MRD lines of
//! length L (C1D = lambda q C2D, Eq. 76) on springs E*(t) dx that separate at zero force
//! (Eq. 63; Ting's problem in 1D).
//!
//! Each side is also solved elastically at the same approach: Radok's prediction is that
//! while the contact does not recede the contact set is the elastic one at the current
//! approach (whatever the modulus), so area / elastic area = 1 through ramp and hold
//! (under a held force the approach creeps and the area grows with it); on unloading the
//! material lags behind the withdrawing punch and the contact is smaller than the
//! elastic one at the same approach. Reported per step: approach / h and contact fraction (3D: cells of the
//! face; MRD: springs), mean over realisations with a 95 % interval (3D), and the ratio
//! to the elastic contact fraction; per phase the largest deviation from Radok on each
//! side and the MRD / 3D approach ratio.
//!
//! Radok's correspondence also fixes the force: while the contact does not recede the
//! displacement field is the elastic one at the current approach, so the force is the
//! hereditary integral of the elastic force at the same approach,
//! F(t) = Int E*(t - t') / E_inf dF_el(t') (Eq. 63 for one spring; [`radok`]). Each side
//! is checked against it at every step, under either control.

mod kind;
mod radok;
mod report;
mod runs;

use crate::error::{Context as _, Result};
use crate::experiment::lambda::LambdaSpec;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModulusSpec {
    /// E_inf, the relaxed contact modulus (> 0: the forces are in its units).
    pub relaxed: f64,
    /// [E_k, tau_k] pairs.
    pub terms: Vec<[f64; 2]>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViscoelasticRough {
    /// Hurst exponent H of the self-affine spectrum, in [0, 1].
    hurst: f64,
    /// Roughness modes |k| <= bandwidth (units of 2 pi / L).
    bandwidth: usize,
    /// Cells per shortest wavelength: the 3D grid is bandwidth x cells a side.
    #[serde(default = "crate::checks::default_count::<8>")]
    cells: usize,
    /// Rough surfaces solved in 3D (independent realisations of the spectrum).
    realisations_3d: u64,
    /// MRD rough lines (independent realisations, C1D = lambda q C2D) behind each MRD
    /// curve.
    realisations_1d: u64,
    /// MRD springs per 3D cell across.
    #[serde(default = "crate::checks::default_count::<16>")]
    points_1d_per_cell: usize,
    /// lambda of Eq. 76, one MRD curve per entry: a number, "pi" (Eq. 73), "cut",
    /// "calibrated" (the shipped lambda(H) table) or a CSV table's path; default ["pi"].
    #[serde(default = "crate::experiment::lambda::default_lambdas")]
    lambda: Vec<LambdaSpec>,
    /// The contact modulus E_inf + sum_k E_k exp(-t / tau_k): { relaxed = E_inf, terms =
    /// [[E_k, tau_k], ...] }.
    modulus: ModulusSpec,
    /// f = F / (E_inf h L) at the end of the ramp (force control).
    force: Option<f64>,
    /// d / h at the end of the ramp (approach control; d from the first contact).
    approach: Option<f64>,
    /// Duration of the ramp, of the unload and of the reload.
    ramp: f64,
    /// Duration of the hold.
    hold: f64,
    /// The unload goes down to this fraction of the force.
    unload: f64,
    /// Time steps per ramp.
    steps: usize,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "crate::checks::default_tolerance")]
    tolerance: f64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
}

/// The four phases of the history, in order.
pub const PHASES: [&str; 4] = ["ramp", "hold", "unload", "reload"];

impl ViscoelasticRough {
    fn grid(&self) -> usize {
        self.bandwidth * self.cells
    }

    /// Whether the history prescribes the approach (else the force).
    fn by_approach(&self) -> bool {
        self.approach.is_some()
    }

    /// The prescribed value at the end of the ramp: f, or d / h.
    fn target(&self) -> f64 {
        self.approach.or(self.force).unwrap_or(f64::NAN)
    }

    fn dt(&self) -> f64 {
        self.ramp / self.steps as f64
    }

    fn hold_steps(&self) -> usize {
        (self.hold / self.dt()).round().max(1.0) as usize
    }

    /// (dt, the prescribed f or d / h at the step's end) for every step.
    fn history(&self) -> Vec<(f64, f64)> {
        let (dt, n, f) = (self.dt(), self.steps, self.target());
        let lerp = |a: f64, b: f64, k: usize| a + (b - a) * k as f64 / n as f64;
        let mut out: Vec<(f64, f64)> = (1..=n).map(|k| (dt, lerp(0.0, f, k))).collect();
        out.extend((0..self.hold_steps()).map(|_| (dt, f)));
        out.extend((1..=n).map(|k| (dt, lerp(f, self.unload * f, k))));
        out.extend((1..=n).map(|k| (dt, lerp(self.unload * f, f, k))));
        out
    }

    /// Phase index of each step of [`Self::history`].
    fn phases(&self) -> Vec<usize> {
        let n = self.steps;
        let mut p = vec![0; n];
        p.extend(vec![1; self.hold_steps()]);
        p.extend(vec![2; n]);
        p.extend(vec![3; n]);
        p
    }

    fn relaxation(&self) -> Result<bem3d::viscoelastic::Relaxation> {
        let terms = self.modulus.terms.iter().map(|t| (t[0], t[1])).collect();
        bem3d::viscoelastic::Relaxation::new(self.modulus.relaxed, terms)
            .map_err(|e| crate::error::CompareError::Scene(format!("modulus: {e}")))
    }

    fn prony(&self) -> Result<mrd::viscoelastic::Prony> {
        let terms = self.modulus.terms.iter().map(|t| (t[0], t[1])).collect();
        mrd::viscoelastic::Prony::new(self.modulus.relaxed, terms).ctx("modulus")
    }
}

/// The largest `steps` of the ramp.
const MAX_STEPS: u64 = 100_000;
