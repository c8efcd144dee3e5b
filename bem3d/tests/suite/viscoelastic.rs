//! The transient viscoelastic contact (`bem3d::viscoelastic`) against the elastic solver
//! and closed forms in time.

use bem3d::viscoelastic::{Relaxation, TransientContact};
use bem3d::{ContactSolver, Load, NonPeriodicHalfSpace, PeriodicHalfSpace, SolverOptions};
use std::f64::consts::PI;

fn opts() -> SolverOptions {
    SolverOptions::new(1e-11, 5000)
}

/// A transient contact on the periodic unit square of `n x n` cells: the operator's
/// modulus 1, scaled in time by the relaxation function `modulus`.
fn periodic(n: usize, h: &[f64], modulus: Relaxation) -> TransientContact<PeriodicHalfSpace> {
    TransientContact::new(
        PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0),
        h,
        None,
        modulus,
    )
    .unwrap()
}

/// A smooth random-looking periodic surface: a few modes.
fn bumpy(n: usize) -> Vec<f64> {
    (0..n * n)
        .map(|k| {
            let (x, y) = ((k % n) as f64 / n as f64, (k / n) as f64 / n as f64);
            let t = 2.0 * PI;
            1e-3 * ((t * x).cos()
                + 0.6 * (t * (2.0 * x + y) + 1.0).cos()
                + 0.3 * (t * (3.0 * y - x) + 2.0).sin()
                + 0.2 * (t * (5.0 * x + 4.0 * y)).cos())
        })
        .collect()
}

#[test]
fn constant_modulus_steps_are_elastic_solves() {
    let n = 64;
    let h = bumpy(n);
    let modulus = Relaxation::new(2.0, vec![]).unwrap();
    let mut vc = periodic(n, &h, modulus);
    let mut el = ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 2.0), &h, None).unwrap();
    for (i, f) in [1e-4, 5e-4, 2e-3, 5e-4].into_iter().enumerate() {
        let s = vc.step(0.1, Load::Force(f), &opts()).unwrap();
        let e = el.solve(Load::Force(f), &opts(), None).unwrap();
        let peak = e.pressure.iter().cloned().fold(0.0, f64::max);
        let diff = s
            .pressure
            .iter()
            .zip(&e.pressure)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(diff < 1e-8 * peak, "step {i}: {diff} of {peak}");
        assert!(
            (s.approach - e.approach).abs() < 1e-9 * e.approach,
            "step {i}"
        );
        assert!((s.force / f - 1.0).abs() < 1e-12);
        assert!(s.contact_cells > 0 && s.contact_cells < n * n);
    }
}

#[test]
fn sinusoid_in_full_contact_relaxes_as_the_closed_form() {
    // h = h0 cos(2 pi x) pressed at a mean pressure far above pi E*(0) h0: complete
    // contact from the first step on, so u's varying part is h - mean h from t = dt on,
    // reached linearly over the first step. Its pressure amplitude is then the elastic
    // one (unit modulus) times (1/dt) Int_0^dt E*(t - s) ds, for every t >= dt.
    let (nx, ny, h0) = (64, 4, 1e-3);
    let h: Vec<f64> = (0..nx * ny)
        .map(|k| h0 * (2.0 * PI * (k % nx) as f64 / nx as f64).cos())
        .collect();
    let modulus = Relaxation::new(1.0, vec![(4.0, 0.5), (2.0, 0.05)]).unwrap();
    let p_mean = 0.2;
    assert!(p_mean > 2.0 * PI * modulus.glassy() * h0);
    let amplitude = |p: &[f64]| -> f64 {
        2.0 / (nx * ny) as f64
            * p.iter()
                .enumerate()
                .map(|(k, v)| v * (2.0 * PI * (k % nx) as f64 / nx as f64).cos())
                .sum::<f64>()
    };
    let mut el =
        ContactSolver::new(PeriodicHalfSpace::new(nx, ny, 1.0, 1.0, 1.0), &h, None).unwrap();
    let unit = amplitude(
        &el.solve(Load::MeanPressure(p_mean), &opts(), None)
            .unwrap()
            .pressure,
    );
    let mut vc = TransientContact::new(
        PeriodicHalfSpace::new(nx, ny, 1.0, 1.0, 1.0),
        &h,
        None,
        modulus.clone(),
    )
    .unwrap();
    let dt = 0.02;
    for step in 1..=100 {
        let s = vc.step(dt, Load::MeanPressure(p_mean), &opts()).unwrap();
        assert_eq!(s.contact_cells, nx * ny, "complete contact");
        let t = s.time;
        let exact = modulus.relaxed
            + modulus
                .terms
                .iter()
                .map(|&(e, tau)| e * tau / dt * (1.0 - (-dt / tau).exp()) * (-(t - dt) / tau).exp())
                .sum::<f64>();
        let got = amplitude(&s.pressure) / unit;
        assert!(
            (got / exact - 1.0).abs() < 1e-8,
            "step {step}, t = {t}: {got} vs {exact}"
        );
    }
}

