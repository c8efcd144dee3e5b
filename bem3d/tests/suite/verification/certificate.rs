//! The solver's certificate (bem3d::solver docs, "What a converged solve guarantees"):
//! a converged solve's certificate c is at most the tolerance, and the pressure error
//! against a much tighter solve of the same problem obeys the bound it states,
//! `(p - p*).K(p - p*) <= 2 c F h_rms`, on every path (full grid, candidate set, window;
//! periodic and free), also after a warm start far from the answer.

use super::common::{self, rel, sphere};
use bem3d::*;

const TOL: f64 = 1e-4;

fn options(tolerance: f64) -> SolverOptions {
    SolverOptions {
        tolerance,
        max_iterations: 20_000,
        ..Default::default()
    }
}

/// `(a - b).K(a - b)` with sums times the cell area (the elastic energy of the
/// difference, doubled).
fn energy_norm<K: Compliance>(op: &mut K, a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    let mut u = vec![0.0; d.len()];
    op.apply(&d, &mut u);
    d.iter().zip(&u).map(|(x, y)| x * y).sum::<f64>() * op.cell_area()
}

/// The certificate of `sol` recomputed from scratch (bem3d::solver docs): the gap
/// `g = K p + max(h) - h - approach` from a fresh application of K, then
/// `sum p (g - min(0, min g)) / (sum p h_rms)`.
fn certificate_of<K: Compliance>(op: &mut K, h: &[f64], sol: &Solution, h_rms: f64) -> f64 {
    let mut u = vec![0.0; h.len()];
    op.apply(&sol.pressure, &mut u);
    let top = h.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let g: Vec<f64> = (0..h.len())
        .map(|i| u[i] + top - h[i] - sol.approach)
        .collect();
    let low = g.iter().fold(0.0f64, |m, &v| m.min(v));
    let pg: f64 = sol
        .pressure
        .iter()
        .zip(&g)
        .map(|(p, g)| p * (g - low))
        .sum();
    pg / (sol.pressure.iter().sum::<f64>() * h_rms)
}

/// Solves `load` at TOL (after `warm`, if given), checks the certificate against its
/// recomputation and the tolerance, then the bound it states against a solve to 1e-12
/// under force control at the force reached. Returns the loose solution.
fn check<K: SolverOperator>(
    op: impl Fn() -> K,
    h: &[f64],
    load: Load,
    warm: Option<&Solution>,
    what: &str,
) -> Solution {
    let mut s = ContactSolver::new(op(), h, None).unwrap();
    let a = s.solve(load, &options(TOL), warm).unwrap();
    let again = certificate_of(&mut op(), h, &a, s.h_rms());
    assert!(
        rel(a.certificate, again) < 1e-6,
        "{what}: certificate {:e}, recomputed {again:e}",
        a.certificate
    );
    assert!(
        a.certificate <= TOL && a.certificate > 0.0,
        "{what}: certificate {:e} against the tolerance {TOL:e}",
        a.certificate
    );
    let b = ContactSolver::new(op(), h, None)
        .unwrap()
        .solve(Load::Force(a.force), &options(1e-12), None)
        .unwrap();
    assert!(b.certificate <= 1e-12, "{what}: reference certificate");
    let err = energy_norm(&mut op(), &a.pressure, &b.pressure);
    let bound = 2.0 * a.certificate * a.force * s.h_rms();
    // The bound is far from tight once CG has converged (measured: the error 1e-6 to
    // 3e-4 of it here); it is a guarantee, and the recomputation above checks its value.
    assert!(
        err > 0.0 && err <= bound,
        "{what}: energy error {err:e} against the certificate's bound {bound:e}"
    );
    a
}

#[test]
fn the_certificate_bounds_the_pressure_error_on_every_path() {
    let n = 128;
    let rough = common::self_affine(n, 0.8, 5);
    let periodic = || PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
    let free = || NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
    // Full grid at about 1 % and 20 % contact, and a small contact set (candidate set).
    for (pm, restricted) in [(1e-2, false), (5e-2, false), (1e-4, true)] {
        let a = check(
            periodic,
            &rough,
            Load::MeanPressure(pm),
            None,
            &format!("periodic rough, mean pressure {pm}"),
        );
        assert_eq!(a.restricted(), restricted, "path at mean pressure {pm}");
    }
    // Under displacement control too (against the force-controlled answer at the force
    // reached).
    let at = ContactSolver::new(periodic(), &rough, None)
        .unwrap()
        .solve(Load::MeanPressure(1e-2), &options(1e-12), None)
        .unwrap()
        .approach;
    check(
        periodic,
        &rough,
        Load::Approach(at),
        None,
        "periodic rough, approach",
    );
    // A sphere on the free half-space: a window around its compact contact.
    let ball = sphere(n, 1.0, 1.0);
    let a = check(free, &ball, Load::Force(1e-3), None, "sphere");
    assert!(a.restricted(), "the sphere's solve takes a window");
    check(free, &rough, Load::MeanPressure(1e-2), None, "free rough");
}

/// A warm start far from the answer (another surface's pressure at the same force, so
/// the solver takes it) must not pass the stop: the interpenetration of the cells
/// without pressure counts in the criterion, and the certificate bounds the result as
/// after a cold start.
#[test]
fn a_warm_start_far_from_the_answer_is_not_accepted() {
    let n = 128;
    let op = || PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
    let other = common::self_affine(n, 0.8, 11);
    let rough = common::self_affine(n, 0.8, 5);
    let load = Load::MeanPressure(1e-2);
    let wrong = ContactSolver::new(op(), &other, None)
        .unwrap()
        .solve(load, &options(TOL), None)
        .unwrap();
    let a = check(op, &rough, load, Some(&wrong), "warm start");
    assert!(a.warm_started, "the warm start was taken");
    assert!(
        a.iterations > 5,
        "{} iterations after a wrong start",
        a.iterations
    );
    let cold = ContactSolver::new(op(), &rough, None)
        .unwrap()
        .solve(load, &options(TOL), None)
        .unwrap();
    assert!(rel(a.approach, cold.approach) < 1e-3);
}
