//! Property tests (proptest) of the 1D method: scaling laws, monotonicity, the rule of
//! Hess and its inverse, and equilibrium of the Abel pressure, on random profiles and
//! random rough lines; plus stress cases at the edges of the parameter ranges.

use mrd::normal::AxisymmetricContact;
use mrd::pressure::{abel_pressure, integrate_force};
use mrd::rough_contact::RoughLine;
use mrd::{Profile, Shape};
use proptest::prelude::*;

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// A random rough line (sum of a few sines with random phases), periodic.
fn line(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed.wrapping_add(1);
    (0..n)
        .map(|i| {
            (1..8)
                .map(|k| {
                    s = s
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    let ph = (s >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU;
                    (std::f64::consts::TAU * k as f64 * i as f64 / n as f64 + ph).cos() / k as f64
                })
                .sum()
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Table 1 and Eq. (80) for the profiles MRD maps exactly: a power-law indenter
    /// z = c r^n has k proportional to F^(1/(1+n)) (the scaling law that gives
    /// alpha = 1/(1+H) for H = n), and F(d) is homogeneous of degree (n+1)/n.
    #[test]
    fn power_law_scaling(n in 0.3f64..8.0, c in 0.1f64..10.0, e in 0.01f64..100.0,
                         f1 in 1e-4f64..1.0, ratio in 1.1f64..100.0) {
        let con = AxisymmetricContact::new(Profile::single(Shape::power_law(c, n).unwrap()), e).unwrap();
        let a = con.state_at_force(f1).unwrap();
        let b = con.state_at_force(f1 * ratio).unwrap();
        prop_assert!(rel(b.stiffness / a.stiffness, ratio.powf(1.0 / (1.0 + n))) < 1e-8);
        prop_assert!(rel(b.depth / a.depth, ratio.powf(n / (1.0 + n))) < 1e-8);
    }

    /// F(d) increases and k(d) does not decrease, for sums of a sphere and a cone.
    #[test]
    fn force_and_stiffness_are_monotone(r in 0.1f64..10.0, t in 0.01f64..1.0,
                                       mut depths in proptest::collection::vec(1e-6f64..1.0, 2..12)) {
        let p = Profile::new(vec![Shape::paraboloid(r).unwrap(), Shape::cone(t).unwrap()], None).unwrap();
        let con = AxisymmetricContact::new(p, 1.0).unwrap();
        depths.sort_by(f64::total_cmp);
        depths.dedup();
        let s: Vec<_> = depths.iter().map(|&d| con.state_at_depth(d).unwrap()).collect();
        for w in s.windows(2) {
            prop_assert!(w[1].force > w[0].force);
            prop_assert!(w[1].stiffness >= w[0].stiffness * (1.0 - 1e-12));
        }
    }

    /// The rule of Hess (Eq. 11, closed form per shape) and its inverse (quadrature)
    /// are a transform pair: inverse(z1d) = z.
    #[test]
    fn rule_of_hess_round_trip(r in 0.2f64..5.0, t in 0.01f64..1.0, n in 0.5f64..5.0,
                               c in 0.1f64..3.0, x in 0.01f64..2.0) {
        let p = Profile::new(
            vec![Shape::paraboloid(r).unwrap(), Shape::cone(t).unwrap(), Shape::power_law(c, n).unwrap()],
            None,
        )
        .unwrap();
        let z = mrd::hess::inverse(|s| p.z1d(s), &p.breaks(), x).unwrap();
        prop_assert!(rel(z, p.z(x)) < 1e-9, "{} vs {}", z, p.z(x));
    }

    /// Equilibrium of the Abel transform pair: the pressure of Eq. (26) integrates to the
    /// force of the 1D line load.
    #[test]
    fn abel_pressure_carries_the_force(n in 1.2f64..5.0, c in 0.1f64..3.0, d in 1e-3f64..0.5) {
        let p = Profile::single(Shape::power_law(c, n).unwrap());
        let con = AxisymmetricContact::new(p.clone(), 1.7).unwrap();
        let s = con.state_at_depth(d).unwrap();
        let total = integrate_force(|r| abel_pressure(&p, 1.7, d, s.radius, 0.0, r), s.radius, &p.breaks()).unwrap();
        prop_assert!(rel(total, s.force) < 1e-7, "{} vs {}", total, s.force);
    }

    /// The foundation is linear (Winkler): heights and depth scaled by s scale the force
    /// by s; the modulus scales it likewise; F(d) increases and k(d) does not decrease.
    #[test]
    fn rough_line_homogeneity_and_monotonicity(seed in 0u64..10_000, s in 1e-6f64..1e6,
                                               e in 1e-3f64..1e3, frac in 0.01f64..0.99) {
        let h = line(257, seed);
        let a = RoughLine::new(&h, 1.0, 1.0).unwrap();
        let hs: Vec<f64> = h.iter().map(|v| v * s).collect();
        let b = RoughLine::new(&hs, 1.0, e).unwrap();
        let d = frac * a.full_contact_depth();
        let (sa, sb) = (a.at_depth(d).unwrap(), b.at_depth(d * s).unwrap());
        prop_assert!(rel(sb.force, sa.force * s * e) < 1e-9);
        prop_assert_eq!(sb.contacts, sa.contacts);
        let s2 = a.at_depth(d * 1.01).unwrap();
        prop_assert!(s2.force > sa.force && s2.stiffness >= sa.stiffness);
        // The force-controlled state inverts the depth-controlled one.
        let back = a.at_force(sa.force).unwrap();
        prop_assert!(rel(back.depth, d) < 1e-9);
    }
}

/// Adhesion with a vanishing work of adhesion is the non-adhesive contact: pull-off
/// tends to zero and the unloading branch to the loading one.
#[test]
fn adhesion_without_surface_energy_is_hertz() {
    use mrd::adhesion::{AdhesiveContact, Control};
    let con =
        AxisymmetricContact::new(Profile::single(Shape::paraboloid(1.0).unwrap()), 1.0).unwrap();
    for gamma in [1e-10, 1e-14] {
        let ad = AdhesiveContact::new(con.clone(), gamma).unwrap();
        for a in [0.05, 0.1, 0.2] {
            let f0 = con.state_at_radius(a).unwrap().force;
            let f = ad.force_at_radius(a).unwrap();
            // JKR: F = F_Hertz - sqrt(8 pi gamma E* a^3): the adhesive term vanishes
            // like sqrt(gamma).
            let jkr = mrd::reference::jkr::force(1.0, 1.0, gamma, a);
            assert!(rel(f, jkr) < 1e-9, "gamma {gamma}, a {a}: {f} vs JKR {jkr}");
            let term = (8.0 * std::f64::consts::PI * gamma * a.powi(3)).sqrt();
            assert!((f0 - f - term).abs() < 1e-9 * f0, "gamma {gamma}, a {a}");
            if gamma <= 1e-14 {
                assert!(rel(f, f0) < 1e-4);
            }
        }
        let po = ad.pull_off(0.2, Control::Force).unwrap();
        let hertz_scale = con.state_at_radius(0.2).unwrap().force;
        assert!(po.force.abs() < 1e3 * gamma * hertz_scale.max(1.0) + 10.0 * gamma);
    }
}

/// Friction coefficients near zero and very large: finite states that match
/// Cattaneo-Mindlin (stick radius and displacement).
#[test]
fn tangential_contact_at_extreme_friction() {
    use mrd::reference::cattaneo_mindlin as cm;
    use mrd::tangential::TangentialContact;
    let (e, g) = (1.0, 0.7);
    let con =
        AxisymmetricContact::new(Profile::single(Shape::paraboloid(1.0).unwrap()), e).unwrap();
    for mu in [1e-9, 1e-3, 10.0, 1e6] {
        let tc = TangentialContact::new(con.clone(), g, mu, 0.01).unwrap();
        let n = tc.normal;
        for frac in [0.0, 0.3, 0.9] {
            let fx = frac * mu * n.force;
            let st = tc.at_force(fx).unwrap();
            assert!(st.displacement.is_finite() && st.stick_radius.is_finite());
            let c = n.radius * cm::stick_ratio(fx, mu, n.force);
            assert!((st.stick_radius - c).abs() <= 1e-9 * n.radius, "mu {mu}");
            if fx > 0.0 {
                let u = cm::displacement(mu, e, g, n.depth, fx, n.force);
                assert!(
                    rel(st.displacement, u) < 1e-9,
                    "mu {mu}: {} vs {u}",
                    st.displacement
                );
            }
        }
        assert!(
            rel(
                tc.max_displacement(),
                cm::max_displacement(mu, e, g, n.depth)
            ) < 1e-12
        );
    }
}

/// Rough lines at the ends of the Hurst range synthesise and load without NaN.
#[test]
fn rough_lines_at_hurst_minus_one_and_three() {
    use mrd::roughness::synthesis::{line as synth, Amplitudes};
    use mrd::roughness::SelfAffine;
    let q0 = std::f64::consts::TAU;
    for hurst in [-1.0, 3.0] {
        let spec = SelfAffine::new(hurst, q0, q0, q0 * 256.0)
            .unwrap()
            .to_line(std::f64::consts::PI)
            .with_rms_height(1.0)
            .unwrap();
        let z = synth(&spec, 2048, 1.0, 3, 0, Amplitudes::Deterministic).unwrap();
        assert!(z.iter().all(|v| v.is_finite()));
        let rl = RoughLine::new(&z, 1.0, 1.0).unwrap();
        // Parseval: the realisation's mean square is the discrete spectral sum of
        // Eq. (72), 2 sum_k (2 pi / L) C1D(q_k) (deterministic amplitudes). It differs
        // from the continuous moment (Eq. 75) that `with_rms_height` sets, by a factor
        // 2.5 at H = 3 where the first bin dominates; outputs use the realisation's own h.
        let sum: f64 = (1..1024)
            .map(|k| 2.0 * std::f64::consts::TAU * spec.c1d(q0 * k as f64))
            .sum();
        assert!(rel(rl.rms_height.powi(2), sum) < 1e-9, "H = {hurst}");
        let mut last = 0.0;
        for f in [1e-4, 1e-2, 1.0] {
            let s = rl.at_force(f).unwrap();
            assert!(s.stiffness.is_finite() && s.stiffness >= last);
            last = s.stiffness;
        }
    }
}
