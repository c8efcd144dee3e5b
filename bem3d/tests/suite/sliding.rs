//! Steady viscoelastic sliding (`bem3d::sliding`): closed forms, limits against the
//! elastic solver, the two friction routes, grid refinement and determinism.
use crate::common;

use bem3d::{ContactSolver, Load, PeriodicHalfSpace, SlidingContact, SolverOptions};
use common::{dense_reference, max_abs_diff, rel, rough, self_affine};
use rustfft::num_complex::Complex64;
use std::f64::consts::PI;

/// Standard linear solid: E*(omega) = e0 + e1 i omega tau / (1 + i omega tau).
fn zener(e0: f64, e1: f64, tau: f64) -> impl Fn(f64) -> (f64, f64) {
    move |w: f64| {
        let wt = w * tau;
        let d = 1.0 + wt * wt;
        (e0 + e1 * wt * wt / d, e1 * wt / d)
    }
}

/// h = h0 cos(2 pi m x / l) on an nx x ny grid of side l.
fn wave(nx: usize, ny: usize, l: f64, h0: f64, m: f64) -> Vec<f64> {
    let mut h = vec![0.0; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            h[j * nx + i] = h0 * (2.0 * PI * m * i as f64 / nx as f64).cos();
        }
    }
    let _ = l;
    h
}

fn opts(tol: f64) -> SolverOptions {
    SolverOptions::new(tol, 500)
}

#[test]
fn full_contact_sinusoid_matches_the_closed_form() {
    let (nx, ny, l, h0) = (64, 8, 1.0, 1e-3);
    let q = 2.0 * PI / l;
    let modulus = zener(1.0, 10.0, 1.0);
    for &v in &[0.03, 0.3 / q, 1.0 / q, 3.0 / q] {
        let (e1, e2) = modulus(q * v);
        // Full contact needs p_mean > h0 q |E*| / 2.
        let pm = 2.0 * h0 * q * (e1 * e1 + e2 * e2).sqrt();
        let h = wave(nx, ny, l, h0, 1.0);
        let mut s = SlidingContact::new(nx, ny, l, l / 8.0, &h, v, &modulus).unwrap();
        let sol = s.solve(pm, &opts(1e-12), None).unwrap();
        let mut worst = 0.0f64;
        for i in 0..nx {
            let x = 2.0 * PI * i as f64 / nx as f64;
            let p = pm + 0.5 * h0 * q * (e1 * x.cos() + e2 * x.sin());
            worst = worst.max((sol.contact.pressure[i] - p).abs() / pm);
        }
        let mu = q * q * h0 * h0 * e2 / (4.0 * pm);
        eprintln!(
            "v {v}: p err {worst:e}, mu {} {} exact {mu} outer {} inner {}",
            sol.mu, sol.mu_dissipation, sol.contact.iterations, sol.inner_iterations
        );
        assert!(worst < 1e-9, "pressure error {worst:e} at v = {v}");
        assert!(rel(sol.mu, mu) < 1e-9, "mu {} vs {mu}", sol.mu);
        assert!(
            rel(sol.mu_dissipation, mu) < 1e-9,
            "dissipation mu {} vs {mu}",
            sol.mu_dissipation
        );
    }
}

/// The sliding operator as a dense matrix, straight from its definition: the sum over all
/// modes q of C(q) e^{i q.(x_a - x_b)} / N with C(q) = 2 / (|q| conj E*(q_x v)) for
/// q_x >= 0, C(-q) = conj C(q), C(0) = 0 and the storage part alone on the Nyquist
/// column.
fn dense_sliding(
    nx: usize,
    ny: usize,
    l: f64,
    v: f64,
    modulus: &dyn Fn(f64) -> (f64, f64),
) -> Vec<f64> {
    let n = nx * ny;
    let signed = |m: usize, n: usize| {
        if m <= n / 2 {
            m as f64
        } else {
            m as f64 - n as f64
        }
    };
    let mut table = vec![0.0; n];
    for mx in 0..nx {
        for my in 0..ny {
            let (kx, ky) = (2.0 * PI * signed(mx, nx) / l, 2.0 * PI * signed(my, ny) / l);
            let q = (kx * kx + ky * ky).sqrt();
            if q == 0.0 {
                continue;
            }
            let (e1, e2) = modulus(kx.abs() * v);
            let mut c = 2.0 / (q * Complex64::new(e1, -e2));
            if kx < 0.0 {
                c = c.conj();
            }
            if nx.is_multiple_of(2) && mx == nx / 2 {
                c = Complex64::new(c.re, 0.0);
            }
            for dy in 0..ny {
                for dx in 0..nx {
                    let arg = 2.0
                        * PI
                        * (mx as f64 * dx as f64 / nx as f64 + my as f64 * dy as f64 / ny as f64);
                    table[dy * nx + dx] += (c * Complex64::from_polar(1.0, arg)).re / n as f64;
                }
            }
        }
    }
    let mut m = vec![0.0; n * n];
    for a in 0..n {
        for b in 0..n {
            let dx = (a % nx + nx - b % nx) % nx;
            let dy = (a / nx + ny - b / nx) % ny;
            m[a * n + b] = table[dy * nx + dx];
        }
    }
    m
}

