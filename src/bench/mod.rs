//! `mrdw bench`: run time against error for the MRD solvers (not a test: figures go to
//! the README's performance section with the command that produced them).

mod adhesion;
pub mod common;
mod families;
mod large;
mod plastic;
pub mod report;
mod rough_ladder;
mod tangential;
mod viscoelastic;
pub use adhesion::run_adhesion;
pub use families::run_families;
pub use large::{run_large, run_large_case};
pub use plastic::run_plastic;
pub use tangential::run_tangential;
pub use viscoelastic::run_viscoelastic;

use common::{child_error, field, peak_memory_mib, reference_surface, Case, Result};
use mrd::discrete::DiscreteAxisymmetric;
use mrd::oscillation::OscillatingContact;
use mrd::reference as rf;
use mrd::{Profile, Shape};
use std::io::Write;
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
pub fn run_mrd(w: &mut dyn Write, max_exp: u32) -> Result<()> {
    let (r, e, g, mu, d) = (1.0, 1.0, 0.8, 0.3, 0.01);
    let sphere = Profile::single(Shape::paraboloid(r).case("sphere")?);
    let a = rf::hertz::radius(r, d);
    let f_target = rf::hertz::force(e, r, d);
    writeln!(
        w,
        "MRD benchmark: Hertz sphere R = 1, E* = 1, d = 0.01 (a = 0.1), springs on [-1.2a, 1.2a]"
    )?;
    writeln!(w, "single thread; median of repeated runs\n")?;
    writeln!(
        w,
        "{:>9} | {:>12} | {:>12} | {:>12} | {:>11} | {:>14} | {:>11}",
        "springs", "setup [s]", "F(d) [s]", "d(F) [s]", "|dF/F|", "cycle [s]", "|dW/W|"
    )?;
    writeln!(w, "{}", "-".repeat(99))?;
    for k in 3..=max_exp {
        let n = 10usize.pow(k);
        let l = 1.2 * a;
        let case = format!("{n} springs");
        // Each timed call ran once, checked, before it is timed.
        let disc = DiscreteAxisymmetric::new(&sphere, e, n, l).case(&case)?;
        let setup = time_it(
            || {
                drop(std::hint::black_box(DiscreteAxisymmetric::new(
                    &sphere, e, n, l,
                )))
            },
            0.3,
        );
        let at_depth = disc.state_at_depth(d, false).case(&case)?;
        disc.state_at_force(f_target, false).case(&case)?;
        let t_depth = time_it(
            || drop(std::hint::black_box(disc.state_at_depth(d, false))),
            0.1,
        );
        let t_force = time_it(
            || drop(std::hint::black_box(disc.state_at_force(f_target, false))),
            0.1,
        );
        let err_f = (at_depth.force / f_target - 1.0).abs();
        let beta = e / g;
        let amp = 0.5 * mu * beta * d;
        let osc = OscillatingContact::new(&sphere, e, g, mu, d, n / 2, l).case(&case)?;
        osc.simulate(amp, 1, 8).case(&case)?;
        let t_cycle = time_it(|| drop(std::hint::black_box(osc.simulate(amp, 1, 8))), 0.3);
        let w_sim = osc.simulate(amp, 2, 8).case(&case)?.dissipation;
        let w_exact = rf::mindlin_damping::dissipation_exact(e, beta, r, mu, d, amp);
        writeln!(
            w,
            "{:>9} | {:>12.3e} | {:>12.3e} | {:>12.3e} | {:>11.2e} | {:>14.3e} | {:>11.2e}",
            n,
            setup,
            t_depth,
            t_force,
            err_f,
            t_cycle,
            (w_sim / w_exact - 1.0).abs()
        )?;
    }
    writeln!(w, "\nsetup: z1d at N springs + sort + prefix sums (O(N log N)); F(d), d(F): exact solves (O(log N));")?;
    writeln!(
        w,
        "cycle: one oscillation period in 8 steps (every spring updated per step, O(N) per step)."
    )?;
    Ok(())
}

