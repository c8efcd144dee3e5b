//! Steady sliding of a rigid periodic rough surface over a linear viscoelastic
//! half-space (frictionless interface, no adhesion), mean pressure prescribed.
//!
//! The surface moves at velocity v in +x. In its frame the steady state does not depend
//! on time, and a material point passes a pressure mode exp(i q.x) with time dependence
//! exp(-i q_x v t): with the contact modulus E*(omega) = E' + i E'' of the material
//! (E'' >= 0 for omega > 0; E*(-omega) = conj E*(omega)) the surface compliance of mode q
//! is C(q) = 2 / (|q| conj E*(q_x v)) (the elastic 2 / (|q| E*) of Stanley & Kato at
//! v = 0). The operator u = K p is real but not symmetric; K = K_s + K_a with K_s the
//! storage part (positive definite) and K_a skew. The contact problem, p >= 0,
//! g = K p + z - d >= 0, p g = 0, mean p given, is a monotone linear complementarity
//! problem.
//!
//! Solver (choice and reasons). K's skew part is not small: the loss tangent E''/E' of
//! rubber exceeds 3 near its glass transition (Eq. 84 of the MRD review), so no splitting
//! that treats the loss part explicitly converges by itself. We split K = B + (K - B)
//! with B the symmetric positive definite operator of the storage compliance
//! 2 / (|q| E'(q_x v)): the map x -> S_B(z + (K - B) x), S_B the solution of the
//! symmetric contact problem with operator B (the preconditioned Polonsky-Keer solver of
//! [`crate::solver`], warm-started), has the sliding solution as its fixed point, and on
//! unconstrained modes its linearisation 1 - C/B = -i E'' / conj E* has modulus sin(phi)
//! (phi the loss angle): the smallest of any real symmetric B chosen per mode (|C| as B
//! gives 2 sin(phi / 2)). Near phi = 90 degrees that still contracts slowly, so the outer
//! iteration is accelerated by Anderson mixing (a least-squares combination of the last
//! six iterates, GMRES-like on the linear part). The inner solves are inexact: to a tenth
//! of the outer residual reached (from 1e-2 down to half the requested tolerance), which
//! halves the work against solving each to full accuracy. Convergence is judged on the
//! sliding problem itself, with the elastic solver's criterion (pressure-weighted gap and
//! interpenetration relative to the rms height) and the true K. Measured on the Fig. 7
//! surface at 256^2: 20-100 outer iterations, most near the loss peak.
//!
//! Friction, two routes. Direct: the horizontal force on the surface from the normal
//! pressure on its slopes; since on contact u = h + const and material points move by
//! -v d/dx, the power per area is -v <p dh/dx>, so mu = -<p dh/dx> / p_mean (dh/dx
//! spectral). Fourier: the power dissipated in the half-space, sum over modes of
//! q_x v Im C(q) |P(q)|^2, over v p_mean. The two agree as the grid is refined (tested).
//! For h = h0 cos(q x) in full contact, p = p_mean + (h0 q / 2)(E' cos qx + E'' sin qx)
//! (the peak moves to the leading side of the asperity, +x) and
//! mu = q^2 h0^2 E''(q v) / (4 p_mean).
//!
//! Limits: as v -> 0 the elastic contact with E*(0); as v -> infinity every mode with
//! q_x != 0 sees the glassy E*(inf), but modes with q_x = 0 (heights constant along x)
//! never change in time and keep E*(0).
//!
//! Grid conventions as [`crate::PeriodicHalfSpace`]; on an even grid the Nyquist column
//! (kx = pi nx / lx, whose direction of motion is ambiguous) takes the storage
//! compliance only.

use crate::error::{BemError, Result};
use crate::fft::Fft2;
use crate::kit::anderson::Anderson;
use crate::operator::{spectral_grid, PeriodicHalfSpace};
use crate::solver::{ContactSolver, Load, Solution, SolverOptions};
use rustfft::num_complex::Complex64;