#[test]
fn rough_partial_contact_matches_a_dense_active_set_solve() {
    let (n, l) = (16, 1.0);
    let h = rough(n, n, 5);
    let hmax = h.iter().cloned().fold(f64::MIN, f64::max);
    let z: Vec<f64> = h.iter().map(|v| hmax - v).collect();
    // Loss tangent up to ~1.6 (e1 / e0 = 10) near omega tau = 1: v = 1 / k for k ~ 2 pi.
    let modulus = zener(1.0, 10.0, 1.0);
    for &v in &[0.05, 0.2, 1.0] {
        let pm = 0.2;
        let mut s = SlidingContact::new(n, n, l, l, &h, v, &modulus).unwrap();
        let sol = s.solve(pm, &opts(1e-12), None).unwrap();
        let (p_ref, _) = dense_reference(
            &dense_sliding(n, n, l, v, &modulus),
            &z,
            pm * l * l,
            l * l / (n * n) as f64,
        );
        let err = max_abs_diff(&sol.contact.pressure, &p_ref) / pm;
        let area = sol.contact.contact_cells as f64 / (n * n) as f64;
        eprintln!(
            "v {v}: err {err:e} area {area} mu {} {} outer {} inner {}",
            sol.mu, sol.mu_dissipation, sol.contact.iterations, sol.inner_iterations
        );
        assert!(
            err < 1e-8,
            "pressure differs from the dense solve by {err:e} p_mean at v = {v}"
        );
    }
}

#[test]
fn a_constant_modulus_is_the_elastic_solver() {
    let n = 64;
    let h = self_affine(n, 0.8, 3);
    let opts = opts(1e-10);
    let mut s = SlidingContact::new(n, n, 1.0, 1.0, &h, 0.7, &|_| (2.0, 0.0)).unwrap();
    let slide = s.solve(0.05, &opts, None).unwrap();
    let mut e = ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 2.0), &h, None).unwrap();
    let el = e.solve(Load::MeanPressure(0.05), &opts, None).unwrap();
    let err = max_abs_diff(&slide.contact.pressure, &el.pressure) / 0.05;
    eprintln!(
        "elastic: err {err:e}, mu {} {}, outer {}",
        slide.mu, slide.mu_dissipation, slide.contact.iterations
    );
    assert!(err < 1e-8, "{err:e}");
    // No loss, no dissipation; the direct route's <p dh/dx> vanishes only as the grid
    // resolves the contact edges (here 1e-3 of the rms slope).
    let slope = common::rms_slope(&h, n, 1.0);
    assert!(slide.mu_dissipation == 0.0);
    assert!(
        slide.mu.abs() < 1e-3 * slope,
        "{} against slope {slope}",
        slide.mu
    );
    assert!(rel(slide.contact.approach, el.approach) < 1e-8);
}