/// One convolution on an `nx x ny` grid (a forward and an inverse transform with a
/// product between, as the operators apply K and M).
fn fft_pair_time(nx: usize, ny: usize) -> f64 {
    let mut f = bem3d::fft::Fft2::new(nx, ny);
    let x: Vec<f64> = (0..nx * ny).map(|k| (k % 7) as f64).collect();
    let symbol = vec![0.5; f.spectrum_len()];
    let mut y = vec![0.0; nx * ny];
    time_it(|| f.convolve(&x, (nx, ny), &symbol, &mut y), 0.3)
}

/// Time of one application of K and of M (the preconditioner) of `op`, in seconds:
/// with the solve's iterations they split an iteration into K, M and the rest (the
/// sweeps, fresh `K p` where the projection changed many cells, the set-up's share).
fn operator_times<K: bem3d::SolverOperator>(mut op: K) -> (f64, f64) {
    let n = op.cells();
    let x: Vec<f64> = (0..n).map(|k| (k % 7) as f64).collect();
    let mut y = vec![0.0; n];
    let k = time_it(|| op.apply(&x, &mut y), 0.3);
    let m = time_it(|| op.precondition(&mut y), 0.3);
    (k, m)
}

/// One benchmark case, run in its own process so that its peak memory is its own.
/// Prints one machine-readable line `RESULT key=value ...`.
pub fn run_bem_case(
    w: &mut dyn Write,
    kind: &str,
    n: usize,
    write_dir: Option<&std::path::Path>,
) -> std::result::Result<(), String> {
    use bem3d::*;
    let opts = SolverOptions {
        tolerance: 1e-10,
        max_iterations: 50_000,
        ..Default::default()
    };
    let tight = SolverOptions {
        tolerance: 1e-12,
        max_iterations: 100_000,
        ..Default::default()
    };
    if !matches!(kind, "periodic" | "sparse" | "hertz") {
        return Err(format!(
            "unknown benchmark case {kind:?}: periodic, sparse or hertz"
        ));
    }
    if !(16..=16384).contains(&n) {
        return Err(format!("grid side n = {n} must lie in 16..=16384"));
    }
    // The operator and solver here, and the reference solve's copy.
    bem3d::operator::HalfSpace {
        nx: n,
        ny: n,
        lx: 1.0,
        ly: 1.0,
        e_star: 1.0,
    }
    .check(kind != "hertz")
    .map_err(|e| e.to_string())?;
    let failed = |e: bem3d::BemError| e.to_string();
    let stdout = |e: std::io::Error| format!("writing to standard output: {e}");
    // The periodic surface at 20 % contact, or at 0.1 % ("sparse": a restricted solve).
    let periodic = kind != "hertz";
    let mean_pressure = if kind == "sparse" { 5e-5 } else { 0.01 };
    let (pair, (k_time, m_time)) = if periodic {
        (
            fft_pair_time(n, n),
            operator_times(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0)),
        )
    } else {
        (
            fft_pair_time(2 * n, 2 * n),
            operator_times(NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0)),
        )
    };
    let base_mem = peak_memory_mib().unwrap_or(0.0);
    let (t, sol, err) = if periodic {
        let h = reference_surface(n).map_err(|e| e.to_string())?;
        let t0 = Instant::now();
        let mut s = ContactSolver::new(PeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &h, None)
            .map_err(failed)?;
        let sol = s
            .solve(Load::MeanPressure(mean_pressure), &opts, None)
            .map_err(failed)?;
        let t = t0.elapsed().as_secs_f64();
        let mem = peak_memory_mib().unwrap_or(0.0);
        let refsol = s
            .solve(Load::MeanPressure(mean_pressure), &tight, None)
            .map_err(failed)?;
        let num: f64 = sol
            .pressure
            .iter()
            .zip(&refsol.pressure)
            .map(|(a, b)| (a - b).powi(2))
            .sum();
        let den: f64 = refsol.pressure.iter().map(|b| b * b).sum();
        if let (Some(dir), "periodic") = (write_dir, kind) {
            let written = |e: mrd::MrdError| format!("--write-surfaces: {e}");
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("--write-surfaces {}: {e}", dir.display()))?;
            let hm = mrd::topography::HeightMap {
                rows: n,
                cols: n,
                data: h.clone(),
            };
            hm.write_npy(&dir.join(format!("surface_{n}.npy")))
                .map_err(written)?;
            let pm = mrd::topography::HeightMap {
                rows: n,
                cols: n,
                data: sol.pressure.clone(),
            };
            pm.write_npy(&dir.join(format!("mrdw_pressure_{n}.npy")))
                .map_err(written)?;
        }
        writeln!(w, "RESULT kind={kind} n={n} time={t:e} iterations={} pair={pair:e} k={k_time:e} m={m_time:e} mem={:.1} base_mem={base_mem:.1} err_pressure_l2={:e} err_approach={:e} area={:e} restricted={}",
            sol.iterations, mem, (num / den).sqrt(), ((sol.approach - refsol.approach) / refsol.approach).abs(), sol.contact_area, sol.restricted() as u8).map_err(stdout)?;
        return Ok(());
    } else {
        let (a, r) = (0.25, 1.0);
        let hgt: Vec<f64> = (0..n * n)
            .map(|k| {
                let h = 1.0 / n as f64;
                let (x, y) = (
                    ((k % n) as f64 - (n / 2) as f64) * h,
                    ((k / n) as f64 - (n / 2) as f64) * h,
                );
                -(x * x + y * y) / (2.0 * r)
            })
            .collect();
        let f = 4.0 * a * a * a / (3.0 * r);
        let t0 = Instant::now();
        let mut s = ContactSolver::new(NonPeriodicHalfSpace::new(n, n, 1.0, 1.0, 1.0), &hgt, None)
            .map_err(failed)?;
        let sol = s.solve(Load::Force(f), &opts, None).map_err(failed)?;
        let t = t0.elapsed().as_secs_f64();
        let pmax = sol.pressure.iter().fold(0.0f64, |m, &v| m.max(v));
        let err = (
            (pmax / (2.0 * a / (std::f64::consts::PI * r)) - 1.0).abs(),
            (sol.approach / (a * a / r) - 1.0).abs(),
        );
        (t, sol, err)
    };
    writeln!(w, "RESULT kind=hertz n={n} time={t:e} iterations={} pair={pair:e} k={k_time:e} m={m_time:e} mem={:.1} base_mem={base_mem:.1} err_peak={:e} err_approach={:e} restricted={}",
        sol.iterations, peak_memory_mib().unwrap_or(0.0), err.0, err.1, sol.restricted() as u8).map_err(stdout)?;
    Ok(())
}

