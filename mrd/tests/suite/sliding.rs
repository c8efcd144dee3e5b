//! Sliding friction on viscoelastic springs (Section 10.1) in partial contact: the
//! accelerated steady state equals the natural one, results converge with the time step
//! at a measured order, and do not depend on the Prony discretisation of Eq. (84) once
//! it is fine enough. (Closed-form checks: `mrd::sliding` unit tests.)

use mrd::rheology::{Eq84, Prony};
use mrd::roughness::synthesis::{line_from, Amplitudes};
use mrd::sliding::{slide, Line, Sliding, SlidingResult};
use std::f64::consts::TAU;

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// A band-limited line (flat 2D spectrum on k/sqrt 2 .. k sqrt 2), `waves` over L = 1,
/// n points, rms height 1e-3.
fn band_line(n: usize, waves: f64, seed: u64) -> Line {
    let k0 = TAU * waves;
    let (lo, hi) = (k0 / 2f64.sqrt(), k0 * 2f64.sqrt());
    let z = line_from(
        &|q: f64| if (lo..=hi).contains(&q) { q } else { 0.0 },
        n,
        1.0,
        seed,
        0,
        Amplitudes::Deterministic,
    )
    .unwrap();
    let h = Line::new(&z, 1.0).unwrap().rms_height;
    let z: Vec<f64> = z.iter().map(|v| v * 1e-3 / h).collect();
    Line::new(&z, 1.0).unwrap()
}

fn run(line: &Line, g: &Prony, springs: usize, stride: usize, kv: f64, acc: bool) -> SlidingResult {
    slide(
        line,
        &Sliding {
            modulus: g.scaled(4.0),
            springs,
            stride,
            normal_force: 4.0 * g.relaxed * line.rms_height,
            velocity: kv / line.wave_vector(),
            tolerance: if acc { 1e-9 } else { 0.0 },
            max_passes: if acc { 400 } else { 3000 },
            accelerate: acc,
        },
    )
    .unwrap()
}

/// The unaccelerated dynamics settle (bit-exactly periodic) on the same steady state as
/// the accelerated passes, in partial contact with Eq. (84) at k v = 10 rad/s where the
/// creep takes hundreds of passes.
#[test]
fn accelerated_steady_state_is_the_natural_one() {
    let line = band_line(128, 2.0, 7);
    let g = Eq84::PAPER.prony(12).unwrap();
    let acc = run(&line, &g, 128, 1, 10.0, true);
    let nat = run(&line, &g, 128, 1, 10.0, false);
    assert!(
        acc.converged && nat.converged,
        "{} / {} passes",
        acc.history.len(),
        nat.history.len()
    );
    assert!(nat.history.len() > 5 * acc.history.len());
    assert!(rel(acc.mu, nat.mu) < 1e-6, "{} vs {}", acc.mu, nat.mu);
    assert!((acc.depth - nat.depth).abs() < 1e-5 * line.rms_height);
    assert!(acc.contact_fraction < 0.5, "partial contact");
}

/// Halving the time step (the line moves 8, 4, 2, 1 of its points per step under 256
/// springs): mu converges monotonically at an observed order above 1, the finest two
/// agree to 0.5 %, and the energy route agrees with the slope route to 1 % at the finest.
#[test]
fn time_step_convergence_in_partial_contact() {
    let line = band_line(2048, 4.0, 7);
    let g = Eq84::PAPER.prony(12).unwrap();
    let r: Vec<SlidingResult> = [8, 4, 2, 1]
        .iter()
        .map(|&s| run(&line, &g, 256, s, 10.0, true))
        .collect();
    let mu: Vec<f64> = r.iter().map(|x| x.mu).collect();
    let diffs: Vec<f64> = mu.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    let order = (diffs[0] / diffs[1]).log2();
    assert!(order > 1.0, "order {order}: {mu:?}");
    assert!(diffs[2] < diffs[1] && rel(mu[2], mu[3]) < 5e-3, "{mu:?}");
    assert!(rel(r[3].mu_energy, r[3].mu) < 1e-2, "{:?}", r[3]);
}

/// Results do not depend on the Prony discretisation of Eq. (84) beyond 12 terms.
#[test]
fn independent_of_the_prony_discretisation() {
    let line = band_line(512, 4.0, 3);
    for kv in [0.1, 10.0] {
        let a = run(&line, &Eq84::PAPER.prony(12).unwrap(), 512, 1, kv, true);
        let b = run(&line, &Eq84::PAPER.prony(24).unwrap(), 512, 1, kv, true);
        assert!(rel(a.mu, b.mu) < 1e-3, "kv {kv}: {} vs {}", a.mu, b.mu);
    }
}

/// Without a relaxed modulus there is no steady state under a constant normal force.
#[test]
fn a_material_that_creeps_without_end_is_refused() {
    let line = band_line(64, 2.0, 1);
    let g = Prony::new(0.0, vec![(5.0, 1.0)]).unwrap();
    let e = slide(
        &line,
        &Sliding {
            modulus: g.scaled(4.0),
            springs: 64,
            stride: 1,
            normal_force: 1e-3,
            velocity: 1.0,
            tolerance: 1e-6,
            max_passes: 10,
            accelerate: true,
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("sinks without end"), "{e}");
}
