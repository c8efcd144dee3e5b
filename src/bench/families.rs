//! `mrdw bench families`: what one load step of each 3D solver family costs against a
//! load step of the normal solver, on one surface, one grid and one force ladder, so the
//! families can be held to one bar (at most 3x a normal step).

use super::common::{reference_surface, Case, Result};
use bem3d::adhesion::AdhesiveContact;
use bem3d::cohesive::{CohesiveContact, CohesiveLaw};
use bem3d::plastic::PlasticContact;
use bem3d::tangential::{CerrutiFree, CerrutiPeriodic, PartialSlip, ViscoelasticSlip};
use bem3d::viscoelastic::{Relaxation, TransientContact};
use bem3d::{
    ContactSolver, Load, NonPeriodicHalfSpace, PeriodicHalfSpace, SlidingContact, Solution,
    SolverOptions,
};
use std::io::Write;
use std::time::Instant;

/// The force ladder: mean pressures over E* (on the reference surface, rms slope 0.1,
/// about 5 % to 17 % of the cell in elastic contact).
const PRESSURES: [f64; 4] = [0.002, 0.004, 0.006, 0.008];
/// Tangential steps to 0.9 mu P.
const SLIP_STEPS: usize = 4;
/// Every solve's relative tolerance.
const TOLERANCE: f64 = 1e-8;
/// Each family's ladder is run this many times from a fresh solver; the median per-step
/// time is reported.
const RUNS: usize = 3;
/// Poisson's ratio and friction coefficient of the tangential families (E* = 1, so the
/// shear modulus is (1 - nu) / 2).
const NU: f64 = 0.3;
const MU: f64 = 0.5;
/// The factor of a normal step the issue sets as every family's bar.
const BAR: f64 = 3.0;

/// One family's measured ladder.
struct Row {
    family: &'static str,
    periodic: bool,
    steps: usize,
    /// Median over [`RUNS`] of the wall time per step [s].
    step: f64,
    /// Inner iterations per step (the conjugate-gradient iterations of all its solves).
    iterations: f64,
    /// Cells in contact (stick and slip for the tangential ones) over all cells, at the
    /// ladder's last step.
    contact: f64,
}