/// `mrdw bench bem`: each case in a fresh process of this executable (`mrdw bench-case
/// KIND N`), so that its peak memory is its own; periodic grids from 128^2 to `max_n`,
/// the same at 0.1 % contact ("sparse") and non-periodic Hertz from 128^2 to
/// min(max_n, 1024)^2.
pub fn run_bem(
    w: &mut dyn Write,
    max_n: usize,
    write_surfaces: Option<&std::path::Path>,
) -> std::result::Result<(), String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut lines = Vec::new();
    for kind in ["periodic", "sparse", "hertz"] {
        let mut n = 128;
        while n <= max_n && (kind == "periodic" || n <= 1024) {
            let _ = writeln!(std::io::stderr(), "running {kind} {n}^2 ...");
            let mut cmd = std::process::Command::new(&exe);
            cmd.args(["bench-case", kind, &n.to_string()]);
            if let (Some(d), "periodic") = (write_surfaces, kind) {
                cmd.arg("--write-surfaces").arg(d);
            }
            let out = cmd.output().map_err(|e| e.to_string())?;
            if !out.status.success() {
                let reason = child_error(&out.stderr);
                return Err(format!("benchmark case {kind} {n} failed: {reason}"));
            }
            lines.extend(
                String::from_utf8_lossy(&out.stdout)
                    .lines()
                    .filter(|l| l.starts_with("RESULT"))
                    .map(String::from),
            );
            n *= 2;
        }
    }
    print_bem_table(w, &lines).map_err(|e| format!("writing to standard output: {e}"))
}

