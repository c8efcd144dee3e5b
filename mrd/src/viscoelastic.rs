//! Viscoelastic normal contact on the MRD foundation (Section 8, Eqs. 62-63).
//!
//! Each spring carries `f(t) = dx Int_{-inf}^t E*(t - t') du/dt' dt'` (Eq. 63 with
//! E*(t) = 4 G(t) for an incompressible medium), u = d(t) - z1d(x) while in contact. The
//! relaxation modulus is a Prony series `E*(t) = E_inf + sum_i E_i exp(-t/tau_i)`, whose
//! hereditary integrals are updated recursively, exactly for piecewise-linear u(t).
//! During monotonic indentation the contact radius never shrinks and the result equals
//! Radok's (1957) solution `F(t) = Int_0^t E*(t - s) dF_el/ds ds / E*` built on the
//! elastic force-depth law, which [`radok_force`] evaluates by quadrature.

use crate::error::{positive, MrdError, Result};
use crate::profile::Profile;

pub use crate::rheology::Prony;

/// Time-steps the spring row under a prescribed depth history `depth(t)` sampled at
/// `times` (increasing, from 0 with depth 0), with `n_half` springs on [0, half_length]
/// (mirrored). Returns the force at each time.
pub fn simulate(
    profile: &Profile,
    modulus: &Prony,
    depth: &dyn Fn(f64) -> f64,
    times: &[f64],
    n_half: usize,
    half_length: f64,
) -> Result<Vec<f64>> {
    positive("half_length", half_length)?;
    if n_half < 2 || times.len() < 2 || times.windows(2).any(|w| w[1] <= w[0]) {
        return Err(MrdError::InvalidParameter {
            name: "times",
            value: times.len() as f64,
            reason: "need >= 2 increasing times and >= 2 springs",
        });
    }
    let (l, dx, gaps) = crate::foundation::half_line(profile, n_half, half_length)?;
    let m = modulus.terms.len();
    // Per spring: current u and one hereditary variable per Prony term.
    let mut u = vec![0.0f64; n_half];
    let mut h = vec![0.0f64; n_half * m];
    let mut out = Vec::with_capacity(times.len());
    let force = |u: &[f64], h: &[f64]| -> f64 {
        let mut f = 0.0;
        for i in 0..n_half {
            f += modulus.relaxed * u[i]
                + (0..m)
                    .map(|k| modulus.terms[k].0 * h[i * m + k])
                    .sum::<f64>();
        }
        2.0 * dx * f
    };
    out.push(force(&u, &h));
    for w in times.windows(2) {
        let dt = w[1] - w[0];
        let d = depth(w[1]);
        let decay: Vec<(f64, f64)> = modulus
            .terms
            .iter()
            .map(|&(_, tau)| {
                let a = (-dt / tau).exp();
                (a, tau / dt * (1.0 - a)) // exact for u linear over the step
            })
            .collect();
        for i in 0..n_half {
            let u_new = (d - gaps[i]).max(0.0);
            let du = u_new - u[i];
            for (k, &(a, b)) in decay.iter().enumerate() {
                h[i * m + k] = a * h[i * m + k] + b * du;
            }
            u[i] = u_new;
        }
        if u.last().is_some_and(|&v| v > 0.0) && profile.rim().is_none() {
            return Err(MrdError::OutOfRange {
                needed: f64::INFINITY,
                limit: l,
            });
        }
        out.push(force(&u, &h));
    }
    Ok(out)
}

/// Radok's solution for monotonic indentation: `F(t) = Int_0^t E*(t - s) dPhi(d(s))/ds ds`
/// with Phi(d) = F_el(d)/E* the elastic force-depth law at unit modulus, by quadrature
/// (d' from the given derivative; `breaks` are times where d' jumps).
pub fn radok_force(
    profile: &Profile,
    modulus: &Prony,
    depth: &dyn Fn(f64) -> f64,
    depth_rate: &dyn Fn(f64) -> f64,
    breaks: &[f64],
    t: f64,
) -> Result<f64> {
    let unit = crate::normal::AxisymmetricContact::new(profile.clone(), 1.0)?;
    // dPhi/ds = dF/dd (unit modulus) * d'(s) = 2 a(d(s)) d'(s)   (Eq. 20)
    let integrand = |s: f64| -> f64 {
        let a = unit
            .state_at_depth(depth(s).max(0.0))
            .map(|st| st.radius)
            .unwrap_or(f64::NAN);
        modulus.at(t - s) * 2.0 * a * depth_rate(s)
    };
    crate::numerics::quad::tanh_sinh_split(integrand, 0.0, t, breaks, 1e-11)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::Shape;

    #[test]
    fn ramp_into_standard_linear_solid_matches_radok() {
        // Sphere R = 1, d = v t, E*(t) = 1 + 4 exp(-t/0.5), t in [0, 2].
        let p = Profile::single(Shape::paraboloid(1.0).unwrap());
        let g = Prony::new(1.0, vec![(4.0, 0.5)]).unwrap();
        let v = 0.05;
        let times: Vec<f64> = (0..=400).map(|k| 2.0 * k as f64 / 400.0).collect();
        let f = simulate(&p, &g, &|t| v * t, &times, 20_000, 0.5).unwrap();
        for &k in &[100usize, 200, 400] {
            let exact = radok_force(&p, &g, &|t| v * t, &|_| v, &[], times[k]).unwrap();
            // Stated tolerance: 2e-3 at 20000 springs and 400 steps.
            assert!(
                (f[k] / exact - 1.0).abs() < 2e-3,
                "t = {}: {} vs {exact}",
                times[k],
                f[k]
            );
        }
        // Limits: a purely elastic modulus gives Hertz.
        let el = Prony::new(3.0, vec![]).unwrap();
        let fe = simulate(&p, &el, &|t| v * t, &times, 20_000, 0.5).unwrap();
        let hertz = crate::reference::hertz::force(3.0, 1.0, 0.1);
        assert!((fe[400] / hertz - 1.0).abs() < 1e-3);
    }

    #[test]
    fn relaxation_at_fixed_depth() {
        // Step to d0 then hold: F(t) = E*(t) Phi(d0) for the flat punch (contact fixed).
        let p = Profile::flat_punch(0.5).unwrap();
        let g = Prony::new(1.0, vec![(2.0, 1.0)]).unwrap();
        let times: Vec<f64> = (0..=1000).map(|k| 5.0 * k as f64 / 1000.0).collect();
        let d0 = 0.01;
        let ramp = 0.005; // reach d0 linearly in one step of 0.005
        let f = simulate(
            &p,
            &g,
            &|t| if t < ramp { d0 * t / ramp } else { d0 },
            &times,
            100,
            0.5,
        )
        .unwrap();
        let at = |t: f64| {
            // Radok for a linear ramp then hold on a flat punch (Phi = 2 a d).
            let rate = d0 / ramp;
            let s1 = t.min(ramp);
            2.0 * 0.5 * rate * (1.0 * s1 + 2.0 * 1.0 * ((-(t - s1)).exp() - (-t).exp()))
        };
        for &k in &[1usize, 10, 200, 1000] {
            assert!((f[k] / at(times[k]) - 1.0).abs() < 1e-9, "t = {}", times[k]);
        }
        assert!(Prony::new(-1.0, vec![]).is_err());
        assert!(Prony::new(1.0, vec![(1.0, 0.0)]).is_err());
    }
}
