//! Which tasks a round computes: the realisations each case still needs (adaptive: until
//! lambda's interval meets its target, judged on the estimates of the analysis), then the
//! tasks of this shard, computed and checkpointed.

use super::analysis;
use super::tasks::{
    approach_file, cases, done, mrd_file, run_bem, run_control, run_mrd, run_mrd_approach,
    top_checked, Case, Role, Task,
};
use super::LambdaStudy;
use crate::error::{io_err, CompareError, Result};
use crate::experiment::fit::Estimate;
use crate::experiment::tasks::{self, json};
use crate::output::RunControl;
use std::path::Path;

/// How many realisations `case` needs given `n` done: the adaptive rule below, and at
/// least `scatter.realisations` on the main ladder at the scatter's bandwidth;
/// `top_check.realisations` for the largest grid's checks.
fn needed(s: &LambdaStudy, work: &Path, case: &Case, n: u64) -> Result<u64> {
    if top_checked(s, case) {
        return Ok(s.top_check.map_or(0, |t| t.realisations));
    }
    let floor = match s.scatter {
        Some(sc) if case.role == Role::Ladder && case.band == sc.bandwidth => sc.realisations,
        _ => 0,
    };
    Ok(adaptive(s, work, case, n)?.max(floor))
}

/// The adaptive rule: realisations in batches until lambda meets its target (complete
/// batches decide).
fn adaptive(s: &LambdaStudy, work: &Path, case: &Case, n: u64) -> Result<u64> {
    let r = s.realisations;
    if case.role == Role::Above {
        return above(s, work, case, n);
    }
    if case.role != Role::Ladder || n < r.min {
        return Ok(r.min);
    }
    if n >= r.max {
        return Ok(r.max);
    }
    if !n.is_multiple_of(r.batch) {
        return Ok(n.div_ceil(r.batch) * r.batch);
    }
    if !work.join(mrd_file(case.hurst, case.band)).exists() {
        return Ok(n);
    }
    let e = analysis::case_lambda(s, work, case, n)?;
    let target = s.target_at(case.hurst);
    let met =
        e.value.is_finite() && e.lo >= (1.0 - target) * e.value && e.hi <= (1.0 + target) * e.value;
    Ok(if met { n } else { (n + r.batch).min(r.max) })
}

/// Realisations a bandwidth above `calibrate_at` starts with, and adds at a time.
const ABOVE_FIRST: u64 = 8;

const ABOVE_BATCH: u64 = 4;

/// The rule for a bandwidth above `calibrate_at`, whose question is whether lambda
/// moves from `calibrate_at` to it: realisations in batches of [`ABOVE_BATCH`] (from
/// [`ABOVE_FIRST`], at most `realisations.min`) until the paired ratio's 95 % interval
/// answers it, lying inside [1 - target, 1 + target] (the change is within the shipped
/// row's target) or wholly outside it (lambda moves by more). Complete batches decide.
fn above(s: &LambdaStudy, work: &Path, case: &Case, n: u64) -> Result<u64> {
    let cap = s.realisations.min;
    let first = ABOVE_FIRST.min(cap);
    if n < first {
        return Ok(first);
    }
    if n >= cap {
        return Ok(cap);
    }
    if !n.is_multiple_of(ABOVE_BATCH) {
        return Ok((n.div_ceil(ABOVE_BATCH) * ABOVE_BATCH).min(cap));
    }
    let Some(e) = analysis::above_ratio(s, work, case, n)? else {
        return Ok(n);
    };
    Ok(if settled(&e, s.target_at(case.hurst)) {
        n
    } else {
        (n + ABOVE_BATCH).min(cap)
    })
}

/// Whether a ratio's interval answers "does it differ from 1 by more than t?": inside
/// [1 - t, 1 + t] or wholly outside it (an undefined bound answers nothing).
fn settled(e: &Estimate, t: f64) -> bool {
    let inside = e.lo >= 1.0 - t && e.hi <= 1.0 + t;
    let outside = e.hi < 1.0 - t || e.lo > 1.0 + t;
    inside || outside
}

/// The tasks still to compute: MRD ensembles first, then 3D realisations, cheapest
/// grids first (an interrupted round leaves every case with data).
pub fn plan(s: &LambdaStudy, work: &Path) -> Result<Vec<Task>> {
    let cs = cases(s);
    let mut todo: Vec<Task> = Vec::new();
    let mut bands: Vec<(f64, usize)> = Vec::new();
    for c in &cs {
        if !bands.contains(&(c.hurst, c.band)) {
            bands.push((c.hurst, c.band));
        }
    }
    for &(hurst, band) in &bands {
        if !work.join(mrd_file(hurst, band)).exists() {
            todo.push(Task::Mrd { hurst, band });
        }
        let scatter = s.scatter.is_some_and(|sc| sc.bandwidth == band);
        if scatter && !work.join(approach_file(hurst, band)).exists() {
            todo.push(Task::MrdApproach { hurst, band });
        }
    }
    let mut grids: Vec<(f64, usize, usize)> = Vec::new();
    // The largest grid's checks have too few realisations for control variates (the
    // means of fewer than 6 are plain): no control ensemble for them.
    for c in cs.iter().filter(|c| !top_checked(s, c)) {
        if !grids.contains(&(c.hurst, c.band, c.cells)) {
            grids.push((c.hurst, c.band, c.cells));
            let t = Task::Control {
                case: *c,
                m: s.control_count(c.grid()),
            };
            if !work.join(t.file_name()).exists() {
                todo.push(t);
            }
        }
    }
    for case in &cs {
        let n = done(work, case);
        let want = needed(s, work, case, n)?;
        todo.extend(
            (n..want)
                .map(|r| Task::Bem { case: *case, r })
                .filter(|t| !work.join(t.file_name()).exists()),
        );
    }
    todo.sort_by_key(|t| {
        (
            t.cost(),
            match t {
                Task::Bem { r, .. } => *r,
                Task::Mrd { .. } | Task::MrdApproach { .. } | Task::Control { .. } => 0,
            },
        )
    });
    Ok(todo)
}

