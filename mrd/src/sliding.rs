//! Sliding friction of an elastomer (Section 10.1): a rigid rough line slides at
//! constant velocity over the viscoelastic MRD foundation under a constant normal force.
//!
//! Springs (Eq. 63): spring j, of width dx, carries f_j = dx [M_inf u_j + sum_k M_k w_jk]
//! with the spring modulus M(t) = 4 G(t) of an incompressible elastomer against a rigid
//! body (Eq. 62; callers pass the scaled [`Prony`]) and one internal variable per Prony
//! term, w_k = u - v_k (v_k the dashpot's displacement, dv_k/dt = (u - v_k)/tau_k).
//! For a displacement u that is linear within a step of length dt the update is exact:
//! `w_k <- a_k w_k + beta_k du`, a_k = exp(-dt/tau_k), beta_k = tau_k (1 - a_k)/dt
//! (unconditionally stable, O(1) per term, no history). [`MaxwellRow`].
//!
//! Contact: the rigid line, at approach d, indents spring j by delta_j = d - g_j(t)
//! (g = max z - z, the gap under the undeformed surface). A spring's force is linear in
//! its end-of-step displacement, f_j = A (u_j - u_free_j), with the same A = dx (M_inf +
//! sum M_k beta_k) for every spring; u_free_j is where it would be without load (a
//! detached spring relaxes freely). So u_j = max(delta_j, u_free_j): a spring touches
//! when the line reaches its (relaxing) surface and detaches instead of pulling. The
//! total force A sum_j (d - e_j)+, e_j = g_j + u_free_j, is piecewise linear and convex in
//! d: the approach that carries the normal force is found exactly by Newton's method
//! (the contact set changes a few times per step at most).
//!
//! Kinematics: the line moves by `stride` of its points per step, dt = stride dx_line / v;
//! spring j sits under line point j s + offset (s = line points per spring). Friction
//! (the horizontal force on the line from the normal spring forces on its inclined
//! surface) F_x = sum_j f_j z'(x_j), z' the spectral derivative of the line; mu = F_x/F_N.
//! Independently, the energy dissipated in the dashpots, dx M_k w_k^2 / tau_k integrated
//! exactly over each step, per unit sliding distance, must equal the mean F_x in steady
//! state (the stored energy returns after a pass and the normal force does no net work).
//!
//! Steady state: the line is periodic, so the steady state is periodic with one pass
//! (L/v), and then every internal variable has zero mean over a pass (dw/dt = u' -
//! w/tau with u periodic). Under a constant normal force the material creeps with
//! retardation times tau G(0)/G_inf (1e3 tau for Eq. 84), far longer than a pass at most
//! velocities. After each pass the homogeneous (decaying) part of every internal
//! variable is removed using that condition: with w_n = w*_n + c a^n and <w*> = 0,
//! c = <w> / <a^n>, so `w_P <- w_P - c a^P` (a = exp(-dt/tau), a^P over the pass). This
//! is exact for a fixed displacement history, the identity at the steady state, and
//! does not amplify the creep transient (an estimate of c from w_0 - w_P would, by
//! 1/(1 - a^P)). Passes repeat until mu and the mean approach change by less than the
//! tolerance (relative to mu and to the rms height) between two passes; the last pass is
//! measured.

use crate::error::{positive, MrdError, Result};
use crate::rheology::Prony;
use fftplans::Planned;

/// A rigid periodic line z(x) of N points over length L, with its slope.
#[derive(Debug, Clone)]
pub struct Line {
    /// Gaps g = max z - z (>= 0).
    gaps: Vec<f64>,
    /// z'(x) at the points, by spectral differentiation.
    slopes: Vec<f64>,
    length: f64,
    /// rms height about the mean and rms slope.
    pub rms_height: f64,
    pub rms_slope: f64,
}