/// A steady sliding state.
#[derive(Debug, Clone, PartialEq)]
pub struct SlidingSolution {
    /// Pressure, gap, approach, contact area, ... (`iterations`: outer iterations).
    pub contact: Solution,
    /// mu = -<p dh/dx> / p_mean (direct route).
    pub mu: f64,
    /// Dissipated power / (v p_mean) (Fourier route).
    pub mu_dissipation: f64,
    /// Inner (Polonsky-Keer) iterations over all outer iterations.
    pub inner_iterations: usize,
}

/// Solver of steady sliding for one surface, modulus and velocity.
pub struct SlidingContact {
    nx: usize,
    ny: usize,
    lx: f64,
    ly: f64,
    velocity: f64,
    heights: Vec<f64>,
    /// z = max h - h and dh/dx.
    z: Vec<f64>,
    slope: Vec<f64>,
    h_rms: f64,
    /// Complex compliance C(q) and C - |C| per bin (transposed half spectrum).
    c: Vec<Complex64>,
    c_minus_b: Vec<Complex64>,
    fft: Fft2,
    spec: Vec<Complex64>,
    inner: ContactSolver<PeriodicHalfSpace>,
}

impl SlidingContact {
    /// `heights` (`ny x nx`, peaks up, periodic, size `lx x ly`); the surface slides at
    /// `velocity` >= 0 in +x; `modulus(omega)` = (E*', E*'') for omega >= 0, the contact
    /// modulus (4 G for an incompressible half-space against a rigid surface).
    pub fn new(
        nx: usize,
        ny: usize,
        lx: f64,
        ly: f64,
        heights: &[f64],
        velocity: f64,
        modulus: &dyn Fn(f64) -> (f64, f64),
    ) -> Result<Self> {
        if !(velocity.is_finite() && velocity >= 0.0) {
            return Err(BemError::InvalidInput(format!(
                "velocity = {velocity} must be finite and >= 0"
            )));
        }
        if nx < 2 || ny < 1 || !(lx > 0.0 && ly > 0.0) {
            return Err(BemError::InvalidInput(
                "grid must be >= 2 x 1 with a positive size".into(),
            ));
        }
        // The modulus depends on kx alone: one evaluation per column (kx >= 0 in the half
        // spectrum), checked.
        let nc = nx / 2 + 1;
        let column_kx = |c: usize| 2.0 * std::f64::consts::PI * c as f64 / lx;
        let mut e_col = Vec::with_capacity(nc);
        for col in 0..nc {
            let w = column_kx(col) * velocity;
            let (re, im) = modulus(w);
            if !(re.is_finite() && im.is_finite() && re > 0.0 && im >= 0.0) {
                return Err(BemError::InvalidInput(format!(
                    "contact modulus at omega = {w:e}: E' = {re}, E'' = {im} (need E' > 0, E'' >= 0)"
                )));
            }
            e_col.push(Complex64::new(re, im));
        }
        let col_of =
            |kx: f64| ((kx * lx / (2.0 * std::f64::consts::PI)).round() as usize).min(nc - 1);
        let nyquist = |col: usize| nx.is_multiple_of(2) && col == nc - 1;
        // C = 2 / (|q| conj E*(kx v)), storage part only on the Nyquist column; B = the
        // storage compliance 2 / (|q| E'(kx v)), symmetric positive definite.
        let qs = spectral_grid(nx, ny, lx, ly, |kx, ky| (kx * kx + ky * ky).sqrt());
        let mut c = vec![Complex64::default(); nc * ny];
        let mut c_minus_b = vec![Complex64::default(); nc * ny];
        for (i, q) in qs.iter().enumerate() {
            if *q == 0.0 {
                continue;
            }
            let col = i / ny;
            let e = e_col[col];
            let full = 2.0 / (q * e.conj());
            c[i] = if nyquist(col) {
                Complex64::new(full.re, 0.0)
            } else {
                full
            };
            c_minus_b[i] = c[i] - 2.0 / (q * e.re);
        }
        let k_min = (2.0 * std::f64::consts::PI / lx).min(2.0 * std::f64::consts::PI / ly);
        let e_scale = e_col[col_of(k_min)].re;
        let b_op = PeriodicHalfSpace::with_compliance(nx, ny, lx, ly, e_scale, |kx, ky| {
            2.0 / ((kx * kx + ky * ky).sqrt() * e_col[col_of(kx)].re)
        });
        let inner = ContactSolver::new(b_op, heights, None)?;
        let h_rms = inner.h_rms();
        let hmax = heights.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
        let mut fft = Fft2::new(nx, ny);
        let mut spec = vec![Complex64::default(); fft.spectrum_len()];
        // dh/dx spectrally: multiply by i kx (the Nyquist column has no derivative).
        fft.forward(heights, &mut spec);
        for (i, s) in spec.iter_mut().enumerate() {
            let col = i / ny;
            *s = if nyquist(col) {
                Complex64::default()
            } else {
                Complex64::new(0.0, column_kx(col)) * *s
            };
        }
        let mut slope = vec![0.0; nx * ny];
        fft.inverse(&mut spec, &mut slope);
        Ok(Self {
            nx,
            ny,
            lx,
            ly,
            velocity,
            heights: heights.to_vec(),
            z: heights.iter().map(|h| hmax - h).collect(),
            slope,
            h_rms,
            c,
            c_minus_b,
            fft,
            spec,
            inner,
        })
    }

