//! Progress of the parallel tasks of a long output on stderr (nothing when progress is
//! off: `Env::progress`, false in tests and with `--quiet`): a bar in a terminal, and a
//! line per tenth of the tasks where stderr is not one (a CI log, a notebook, a file),
//! so that a long run never looks like a hang.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Counts finished tasks of one stage on stderr.
pub struct Progress(Option<Shown>);

enum Shown {
    Bar(indicatif::ProgressBar),
    Lines {
        done: AtomicUsize,
        len: usize,
        msg: &'static str,
        unit: String,
        start: Instant,
    },
}

impl Progress {
    /// `len` tasks of `unit` (e.g. "solves", "cycles"), labelled `msg`.
    pub fn new(show: bool, len: usize, msg: &'static str, unit: &str) -> Self {
        if !show {
            return Self(None);
        }
        if !std::io::stderr().is_terminal() {
            eprintln!("{msg}: {len} {unit} to compute");
            return Self(Some(Shown::Lines {
                done: AtomicUsize::new(0),
                len,
                msg,
                unit: unit.to_string(),
                start: Instant::now(),
            }));
        }
        let b = indicatif::ProgressBar::new(len as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template(&format!(
                "{{msg}} [{{bar:30}}] {{pos}}/{{len}} {unit}, {{elapsed}} elapsed, ETA {{eta}}"
            ))
            .expect("valid template")
            .progress_chars("=> "),
        );
        b.set_message(msg);
        Self(Some(Shown::Bar(b)))
    }

    pub fn inc(&self) {
        match &self.0 {
            Some(Shown::Bar(b)) => b.inc(1),
            Some(Shown::Lines {
                done,
                len,
                msg,
                unit,
                start,
            }) => {
                let k = done.fetch_add(1, Ordering::Relaxed) + 1;
                // A line each time a tenth more of the tasks is done.
                if *len > 0 && (10 * k) / len > (10 * (k - 1)) / len {
                    eprintln!(
                        "{msg}: {k}/{len} {unit} ({:.0} %), {:.0} s elapsed",
                        100.0 * k as f64 / *len as f64,
                        start.elapsed().as_secs_f64()
                    );
                }
            }
            None => {}
        }
    }

    pub fn finish(&self) {
        if let Some(Shown::Bar(b)) = &self.0 {
            b.finish_and_clear();
        }
    }
}
