//! `mrdw`: the MRD validation workbench command-line tool.

use clap::{Parser, Subcommand};
use compare::scene::Scene;
use compare::scenes;
use std::path::PathBuf;
use std::process::ExitCode;

/// MRD validation workbench: the method of reduction of dimensionality (1D springs)
/// checked against closed forms and 3D boundary elements.
///
/// A scene (TOML case file) declares material, indenter and the outputs it wants;
/// `mrdw run` computes only what those outputs need and writes one CSV per table, one
/// PNG per figure and summary.json into a report folder.
#[derive(Parser)]
#[command(name = "mrdw", version, about, long_about, after_help = EXAMPLES)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

const EXAMPLES: &str = "Examples:
  mrdw run                      the default scene, fig6 (< 2 min), into reports/fig6/
  mrdw run tour                 every axisymmetric output on one sphere (instant)
  mrdw run cases/jkr.toml --out /tmp/jkr
  mrdw scenes                   list the embedded scenes
  mrdw show jkr > my.toml       start a new scene from an embedded one
  mrdw run fig6-full --shard 0/4 --out shards/0    one machine's share of a sweep
  mrdw merge shards/0 shards/1 shards/2 shards/3   combine the shares into one report
  mrdw bench mrd | rough | bem  run time against error of the solvers

The scene format is documented in cases/README.md.";

