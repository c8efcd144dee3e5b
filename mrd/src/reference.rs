//! Closed-form solutions of classical contact mechanics, each with its source.
//!
//! These are the yardsticks the numerical paths are tested against; they are written
//! from the 3D literature forms, not from the MRD procedure. E* is the effective modulus
//! (Eq. 2), G* the tangential one (Eq. 5), gamma the work of adhesion.

use crate::profile::kappa;
use std::f64::consts::PI;

/// Hertz: sphere of radius R (paraboloid). Contact radius a = sqrt(R d).
pub mod hertz {
    pub fn radius(r: f64, d: f64) -> f64 {
        (r * d).sqrt()
    }
    /// F = 4/3 E* R^(1/2) d^(3/2).
    pub fn force(e_star: f64, r: f64, d: f64) -> f64 {
        4.0 / 3.0 * e_star * r.sqrt() * d.powf(1.5)
    }
    /// Depth under force F.
    pub fn depth(e_star: f64, r: f64, f: f64) -> f64 {
        (3.0 * f / (4.0 * e_star * r.sqrt())).powf(2.0 / 3.0)
    }
    /// p(r) = (2/pi) E* (d/R)^(1/2) sqrt(1 - r^2/a^2) (Eq. 30).
    pub fn pressure(e_star: f64, r_sphere: f64, d: f64, r: f64) -> f64 {
        let a = radius(r_sphere, d);
        if r >= a {
            0.0
        } else {
            2.0 / std::f64::consts::PI
                * e_star
                * (d / r_sphere).sqrt()
                * (1.0 - (r / a).powi(2)).sqrt()
        }
    }
}

/// Hertz's impact of a rigid sphere (radius R, mass m) on an elastic half-space at
/// speed v (Johnson, Contact Mechanics, 1985, Section 11.4, Eqs. 11.23-11.24): quasi-
/// static Hertz contact during the impact, no energy lost. The energy balance
/// `m v^2 / 2 = (8/15) E* sqrt(R) d^(5/2)` gives the largest approach; the duration is
/// `2 int_0^dmax dd / sqrt(v^2 - (16/15) E* sqrt(R) d^(5/2) / m)`, i.e. `c dmax / v` with
/// `c = (4/5) B(2/5, 1/2) = 2.9432...`.
pub mod hertz_impact {
    /// The largest approach [length].
    pub fn max_approach(e_star: f64, r: f64, m: f64, v: f64) -> f64 {
        (15.0 * m * v * v / (16.0 * e_star * r.sqrt())).powf(0.4)
    }
    /// The largest force [force].
    pub fn max_force(e_star: f64, r: f64, m: f64, v: f64) -> f64 {
        super::hertz::force(e_star, r, max_approach(e_star, r, m, v))
    }
    /// The duration coefficient `c = (4/5) B(2/5, 1/2)`.
    pub fn duration_coefficient() -> f64 {
        let beta = libm::tgamma(0.4) * libm::tgamma(0.5) / libm::tgamma(0.9);
        0.8 * beta
    }
    /// The contact duration [time].
    pub fn duration(e_star: f64, r: f64, m: f64, v: f64) -> f64 {
        duration_coefficient() * max_approach(e_star, r, m, v) / v
    }
}

/// A rigid sphere (radius R, mass m) striking an elastic half-space at speed v with
/// zero-range adhesion of work w (the JKR limit; Johnson, Kendall & Roberts, Proc. R.
/// Soc. A 324 (1971) 301, and Johnson, Contact Mechanics, 1985, Section 5.5), the
/// contact quasi-static and the only loss the adhesive hysteresis:
///
/// - loading is Hertz's (surfaces adhere only where they touch, the model of the
///   review's Eq. 33 and of the 3D solver), so the largest approach is
///   [`hertz_impact::max_approach`] and the contact radius there `a_m = sqrt(R d_max)`;
/// - unloading first holds the radius `a_m` (the flat punch's line
///   `F = F_H(d_max) - 2 a_m E* (d_max - d)`) until it meets JKR's curve at `a_m`, then
///   follows JKR's curve `d(a) = a^2 / R - sqrt(2 pi w a / E*)`,
///   `F(a) = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3)` down to the radius where `dd/da = 0`,
///   `a_c = (pi w R^2 / (8 E*))^(1/3)` (separation under the approach a mass imposes),
///   or, if `a_m <= a_c`, separates where it meets the curve.
///
/// The work the contact gives back on unloading, `W_out`, is the kinetic energy left at
/// separation: the restitution is `sqrt(W_out / (m v^2 / 2))`, and the sphere is
/// captured where `W_out <= 0`.
pub mod adhesive_impact {
    use super::{hertz, hertz_impact, jkr};
    use std::f64::consts::PI;

    /// A force scale of the adhesive cycle: JKR's pull-off under force control,
    /// `3 pi w R / 2` [force].
    pub fn pull_off_scale(r: f64, w: f64) -> f64 {
        jkr::pull_off_force_control(r, w)
    }

    /// The radius of JKR's curve where the approach is least,
    /// `(pi w R^2 / (8 E*))^(1/3)` [length].
    pub fn separation_radius(e_star: f64, r: f64, w: f64) -> f64 {
        (PI * w * r * r / (8.0 * e_star)).cbrt()
    }

    /// The work given back from the largest approach to separation [force x length].
    pub fn work_returned(e_star: f64, r: f64, w: f64, m: f64, v: f64) -> f64 {
        let d_max = hertz_impact::max_approach(e_star, r, m, v);
        let a_m = hertz::radius(r, d_max);
        // The flat punch's line from d_max down to JKR's curve at a_m.
        let drop = (2.0 * PI * w * a_m / e_star).sqrt();
        let f_max = hertz::force(e_star, r, d_max);
        let punch = f_max * drop - a_m * e_star * drop * drop;
        let a_c = separation_radius(e_star, r, w);
        if a_m <= a_c {
            return punch;
        }
        // Along JKR's curve: the integral of F dd from a_c to a_m.
        let slope = |a: f64| 2.0 * a / r - 0.5 * (2.0 * PI * w / (e_star * a)).sqrt();
        let curve = crate::numerics::quad::tanh_sinh(
            |a| jkr::force(e_star, r, w, a) * slope(a),
            a_c,
            a_m,
            1e-12,
        )
        .unwrap_or(f64::NAN);
        punch + curve
    }