/// Computes rounds of the plan until nothing is needed (or the control stops it): each
/// round the tasks of the plan's first priority (see [`Task::priority`]), cheapest
/// grids first.
pub fn compute(s: &LambdaStudy, work: &Path, control: &RunControl) -> Result<()> {
    std::fs::create_dir_all(work).map_err(io_err(format!("creating {}", work.display())))?;
    let done_before = std::fs::read_dir(work).map_or(0, |d| d.count());
    if control.progress && done_before > 0 {
        let _ = std::io::Write::write_fmt(
            &mut std::io::stderr(),
            format_args!(
                "lambda study: resuming from {done_before} checkpoints in {}\n",
                work.display()
            ),
        );
    }
    let mut computed = 0;
    loop {
        let all = plan(s, work)?;
        let first = all.iter().map(|t| t.priority(s)).min();
        let round: Vec<Task> = all
            .into_iter()
            .filter(|t| Some(t.priority(s)) == first)
            .collect();
        if control.report_only && control.progress {
            let _ = std::io::Write::write_fmt(
                &mut std::io::stderr(),
                format_args!(
                    "lambda study: report only (3D tasks are left to a run without \
                     --report-only); the plan's next round: {}\n",
                    summary(&round)
                ),
            );
        }
        // Report only: the MRD ensembles alone (priority 0), which are not committed
        // (deterministic, about two CPU-minutes): the report needs them beside the 3D
        // checkpoints.
        let round: Vec<Task> = round
            .into_iter()
            .filter(|t| !control.report_only || t.priority(s) == 0)
            .collect();
        if round.is_empty() {
            return Ok(());
        }
        // The shared task layer takes this shard's share of the round (K modulo N) and
        // hands the tasks out in the plan's order (cheapest grids first); the limit of
        // `stop_after` counts the tasks of every round of this run.
        let names: Vec<String> = round.iter().map(Task::file_name).collect();
        let left = RunControl {
            stop_after: control.stop_after.map(|n| n.saturating_sub(computed)),
            ..*control
        };
        let run = |i: usize| -> Result<String> {
            match &round[i] {
                Task::Bem { case, r } => json(&run_bem(s, case, *r)?),
                Task::Mrd { hurst, band } => json(&run_mrd(s, *hurst, *band)?),
                Task::MrdApproach { hurst, band } => json(&run_mrd_approach(s, *hurst, *band)?),
                Task::Control { case, m } => json(&run_control(s, case, *m)?),
            }
        };
        match tasks::compute(
            work,
            "lambda study",
            &names,
            names.len(),
            false,
            &left,
            &run,
        ) {
            Err(CompareError::Stopped { tasks }) => {
                return Err(CompareError::Stopped {
                    tasks: tasks + computed,
                })
            }
            other => other?,
        }
        computed += names.len();
        // A shard computes one round: later rounds depend on every shard's results. A
        // report only stops after the MRD ensembles.
        if control.shard.is_some() || control.report_only {
            return Ok(());
        }
    }
}

/// What a round of the plan still holds, e.g. "the next round holds 45 tasks: 45 3D
/// realisations on 2048^2 grids" (MRD ensembles and control ensembles counted apart).
fn summary(todo: &[Task]) -> String {
    if todo.is_empty() {
        return "the plan is complete".into();
    }
    let mut grids: Vec<(usize, usize)> = Vec::new();
    let (mut mrd, mut control) = (0, 0);
    for t in todo {
        match t {
            Task::Bem { case, .. } => match grids.iter_mut().find(|g| g.0 == case.grid()) {
                Some(g) => g.1 += 1,
                None => grids.push((case.grid(), 1)),
            },
            Task::Mrd { .. } | Task::MrdApproach { .. } => mrd += 1,
            Task::Control { .. } => control += 1,
        }
    }
    let mut parts: Vec<String> = grids
        .iter()
        .map(|(g, k)| format!("{k} 3D realisations on {g}^2 grids"))
        .collect();
    if mrd > 0 {
        parts.push(format!("{mrd} MRD ensembles"));
    }
    if control > 0 {
        parts.push(format!("{control} control ensembles"));
    }
    format!(
        "the next round holds {} tasks: {} (later rounds follow from its results)",
        todo.len(),
        parts.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ratio_is_settled_inside_or_wholly_outside_the_target_only() {
        let e = |value: f64, lo: f64, hi: f64| Estimate { value, lo, hi };
        assert!(settled(&e(1.0, 0.95, 1.08), 0.1));
        assert!(settled(&e(0.8, 0.75, 0.85), 0.1));
        assert!(settled(&e(1.3, 1.15, 1.4), 0.1));
        assert!(!settled(&e(1.0, 0.85, 1.05), 0.1));
        assert!(!settled(&e(0.88, 0.85, 0.95), 0.1));
        assert!(!settled(&e(1.0, f64::NAN, 1.05), 0.1));
    }
}
