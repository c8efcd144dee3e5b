//! The shape of the workspace, checked on its sources: no function longer than 150 lines
//! in any crate; a budget for bem3d's public API; no import cycle among the top-level modules of `bem3d` and `compare`
//! (through `crate::`) nor among the solver's files (through `super::`); `compare`'s
//! documented module order; the registry as the one place that lists output kinds; no
//! `unwrap()` or `expect(..)` in the benchmarks.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The `src` folder of the workspace member `krate` ("" for the root package).
fn src(krate: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(krate)
        .join("src")
}

use crate::common::rust_files as files;

/// Code without comments (line and doc comments) and without its unit tests (a test
/// module, always last in a file, may use any module).
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) if !l[..i].contains('"') => &l[..i],
            _ => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The identifiers that follow `prefix` in `text` (`crate::solver::Load` -> `solver`).
fn names_after<'a>(text: &'a str, prefix: &'a str) -> impl Iterator<Item = String> + 'a {
    text.match_indices(prefix).map(move |(i, _)| {
        text[i + prefix.len()..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    })
}

/// The top-level module graph of a crate: `crate::x` in a file of module m is an edge
/// m -> x (lower-case names only: modules, not re-exported items).
fn module_graph(root: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in files(root) {
        let rel = f.strip_prefix(root).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        let module = first.trim_end_matches(".rs").to_string();
        if module == "lib" {
            continue;
        }
        let text = code(&std::fs::read_to_string(&f).unwrap());
        graph.entry(module.clone()).or_default().extend(
            names_after(&text, "crate::")
                .filter(|d| *d != module && d.chars().next().is_some_and(|c| c.is_lowercase())),
        );
    }
    graph
}

/// Panics with the path of the first cycle found in `graph`.
fn assert_acyclic(graph: &BTreeMap<String, BTreeSet<String>>) {
    fn visit(
        n: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) {
        match state.get(n) {
            Some(1) => panic!("import cycle: {} -> {n}", path.join(" -> ")),
            Some(2) => return,
            _ => {}
        }
        state.insert(n.to_string(), 1);
        path.push(n.to_string());
        for d in g.get(n).into_iter().flatten() {
            visit(d, g, state, path);
        }
        path.pop();
        state.insert(n.to_string(), 2);
    }
    let mut state = BTreeMap::new();
    for n in graph.keys() {
        visit(n, graph, &mut state, &mut Vec::new());
    }
}

#[test]
fn no_import_cycles() {
    let compare = module_graph(&src("compare"));
    let bem3d = module_graph(&src("bem3d"));
    assert!(compare.contains_key("outputs") && bem3d.contains_key("solver"));
    assert_acyclic(&compare);
    assert_acyclic(&bem3d);
    // The solver's parts (files in bem3d/src/solver/): `super::x` naming a sibling file
    // is an edge; a part's use of the solver itself (`super::ContactSolver`) is not.
    let dir = src("bem3d").join("solver");
    let stem = |f: &Path| f.file_stem().unwrap().to_string_lossy().into_owned();
    let siblings: BTreeSet<String> = files(&dir).iter().map(|f| stem(f)).collect();
    let mut parts: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in files(&dir) {
        let me = stem(&f);
        let text = code(&std::fs::read_to_string(&f).unwrap());
        let deps = names_after(&text, "super::").filter(|d| *d != me && siblings.contains(d));
        parts.entry(me.clone()).or_default().extend(deps);
    }
    assert!(parts.contains_key("iteration"));
    assert_acyclic(&parts);
    // compare's documented order: the kinds and the layers below them never reach up to
    // the registry, the scene parser, the run or the shards.
    for low in [
        "error",
        "files",
        "plan",
        "report",
        "context",
        "output",
        "checks",
        "experiment",
        "outputs",
    ] {
        for high in ["registry", "scene", "run", "shards"] {
            assert!(
                !compare[low].contains(high),
                "compare: `{low}` imports `{high}`, above it"
            );
        }
    }
}

/// The module path of a source file under `root` (`outputs/lambda_study/tasks.rs` ->
/// `outputs::lambda_study::tasks`; `mod.rs` and `lib.rs`/`main.rs` name their folder).
fn module_path(root: &Path, f: &Path) -> Vec<String> {
    let rel = f.strip_prefix(root).unwrap();
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| {
            c.as_os_str()
                .to_string_lossy()
                .trim_end_matches(".rs")
                .to_string()
        })
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// The file-level import graph of a crate: in a file of module `m`, a path
/// `crate::a::b::...`, `super::a::...`, `self::a::...` or `a::...` for a child `mod a;`
/// is an edge to the file of the longest module prefix it names. A file's own module
/// and its ancestors' `mod` declarations are not edges (a parent declares, it need not
/// import).
fn file_graph(root: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let all = files(root);
    let by_path: BTreeMap<Vec<String>, String> = all
        .iter()
        .map(|f| {
            let rel = f.strip_prefix(root).unwrap().to_string_lossy().into_owned();
            (module_path(root, f), rel)
        })
        .collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &all {
        let me = module_path(root, f);
        let rel = f.strip_prefix(root).unwrap().to_string_lossy().into_owned();
        let text = code(&std::fs::read_to_string(f).unwrap());
        // `use` groups (`use crate::a::{b, c::d}`) are expanded to whole paths first.
        let text = expand_use_groups(&text);
        let children: BTreeSet<String> = text
            .lines()
            .filter_map(|l| {
                let l = l.trim();
                let l = l
                    .strip_prefix("pub ")
                    .or(l.strip_prefix("pub(crate) "))
                    .unwrap_or(l);
                l.strip_prefix("mod ")
                    .and_then(|r| r.strip_suffix(';'))
                    .map(str::to_string)
            })
            .collect();
        // The module a path names: the longest prefix that is a file of this crate,
        // read from the crate root, this module, its ancestors, a child or an alias.
        let resolve = |path: &str, aliases: &BTreeMap<String, Vec<String>>| {
            let mut segs: Vec<&str> = path.split("::").collect();
            let mut base: Vec<String> = match segs[0] {
                "crate" => Vec::new(),
                "self" => me.clone(),
                "super" => {
                    let mut b = me.clone();
                    while segs.first() == Some(&"super") {
                        b.pop();
                        segs.remove(0);
                    }
                    segs.insert(0, "super");
                    b
                }
                s if children.contains(s) => {
                    segs.insert(0, "self");
                    me.clone()
                }
                s if aliases.contains_key(s) => aliases[s].clone(),
                _ => return None,
            };
            base.extend(
                segs[1..]
                    .iter()
                    .filter(|s| **s != "self")
                    .map(|s| s.to_string()),
            );
            let exact = by_path.contains_key(&base);
            while !base.is_empty() && !by_path.contains_key(&base) {
                base.pop();
            }
            (!base.is_empty()).then_some((base, exact))
        };
        // `use crate::outputs::rough;` makes `rough::x` a path into that module.
        let mut aliases = BTreeMap::new();
        for l in text.lines().filter_map(|l| l.trim().strip_prefix("use ")) {
            let l = l.trim_end_matches(';');
            let (path, name) = match l.split_once(" as ") {
                Some((p, n)) => (p, n.to_string()),
                None => (
                    l,
                    l.trim_end_matches("::self")
                        .rsplit("::")
                        .next()
                        .unwrap_or("")
                        .to_string(),
                ),
            };
            if let Some((module, true)) = resolve(path, &aliases) {
                aliases.insert(name, module);
            }
        }
        let mut deps = BTreeSet::new();
        for path in paths_in(&text) {
            if let Some((base, _)) = resolve(&path, &aliases) {
                if base != me {
                    deps.insert(by_path[&base].clone());
                }
            }
        }
        graph.entry(rel).or_default().extend(deps);
    }
    graph
}

/// `use a::{b, c::{d, e}}` written as `a::b`, `a::c::d`, `a::c::e` (one per line).
fn expand_use_groups(text: &str) -> String {
    fn expand(prefix: &str, body: &str, out: &mut Vec<String>) {
        let mut depth = 0;
        let mut start = 0;
        let chars: Vec<char> = body.chars().collect();
        let mut items = Vec::new();
        for (i, c) in chars.iter().enumerate() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    items.push(chars[start..i].iter().collect::<String>());
                    start = i + 1;
                }
                _ => {}
            }
        }
        items.push(chars[start..].iter().collect::<String>());
        for item in items {
            let item = item.trim();
            if item.is_empty() {
                continue;
            }
            match item.find('{') {
                Some(i) => {
                    let head = item[..i].trim_end_matches("::");
                    let inner = &item[i + 1..item.rfind('}').unwrap_or(item.len())];
                    expand(&join(prefix, head), inner, out);
                }
                None => out.push(join(prefix, item)),
            }
        }
    }
    fn join(a: &str, b: &str) -> String {
        if a.is_empty() {
            b.to_string()
        } else {
            format!("{a}::{b}")
        }
    }
    let mut out = String::new();
    let mut rest = text;
    // A `use` statement starts a line (after `pub`, `pub(crate)`, ...).
    let starts_use = |t: &str, i: usize| {
        let line = t[..i].rsplit('\n').next().unwrap_or("");
        line.split_whitespace()
            .all(|w| w == "pub" || w.starts_with("pub("))
    };
    while let Some(i) = rest
        .match_indices("use ")
        .map(|(i, _)| i)
        .find(|&i| starts_use(rest, i))
    {
        out.push_str(&rest[..i]);
        let tail = &rest[i + 4..];
        let end = tail.find(';').unwrap_or(tail.len());
        let stmt: String = tail[..end].split_whitespace().collect::<Vec<_>>().join(" ");
        let mut items = Vec::new();
        expand("", &stmt, &mut items);
        let lines: Vec<String> = items.iter().map(|i| format!("use {i}")).collect();
        out.push_str(&lines.join(";\n"));
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

/// Every path with `::` in `text` (`crate::a::B`, `super::x`, `tasks::load`).
fn paths_in(text: &str) -> Vec<String> {
    let ident = |c: char| c.is_alphanumeric() || c == '_' || c == ':';
    let mut out = Vec::new();
    let mut cur = String::new();
    for c in text.chars().chain(std::iter::once(' ')) {
        if ident(c) {
            cur.push(c);
        } else {
            if cur.contains("::") {
                let p = cur.trim_matches(':').to_string();
                if !p.is_empty() {
                    out.push(p);
                }
            }
            cur.clear();
        }
    }
    out
}

/// Every import cycle of `graph`, each as its files (strongly connected components of
/// more than one file; Tarjan's algorithm).
fn cycles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<String, usize>,
        low: BTreeMap<String, usize>,
        stack: Vec<String>,
        on: BTreeSet<String>,
        out: Vec<Vec<String>>,
    }
    fn strong(t: &mut T, v: &str) {
        let i = t.index.len();
        t.index.insert(v.to_string(), i);
        t.low.insert(v.to_string(), i);
        t.stack.push(v.to_string());
        t.on.insert(v.to_string());
        for w in t.g.get(v).into_iter().flatten() {
            if !t.index.contains_key(w) {
                strong(t, w);
                let lw = t.low[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if t.on.contains(w) {
                let iw = t.index[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if t.low[v] == t.index[v] {
            let mut comp = Vec::new();
            while let Some(w) = t.stack.pop() {
                t.on.remove(&w);
                let done = w == v;
                comp.push(w);
                if done {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                t.out.push(comp);
            }
        }
    }
    let mut t = T {
        g: graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in graph.keys() {
        if !t.index.contains_key(v) {
            strong(&mut t, v);
        }
    }
    t.out
}

#[test]
fn no_import_cycle_between_files() {
    // None, the solver's files included: its state's types live in `solver/state.rs`,
    // which names no file that acts on them.
    let mut found = Vec::new();
    for krate in [
        "", "sysmem", "fftplans", "mrd", "bem3d", "compare", "python",
    ] {
        let g = file_graph(&src(krate));
        for c in cycles(&g) {
            found.push(format!("{krate}/src: {}", c.join(" <-> ")));
        }
    }
    assert!(
        found.is_empty(),
        "import cycles between files:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_file_graph_sees_imports() {
    // The graph must see the imports it is meant to judge (a test that cannot fail is
    // no test): a group import, a `super::` path, a child module's path.
    let g = file_graph(&src("compare"));
    let run = &g["run.rs"];
    assert!(run.contains("output.rs"), "{run:?}");
    assert!(g["registry.rs"].contains("outputs/rough/lambda_study/mod.rs"));
    assert!(
        g["outputs/rough/lambda_study/kind.rs"].contains("outputs/rough/lambda_study/schedule.rs")
    );
    let text = "use crate::a::{b::C, d};\nfn f() { super::x::y(); }";
    let e = expand_use_groups(text);
    assert!(
        e.contains("crate::a::b::C") && e.contains("crate::a::d"),
        "{e}"
    );
    assert!(paths_in(&e).contains(&"super::x::y".to_string()));
    let mut toy = BTreeMap::new();
    toy.insert("a".to_string(), BTreeSet::from(["b".to_string()]));
    toy.insert("b".to_string(), BTreeSet::from(["a".to_string()]));
    toy.insert("c".to_string(), BTreeSet::from(["a".to_string()]));
    assert_eq!(cycles(&toy), vec![vec!["a".to_string(), "b".to_string()]]);
}

#[test]
fn no_function_longer_than_150_lines() {
    let mut long = Vec::new();
    for krate in [
        "", "sysmem", "fftplans", "mrd", "bem3d", "compare", "python",
    ] {
        for f in files(&src(krate)) {
            let text = std::fs::read_to_string(&f).unwrap();
            let lines: Vec<&str> = text.lines().collect();
            let mut i = 0;
            while i < lines.len() {
                // `fn`, `pub fn`, `pub(crate) fn`, `pub(super) fn`, `unsafe fn`, ...
                let l = lines[i].trim_start();
                let head = l.split("fn ").next().unwrap_or("");
                let is_fn = l.contains("fn ")
                    && head.split_whitespace().all(|w| {
                        w == "pub" || w.starts_with("pub(") || w == "unsafe" || w == "const"
                    })
                    && !l.trim_end().ends_with(';');
                if !is_fn {
                    i += 1;
                    continue;
                }
                // Count braces (outside comments) from the signature to the close.
                let (mut depth, mut opened, start) = (0i64, false, i);
                while i < lines.len() {
                    let c = lines[i].split("//").next().unwrap_or("");
                    depth += c.matches('{').count() as i64 - c.matches('}').count() as i64;
                    opened |= c.contains('{');
                    i += 1;
                    if opened && depth <= 0 {
                        break;
                    }
                }
                if i - start > 150 {
                    long.push(format!(
                        "{}:{} ({} lines)",
                        f.display(),
                        start + 1,
                        i - start
                    ));
                }
            }
        }
    }
    assert!(long.is_empty(), "functions over 150 lines: {long:?}");
}

/// The benchmarks (`mrdw bench`) report a failed case as an error naming it, never by a
/// panic: no `unwrap()` or `expect(..)` outside their unit tests.
#[test]
fn benchmarks_do_not_panic_on_a_failed_case() {
    let mut found = Vec::new();
    for f in files(&src("").join("bench")) {
        let text = code(&std::fs::read_to_string(&f).unwrap());
        for (i, l) in text.lines().enumerate() {
            if l.contains(".unwrap()") || l.contains(".expect(") {
                found.push(format!("{}:{}", f.display(), i + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "unwrap or expect in the benchmarks: {found:?}"
    );
}

#[test]
fn output_kinds_are_listed_only_in_the_registry() {
    // Each kind's name appears as a string literal in the registry; outside `outputs/`
    // no module of `compare` matches on kinds.
    let root = src("compare");
    for f in files(&root) {
        let rel = f
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .into_owned();
        if rel.starts_with("outputs") || rel == "registry.rs" {
            continue;
        }
        let text = code(&std::fs::read_to_string(&f).unwrap());
        for k in [
            "\"force_depth\"",
            "\"hurst_sweep\"",
            "\"bem_contact\"",
            "\"adhesion\"",
        ] {
            assert!(!text.contains(k), "{rel} names the kind {k}");
        }
    }
}

/// The files of a crate's public modules, from its `lib.rs` down through `pub mod`
/// (relative to `src`, with their module paths), and below them the files of their
/// private modules (`mod x;`), under the path of their public ancestor and marked
/// `false`: the methods there belong to re-exported types and are API too.
fn public_files(root: &Path) -> Vec<(String, PathBuf, bool)> {
    let mut out = Vec::new();
    let mut stack = vec![(String::new(), root.join("lib.rs"), true)];
    while let Some((path, file, public)) = stack.pop() {
        let text = code(&std::fs::read_to_string(&file).unwrap());
        // Children live beside lib.rs / mod.rs, or in a folder named after the file.
        let dir = match file.file_name().and_then(|f| f.to_str()) {
            Some("lib.rs") | Some("mod.rs") => file.parent().unwrap().to_path_buf(),
            _ => file.with_extension(""),
        };
        let child_file = |child: &str| {
            let single = dir.join(format!("{child}.rs"));
            let folder = dir.join(child).join("mod.rs");
            if single.exists() {
                single
            } else {
                folder
            }
        };
        for child in names_after(&text, "pub mod ") {
            if public {
                let p = if path.is_empty() {
                    child.clone()
                } else {
                    format!("{path}::{child}")
                };
                stack.push((p, child_file(&child), true));
            } else {
                stack.push((path.clone(), child_file(&child), false));
            }
        }
        // Private children of a public module other than the crate root (the root's
        // private modules are internal unless re-exported by name).
        if !path.is_empty() {
            for l in text.lines().map(str::trim) {
                if let Some(child) = l.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
                    stack.push((path.clone(), child_file(child), false));
                }
            }
        }
        out.push((
            if path.is_empty() {
                "(crate root)".into()
            } else {
                path
            },
            file,
            public,
        ));
    }
    out.sort();
    out
}

/// The public items of one file: `pub fn`, `pub struct`, `pub enum`, `pub trait`,
/// `pub const`, `pub type` and `pub use` (not `pub(crate)`), outside its unit tests;
/// of a private module's file (`public` false) its `pub fn`s only (the methods of types
/// its public parent re-exports: the types are counted there, by name).
fn public_items(file: &Path, public: bool) -> usize {
    let text = std::fs::read_to_string(file).unwrap();
    // The file's test module (last in the file), then item by item: an item under
    // `#[cfg(test)]` is not API; a `pub use` counts the names it re-exports.
    let text = text.split("\n#[cfg(test)]\nmod ").next().unwrap_or("");
    let lines: Vec<&str> = text.lines().map(str::trim_start).collect();
    let mut count = 0;
    for i in 0..lines.len() {
        let l = lines[i];
        if i > 0 && lines[i - 1].starts_with("#[cfg(test)]") {
            continue;
        }
        if !public {
            count += l.starts_with("pub fn ") as usize;
        } else if l.starts_with("pub use ") {
            let statement: String = lines[i..].join(" ");
            let statement = statement.split(';').next().unwrap_or("");
            count += match statement.split_once('{') {
                Some((_, names)) => names
                    .split(',')
                    .filter(|n| !n.trim().trim_end_matches('}').trim().is_empty())
                    .count(),
                None => 1,
            };
        } else if [
            "pub fn ",
            "pub struct ",
            "pub enum ",
            "pub trait ",
            "pub const ",
            "pub type ",
        ]
        .iter()
        .any(|p| l.starts_with(p))
        {
            count += 1;
        }
    }
    count
}

/// bem3d's public API has a budget per public module (210 items: declarations, the
/// names of `pub use` re-exports, and the methods in a public module's private files):
/// a change that adds public items raises the budget here, and the commit says who
/// needs them (the crate doc names the users of `fft`, `wide` and `mask`). The crate
/// root's private modules (`symbol`, `stencil`, `love`, `pool`, `set_solve`) are not
/// counted unless re-exported: they are not reachable.
#[test]
fn bem3d_public_api_stays_within_its_budget() {
    const BUDGET: &[(&str, usize)] = &[
        // SolverOperator, HalfSpaceOperator and SlipOperator, the bounds of the solvers'
        // entry points, and the 17 entry points (compiled.rs: constructors, solves and
        // steps of ContactSolver, AdhesiveContact, CohesiveContact, PlasticContact,
        // TransientContact, PartialSlip and ViscoelasticSlip; their other methods count in
        // their modules).
        ("(crate root)", 44),
        // interrupt_on here, in cohesive and twice in tangential (PartialSlip,
        // ViscoelasticSlip), and CerrutiPeriodic::stick_stiffness_until: Python stops a
        // step on Ctrl-C through them.
        // AdhesiveContact::snapshot and ::restore with their AdhesiveSnapshot: the
        // adhesive contact law of `dynamics` takes a rejected time step back.
        ("adhesion", 14),
        // CohesiveLaw with CohesiveContact::with_law and ::law: the exponential law, chosen
        // by Python's CohesiveContact(law="exponential") (checked against Tamaas there).
        ("cohesive", 11),
        ("error", 3),
        ("fft", 25),
        ("mask", 2),
        // PlasticContact (new, step, pressure, plastic_displacement, gap, force_limit,
        // hardness, interrupt_on), PlasticStep, AT_CAP and STEP_TOLERANCE (the bindings'
        // default): the pressure-cap family, for compare's plastic_3d and Python's
        // PlasticContact.
        ("plastic", 10),
        ("operator", 34),
        ("sliding", 4),
        ("solution", 5),
        // ContactSolver::new_shared and its SharedHeights: Python's Contact reads the
        // caller's numpy heights in place (no copy beside the user's array).
        ("solver", 25),
        // CerrutiFree (the free half-space: tangential_3d, tangential_viscoelastic, Python
        // PartialSlip(periodic=False)), the TangentialCompliance trait both operators
        // implement, ViscoelasticSlip and its step (tangential_viscoelastic's 3D side);
        // ViscoelasticSlip::snapshot and ::restore with their SlipSnapshot: the 3D
        // partial-slip law of `dynamics` (`SlipBem3d`) takes a rejected time step back;
        // equivalent_body, the (E*, G*) -> (nu, G) the Cerruti operators take, for compare
        // and `dynamics`; ViscoelasticSlip::press, the pressure of a varying normal force
        // step by step (`dynamics::ObliqueBem3d`).
        ("tangential", 24),
        // TransientContact::snapshot and ::restore with their Snapshot: the viscoelastic
        // contact law of `dynamics` takes a rejected time step back.
        ("viscoelastic", 12),
        ("wide", 5),
    ];
    let root = src("bem3d");
    let mut over = Vec::new();
    let mut seen = BTreeMap::new();
    // The solvers' constructors, solves and steps, compiled once in bem3d for each
    // operator (compiled.rs, a private module of the root), count at the root.
    let mut files = public_files(&root);
    files.push(("(crate root)".into(), root.join("compiled.rs"), false));
    for (path, file, public) in files {
        *seen
            .entry(path.split("::").next().unwrap().to_string())
            .or_insert(0) += public_items(&file, public);
    }
    for (module, count) in &seen {
        match BUDGET.iter().find(|(m, _)| m == module) {
            Some((_, b)) if count <= b => {}
            Some((_, b)) => over.push(format!("{module}: {count} public items, budget {b}")),
            None => over.push(format!("{module}: {count} public items, no budget")),
        }
    }
    assert!(
        over.is_empty(),
        "bem3d's public API grew past its budget: {over:?} (all: {seen:?})"
    );
    // The budget is tight: a module that shrank lowers it (so the next growth is seen).
    let slack: Vec<_> = BUDGET
        .iter()
        .filter(|(m, b)| seen.get(*m).is_some_and(|c| c < b))
        .collect();
    assert!(
        slack.is_empty(),
        "lower the budget of {slack:?} to the counts {seen:?}"
    );
}

#[test]
fn the_contact_solver_stays_small() {
    // Its state split by job (at most 10 fields) and its methods in at most 3 files,
    // so that a new strategy lands as a part or a problem's method, not as more
    // solver. Its public entry points are in compiled.rs (below).
    let root = src("bem3d");
    let mut with_methods = Vec::new();
    let mut all = files(&root.join("solver"));
    all.push(root.join("solver.rs"));
    for f in &all {
        let text = code(&std::fs::read_to_string(f).unwrap());
        if text.contains("> ContactSolver<K> {") && text.contains("impl<") {
            with_methods.push(f.display().to_string());
        }
    }
    assert!(
        (1..=3).contains(&with_methods.len()),
        "ContactSolver's methods in {} files: {with_methods:?}",
        with_methods.len()
    );
    let state = code(&std::fs::read_to_string(root.join("solver/state.rs")).unwrap());
    let body = state
        .split("pub struct ContactSolver<K: GridOperator> {")
        .nth(1)
        .and_then(|rest| rest.split('}').next())
        .expect("ContactSolver is defined in solver/state.rs");
    let fields = body.lines().filter(|l| l.trim_end().ends_with(',')).count();
    assert!(
        (1..=10).contains(&fields),
        "ContactSolver has {fields} fields"
    );
}

/// The solvers' public entry points (bem3d/src/compiled.rs, compiled once in bem3d for
/// each operator: a release build instantiates generic code anew in every calling
/// crate) hold no solver code: each is one call of its operator's entry, whose
/// implementations each call one generic body.
#[test]
fn the_compiled_entry_points_only_forward() {
    let text = code(&std::fs::read_to_string(src("bem3d").join("compiled.rs")).unwrap());
    let mut entries = 0;
    for body in text
        .split("pub fn ")
        .skip(1)
        .chain(text.split("            fn ").skip(1))
    {
        let body = body.split_once('{').unwrap().1;
        let body = body
            .split("\n    }")
            .next()
            .unwrap()
            .split("\n            }")
            .next();
        let lines: Vec<&str> = body.unwrap().trim().lines().collect();
        assert!(
            lines.len() == 1 && !lines[0].contains(';'),
            "an entry point in bem3d/src/compiled.rs does more than forward: {lines:?}"
        );
        entries += 1;
    }
    assert!(
        entries >= 30,
        "{entries} entry points found: is the file's layout the same?"
    );
}

/// The Markdown pages of the repository (README, docs/, cases/, bench/).
fn pages() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut p = vec![root.join("README.md"), root.join("cases/README.md")];
    for dir in ["docs", "bench"] {
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let f = e.unwrap().path();
            if f.extension().is_some_and(|x| x == "md") {
                p.push(f);
            }
        }
    }
    p
}

/// The relative links `](target)` of a page (no URLs, no anchors).
fn links(text: &str) -> Vec<String> {
    text.split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .map(|l| l.split('#').next().unwrap().trim().to_string())
        .filter(|l| !l.is_empty() && !l.contains("://") && !l.starts_with("mailto:"))
        .collect()
}

/// Every relative link of the pages leads to a file, and every figure under docs/ is
/// shown on a page (a figure nobody sees is either shown or removed).
#[test]
fn links_resolve_and_every_docs_figure_is_shown() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut broken = Vec::new();
    let mut shown = BTreeSet::new();
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        for l in links(&text) {
            let target = page.parent().unwrap().join(&l);
            match target.canonicalize() {
                Ok(t) => {
                    shown.insert(t);
                }
                Err(_) => broken.push(format!("{}: {l}", page.display())),
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
    let mut unshown = Vec::new();
    let mut stack = vec![root.join("docs")];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(dir).unwrap() {
            let f = e.unwrap().path();
            if f.is_dir() {
                stack.push(f);
            } else if f.extension().is_some_and(|x| x == "png")
                && !shown.contains(&f.canonicalize().unwrap())
            {
                unshown.push(f.display().to_string());
            }
        }
    }
    assert!(
        unshown.is_empty(),
        "figures shown on no page:\n{}",
        unshown.join("\n")
    );
}

/// Phrases that quote a run time ("40 s on 2 cores", "about a minute", "a few CPU-minutes").
const TIME_PHRASES: &[&str] = &[
    "on 2 cores",
    "on two cores",
    "cpu-seconds",
    "cpu-minutes",
    "cpu-hours",
    "about a second",
    "about a minute",
    "about an hour",
    "a few seconds",
    "a few minutes",
    "under a second",
    "under a minute",
    "(instant)",
];

/// docs/times.md is the one table of run times (written by scripts/setup-times.sh from
/// one dated run): it times every embedded scene, the pages a newcomer reads first (the
/// README, cases/, the scenes' own comments, the CLI's help, the Python page) quote no
/// run time of their own, and a time the README quotes beside its link is in the table.
#[test]
fn run_times_have_one_table() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let table = std::fs::read_to_string(root.join("docs/times.md")).unwrap();
    let mut missing = Vec::new();
    let mut quoted = Vec::new();
    let mut sources = vec![
        root.join("README.md"),
        root.join("cases/README.md"),
        root.join("docs/python.md"),
        root.join("src/main.rs"),
    ];
    for e in std::fs::read_dir(root.join("cases")).unwrap() {
        let f = e.unwrap().path();
        if f.extension().is_some_and(|x| x == "toml") {
            let text = std::fs::read_to_string(&f).unwrap();
            let name = text
                .lines()
                .find_map(|l| l.strip_prefix("name = \""))
                .and_then(|l| l.split('"').next())
                .unwrap_or_default()
                .to_string();
            let long = ["fig6-full", "fig6-converged"].contains(&name.as_str());
            if !long && !table.contains(&format!("| `{name}` |")) {
                missing.push(name);
            }
            sources.push(f);
        }
    }
    for f in &sources {
        let text = std::fs::read_to_string(f).unwrap();
        for (i, line) in text.lines().enumerate() {
            let lower = line.to_lowercase();
            let linked = line.contains("docs/times.md");
            if !linked && TIME_PHRASES.iter().any(|p| lower.contains(p)) {
                quoted.push(format!("{}:{}: {line}", f.display(), i + 1));
            }
            // "N min M s" beside the link: the table must hold it.
            if linked {
                for (at, _) in line.match_indices(" min ") {
                    let m = line[..at].rsplit(' ').next().unwrap_or("");
                    let sec = line[at + 5..].split(' ').next().unwrap_or("");
                    let quote = format!("{m} min {sec} s");
                    if !table.contains(&quote) {
                        let at = format!("{}:{}", f.display(), i + 1);
                        quoted.push(format!("{at}: {quote} is not in docs/times.md"));
                    }
                }
            }
        }
    }
    assert!(
        missing.is_empty(),
        "scenes docs/times.md does not time (bash scripts/setup-times.sh): {missing:?}"
    );
    assert!(
        quoted.is_empty(),
        "run times quoted outside docs/times.md (link to it instead):\n{}",
        quoted.join("\n")
    );
}
