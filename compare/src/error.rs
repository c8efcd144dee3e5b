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

pub(crate) fn io_err(context: impl Into<String>) -> impl FnOnce(std::io::Error) -> CompareError {
    let context = context.into();
    move |source| CompareError::Io { context, source }
}