impl Line {
    pub fn new(heights: &[f64], length: f64) -> Result<Self> {
        positive("length", length)?;
        let n = heights.len();
        if n < 4 || crate::error::bad_height(heights).is_some() {
            return Err(MrdError::InvalidData(
                "a sliding line needs >= 4 finite heights, |h| <= 1e100".into(),
            ));
        }
        let zmax = heights.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
        let mean = heights.iter().sum::<f64>() / n as f64;
        let rms_height =
            (heights.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
        let slopes = spectral_slope(heights, length)?;
        let rms_slope = (slopes.iter().map(|s| s * s).sum::<f64>() / n as f64).sqrt();
        Ok(Self {
            gaps: heights.iter().map(|z| zmax - z).collect(),
            slopes,
            length,
            rms_height,
            rms_slope,
        })
    }

    pub fn len(&self) -> usize {
        self.gaps.len()
    }
    pub fn is_empty(&self) -> bool {
        self.gaps.is_empty()
    }
    pub fn length(&self) -> f64 {
        self.length
    }
    /// The characteristic wave vector k = rms slope / rms height (exactly the wave
    /// number of a sinusoid).
    pub fn wave_vector(&self) -> f64 {
        self.rms_slope / self.rms_height
    }
}

/// z'(x) of a periodic sampled z by multiplication with i q in Fourier space (the
/// Nyquist mode, whose derivative is not real, is dropped).
fn spectral_slope(z: &[f64], length: f64) -> Result<Vec<f64>> {
    let n = z.len();
    let r2c = f64::real_forward(n);
    let c2r = f64::real_inverse(n);
    let mut input = z.to_vec();
    let mut spec = r2c.make_output_vec();
    r2c.process(&mut input, &mut spec)
        .map_err(|e| MrdError::InvalidData(format!("FFT: {e}")))?;
    let nc = spec.len();
    for (k, s) in spec.iter_mut().enumerate() {
        let q = std::f64::consts::TAU * k as f64 / length;
        *s = if k == 0 || (n.is_multiple_of(2) && k == nc - 1) {
            Default::default()
        } else {
            rustfft::num_complex::Complex64::new(-q * s.im, q * s.re)
        };
    }
    let mut out = vec![0.0; n];
    c2r.process(&mut spec, &mut out)
        .map_err(|e| MrdError::InvalidData(format!("inverse FFT: {e}")))?;
    out.iter_mut().for_each(|v| *v /= n as f64);
    Ok(out)
}

/// A row of generalised-Maxwell springs (per unit width: forces per dx) advanced with a
/// fixed time step by the exact update for piecewise-linear displacement. Internal
/// variables are stored term by term (`w[k * n + j]`), so that every operation is a loop
/// over springs with the term's constants fixed (it vectorises).
#[derive(Debug, Clone)]
pub struct MaxwellRow {
    relaxed: f64,
    moduli: Vec<f64>,
    taus: Vec<f64>,
    /// exp(-dt/tau_k) and tau_k (1 - exp(-dt/tau_k)) / dt.
    a: Vec<f64>,
    beta: Vec<f64>,
    /// 1 - exp(-dt/tau_k), 1 - exp(-2 dt/tau_k), M_k / tau_k (dissipation integrals).
    one_a: Vec<f64>,
    one_a2: Vec<f64>,
    loss: Vec<f64>,
    /// M_inf + sum M_k beta_k: d(force per width)/d(end-of-step displacement).
    slope: f64,
    dt: f64,
    /// Displacement u_j and internal variables w_kj (term-major).
    pub u: Vec<f64>,
    pub w: Vec<f64>,
}

impl MaxwellRow {
    pub fn new(modulus: &Prony, springs: usize, dt: f64) -> Result<Self> {
        positive("time step", dt)?;
        let m = modulus.terms.len();
        let taus: Vec<f64> = modulus.terms.iter().map(|t| t.1).collect();
        let moduli: Vec<f64> = modulus.terms.iter().map(|t| t.0).collect();
        let a: Vec<f64> = taus.iter().map(|&t| (-dt / t).exp()).collect();
        let beta: Vec<f64> = taus.iter().map(|&t| -(-dt / t).exp_m1() * t / dt).collect();
        let slope = modulus.relaxed + moduli.iter().zip(&beta).map(|(g, b)| g * b).sum::<f64>();
        let one_a = taus.iter().map(|&t| -(-dt / t).exp_m1()).collect();
        let one_a2 = taus.iter().map(|&t| -(-2.0 * dt / t).exp_m1()).collect();
        let loss = moduli.iter().zip(&taus).map(|(g, t)| g / t).collect();
        Ok(Self {
            relaxed: modulus.relaxed,
            moduli,
            taus,
            a,
            beta,
            one_a,
            one_a2,
            loss,
            slope,
            dt,
            u: vec![0.0; springs],
            w: vec![0.0; springs * m],
        })
    }

    fn terms(&self) -> usize {
        self.moduli.len()
    }

    fn springs(&self) -> usize {
        self.u.len()
    }

    /// The relaxed modulus M_inf.
    pub fn relaxed(&self) -> f64 {
        self.relaxed
    }