/// Parses the RESULT lines of child runs and prints the table.
fn print_bem_table(w: &mut dyn Write, lines: &[String]) -> std::io::Result<()> {
    writeln!(
        w,
        "{:>9} | {:>6} | {:>9} | {:>6} | {:>6} | {:>10} | {:>11} | {:>10} | {:>8} | {:>8} | {:>9} | {:>9} | {:>10} | {:>10}",
        "case",
        "grid",
        "time [s]",
        "iters",
        "path",
        "t/iter [s]",
        "t/iter/FFT",
        "t/FFT",
        "K [ms]",
        "M [ms]",
        "rest [ms]",
        "mem [MiB]",
        "error 1",
        "error 2"
    )?;
    writeln!(w, "{}", "-".repeat(161))?;
    for l in lines {
        let kind = ["periodic", "sparse", "hertz"]
            .into_iter()
            .find(|k| l.contains(&format!("kind={k} ")))
            .unwrap_or("?");
        let (t, it, pair) = (field(l, "time"), field(l, "iterations"), field(l, "pair"));
        let (k, m) = (field(l, "k"), field(l, "m"));
        let (e1, e2) = if kind != "hertz" {
            (field(l, "err_pressure_l2"), field(l, "err_approach"))
        } else {
            (field(l, "err_peak"), field(l, "err_approach"))
        };
        // Restricted solves iterate on a window or a candidate set: their iterations
        // are not full-grid ones, so the per-iteration split does not apply.
        let path = match (field(l, "restricted") == 1.0, kind) {
            (false, _) => "full",
            (true, "hertz") => "window",
            (true, _) => "dense",
        };
        let per_iteration = |v: f64| {
            if path == "full" {
                format!("{v:.2}")
            } else {
                "-".into()
            }
        };
        writeln!(
            w,
"{:>9} | {:>6} | {:>9.3} | {:>6} | {:>6} | {:>10.3e} | {:>11} | {:>10.0} | {:>8.3} | {:>8.3} | {:>9} | {:>9.0} | {:>10.2e} | {:>10.2e}",
            kind,
            format!("{}^2", field(l, "n")),
            t,
            it,
            path,
            t / it.max(1.0),
            per_iteration(t / it.max(1.0) / pair),
            t / pair,
            k * 1e3,
            m * 1e3,
            per_iteration((t / it.max(1.0) - k - m) * 1e3),
            field(l, "mem") - 0.0,
            e1,
            e2
        )?;
    }
    writeln!(
        w,
        "\nperiodic: self-affine H = 0.8, rms slope 0.1, mean pressure 0.01 E*, tolerance 1e-10;"
    )?;
    writeln!(w, "  error 1 = relative L2 pressure error, error 2 = relative approach error, both against a 1e-12 run.")?;
    writeln!(
        w,
        "sparse: the same surfaces at mean pressure 5e-5 E* (0.1 % contact); errors as periodic."
    )?;
    writeln!(
        w,
        "hertz: non-periodic, R = 1, a = L/4, force control, tolerance 1e-10;"
    )?;
    writeln!(
        w,
        "  error 1 = peak pressure, error 2 = approach, relative to Hertz."
    )?;
    writeln!(
        w,
        "path: full = the full-grid iteration; window = solved on a window around the contact (its"
    )?;
    writeln!(
        w,
        "  iterations on the window); dense = solved on a candidate set with a dense K (iterations:"
    )?;
    writeln!(
        w,
        "  applications of that K); t/iter/FFT and rest then do not apply (bem3d::solver docs)."
    )?;
    writeln!(
        w,
        "t/iter/FFT: time per iteration over one FFT pair (a convolution) of the (padded) grid"
    )?;
    writeln!(
        w,
        "  (an iteration applies K and the preconditioner once each, and K p where the projection"
    )?;
    writeln!(
        w,
        "  changed too many cells); t/FFT: the whole solve (set-up included) in FFT-pair times;"
    )?;
    writeln!(
        w,
        "K, M: one application of the operator and of the preconditioner alone; rest = t/iter - K - M"
    )?;
    writeln!(
        w,
        "  (the sweeps not fused into K and M, fresh K p, the set-up's share per iteration);"
    )?;
    writeln!(
        w,
        "mem: peak resident memory of the whole process running that case."
    )?;
    Ok(())
}

