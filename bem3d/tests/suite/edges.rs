//! The solver at its edges: complete contact, infeasible loads, iteration caps and warm
//! starts. Each test pins a defect that once hung, returned NaN or cost more than a cold
//! start (issue "Nothing lost, nothing hidden").

use crate::common;
use bem3d::*;
use common::{rel, self_affine, sphere};

fn opts(tolerance: f64, max_iterations: usize) -> SolverOptions {
    SolverOptions::new(tolerance, max_iterations)
}

/// Beyond complete contact of a periodic rough surface (0.3 and 3 E*, where it starts
/// near 0.05 E* here): the solve converges, every cell carries pressure, the gap is zero
/// everywhere (K p + z is the constant approach, to 1e-12 of the rms height) and the
/// stiffness is +inf (the mean mode of K is free), returned at once.
#[test]
fn periodic_complete_contact_solves_and_has_infinite_stiffness() {
    let n = 64;
    let h = self_affine(n, 0.8, 3);
    let mut s = ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None).unwrap();
    for pm in [0.3, 3.0] {
        let sol = s
            .solve(Load::MeanPressure(pm), &opts(1e-10, 100), None)
            .unwrap();
        assert!(
            sol.complete_contact(),
            "p = {pm}: {} cells",
            sol.contact_cells
        );
        assert!(
            sol.iterations <= 3,
            "p = {pm}: {} iterations",
            sol.iterations
        );
        assert!(rel(sol.force, pm) < 1e-12);
        let max_gap = sol.gap.iter().fold(0.0f64, |m, &g| m.max(g));
        assert!(max_gap < 1e-12 * 0.01, "gap {max_gap}");
        // Independent check of the field: K p = approach - z on every cell.
        let mut op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
        let mut u = vec![0.0; n * n];
        op.apply(&sol.pressure, &mut u);
        let hmax = h.iter().cloned().fold(f64::MIN, f64::max);
        let worst = u
            .iter()
            .zip(&h)
            .map(|(u, h)| (u + (hmax - h) - sol.approach).abs())
            .fold(0.0f64, f64::max);
        assert!(worst < 1e-12, "K p + z - d = {worst}");
        let k = s.tangent_stiffness(&sol, &opts(1e-10, 1000)).unwrap();
        assert_eq!(k, f64::INFINITY);
    }
}

/// A flat map is in complete contact at any load: uniform pressure, one iteration.
/// Periodic: stiffness +inf, any approach > 0 infeasible. Non-periodic: the stiffness
/// is the flat square punch's, k = F / d exactly (the contact set cannot change).
#[test]
fn flat_map_complete_contact() {
    let n = 32;
    let flat = vec![0.25; n * n];
    let mut s =
        ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &flat, None).unwrap();
    let sol = s
        .solve(Load::MeanPressure(0.2), &opts(1e-10, 50), None)
        .unwrap();
    assert!(sol.complete_contact());
    assert!(sol.pressure.iter().all(|&p| rel(p, 0.2) < 1e-12));
    assert_eq!(
        s.tangent_stiffness(&sol, &opts(1e-10, 50)).unwrap(),
        f64::INFINITY
    );
    match s.solve(Load::Approach(1e-3), &opts(1e-10, 50), None) {
        Err(BemError::Infeasible(m)) => assert!(m.contains("complete contact"), "{m}"),
        other => panic!("expected Infeasible, got {:?}", other.map(|s| s.iterations)),
    }
    let mut s =
        ContactSolver::new(NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &flat, None).unwrap();
    let sol = s.solve(Load::Force(0.2), &opts(1e-12, 500), None).unwrap();
    assert!(sol.complete_contact());
    let k = s.tangent_stiffness(&sol, &opts(1e-12, 500)).unwrap();
    assert!(
        rel(k, sol.force / sol.approach) < 1e-8,
        "k {k} vs F/d {}",
        sol.force / sol.approach
    );
}