    /// d(force per width)/d(end-of-step displacement), the same for every spring.
    pub fn slope(&self) -> f64 {
        self.slope
    }

    /// Where every spring would be at the end of the step without load, into `free`.
    pub fn free(&self, free: &mut [f64]) {
        let n = self.springs();
        free.iter_mut().for_each(|c| *c = 0.0);
        for k in 0..self.terms() {
            let (gb, ga) = (self.moduli[k] * self.beta[k], self.moduli[k] * self.a[k]);
            let w = &self.w[k * n..(k + 1) * n];
            for ((c, &u), &wk) in free.iter_mut().zip(&self.u).zip(w) {
                *c += gb * u - ga * wk;
            }
        }
        let inv = 1.0 / self.slope;
        free.iter_mut().for_each(|c| *c *= inv);
    }

    /// Force per width of spring j now.
    pub fn force(&self, j: usize) -> f64 {
        let n = self.springs();
        self.relaxed * self.u[j]
            + (0..self.terms())
                .map(|k| self.moduli[k] * self.w[k * n + j])
                .sum::<f64>()
    }

    /// Moves every spring linearly to `u_new` over the step; returns the energy per width
    /// dissipated in the dashpots during the step, summed over the springs (exact for
    /// the linear histories). `du` is scratch of the row's length.
    pub fn advance(&mut self, u_new: &[f64], du: &mut [f64]) -> f64 {
        let n = self.springs();
        for ((d, &un), &u) in du.iter_mut().zip(u_new).zip(&self.u) {
            *d = un - u;
        }
        let mut diss = 0.0;
        for k in 0..self.terms() {
            let (a, beta, tau) = (self.a[k], self.beta[k], self.taus[k]);
            // w(s) = b + (w0 - b) exp(-s/tau), b = tau du/dt: Int w^2 ds exactly.
            let (rate, dt) = (tau / self.dt, self.dt);
            let (c1, c2) = (2.0 * tau * self.one_a[k], 0.5 * tau * self.one_a2[k]);
            let w = &mut self.w[k * n..(k + 1) * n];
            let step = |wk: &mut f64, d: f64| -> f64 {
                let w0 = *wk;
                let b = rate * d;
                let c = w0 - b;
                *wk = a * w0 + beta * d;
                b * b * dt + b * c * c1 + c * c * c2
            };
            // Four independent sums (vectorisable, fixed order).
            let mut sum = [0.0f64; 4];
            let mut wc = w.chunks_exact_mut(4);
            let mut dc = du.chunks_exact(4);
            for (wq, dq) in (&mut wc).zip(&mut dc) {
                for l in 0..4 {
                    sum[l] += step(&mut wq[l], dq[l]);
                }
            }
            for (wk, &d) in wc.into_remainder().iter_mut().zip(dc.remainder()) {
                sum[0] += step(wk, d);
            }
            diss += self.loss[k] * ((sum[0] + sum[1]) + (sum[2] + sum[3]));
        }
        self.u.copy_from_slice(u_new);
        diss
    }

