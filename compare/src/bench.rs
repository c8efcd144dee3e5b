//! `mrdw bench`: run time against error for the MRD solvers (not a test: figures go to
//! the README's performance section with the command that produced them).

use mrd::discrete::DiscreteAxisymmetric;
use mrd::oscillation::OscillatingContact;
use mrd::reference as rf;
use mrd::{Profile, Shape};
use std::time::Instant;

/// Median wall time of `f` over enough repetitions to fill ~`budget` seconds.
fn time_it<F: FnMut()>(mut f: F, budget: f64) -> f64 {
    let t0 = Instant::now();
    f();
    let once = t0.elapsed().as_secs_f64().max(1e-9);
    let reps = ((budget / once) as usize).clamp(1, 10_000);
    let mut ts: Vec<f64> = (0..reps)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .collect();
    ts.sort_by(f64::total_cmp);
    ts[ts.len() / 2]
}

/// Prints the MRD benchmark table; `max_exp` is the largest log10(N).
pub fn run_mrd(max_exp: u32) {
    let (r, e, g, mu, d) = (1.0, 1.0, 0.8, 0.3, 0.01);
    let sphere = Profile::single(Shape::paraboloid(r).unwrap());
    let a = rf::hertz::radius(r, d);
    let f_target = rf::hertz::force(e, r, d);
    println!(
        "MRD benchmark: Hertz sphere R = 1, E* = 1, d = 0.01 (a = 0.1), springs on [-1.2a, 1.2a]"
    );
    println!("single thread; median of repeated runs\n");
    println!(
        "{:>9} | {:>12} | {:>12} | {:>12} | {:>11} | {:>14} | {:>11}",
        "springs", "setup [s]", "F(d) [s]", "d(F) [s]", "|dF/F|", "cycle [s]", "|dW/W|"
    );
    println!("{}", "-".repeat(99));
    for k in 3..=max_exp {
        let n = 10usize.pow(k);
        let l = 1.2 * a;
        let setup = time_it(
            || drop(DiscreteAxisymmetric::new(&sphere, e, n, l).unwrap()),
            0.3,
        );
        let disc = DiscreteAxisymmetric::new(&sphere, e, n, l).unwrap();
        let t_depth = time_it(
            || {
                std::hint::black_box(disc.state_at_depth(d, false).unwrap());
            },
            0.1,
        );
        let t_force = time_it(
            || {
                std::hint::black_box(disc.state_at_force(f_target, false).unwrap());
            },
            0.1,
        );
        let err_f = (disc.state_at_depth(d, false).unwrap().force / f_target - 1.0).abs();
        let beta = e / g;
        let amp = 0.5 * mu * beta * d;
        let osc = OscillatingContact::new(&sphere, e, g, mu, d, n / 2, l).unwrap();
        let t_cycle = time_it(
            || drop(std::hint::black_box(osc.simulate(amp, 1, 8).unwrap())),
            0.3,
        );
        let w = osc.simulate(amp, 2, 8).unwrap().dissipation;
        let w_exact = rf::mindlin_damping::dissipation_exact(e, beta, r, mu, d, amp);
        println!(
            "{:>9} | {:>12.3e} | {:>12.3e} | {:>12.3e} | {:>11.2e} | {:>14.3e} | {:>11.2e}",
            n,
            setup,
            t_depth,
            t_force,
            err_f,
            t_cycle,
            (w / w_exact - 1.0).abs()
        );
    }
    println!("\nsetup: z1d at N springs + sort + prefix sums (O(N log N)); F(d), d(F): exact solves (O(log N));");
    println!(
        "cycle: one oscillation period in 8 steps (every spring updated per step, O(N) per step)."
    );
}
