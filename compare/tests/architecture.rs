//! The shape of the crate, checked on its sources: no import cycle among `compare`'s
//! top-level modules, no function longer than 150 lines, and the registry as the one
//! place that lists the output kinds.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every .rs file under `dir`, recursively.
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

/// The top-level module a file belongs to (`outputs/hurst_sweep/fit.rs` -> `outputs`).
fn top_module(file: &Path) -> String {
    let rel = file.strip_prefix(src()).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// Code without comments (line comments and doc comments).
fn code(text: &str) -> String {
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) if !l[..i].contains('"') => &l[..i],
            _ => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn no_import_cycles_among_modules() {
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in files(&src()) {
        let m = top_module(&f);
        if m == "lib" {
            continue;
        }
        let text = code(&std::fs::read_to_string(&f).unwrap());
        let deps = graph.entry(m.clone()).or_default();
        for (i, _) in text.match_indices("crate::") {
            let rest = &text[i + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() && name != m && name.chars().next().unwrap().is_lowercase() {
                deps.insert(name);
            }
        }
    }
    // Depth-first search for a back edge.
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
        visit(n, &graph, &mut state, &mut Vec::new());
    }
    // The documented order holds: outputs never reach up to scene, run or shards.
    for low in ["error", "files", "plan", "report", "context", "outputs"] {
        for high in ["scene", "run", "shards"] {
            assert!(
                !graph[low].contains(high),
                "`{low}` imports `{high}`, above it"
            );
        }
    }
}

#[test]
fn no_function_longer_than_150_lines() {
    let mut long = Vec::new();
    for f in files(&src()) {
        let text = std::fs::read_to_string(&f).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let mut i = 0;
        while i < lines.len() {
            let l = lines[i].trim_start();
            let is_fn = (l.starts_with("fn ")
                || l.starts_with("pub fn ")
                || l.starts_with("pub(crate) fn "))
                && !l.ends_with(';');
            if !is_fn {
                i += 1;
                continue;
            }
            // Count braces from the signature to the matching close.
            let (mut depth, mut opened, start) = (0i64, false, i);
            while i < lines.len() {
                for c in lines[i].chars() {
                    match c {
                        '{' => {
                            depth += 1;
                            opened = true;
                        }
                        '}' => depth -= 1,
                        _ => {}
                    }
                }
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

#[test]
fn output_kinds_are_listed_only_in_the_registry() {
    // Each kind's name appears as a string literal in the registry; outside `outputs/`
    // no module matches on kinds.
    for f in files(&src()) {
        let rel = f
            .strip_prefix(src())
            .unwrap()
            .to_string_lossy()
            .into_owned();
        if rel.starts_with("outputs") {
            continue;
        }
        let text = code(&std::fs::read_to_string(&f).unwrap());
        // Unit tests may name kinds.
        let text = text.split("#[cfg(test)]").next().unwrap();
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
