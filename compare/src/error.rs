//! Typed errors of the comparison layer (scenes, runs, reports).

use thiserror::Error;

#[derive(Debug, Error)]
pub enum CompareError {
    /// The scene file could not be parsed or is inconsistent.
    #[error("{0}")]
    Scene(String),
    /// A physical computation failed (invalid input, out of range, no convergence).
    #[error("{context}: {source}")]
    Mrd {
        context: String,
        #[source]
        source: mrd::MrdError,
    },
    #[error("{context}: {source}")]
    Io {
        context: String,
        #[source]
        source: std::io::Error,
    },
    #[error("plotting {file}: {message}")]
    Plot { file: String, message: String },
}

pub type Result<T> = std::result::Result<T, CompareError>;

/// Attaches a context (which output, which quantity) to an `mrd` error.
pub trait MrdContext<T> {
    fn ctx(self, context: impl Into<String>) -> Result<T>;
}

impl<T> MrdContext<T> for std::result::Result<T, mrd::MrdError> {
    fn ctx(self, context: impl Into<String>) -> Result<T> {
        self.map_err(|source| CompareError::Mrd {
            context: context.into(),
            source,
        })
    }
}

pub(crate) fn io_err(context: impl Into<String>) -> impl FnOnce(std::io::Error) -> CompareError {
    let context = context.into();
    move |source| CompareError::Io { context, source }
}