/// An approach beyond complete contact of a periodic surface has no solution: refused
/// at once with a typed error naming the limit, instead of iterating to the cap.
#[test]
fn periodic_approach_beyond_complete_contact_is_infeasible() {
    let n = 64;
    let h = self_affine(n, 0.8, 5);
    let hmax = h.iter().cloned().fold(f64::MIN, f64::max);
    let mean = h.iter().sum::<f64>() / h.len() as f64;
    let mut s = ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None).unwrap();
    for d in [hmax - mean, 1.5 * (hmax - mean)] {
        assert!(matches!(
            s.solve(Load::Approach(d), &opts(1e-10, 100_000), None),
            Err(BemError::Infeasible(_))
        ));
    }
    // Just below it the solve converges, nearly everywhere in contact.
    let sol = s
        .solve(
            Load::Approach(0.98 * (hmax - mean)),
            &opts(1e-8, 20_000),
            None,
        )
        .unwrap();
    assert!(sol.contact_cells as f64 > 0.5 * (n * n) as f64);
    // A mask lifts the limit: the free cells outside it take the mean displacement.
    let mask: Vec<bool> = (0..n * n).map(|k| k % n < n / 2).collect();
    let mut s =
        ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, Some(mask)).unwrap();
    assert!(s
        .solve(Load::Approach(hmax - mean), &opts(1e-8, 20_000), None)
        .is_ok());
}

/// The stiffness iteration honours its cap and reports the residual it reached.
#[test]
fn stiffness_honours_max_iterations() {
    let n = 64;
    let h = sphere(n, 1.0, 1.0);
    let mut s =
        ContactSolver::new(NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None).unwrap();
    let sol = s
        .solve(Load::Force(0.01), &opts(1e-10, 1000), None)
        .unwrap();
    match s.tangent_stiffness(&sol, &opts(1e-14, 2)) {
        Err(BemError::NoConvergence {
            what,
            iterations,
            residual,
            ..
        }) => {
            assert_eq!(what, "tangent stiffness");
            assert_eq!(iterations, 2);
            assert!(residual.is_finite() && residual > 1e-14);
        }
        other => panic!("expected NoConvergence, got {other:?}"),
    }
    // Invalid options are refused, not looped on.
    assert!(matches!(
        s.solve(Load::Force(0.01), &opts(1e-10, 0), None),
        Err(BemError::InvalidInput(_))
    ));
    assert!(matches!(
        s.solve(Load::Force(0.01), &opts(f64::NAN, 10), None),
        Err(BemError::InvalidInput(_))
    ));
}

/// On a load ladder with large and small steps, a warm-started sequence never needs
/// more iterations than cold starts: large steps start cold (same iterations), small
/// steps (ratio in the window) start warm and need fewer.
#[test]
fn warm_start_never_costs_more_than_cold() {
    let n = 128;
    let h = self_affine(n, 0.8, 11);
    let mut s = ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None).unwrap();
    let o = opts(1e-10, 5000);
    let ladder = [0.01, 0.05, 0.1, 0.104, 0.107, 0.06, 0.058, 0.01];
    let mut warm: Option<Solution> = None;
    let (mut tw, mut tc) = (0, 0);
    for &pm in &ladder {
        let w = s.solve(Load::MeanPressure(pm), &o, warm.as_ref()).unwrap();
        let c = s.solve(Load::MeanPressure(pm), &o, None).unwrap();
        assert!(
            w.iterations <= c.iterations,
            "p = {pm}: warm {} > cold {}",
            w.iterations,
            c.iterations
        );
        if w.warm_started {
            assert!(rel(w.force, c.force) < 1e-12);
            let dp = w
                .pressure
                .iter()
                .zip(&c.pressure)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0f64, f64::max);
            assert!(dp < 1e-6 * pm, "same solution: {dp}");
        } else {
            assert_eq!(w.iterations, c.iterations);
        }
        tw += w.iterations;
        tc += c.iterations;
        warm = Some(w);
    }
    assert!(tw < tc, "ladder: warm {tw} cold {tc}");
}