    /// Removes from every internal variable the homogeneous (decaying) part implied by
    /// its mean over the last `steps` steps, and moves every spring by the common
    /// creep `creep` (module docs).
    pub fn settle(&mut self, mean: &[f64], steps: usize, creep: f64) {
        let p = steps as f64;
        // c a^P = <w> a^P / <a^n>, <a^n> = a (1 - a^P) / (P (1 - a)).
        let factor: Vec<f64> = self
            .taus
            .iter()
            .map(|&tau| {
                let x = self.dt / tau;
                let one_a = -(-x).exp_m1();
                let one_ap = -(-p * x).exp_m1();
                p * one_a * (-(p - 1.0) * x).exp() / one_ap
            })
            .collect();
        let n = self.springs();
        for (i, w) in self.w.iter_mut().enumerate() {
            *w -= factor[i / n] * mean[i];
        }
        self.u.iter_mut().for_each(|u| *u += creep);
    }
}

/// The sliding experiment's parameters.
#[derive(Debug, Clone)]
pub struct Sliding {
    /// Spring modulus M(t) (= 4 G(t) for an incompressible elastomer, Eq. 62).
    pub modulus: Prony,
    /// Number of springs; the line's point count must be a multiple of it.
    pub springs: usize,
    /// Line points the line moves per time step (dt = stride dx_line / v).
    pub stride: usize,
    pub normal_force: f64,
    pub velocity: f64,
    /// Steady state: mu changes by less than this (relative) between two passes.
    pub tolerance: f64,
    pub max_passes: usize,
    /// Settle the slow variables after each pass (module docs); without it, the
    /// natural dynamics (for verification: both reach the same steady state).
    pub accelerate: bool,
}

/// The steady state of one sliding run.
#[derive(Debug, Clone, PartialEq)]
pub struct SlidingResult {
    /// mu = <F_x> / F_N over the last pass (F_x from the slopes).
    pub mu: f64,
    /// Dissipated energy per unit sliding distance over F_N (last pass).
    pub mu_energy: f64,
    /// Mean fraction of springs in contact.
    pub contact_fraction: f64,
    /// Mean approach.
    pub depth: f64,
    /// mu of every pass (the last is the result).
    pub history: Vec<f64>,
    /// Whether two consecutive passes agreed to the tolerance within max_passes.
    pub converged: bool,
}

/// Approach d with A sum (d - e)+ = target (A > 0, target > 0), exact, from `start`.
fn carry(e: &[f64], a: f64, target: f64, start: f64) -> f64 {
    let goal = target / a;
    let mut d = start;
    let mut last = (usize::MAX, f64::NAN);
    for _ in 0..100 {
        let (mut cnt, mut sum) = (0usize, 0.0);
        for &x in e {
            if x < d {
                cnt += 1;
                sum += x;
            }
        }
        if cnt == 0 {
            d = e.iter().fold(f64::INFINITY, |m, &x| m.min(x)) + goal;
            continue;
        }
        if (cnt, sum) == last {
            return d;
        }
        last = (cnt, sum);
        d = (goal + sum) / cnt as f64;
    }
    // Fallback (never seen): sort and invert the piecewise-linear law.
    let mut s = e.to_vec();
    s.sort_by(f64::total_cmp);
    let mut sum = 0.0;
    for (m, &x) in s.iter().enumerate() {
        sum += x;
        let d = (goal + sum) / (m + 1) as f64;
        if m + 1 == s.len() || d <= s[m + 1] {
            return d;
        }
    }
    unreachable!("a non-empty row carries any load")
}

/// The sliding state, advanced one time step at a time (module docs).
pub struct Slider<'a> {
    line: &'a Line,
    p: &'a Sliding,
    row: MaxwellRow,
    /// Line points per spring, spring width, A = dx (M_inf + sum M_k beta_k).
    s: usize,
    dx: f64,
    a: f64,
    /// Steps per pass (the line moves by its length).
    pub steps: usize,
    step: usize,
    /// The approach of the last step.
    pub depth: f64,
    e: Vec<f64>,
    free: Vec<f64>,
    u_new: Vec<f64>,
    scratch: Vec<f64>,
}

/// What one step measured.
#[derive(Debug, Clone, Copy, Default)]
pub struct StepResult {
    /// sum_j f_j z'(x_j).
    pub friction: f64,
    /// Energy dissipated during the step.
    pub dissipation: f64,
    pub contacts: usize,
    /// sum_j u_j.
    pub displacement: f64,
}

impl<'a> Slider<'a> {
    pub fn new(line: &'a Line, p: &'a Sliding) -> Result<Self> {
        positive("normal_force", p.normal_force)?;
        positive("velocity", p.velocity)?;
        if p.modulus.relaxed <= 0.0 {
            return Err(MrdError::InvalidParameter {
                name: "relaxed modulus",
                value: p.modulus.relaxed,
                reason:
                    "must be > 0: without it the line sinks without end under a constant normal force",
            });
        }
        let n_line = line.len();
        for (name, v) in [("springs", p.springs), ("stride", p.stride)] {
            if v == 0 || !n_line.is_multiple_of(v) {
                return Err(MrdError::InvalidParameter {
                    name,
                    value: v as f64,
                    reason: "must divide the line's number of points",
                });
            }
        }
        let ns = p.springs;
        let dx = line.length / ns as f64;
        let dt = p.stride as f64 * line.length / n_line as f64 / p.velocity;
        let row = MaxwellRow::new(&p.modulus, ns, dt)?;
        Ok(Self {
            line,
            p,
            s: n_line / ns,
            dx,
            a: dx * row.slope(),
            steps: n_line / p.stride,
            step: 0,
            depth: 0.0,
            row,
            e: vec![0.0; ns],
            free: vec![0.0; ns],
            u_new: vec![0.0; ns],
            scratch: vec![0.0; ns],
        })
    }

