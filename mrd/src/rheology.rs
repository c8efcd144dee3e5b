//! Linear viscoelastic materials (Section 8): relaxation moduli as Prony series, the
//! continuous relaxation spectrum of Eq. (84), and their complex moduli.
//!
//! A modulus relaxes as M(t) = M_inf + sum_k M_k exp(-t/tau_k) (a generalised Maxwell
//! model); its complex modulus is M(omega) = M_inf + sum_k M_k i omega tau_k /
//! (1 + i omega tau_k), so M'(omega) = M_inf + sum_k M_k w^2 / (1 + w^2) and
//! M''(omega) = sum_k M_k w / (1 + w^2), w = omega tau_k. The MRD springs of an
//! incompressible elastomer against a rigid body carry E*(t) = 4 G(t) (Eq. 62).
//!
//! Eq. (84): G(t) = G0 + G1 tau1 Int_{tau1}^{tau2} tau^(-s) exp(-t/tau) dtau. For s = 2
//! both G(t) and G(omega) are closed forms (derived below); any s by quadrature. It is
//! discretised into a Prony series by Gauss-Legendre quadrature in ln tau, which
//! converges exponentially: [`Eq84::prony`] with its measured accuracy.

use crate::error::{positive, MrdError, Result};
use crate::numerics::quad::tanh_sinh;

/// A relaxation modulus as a Prony series.
#[derive(Debug, Clone, PartialEq)]
pub struct Prony {
    /// Long-time (relaxed) modulus M_inf >= 0.
    pub relaxed: f64,
    /// (M_k > 0, tau_k > 0) pairs.
    pub terms: Vec<(f64, f64)>,
}

impl Prony {
    pub fn new(relaxed: f64, terms: Vec<(f64, f64)>) -> Result<Self> {
        crate::error::non_negative("relaxed modulus", relaxed)?;
        for &(m, tau) in &terms {
            positive("prony modulus", m)?;
            positive("relaxation time", tau)?;
        }
        if relaxed == 0.0 && terms.is_empty() {
            return Err(MrdError::InvalidParameter {
                name: "relaxed modulus",
                value: 0.0,
                reason: "the modulus must not vanish",
            });
        }
        Ok(Self { relaxed, terms })
    }

    /// M(t).
    pub fn at(&self, t: f64) -> f64 {
        self.relaxed
            + self
                .terms
                .iter()
                .map(|&(m, tau)| m * (-t / tau).exp())
                .sum::<f64>()
    }

    /// Instantaneous (glassy) modulus M(0).
    pub fn glassy(&self) -> f64 {
        self.relaxed + self.terms.iter().map(|t| t.0).sum::<f64>()
    }

    /// (M'(omega), M''(omega)).
    pub fn complex(&self, omega: f64) -> (f64, f64) {
        let (mut re, mut im) = (self.relaxed, 0.0);
        for &(m, tau) in &self.terms {
            let w = omega * tau;
            let d = 1.0 + w * w;
            re += m * w * w / d;
            im += m * w / d;
        }
        (re, im)
    }

    /// The factors of a time step dt of the hereditary integrals
    /// `h_k(t) = Int exp(-(t - t')/tau_k) du/dt' dt'`, exact for u linear over the step:
    /// `h_k <- a_k h_k + b_k du` with `a_k = exp(-dt/tau_k)`, `b_k = (tau_k/dt)(1 - a_k)`;
    /// and the step's effective modulus `M_inf + sum_k M_k b_k` (the response to du).
    pub fn step_factors(&self, dt: f64) -> (Vec<(f64, f64)>, f64) {
        let ab: Vec<(f64, f64)> = self
            .terms
            .iter()
            .map(|&(_, tau)| {
                let x = -dt / tau;
                (x.exp(), -x.exp_m1() * tau / dt)
            })
            .collect();
        let effective = self.relaxed
            + self
                .terms
                .iter()
                .zip(&ab)
                .map(|(t, c)| t.0 * c.1)
                .sum::<f64>();
        (ab, effective)
    }

    /// The same material with every modulus times `factor` (e.g. 4 for E* = 4 G).
    pub fn scaled(&self, factor: f64) -> Self {
        Self {
            relaxed: self.relaxed * factor,
            terms: self.terms.iter().map(|&(m, t)| (m * factor, t)).collect(),
        }
    }
}

/// The continuous relaxation spectrum of Eq. (84).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eq84 {
    pub g0: f64,
    pub g1: f64,
    pub tau1: f64,
    pub tau2: f64,
    pub s: f64,
}

