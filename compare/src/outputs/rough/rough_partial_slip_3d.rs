//! `rough_partial_slip_3d`: MRD's tangential mapping on rough contacts, against 3D
//! partial slip.
//!
//! In MRD a spring of indentation w sticks while G* u < mu E* w, so a contact at the
//! approach d loaded by the shift u carries Q(u) = mu [F_N(d) - F_N(d - G* u / (mu E*))]:
//! the tangential curve is the normal one, shifted (the principle of Ciavarella and
//! Jaeger, exact for every profile in MRD because the springs are independent); under an
//! oscillating force, Masing's rule gives the energy per cycle of amplitude Q* from it,
//! W = 4 [Q* u(Q*) - 2 int_0^Q* u(Q) dQ] (Section 7). This output applies that mapping to
//! the 3D normal curve of each rough surface and puts it next to 3D partial slip under
//! Coulomb's law with Cerruti's operator on the same surface, so what is compared is
//! MRD's tangential law alone (its normal curve, lambda's subject, is the study's input
//! here):
//!
//! - the surfaces: periodic self-affine patches ([`crate::experiment::periodic`]) pressed
//!   to the mean pressure `pressure` x E* h'; the mapped shift at each force Q is
//!   mu (d - d') E* / G* with d' the approach of a 3D normal solve at F_N - Q / mu;
//! - 3D: [`bem3d::tangential::PartialSlip`] under the held pressure, the force ramped
//!   through `fractions` of mu F_N (the shift from the mean surface displacement, as the
//!   approach), and cycles of each amplitude ([`bem3d::tangential::PartialSlip::cycle`]).
//!
//! At nu = 0 Cerruti's operator is the normal one (G* = E*), the mapping is exact on the
//! grid too, and the two sides agree to the solvers' tolerance: a check of both. For
//! nu > 0 the traction is held along x (q_y = 0; 0.6-2.6 % softer than the full tensor at
//! nu = 0.5, `tangential_stiffness_3d`).

use crate::checks::{bad, cell_bytes, check_tolerance, count_in, positive, MIN_CONTACT_CELLS};
use crate::context::Context;
use crate::error::{Context as _, Result};
use crate::experiment::periodic::{Ensemble, Ladder};
use crate::experiment::tangential_map::{e_over_g, Mapping, NODES};
use crate::output::{Env, Output};
use crate::plan::Stage;
use crate::report::{Figure, Section, Series, Style, Table};
use bem3d::tangential::{CerrutiPeriodic, PartialSlip};
use bem3d::Load;
use mrd::rough_contact::Stat;
use serde::Deserialize;

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoughPartialSlip3d {
    /// Hurst exponents, each in [0, 1].
    hurst: Vec<f64>,
    /// Poisson's ratios of the substrate, each in [0, 0.5] (0: the exact check).
    poisson: Vec<f64>,
    /// Shortest wavelength L / bandwidth; the period L is 1.
    bandwidth: usize,
    /// Cells per shortest wavelength, coarse to fine (a refinement ladder of the same
    /// surfaces).
    cells: Vec<usize>,
    /// Mean pressure over E* h' (h' the rms slope).
    pressure: f64,
    /// Coulomb friction coefficient.
    mu: f64,
    /// Tangential forces of the monotonic loading over mu F_N, increasing, in [1e-6, 1).
    fractions: Vec<f64>,
    /// Force amplitudes of the cycles over mu F_N, in [1e-6, 1).
    amplitudes: Vec<f64>,
    /// Force steps per half cycle.
    #[serde(default = "crate::checks::default_count::<10>")]
    steps: usize,
    /// Rough surfaces per Hurst exponent.
    realisations: u64,
    /// Relative convergence criterion of the 3D solves.
    #[serde(default = "crate::checks::default_tolerance")]
    tolerance: f64,
    /// Seed of the random surfaces and lines: the same seed gives the same realisations
    /// whatever the thread count.
    #[serde(default)]
    seed: u64,
}