    /// One time step: the line moves by `stride` points, the approach carries the
    /// normal force, every spring moves.
    pub fn step(&mut self) -> StepResult {
        let (line, n_line, ns, s) = (self.line, self.line.len(), self.p.springs, self.s);
        self.step += 1;
        let offset = (self.step * self.p.stride) % n_line;
        self.row.free(&mut self.free);
        for j in 0..ns {
            self.e[j] = line.gaps[(j * s + offset) % n_line] + self.free[j];
        }
        self.depth = carry(&self.e, self.a, self.p.normal_force, self.depth);
        let mut r = StepResult::default();
        for j in 0..ns {
            let i = (j * s + offset) % n_line;
            let u = (self.depth - line.gaps[i]).max(self.free[j]);
            let f = self.a * (u - self.free[j]);
            if f > 0.0 {
                r.contacts += 1;
            }
            r.friction += f * line.slopes[i];
            self.u_new[j] = u;
            r.displacement += u;
        }
        r.dissipation = self.dx * self.row.advance(&self.u_new, &mut self.scratch);
        r
    }
}

/// Slides `line` over the foundation until the periodic steady state (module docs).
pub fn slide(line: &Line, p: &Sliding) -> Result<SlidingResult> {
    let mut sl = Slider::new(line, p)?;
    let (steps, ns) = (sl.steps, p.springs);
    let mut history = Vec::new();
    let mut w_mean = vec![0.0; sl.row.w.len()];
    let mut last_depth = f64::NAN;
    loop {
        let (mut fx, mut diss, mut contacts, mut d_sum, mut u_sum) = (0.0, 0.0, 0usize, 0.0, 0.0);
        for _ in 0..steps {
            let r = sl.step();
            w_mean.iter_mut().zip(&sl.row.w).for_each(|(s, w)| *s += w);
            fx += r.friction;
            diss += r.dissipation;
            contacts += r.contacts;
            u_sum += r.displacement;
            d_sum += sl.depth;
        }
        let mu = fx / steps as f64 / p.normal_force;
        let mu_energy = diss / line.length / p.normal_force;
        let depth = d_sum / steps as f64;
        // mu near zero (at the ends of the velocity range) is judged against 1e-3 of the
        // rms slope, the scale of mu.
        let mu_scale = mu.abs().max(1e-3 * line.rms_slope);
        let converged = history
            .last()
            .is_some_and(|&prev: &f64| (mu - prev).abs() <= p.tolerance * mu_scale)
            && (depth - last_depth).abs() <= p.tolerance * line.rms_height;
        history.push(mu);
        last_depth = depth;
        if converged || history.len() >= p.max_passes {
            return Ok(SlidingResult {
                mu,
                mu_energy,
                contact_fraction: contacts as f64 / (steps * ns) as f64,
                depth,
                history,
                converged,
            });
        }
        // The common creep: in the steady state every spring has the same mean
        // displacement (the springs see the same periodic line, shifted in time), which
        // M_inf alone relates to the mean load F_N / ns (module docs).
        w_mean.iter_mut().for_each(|s| *s /= steps as f64);
        let creep = p.normal_force / (line.length * sl.row.relaxed()) - u_sum / (steps * ns) as f64;
        if p.accelerate {
            sl.row.settle(&w_mean, steps, creep);
            sl.depth += creep;
        }
        w_mean.iter_mut().for_each(|s| *s = 0.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::rel;
    use std::f64::consts::{PI, TAU};

    /// One spring driven by u = u0 sin(omega t) settles to f = u0 |M| sin(omega t + phi)
    /// with M' + i M'' the complex modulus: to 1e-9 at 2e5 steps per period, and the
    /// error falls at second order in dt.
    #[test]
    fn single_spring_follows_the_complex_modulus() {
        let m = Prony::new(1.0, vec![(3.0, 0.2), (10.0, 5.0), (0.5, 0.01)]).unwrap();
        let (u0, omega) = (1e-3, 2.0);
        let (re, im) = m.complex(omega);
        let mut errs = Vec::new();
        for per in [200usize, 400, 800, 200_000] {
            let dt = TAU / omega / per as f64;
            let mut row = MaxwellRow::new(&m, 1, dt).unwrap();
            let mut scratch = [0.0];
            // Start on the steady orbit of the slow term by running 30 periods (tau = 5
            // against a period of pi: e^-19 of the transient remains).
            let mut worst: f64 = 0.0;
            for step in 1..=(31 * per) {
                let t = step as f64 * dt;
                row.advance(&[u0 * (omega * t).sin()], &mut scratch);
                if step > 30 * per {
                    let exact = u0 * (re * (omega * t).sin() + im * (omega * t).cos());
                    worst = worst.max((row.force(0) - exact).abs());
                }
            }
            errs.push(worst / (u0 * re.hypot(im)));
        }
        assert!(errs[3] < 1e-9, "fine step: {}", errs[3]);
        for w in errs[..3].windows(2) {
            let order = (w[0] / w[1]).log2();
            assert!((order - 2.0).abs() < 0.15, "order {order} ({errs:?})");
        }
    }

    /// The exact dissipation of one cycle equals pi u0^2 M''(omega) per unit width.
    #[test]
    fn dissipation_per_cycle_is_pi_u0_squared_loss_modulus() {
        let m = Prony::new(1.0, vec![(3.0, 0.2), (10.0, 5.0)]).unwrap();
        let (u0, omega, per) = (1e-3, 2.0, 2000usize);
        let dt = TAU / omega / per as f64;
        let mut row = MaxwellRow::new(&m, 1, dt).unwrap();
        let mut scratch = [0.0];
        let mut diss = 0.0;
        for step in 1..=(31 * per) {
            let d = row.advance(&[u0 * (omega * step as f64 * dt).sin()], &mut scratch);
            if step > 30 * per {
                diss += d;
            }
        }
        assert!(
            rel(diss, PI * u0 * u0 * m.complex(omega).1) < 1e-5,
            "{diss}"
        );
    }

    /// A harmonic line in full contact against the closed form of
    /// [`crate::reference::sliding::harmonic_mu`], from slopes and from the dissipated
    /// energy: 5e-4 at 128 points per wavelength, converging at second order.
    #[test]
    fn harmonic_line_in_full_contact_matches_the_closed_form() {
        let m = Prony::new(1.0, vec![(30.0, 0.05), (8.0, 2.0)])
            .unwrap()
            .scaled(4.0);
        let (k_waves, h0, l) = (8usize, 1e-3, 1.0);
        let k = TAU * k_waves as f64 / l;
        let v = 1.0 / k; // omega = k v = 1
        let (re, im) = m.complex(k * v);
        let d_mean = 2.0 * h0 * re.hypot(im) / m.relaxed;
        let exact = crate::reference::sliding::harmonic_mu(k, h0, im, m.relaxed, d_mean);
        let mut errs = Vec::new();
        for per_wave in [32usize, 64, 128] {
            let n = per_wave * k_waves;
            let z: Vec<f64> = (0..n)
                .map(|i| h0 * (k * i as f64 * l / n as f64).cos())
                .collect();
            let line = Line::new(&z, l).unwrap();
            assert!(rel(line.wave_vector(), k) < 1e-9);
            let r = slide(
                &line,
                &Sliding {
                    modulus: m.clone(),
                    springs: n,
                    stride: 1,
                    normal_force: m.relaxed * d_mean * l,
                    velocity: v,
                    tolerance: 1e-10,
                    max_passes: 60,
                    accelerate: true,
                },
            )
            .unwrap();
            assert!(r.converged && r.contact_fraction == 1.0, "{r:?}");
            assert!(
                rel(r.depth - h0, d_mean) < 1e-9,
                "mean indentation {} vs {d_mean}: {r:?}",
                r.depth - h0
            );
            errs.push((rel(r.mu, exact), rel(r.mu_energy, exact)));
        }
        assert!(errs[2].0 < 5e-4 && errs[2].1 < 5e-4, "{errs:?}");
        for w in errs.windows(2) {
            for (a, b) in [(w[0].0, w[1].0), (w[0].1, w[1].1)] {
                let order = (a / b).log2();
                assert!(order > 1.8, "order {order}: {errs:?}");
            }
        }
    }

    /// The approach solve inverts the convex piecewise-linear force law exactly.
    #[test]
    fn carry_is_exact() {
        let e = [0.3, -0.1, 0.25, 2.0, 0.0];
        for (target, start) in [(0.5, 0.0), (0.05, 5.0), (10.0, -3.0)] {
            let d = carry(&e, 2.0, target, start);
            let f: f64 = e.iter().map(|&x| 2.0 * (d - x).max(0.0)).sum();
            assert!(rel(f, target) < 1e-14, "{target}: {f}");
        }
    }
}