/// Creep compliance of E*(t) = e_inf + e1 exp(-t/tau) (standard linear solid) and its
/// integral from 0 to t.
fn creep(e_inf: f64, e1: f64, tau: f64, t: f64) -> (f64, f64) {
    let e0 = e_inf + e1;
    let tc = tau * e0 / e_inf;
    let c = 1.0 / e_inf - 1.0 / e0;
    (
        1.0 / e_inf - c * (-t / tc).exp(),
        t / e_inf - c * tc * (1.0 - (-t / tc).exp()),
    )
}

/// The flat punch's approach under a force history sampled at steps of dt up to t_end,
/// relative to its elastic approach at unit modulus and unit force (the discrete
/// compliance c: the contact set is the whole disc at every load, so D(t) = c Int
/// J(t - s) dF(s) exactly in continuous time).
fn punch_creep(force: &dyn Fn(f64) -> f64, dt: f64, t_end: f64) -> Vec<(f64, f64)> {
    let n = 24;
    let mask = bem3d::mask::disc(n, n, 1.0, 1.0, 0.5);
    let flat = vec![0.0; n * n];
    let mut el = ContactSolver::new(
        NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0),
        &flat,
        Some(mask.clone()),
    )
    .unwrap();
    let c = el.solve(Load::Force(1.0), &opts(), None).unwrap().approach;
    let modulus = Relaxation::new(1.0, vec![(3.0, 1.0)]).unwrap();
    let mut vc = TransientContact::new(
        NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0),
        &flat,
        Some(mask),
        modulus,
    )
    .unwrap();
    let steps = (t_end / dt).round() as usize;
    (1..=steps)
        .map(|k| {
            let s = vc
                .step(dt, Load::Force(force(k as f64 * dt)), &opts())
                .unwrap();
            (s.time, s.approach / c)
        })
        .collect()
}

#[test]
fn flat_punch_creep_under_a_step_and_a_ramp_converges_to_the_closed_form() {
    // Step load F = 1 from t = 0: D/c = J(t); the first step ramps it over dt, so the
    // error is first order in dt.
    let err_step = |dt: f64| {
        let r = punch_creep(&|_| 1.0, dt, 4.0);
        let (t, d) = *r.last().unwrap();
        (d / creep(1.0, 3.0, 1.0, t).0 - 1.0).abs()
    };
    let (e1, e2) = (err_step(0.2), err_step(0.1));
    assert!(e2 < 0.02, "{e2}");
    let order = (e1 / e2).log2();
    assert!(
        (0.8..1.3).contains(&order),
        "step load: order {order} ({e1}, {e2})"
    );
    // Ramp F = t / 2 up to t = 2, held after: D/c = Int_0^t J(s) ds / 2 on the ramp; the
    // displacement is smooth in time, the error second order.
    let ramp = |t: f64| 0.5 * t.min(2.0);
    let err_ramp = |dt: f64| {
        punch_creep(&ramp, dt, 2.0)
            .iter()
            .map(|&(t, d)| (d - 0.5 * creep(1.0, 3.0, 1.0, t).1).abs())
            .fold(0.0, f64::max)
    };
    let (r1, r2) = (err_ramp(0.2), err_ramp(0.1));
    let order = (r1 / r2).log2();
    assert!(r2 < 2e-3, "{r2}");
    assert!(
        (1.7..2.4).contains(&order),
        "ramp: order {order} ({r1}, {r2})"
    );
}