    /// out = (kernel * p) in real space.
    fn apply(&mut self, kernel_is_full: bool, p: &[f64], out: &mut [f64]) {
        let k = if kernel_is_full {
            &self.c
        } else {
            &self.c_minus_b
        };
        self.fft.convolve(p, (self.nx, self.ny), k, out);
    }

    /// The sliding problem's residual (the elastic criterion with the true K), the
    /// approach and the gap for pressure `p`.
    fn evaluate(&mut self, p: &[f64]) -> (f64, f64, Vec<f64>) {
        let n = p.len();
        let mut u = vec![0.0; n];
        self.apply(true, p, &mut u);
        let (mut sg, mut nc) = (0.0, 0usize);
        for i in 0..n {
            if p[i] > 0.0 {
                sg += u[i] + self.z[i];
                nc += 1;
            }
        }
        let d = if nc > 0 { sg / nc as f64 } else { 0.0 };
        let g: Vec<f64> = (0..n).map(|i| u[i] + self.z[i] - d).collect();
        let (mut pg, mut ps, mut worst) = (0.0, 0.0, 0.0f64);
        for i in 0..n {
            pg += p[i] * g[i].abs();
            ps += p[i];
            worst = worst.max(-g[i]);
        }
        let residual = (if ps > 0.0 {
            pg / (ps * self.h_rms)
        } else {
            0.0
        })
        .max(worst / self.h_rms);
        (residual, d, g)
    }

    /// The two friction coefficients of pressure `p` at mean pressure `pm`.
    fn friction(&mut self, p: &[f64], pm: f64) -> (f64, f64) {
        let n = p.len() as f64;
        let direct = -p.iter().zip(&self.slope).map(|(p, s)| p * s).sum::<f64>() / n / pm;
        // Power: sum over all modes of q_x v Im C |P_q|^2 with P_q = p_hat / N; the half
        // spectrum holds each +-q pair once (columns 0 and Nyquist alone, kx = 0 there or
        // Im C = 0).
        self.fft.forward(p, &mut self.spec);
        let kxs = spectral_grid(self.nx, self.ny, self.lx, self.ly, |kx, _| kx);
        let mut power = 0.0;
        for (i, (s, c)) in self.spec.iter().zip(&self.c).enumerate() {
            power += 2.0 * kxs[i] * self.velocity * c.im * s.norm_sqr() / (n * n);
        }
        let dissipation = if self.velocity > 0.0 {
            power / (self.velocity * pm)
        } else {
            0.0
        };
        (direct, dissipation)
    }