    /// The coefficient of restitution (0: captured).
    pub fn restitution(e_star: f64, r: f64, w: f64, m: f64, v: f64) -> f64 {
        let back = work_returned(e_star, r, w, m, v);
        if back <= 0.0 {
            0.0
        } else {
            (back / (0.5 * m * v * v)).sqrt()
        }
    }

    /// The largest speed at which the sphere is captured (`W_out = 0`), by bisection in
    /// ln v [length / time].
    pub fn capture_speed(e_star: f64, r: f64, w: f64, m: f64) -> f64 {
        // A scale: the speed whose Hertz approach reaches JKR's separation depth's size.
        let a_c = separation_radius(e_star, r, w);
        let d = a_c * a_c / r;
        let scale = (16.0 / 15.0 * e_star * r.sqrt() * d.powf(2.5) / m).sqrt();
        let (mut lo, mut hi) = (1e-6 * scale, 1e6 * scale);
        for _ in 0..200 {
            let mid = (lo * hi).sqrt();
            if work_returned(e_star, r, w, m, mid) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        (lo * hi).sqrt()
    }
}

/// Cone of slope tan(theta) (Love 1939; Eqs. 31-32).
pub mod cone {
    use std::f64::consts::PI;
    /// a = 2 d / (pi tan theta).
    pub fn radius(tan_theta: f64, d: f64) -> f64 {
        2.0 * d / (PI * tan_theta)
    }
    /// F = 2 E* d^2 / (pi tan theta).
    pub fn force(e_star: f64, tan_theta: f64, d: f64) -> f64 {
        2.0 * e_star * d * d / (PI * tan_theta)
    }
    /// p(r) = E* tan(theta)/2 * arccosh(a/r) (Eq. 32).
    pub fn pressure(e_star: f64, tan_theta: f64, d: f64, r: f64) -> f64 {
        let a = radius(tan_theta, d);
        if r >= a {
            0.0
        } else {
            0.5 * e_star * tan_theta * (a / r).acosh()
        }
    }
}

/// Flat cylindrical punch of radius a (Boussinesq; Eqs. 1, 28).
pub mod flat_punch {
    use std::f64::consts::PI;
    pub fn force(e_star: f64, a: f64, d: f64) -> f64 {
        2.0 * a * e_star * d
    }
    /// p(r) = F / (2 pi a^2 sqrt(1 - r^2/a^2)) (Eq. 28).
    pub fn pressure(f: f64, a: f64, r: f64) -> f64 {
        if r >= a {
            0.0
        } else {
            f / (2.0 * PI * a * a * (1.0 - (r / a).powi(2)).sqrt())
        }
    }
}

/// Flattened paraboloid (Ejike 1981; Eqs. 24-25).
pub mod ejike {
    /// d(a) = a sqrt(a^2 - a0^2) / R (Eq. 24).
    pub fn depth(r: f64, a0: f64, a: f64) -> f64 {
        a * (a * a - a0 * a0).sqrt() / r
    }
    /// F(a) = 2E*/(3R) sqrt(a^2 - a0^2) (2a^2 + a0^2) (Eq. 25).
    pub fn force(e_star: f64, r: f64, a0: f64, a: f64) -> f64 {
        2.0 * e_star / (3.0 * r) * (a * a - a0 * a0).sqrt() * (2.0 * a * a + a0 * a0)
    }
}

/// Power-law indenter z = c r^n (Sneddon 1965; Eqs. 19-21 with the exact prefactor).
pub mod power_law {
    use super::kappa;
    /// d = kappa_n c a^n.
    pub fn depth(c: f64, n: f64, a: f64) -> f64 {
        kappa(n) * c * a.powf(n)
    }
    /// F = 2 E* n/(n+1) kappa_n c a^(n+1).
    pub fn force(e_star: f64, c: f64, n: f64, a: f64) -> f64 {
        2.0 * e_star * n / (n + 1.0) * kappa(n) * c * a.powf(n + 1.0)
    }
}

/// JKR adhesive sphere (Johnson, Kendall & Roberts 1971), parametric in a.
pub mod jkr {
    use std::f64::consts::PI;
    pub fn depth(e_star: f64, r: f64, gamma: f64, a: f64) -> f64 {
        a * a / r - (2.0 * PI * a * gamma / e_star).sqrt()
    }
    pub fn force(e_star: f64, r: f64, gamma: f64, a: f64) -> f64 {
        4.0 * e_star * a.powi(3) / (3.0 * r) - (8.0 * PI * gamma * e_star * a.powi(3)).sqrt()
    }
    /// Pull-off force magnitude under force control, 3/2 pi R gamma.
    pub fn pull_off_force_control(r: f64, gamma: f64) -> f64 {
        1.5 * PI * r * gamma
    }
    /// Force magnitude at separation under displacement control, 5/6 pi R gamma.
    pub fn pull_off_displacement_control(r: f64, gamma: f64) -> f64 {
        5.0 / 6.0 * PI * r * gamma
    }
}

/// Maugis-Dugdale adhesive sphere (Maugis 1992, J. Colloid Interface Sci. 150), in
/// Maugis' dimensionless variables: contact radius A = a (4 E* / (3 pi w R^2))^(1/3),
/// load P = F / (pi w R), parametric in m = c/a (c the outer radius of the cohesive zone),
/// for the Tabor-Maugis parameter lambda = sigma0 (9 R / (2 pi w E*^2))^(1/3).
pub mod maugis_dugdale {
    /// lambda of a cohesive stress sigma0.
    pub fn lambda(sigma0: f64, r: f64, w: f64, e_star: f64) -> f64 {
        sigma0 * (9.0 * r / (2.0 * std::f64::consts::PI * w * e_star * e_star)).cbrt()
    }
    /// (A, P) at m > 1: A from lambda A^2/2 [s + (m^2 - 2) atan s] + 4 lambda^2 A/3
    /// [s atan s - m + 1] = 1 with s = sqrt(m^2 - 1), then P = A^3 - lambda A^2
    /// [s + m^2 atan s].
    pub fn state(lambda: f64, m: f64) -> (f64, f64) {
        let s = (m * m - 1.0).sqrt();
        let at = s.atan();
        let qa = lambda / 2.0 * (s + (m * m - 2.0) * at);
        let qb = 4.0 * lambda * lambda / 3.0 * (s * at - m + 1.0);
        // The positive root of qa A^2 + qb A - 1 = 0, without cancellation.
        let a = 2.0 / (qb + (qb * qb + 4.0 * qa).sqrt());
        (a, a.powi(3) - lambda * a * a * (s + m * m * at))
    }
    /// Pull-off load under force control over pi w R (negative): the smallest P over m,
    /// scanned with m - 1 from 1e-12 to 1e9 evenly in its logarithm and refined by golden
    /// sections (-2 in Bradley's limit lambda -> 0, -1.5 in JKR's).
    pub fn pull_off(lambda: f64) -> f64 {
        let x = |k: f64| -12.0 + k * 1e-3;
        let p = |x: f64| state(lambda, 1.0 + 10f64.powf(x)).1;
        let mut best = (0.0, f64::INFINITY);
        for k in 0..=21_000 {
            let v = p(x(k as f64));
            if v < best.1 {
                best = (x(k as f64), v);
            }
        }
        let (mut lo, mut hi) = (best.0 - 1e-3, best.0 + 1e-3);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..100 {
            let (a, b) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if p(a) < p(b) {
                hi = b;
            } else {
                lo = a;
            }
        }
        p(0.5 * (lo + hi)).min(best.1)
    }
}

/// Adhesive flat punch (Kendall 1971; Eq. 34): F_A = sqrt(8 pi a^3 E* gamma).
pub fn adhesive_flat_punch_pull_off(e_star: f64, a: f64, gamma: f64) -> f64 {
    (8.0 * e_star * a.powi(3) * PI * gamma).sqrt()
}

/// Adhesive cone (Maugis 1995; Eq. 37): F_A = 54 gamma^2 / (pi E* tan^3 theta).
pub fn adhesive_cone_pull_off(e_star: f64, tan_theta: f64, gamma: f64) -> f64 {
    54.0 * gamma * gamma / (PI * e_star * tan_theta.powi(3))
}

/// Cattaneo-Mindlin tangential contact of a sphere.
pub mod cattaneo_mindlin {
    /// c/a = (1 - Fx/(mu FN))^(1/3) (Eq. 49).
    pub fn stick_ratio(fx: f64, mu: f64, fn_: f64) -> f64 {
        (1.0 - fx / (mu * fn_)).cbrt()
    }
    /// u_x,max = mu E*/G* d (Eq. 50).
    pub fn max_displacement(mu: f64, e_star: f64, g_star: f64, d: f64) -> f64 {
        mu * e_star / g_star * d
    }
    /// Tangential displacement at Fx (Mindlin 1949):
    /// u = mu E*/G* d (1 - (1 - Fx/(mu FN))^(2/3)).
    pub fn displacement(mu: f64, e_star: f64, g_star: f64, d: f64, fx: f64, fn_: f64) -> f64 {
        mu * e_star / g_star * d * (1.0 - (1.0 - fx / (mu * fn_)).powf(2.0 / 3.0))
    }
    /// Traction tau(r) = mu p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)], p0 = peak
    /// Hertz pressure.
    pub fn traction(mu: f64, p0: f64, a: f64, c: f64, r: f64) -> f64 {
        let outer = if r < a {
            (1.0 - (r / a).powi(2)).sqrt()
        } else {
            0.0
        };
        let inner = if r < c {
            c / a * (1.0 - (r / c).powi(2)).sqrt()
        } else {
            0.0
        };
        mu * p0 * (outer - inner)
    }
}

/// Frictional damping of an oscillating sphere contact (Mindlin et al. 1952; Section 7).
pub mod mindlin_damping {
    /// Exact dissipation per cycle for displacement amplitude A (any nu via
    /// beta = E*/G*): W = 4 mu E* sqrt(R) Int_0^{ds} delta (A - mu beta delta)
    /// (d - delta)^(-1/2) d delta, ds = min(d, A/(mu beta)), in closed form.
    /// For beta = 5/4 (nu = 1/3) this is Eq. (58).
    pub fn dissipation_exact(e_star: f64, beta: f64, r: f64, mu: f64, d: f64, amp: f64) -> f64 {
        let ds = (amp / (mu * beta)).min(d);
        let ratio = ds / d;
        let integral = if ratio <= SERIES_BELOW {
            // A - mu beta delta = mu beta (ds - delta); with delta = ds t the integral is
            // mu beta ds^3 d^(-1/2) Int_0^1 t (1 - t) (1 - e t)^(-1/2) dt (e = ds/d), term
            // by term: (1 - e t)^(-1/2) = sum c_k (e t)^k, c_k = c_{k-1} (2k - 1)/(2k),
            // Int_0^1 t^(k+1) (1 - t) dt = 1/((k + 2)(k + 3)). The closed form below
            // cancels to e^3 of terms of order e (relative error eps_mach / e^2).
            let sum = sum_to_rounding((0..200).scan(1.0, |c, k| {
                if k > 0 {
                    *c *= (2 * k - 1) as f64 / (2 * k) as f64;
                }
                Some(*c * ratio.powi(k) / ((k + 2) * (k + 3)) as f64)
            }));
            mu * beta * ds.powi(3) / d.sqrt() * sum
        } else {
            // Antiderivatives in s = d - delta (see module docs).
            // d^p - s^p without cancellation for s close to d.
            let pd = |p: f64| -d.powf(p) * (p * (-ds / d).ln_1p()).exp_m1();
            let lin = 2.0 * d * pd(0.5) - 2.0 / 3.0 * pd(1.5);
            let quad = 2.0 * d * d * pd(0.5) - 4.0 / 3.0 * d * pd(1.5) + 0.4 * pd(2.5);
            amp * lin - mu * beta * quad
        };
        4.0 * mu * e_star * r.sqrt() * integral
    }