#[test]
fn lifted_off_surface_recovers_and_bad_steps_are_refused() {
    let n = 32;
    let h = bumpy(n);
    let modulus = Relaxation::new(1.0, vec![(2.0, 0.2)]).unwrap();
    let mut vc = periodic(n, &h, modulus);
    let mut loaded = 0.0f64;
    for k in 1..=5 {
        let s = vc
            .step(0.05, Load::Approach(2e-4 * k as f64), &opts())
            .unwrap();
        loaded = loaded.max(vc.displacement().iter().cloned().fold(0.0, f64::max));
        assert!(s.force > 0.0);
    }
    // Lift off: no contact, no force, the medium recovers towards u = 0.
    for _ in 0..300 {
        let s = vc.step(0.05, Load::Approach(-1e-3), &opts()).unwrap();
        assert_eq!((s.force, s.contact_cells), (0.0, 0));
        assert!(s.solve.is_none());
    }
    let left = vc
        .displacement()
        .iter()
        .map(|v| v.abs())
        .fold(0.0, f64::max);
    // Free recovery under zero pressure decays with the retardation time
    // tau E*(0) / E_inf = 0.6: after 15 s, exp(-25).
    assert!(loaded > 0.0 && left < 1e-6 * loaded, "{left} of {loaded}");
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(
            vc.step(dt, Load::Force(1e-4), &opts()).is_err(),
            "dt = {dt}"
        );
    }
    // A load beyond the bound is refused naming the value given (the solve sees it
    // scaled by E*(0) / E_eff).
    let e = vc.step(0.05, Load::Force(1e300), &opts()).unwrap_err();
    assert!(
        e.to_string()
            .contains("a force of 1e300 is a mean pressure of 1e300"),
        "{e}"
    );
    for (e_inf, terms) in [
        (-1.0, vec![]),
        (0.0, vec![]),
        (1.0, vec![(0.0, 1.0)]),
        (1.0, vec![(1.0, -1.0)]),
        (f64::NAN, vec![]),
    ] {
        assert!(Relaxation::new(e_inf, terms).is_err());
    }
}

/// Li, Brenner & Frerot (arXiv 2511.19402, 2025) prove that for any linear viscoelastic
/// medium the contact area cannot decrease while a reduced load is held after a load
/// decrease. Checked here on a rough periodic surface with two relaxation times: load,
/// hold, drop to a quarter, hold; the contact cells never decrease after the drop (and
/// they do grow: the medium creeps).
#[test]
fn area_does_not_decrease_after_a_load_decrease() {
    let n = 64;
    let h = bumpy(n);
    let modulus = Relaxation::new(1.0, vec![(3.0, 0.2), (2.0, 2.0)]).unwrap();
    let mut vc = periodic(n, &h, modulus);
    let f1 = 2e-3;
    for _ in 0..30 {
        vc.step(0.05, Load::Force(f1), &opts()).unwrap();
    }
    let mut cells = Vec::new();
    for _ in 0..80 {
        cells.push(
            vc.step(0.05, Load::Force(f1 / 4.0), &opts())
                .unwrap()
                .contact_cells,
        );
    }
    for w in cells.windows(2) {
        assert!(w[1] >= w[0], "{cells:?}");
    }
    assert!(cells[79] > cells[0], "{cells:?}");
}

/// The stiffness S = K^-1 of a periodic unit-modulus operator on zero-mean fields, by
/// its Fourier multiplier (K is circulant: its response to a point load, transformed).
struct Stiffness {
    n: usize,
    inverse: Vec<f64>,
}

