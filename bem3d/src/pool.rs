//! Solves run on a thread of rayon's pool, the pool's other threads standing by (so do
//! the constructors of the operators and the solver, whose loops are as short).
//!
//! An iteration of the solvers is a dozen short parallel loops (sweeps, FFT row and
//! column passes). Started from a thread outside the pool, each loop is injected into
//! the pool and the caller sleeps until it ends: a wake-up of a pool thread and of the
//! caller per loop. Running the whole solve on a pool thread makes each loop start in
//! place. Measured on the periodic benchmark surfaces: 128^2 4.2x,
//! 256^2 1.6x, 512^2 1.24x faster on one thread; 1.4x and 1.3x at 128^2 and 256^2 on two.
//!
//! Between two loops an idle pool thread still goes to sleep within microseconds, and the
//! next loop wakes it: a system call for the solving thread and, on a virtual machine, a
//! costly wake-up of an idle virtual CPU, during which the solving thread does the
//! loop's work alone. Measured (perf, periodic 512^2 at 1 % contact,
//! two threads): 19 % of the samples in the kernel's scheduler (wake-ups and sleeps).
//! So a solve started from outside the pool keeps the other threads busy-waiting for
//! its loops' work ([`rayon::yield_now`]) until it returns. Measured the same way, two
//! threads, alternated runs: in a spell of slow wake-ups (medians of 10 solves in one
//! process) 512^2 at 1 % 0.154-0.188 s -> 0.102-0.111 s, at 20 % 0.250 -> 0.183 s,
//! 1024^2 at 1 % 0.68-0.84 -> 0.54-0.68 s; in a spell of fast ones (8 % of the samples
//! in the kernel) no difference; cold solves from Python (`Contact(...).solve(...)` in 9
//! fresh processes each) 1.13-1.26x faster at 512^2-1024^2, 1 % and 20 %, periodic and
//! free. One thread: unchanged (no stand-bys). The waiting threads give their core back
//! to the system every few polls ([`std::thread::yield_now`]), and no more threads stand
//! by than the machine has cores besides the solving one (a pool larger than the machine
//! keeps its other threads asleep; 8 threads on 2 cores, 512^2 at 1 %: once 0.092 s
//! with the previous code against 0.120 s with every thread standing by, once 0.089
//! against 0.081 s, and 0.075 s with the limit).
//!
//! Results are bit-identical either way (every reduction has a fixed order whatever the
//! thread).
//!
//! Deadlock freedom: a standing-by thread must never sit on top of work its solve waits
//! for (two solves, each waiting on a thread held by the other's stand-by, would wait
//! forever). Hence a stand-by that starts on a thread inside a solve returns at once,
//! and solves called from inside the pool (e.g. one per task of a parallel loop) run in
//! place without stand-bys. That rule does not see the other way in: a pool thread that
//! took half of one of the solve's parallel loops may run its own broadcast job while it
//! waits inside that half, and stand by there; the solve then waits for the half below
//! the stand-by, and nothing runs (the stand-by spinning, the solve's thread asleep in
//! its join). So a stand-by also returns after [`IDLE_LIMIT`] without any work to
//! run: a solve between two loops leaves its stand-bys idle for microseconds, a solve
//! blocked on one of them for ever.

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

thread_local! {
    /// Whether this thread is running a solve (on any level of its stack).
    static SOLVING: Cell<bool> = const { Cell::new(false) };
}

/// Marks the current thread as solving until dropped (also when unwinding).
struct Solving(bool);

impl Solving {
    fn enter() -> Self {
        Self(SOLVING.with(|s| s.replace(true)))
    }
}

impl Drop for Solving {
    fn drop(&mut self) {
        SOLVING.with(|s| s.set(self.0));
    }
}

/// Sets the flag when dropped (also when unwinding): the stand-bys then return.
struct Finished<'a>(&'a AtomicBool);

impl Drop for Finished<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Release);
    }
}

/// Polls of an idle stand-by between two yields of its core to the system.
const POLLS_PER_YIELD: u32 = 64;

/// How long a stand-by polls without finding work before it returns (module docs): far
/// above the gaps between a solve's loops, short against a stalled test or run.
const IDLE_LIMIT: std::time::Duration = std::time::Duration::from_millis(100);

/// The machine's cores besides the solving thread's: the most threads that stand by.
fn stand_by_limit() -> usize {
    static LIMIT: OnceLock<usize> = OnceLock::new();
    *LIMIT.get_or_init(|| {
        std::thread::available_parallelism()
            .map_or(1, |n| n.get())
            .saturating_sub(1)
    })
}