#[derive(Subcommand)]
enum Command {
    /// Run a scene (a .toml path or an embedded scene name; default: fig6).
    Run {
        /// Scene file path or embedded scene name.
        scene: Option<String>,
        /// Output folder (default: reports/<scene name>/). Replaced atomically.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Worker threads (default: all cores). Results do not depend on it.
        #[arg(long)]
        threads: Option<usize>,
        /// Compute only shard K of N of the sweep tasks (e.g. 0/4) into --out, for
        /// `mrdw merge`; no report is written.
        #[arg(long, value_parser = parse_shard)]
        shard: Option<(usize, usize)>,
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
        /// Largest log10 of the number of springs (mrd).
        #[arg(long, default_value_t = 6)]
        max_exp: u32,
        /// Largest grid side (bem): periodic 128.. and Hertz 128.. up to this.
        #[arg(long, default_value_t = 1024)]
        max_n: usize,
        /// Also write the periodic surfaces and our pressures as .npy here (bem), for
        /// bench/tamaas_compare.py.
        #[arg(long)]
        write_surfaces: Option<PathBuf>,
    },
    /// Internal: one benchmark case in a fresh process (for its peak memory).
    #[command(hide = true)]
    BenchCase {
        kind: String,
        n: usize,
        #[arg(long)]
        write_surfaces: Option<PathBuf>,
    },
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum BenchTarget {
    /// Normal solves and oscillation cycles on N = 1e3 .. 1e6 springs.
    Mrd,
    /// The 3D solver: periodic self-affine 128^2.. and non-periodic Hertz 128^2..
    Bem,
    /// Rough lines: generation and a 100-point k(F) curve, N = 1e3 .. 1e7.
    Rough,
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

fn stop_after() -> Option<usize> {
    std::env::var("MRDW_STOP_AFTER_TASKS")
        .ok()
        .and_then(|v| v.parse().ok())
}

fn load(scene: Option<&str>) -> Result<Scene, String> {
    let name = scene.unwrap_or(scenes::DEFAULT);
    let path = PathBuf::from(name);
    if path.exists() {
        return Scene::load(&path).map_err(|e| e.to_string());
    }
    if let Some(text) = scenes::get(name) {
        return Scene::parse(text, &format!("<embedded:{name}>"), None).map_err(|e| e.to_string());
    }
    let hint = if name.ends_with(".toml") {
        "no such file"
    } else {
        "neither a file nor an embedded scene (see `mrdw scenes`)"
    };
    Err(format!("scene `{name}`: {hint}"))
}

fn run(cmd: Command) -> Result<(), String> {
    match cmd {
        Command::Run {
            scene,
            out,
            threads,
            shard,
        } => {
            if let Some(t) = threads {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(t.max(1))
                    .build_global()
                    .map_err(|e| e.to_string())?;
            }
            let scene = load(scene.as_deref())?;
            let out = out.unwrap_or_else(|| PathBuf::from("reports").join(&scene.file.name));
            let control = compare::sweep::RunControl {
                shard,
                stop_after: stop_after(),
                progress: true,
            };
            if let Some((k, n)) = shard {
                compare::shards::run_shard(&scene, &out, &control).map_err(|e| e.to_string())?;
                println!(
                    "shard {k}/{n} of `{}` computed into {}",
                    scene.file.name,
                    out.display()
                );
                return Ok(());
            }
            let (report, files) =
                compare::run_and_write_with(&scene, &out, &control).map_err(|e| e.to_string())?;
            for w in &report.warnings {
                eprintln!("warning: {w}");
            }
            println!(
                "scene `{}`: stages {}",
                scene.file.name,
                report.stages.join(", ")
            );
            for (k, v) in &report.scalars {
                if !v.is_object() {
                    println!("  {k} = {v}");
                }
            }
            println!("wrote {} files to {}", files.len(), out.display());
            Ok(())
        }
        Command::Merge { shards, out } => {
            let (scene, report, files) =
                compare::shards::merge(&shards, out.as_deref()).map_err(|e| e.to_string())?;
            println!(
                "merged {} shards of `{}`: stages {}",
                shards.len(),
                scene.file.name,
                report.stages.join(", ")
            );
            println!("wrote {} files", files.len());
            Ok(())
        }
        Command::Scenes => {
            for (name, text) in scenes::EMBEDDED {
                let mark = if *name == scenes::DEFAULT {
                    " (default)"
                } else {
                    ""
                };
                println!("{name:<18} {}{mark}", scenes::title(text));
            }
            Ok(())
        }
        Command::Show { name } => {
            let text = scenes::get(&name)
                .ok_or_else(|| format!("no embedded scene `{name}` (see `mrdw scenes`)"))?;
            print!("{text}");
            Ok(())
        }
        Command::Bench {
            target,
            max_exp,
            max_n,
            write_surfaces,
        } => {
            match target {
                BenchTarget::Mrd => compare::bench::run_mrd(max_exp.clamp(3, 8)),
                BenchTarget::Rough => {
                    compare::bench::run_rough(if max_exp == 6 { 7 } else { max_exp.clamp(3, 8) })
                }
                BenchTarget::Bem => {
                    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
                    let mut lines = Vec::new();
                    for kind in ["periodic", "hertz"] {
                        let mut n = 128;
                        while n <= max_n && (kind == "periodic" || n <= 1024) {
                            eprintln!("running {kind} {n}^2 ...");
                            let mut cmd = std::process::Command::new(&exe);
                            cmd.args(["bench-case", kind, &n.to_string()]);
                            if let (Some(d), "periodic") = (&write_surfaces, kind) {
                                cmd.arg("--write-surfaces").arg(d);
                            }
                            let out = cmd.output().map_err(|e| e.to_string())?;
                            if !out.status.success() {
                                return Err(format!(
                                    "benchmark case {kind} {n} failed: {}",
                                    String::from_utf8_lossy(&out.stderr)
                                ));
                            }
                            lines.extend(
                                String::from_utf8_lossy(&out.stdout)
                                    .lines()
                                    .filter(|l| l.starts_with("RESULT"))
                                    .map(String::from),
                            );
                            n *= 2;
                        }
                    }
                    compare::bench::print_bem_table(&lines);
                }
            }
            Ok(())
        }
        Command::BenchCase {
            kind,
            n,
            write_surfaces,
        } => {
            compare::bench::run_bem_case(&kind, n, write_surfaces.as_deref());
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // One readable line.
            eprintln!("error: {}", e.replace('\n', " "));
            ExitCode::from(2)
        }
    }
}