impl Stiffness {
    fn new(n: usize) -> Self {
        use bem3d::Compliance;
        let mut op = PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0);
        let mut delta = vec![0.0; n * n];
        delta[0] = 1.0;
        let mut kernel = vec![0.0; n * n];
        op.apply(&delta, &mut kernel);
        let spectrum = Self::dft(
            n,
            &kernel.iter().map(|&v| (v, 0.0)).collect::<Vec<_>>(),
            -1.0,
        );
        let inverse = spectrum
            .iter()
            .enumerate()
            .map(|(k, c)| if k == 0 { 0.0 } else { 1.0 / c.0 })
            .collect();
        Self { n, inverse }
    }

    /// Naive 2D DFT (sign -1 forward, +1 backward without normalisation).
    fn dft(n: usize, x: &[(f64, f64)], sign: f64) -> Vec<(f64, f64)> {
        let mut out = vec![(0.0, 0.0); n * n];
        for ky in 0..n {
            for kx in 0..n {
                let mut acc = (0.0, 0.0);
                for y in 0..n {
                    for xx in 0..n {
                        let ph = sign * 2.0 * PI * ((kx * xx + ky * y) as f64) / n as f64;
                        let (c, s) = (ph.cos(), ph.sin());
                        let v = x[y * n + xx];
                        acc.0 += v.0 * c - v.1 * s;
                        acc.1 += v.0 * s + v.1 * c;
                    }
                }
                out[ky * n + kx] = acc;
            }
        }
        out
    }

    /// a . S b for zero-mean a, b.
    fn energy(&self, a: &[f64], b: &[f64]) -> f64 {
        let n = self.n;
        let fb = Self::dft(n, &b.iter().map(|&v| (v, 0.0)).collect::<Vec<_>>(), -1.0);
        let sb: Vec<(f64, f64)> = fb
            .iter()
            .zip(&self.inverse)
            .map(|(c, s)| (c.0 * s, c.1 * s))
            .collect();
        let back = Self::dft(n, &sb, 1.0);
        a.iter()
            .zip(&back)
            .map(|(x, y)| x * y.0 / (n * n) as f64)
            .sum()
    }
}

#[test]
fn work_equals_stored_plus_dissipated_energy() {
    // Approach-controlled press, hold and partial withdrawal of a rough periodic surface
    // on a standard linear solid; the hereditary variables are rebuilt from the
    // displacement history (exact for piecewise-linear u). Work sum_i p_i du_i and
    // dissipation (E1 / tau) h.S h dt by the trapezoidal rule: the balance closes to
    // second order in dt.
    let n = 16;
    let h = bumpy(n);
    let (e_inf, e1, tau) = (1.0, 3.0, 0.3);
    let imbalance = |dt: f64| -> (f64, f64) {
        let modulus = Relaxation::new(e_inf, vec![(e1, tau)]).unwrap();
        let mut vc = periodic(n, &h, modulus);
        let s = Stiffness::new(n);
        let steps = (3.0 / dt).round() as usize;
        let approach = |t: f64| {
            4e-4 * if t < 1.0 {
                t
            } else if t < 2.0 {
                1.0
            } else {
                2.0 - 0.5 * t
            }
        };
        let (mut u_old, mut p_old, mut hk) = (vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]);
        let (mut work, mut dissipated) = (0.0, 0.0);
        let mut diss_old = 0.0;
        let area = 1.0 / (n * n) as f64;
        for k in 1..=steps {
            let st = vc
                .step(dt, Load::Approach(approach(k as f64 * dt)), &opts())
                .unwrap();
            let u = vc.displacement().to_vec();
            let a = (-dt / tau).exp();
            let b = tau / dt * (1.0 - a);
            for i in 0..n * n {
                hk[i] = a * hk[i] + b * (u[i] - u_old[i]);
            }
            work += 0.5
                * area
                * (0..n * n)
                    .map(|i| (st.pressure[i] + p_old[i]) * (u[i] - u_old[i]))
                    .sum::<f64>();
            let diss = area * e1 / tau * s.energy(&hk, &hk);
            dissipated += 0.5 * dt * (diss + diss_old);
            diss_old = diss;
            u_old = u;
            p_old = st.pressure;
        }
        let stored = 0.5 * area * (e_inf * s.energy(&u_old, &u_old) + e1 * s.energy(&hk, &hk));
        (work, (work - stored - dissipated).abs() / work)
    };
    let (w1, r1) = imbalance(0.05);
    let (_, r2) = imbalance(0.025);
    assert!(w1 > 0.0);
    assert!(r2 < 1e-3, "{r1} {r2}");
    assert!(r1 / r2 > 3.0, "second order: {r1} {r2}");
}
