//! `mrdw`: the MRD validation workbench command-line tool. It parses arguments and
//! calls the `compare` library; everything it prints goes through [`Out`], so a closed
//! pipe or a full disk is an error like any other, not a panic.

mod bench;

use clap::{Parser, Subcommand};
use compare::scene::Scene;
use compare::{scenes, CompareError, RunControl};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

/// MRD validation workbench: the method of reduction of dimensionality (1D springs)
/// checked against closed forms and 3D boundary elements.
///
/// A scene (TOML case file) declares material, indenter and the outputs it wants;
/// `mrdw run` prints the plan of stages those outputs need, computes only those, and
/// writes one CSV per table, one PNG per figure and summary.json into a report folder.
#[derive(Parser)]
#[command(name = "mrdw", version, about, long_about, after_help = EXAMPLES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

const EXAMPLES: &str = "Examples:
  mrdw run                      the default scene, fig6 (run times: docs/times.md), into reports/fig6/
  mrdw run tour                 every axisymmetric output on one sphere
  mrdw run cases/jkr.toml --out /tmp/jkr
  mrdw scenes                   list the embedded scenes
  mrdw kinds                    list the output kinds a scene can request
  mrdw show jkr > my.toml       start a new scene from an embedded one
  mrdw run fig6-full --shard 0/4 --out shards/0    one machine's share of a sweep
  mrdw merge shards/0 shards/1 shards/2 shards/3   combine the shares into one report
  mrdw bench mrd | rough | bem | sliding | sliding3d | viscoelastic | adhesion | tangential
             | plastic | families | large
                                                     run time (and error) of the solvers
  mrdw bench report [--quick]   run time against error as a report folder, reports/bench/

Report folders: --out may name a new folder, an empty one, or a report folder mrdw
wrote before (replaced as a whole); any other existing path is refused. A run holds a
lock on its folder: a second run into the same folder is refused while the first runs.