/// One raised cell carries the whole load: its pressure is F / cell area and the
/// approach is that pressure times the operator's self-influence (Love's coefficient
/// of a cell on itself; the dense periodic matrix's diagonal for periodic grids). The
/// same with a mask of that one cell (a one-cell domain).
#[test]
fn a_single_contacting_cell() {
    let n = 16;
    let (l, f) = (1.0, 1e-6);
    let mut h = vec![0.0; n * n];
    h[5 * n + 7] = 1e-3;
    let cell = (l / n as f64).powi(2);
    let one: Vec<bool> = (0..n * n).map(|k| k == 5 * n + 7).collect();
    for (periodic, mask) in [
        (false, None),
        (true, None),
        (false, Some(one.clone())),
        (true, Some(one)),
    ] {
        let sol = if periodic {
            let mut s =
                ContactSolver::new(PeriodicHalfSpace::new(n, n, l, l, 2.0), &h, mask).unwrap();
            s.solve(Load::Force(f), &opts(1e-12, 1000), None).unwrap()
        } else {
            let mut s =
                ContactSolver::new(NonPeriodicHalfSpace::new(n, n, l, l, 2.0), &h, mask).unwrap();
            s.solve(Load::Force(f), &opts(1e-12, 1000), None).unwrap()
        };
        assert_eq!(sol.contact_cells, 1, "periodic = {periodic}");
        let p = f / cell;
        assert!(rel(sol.pressure[5 * n + 7], p) < 1e-12);
        let self_influence = if periodic {
            let d = DenseCompliance::periodic(n, n, l, l, 2.0);
            let k = 5 * n + 7;
            d.matrix[k * n * n + k]
        } else {
            let hh = l / n as f64;
            bem3d::operator::love_coefficient(0.0, 0.0, hh / 2.0, hh / 2.0)
                / (std::f64::consts::PI * 2.0)
        };
        assert!(
            rel(sol.approach, self_influence * p) < 1e-9,
            "periodic = {periodic}: {} vs {}",
            sol.approach,
            self_influence * p
        );
    }
}

/// Dimensionless results do not depend on the units: heights, loads and moduli scaled
/// by 1e-9 and 1e9 give the same pressures relative to the load and the same
/// iterations.
#[test]
fn results_scale_with_heights_and_moduli() {
    let n = 32;
    let h = self_affine(n, 0.5, 21);
    let base = |hs: f64, e: f64, periodic: bool| -> Solution {
        let hh: Vec<f64> = h.iter().map(|v| v * hs).collect();
        let load = Load::MeanPressure(0.02 * hs * e);
        if periodic {
            let mut s =
                ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, e), &hh, None).unwrap();
            s.solve(load, &opts(1e-10, 5000), None).unwrap()
        } else {
            let mut s = ContactSolver::new(NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, e), &hh, None)
                .unwrap();
            s.solve(load, &opts(1e-10, 5000), None).unwrap()
        }
    };
    for periodic in [true, false] {
        let r = base(1.0, 1.0, periodic);
        for (hs, e) in [
            (1e-9, 1.0),
            (1e9, 1.0),
            (1.0, 1e-9),
            (1.0, 1e9),
            (1e-9, 1e9),
        ] {
            let s = base(hs, e, periodic);
            assert_eq!(s.contact_cells, r.contact_cells, "h x {hs}, E x {e}");
            let scale = hs * e;
            let worst = s
                .pressure
                .iter()
                .zip(&r.pressure)
                .map(|(a, b)| (a / scale - b).abs())
                .fold(0.0f64, f64::max);
            let pmax = r.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
            assert!(worst <= 1e-9 * pmax, "h x {hs}, E x {e}: {worst}");
            assert!(rel(s.approach / hs, r.approach) < 1e-9);
        }
    }
}