/// `mrdw bench rough`: a rough line of N points (generation) and a 100-point k(F) curve
/// on it, N = 1e3 .. 10^max_exp, single thread.
pub fn run_rough(w: &mut dyn Write, max_exp: u32) -> Result<()> {
    use mrd::rough_contact::RoughLine;
    use mrd::roughness::synthesis::{line, Amplitudes};
    use mrd::roughness::SelfAffine;
    use std::f64::consts::PI;
    writeln!(w, "rough-line benchmark: H = 0.7, spectrum 2 pi/L .. half Nyquist, 100 forces from f = 1e-6 to 1e-1")?;
    writeln!(w, "single thread; median of repeated runs\n")?;
    writeln!(
        w,
        "{:>10} | {:>12} | {:>12} | {:>12} | {:>12} | {:>14}",
        "points", "line [s]", "setup [s]", "k(F) x100 [s]", "total [s]", "total/(N log2 N)"
    )?;
    writeln!(w, "{}", "-".repeat(88))?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .case("a one-thread pool")?;
    // Rows are collected in the single-thread pool and printed after it.
    let mut buf: Vec<u8> = Vec::new();
    pool.install(|| -> Result<()> {
        for e in 3..=max_exp {
            let n = 10usize.pow(e);
            let case = format!("a rough line of {n} points");
            let spec = SelfAffine::new(0.7, 2.0 * PI, 2.0 * PI, PI * n as f64 * 0.5)
                .and_then(|s| s.to_line(PI).with_rms_height(1.0))
                .case(&case)?;
            let budget = if e >= 7 { 0.5 } else { 0.3 };
            // Each timed call ran once, checked, before it is timed.
            let h = line(&spec, n, 1.0, 1, 0, Amplitudes::Deterministic).case(&case)?;
            let t_gen = time_it(
                || {
                    drop(std::hint::black_box(line(
                        &spec,
                        n,
                        1.0,
                        1,
                        0,
                        Amplitudes::Deterministic,
                    )))
                },
                budget,
            );
            let rl = RoughLine::new(&h, 1.0, 1.0).case(&case)?;
            let t_setup = time_it(
                || drop(std::hint::black_box(RoughLine::new(&h, 1.0, 1.0))),
                budget,
            );
            let fs = mrd::friction::log_space(1e-6, 1e-1, 100);
            for &f in &fs {
                rl.at_force(f * rl.rms_height).case(&case)?;
            }
            let t_curve = time_it(
                || {
                    for &f in &fs {
                        drop(std::hint::black_box(rl.at_force(f * rl.rms_height)));
                    }
                },
                0.1,
            );
            let total = t_gen + t_setup + t_curve;
            writeln!(
                buf,
                "{:>10} | {:>12.3e} | {:>12.3e} | {:>12.3e} | {:>12.3e} | {:>14.3e}",
                n,
                t_gen,
                t_setup,
                t_curve,
                total,
                total / (n as f64 * (n as f64).log2())
            )?;
        }
        Ok(())
    })?;
    w.write_all(&buf)?;
    writeln!(w, "\nline: synthesis by inverse real FFT (Eq. 72); setup: sort + prefix sums; k(F): 100 exact force-controlled solves.")?;
    Ok(())
}