/// One run of a ladder: its wall time per step, iterations per step and the contact share.
type Run = (f64, f64, f64);

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs `ladder` [`RUNS`] times (each builds its own solver, outside the clock it
/// returns) and keeps the median step time.
fn measure(
    family: &'static str,
    periodic: bool,
    steps: usize,
    mut ladder: impl FnMut() -> Result<Run>,
) -> Result<Row> {
    let mut times = Vec::with_capacity(RUNS);
    let (mut iterations, mut contact) = (0.0, 0.0);
    for _ in 0..RUNS {
        let (t, it, c) = ladder().case(family)?;
        times.push(t);
        (iterations, contact) = (it, c);
    }
    Ok(Row {
        family,
        periodic,
        steps,
        step: median(times),
        iterations,
        contact,
    })
}

/// The problem every family is loaded on, and each family's parameters.
struct Problem {
    n: usize,
    heights: Vec<f64>,
    opts: SolverOptions,
    /// Work of adhesion, cohesive stress and range (adhesive and cohesive families).
    work: f64,
    sigma0: f64,
    range: f64,
    /// The pressure cap's hardness.
    hardness: f64,
    /// The viscoelastic families' relaxation and time step.
    relaxation: Relaxation,
    dt: f64,
    /// The shear modulus of the tangential families.
    shear: f64,
    /// Steady sliding's velocity.
    velocity: f64,
}

/// What the baselines hand on: the periodic solve's approaches, and each half-space's
/// last pressure (the tangential families' held normal contact).
struct Baselines {
    approaches: Vec<f64>,
    pressure_periodic: Vec<f64>,
    pressure_free: Vec<f64>,
}

/// Steady sliding's contact modulus, the standard linear solid of the transient family
/// in frequency: E*(omega) = 1/2 + (1/2) i omega / (1 + i omega).
fn sls(om: f64) -> (f64, f64) {
    let d = 1.0 + om * om;
    (0.5 + 0.5 * om * om / d, 0.5 * om / d)
}

fn per_step(t0: Instant, steps: usize) -> f64 {
    t0.elapsed().as_secs_f64() / steps as f64
}

/// The normal solver's ladder on `op`, warm-started: time per step and the solutions.
fn normal_ladder<K: bem3d::SolverOperator>(
    op: K,
    p: &Problem,
) -> bem3d::Result<(f64, Vec<Solution>)> {
    let mut s = ContactSolver::new(op, &p.heights, None)?;
    let mut sols: Vec<Solution> = Vec::new();
    let t0 = Instant::now();
    for pm in PRESSURES {
        let sol = s.solve(Load::MeanPressure(pm), &p.opts, sols.last())?;
        sols.push(sol);
    }
    Ok((per_step(t0, PRESSURES.len()), sols))
}

impl Problem {
    fn new(n: usize) -> Result<Self> {
        let heights = reference_surface(n).case("reference surface")?;
        let mean = heights.iter().sum::<f64>() / heights.len() as f64;
        let h_rms =
            (heights.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / heights.len() as f64).sqrt();
        // Adhesion: the cohesive range a tenth of the rms height, the cohesive stress
        // such that the Dugdale length E* w / sigma0^2 is 0.04 (20 cells on 512^2); the
        // JKR limit at the same work of adhesion.
        let range = 0.1 * h_rms;
        let sigma0 = range / 0.04;
        Ok(Self {
            n,
            heights,
            opts: SolverOptions::new(TOLERANCE, 100_000),
            work: sigma0 * range,
            sigma0,
            range,
            hardness: 0.1,
            // The viscoelastic moduli fall from E* = 1 (glassy) to 1/2 (relaxed), so
            // their contact shares stay near the elastic ones.
            relaxation: Relaxation::new(0.5, vec![(0.5, 1.0)]).case("relaxation")?,
            dt: 0.5,
            shear: (1.0 - NU) / 2.0,
            // omega = 1 at the sixteenth wavelength of the cell.
            velocity: 1.0 / (std::f64::consts::TAU * 16.0),
        })
    }

    fn periodic_op(&self) -> PeriodicHalfSpace {
        PeriodicHalfSpace::new(self.n, self.n, 1.0, 1.0, 1.0)
    }

    fn share(&self, cells: usize) -> f64 {
        cells as f64 / (self.n * self.n) as f64
    }

    /// The normal solver on both half-spaces, and what the other families take from it.
    fn normal_rows(&self) -> Result<(Vec<Row>, Baselines)> {
        let mut b = Baselines {
            approaches: Vec::new(),
            pressure_periodic: Vec::new(),
            pressure_free: Vec::new(),
        };
        let summary = |t: f64, sols: &[Solution]| -> Run {
            let it = sols.iter().map(|s| s.iterations).sum::<usize>() as f64 / sols.len() as f64;
            (t, it, self.share(sols[sols.len() - 1].contact_cells))
        };
        let steps = PRESSURES.len();
        let rows = vec![
            measure("normal", true, steps, || {
                let (t, sols) = normal_ladder(self.periodic_op(), self)?;
                b.approaches = sols.iter().map(|s| s.approach).collect();
                b.pressure_periodic = sols[sols.len() - 1].pressure.clone();
                Ok(summary(t, &sols))
            })?,
            measure("normal", false, steps, || {
                let op = NonPeriodicHalfSpace::new(self.n, self.n, 1.0, 1.0, 1.0);
                let (t, sols) = normal_ladder(op, self)?;
                b.pressure_free = sols[sols.len() - 1].pressure.clone();
                Ok(summary(t, &sols))
            })?,
        ];
        Ok((rows, b))
    }

    /// The normal families along the force ladder (the cohesive ones along the periodic
    /// normal solve's approaches), all on the periodic half-space.
    fn load_rows(&self, approaches: &[f64]) -> Result<Vec<Row>> {
        let (steps, heights) = (PRESSURES.len(), &self.heights);
        let mut rows = vec![measure("pressure cap", true, steps, || {
            let mut c = PlasticContact::new(self.periodic_op(), heights, None, self.hardness)?;
            let t0 = Instant::now();
            let (mut it, mut last) = (0, 0);
            for p in PRESSURES {
                let s = c.step(Load::MeanPressure(p), TOLERANCE)?;
                (it, last) = (it + s.iterations, s.contact_cells);
            }
            Ok((
                per_step(t0, steps),
                it as f64 / steps as f64,
                self.share(last),
            ))
        })?];
        rows.push(measure("adhesive (JKR limit)", true, steps, || {
            let mut c = AdhesiveContact::new(self.periodic_op(), heights, None, self.work)?;
            let t0 = Instant::now();
            let (mut it, mut last) = (0, 0);
            for p in PRESSURES {
                let s = c.step(Load::MeanPressure(p), TOLERANCE)?;
                (it, last) = (it + s.iterations, s.contact_cells);
            }
            Ok((
                per_step(t0, steps),
                it as f64 / steps as f64,
                self.share(last),
            ))
        })?);
        for (family, law) in [
            ("cohesive Maugis-Dugdale", CohesiveLaw::Dugdale),
            ("cohesive exponential", CohesiveLaw::Exponential),
        ] {
            rows.push(measure(family, true, steps, || {
                let op = self.periodic_op();
                let mut c =
                    CohesiveContact::new(op, heights, None, self.work, self.sigma0)?.with_law(law);
                let t0 = Instant::now();
                let (mut it, mut last) = (0, 0);
                for &d in approaches {
                    let s = c.step(d, TOLERANCE)?;
                    (it, last) = (it + s.iterations, s.contact_cells);
                }
                Ok((
                    per_step(t0, steps),
                    it as f64 / steps as f64,
                    self.share(last),
                ))
            })?);
        }
        rows.push(measure("transient viscoelastic", true, steps, || {
            let modulus = self.relaxation.clone();
            let mut c = TransientContact::new(self.periodic_op(), heights, None, modulus)?;
            let t0 = Instant::now();
            let (mut it, mut last) = (0, 0);
            for p in PRESSURES {
                let s = c.step(self.dt, Load::MeanPressure(p), &self.opts)?;
                it += s.solve.as_ref().map_or(0, |s| s.iterations);
                last = s.contact_cells;
            }
            Ok((
                per_step(t0, steps),
                it as f64 / steps as f64,
                self.share(last),
            ))
        })?);
        rows.push(measure("steady viscoelastic sliding", true, steps, || {
            let (n, v) = (self.n, self.velocity);
            let mut c = SlidingContact::new(n, n, 1.0, 1.0, heights, v, &sls)?;
            let t0 = Instant::now();
            let (mut it, mut last) = (0, None::<bem3d::SlidingSolution>);
            for p in PRESSURES {
                let s = c.solve(p, &self.opts, last.as_ref())?;
                it += s.inner_iterations;
                last = Some(s);
            }
            let cells = last.map_or(0, |s| s.contact.contact_cells);
            Ok((
                per_step(t0, steps),
                it as f64 / steps as f64,
                self.share(cells),
            ))
        })?);
        Ok(rows)
    }

    /// The tangential families under the normal solves' last pressures: partial slip to
    /// 0.9 mu P on both half-spaces, the viscoelastic partial slip on the free one.
    fn slip_rows(&self, b: &Baselines) -> Result<Vec<Row>> {
        let (n, shear) = (self.n, self.shear);
        let mut rows = Vec::new();
        for periodic in [true, false] {
            let pressure = if periodic {
                &b.pressure_periodic
            } else {
                &b.pressure_free
            };
            rows.push(measure("partial slip", periodic, SLIP_STEPS, || {
                let op: Box<dyn bem3d::tangential::TangentialCompliance + Sync> = if periodic {
                    Box::new(CerrutiPeriodic::new(n, n, 1.0, 1.0, shear, NU)?)
                } else {
                    Box::new(CerrutiFree::new(n, n, 1.0, 1.0, shear, NU)?)
                };
                let mut c = PartialSlip::new(op, pressure, MU)?;
                let limit = c.friction_limit();
                let t0 = Instant::now();
                let (mut it, mut last) = (0, 0);
                for k in 1..=SLIP_STEPS {
                    let s = c.load(0.9 * limit * k as f64 / SLIP_STEPS as f64, TOLERANCE)?;
                    (it, last) = (it + s.iterations, s.stick_cells + s.slip_cells);
                }
                let it = it as f64 / SLIP_STEPS as f64;
                Ok((per_step(t0, SLIP_STEPS), it, self.share(last)))
            })?);
        }
        // The viscoelastic slip moves the body by shifts: those of the elastic partial
        // slip at the glassy modulus to 0.9 mu P (the contact stays short of sliding as
        // it relaxes towards the softer relaxed modulus under the shift's ramp).
        let shifts: Vec<f64> = {
            let op = CerrutiFree::new(n, n, 1.0, 1.0, shear, NU).case("free Cerruti")?;
            let mut c = PartialSlip::new(op, &b.pressure_free, MU).case("partial slip")?;
            let limit = c.friction_limit();
            (1..=SLIP_STEPS)
                .map(|k| {
                    c.load(0.9 * limit * k as f64 / SLIP_STEPS as f64, TOLERANCE)
                        .map(|s| s.shift)
                })
                .collect::<std::result::Result<_, _>>()
                .case("partial slip at the glassy modulus")?
        };
        let family = "viscoelastic partial slip";
        rows.push(measure(family, false, SLIP_STEPS, || {
            let op = CerrutiFree::new(n, n, 1.0, 1.0, 1.0, NU)?;
            let modulus = Relaxation::new(0.5 * shear, vec![(0.5 * shear, 1.0)])?;
            let mut c = ViscoelasticSlip::new(op, &b.pressure_free, MU, modulus)?;
            let t0 = Instant::now();
            let (mut it, mut last) = (0, 0);
            for &shift in &shifts {
                let s = c.step(self.dt, shift, TOLERANCE)?;
                (it, last) = (it + s.iterations, s.stick_cells + s.slip_cells);
            }
            let it = it as f64 / SLIP_STEPS as f64;
            Ok((per_step(t0, SLIP_STEPS), it, self.share(last)))
        })?);
        Ok(rows)
    }

    fn write_header(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let (n, dt) = (self.n, self.dt);
        writeln!(
            w,
            "Solver families against the normal solve, one load step each (the periodic reference surface: self-affine H = 0.8, rms slope 0.1, L = 1, {n}^2 cells; E* = 1; mean pressures {PRESSURES:?} E* in {} steps; tolerance {TOLERANCE:e}; median of {RUNS} runs from a fresh solver), {} threads, {}",
            PRESSURES.len(),
            rayon::current_num_threads(),
            sysmem::cpu_model()
        )?;
        writeln!(
            w,
            "adhesion: w = {:.3e}, cohesive sigma0 = {:.3e} (range {:.3e} = h_rms / 10, Dugdale length 0.04); pressure cap H = {}; transient: E*(t) = (1 + exp(-t)) / 2, dt = {dt}; sliding: E*(omega) = (1 + i omega / (1 + i omega)) / 2, v = {:.4e}; tangential: nu = {NU}, mu = {MU}, {SLIP_STEPS} steps to 0.9 mu P under the normal solve's last pressure; viscoelastic slip: G(t) = G (1 + exp(-t)) / 2, dt = {dt}, the elastic steps' shifts at G\n",
            self.work, self.sigma0, self.range, self.hardness, self.velocity
        )
    }
}

/// The table: each family's step over its half-space's normal step (rows 0 and 1).
fn write_table(w: &mut dyn Write, rows: &[Row]) -> std::io::Result<()> {
    writeln!(
        w,
        "{:>28} | {:>9} | {:>5} | {:>11} | {:>11} | {:>6} | {:>10} | {:>7}",
        "family", "half-space", "steps", "step [s]", "normal [s]", "ratio", "iter./step", "contact"
    )?;
    writeln!(w, "{}", "-".repeat(106))?;
    let baseline = |periodic: bool| rows[if periodic { 0 } else { 1 }].step;
    let mut over = Vec::new();
    for r in rows {
        let ratio = r.step / baseline(r.periodic);
        let half_space = if r.periodic { "periodic" } else { "free" };
        if ratio > BAR {
            over.push(format!("{} ({half_space}, {ratio:.1}x)", r.family));
        }
        writeln!(
            w,
            "{:>28} | {:>10} | {:>5} | {:>11.4e} | {:>11.4e} | {:>6.2} | {:>10.1} | {:>6.2}%",
            r.family,
            half_space,
            r.steps,
            r.step,
            baseline(r.periodic),
            ratio,
            r.iterations,
            100.0 * r.contact
        )?;
    }
    writeln!(
        w,
        "\niter./step: conjugate-gradient iterations per step, of all its solves (steady sliding: the inner solves' iterations); contact: cells in contact (stick and slip) at the last step."
    )?;
    if over.is_empty() {
        writeln!(w, "Every family within {BAR}x of a normal step.")
    } else {
        writeln!(w, "Above {BAR}x a normal step: {}.", over.join(", "))
    }
}

/// The reference surface on `n`^2 cells (periodic, L = 1, E* = 1), loaded along
/// [`PRESSURES`] by the normal solver (warm-started, the baseline of each half-space)
/// and by every family: the pressure cap (H = 0.1 E*), the adhesive contact in its JKR
/// limit, the cohesive laws (Maugis-Dugdale and exponential, at the normal solve's
/// approaches), the transient viscoelastic contact, steady viscoelastic sliding; and,
/// under the normal solve's last pressure, partial slip to 0.9 mu P (periodic and free)
/// and the viscoelastic partial slip (free).
pub fn run_families(w: &mut dyn Write, n: usize) -> Result<()> {
    let problem = Problem::new(n)?;
    problem.write_header(w)?;
    let (mut rows, baselines) = problem.normal_rows()?;
    rows.extend(problem.load_rows(&baselines.approaches)?);
    rows.extend(problem.slip_rows(&baselines)?);
    write_table(w, &rows)?;
    Ok(())
}