#[test]
fn slow_and_fast_sliding_are_the_relaxed_and_glassy_elastic_contacts() {
    // Zener: E*(0) = 1, E*(inf) = 11. Below omega tau = 1e-9 on every grid mode the loss
    // part is under 1e-8 of the modulus: the elastic solution with E*(0). Fast: every
    // mode with q_x != 0 is glassy, but modes with q_x = 0 (heights constant along the
    // sliding direction) never change in time and stay relaxed; the limit is the elastic
    // solution of that compliance, and of E*(inf) alone for a surface without such modes.
    let n = 32;
    let h = self_affine(n, 0.8, 4);
    let modulus = zener(1.0, 10.0, 1.0);
    let k_max = PI * n as f64 * 2f64.sqrt();
    let (pm, slow, fast) = (0.01, 1e-9 / k_max, 1e9 * 2.0 * PI);
    let compare = |h: &[f64], ny: usize, v: f64, reference: PeriodicHalfSpace| {
        let mut s = SlidingContact::new(n, ny, 1.0, 1.0, h, v, &modulus).unwrap();
        let slide = s.solve(pm, &opts(1e-10), None).unwrap();
        let el = ContactSolver::new(reference, h, None)
            .unwrap()
            .solve(Load::MeanPressure(pm), &opts(1e-10), None)
            .unwrap();
        let err = max_abs_diff(&slide.contact.pressure, &el.pressure) / pm;
        assert!(
            err < 1e-7,
            "v = {v:e}: pressure differs from the elastic limit by {err:e} p_mean"
        );
        assert!(
            slide.mu_dissipation.abs() < 1e-7,
            "{}",
            slide.mu_dissipation
        );
    };
    compare(&h, n, slow, PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0));
    let glassy_but_kx0 = PeriodicHalfSpace::with_compliance(n, n, 1.0, 1.0, 11.0, |kx, ky| {
        2.0 / ((kx * kx + ky * ky).sqrt() * if kx == 0.0 { 1.0 } else { 11.0 })
    });
    compare(&h, n, fast, glassy_but_kx0);
    let ridges = wave(n, 2, 1.0, 1e-3, 3.0);
    let (e1, e2) = modulus(6.0 * PI * fast);
    assert!(e2 < 1e-8 * e1);
    let pm_ridges = 0.3 * 0.5 * 1e-3 * 6.0 * PI * 11.0;
    let mut s = SlidingContact::new(n, 2, 1.0, 1.0, &ridges, fast, &modulus).unwrap();
    let slide = s.solve(pm_ridges, &opts(1e-10), None).unwrap();
    let el = ContactSolver::new(PeriodicHalfSpace::new(n, 2, 1.0, 1.0, 11.0), &ridges, None)
        .unwrap()
        .solve(Load::MeanPressure(pm_ridges), &opts(1e-10), None)
        .unwrap();
    let err = max_abs_diff(&slide.contact.pressure, &el.pressure) / pm_ridges;
    assert!(err < 1e-7, "ridges: {err:e}");
}

/// mu of a partially contacting sinusoid (1D, on an nx x 2 grid) at the loss peak.
fn partial_sinusoid(nx: usize) -> bem3d::SlidingSolution {
    let h0 = 1e-3;
    let q = 2.0 * PI;
    let modulus = zener(1.0, 10.0, 1.0);
    let v = 1.0 / (q * 11f64.sqrt()); // omega tau = 1 / sqrt(11): peak of E''/E'
    let (e1, e2) = modulus(q * v);
    let pm = 0.3 * 0.5 * h0 * q * (e1 * e1 + e2 * e2).sqrt();
    let h = wave(nx, 2, 1.0, h0, 1.0);
    let mut s = SlidingContact::new(nx, 2, 1.0, 1.0, &h, v, &modulus).unwrap();
    s.solve(pm, &opts(1e-11), None).unwrap()
}