/// One realisation: the normal force and stiffness, and per Poisson's ratio the 3D and
/// mapped shifts at the fractions and energies per cycle at the amplitudes.
struct Run {
    force: f64,
    kn: f64,
    shift_3d: Vec<Vec<f64>>,
    shift_mrd: Vec<Vec<f64>>,
    energy_3d: Vec<Vec<f64>>,
    energy_mrd: Vec<Vec<f64>>,
}

/// The rows of one ensemble in a table of the study, and what tells it apart in a
/// figure: the colour of its Poisson's ratio (index `k`), the marker and line style of
/// its Hurst exponent (index `i`).
struct EnsembleRows<'t> {
    k: usize,
    nu: f64,
    i: usize,
    h: f64,
    rows: Vec<&'t Vec<f64>>,
}

impl EnsembleRows<'_> {
    /// The 3D means' markers: alternating with the Hurst exponent.
    fn marker(&self) -> Style {
        if self.i.is_multiple_of(2) {
            Style::Markers
        } else {
            Style::Crosses
        }
    }

    /// MRD's lines: alternating with the Hurst exponent.
    fn line(&self) -> Style {
        if self.i.is_multiple_of(2) {
            Style::Line
        } else {
            Style::Dashed
        }
    }
}

/// The stages of a case (3D and MRD), run together on the pool.
const STAGES: &[Stage] = &[
    Stage::RoughSynthesis,
    Stage::Bem3d,
    Stage::Bem3dStiffness,
    Stage::Tangential,
    Stage::Tangential3d,
];

impl Output for RoughPartialSlip3d {
    fn validate(&self, _: &Context) -> Result<()> {
        // Beside the normal solver: a partial-slip state. Measured peaks of one
        // realisation (process included): 208 bytes per cell at 1024^2, 178 at 2048^2.
        self.ladder().check(cell_bytes::ROUGH_PARTIAL_SLIP)?;
        crate::checks::check_fractions("fractions", &self.fractions, true)?;
        crate::experiment::tangential_map::check_amplitudes(&self.amplitudes, self.tolerance)?;
        if !(positive(self.pressure) && self.pressure <= 1.0) {
            return bad(format!(
                "pressure = {} (mean pressure over E* h') must lie in (0, 1]",
                self.pressure
            ));
        }
        if !(positive(self.mu) && self.mu <= 10.0) {
            return bad(format!("mu = {} must lie in (0, 10]", self.mu));
        }
        count_in("steps", self.steps as u64, 2..=1000)?;
        check_tolerance(self.tolerance)?;
        Ok(())
    }

    fn stages(&self, _: &Context) -> Vec<Stage> {
        STAGES.to_vec()
    }

    fn seed(&self) -> Option<u64> {
        Some(self.seed)
    }

    fn run(&self, env: &Env, out: &mut Section) -> Result<()> {
        let e_star = env.ctx.material.e_star;
        let runs = out.stages_together(STAGES, || {
            self.ladder()
                .run(|h, cells, r| self.run_one(h, cells, r, e_star))
        })?;
        self.report(env, out, &runs);
        Ok(())
    }
}