/// A long thin grid (1024 x 4) and its transpose give the same (transposed) solution.
#[test]
fn long_thin_grids_equal_their_transpose() {
    let (nx, ny) = (1024, 4);
    let wave = |i: usize, j: usize| {
        let x = i as f64 / nx as f64;
        0.01 * (2.0 * std::f64::consts::PI * 3.0 * x).cos() + 1e-4 * j as f64
    };
    let a: Vec<f64> = (0..nx * ny).map(|k| wave(k % nx, k / nx)).collect();
    let b: Vec<f64> = (0..nx * ny).map(|k| wave(k / ny, k % ny)).collect(); // 4 x 1024 -> (i = row)
    let (lx, ly) = (1.0, ny as f64 / nx as f64);
    let o = opts(1e-11, 5000);
    for periodic in [true, false] {
        let (sa, sb) = if periodic {
            let mut s =
                ContactSolver::new(PeriodicHalfSpace::new(nx, ny, lx, ly, 1.0), &a, None).unwrap();
            let mut t =
                ContactSolver::new(PeriodicHalfSpace::new(ny, nx, ly, lx, 1.0), &b, None).unwrap();
            (
                s.solve(Load::MeanPressure(0.01), &o, None).unwrap(),
                t.solve(Load::MeanPressure(0.01), &o, None).unwrap(),
            )
        } else {
            let mut s =
                ContactSolver::new(NonPeriodicHalfSpace::new(nx, ny, lx, ly, 1.0), &a, None)
                    .unwrap();
            let mut t =
                ContactSolver::new(NonPeriodicHalfSpace::new(ny, nx, ly, lx, 1.0), &b, None)
                    .unwrap();
            (
                s.solve(Load::MeanPressure(0.01), &o, None).unwrap(),
                t.solve(Load::MeanPressure(0.01), &o, None).unwrap(),
            )
        };
        let pmax = sa.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
        for j in 0..ny {
            for i in 0..nx {
                let (pa, pb) = (sa.pressure[j * nx + i], sb.pressure[i * ny + j]);
                assert!(
                    (pa - pb).abs() <= 1e-8 * pmax,
                    "periodic = {periodic}: ({i}, {j})"
                );
            }
        }
        assert!(rel(sa.approach, sb.approach) < 1e-8);
    }
}

/// A non-periodic rough map pressed beyond complete contact: one solve, every cell
/// in contact, a finite stiffness (no periodic free mode), and the stiffness the same
/// at two loads (the contact set cannot change any more).
#[test]
fn non_periodic_beyond_complete_contact() {
    let n = 24;
    let h = self_affine(n, 0.8, 4);
    let mut s =
        ContactSolver::new(NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None).unwrap();
    // The criterion is relative to the rms height (0.01 here) while the displacements
    // reach hundreds of rms heights: 1e-10 is near the rounding floor of the gap.
    let a = s
        .solve(Load::MeanPressure(2.0), &opts(1e-10, 2000), None)
        .unwrap();
    let b = s
        .solve(Load::MeanPressure(4.0), &opts(1e-10, 2000), None)
        .unwrap();
    assert!(a.complete_contact() && b.complete_contact());
    let ka = s.tangent_stiffness(&a, &opts(1e-12, 2000)).unwrap();
    let kb = s.tangent_stiffness(&b, &opts(1e-12, 2000)).unwrap();
    assert!(ka.is_finite() && ka > 0.0);
    assert!(rel(ka, kb) < 1e-9);
    // And the force-approach relation is linear there with that slope.
    assert!(rel((b.force - a.force) / (b.approach - a.approach), ka) < 1e-7);
}

/// Under force control a cold solve starts from the heights' overlap with a plane
/// (solver module docs), not from uniform pressure. Both starts reach the same solution
/// (the uniform one given as a warm start at the target force); the overlap start needs
/// fewer iterations at low contact fractions and not many more at high ones. (The
/// full-grid iteration: small contact sets would otherwise run restricted.)
#[test]
fn overlap_cold_start_matches_the_uniform_start() {
    let n = 128;
    let h = self_affine(n, 0.8, 5);
    let op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
    let mut s = ContactSolver::new(op, &h, None).unwrap();
    // The plain full-grid iteration (M by transforms, K in double precision): the
    // comparison is of the starts alone.
    let o = SolverOptions {
        paths: Paths::plain(),
        ..opts(1e-10, 5000)
    };
    for (pm, fewer) in [(1e-4, 2.0), (1e-3, 1.5), (1e-2, 0.8)] {
        let cold = s.solve(Load::MeanPressure(pm), &o, None).unwrap();
        let uniform = Solution {
            pressure: vec![pm; n * n],
            approach: 1.0,
            force: pm,
            ..cold.clone()
        };
        let u = s.solve(Load::MeanPressure(pm), &o, Some(&uniform)).unwrap();
        assert!(u.warm_started);
        eprintln!(
            "p = {pm}: contact {:.4}, iterations {} (overlap start) vs {} (uniform)",
            cold.contact_cells as f64 / (n * n) as f64,
            cold.iterations,
            u.iterations
        );
        let pmax = u.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
        for (a, b) in cold.pressure.iter().zip(&u.pressure) {
            assert!((a - b).abs() <= 1e-8 * pmax, "p = {pm}: {a} vs {b}");
        }
        assert!(rel(cold.approach, u.approach) < 1e-8);
        assert!(
            cold.iterations as f64 * fewer <= u.iterations as f64,
            "p = {pm}: {} vs {} iterations",
            cold.iterations,
            u.iterations
        );
    }
}

