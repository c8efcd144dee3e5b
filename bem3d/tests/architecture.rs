//! The shape of the crate, checked on its sources: no import cycle among its modules
//! (top-level modules through `crate::`, the solver's parts through `super::`), and no
//! function longer than 150 lines.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
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
    let root = src();
    // Top-level modules: `crate::x` from a file of module m is an edge m -> x.
    let mut top: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    // The solver's parts (files in src/solver/): `super::x` naming a sibling file is an
    // edge; a part's use of the solver itself (`super::ContactSolver`) is not.
    let mut parts: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let siblings: BTreeSet<String> = files(&root.join("solver"))
        .iter()
        .map(|f| f.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    for f in files(&root) {
        let rel = f.strip_prefix(&root).unwrap();
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
        let deps = top.entry(module.clone()).or_default();
        deps.extend(names_after(&text, "crate::").filter(|d| *d != module && !d.is_empty()));
        if module == "solver" && rel.components().count() == 2 {
            let me = f.file_stem().unwrap().to_string_lossy().into_owned();
            let deps = parts.entry(me.clone()).or_default();
            deps.extend(names_after(&text, "super::").filter(|d| *d != me && siblings.contains(d)));
        }
    }
    // Items re-exported by lib.rs are named from lib; the graph keeps modules only.
    for deps in top.values_mut() {
        deps.retain(|d| d.chars().next().is_some_and(|c| c.is_lowercase()));
    }
    assert!(top.contains_key("solver") && parts.contains_key("iteration"));
    assert_acyclic(&top);
    assert_acyclic(&parts);
}

#[test]
fn no_function_longer_than_150_lines() {
    let mut long = Vec::new();
    for f in files(&src()) {
        let text = std::fs::read_to_string(&f).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let mut i = 0;
        while i < lines.len() {
            // `fn`, `pub fn`, `pub(crate) fn`, `pub(super) fn`, `unsafe fn`, ...
            let l = lines[i].trim_start();
            let head = l.split("fn ").next().unwrap_or("");
            let is_fn = l.contains("fn ")
                && head
                    .split_whitespace()
                    .all(|w| w == "pub" || w.starts_with("pub(") || w == "unsafe" || w == "const")
                && !l.trim_end().ends_with(';');
            if !is_fn {
                i += 1;
                continue;
            }
            // Count braces (outside comments) from the signature to the matching close.
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
    assert!(long.is_empty(), "functions over 150 lines: {long:?}");
}