    /// Where the closed forms of this module switch to their power series (summed to the
    /// last term that changes the sum; below this ratio the terms fall as 2^-k at
    /// least): below it the closed forms lose digits to cancellation (eps_mach over the
    /// amplitude ratio squared or cubed), above it the series need more terms.
    const SERIES_BELOW: f64 = 0.5;

    /// The sum of `terms` up to the first that no longer changes it.
    fn sum_to_rounding(terms: impl Iterator<Item = f64>) -> f64 {
        let mut sum = 0.0;
        for t in terms {
            if sum + t == sum {
                break;
            }
            sum += t;
        }
        sum
    }

    /// Eq. (58) as printed, generalised from nu = 1/3 (beta = 5/4) to any beta by
    /// replacing 4/5 with 1/beta; A_c0 = mu beta d. Valid for A <= A_c0.
    pub fn dissipation_eq58(e_star: f64, beta: f64, r: f64, mu: f64, d: f64, amp: f64) -> f64 {
        let ac0 = mu * beta * d;
        let rest = ac0 - amp;
        let bracket = ac0 * (amp - ac0) * (ac0.sqrt() - rest.sqrt())
            + (2.0 * ac0 - amp) / 3.0 * (ac0.powf(1.5) - rest.powf(1.5))
            - 0.2 * (ac0.powf(2.5) - rest.powf(2.5));
        8.0 * e_star * r.sqrt() * (1.0 / beta).powf(1.5) * mu.powf(-0.5) * bracket
    }

