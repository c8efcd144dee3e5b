//! Typed errors of the comparison layer. The binary turns each into one line and an
//! exit code (see `mrdw --help`).

use thiserror::Error;

#[derive(Debug, Error)]
pub enum CompareError {
    /// The scene or a file it names is unusable: parse errors, out-of-range values,
    /// missing files. The message names the key and the valid range.
    #[error("{0}")]
    Scene(String),
    /// A 1D computation refused its input or failed.
    #[error("{context}: {source}")]
    Mrd {
        context: String,
        #[source]
        source: mrd::MrdError,
    },
    /// A 3D solve failed; for iteration failures the error carries the iterations and
    /// the residual reached ([`bem3d::BemError::progress`]).
    #[error("{context}: {source}")]
    Bem {
        context: String,
        #[source]
        source: bem3d::BemError,
    },
    #[error("{context}: {source}")]
    Io {
        context: String,
        #[source]
        source: std::io::Error,
    },
    #[error("plotting {file}: {message}")]
    Plot { file: String, message: String },
    /// The run stopped on request after computing some of its tasks (their checkpoints
    /// are kept: the same command resumes).
    #[error("stopped after {tasks} new tasks; rerun the same command to resume")]
    Stopped { tasks: usize },
    /// Another process holds the lock on this report or work folder.
    #[error("{0}")]
    Busy(String),
    /// A size the scene chose needs more memory than this process may use.
    #[error(transparent)]
    Memory(#[from] sysmem::MemoryError),
    /// A bug: an invariant of the program does not hold.
    #[error("internal error: {0}")]
    Internal(String),
}

pub type Result<T> = std::result::Result<T, CompareError>;

impl CompareError {
    /// The same error, its message prefixed with where it happened (e.g. which output).
    pub fn within(self, place: &str) -> Self {
        match self {
            CompareError::Scene(m) => CompareError::Scene(format!("{place}: {m}")),
            CompareError::Mrd { context, source } => CompareError::Mrd {
                context: format!("{place}: {context}"),
                source,
            },
            CompareError::Bem { context, source } => CompareError::Bem {
                context: format!("{place}: {context}"),
                source,
            },
            CompareError::Io { context, source } => CompareError::Io {
                context: format!("{place}: {context}"),
                source,
            },
            other => other,
        }
    }
}

/// Attaches a context (which output, which quantity) to an `mrd` or `bem3d` error.
pub trait Context<T> {
    fn ctx(self, context: impl Into<String>) -> Result<T>;
}

impl<T> Context<T> for std::result::Result<T, mrd::MrdError> {
    fn ctx(self, context: impl Into<String>) -> Result<T> {
        self.map_err(|source| CompareError::Mrd {
            context: context.into(),
            source,
        })
    }
}

impl<T> Context<T> for std::result::Result<T, bem3d::BemError> {
    fn ctx(self, context: impl Into<String>) -> Result<T> {
        self.map_err(|source| CompareError::Bem {
            context: context.into(),
            source,
        })
    }
}

impl<T> Context<T> for std::result::Result<T, dynamics::DynamicsError> {
    fn ctx(self, context: impl Into<String>) -> Result<T> {
        self.map_err(|e| match e {
            dynamics::DynamicsError::InvalidInput(m) => {
                CompareError::Scene(format!("{}: {m}", context.into()))
            }
            dynamics::DynamicsError::Mrd(source) => CompareError::Mrd {
                context: context.into(),
                source,
            },
            dynamics::DynamicsError::Bem(source) => CompareError::Bem {
                context: context.into(),
                source,
            },
        })
    }
}

pub(crate) fn io_err(context: impl Into<String>) -> impl FnOnce(std::io::Error) -> CompareError {
    let context = context.into();
    move |source| CompareError::Io { context, source }
}

/// `message` with each number that Rust's `Display` wrote out digit by digit at an
/// extreme magnitude in the shortest scientific form: more than 20 digits before the
/// point (1e300 prints as 1 and 300 zeros) or six or more zeros after "0." (1e-300
/// prints 299 of them). The numbers a user gave at the edge of double precision then
/// stay legible in an error line; integers of up to 20 digits (any `u64`, e.g. a seed)
/// and every other number are left as written.
pub fn readable_numbers(message: &str) -> String {
    let b = message.as_bytes();
    let mut out = String::with_capacity(message.len());
    let mut copied = 0;
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_digit() && (i == 0 || !is_word(b[i - 1]));
        if !starts {
            i += 1;
            continue;
        }
        let int_end = digits_from(b, i);
        let mut end = int_end;
        if end + 1 < b.len() && b[end] == b'.' && b[end + 1].is_ascii_digit() {
            end = digits_from(b, end + 1);
        }
        let whole = end == b.len() || !is_word(b[end]);
        let long = int_end - i > 20;
        let tiny = &message[i..int_end] == "0" && message[int_end..end].starts_with(".000000");
        if whole && (long || tiny) {
            if let Ok(v) = message[i..end].parse::<f64>() {
                out.push_str(&message[copied..i]);
                out.push_str(&format!("{v:e}"));
                copied = end;
            }
        }
        i = end;
    }
    out.push_str(&message[copied..]);
    out
}

/// A byte that continues a word or a number (a number glued to one is not rewritten).
fn is_word(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_' || c == b'.'
}

/// The end of the run of ASCII digits that starts at `i`.
fn digits_from(b: &[u8], i: usize) -> usize {
    i + b[i..].iter().take_while(|c| c.is_ascii_digit()).count()
}

#[cfg(test)]
mod tests {
    use super::readable_numbers;

    #[test]
    fn extreme_numbers_read_in_scientific_form() {
        for v in [
            1e300,
            1e21,
            1.5e250,
            f64::MAX,
            1e-300,
            2.5e-7,
            1e-7,
            f64::MIN_POSITIVE,
        ] {
            let message = format!("mu = {v} must lie in (0, 10]; also -{v}, `{v}`");
            assert_eq!(
                readable_numbers(&message),
                format!("mu = {v:e} must lie in (0, 10]; also -{v:e}, `{v:e}`"),
                "{v:e}"
            );
        }
        // Left as written: ordinary numbers, any u64, numbers inside words, versions.
        for m in [
            "seed = 18446744073709551615 and 1e300 as typed",
            "r_max = 0.000001, 123456.789, 1e-12, x86_64, v0.1.0, 3.14159",
            "name_100000000000000000000000000000 a100000000000000000000000",
            "1000000000000000000000px",
        ] {
            assert_eq!(readable_numbers(m), m);
        }
        // The value is the one given (Display round-trips).
        for v in [1e300, 1.2345678901234567e-200] {
            let r = readable_numbers(&format!("{v}"));
            assert_eq!(r.parse::<f64>().unwrap(), v);
        }
    }
}