/// Runs `f` on a thread of the current rayon pool (in place when already on one); from
/// outside the pool, with the pool's other threads standing by (module docs).
pub(crate) fn on_pool<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    let inside = rayon::current_thread_index().is_some();
    if inside || rayon::current_num_threads() < 2 {
        return rayon::scope(|_| {
            let _solving = Solving::enter();
            f()
        });
    }
    let task = Mutex::new(Some(f));
    let result = Mutex::new(None);
    let finished = AtomicBool::new(false);
    let standing = AtomicUsize::new(0);
    // Every pool thread runs this once: the first to arrive runs f, the others stand by
    // (up to the limit).
    rayon::broadcast(|_| {
        let claimed = task.lock().unwrap_or_else(|e| e.into_inner()).take();
        match claimed {
            Some(f) => {
                let _done = Finished(&finished);
                let _solving = Solving::enter();
                let r = f();
                *result.lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
            }
            None if standing.fetch_add(1, Ordering::Relaxed) < stand_by_limit() => {
                stand_by(&finished)
            }
            None => {}
        }
    });
    let r = result.into_inner().unwrap_or_else(|e| e.into_inner());
    r.expect("the solve ran on one of the pool's threads")
}

/// Runs the pool's pending work until `finished` is set or no work has come for
/// [`IDLE_LIMIT`]; returns at once on a thread inside a solve (module docs).
fn stand_by(finished: &AtomicBool) {
    if SOLVING.with(Cell::get) {
        return;
    }
    let mut idle = 0u32;
    let mut idle_since = std::time::Instant::now();
    while !finished.load(Ordering::Acquire) {
        match rayon::yield_now() {
            Some(rayon::Yield::Executed) => idle = 0,
            _ => {
                if idle == 0 {
                    idle_since = std::time::Instant::now();
                }
                idle += 1;
                if idle.is_multiple_of(POLLS_PER_YIELD) {
                    if idle_since.elapsed() > IDLE_LIMIT {
                        return;
                    }
                    std::thread::yield_now();
                } else {
                    std::hint::spin_loop();
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;
    use std::sync::mpsc;
    use std::time::Duration;

    /// A parallel sum whose chunks the stand-bys can take.
    fn work(seed: u64) -> u64 {
        (0..100_000u32)
            .into_par_iter()
            .with_min_len(500)
            .map(|k| (k as u64 ^ seed).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40)
            .sum()
    }

    /// `f` on a new thread, failing the test if it has not returned within a minute
    /// (instead of hanging it).
    fn within_a_minute<R: Send + 'static>(f: impl FnOnce() -> R + Send + 'static) -> R {
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || tx.send(f()).ok());
        rx.recv_timeout(Duration::from_secs(60))
            .expect("no result within a minute: a deadlock")
    }

    #[test]
    fn solves_run_on_the_pool_from_outside_and_inside() {
        // From this (outside) thread: one pool thread runs f, the others stand by.
        let (on, sum) = on_pool(|| (rayon::current_thread_index().is_some(), work(7)));
        assert!(on, "f runs on a pool thread");
        let serial: u64 = (0..100_000u64)
            .map(|k| (k ^ 7).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40)
            .sum();
        assert_eq!(sum, serial);
        // From inside, one solve per task of a parallel loop: in place.
        let all: Vec<u64> = (0..8u64)
            .into_par_iter()
            .map(|s| on_pool(|| work(s)))
            .collect();
        assert_eq!(all, (0..8u64).map(work).collect::<Vec<_>>());
    }

    #[test]
    fn a_stand_by_inside_a_solve_returns_at_once() {
        within_a_minute(|| {
            let _solving = Solving::enter();
            stand_by(&AtomicBool::new(false));
        });
    }

    /// A stand-by with nothing to run returns within about IDLE_LIMIT, even if its solve
    /// never finishes: a solve that waits on work below the stand-by in the same thread's
    /// stack (module docs) is then released.
    #[test]
    fn an_idle_stand_by_returns() {
        let waited = within_a_minute(|| {
            let t0 = std::time::Instant::now();
            stand_by(&AtomicBool::new(false));
            t0.elapsed()
        });
        assert!(
            waited >= IDLE_LIMIT && waited < 50 * IDLE_LIMIT,
            "{waited:?}"
        );
    }

    #[test]
    fn concurrent_solves_from_outside_threads_all_finish() {
        // Threads outside the pool start solves at once, repeatedly: each solve's
        // stand-bys meet the other solves on the pool's threads, and every solve must
        // still return (a smoke test: the rule that prevents a deadlock is checked on
        // its own above).
        let sums = within_a_minute(|| {
            let handles: Vec<_> = (0..8u64)
                .map(|s| {
                    std::thread::spawn(move || {
                        // Each round's sum, all of which must agree.
                        let sums: Vec<u64> = (0..100)
                            .map(|_| on_pool(|| work(s) + on_pool(|| work(s + 1))))
                            .collect();
                        sums.iter().all(|&v| v == sums[0]).then_some(sums[0])
                    })
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().unwrap())
                .collect::<Vec<_>>()
        });
        for (s, got) in sums.into_iter().enumerate() {
            assert_eq!(got, Some(work(s as u64) + work(s as u64 + 1)));
        }
    }

    #[test]
    fn a_panicking_solve_releases_the_stand_bys() {
        let r = within_a_minute(|| {
            std::thread::spawn(|| on_pool(|| -> u64 { panic!("a solver bug") })).join()
        });
        assert!(r.is_err(), "the panic reaches the caller");
        assert_eq!(within_a_minute(|| on_pool(|| work(3))), work(3));
    }
}