    /// Small-amplitude limit (Eq. 61): W = 2/3 (1/beta)^2 E* R^(1/2) mu^-1 d^(-1/2) A^3,
    /// with 1/beta = 2(1-nu)/(2-nu).
    pub fn dissipation_small_amplitude(
        e_star: f64,
        beta: f64,
        r: f64,
        mu: f64,
        d: f64,
        amp: f64,
    ) -> f64 {
        2.0 / 3.0 / (beta * beta) * e_star * r.sqrt() / (mu * d.sqrt()) * amp.powi(3)
    }

    /// Mindlin's small-amplitude law in force terms: W = F*^3 / (9 G* a mu F_N).
    pub fn dissipation_force_amplitude(g_star: f64, a: f64, mu: f64, fn_: f64, f_amp: f64) -> f64 {
        f_amp.powi(3) / (9.0 * g_star * a * mu * fn_)
    }

    /// Mindlin and Deresiewicz in force terms: the energy per cycle of a tangential
    /// force of amplitude F* = x mu F_N (x in [0, 1]), W = 18 (mu F_N)^2 / (5 G* a) f(x)
    /// with f(x) = 1 - (1 - x)^(5/3) - 5x/6 (1 + (1 - x)^(2/3)) (G* = 4G/(2 - nu));
    /// f(x) = 5x^3/162 + 5x^4/243 + ..., whose first term is
    /// [`dissipation_force_amplitude`].
    pub fn dissipation_force_amplitude_exact(
        g_star: f64,
        a: f64,
        mu: f64,
        fn_: f64,
        f_amp: f64,
    ) -> f64 {
        let x = f_amp / (mu * fn_);
        let f = if x <= SERIES_BELOW {
            // a_k, b_k: the coefficients of x^k in (1 - x)^(5/3) and (1 - x)^(2/3)
            // (c_k = c_{k-1} (k - 1 - alpha)/k); f's are -a_k - 5/6 b_{k-1}, zero up to
            // k = 2 (the closed form cancels to x^3 of terms of order x).
            let terms = (1..200).scan((1.0, 1.0), |(a_k, b_prev), k| {
                if k >= 2 {
                    *b_prev *= (k as f64 - 2.0 - 2.0 / 3.0) / (k - 1) as f64;
                }
                *a_k *= (k as f64 - 1.0 - 5.0 / 3.0) / k as f64;
                Some((-*a_k - 5.0 / 6.0 * *b_prev) * x.powi(k))
            });
            sum_to_rounding(terms.skip(2))
        } else {
            1.0 - (1.0 - x).powf(5.0 / 3.0) - 5.0 * x / 6.0 * (1.0 + (1.0 - x).powf(2.0 / 3.0))
        };
        18.0 * (mu * fn_).powi(2) / (5.0 * g_star * a) * f
    }
}

/// Frictional damping of any contact from its normal force-approach curve F(d): the
/// tangential problem under a held normal force as a difference of two normal problems
/// (Ciavarella, Int. J. Solids Struct. 35 (1998) 2349; Jaeger, Wear 219 (1998) 181), and
/// the unloading and reloading branches by Masing's rule (as Mindlin and Deresiewicz's
/// for the sphere). Exact for MRD's springs on any profile or rough line (each spring
/// slips where `G* u > mu E* g`); in 3D exact for Mindlin's model (q_y = 0) where the
/// tangential compliance is the normal one scaled (nu = 0, G* = E*), for any shape.
///
/// With `kappa = mu E* / G*`, the virgin loading to the tangential displacement
/// `u = kappa c` carries `Q = mu (F(d0) - F(d0 - c))`; an oscillation of force amplitude
/// `Q*` (its `c*` from the same relation) dissipates per cycle
/// `W = 4 mu kappa [c* (F(d0) + F(d0 - c*)) - 2 Int_{d0 - c*}^{d0} F(x) dx]`, which is
/// 8 Int_0^u* Q(s) ds - 4 Q* u*. The same law with the force as the variable (the
/// approach d(F) of force-controlled solves) is `compare`'s `experiment::tangential_map`.
pub mod masing {
    /// Panels of the integral of F, and Gauss-Legendre points per panel.
    const PANELS: usize = 4;
    const NODES: usize = 8;