impl Eq84 {
    /// The paper's example: G0 = 1 MPa, G1 = 1000 MPa, tau1 = 1e-2 s, tau2 = 1e2 s,
    /// s = 2 (moduli in MPa).
    pub const PAPER: Eq84 = Eq84 {
        g0: 1.0,
        g1: 1000.0,
        tau1: 1e-2,
        tau2: 1e2,
        s: 2.0,
    };

    pub fn new(g0: f64, g1: f64, tau1: f64, tau2: f64, s: f64) -> Result<Self> {
        crate::error::non_negative("g0", g0)?;
        positive("g1", g1)?;
        positive("tau1", tau1)?;
        positive("tau2", tau2)?;
        if tau2 <= tau1 {
            return Err(MrdError::InvalidParameter {
                name: "tau2",
                value: tau2,
                reason: "must exceed tau1",
            });
        }
        if !s.is_finite() {
            return Err(MrdError::InvalidParameter {
                name: "s",
                value: s,
                reason: "must be finite",
            });
        }
        Ok(Self {
            g0,
            g1,
            tau1,
            tau2,
            s,
        })
    }

    fn closed_form(&self) -> bool {
        self.s == 2.0
    }

    /// G(t) (Eq. 84). For s = 2, with u = 1/tau: G1 tau1 Int u^0 exp(-t u) du
    /// = G1 tau1 (exp(-t/tau2) - exp(-t/tau1)) / t.
    pub fn relaxation(&self, t: f64) -> Result<f64> {
        let (g1, t1, t2) = (self.g1, self.tau1, self.tau2);
        if t == 0.0 {
            return Ok(self.glassy());
        }
        if self.closed_form() {
            // exp(-t/t2) - exp(-t/t1) without cancellation for small t.
            let diff = (-t / t2).exp() * -(-(t / t1 - t / t2)).exp_m1();
            return Ok(self.g0 + g1 * t1 * diff / t);
        }
        let s = self.s;
        let q = tanh_sinh(
            |x: f64| x.exp().powf(1.0 - s) * (-t / x.exp()).exp(),
            t1.ln(),
            t2.ln(),
            1e-13,
        )?;
        Ok(self.g0 + g1 * t1 * q)
    }

    /// G(0) = G0 + G1 tau1 Int tau^(-s) dtau.
    pub fn glassy(&self) -> f64 {
        let (t1, t2, s) = (self.tau1, self.tau2, self.s);
        let integral = if (s - 1.0).abs() < 1e-12 {
            (t2 / t1).ln()
        } else {
            (t2.powf(1.0 - s) - t1.powf(1.0 - s)) / (1.0 - s)
        };
        self.g0 + self.g1 * t1 * integral
    }

    /// (G'(omega), G''(omega)). For s = 2:
    /// G(omega) - G0 = G1 tau1 i omega Int tau^-1 / (1 + i omega tau) dtau
    ///              = G1 tau1 i omega [ln(tau2/tau1) - ln((1 + i omega tau2)/(1 + i omega tau1))],
    /// so G' - G0 = G1 tau1 omega (atan omega tau2 - atan omega tau1) and
    /// G'' = G1 tau1 omega [ln(tau2/tau1) - ln((1 + omega^2 tau2^2)/(1 + omega^2 tau1^2))/2].
    pub fn complex(&self, omega: f64) -> Result<(f64, f64)> {
        let (g1, t1, t2) = (self.g1, self.tau1, self.tau2);
        if self.closed_form() {
            let (w1, w2) = (omega * t1, omega * t2);
            let re = self.g0 + g1 * t1 * omega * (w2.atan() - w1.atan());
            // ln(t2/t1) - ln((1+w2^2)/(1+w1^2))/2 = ln(w2/w1) - ... written for accuracy:
            // = ln(t2/t1) - (ln_1p(w2^2) - ln_1p(w1^2))/2.
            let im = g1
                * t1
                * omega
                * ((t2 / t1).ln() - 0.5 * (w2 * w2).ln_1p() + 0.5 * (w1 * w1).ln_1p());
            return Ok((re, im));
        }
        let s = self.s;
        let part = |f: &dyn Fn(f64) -> f64| tanh_sinh(f, t1.ln(), t2.ln(), 1e-13);
        // In x = ln tau: tau^(1-s) w^2/(1+w^2) and tau^(1-s) w/(1+w^2), w = omega tau.
        let re = part(&|x: f64| {
            let tau = x.exp();
            let w = omega * tau;
            tau.powf(1.0 - s) * w * w / (1.0 + w * w)
        })?;
        let im = part(&|x: f64| {
            let tau = x.exp();
            let w = omega * tau;
            tau.powf(1.0 - s) * w / (1.0 + w * w)
        })?;
        Ok((self.g0 + g1 * t1 * re, g1 * t1 * im))
    }