    /// Solves for mean pressure `pm` (> 0) to `opts.tolerance`, with at most
    /// `opts.max_iterations` outer iterations (each inner solve has the same cap);
    /// `warm`: a previous solution (e.g. the neighbouring velocity).
    pub fn solve(
        &mut self,
        pm: f64,
        opts: &SolverOptions,
        warm: Option<&SlidingSolution>,
    ) -> Result<SlidingSolution> {
        crate::pool::on_pool(|| self.solve_on_pool(pm, opts, warm))
    }

    fn solve_on_pool(
        &mut self,
        pm: f64,
        opts: &SolverOptions,
        warm: Option<&SlidingSolution>,
    ) -> Result<SlidingSolution> {
        if !(pm.is_finite() && pm > 0.0) {
            return Err(BemError::InvalidInput(format!(
                "mean pressure = {pm} must be > 0"
            )));
        }
        let n = self.nx * self.ny;
        let inner_floor = 0.5 * opts.tolerance;
        let mut mixer = Anderson::new(6);
        let mut x: Vec<f64> = match warm {
            Some(w) if w.contact.pressure.len() == n => w.contact.pressure.clone(),
            _ => vec![pm; n],
        };
        let mut inner_warm: Option<Solution> = match warm {
            Some(w) if w.contact.pressure.len() == n => Some(w.contact.clone()),
            _ => None,
        };
        let mut inner_iterations = 0;
        let mut r = vec![0.0; n];
        let mut best: Option<(f64, Solution)> = None;
        let mut last_residual = f64::INFINITY;
        for outer in 1..=opts.max_iterations {
            // g = S_B(z + (K - B) x): heights h - (K - B) x.
            self.apply(false, &x, &mut r);
            let h_mod: Vec<f64> = self.heights.iter().zip(&r).map(|(h, r)| h - r).collect();
            self.inner.set_heights(&h_mod)?;
            let inner_opts = SolverOptions {
                tolerance: (0.1 * last_residual).clamp(inner_floor, 1e-2f64.max(inner_floor)),
                max_iterations: opts.max_iterations,
                ..opts.clone()
            };
            let sol =
                match self
                    .inner
                    .solve(Load::MeanPressure(pm), &inner_opts, inner_warm.as_ref())
                {
                    Ok(s) => s,
                    Err(BemError::NoConvergence { last, .. }) => *last,
                    Err(e) => return Err(e),
                };
            inner_iterations += sol.iterations;
            let (residual, d, g) = self.evaluate(&sol.pressure);
            last_residual = residual;
            if !residual.is_finite() {
                return Err(BemError::Breakdown {
                    what: "sliding contact",
                    iterations: outer,
                    residual,
                    reason: "non-finite residual",
                });
            }
            let mut contact = sol.clone();
            contact.approach = d;
            contact.gap = g.iter().map(|&v| v.max(0.0)).collect();
            contact.mean_gap = contact.gap.iter().sum::<f64>() / n as f64;
            contact.iterations = outer;
            contact.residual = residual;
            contact.warm_started = warm.is_some();
            if residual <= opts.tolerance {
                let (mu, mu_dissipation) = self.friction(&contact.pressure, pm);
                return Ok(SlidingSolution {
                    contact,
                    mu,
                    mu_dissipation,
                    inner_iterations,
                });
            }
            if best.as_ref().is_none_or(|b| residual < b.0) {
                best = Some((residual, contact));
            }
            x = mixer.next(&x, &sol.pressure);
            inner_warm = Some(sol);
        }
        let (residual, last) = best.expect("at least one outer iteration");
        Err(BemError::NoConvergence {
            what: "sliding contact",
            iterations: opts.max_iterations,
            residual,
            tolerance: opts.tolerance,
            last: Box::new(last),
        })
    }
}