    /// The reduction `c` of the approach whose normal-force drop is `q / mu`:
    /// `mu (F(d0) - F(d0 - c)) = q`, F non-decreasing, `q` in [0, mu F(d0)], by regula
    /// falsi (Illinois) on [0, d0 - first], `first` an approach at or below first contact
    /// (where F vanishes); to `1e-13` of that bracket. None where `q` lies outside.
    pub fn reduction(
        force: &mut dyn FnMut(f64) -> f64,
        (first, d0): (f64, f64),
        mu: f64,
        q: f64,
    ) -> Option<f64> {
        let f0 = force(d0);
        let drop = |f: f64| mu * (f0 - f) - q;
        if !(q >= 0.0 && q <= mu * f0 && d0 > first) {
            return None;
        }
        if q == 0.0 {
            return Some(0.0);
        }
        // g(c) = mu (F(d0) - F(d0 - c)) - q rises from -q at c = 0 to >= 0 at d0 - first.
        let (mut a, mut ga) = (0.0, -q);
        let (mut b, mut gb) = (d0 - first, drop(force(first)));
        let mut side = 0;
        for _ in 0..200 {
            if b - a <= 1e-13 * (d0 - first) {
                break;
            }
            let c = if gb > ga {
                b - gb * (b - a) / (gb - ga)
            } else {
                0.5 * (a + b)
            };
            let c = if c > a && c < b { c } else { 0.5 * (a + b) };
            let gc = drop(force(d0 - c));
            if gc == 0.0 {
                return Some(c);
            }
            if gc < 0.0 {
                (a, ga) = (c, gc);
                if side == -1 {
                    gb *= 0.5;
                }
                side = -1;
            } else {
                (b, gb) = (c, gc);
                if side == 1 {
                    ga *= 0.5;
                }
                side = 1;
            }
        }
        Some(0.5 * (a + b))
    }

    /// The loss per cycle of a tangential force of amplitude `q` (module docs) at the
    /// held approach `d0`, with `kappa = mu E* / G*`; `first` as for [`reduction`].
    /// Returns `(W, u*)`: the loss and the displacement amplitude of the virgin loading.
    pub fn loss_per_cycle(
        force: &mut dyn FnMut(f64) -> f64,
        (first, d0): (f64, f64),
        mu: f64,
        kappa: f64,
        q: f64,
    ) -> Option<(f64, f64)> {
        let c = reduction(force, (first, d0), mu, q)?;
        let (f0, fc) = (force(d0), force(d0 - c));
        let (xg, wg) = crate::numerics::gauss::legendre(NODES);
        let h = c / PANELS as f64;
        let mut integral = 0.0;
        for k in 0..PANELS {
            let mid = d0 - c + (k as f64 + 0.5) * h;
            for (x, w) in xg.iter().zip(&wg) {
                integral += 0.5 * h * w * force(mid + 0.5 * h * x);
            }
        }
        let w = 4.0 * mu * kappa * (c * (f0 + fc) - 2.0 * integral);
        Some((w, kappa * c))
    }
}

/// Viscoelastic sliding friction (Section 10.1).
pub mod sliding {
    /// A harmonic line z = h0 cos(k x) sliding at velocity v in full contact over
    /// Winkler springs of complex modulus M(omega) = M' + i M'' (per unit width) at mean
    /// indentation D (the approach minus h0). Steady state, theta = k (x + v t):
    /// f/dx = M_inf D + h0 (M' cos theta - M'' sin theta), and with z' = -h0 k sin theta
    /// the mean of f z' is h0^2 k M''/2 per unit length, while the mean force is
    /// M_inf D. So mu = h0^2 k M''(k v) / (2 M_inf D), independent of the factor 4 in
    /// M = 4 G. Full contact needs M_inf D >= h0 |M(k v)|.
    pub fn harmonic_mu(k: f64, h0: f64, loss: f64, relaxed: f64, mean_indentation: f64) -> f64 {
        h0 * h0 * k * loss / (2.0 * relaxed * mean_indentation)
    }

    /// Eq. (82): mu = xi grad z G''(k v) / |G(k v)|.
    pub fn eq82(xi: f64, grad_z: f64, storage: f64, loss: f64) -> f64 {
        xi * grad_z * loss / storage.hypot(loss)
    }
}

/// Kogut & Etsion (J. Appl. Mech. 69 (2002) 657-662, doi 10.1115/1.1490373):
/// finite-element fits for an elastic-perfectly plastic sphere (yield stress Y, Poisson's
/// ratio nu) pressed by a rigid flat, in the interference w over its value at the onset
/// of yield,
/// `w_c = (pi K H / (2 E*))^2 R` with `K = 0.454 + 0.41 nu` and the hardness
/// `H = 2.8 Y` (so that `K H` is the peak Hertz pressure at first yield, 1.6 Y at nu =
/// 0.3). Load over `P_c = (4/3) E* sqrt(R) w_c^(3/2)`, area over `A_c = pi R w_c`. Valid
/// for 1 <= w/w_c <= 110; the fits hold the computed points to within a few per cent
/// (the paper's statement).
pub mod kogut_etsion {
    /// The hardness coefficient K of the onset of yield.
    pub fn k(nu: f64) -> f64 {
        0.454 + 0.41 * nu
    }

    /// The critical interference w_c [length].
    pub fn critical_interference(e_star: f64, r: f64, yield_stress: f64, nu: f64) -> f64 {
        let hardness = 2.8 * yield_stress;
        (std::f64::consts::PI * k(nu) * hardness / (2.0 * e_star)).powi(2) * r
    }

