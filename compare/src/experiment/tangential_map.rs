//! MRD's tangential law on any normal curve, shared by the rough partial-slip studies.
//!
//! In MRD a spring of indentation w sticks while G* u < mu E* w, so a contact held at
//! the normal force F_N and loaded by the tangential force Q shifts by
//! u(Q) = mu (E* / G*) [d(F_N) - d(F_N - Q / mu)], d(F) the approach of the normal curve
//! (the principle of Ciavarella and Jaeger, exact for every profile in MRD because the
//! springs are independent). Under a force oscillating with amplitude Q*, Masing's rule
//! gives the energy per cycle W = 4 (E* / G*) [Q* b(Q*) - 2 int_0^Q* b(Q) dQ] with
//! b(Q) = mu [d(F_N) - d(F_N - Q / mu)] (Section 7). [`Mapping`] holds b at the
//! requested forces and the integrals, so that one normal curve serves every Poisson's
//! ratio (E* / G* = (2 - nu) / (2 (1 - nu)) for a rigid indenter, Eqs. 2 and 5).
//! The same law with the approach as the variable, for a contact law that gives F(d)
//! (the ring-down's), is `mrd::reference::masing`.

use crate::checks::{bad, check_fractions};
use crate::error::Result;
use mrd::numerics::gauss::legendre;

/// Gauss-Legendre nodes of the integral of Masing's rule.
pub const NODES: usize = 12;

/// The amplitudes of Masing's energies, as fractions x of mu F_N. The energy per cycle
/// is of order x^2 relative to `Q* b(Q*)`, while each `b` carries the relative error
/// `tolerance` of the solves it differences: the energy's relative error is about
/// tolerance / x^2, so an amplitude below sqrt(1e4 tolerance) (0.01 at the default
/// 1e-8) would leave more than 1e-4 of the energy to the solver's stop (on coarse grids
/// the cells that enter and leave the contact add more there).
pub fn check_amplitudes(amplitudes: &[f64], tolerance: f64) -> Result<()> {
    check_fractions("amplitudes", amplitudes, false)?;
    let least = (1e4 * tolerance).sqrt();
    if let Some(x) = amplitudes.iter().find(|x| **x < least) {
        return bad(format!(
            "amplitudes: {x} of mu F_N is below {least:.3e} = sqrt(1e4 x tolerance {tolerance:e}): the energy per cycle (of order x^2 of Q* times the shift) would be left to the solvers' stop; raise the amplitude or lower tolerance"
        ));
    }
    Ok(())
}

/// E* / G* of a rigid indenter on a substrate of Poisson's ratio `nu` (Eqs. 2 and 5).
pub fn e_over_g(nu: f64) -> f64 {
    (2.0 - nu) / (2.0 * (1.0 - nu))
}

/// b(Q) = mu [d(F_N) - d(F_N - Q / mu)] at the fractions of mu F_N, and per amplitude
/// (Q*, b(Q*), int_0^Q* b dQ).
#[derive(Debug, Clone, PartialEq)]
pub struct Mapping {
    pub base: Vec<f64>,
    pub masing: Vec<(f64, f64, f64)>,
}

impl Mapping {
    /// `reduced(Q)` returns b(Q); `mu_fn` is mu F_N, `fractions` and `amplitudes` are
    /// fractions of it. Calls `reduced` once per fraction and `NODES + 1` times per
    /// amplitude, in that order.
    pub fn new(
        mu_fn: f64,
        fractions: &[f64],
        amplitudes: &[f64],
        mut reduced: impl FnMut(f64) -> Result<f64>,
    ) -> Result<Self> {
        let base: Vec<f64> = fractions
            .iter()
            .map(|x| reduced(x * mu_fn))
            .collect::<Result<_>>()?;
        let (xg, wg) = legendre(NODES);
        let mut masing = Vec::with_capacity(amplitudes.len());
        for a in amplitudes {
            let amp = a * mu_fn;
            let mut integral = 0.0;
            for (x, w) in xg.iter().zip(&wg) {
                integral += 0.5 * amp * w * reduced(0.5 * amp * (1.0 + x))?;
            }
            masing.push((amp, reduced(amp)?, integral));
        }
        Ok(Self { base, masing })
    }

    /// The shifts at the fractions on a substrate with E* / G* = `ratio`.
    pub fn shifts(&self, ratio: f64) -> Vec<f64> {
        self.base.iter().map(|u| u * ratio).collect()
    }

    /// The energies per cycle at the amplitudes (Masing's rule) with E* / G* = `ratio`.
    pub fn energies(&self, ratio: f64) -> Vec<f64> {
        self.masing
            .iter()
            .map(|(amp, u, int)| 4.0 * ratio * (amp * u - 2.0 * int))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hertz_gives_mindlin_and_the_mindlin_deresiewicz_energy() {
        // Hertz, d(F) = c F^(2/3), x = Q / (mu F): Mindlin's shift
        // u = (E*/G*) mu c F^(2/3) [1 - (1 - x)^(2/3)], and Masing's energy from
        // int_0^Q* b dQ = mu^2 c F^(5/3) [x - 3/5 (1 - (1 - x)^(5/3))] (Mindlin-Deresiewicz).
        let (mu, f, c) = (0.4, 2.0, 0.7);
        let d = |g: f64| c * g.powf(2.0 / 3.0);
        let m = Mapping::new(mu * f, &[0.3, 0.9], &[0.5, 0.95], |q| {
            Ok(mu * (d(f) - d(f - q / mu)))
        })
        .unwrap();
        let ratio = e_over_g(0.5);
        for (x, u) in [0.3f64, 0.9].iter().zip(m.shifts(ratio)) {
            let exact = ratio * mu * d(f) * (1.0 - (1.0 - x).powf(2.0 / 3.0));
            assert!((u / exact - 1.0).abs() < 1e-14, "{u} {exact}");
        }
        for (x, w) in [0.5f64, 0.95].iter().zip(m.energies(ratio)) {
            let int =
                mu * c * f.powf(2.0 / 3.0) * mu * f * (x - 0.6 * (1.0 - (1.0 - x).powf(5.0 / 3.0)));
            let b = mu * c * f.powf(2.0 / 3.0) * (1.0 - (1.0 - x).powf(2.0 / 3.0));
            let exact = 4.0 * ratio * (x * mu * f * b - 2.0 * int);
            // Twelve Gauss nodes on the (1 - x)^(2/3) endpoint behaviour.
            assert!((w / exact - 1.0).abs() < 2e-4, "x = {x}: {w} {exact}");
        }
        assert_eq!(e_over_g(0.0), 1.0);
    }

    /// The least amplitude follows the tolerance: 0.01 at 1e-8, 1e-4 at 1e-12.
    #[test]
    fn amplitudes_below_the_solvers_resolution_are_refused() {
        let e = check_amplitudes(&[0.3, 1e-3], 1e-8)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("amplitudes: 0.001") && e.contains("1.000e-2"),
            "{e}"
        );
        assert!(check_amplitudes(&[0.01, 0.5], 1e-8).is_ok());
        assert!(check_amplitudes(&[1e-3], 1e-12).is_ok());
        assert!(check_amplitudes(&[1e-5], 1e-12).is_err());
        assert!(check_amplitudes(&[1.0], 1e-8).is_err());
    }
}