/// Far beyond complete contact the gap is a small difference of large displacements and
/// double precision cannot resolve it to 1e-10 of the rms height (the solver docs,
/// "Complete contact"): such solves stop at the reachable tolerance in a few dozen
/// iterations (they ran to the cap), and the answer is checked independently. On the
/// free half-space the pressure beyond complete contact is affine in the force (the
/// contact set cannot change): p(F3) - p(F1) = (F3 - F1)/(F2 - F1) (p(F2) - p(F1)). On the
/// periodic one the pressure's fluctuation does not depend on the load at all.
#[test]
fn far_beyond_complete_contact_converges() {
    let n = 128;
    let h = self_affine(n, 0.8, 3);
    let o = opts(1e-10, 500);
    let free = |pm: f64| {
        ContactSolver::new(NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None)
            .unwrap()
            .solve(Load::MeanPressure(pm), &o, None)
            .unwrap()
    };
    let loads = [10.0, 100.0, 1e4];
    let sols: Vec<Solution> = loads.iter().map(|&pm| free(pm)).collect();
    for (s, pm) in sols.iter().zip(loads) {
        assert!(s.complete_contact(), "free, {pm} E*");
        assert!(
            s.iterations < 100,
            "free, {pm} E*: {} iterations",
            s.iterations
        );
        // The reachable tolerance: 1e3 ulps of p L / E* over the rms height (0.01).
        assert!(s.residual <= 1e-10f64.max(1e3 * f64::EPSILON * pm / 0.01) * 1.0001);
    }
    let ratio = (loads[2] - loads[0]) / (loads[1] - loads[0]);
    let peak = sols[2].pressure.iter().fold(0.0f64, |m, &p| m.max(p));
    let off = (0..n * n)
        .map(|i| {
            let d1 = sols[1].pressure[i] - sols[0].pressure[i];
            let d2 = sols[2].pressure[i] - sols[0].pressure[i];
            (d2 - ratio * d1).abs()
        })
        .fold(0.0f64, f64::max);
    // Measured 1.3e-12 of the peak.
    assert!(
        off < 1e-10 * peak,
        "free: affine in the force to {:e}",
        off / peak
    );
    let periodic = |pm: f64| {
        ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None)
            .unwrap()
            .solve(Load::MeanPressure(pm), &o, None)
            .unwrap()
    };
    let (a, b) = (periodic(1.0), periodic(1e6));
    assert!(a.complete_contact() && b.complete_contact());
    // Converged to its floor in 3 iterations, then 10 to see that it stalls.
    assert!(
        b.iterations <= 15,
        "periodic, 1e6 E*: {} iterations",
        b.iterations
    );
    let amp = a
        .pressure
        .iter()
        .fold(0.0f64, |m, &p| m.max((p - 1.0).abs()));
    let off = (0..n * n)
        .map(|i| ((b.pressure[i] - 1e6) - (a.pressure[i] - 1.0)).abs())
        .fold(0.0f64, f64::max);
    // At 1e6 E* the solve stops at its reachable tolerance (1e3 ulps of 1e6 L / E* over
    // the rms height: 2e-5); measured: the fluctuation within 2e-6 of its amplitude.
    assert!(
        off < 1e-5 * amp,
        "periodic: fluctuation moved by {:e}",
        off / amp
    );
}