    /// The spectrum discretised into `n` Prony terms: Gauss-Legendre nodes in
    /// x = ln tau on [ln tau1, ln tau2], G_j = w_j G1 tau1 tau_j^(1-s).
    pub fn prony(&self, n: usize) -> Result<Prony> {
        if n == 0 {
            return Err(MrdError::InvalidParameter {
                name: "prony_terms",
                value: 0.0,
                reason: "need at least one term",
            });
        }
        let (x, w) = crate::numerics::gauss::legendre(n);
        let (a, b) = (self.tau1.ln(), self.tau2.ln());
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let terms = x
            .iter()
            .zip(&w)
            .map(|(&xi, &wi)| {
                let tau = (mid + half * xi).exp();
                (
                    half * wi * self.g1 * self.tau1 * tau.powf(1.0 - self.s),
                    tau,
                )
            })
            .collect();
        Prony::new(self.g0, terms)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::rel;

    #[test]
    fn eq84_closed_forms_agree_with_quadrature() {
        // s = 2 closed forms against the general quadrature path (s = 2 + 1e-12 is
        // indistinguishable in value but takes the quadrature branch).
        let m = Eq84::PAPER;
        let q = Eq84 {
            s: 2.0 + 1e-12,
            ..m
        };
        for t in [1e-5, 1e-2, 0.3, 10.0, 1e3] {
            assert!(
                rel(m.relaxation(t).unwrap(), q.relaxation(t).unwrap()) < 1e-9,
                "t {t}"
            );
        }
        for om in [1e-5, 1e-2, 1.0, 30.0, 1e4] {
            let (a, b) = (m.complex(om).unwrap(), q.complex(om).unwrap());
            assert!(rel(a.0, b.0) < 1e-9 && rel(a.1, b.1) < 1e-9, "omega {om}");
        }
        // Limits: G(0) and G(inf); G'(inf) = G(0), G'(0) = G0, G'' -> 0 at both ends.
        assert!(rel(m.glassy(), 1.0 + 1000.0 * (1.0 - 1e-4)) < 1e-15);
        assert!(rel(m.relaxation(1e9).unwrap(), 1.0) < 1e-12);
        assert!(rel(m.complex(1e9).unwrap().0, m.glassy()) < 1e-6);
        assert!(rel(m.complex(1e-9).unwrap().0, 1.0) < 1e-6);
        assert!(m.complex(1e-9).unwrap().1 < 1e-5 && m.complex(1e9).unwrap().1 < 1e-3);
    }

    /// The stated accuracy of the Prony discretisation of Eq. (84) (paper values), the
    /// worst relative error of G(t) for t in [1e-4, 1e4] s and of G', G'' (relative to
    /// |G|) for omega in [1e-8, 1e4] rad/s: 12 terms 2e-3, 16 terms 1e-4, 20 terms 1e-5,
    /// 32 terms 3e-9 (exponential convergence, about 10x per 4 terms; the worst point is
    /// near t = omega^-1 = 1-10 s, inside the spectrum).
    #[test]
    fn prony_discretisation_of_eq84() {
        let m = Eq84::PAPER;
        for (n, tol) in [(12usize, 3e-3), (16, 2e-4), (20, 2e-5), (32, 1e-8)] {
            let p = m.prony(n).unwrap();
            assert!(rel(p.glassy(), m.glassy()) < 1e-12);
            let mut worst: f64 = 0.0;
            for k in 0..=80 {
                let t = 10f64.powf(-4.0 + 8.0 * k as f64 / 80.0);
                worst = worst.max(rel(p.at(t), m.relaxation(t).unwrap()));
            }
            for k in 0..=120 {
                let om = 10f64.powf(-8.0 + 12.0 * k as f64 / 120.0);
                let (re, im) = m.complex(om).unwrap();
                let (pr, pi) = p.complex(om);
                let mag = re.hypot(im);
                worst = worst.max(rel(pr, re)).max((pi - im).abs() / mag);
            }
            assert!(worst < tol, "{n} terms: {worst}");
        }
    }

    #[test]
    fn prony_complex_modulus_limits() {
        let p = Prony::new(2.0, vec![(3.0, 0.1), (5.0, 10.0)]).unwrap();
        assert_eq!(p.complex(0.0), (2.0, 0.0));
        let (re, im) = p.complex(1e12);
        assert!(rel(re, 10.0) < 1e-9 && im < 1e-9);
        // A single Maxwell term peaks in loss at omega tau = 1 with M''/M_k = 1/2.
        let m = Prony::new(0.0, vec![(4.0, 0.5)]).unwrap();
        assert!(rel(m.complex(2.0).1, 2.0) < 1e-15);
        assert_eq!(p.scaled(4.0).glassy(), 40.0);
    }
}