#[test]
fn partial_contact_moves_to_the_leading_side_and_converges_under_refinement() {
    // The surface moves in +x over the half-space: material ahead of the crest (x > 0) is
    // being loaded, behind it unloaded and not yet recovered, so the pressure and the
    // contact patch shift forward (to +x), against the half-space's motion relative to the
    // surface, and the pressure does work against the motion (mu > 0).
    let nx = 256;
    let sol = partial_sinusoid(nx);
    let p = &sol.contact.pressure[..nx];
    let x = |i: usize| {
        if i < nx / 2 {
            i as f64
        } else {
            i as f64 - nx as f64
        }
    };
    let on: Vec<f64> = (0..nx).filter(|&i| p[i] > 0.0).map(x).collect();
    let (lead, trail) = (
        on.iter().cloned().fold(f64::MIN, f64::max),
        on.iter().cloned().fold(f64::MAX, f64::min),
    );
    let centroid = (0..nx).map(|i| p[i] * x(i)).sum::<f64>() / p.iter().sum::<f64>();
    eprintln!("contact {trail}..{lead} cells, pressure centroid {centroid}");
    assert!(
        lead + trail >= 2.0,
        "contact edges {trail}, {lead}: not shifted forward"
    );
    assert!(centroid > 1.0, "pressure centroid {centroid} cells");
    assert!(sol.mu > 0.0 && sol.mu_dissipation > 0.0);
    // Refinement: mu at 32 .. 1024 cells per wavelength against 4096; the two routes agree
    // ever better.
    let fine = partial_sinusoid(4096);
    let mut errors = Vec::new();
    for nx in [64, 128, 256, 512, 1024] {
        let s = partial_sinusoid(nx);
        errors.push((
            nx as f64,
            rel(s.mu, fine.mu),
            rel(s.mu_dissipation, fine.mu_dissipation),
            rel(s.mu, s.mu_dissipation),
        ));
    }
    // Order of convergence: least-squares slope of log error against log cells.
    let order = |pick: fn(&(f64, f64, f64, f64)) -> f64| {
        let pts: Vec<(f64, f64)> = errors.iter().map(|e| (e.0.ln(), pick(e).ln())).collect();
        let (mx, my) = (
            pts.iter().map(|p| p.0).sum::<f64>() / 5.0,
            pts.iter().map(|p| p.1).sum::<f64>() / 5.0,
        );
        -pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
            / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>()
    };
    let (direct, dissipation) = (order(|e| e.1), order(|e| e.2));
    eprintln!("{errors:?}: orders {direct}, {dissipation}");
    // Measured: orders 2.1 and 2.1 (irregular: the contact edges cross cells); the
    // routes differ by 1.4e-3 at 64 cells per wavelength and 4e-6 at 1024.
    assert!(
        direct > 1.5 && dissipation > 1.5,
        "orders {direct}, {dissipation}"
    );
    let last = errors.last().unwrap();
    assert!(last.1 < 1e-5 && last.2 < 2e-5 && last.3 < 1e-5, "{last:?}");
    assert!(errors.iter().all(|e| e.3 < 2e-3), "{errors:?}");
}

#[test]
fn bit_identical_whatever_the_thread_count() {
    let n = 64;
    let h = self_affine(n, 0.7, 9);
    let modulus = zener(1.0, 100.0, 1.0);
    common::same_on_1_and_3_threads(|| {
        let mut s = SlidingContact::new(n, n, 1.0, 1.0, &h, 0.02, &modulus).unwrap();
        let r = s.solve(0.05, &opts(1e-9), None).unwrap();
        (r.contact.pressure, r.mu, r.mu_dissipation)
    });
}

#[test]
fn bad_input_and_non_convergence_are_typed() {
    use bem3d::BemError;
    let n = 16;
    let h = self_affine(n, 0.7, 2);
    let ok = zener(1.0, 10.0, 1.0);
    assert!(matches!(
        SlidingContact::new(n, n, 1.0, 1.0, &h, -1.0, &ok),
        Err(BemError::InvalidInput(_))
    ));
    assert!(matches!(
        SlidingContact::new(n, n, 1.0, 1.0, &h, f64::NAN, &ok),
        Err(BemError::InvalidInput(_))
    ));
    assert!(matches!(
        SlidingContact::new(n, n, 1.0, 1.0, &h[1..], 1.0, &ok),
        Err(BemError::InvalidInput(_))
    ));
    let negative_loss = |w: f64| (1.0, -w);
    match SlidingContact::new(n, n, 1.0, 1.0, &h, 1.0, &negative_loss) {
        Err(BemError::InvalidInput(m)) => assert!(m.contains("E''"), "{m}"),
        _ => panic!("a negative loss modulus must be refused"),
    }
    let mut s = SlidingContact::new(n, n, 1.0, 1.0, &h, 0.1, &ok).unwrap();
    assert!(matches!(
        s.solve(0.0, &opts(1e-9), None),
        Err(BemError::InvalidInput(_))
    ));
    match s.solve(0.05, &SolverOptions::new(1e-14, 2), None) {
        Err(BemError::NoConvergence {
            residual,
            iterations,
            ..
        }) => {
            assert!(residual.is_finite() && residual > 1e-14 && iterations == 2)
        }
        other => panic!("expected NoConvergence, got ok = {}", other.is_ok()),
    }
}