    /// P/P_c at w/w_c in [1, 110] (None outside): `1.03 x^1.425` up to 6, `1.40 x^1.263`
    /// beyond.
    pub fn load_ratio(x: f64) -> Option<f64> {
        match x {
            x if (1.0..=6.0).contains(&x) => Some(1.03 * x.powf(1.425)),
            x if x > 6.0 && x <= 110.0 => Some(1.40 * x.powf(1.263)),
            _ => None,
        }
    }

    /// A/A_c at w/w_c in [1, 110] (None outside): `0.93 x^1.136` up to 6, `0.94 x^1.146`
    /// beyond.
    pub fn area_ratio(x: f64) -> Option<f64> {
        match x {
            x if (1.0..=6.0).contains(&x) => Some(0.93 * x.powf(1.136)),
            x if x > 6.0 && x <= 110.0 => Some(0.94 * x.powf(1.146)),
            _ => None,
        }
    }
}

/// The closed forms that apply to a whole profile: a flat punch (no shapes, a rim), or a
/// single analytic shape without a rim. Sums of shapes and tables have none.
pub mod for_profile {
    use super::*;
    use crate::profile::{Profile, Shape};

    /// What the profile is, where a closed form exists.
    enum Known<'a> {
        FlatPunch(f64),
        Single(&'a Shape),
    }

    fn known(profile: &Profile) -> Option<Known<'_>> {
        match (profile.shapes(), profile.rim()) {
            ([], Some(a)) => Some(Known::FlatPunch(a)),
            ([Shape::Table(_)], None) => None,
            ([s], None) => Some(Known::Single(s)),
            _ => None,
        }
    }

    /// The literature source of the profile's closed form, for legends.
    pub fn name(profile: &Profile) -> Option<String> {
        Some(match known(profile)? {
            Known::FlatPunch(_) => "flat punch, F = 2aE*d (Eq. 1)".into(),
            Known::Single(Shape::Paraboloid { .. }) => "Hertz".into(),
            Known::Single(Shape::Cone { .. }) => "cone (Love 1939)".into(),
            Known::Single(Shape::PowerLaw { n, .. }) => {
                format!("power law n = {n} (Sneddon 1965)")
            }
            Known::Single(Shape::FlattenedParaboloid { .. }) => "Ejike 1981 (Eqs. 24-25)".into(),
            Known::Single(Shape::Table(_)) => return None,
        })
    }

    /// Normal force at depth d.
    pub fn force(profile: &Profile, e_star: f64, d: f64) -> Option<f64> {
        Some(match known(profile)? {
            Known::FlatPunch(a) => flat_punch::force(e_star, a, d),
            Known::Single(&Shape::Paraboloid { radius }) => hertz::force(e_star, radius, d),
            Known::Single(&Shape::Cone { tan_theta }) => cone::force(e_star, tan_theta, d),
            Known::Single(&Shape::PowerLaw { c, n }) => {
                let a = (d / (kappa(n) * c)).powf(1.0 / n);
                power_law::force(e_star, c, n, a)
            }
            Known::Single(&Shape::FlattenedParaboloid {
                radius,
                flat_radius,
            }) => {
                // Invert Eq. (24) for a: a^2 = (a0^2 + sqrt(a0^4 + 4 R^2 d^2))/2.
                let a0 = flat_radius;
                let a =
                    (0.5 * (a0 * a0 + (a0.powi(4) + 4.0 * radius * radius * d * d).sqrt())).sqrt();
                ejike::force(e_star, radius, a0, a)
            }
            Known::Single(Shape::Table(_)) => return None,
        })
    }

    /// Whether [`pressure`] has a closed form for this profile.
    pub fn has_pressure(profile: &Profile) -> bool {
        matches!(
            known(profile),
            Some(
                Known::FlatPunch(_)
                    | Known::Single(Shape::Paraboloid { .. })
                    | Known::Single(Shape::Cone { .. })
            )
        )
    }

    /// Pressure at radius r, at depth d under force f.
    pub fn pressure(profile: &Profile, e_star: f64, d: f64, f: f64, r: f64) -> Option<f64> {
        Some(match known(profile)? {
            Known::FlatPunch(a) => flat_punch::pressure(f, a, r),
            Known::Single(&Shape::Paraboloid { radius }) => hertz::pressure(e_star, radius, d, r),
            Known::Single(&Shape::Cone { tan_theta }) => cone::pressure(e_star, tan_theta, d, r),
            _ => return None,
        })
    }

    /// The sphere's radius, if the profile is one sphere (Cattaneo-Mindlin, Mindlin
    /// damping and JKR apply).
    pub fn sphere_radius(profile: &Profile) -> Option<f64> {
        match known(profile)? {
            Known::Single(&Shape::Paraboloid { radius }) => Some(radius),
            _ => None,
        }
    }