/// `mrdw bench sliding`: steady sliding on viscoelastic springs (Section 10.1): time
/// steps per second for N = 1e4 .. 10^max_exp springs with 20 Prony terms (Eq. 84), and
/// the time of one velocity point of the `fig7` scene (one line, to its steady state),
/// single thread.
pub fn run_sliding(w: &mut dyn Write, max_exp: u32) -> Result<()> {
    use mrd::rheology::Eq84;
    use mrd::roughness::synthesis::{line_from, Amplitudes};
    use mrd::sliding::{slide, Line, Slider, Sliding};
    use std::f64::consts::TAU;
    let band_line = |n: usize, waves: f64| -> Result<Line> {
        let k0 = TAU * waves;
        let (lo, hi) = (k0 / 2f64.sqrt(), k0 * 2f64.sqrt());
        let z = line_from(
            &|q: f64| if (lo..=hi).contains(&q) { q } else { 0.0 },
            n,
            1.0,
            7,
            0,
            Amplitudes::Deterministic,
        )
        .case(format!("a band line of {n} springs"))?;
        Line::new(&z, 1.0).case(format!("a band line of {n} springs"))
    };
    let setup = |terms: usize, line: &Line, kv: f64| -> Result<Sliding> {
        let g = Eq84::PAPER
            .prony(terms)
            .case(format!("{terms} Prony terms"))?;
        Ok(Sliding {
            normal_force: 4.0 * g.relaxed * line.rms_height,
            modulus: g.scaled(4.0),
            springs: line.len(),
            stride: 1,
            velocity: kv / line.wave_vector(),
            tolerance: 1e-4,
            max_passes: 400,
            accelerate: true,
        })
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .case("a one-thread pool")?;
    writeln!(
        w,
        "Sliding on viscoelastic springs: band line (4 waves), Eq. (84) with 20 Prony terms, k v = 1 rad/s, single thread\n"
    )?;
    writeln!(
        w,
        "{:>9} | {:>12} | {:>16}",
        "springs", "steps/s", "ns/(spring step)"
    )?;
    writeln!(w, "{}", "-".repeat(44))?;
    let mut rows = Vec::new();
    pool.install(|| -> Result<()> {
        for e in 4..=max_exp.max(4) {
            let n = 10usize.pow(e);
            let line = band_line(n, 4.0)?;
            let p = setup(20, &line, 1.0)?;
            let mut sl = Slider::new(&line, &p).case(format!("a slider of {n} springs"))?;
            for _ in 0..3 {
                sl.step(); // warm-up
            }
            let steps = (2e7 / n as f64).clamp(5.0, 2000.0) as usize;
            let t0 = Instant::now();
            for _ in 0..steps {
                std::hint::black_box(sl.step());
            }
            let t = t0.elapsed().as_secs_f64() / steps as f64;
            rows.push((n, 1.0 / t, t / n as f64 * 1e9));
        }
        Ok(())
    })?;
    for (n, rate, ns) in rows {
        writeln!(w, "{n:>9} | {rate:>12.3e} | {ns:>16.2}")?;
    }
    // One velocity point of fig7: 2048 springs, 16 terms, to the steady state.
    let line = band_line(2048, 4.0)?;
    let mut out = Vec::new();
    pool.install(|| -> Result<()> {
        for kv in [1e-2, 1e0, 1e2] {
            let p = setup(16, &line, kv)?;
            let t0 = Instant::now();
            let r = slide(&line, &p).case(format!("fig7 at k v = {kv:e} rad/s"))?;
            out.push((kv, t0.elapsed().as_secs_f64(), r.history.len()));
        }
        Ok(())
    })?;
    writeln!(
        w,
        "\nfig7 velocity point (one line, 2048 springs, 16 terms, to the steady state):"
    )?;
    for (kv, t, passes) in out {
        writeln!(w, "  k v = {kv:e} rad/s: {t:.2} s, {passes} passes")?;
    }
    Ok(())
}

/// `mrdw bench sliding3d`: steady viscoelastic sliding in 3D (`bem3d::sliding`) on the
/// `fig7-3d` surface (band spectrum, 4 waves, h = 2 um over L = 1 mm, Eq. 84, mean
/// pressure 4 G0 h / L, tolerance 1e-6): wall time, outer and inner iterations of one
/// cold-started velocity point at k v = 1e-2 .. 1e2 rad/s on grids 128^2 .. max_n^2, and
/// the change of mu against the finest grid (all threads of the pool).
pub fn run_sliding_3d(w: &mut dyn Write, max_n: usize) -> Result<()> {
    let (cases, failures) = sliding_3d_table(w, max_n)?;
    if cases > 0 && failures == cases {
        return Err(format!("every case of the benchmark failed ({failures} of {cases})").into());
    }
    Ok(())
}

/// The table of [`run_sliding_3d`]; returns the number of cases and of failed ones.
fn sliding_3d_table(w: &mut dyn Write, max_n: usize) -> Result<(usize, usize)> {
    use bem3d::{SlidingContact, SolverOptions};
    use mrd::rheology::Eq84;
    use mrd::roughness::stats::surface_moments;
    use mrd::roughness::synthesis::{surface_from, upsample, Amplitudes, Grid};
    use std::f64::consts::TAU;
    let (l, h_rms) = (1.0, 0.002);
    let k0 = TAU * 4.0 / l;
    let (lo, hi) = (k0 / 2f64.sqrt(), k0 * 2f64.sqrt());
    let base = Grid::square(16, l);
    let band = |q: f64| if (lo..=hi).contains(&q) { 1.0 } else { 0.0 };
    let h0 = surface_from(&band, &base, 7, 0, Amplitudes::Deterministic).case("fig7-3d surface")?;
    let m = surface_moments(&h0, 16, 16, l, l);
    let k = m.rms_slope / m.rms_height;
    let g = Eq84::PAPER;
    let modulus = |om: f64| {
        g.complex(om)
            .map(|(a, b)| (4.0 * a, 4.0 * b))
            .unwrap_or((f64::NAN, f64::NAN))
    };
    let pm = 4.0 * g.g0 * h_rms / l;
    let opts = SolverOptions {
        tolerance: 1e-6,
        max_iterations: 2000,
        ..Default::default()
    };
    writeln!(
        w,
        "3D viscoelastic sliding (bem3d::sliding): fig7-3d surface 0, Eq. (84), p = 4 G0 h / L, tolerance 1e-6, cold start, {} threads, {}\n",
        rayon::current_num_threads(),
        sysmem::cpu_model()
    )?;
    writeln!(
        w,
        "{:>6} | {:>10} | {:>9} | {:>6} | {:>6} | {:>11} | {:>10}",
        "grid", "kv [rad/s]", "time [s]", "outer", "inner", "mu", "contact"
    )?;
    writeln!(w, "{}", "-".repeat(76))?;
    let grids: Vec<usize> = [128usize, 256, 512, 1024, 2048]
        .into_iter()
        .filter(|&n| n <= max_n.max(128))
        .collect();
    let (mut cases, mut failures) = (0, 0);
    for &n in &grids {
        let h: Vec<f64> = upsample(&h0, &base, &Grid::square(n, l))
            .case(format!("fig7-3d surface on {n}^2 cells"))?
            .iter()
            .map(|v| v * h_rms / m.rms_height)
            .collect();
        for kv in [1e-2, 1e-1, 1e0, 1e1, 1e2] {
            let t0 = Instant::now();
            let mut s = SlidingContact::new(n, n, l, l, &h, kv / k, &modulus)
                .case(format!("sliding contact on {n}^2 cells"))?;
            cases += 1;
            let solved = s.solve(pm, &opts, None);
            failures += solved.is_err() as usize;
            match solved {
                Ok(sol) => writeln!(
                    w,
                    "{n:>6} | {kv:>10.0e} | {:>9.3} | {:>6} | {:>6} | {:>11.5e} | {:>10.4e}",
                    t0.elapsed().as_secs_f64(),
                    sol.contact.iterations,
                    sol.inner_iterations,
                    sol.mu,
                    sol.contact.contact_cells as f64 / (n * n) as f64
                )?,
                Err(e) => writeln!(
                    w,
                    "{n:>6} | {kv:>10.0e} | failed: {}",
                    e.to_string().lines().next().unwrap_or("")
                )?,
            }
        }
    }
    Ok((cases, failures))
}
