//! What an output kind is: the [`Output`] trait every kind implements, what a running
//! output may use ([`Env`], [`RunControl`]), and the [`Checkpointed`] work of the long
//! studies.
//!
//! The life of an output: the scene parser looks its `kind` up in the registry
//! ([`crate::registry::KINDS`]) and deserialises the rest of its `[[outputs]]` table into
//! the kind's struct (unknown keys are errors); [`Output::validate`] checks it against the
//! scene's [`Context`]; [`Output::stages`] declares what it will run; [`Output::run`]
//! computes those stages (each through [`Section::stage`], which records it) and fills its
//! [`Section`] with named tables, figures and results.

use crate::context::Context;
use crate::error::Result;
use crate::plan::Stage;
use crate::report::Section;
use std::path::Path;

/// One requested output.
pub trait Output: std::fmt::Debug + Send + Sync {
    /// Checks the request against the scene before anything runs (ranges, material
    /// constants, files); messages name the key and its valid range.
    fn validate(&self, ctx: &Context) -> Result<()>;
    /// The stages [`Self::run`] will execute, in order.
    fn stages(&self, ctx: &Context) -> Vec<Stage>;
    /// Computes the declared stages and fills `out`.
    fn run(&self, env: &Env, out: &mut Section) -> Result<()>;
    /// The random seed, if the output draws random surfaces.
    fn seed(&self) -> Option<u64> {
        None
    }
    /// Outputs whose work is split into checkpointed tasks (resumable, shardable).
    fn checkpointed(&self) -> Option<&dyn Checkpointed> {
        None
    }
}

/// Work split into tasks, each saved to its own checkpoint file when done.
/// A checkpoint folder's name from the text of the parameters its tasks depend on:
/// FNV-1a, 16 hex digits.
pub(crate) fn checkpoint_key(text: &str) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

pub trait Checkpointed {
    /// A hash of the output's parameters: its checkpoints live in `<work root>/<key>/`.
    fn key(&self) -> String;
    /// The checkpoint file names of all tasks, in their fixed global order (shard K of N
    /// computes every N-th from K).
    fn task_files(&self) -> Vec<String>;
    /// Computes the missing tasks (of the shard in `control`) into `dir`; `ctx` resolves
    /// the scene's files.
    fn compute(&self, ctx: &Context, dir: &Path, control: &RunControl) -> Result<()>;
}

/// How a run divides and limits its work.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunControl {
    /// (K, N): compute only tasks with index % N == K.
    pub shard: Option<(usize, usize)>,
    /// Stop (with [`CompareError::Stopped`]) after computing this many new tasks
    /// (tests of interruption and resume).
    pub stop_after: Option<usize>,
    /// Show progress bars on long work.
    pub progress: bool,
    /// Compute no 3D task: outputs that can report what their checkpoints hold do so
    /// (a lambda study computes its MRD ensembles first where they are missing: they
    /// are not committed).
    pub report_only: bool,
}

/// What a running output may use.
pub struct Env<'a> {
    pub ctx: &'a Context,
    /// Checkpoints of resumable outputs go to `work_root/<key>/`.
    pub work_root: &'a Path,
    pub control: &'a RunControl,
}
