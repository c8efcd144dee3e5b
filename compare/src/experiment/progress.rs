//! A progress bar shared by the parallel tasks of a long output (hidden when progress
//! is off: `Env::progress`, false in tests and with `--quiet`).

/// Counts finished tasks of one stage on stderr.
pub struct Progress(Option<indicatif::ProgressBar>);

impl Progress {
    /// `len` tasks of `unit` (e.g. "solves", "cycles"), labelled `msg`.
    pub fn new(show: bool, len: usize, msg: &'static str, unit: &str) -> Self {
        Self(show.then(|| {
            let b = indicatif::ProgressBar::new(len as u64);
            b.set_style(
                indicatif::ProgressStyle::with_template(&format!(
                    "{{msg}} [{{bar:30}}] {{pos}}/{{len}} {unit}, {{elapsed}} elapsed, ETA {{eta}}"
                ))
                .expect("valid template")
                .progress_chars("=> "),
            );
            b.set_message(msg);
            b
        }))
    }

    pub fn inc(&self) {
        if let Some(b) = &self.0 {
            b.inc(1);
        }
    }

    pub fn finish(&self) {
        if let Some(b) = &self.0 {
            b.finish_and_clear();
        }
    }
}