impl RoughPartialSlip3d {
    fn ladder(&self) -> Ladder<'_> {
        Ladder {
            hurst: &self.hurst,
            poisson: &self.poisson,
            bandwidth: self.bandwidth,
            cells: &self.cells,
            realisations: self.realisations,
            seed: self.seed,
        }
    }

    fn run_one(&self, hurst: f64, cells: usize, r: u64, e_star: f64) -> Result<Run> {
        let mut real = self
            .ladder()
            .realise(hurst, cells, r, e_star, self.tolerance)?;
        let force = self.pressure * e_star * real.patch.rms_slope;
        let (sol, kn) = real.normal_at(force, None)?;
        if sol.contact_cells < MIN_CONTACT_CELLS {
            return bad(format!(
                "pressure = {} leaves {} cells in contact on the {}^2 grid (cells = {cells}, H = {hurst}, realisation {r}), fewer than {MIN_CONTACT_CELLS}: a contact of a few cells has no partial slip to measure; raise pressure or cells",
                self.pressure, sol.contact_cells, real.n
            ));
        }
        // b(Q) = mu (d - d'(Q)) at every force the mapping needs (times E* / G* per
        // Poisson's ratio below).
        let mu_fn = self.mu * force;
        let mapping = Mapping::new(mu_fn, &self.fractions, &self.amplitudes, |q| {
            let s = real
                .solver
                .solve(Load::Force(force - q / self.mu), &real.opts, None)
                .ctx("3D normal solve at a reduced force")?;
            Ok(self.mu * (sol.approach - s.approach))
        })?;
        let mut run = Run {
            force,
            kn,
            shift_3d: Vec::new(),
            shift_mrd: Vec::new(),
            energy_3d: Vec::new(),
            energy_mrd: Vec::new(),
        };
        for &nu in &self.poisson {
            let ratio = e_over_g(nu);
            let g = e_star * (1.0 - nu) / 2.0;
            let fresh = || -> bem3d::Result<PartialSlip> {
                PartialSlip::new(
                    CerrutiPeriodic::new(real.n, real.n, 1.0, 1.0, g, nu)?,
                    &sol.pressure,
                    self.mu,
                )
            };
            let mut ps = fresh().ctx("3D partial slip")?;
            let mut shifts = Vec::with_capacity(self.fractions.len());
            for x in &self.fractions {
                let s = ps.load(x * mu_fn, self.tolerance).ctx("3D partial slip")?;
                shifts.push(s.shift);
            }
            let mut energies = Vec::with_capacity(self.amplitudes.len());
            for a in &self.amplitudes {
                let c = fresh()
                    .and_then(|mut ps| ps.cycle(a * mu_fn, self.steps, 2, self.tolerance))
                    .ctx("3D cycle")?;
                energies.push(c.dissipated);
            }
            run.shift_3d.push(shifts);
            run.shift_mrd.push(mapping.shifts(ratio));
            run.energy_3d.push(energies);
            run.energy_mrd.push(mapping.energies(ratio));
        }
        Ok(run)
    }

    fn report(&self, env: &Env, out: &mut Section, runs: &[Ensemble<Run>]) {
        let units = &env.ctx.units;
        let (length, energy) = (units.length.clone(), units.energy());
        let note = format!(
            "periodic self-affine surfaces, period 1, bandwidth {}, grid = cells per shortest wavelength x bandwidth (the same surfaces on each grid), {} realisations, mean pressure {} E* h', mu = {}; 3D: partial slip under the held pressure (Coulomb, Cerruti's operator, q_y = 0); MRD: Q(u) = mu [F_N(d) - F_N(d - G* u / (mu E*))] on each surface's 3D normal curve, Masing's rule for the cycles ({NODES}-point Gauss-Legendre); interval: mean +- 1.96 standard errors over realisations",
            self.bandwidth, self.realisations, self.pressure, self.mu
        );
        let mut curve = Table::new(
            "curve",
            &[
                "hurst [1]".to_string(),
                "poisson [1]".to_string(),
                "grid [cells]".to_string(),
                "force_over_mu_fn [1]".to_string(),
                format!("shift_3d_mean [{length}]"),
                format!("shift_mrd_mean [{length}]"),
                "shift_3d_over_mrd_mean [1]".to_string(),
                "shift_3d_over_mrd_ci95_low [1]".to_string(),
                "shift_3d_over_mrd_ci95_high [1]".to_string(),
            ],
        );
        curve.notes.push(note.clone());
        let mut cycles = Table::new(
            "dissipation",
            &[
                "hurst [1]".to_string(),
                "poisson [1]".to_string(),
                "grid [cells]".to_string(),
                "amplitude_over_mu_fn [1]".to_string(),
                format!("dissipation_3d_mean [{energy}]"),
                format!("dissipation_mrd_mean [{energy}]"),
                "dissipation_3d_over_mrd_mean [1]".to_string(),
                "dissipation_3d_over_mrd_ci95_low [1]".to_string(),
                "dissipation_3d_over_mrd_ci95_high [1]".to_string(),
                "dissipation_3d_over_scale_mean [1]".to_string(),
                "dissipation_mrd_over_scale_mean [1]".to_string(),
            ],
        );
        cycles.notes.push(format!(
            "{note}; scale: (mu F_N)^2 / k_n of each surface (k_n = dF/dd at F_N)"
        ));
        // Largest |3D / MRD - 1| of the shift and the energy per cycle on the finest grid,
        // for nu > 0 and nu = 0, and the largest change of the ratios from the grid before.
        let (mut dev, mut dev_w, mut change) = ([0.0f64; 2], [0.0f64; 2], 0.0f64);
        let finest = *self.cells.last().unwrap_or(&0);
        let previous = self.cells.len().checked_sub(2).map(|i| self.cells[i]);
        let ratio_of = |h: f64, cells: usize, f: &dyn Fn(&Run) -> f64| {
            runs.iter()
                .find(|(hh, c, _)| *hh == h && *c == cells)
                .map(|(_, _, ens)| Stat::of(&ens.iter().map(f).collect::<Vec<_>>()).mean)
        };
        for (h, cells, ens) in runs {
            let grid = (*cells * self.bandwidth) as f64;
            let fine = *cells == finest;
            for (k, &nu) in self.poisson.iter().enumerate() {
                let exact = (nu == 0.0) as usize;
                let stat =
                    |f: &dyn Fn(&Run) -> f64| Stat::of(&ens.iter().map(f).collect::<Vec<_>>());
                // 3D, MRD and their ratio with its interval; the ratio's deviation and
                // change from the grid before feed the scalars (finest grid only).
                let mut compared = |three: &dyn Fn(&Run) -> f64,
                                    mrd: &dyn Fn(&Run) -> f64,
                                    dev: &mut f64|
                 -> [f64; 5] {
                    let f = |run: &Run| three(run) / mrd(run);
                    let r = stat(&f);
                    if fine {
                        *dev = dev.max((r.mean - 1.0).abs());
                        if let Some(c) = previous.and_then(|c| ratio_of(*h, c, &f)) {
                            change = change.max((r.mean / c - 1.0).abs());
                        }
                    }
                    let (m3, mm) = (stat(three).mean, stat(mrd).mean);
                    [m3, mm, r.mean, r.mean - r.ci95, r.mean + r.ci95]
                };
                for (j, x) in self.fractions.iter().enumerate() {
                    let c = compared(
                        &|run| run.shift_3d[k][j],
                        &|run| run.shift_mrd[k][j],
                        &mut dev[exact],
                    );
                    curve.push([[*h, nu, grid, *x].as_slice(), &c].concat());
                }
                let scaled = |e: f64, run: &Run| e * run.kn / (self.mu * run.force).powi(2);
                for (j, a) in self.amplitudes.iter().enumerate() {
                    let c = compared(
                        &|run| run.energy_3d[k][j],
                        &|run| run.energy_mrd[k][j],
                        &mut dev_w[exact],
                    );
                    let scale = [
                        stat(&|run| scaled(run.energy_3d[k][j], run)).mean,
                        stat(&|run| scaled(run.energy_mrd[k][j], run)).mean,
                    ];
                    cycles.push([[*h, nu, grid, *a].as_slice(), &c, &scale].concat());
                }
            }
        }
        let has = |zero: bool| self.poisson.iter().any(|nu| (*nu == 0.0) == zero);
        if has(false) {
            out.scalar("shift_max_rel_dev_3d_vs_mrd", dev[0]);
            out.scalar("dissipation_max_rel_dev_3d_vs_mrd", dev_w[0]);
        }
        if has(true) {
            out.scalar("shift_max_rel_dev_3d_vs_mrd_at_nu_0", dev[1]);
            out.scalar("dissipation_max_rel_dev_3d_vs_mrd_at_nu_0", dev_w[1]);
        }
        if previous.is_some() {
            out.scalar("ratio_max_rel_change_last_refinement", change);
        }
        let grid = (finest * self.bandwidth) as f64;
        out.figures.push(self.ratio_figure(
            &curve,
            "shift_3d_over_mrd",
            (
                "shift_ratio",
                "Rough partial slip: the 3D shift over MRD's at each tangential force",
                "tangential force over mu F_N [1]",
            ),
            grid,
        ));
        out.figures.push(self.ratio_figure(
            &cycles,
            "dissipation_3d_over_mrd",
            (
                "dissipation_ratio",
                "Rough partial slip: the 3D energy per cycle over MRD's (Masing)",
                "force amplitude over mu F_N [1]",
            ),
            grid,
        ));
        out.figures.push(self.dissipation_figure(&cycles, grid));
        out.tables.push(curve);
        out.tables.push(cycles);
    }

    /// The ensembles of the table `t` on the grid `grid`, Poisson's ratio by Hurst
    /// exponent.
    fn ensembles<'t>(&self, t: &'t Table, grid: f64) -> Vec<EnsembleRows<'t>> {
        let mut all = Vec::new();
        for (k, &nu) in self.poisson.iter().enumerate() {
            for (i, &h) in self.hurst.iter().enumerate() {
                let rows = t
                    .rows
                    .iter()
                    .filter(|r| r[0] == h && r[1] == nu && r[2] == grid)
                    .collect();
                all.push(EnsembleRows { k, nu, i, h, rows });
            }
        }
        all
    }

    /// 3D over MRD (column stem `stem`) against the force or amplitude, one colour per
    /// Poisson's ratio, one marker per Hurst exponent, on the grid `grid`.
    fn ratio_figure(
        &self,
        t: &Table,
        stem: &str,
        (name, title, x_label): (&str, &str, &str),
        grid: f64,
    ) -> Figure {
        let mut fig = Figure::new(name, title, x_label, "3D over MRD [1]");
        fig = fig.plot(
            "MRD (Ciavarella-Jaeger; Masing's rule for the cycles)",
            vec![(0.0, 1.0), (1.0, 1.0)],
            Style::Dashed,
        );
        let [mean, lo, hi] =
            ["mean", "ci95_low", "ci95_high"].map(|s| t.index(&format!("{stem}_{s}")));
        for e in self.ensembles(t, grid) {
            let EnsembleRows { k, nu, h, .. } = e;
            let rows = &e.rows;
            let style = e.marker();
            fig = fig.with(
                Series::new(
                    format!(
                        "3D, H = {h}, nu = {nu}: mean of {} surfaces on {grid}^2 cells, 95 % interval",
                        self.realisations
                    ),
                    rows.iter().map(|r| (r[3], r[mean])).collect(),
                    style,
                )
                .with_bars(rows.iter().map(|r| (r[3], r[lo], r[hi])).collect())
                .colored(k + 1),
            );
        }
        fig
    }

    /// The energy per cycle against the amplitude (Section 7's law), scaled by
    /// (mu F_N)^2 / k_n: MRD's lines, the 3D means as markers.
    fn dissipation_figure(&self, t: &Table, grid: f64) -> Figure {
        let mut fig = Figure::new(
            "dissipation",
            "Energy per cycle of an oscillating tangential force on rough contacts: 3D and MRD",
            "force amplitude over mu F_N [1]",
            "energy per cycle W k_n / (mu F_N)^2 [1]",
        )
        .log_log();
        let (w3, wm) = (
            t.index("dissipation_3d_over_scale_mean"),
            t.index("dissipation_mrd_over_scale_mean"),
        );
        for e in self.ensembles(t, grid) {
            let EnsembleRows { k, nu, h, .. } = e;
            let rows = &e.rows;
            let style = e.marker();
            fig = fig.with(
                Series::new(
                    format!("MRD, H = {h}, nu = {nu}"),
                    rows.iter().map(|r| (r[3], r[wm])).collect(),
                    e.line(),
                )
                .colored(k),
            );
            fig = fig.with(
                Series::new(
                    format!(
                        "3D, H = {h}, nu = {nu} ({grid}^2 cells, mean of {} surfaces)",
                        self.realisations
                    ),
                    rows.iter().map(|r| (r[3], r[w3])).collect(),
                    style,
                )
                .colored(k),
            );
        }
        fig
    }
}
