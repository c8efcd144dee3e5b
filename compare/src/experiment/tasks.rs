//! Checkpointed task sets: work split into named tasks, each written atomically to its
//! own JSON file in a work folder when done. A task whose file exists is not computed
//! again, so a run resumes where an interrupted one stopped; shard K of N computes the
//! tasks whose position in the global list is K modulo N; a progress bar counts them.

use crate::error::{io_err, CompareError, Result};
use crate::files::write_atomic;
use crate::output::RunControl;
use rayon::prelude::*;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The realisation plan of an adaptive study: `min` first, then batches of `batch` (up
/// to `max`) while the quantity's interval is wider than its target; decisions on
/// complete batches only, so results do not depend on threads, shards or interruptions.
#[derive(Debug, Clone, Copy, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Realisations {
    pub min: u64,
    pub max: u64,
    pub batch: u64,
}

impl Realisations {
    /// At least 2 and at most [`crate::checks::MAX_REALISATIONS`], min <= max, a batch
    /// of 1..=max; messages name `realisations.<field>`.
    pub fn validate(&self) -> Result<()> {
        use crate::checks::{count_in, MAX_REALISATIONS};
        count_in("realisations.min", self.min, 2..=MAX_REALISATIONS)?;
        count_in("realisations.max", self.max, self.min..=MAX_REALISATIONS)?;
        count_in("realisations.batch", self.batch, 1..=self.max)
    }
}

/// Computes the missing tasks among the first `upto` of `names` (the global list, in
/// its fixed order; shards take every N-th of the whole list) into `work`, in parallel,
/// one task per thread, handed out in the list's order: `run(i)` computes task `i` and
/// returns its checkpoint's text ([`json`]). `label` names the work on the progress bar
/// and, when `announce` is set and checkpoints are found, in a message saying how many
/// were taken from them (all of them, too: a rerun over a finished work folder says so).
pub fn compute(
    work: &Path,
    label: &'static str,
    names: &[String],
    upto: usize,
    announce: bool,
    control: &RunControl,
    run: &(dyn Fn(usize) -> Result<String> + Sync),
) -> Result<()> {
    std::fs::create_dir_all(work).map_err(io_err(format!("creating {}", work.display())))?;
    let mine: Vec<usize> = (0..upto.min(names.len()))
        .filter(|i| control.shard.is_none_or(|(k, n)| i % n == k))
        .collect();
    let todo: Vec<usize> = mine
        .iter()
        .copied()
        .filter(|&i| !work.join(&names[i]).exists())
        .collect();
    if announce && control.progress && !todo.is_empty() && todo.len() < mine.len() {
        eprintln!(
            "{label}: resuming: {} of {} tasks taken from checkpoints in {}, {} to compute",
            mine.len() - todo.len(),
            mine.len(),
            work.display(),
            todo.len()
        );
    }
    if announce && control.progress && todo.is_empty() && !mine.is_empty() {
        eprintln!(
            "{label}: resuming: all {} tasks taken from checkpoints in {}, nothing to compute",
            mine.len(),
            work.display()
        );
    }
    let bar = super::progress::Progress::new(
        control.progress && !todo.is_empty(),
        todo.len(),
        label,
        "tasks",
    );
    let done = AtomicUsize::new(0);
    // Handed out in the list's order, one task per idle thread: a caller that lists its
    // cheapest tasks first (the lambda study) gets them done first.
    let result = todo.iter().par_bridge().try_for_each(|&i| {
        write_atomic(&work.join(&names[i]), &run(i)?)?;
        bar.inc();
        let n = done.fetch_add(1, Ordering::SeqCst) + 1;
        match control.stop_after {
            Some(s) if n >= s => Err(CompareError::Stopped { tasks: n }),
            _ => Ok(()),
        }
    });
    bar.finish();
    result
}

/// A task's result as its checkpoint's text.
pub fn json<T: Serialize>(v: &T) -> Result<String> {
    serde_json::to_string(v).map_err(|e| CompareError::Internal(e.to_string()))
}

/// Reads the checkpoint `name` of `work`.
pub fn load<T: DeserializeOwned>(work: &Path, name: &str) -> Result<T> {
    let p = work.join(name);
    let text = std::fs::read_to_string(&p).map_err(io_err(format!(
        "reading {} (missing task: run all shards, or rerun to resume)",
        p.display()
    )))?;
    serde_json::from_str(&text).map_err(|e| CompareError::Internal(format!("{}: {e}", p.display())))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Shards cover the list once between them, a finished task is not run again, and
    /// `stop_after` stops a run that a second run completes.
    #[test]
    fn shards_cover_the_list_and_a_rerun_resumes() {
        let dir = crate::files::ScratchDir::new().unwrap();
        let names: Vec<String> = (0..7).map(|i| format!("t{i}.json")).collect();
        let runs = AtomicUsize::new(0);
        let whole = RunControl::default();
        let run = |i: usize| -> Result<String> {
            runs.fetch_add(1, Ordering::SeqCst);
            json(&(i * i))
        };
        for k in 0..3 {
            let c = RunControl {
                shard: Some((k, 3)),
                ..Default::default()
            };
            compute(dir.path(), "test", &names, 7, true, &c, &run).unwrap();
        }
        assert_eq!(runs.load(Ordering::SeqCst), 7);
        compute(dir.path(), "test", &names, 7, true, &whole, &run).unwrap();
        assert_eq!(runs.load(Ordering::SeqCst), 7);
        for (i, n) in names.iter().enumerate() {
            assert_eq!(load::<usize>(dir.path(), n).unwrap(), i * i);
        }
        let other = crate::files::ScratchDir::new().unwrap();
        let stop = RunControl {
            stop_after: Some(2),
            ..Default::default()
        };
        assert!(compute(other.path(), "test", &names, 5, true, &stop, &run).is_err());
        compute(other.path(), "test", &names, 5, true, &whole, &run).unwrap();
        assert!(other.path().join("t4.json").exists() && !other.path().join("t5.json").exists());
    }
}