Exit codes: 0 success; 2 error (bad input, failed computation, I/O), one line on
stderr; 3 stopped on request (MRDW_STOP_AFTER_TASKS) with checkpoints kept: rerun to
resume; 4 report written but some requested results are missing (e.g. unconverged 3D
solves: see the failures in summary.json and the CSV's `converged` column); 5 the
report folder is in use by another run.

The scene format is documented in cases/README.md.";

#[derive(Subcommand)]
enum Command {
    /// Run a scene (a .toml path or an embedded scene name; default: fig6).
    Run {
        /// Scene file path or embedded scene name.
        scene: Option<String>,
        /// Output folder (default: reports/<scene name>/). Written atomically; only a
        /// new, empty or earlier mrdw report folder is accepted.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Worker threads, 1..=1024 (default: all cores). Results do not depend on it.
        #[arg(long)]
        threads: Option<usize>,
        /// Compute only shard K of N of the sweep tasks (e.g. 0/4) into --out, for
        /// `mrdw merge`; no report is written.
        #[arg(long, value_parser = parse_shard)]
        shard: Option<(usize, usize)>,
        /// Checkpoint folder of resumable outputs (sweeps, studies): read, written and
        /// kept, e.g. checkpoints committed as data (default: <out>.work, removed after
        /// the report is written).
        #[arg(long)]
        work: Option<PathBuf>,
        /// Compute no 3D task: report what the checkpoints hold (a lambda_study reports
        /// its cases with data, computing its MRD ensembles first where they are missing;
        /// other outputs compute as usual).
        #[arg(long)]
        report_only: bool,
    },
    /// Combine shard folders of one scene into the report a single run would write.
    Merge {
        /// Shard folders written by `mrdw run SCENE --shard K/N --out DIR`.
        #[arg(required = true)]
        shards: Vec<PathBuf>,
        /// Report folder (default: reports/<scene name>/).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// List the embedded scenes.
    Scenes,
    /// List the output kinds a scene's [[outputs]] can request.
    Kinds,
    /// Print an embedded scene's TOML text.
    Show {
        /// Embedded scene name.
        name: String,
    },
    /// Benchmarks: run time and error (figures for the README's performance section).
    Bench {
        /// What to benchmark.
        #[arg(value_enum, default_value = "mrd")]
        target: BenchTarget,
        /// Largest log10 of the number of springs (mrd, rough, sliding): 3..=8; default 6
        /// (rough: 7).
        #[arg(long, value_parser = clap::value_parser!(u32).range(3..=8))]
        max_exp: Option<u32>,
        /// Largest grid side (bem, sliding3d, viscoelastic, adhesion, tangential, plastic,
        /// families, large: 128..=16384). bem: periodic 128.. up to this, the periodic
        /// surfaces at 0.1 % contact ("sparse") and Hertz 128.. up to min(this, 1024)
        /// (default 1024); sliding3d, viscoelastic, adhesion, tangential and plastic:
        /// 128.. up to this (default 512); families: this one grid (default 512); large:
        /// 4096.. up to this (default 16384; a smaller value runs that one grid).
        #[arg(long, value_parser = clap::value_parser!(u64).range(128..=16384))]
        max_n: Option<u64>,
        /// Also write the periodic surfaces and our pressures as .npy here (bem), for
        /// bench/tamaas_compare.py.
        #[arg(long)]
        write_surfaces: Option<PathBuf>,
        /// Small ladders (report): a quick look, not the numbers docs/performance.md shows.
        #[arg(long)]
        quick: bool,
        /// Report folder (report); default reports/bench (reports/bench-quick with
        /// --quick).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Internal: one benchmark case in a fresh process (for its peak memory).
    #[command(hide = true)]
    BenchCase {
        #[arg(value_parser = ["periodic", "sparse", "hertz", "large"])]
        kind: String,
        n: usize,
        #[arg(long)]
        write_surfaces: Option<PathBuf>,
        /// Mean pressure over E* (large).
        #[arg(long, default_value_t = 1e-2)]
        mean_pressure: f64,
        /// The direction vectors scaled to 16 bits (large): forbid, allow (above 2048^2
        /// cells) or force.
        #[arg(long, default_value = "allow", value_parser = |s: &str| s.parse::<bem3d::Choice>())]
        scaled_directions: bem3d::Choice,
    },
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum BenchTarget {
    /// Normal solves and oscillation cycles on N = 1e3 .. 1e6 springs.
    Mrd,
    /// The 3D solver: periodic self-affine 128^2.. (at 20 % and, "sparse", 0.1 % contact)
    /// and non-periodic Hertz 128^2..
    Bem,
    /// Rough lines: generation and a 100-point k(F) curve, N = 1e3 .. 1e7.
    Rough,
    /// Sliding on viscoelastic springs: steps per second for 1e4 .. 1e6 springs with
    /// 20 Prony terms, and one velocity point of fig7.
    Sliding,
    /// 3D viscoelastic sliding: one velocity point of fig7-3d at k v = 1e-2 .. 1e2 rad/s
    /// on grids 128^2 .. (--max-n)^2 (default up to 512).
    Sliding3d,
    /// The 3D solver's memory on big periodic grids: 4096^2 .. (--max-n)^2 (default
    /// 16384) at 0.1 %, 1 % and 20 % contact; time, iterations, peak resident memory and
    /// bytes per cell, each case in a fresh process (refused before allocating when the
    /// memory is not there).
    Large,
    /// Transient viscoelastic contact: seconds per time step of the 3D rough punch against
    /// elastic solves of the same grid, 128^2 .. (--max-n)^2 (default up to 512), and of
    /// 400 MRD lines on viscoelastic springs.
    Viscoelastic,
    /// Adhesive contact: seconds per load step of a JKR sphere's approach-retraction
    /// cycle (bem3d::adhesion) against warm-started non-adhesive solves at the same
    /// approaches, free grids 128^2 .. (--max-n)^2 (default up to 512).
    Adhesion,
    /// Tangential contact: seconds per partial-slip load step of a sphere (bem3d::tangential,
    /// a ramp and a cycle) against a normal solve of the same grid, periodic and free,
    /// 128^2 .. (--max-n)^2 (default up to 512).
    Tangential,
    /// Elastic-perfectly plastic contact: seconds per load step of the pressure cap
    /// (bem3d::plastic) on the periodic rough reference surface against the elastic solve
    /// at the same forces, 128^2 .. (--max-n)^2 (default up to 512).
    Plastic,
    /// Every 3D solver family against the normal solver: seconds per load step of each
    /// (pressure cap, adhesive, cohesive, transient and sliding viscoelastic, partial slip
    /// periodic and free, viscoelastic partial slip) on the periodic rough reference
    /// surface along one force ladder, over a normal step; one grid, (--max-n)^2
    /// (default 512).
    Families,
    /// Run time against error as a report folder (CSV + PNG): axisymmetric cases with
    /// closed forms (MRD semi-analytic, springs, 3D), rough contacts (alpha against a
    /// reference, 3D and MRD), scaling with fitted exponents.
    Report,
}

impl BenchTarget {
    /// `--max-exp` as given, else this target's default.
    fn max_exp(self, given: Option<u32>) -> u32 {
        given.unwrap_or(if matches!(self, BenchTarget::Rough) {
            7
        } else {
            6
        })
    }

    /// `--max-n` as given, else this target's default.
    fn max_n(self, given: Option<u64>) -> usize {
        let default = match self {
            BenchTarget::Sliding3d
            | BenchTarget::Viscoelastic
            | BenchTarget::Adhesion
            | BenchTarget::Tangential
            | BenchTarget::Plastic
            | BenchTarget::Families => 512,
            BenchTarget::Large => 16384,
            _ => 1024,
        };
        given.unwrap_or(default) as usize
    }
}

/// Refuses a `bench` option that the chosen target would not use (an option is never
/// silently ignored).
fn bench_options_apply(
    target: BenchTarget,
    max_exp: Option<u32>,
    max_n: Option<u64>,
    write_surfaces: &Option<PathBuf>,
    quick: bool,
    out: &Option<PathBuf>,
) -> Result<(), String> {
    use BenchTarget::*;
    let name = clap::ValueEnum::to_possible_value(&target)
        .map(|v| v.get_name().to_string())
        .unwrap_or_default();
    let rules: [(&str, bool, &str); 5] = [
        (
            "--max-exp",
            max_exp.is_some() && !matches!(target, Mrd | Rough | Sliding),
            "mrd, rough and sliding",
        ),
        (
            "--max-n",
            max_n.is_some()
                && !matches!(
                    target,
                    Bem | Sliding3d
                        | Viscoelastic
                        | Adhesion
                        | Tangential
                        | Plastic
                        | Families
                        | Large
                ),
            "bem, sliding3d, viscoelastic, adhesion, tangential, plastic, families and large",
        ),
        (
            "--write-surfaces",
            write_surfaces.is_some() && !matches!(target, Bem),
            "bem",
        ),
        ("--quick", quick && !matches!(target, Report), "report"),
        (
            "--out",
            out.is_some() && !matches!(target, Report),
            "report",
        ),
    ];
    match rules.iter().find(|r| r.1) {
        Some((option, _, applies)) => Err(format!(
            "{option} applies to `mrdw bench {applies}`, not to `mrdw bench {name}`"
        )),
        None => Ok(()),
    }
}

fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    let (k, n) = s.split_once('/').ok_or("expected K/N, e.g. 0/4")?;
    let (k, n): (usize, usize) = (
        k.parse().map_err(|_| "K is not a number")?,
        n.parse().map_err(|_| "N is not a number")?,
    );
    if n == 0 || k >= n {
        return Err(format!("shard {k}/{n}: need 0 <= K < N"));
    }
    Ok((k, n))
}

/// How a command ended, beyond plain success.
enum Failure {
    /// One line for stderr and the exit code.
    Error(String, u8),
}

impl From<CompareError> for Failure {
    fn from(e: CompareError) -> Self {
        let code = match e {
            CompareError::Stopped { .. } => 3,
            CompareError::Busy(_) => 5,
            _ => 2,
        };
        Failure::Error(e.to_string(), code)
    }
}

impl From<String> for Failure {
    fn from(e: String) -> Self {
        Failure::Error(e, 2)
    }
}

impl From<bench::common::Failed> for Failure {
    fn from(e: bench::common::Failed) -> Self {
        Failure::Error(format!("benchmark: {e}"), 2)
    }
}

impl From<std::io::Error> for Failure {
    fn from(e: std::io::Error) -> Self {
        Failure::Error(format!("writing to standard output: {e}"), 2)
    }
}

/// Standard output, with write errors returned instead of panicking.
struct Out(std::io::StdoutLock<'static>);

/// A line on standard error; a failed write (a closed or full stderr) is ignored: the
/// exit code still tells.
macro_rules! note {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

macro_rules! say {
    ($out:expr, $($arg:tt)*) => { writeln!($out.0, $($arg)*)? };
}

fn stop_after() -> Option<usize> {
    std::env::var("MRDW_STOP_AFTER_TASKS")
        .ok()
        .and_then(|v| v.parse().ok())
}

fn load(scene: Option<&str>) -> Result<Scene, Failure> {
    Ok(Scene::open(scene.unwrap_or(scenes::DEFAULT))?)
}

fn set_threads(threads: Option<usize>) -> Result<(), Failure> {
    let Some(t) = threads else { return Ok(()) };
    if !(1..=1024).contains(&t) {
        return Err(format!("--threads {t}: give 1..=1024 (default: all cores)").into());
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(t)
        .build_global()
        .map_err(|e| e.to_string())?;
    Ok(())
}

fn run(cmd: Command, out: &mut Out) -> Result<(), Failure> {
    match cmd {
        Command::Run {
            scene,
            out: dir,
            threads,
            shard,
            work,
            report_only,
        } => {
            set_threads(threads)?;
            let scene = load(scene.as_deref())?;
            let dir = dir.unwrap_or_else(|| PathBuf::from("reports").join(&scene.name));
            let control = RunControl {
                shard,
                stop_after: stop_after(),
                progress: true,
                report_only,
            };
            say!(out, "scene `{}`: plan", scene.name);
            write!(out.0, "{}", compare::run::plan(&scene))?;
            if let Some((k, n)) = shard {
                compare::shards::run_shard(&scene, &dir, &control)?;
                say!(out, "shard {k}/{n} computed into {}", dir.display());
                return Ok(());
            }
            let (report, files) = compare::run_to_folder(&scene, &dir, work.as_deref(), &control)?;
            for w in report.warnings() {
                note!("warning: {w}");
            }
            for (k, v) in report.results() {
                if !v.is_object() {
                    say!(out, "  {k} = {v}");
                }
            }
            say!(out, "wrote {} files to {}", files.len(), dir.display());
            incomplete(&report)
        }
        Command::Merge { shards, out: dir } => {
            let (scene, report, files) = compare::shards::merge(&shards, dir.as_deref())?;
            say!(
                out,
                "merged {} shards of `{}`: stages {}",
                shards.len(),
                scene.name,
                report.stages().join(", ")
            );
            say!(out, "wrote {} files", files.len());
            incomplete(&report)
        }
        Command::Scenes => {
            let width = scenes::EMBEDDED
                .iter()
                .map(|(n, _)| n.len())
                .max()
                .unwrap_or(0);
            for (name, text) in scenes::EMBEDDED {
                let mark = if *name == scenes::DEFAULT {
                    " (default)"
                } else {
                    ""
                };
                say!(out, "{name:<width$} {}{mark}", scenes::title(text));
            }
            Ok(())
        }
        Command::Kinds => {
            for k in compare::registry::KINDS {
                say!(out, "{:<16} {}", k.name, k.about);
            }
            say!(
                out,
                "\nKeys of each kind: cases/README.md; examples: `mrdw show NAME`."
            );
            Ok(())
        }
        Command::Show { name } => {
            let text = scenes::get(&name)
                .ok_or_else(|| format!("no embedded scene `{name}` (see `mrdw scenes`)"))?;
            write!(out.0, "{text}")?;
            Ok(())
        }
        Command::Bench {
            target,
            max_exp,
            max_n,
            write_surfaces,
            quick,
            out: folder,
        } => {
            bench_options_apply(target, max_exp, max_n, &write_surfaces, quick, &folder)?;
            let (exp, side) = (target.max_exp(max_exp), target.max_n(max_n));
            match target {
                BenchTarget::Mrd => bench::run_mrd(&mut out.0, exp)?,
                BenchTarget::Rough => bench::run_rough(&mut out.0, exp)?,
                BenchTarget::Sliding => bench::run_sliding(&mut out.0, exp)?,
                BenchTarget::Sliding3d => bench::run_sliding_3d(&mut out.0, side)?,
                BenchTarget::Viscoelastic => bench::run_viscoelastic(&mut out.0, side)?,
                BenchTarget::Adhesion => bench::run_adhesion(&mut out.0, side)?,
                BenchTarget::Tangential => bench::run_tangential(&mut out.0, side)?,
                BenchTarget::Plastic => bench::run_plastic(&mut out.0, side)?,
                BenchTarget::Families => bench::run_families(&mut out.0, side)?,
                BenchTarget::Large => bench::run_large(&mut out.0, side)?,
                BenchTarget::Bem => bench::run_bem(&mut out.0, side, write_surfaces.as_deref())?,
                BenchTarget::Report => {
                    let folder = folder.unwrap_or_else(|| {
                        PathBuf::from(if quick {
                            "reports/bench-quick"
                        } else {
                            "reports/bench"
                        })
                    });
                    let command: Vec<String> = std::env::args().collect();
                    let files = bench::report::write(
                        bench::common::Options { quick },
                        &command.join(" "),
                        &folder,
                        &mut |what| note!("bench report: {what} ..."),
                    )?;
                    say!(out, "wrote {} files into {}", files.len(), folder.display());
                }
            }
            Ok(())
        }
        Command::BenchCase {
            kind,
            n,
            write_surfaces,
            mean_pressure,
            scaled_directions,
        } => {
            if kind == "large" {
                bench::run_large_case(&mut out.0, n, mean_pressure, scaled_directions)?;
            } else {
                bench::run_bem_case(&mut out.0, &kind, n, write_surfaces.as_deref())?;
            }
            Ok(())
        }
    }
}

/// Exit code 4 when the report lacks requested results.
fn incomplete(report: &compare::report::Report) -> Result<(), Failure> {
    let failures = report.failures();
    if failures.is_empty() {
        return Ok(());
    }
    for f in &failures {
        note!("warning: {f}");
    }
    Err(Failure::Error(
        format!(
            "{} requested results are missing (see `failures` in summary.json)",
            failures.len()
        ),
        4,
    ))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let mut out = Out(std::io::stdout().lock());
    let result = run(cli.command, &mut out).and_then(|()| Ok(out.0.flush()?));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Error(e, code)) => {
            // One readable line.
            let line = compare::error::readable_numbers(&e.replace('\n', " "));
            note!("error: {line}");
            ExitCode::from(code)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::ValueEnum;

    /// A value given on the command line is the one used, for every target and every
    /// value (the defaults among them); a default applies only where none was given.
    #[test]
    fn bench_sizes_given_are_used() {
        for &target in BenchTarget::value_variants() {
            for n in [128, 512, 1024, 16384] {
                assert_eq!(target.max_n(Some(n)), n as usize);
            }
            for e in 3..=8 {
                assert_eq!(target.max_exp(Some(e)), e);
            }
        }
        assert_eq!(BenchTarget::Large.max_n(None), 16384);
        assert_eq!(BenchTarget::Sliding3d.max_n(None), 512);
        assert_eq!(BenchTarget::Rough.max_exp(None), 7);
    }

    /// An option the target does not use is refused, naming it and where it applies.
    #[test]
    fn bench_options_that_do_not_apply_are_refused() {
        let none = None::<PathBuf>;
        let e = bench_options_apply(BenchTarget::Mrd, None, Some(512), &none, false, &none);
        assert!(e
            .unwrap_err()
            .contains("--max-n applies to `mrdw bench bem,"));
        let e = bench_options_apply(BenchTarget::Large, Some(5), None, &none, false, &none);
        assert!(e.unwrap_err().contains("--max-exp"));
        let e = bench_options_apply(BenchTarget::Bem, None, None, &none, true, &none);
        assert!(e.unwrap_err().contains("not to `mrdw bench bem`"));
        bench_options_apply(BenchTarget::Bem, None, Some(128), &none, false, &none).unwrap();
        bench_options_apply(BenchTarget::Report, None, None, &none, true, &none).unwrap();
    }
}
