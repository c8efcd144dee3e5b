//! The shape of the workspace, checked on its sources: no function longer than 150 lines
//! in any crate; no import cycle among the top-level modules of `bem3d` and `compare`
//! (through `crate::`) nor among the solver's files (through `super::`); `compare`'s
//! documented module order; the registry as the one place that lists output kinds.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The `src` folder of the workspace member `krate` ("" for the root package).
fn src(krate: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join(krate)
        .join("src")
}

/// Every .rs file under `dir`, recursively, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(files(&p));
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
    out.sort();
    out
}

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
    // compare's documented order: outputs never reach up to scene, run or shards.
    for low in ["error", "files", "plan", "report", "context", "outputs"] {
        for high in ["scene", "run", "shards"] {
            assert!(
                !compare[low].contains(high),
                "compare: `{low}` imports `{high}`, above it"
            );
        }
    }
}

#[test]
fn no_function_longer_than_150_lines() {
    let mut long = Vec::new();
    for krate in ["", "sysmem", "mrd", "bem3d", "compare", "python"] {
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
        if rel.starts_with("outputs") {
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