    /// Magnitude of the adhesive pull-off force and its source: JKR for a sphere (force
    /// or displacement control), Eq. 37 for a cone (force control), Eq. 34 for a flat
    /// punch.
    pub fn pull_off(
        profile: &Profile,
        e_star: f64,
        gamma: f64,
        force_control: bool,
    ) -> Option<(f64, &'static str)> {
        match known(profile)? {
            Known::Single(&Shape::Paraboloid { radius }) => Some((
                if force_control {
                    jkr::pull_off_force_control(radius, gamma)
                } else {
                    jkr::pull_off_displacement_control(radius, gamma)
                },
                "JKR",
            )),
            Known::Single(&Shape::Cone { tan_theta }) if force_control => {
                Some((adhesive_cone_pull_off(e_star, tan_theta, gamma), "Eq. 37"))
            }
            Known::FlatPunch(a) => Some((adhesive_flat_punch_pull_off(e_star, a, gamma), "Eq. 34")),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    /// The loss per cycle from the normal curve of a sphere (Hertz) is Mindlin and
    /// Deresiewicz's, at amplitudes from 0.05 to 0.95 of mu F_N: within 1e-9 (Gauss-
    /// Legendre on a smooth curve); the displacement amplitude is Mindlin's virgin one.
    #[test]
    fn masing_on_hertz_is_mindlin_deresiewicz() {
        let (e, g, r, mu, d0) = (1.3, 1.1, 0.7, 0.4, 0.02);
        let mut f = |d: f64| if d > 0.0 { hertz::force(e, r, d) } else { 0.0 };
        let (fn_, a) = (hertz::force(e, r, d0), hertz::radius(r, d0));
        for x in [0.05, 0.2, 0.5, 0.8, 0.95] {
            let q = x * mu * fn_;
            let (w, u) = masing::loss_per_cycle(&mut f, (0.0, d0), mu, mu * e / g, q).unwrap();
            let md = mindlin_damping::dissipation_force_amplitude_exact(g, a, mu, fn_, q);
            assert!((w / md - 1.0).abs() < 1e-9, "{x}: {w:e} against {md:e}");
            let mindlin = 3.0 * mu * fn_ / (4.0 * a * g) * (1.0 - (1.0 - x).powf(2.0 / 3.0));
            assert!(
                (u / mindlin - 1.0).abs() < 1e-9,
                "{x}: {u:e} against {mindlin:e}"
            );
        }
        assert!(masing::reduction(&mut f, (0.0, d0), mu, 1.01 * mu * fn_).is_none());
    }

    /// Hertz's impact: the duration coefficient against Johnson's 2.94 and the
    /// classical `2.87 (m^2 / (R E*^2 v))^(1/5)` (the same law with the constants
    /// combined), and the energy balance at the largest approach.
    #[test]
    fn hertz_impact_constants() {
        use super::hertz_impact::*;
        let c = duration_coefficient();
        assert!((c - 2.9432).abs() < 1e-4, "{c}");
        let (e, r, m, v) = (2.0, 0.5, 3.0, 0.7);
        let t = duration(e, r, m, v);
        let classical = 2.868 * (m * m / (r * e * e * v)).powf(0.2);
        assert!((t / classical - 1.0).abs() < 1e-3, "{t} {classical}");
        let d = max_approach(e, r, m, v);
        let stored = 8.0 / 15.0 * e * r.sqrt() * d.powf(2.5);
        assert!((stored / (0.5 * m * v * v) - 1.0).abs() < 1e-12);
    }

    /// Kogut & Etsion's fits as transcribed: the two pieces meet within 2 % at w/w_c = 6,
    /// the load starts within 3 % of Hertz's at the onset, and the onset's peak Hertz
    /// pressure is K H = 1.62 Y at nu = 0.3 (their 1.6 Y).
    #[test]
    fn kogut_etsion_fits_join_and_start_at_hertz() {
        use super::kogut_etsion::*;
        let (low, high) = (1.03 * 6f64.powf(1.425), 1.40 * 6f64.powf(1.263));
        assert!((low / high - 1.0).abs() < 0.02, "{low} {high}");
        assert!((load_ratio(1.0).unwrap() - 1.0).abs() < 0.031);
        assert!((area_ratio(1.0).unwrap() - 1.0).abs() < 0.08);
        assert!(load_ratio(0.5).is_none() && load_ratio(111.0).is_none());
        assert!((k(0.3) * 2.8 - 1.6156).abs() < 1e-9);
        // Hertz's peak pressure at w_c is K H.
        let (e, r, y) = (100.0, 2.0, 0.3);
        let wc = critical_interference(e, r, y, 0.3);
        let p0 = 2.0 * e / std::f64::consts::PI * (wc / r).sqrt();
        assert!((p0 / (k(0.3) * 2.8 * y) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn maugis_dugdale_limits_and_a_middle_value() {
        use super::maugis_dugdale::pull_off;
        // Bradley (-2) and JKR (-1.5) at the ends; lambda = 1 against an independent scan
        // (numpy, m in steps of 0.1 %: -1.600733, above the refined minimum -1.6007349).
        assert!((pull_off(1e-3) + 2.0).abs() < 2e-3, "{}", pull_off(1e-3));
        assert!((pull_off(100.0) + 1.5).abs() < 5e-3, "{}", pull_off(100.0));
        assert!(
            (pull_off(1.0) + 1.6007349).abs() < 1e-7 && pull_off(1.0) < -1.600733,
            "{}",
            pull_off(1.0)
        );
        // Monotonic in lambda.
        let v: Vec<f64> = [0.01, 0.1, 0.3, 1.0, 3.0, 10.0]
            .iter()
            .map(|l| pull_off(*l))
            .collect();
        assert!(v.windows(2).all(|w| w[1] > w[0]), "{v:?}");
    }

    use super::*;

    #[test]
    fn power_law_n2_is_hertz_and_n1_is_cone() {
        let (e, r, d) = (1.3, 2.0, 0.01);
        let a = hertz::radius(r, d);
        let c = 1.0 / (2.0 * r);
        assert!((power_law::depth(c, 2.0, a) - d).abs() < 1e-15);
        assert!((power_law::force(e, c, 2.0, a) / hertz::force(e, r, d) - 1.0).abs() < 1e-13);
        let t = 0.2;
        let a = cone::radius(t, d);
        assert!((power_law::force(e, t, 1.0, a) / cone::force(e, t, d) - 1.0).abs() < 1e-13);
    }

    #[test]
    fn hertz_round_trip_and_ejike_limit() {
        let (e, r) = (2.0, 0.5);
        let f = 3.7;
        assert!((hertz::force(e, r, hertz::depth(e, r, f)) / f - 1.0).abs() < 1e-14);
        let a = 0.1;
        let d = hertz::radius(r, 1.0).powi(0) * a * a / r;
        assert!((ejike::depth(r, 0.0, a) - d).abs() < 1e-15);
        assert!((ejike::force(e, r, 0.0, a) / hertz::force(e, r, d) - 1.0).abs() < 1e-13);
    }

    #[test]
    fn jkr_parametric_minimum_is_pull_off() {
        let (e, r, g) = (1.0, 1.0, 0.01);
        let fmin = (1..100_000)
            .map(|i| jkr::force(e, r, g, i as f64 * 1e-5))
            .fold(f64::INFINITY, f64::min);
        assert!((fmin + jkr::pull_off_force_control(r, g)).abs() < 1e-8);
    }

    #[test]
    fn profile_closed_forms_dispatch_to_the_shapes() {
        use crate::profile::{Profile, Shape};
        let (e, d) = (2.0, 0.01);
        let sphere = Profile::single(Shape::paraboloid(1.5).unwrap());
        assert_eq!(
            for_profile::force(&sphere, e, d),
            Some(hertz::force(e, 1.5, d))
        );
        assert_eq!(for_profile::sphere_radius(&sphere), Some(1.5));
        // n = 2 power law with c = 1/(2R) is Hertz (the closed form is Sneddon's).
        let pl = Profile::single(Shape::power_law(1.0 / 3.0, 2.0).unwrap());
        let f = for_profile::force(&pl, e, d).unwrap();
        assert!((f / hertz::force(e, 1.5, d) - 1.0).abs() < 1e-13);
        assert_eq!(for_profile::sphere_radius(&pl), None);
        // Flattened sphere with a vanishing flat is Hertz.
        let fl = Profile::single(Shape::flattened_paraboloid(1.5, 1e-12).unwrap());
        assert!(
            (for_profile::force(&fl, e, d).unwrap() / hertz::force(e, 1.5, d) - 1.0).abs() < 1e-9
        );
        let punch = Profile::flat_punch(0.3).unwrap();
        assert_eq!(
            for_profile::force(&punch, e, d),
            Some(flat_punch::force(e, 0.3, d))
        );
        assert!(for_profile::has_pressure(&punch) && !for_profile::has_pressure(&pl));
        let sum = Profile::new(
            vec![Shape::paraboloid(1.0).unwrap(), Shape::cone(0.1).unwrap()],
            None,
        )
        .unwrap();
        assert!(for_profile::force(&sum, e, d).is_none() && for_profile::name(&sum).is_none());
        assert_eq!(
            for_profile::pull_off(&sphere, e, 0.1, true),
            Some((jkr::pull_off_force_control(1.5, 0.1), "JKR"))
        );
        let cone = Profile::single(Shape::cone(0.2).unwrap());
        assert!(for_profile::pull_off(&cone, e, 0.1, false).is_none());
    }

    #[test]
    fn damping_forms_agree() {
        let (e, r, mu, d) = (1.0, 1.0, 0.3, 0.01);
        for &beta in &[1.0, 1.25, 1.5] {
            let ac0 = mu * beta * d;
            for &f in &[0.01, 0.3, 0.9, 1.0] {
                let amp = f * ac0;
                let w1 = mindlin_damping::dissipation_exact(e, beta, r, mu, d, amp);
                let w2 = mindlin_damping::dissipation_eq58(e, beta, r, mu, d, amp);
                // Eq. (58) as printed cancels catastrophically at small A: 1e-6 there.
                let tol = if f < 0.1 { 1e-6 } else { 1e-12 };
                assert!(
                    (w1 / w2 - 1.0).abs() < tol,
                    "beta={beta} A/Ac0={f}: {w1} {w2}"
                );
            }
            let amp = 1e-3 * ac0;
            let w = mindlin_damping::dissipation_exact(e, beta, r, mu, d, amp);
            let w0 = mindlin_damping::dissipation_small_amplitude(e, beta, r, mu, d, amp);
            assert!((w / w0 - 1.0).abs() < 1e-3);
        }
    }

    /// Small amplitudes: the series take over from the closed forms, which cancel to the
    /// cube of the amplitude ratio. Both laws approach their cubic limits with the
    /// next term of their series, 0.25 e (e = A/A_c0) for the displacement amplitude
    /// and 2x/3 for the force amplitude (x = F*/(mu F_N)), to rounding down to 1e-12;
    /// at the switch (ratio 0.5) series and closed form agree to the closed form's
    /// rounding.
    #[test]
    fn damping_at_small_amplitudes() {
        use mindlin_damping as md;
        let (e, beta, r, mu, d) = (1.0f64, 1.25, 1.0f64, 0.3, 0.01f64);
        let ac0 = mu * beta * d;
        let (g, a, fn_) = (
            e / beta,
            (r * d).sqrt(),
            4.0 / 3.0 * e * r.sqrt() * d.powf(1.5),
        );
        for k in 3..=12 {
            let x = 10f64.powi(-k);
            let w = md::dissipation_exact(e, beta, r, mu, d, x * ac0);
            let w0 = md::dissipation_small_amplitude(e, beta, r, mu, d, x * ac0);
            let dev = (w / w0 - 1.0 - 0.25 * x).abs();
            assert!(dev < 1e-14 + x * x, "A = 1e-{k} A_c0: {dev:e}");
            let f = x * mu * fn_;
            let w = md::dissipation_force_amplitude_exact(g, a, mu, fn_, f);
            let w0 = md::dissipation_force_amplitude(g, a, mu, fn_, f);
            let dev = (w / w0 - 1.0 - 2.0 / 3.0 * x).abs();
            assert!(dev < 1e-14 + x * x, "F* = 1e-{k} mu F_N: {dev:e}");
        }
        // 0.5 on the series, the next double on the closed form.
        let (x, y) = (0.5, 0.5 * (1.0 + f64::EPSILON));
        let w = |x: f64| md::dissipation_exact(e, beta, r, mu, d, x * ac0);
        assert!((w(y) / w(x) - 1.0).abs() < 1e-14, "{} {}", w(x), w(y));
        // The closed form's rounding there: eps_mach over f(0.5) = 0.0059 (measured 1.2e-14).
        let w = |x: f64| md::dissipation_force_amplitude_exact(g, a, mu, fn_, x * mu * fn_);
        assert!((w(y) / w(x) - 1.0).abs() < 5e-14, "{} {}", w(x), w(y));
    }
}
