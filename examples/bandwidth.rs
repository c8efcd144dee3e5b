//! How much a second thread can speed up a pass that streams grids from memory on this
//! machine: the ceiling of the 3D solver's two-thread scaling in its memory-bound rows
//! (README, "3D boundary elements against ASPHER and Tamaas").
//!
//! ```text
//! cargo run --release --example bandwidth [MiB per array, default 64] [rounds, default 4]
//! ```
//!
//! Two passes over f64 arrays, each the best of 20 repetitions, one thread against
//! two (rayon pools, rounds interleaved): triad `a = b + s c` (read two arrays, write
//! one) and update `a = s a + b` (read two, write one in place, as the solver's sweeps
//! do). 64 MiB arrays stream from memory (a 1024^2 grid of f64 is 8 MiB, the solver's
//! state several of them); 4 MiB arrays (three of them) fit a 32 MiB L3.
use rayon::prelude::*;
use std::time::Instant;

const REPS: usize = 20;
const CHUNK: usize = 1 << 14;
/// Largest array asked for [MiB] (three are allocated at once).
const MAX_MIB: usize = 4096;

/// Best times [s] of the triad and the update over `REPS` repetitions.
fn best_times(a: &mut [f64], b: &[f64], c: &[f64]) -> [f64; 2] {
    let mut best = [f64::INFINITY; 2];
    for _ in 0..REPS {
        let start = Instant::now();
        a.par_chunks_mut(CHUNK)
            .zip(b.par_chunks(CHUNK))
            .zip(c.par_chunks(CHUNK))
            .for_each(|((a, b), c)| {
                for ((a, b), c) in a.iter_mut().zip(b).zip(c) {
                    *a = b + 0.5 * c;
                }
            });
        best[0] = best[0].min(start.elapsed().as_secs_f64());
        let start = Instant::now();
        a.par_chunks_mut(CHUNK)
            .zip(b.par_chunks(CHUNK))
            .for_each(|(a, b)| {
                for (a, b) in a.iter_mut().zip(b) {
                    *a = 0.5 * *a + b;
                }
            });
        best[1] = best[1].min(start.elapsed().as_secs_f64());
        std::hint::black_box(&mut *a);
    }
    best
}

fn main() {
    let arg = |i: usize, default: usize| -> usize {
        match std::env::args().nth(i) {
            None => default,
            Some(s) => match s.parse::<usize>() {
                Ok(v) if v > 0 => v,
                _ => {
                    eprintln!("error: argument {i} = {s:?} must be a positive integer");
                    std::process::exit(2)
                }
            },
        }
    };
    let (mib, rounds) = (arg(1, 64), arg(2, 4));
    if mib > MAX_MIB {
        eprintln!("error: {mib} MiB per array: at most {MAX_MIB} (three arrays are allocated)");
        std::process::exit(2)
    }
    let n = mib * (1 << 20) / 8;
    let cores = std::thread::available_parallelism().map_or(1, |t| t.get());
    // At least two threads (on one core the second only takes turns with the first).
    let threads = cores.max(2);
    println!(
        "{} ({cores} cores); three arrays of {mib} MiB",
        sysmem::cpu_model()
    );
    // Bytes each pass moves: three arrays (two read, one written).
    let bytes = 3.0 * (n * 8) as f64;
    let mut best = [[f64::INFINITY; 2]; 2];
    for round in 0..rounds {
        for (slot, t) in [1, threads].into_iter().enumerate() {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .expect("a thread pool");
            let times = pool.install(|| {
                let (mut a, b, c) = (vec![1.0; n], vec![2.0; n], vec![3.0; n]);
                best_times(&mut a, &b, &c)
            });
            println!(
                "round {round}, {t} thread(s): triad {:.1} GB/s, update {:.1} GB/s",
                bytes / times[0] / 1e9,
                bytes / times[1] / 1e9
            );
            for k in 0..2 {
                best[slot][k] = best[slot][k].min(times[k]);
            }
        }
    }
    println!(
        "{threads} threads / 1 thread (best of all rounds): triad {:.2}x, update {:.2}x",
        best[0][0] / best[1][0],
        best[0][1] / best[1][1]
    );
}
