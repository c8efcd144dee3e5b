//! The key tables of cases/README.md, one per output kind, written from the kind's scene
//! struct: its fields (serde's keys), their `///` documentation and their serde
//! defaults. The struct is the one source; the README's table between the markers
//! `<!-- keys: KIND -->` and `<!-- end of keys -->` must equal the generated one, and
//! `MRDW_BLESS=1 cargo test --release --test suite key_tables` rewrites it.

use std::path::{Path, PathBuf};

/// The `src` folder of `compare`, where every output kind's struct lives.
fn compare_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("compare/src")
}

use crate::common::rust_files as files;

/// One key of a kind: its name, its default as a scene would write it ("required" when
/// it has none) and its documentation.
#[derive(Debug)]
pub(crate) struct Key {
    pub(crate) name: String,
    pub(crate) default: String,
    pub(crate) doc: String,
}

/// The scene struct's name of the output kind `kind`, read from its registry entry
/// (`Kind::of::<path::Type>(\n "name"`).
pub(crate) fn struct_of(kind: &str) -> String {
    let registry = std::fs::read_to_string(compare_src().join("registry.rs")).unwrap();
    registry
        .find(&format!("\"{kind}\","))
        .map(|e| &registry[..e])
        .and_then(|before| before.rfind("Kind::of::<").map(|s| &before[s + 11..]))
        .and_then(|t| t.split(">(").next())
        .map(|t| t.rsplit("::").next().unwrap().to_string())
        .unwrap_or_else(|| panic!("{kind}: no registry entry"))
}

/// The file and the body (between the braces) of the struct `name` under compare/src.
fn struct_body(name: &str) -> Option<(PathBuf, String)> {
    for f in files(&compare_src()) {
        let text = std::fs::read_to_string(&f).unwrap();
        for head in [format!("pub struct {name} {{"), format!("struct {name} {{")] {
            let Some(start) = text.find(&head) else {
                continue;
            };
            // `struct X {` inside `pub struct X {` is the same struct.
            let body = &text[start + head.len()..];
            let body = &body[..body.find("\n}").unwrap_or(body.len())];
            return Some((f, body.to_string()));
        }
    }
    None
}

/// The body of the function `name` (one expression), from `file`, from the module `file`
/// imports it from (`use crate::a::b::{name, ..}`, on one line or several), or from the
/// one file under compare/src that defines it.
fn function_body(name: &str, file: &Path) -> Option<String> {
    let head = format!("fn {name}(");
    let find = |text: &str| -> Option<String> {
        let start = text.find(&head)?;
        let open = start + text[start..].find('{')?;
        let close = open + text[open..].find("\n}")?;
        Some(text[open + 1..close].trim().to_string())
    };
    let text = std::fs::read_to_string(file).unwrap();
    if let Some(b) = find(&text) {
        return Some(b);
    }
    let word = |l: &str| {
        l.split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .any(|w| w == name)
    };
    // Each `use crate::...;` statement whole, over however many lines it spans.
    let statements = text
        .split("\nuse crate::")
        .skip(1)
        .filter_map(|rest| rest.split_once(';').map(|(s, _)| format!("{s};")));
    if let Some(path) = statements.into_iter().find(|s| word(s)) {
        let module = path.split("::{").next().unwrap();
        let module = module.strip_suffix(&format!("::{name};")).unwrap_or(module);
        let base = compare_src().join(module.replace("::", "/"));
        for f in [base.with_extension("rs"), base.join("mod.rs")] {
            if let Some(b) = std::fs::read_to_string(&f).ok().and_then(|t| find(&t)) {
                return Some(b);
            }
        }
    }
    let found: Vec<String> = files(&compare_src())
        .iter()
        .filter_map(|f| find(&std::fs::read_to_string(f).unwrap()))
        .collect();
    (found.len() == 1).then(|| found[0].clone())
}

/// A default function's body as a scene writes the value (`vec![1, 2]` -> `[1, 2]`,
/// `"x".into()` -> `"x"`), or None when it is not a plain value.
fn as_scene_value(body: &str) -> Option<String> {
    let body = body.trim();
    let plain = |s: &str| {
        !s.is_empty()
            && s.chars().all(|c| {
                c.is_ascii_digit()
                    || matches!(c, '.' | '-' | '+' | 'e' | '_' | ',' | ' ' | '[' | ']')
            })
    };
    let v = body
        .strip_prefix("vec![")
        .and_then(|b| b.strip_suffix(']'))
        .map(|b| format!("[{b}]"))
        .unwrap_or_else(|| body.to_string());
    let v = v.replace(".into()", "").replace(".to_string()", "");
    let v = v.as_str();
    if v == "true" || v == "false" {
        return Some(v.to_string());
    }
    let quoted = |s: &str| {
        s.len() >= 2 && s.starts_with('"') && s.ends_with('"') && !s[1..s.len() - 1].contains('"')
    };
    if quoted(v) {
        return Some(v.to_string());
    }
    // A list of strings: ["a", "b"].
    if let Some(items) = v.strip_prefix('[').and_then(|i| i.strip_suffix(']')) {
        if items.split(", ").all(quoted) {
            return Some(v.to_string());
        }
    }
    plain(v).then(|| v.replace('_', ""))
}

/// The default of a field of type `ty` under `#[serde(default)]` (the type's own).
fn type_default(ty: &str) -> Option<String> {
    let ty = ty.trim();
    if ty.starts_with("Option<") {
        return Some("none".into());
    }
    match ty {
        "bool" => Some("false".into()),
        "usize" | "u64" | "u32" => Some("0".into()),
        "f64" => Some("0".into()),
        "String" => Some("\"\"".into()),
        t if t.starts_with("Vec<") => Some("[]".into()),
        _ => None,
    }
}

/// The keys of the scene struct `name`, in declaration order; an error names each field
/// whose documentation or default cannot be read.
pub(crate) fn keys_of(name: &str) -> Result<Vec<Key>, Vec<String>> {
    let (file, body) = struct_body(name).ok_or_else(|| vec![format!("no struct {name}")])?;
    let (mut keys, mut errors) = (Vec::new(), Vec::new());
    let (mut doc, mut attrs) = (Vec::<String>::new(), Vec::<String>::new());
    for line in body.lines().map(str::trim) {
        if let Some(d) = line.strip_prefix("///") {
            doc.push(d.trim().to_string());
            continue;
        }
        if line.starts_with("#[") {
            attrs.push(line.to_string());
            continue;
        }
        if line.starts_with("//") || !line.contains(':') {
            continue;
        }
        let field = line
            .trim_start_matches("pub ")
            .trim_start_matches("pub(crate) ")
            .trim_start_matches("pub(super) ");
        let (key, ty) = field.split_once(':').unwrap();
        let (key, ty) = (key.trim().to_string(), ty.trim().trim_end_matches(','));
        let serde: Vec<&String> = attrs.iter().filter(|a| a.contains("serde(")).collect();
        let default = if let Some(a) = serde.iter().find(|a| a.contains("default = \"")) {
            let path = a
                .split("default = \"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            let f = path.rsplit("::").next().unwrap();
            if let Some(n) = path.split("::<").nth(1) {
                // default_count::<N>: the count is the default.
                Some(n.trim_end_matches('>').replace('_', ""))
            } else {
                function_body(f, &file).and_then(|b| as_scene_value(&b))
            }
        } else if serde.iter().any(|a| a.contains("default")) {
            type_default(ty)
        } else if ty.starts_with("Option<") {
            // serde reads a missing Option as None; where None stands for a value the
            // output computes, the documentation states it.
            if doc.join(" ").contains("efault") {
                None
            } else {
                Some("none".into())
            }
        } else {
            Some("required".into())
        };
        if serde
            .iter()
            .any(|a| a.contains("rename") || a.contains("flatten"))
        {
            errors.push(format!(
                "{name}.{key}: renamed or flattened (the table reads field names)"
            ));
        }
        let text = doc.join(" ");
        if text.is_empty() {
            errors.push(format!("{name}.{key}: no /// documentation"));
        }
        let default = match default {
            Some(d) => d,
            // A default that is no plain value (a struct, a computed value): its
            // documentation must state it.
            None if text.contains("efault") => "see meaning".into(),
            None => {
                errors.push(format!(
                    "{name}.{key}: its default is no plain value; state it in its documentation"
                ));
                String::new()
            }
        };
        keys.push(Key {
            name: key,
            default,
            doc: text,
        });
        doc.clear();
        attrs.clear();
    }
    if errors.is_empty() {
        Ok(keys)
    } else {
        Err(errors)
    }
}

/// The Markdown table of `keys`.
fn table(keys: &[Key]) -> String {
    let mut t = String::from("| key | default | meaning |\n|---|---|---|\n");
    for k in keys {
        let cell = |s: &str| s.replace('|', "\\|");
        t.push_str(&format!(
            "| `{}` | {} | {} |\n",
            k.name,
            if k.default == "required" || k.default == "see meaning" {
                k.default.clone()
            } else {
                format!("`{}`", cell(&k.default))
            },
            cell(&k.doc)
        ));
    }
    t
}

const END: &str = "<!-- end of keys -->";

fn start_marker(kind: &str) -> String {
    format!("<!-- keys: {kind} (written from its struct: MRDW_BLESS=1 cargo test --release --test suite key_tables) -->")
}

/// The README's text with every kind's key table written from its struct: a table
/// between its markers is replaced; a section without one gets it at its end.
fn written(readme: &str, errors: &mut Vec<String>) -> String {
    let mut text = readme.to_string();
    for kind in compare::registry::KINDS {
        let keys = match keys_of(&struct_of(kind.name)) {
            Ok(k) => k,
            Err(e) => {
                errors.extend(e.into_iter().map(|e| format!("{}: {e}", kind.name)));
                continue;
            }
        };
        let block = format!("{}\n\n{}\n{END}", start_marker(kind.name), table(&keys));
        let marker = format!("### `{}`", kind.name);
        let Some(at) = text.find(&marker) else {
            errors.push(format!(
                "{}: no section `{marker}` in cases/README.md",
                kind.name
            ));
            continue;
        };
        let end = at + 4 + text[at + 4..].find("\n##").unwrap_or(text.len() - at - 4);
        let prefix = format!("<!-- keys: {} ", kind.name);
        match text[at..end].find(&prefix) {
            Some(s) => {
                let s = at + s;
                let e = s + text[s..].find(END).expect("an end marker after the start") + END.len();
                text.replace_range(s..e, &block);
            }
            None => {
                let body = text[at..end].trim_end();
                let insert = at + body.len();
                text.insert_str(insert, &format!("\n\n{block}"));
            }
        }
    }
    text
}

/// The keys an example of a kind's section sets (also those commented out, `# key = ..`),
/// with their line (uncommented), from its ```toml blocks' `[[outputs]]` tables.
fn example_keys(section: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for block in section.split("```toml").skip(1) {
        let block = block.split("```").next().unwrap_or("");
        let mut in_output = false;
        for line in block.lines() {
            let t = line.trim();
            if t.starts_with('[') {
                in_output = t == "[[outputs]]";
                continue;
            }
            let t = t.trim_start_matches('#').trim_start();
            let Some((key, _)) = t.split_once('=') else {
                continue;
            };
            let key = key.trim();
            if in_output
                && key != "kind"
                && !key.is_empty()
                && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            {
                out.push((key.to_string(), t.to_string()));
            }
        }
    }
    out
}

/// The examples of cases/README.md set only keys their kind has, and leave defaults to
/// the key tables (no example comment states one, so none can disagree with the struct).
#[test]
fn examples_set_only_known_keys_and_state_no_defaults() {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/README.md"))
            .unwrap();
    let mut errors = Vec::new();
    for kind in compare::registry::KINDS {
        let marker = format!("### `{}`", kind.name);
        let Some(at) = readme.find(&marker) else {
            continue;
        };
        let section = &readme[at..];
        let section = &section[..section[4..].find("\n##").map_or(section.len(), |e| e + 4)];
        let Ok(keys) = keys_of(&struct_of(kind.name)) else {
            continue;
        };
        for (key, line) in example_keys(section) {
            if !keys.iter().any(|k| k.name == key) {
                errors.push(format!(
                    "{}: the example sets `{key}`, no key of the kind",
                    kind.name
                ));
            }
            if line
                .split_once('#')
                .is_some_and(|(_, c)| c.contains("default"))
            {
                errors.push(format!(
                    "{}: the example states a default: {line}",
                    kind.name
                ));
            }
        }
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}

/// Every output kind's key table in cases/README.md is the one its struct gives: each key,
/// its default and its documentation (a key without documentation, or a default that is
/// not a plain value and not stated, fails here).
#[test]
fn key_tables_are_written_from_the_structs() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/README.md");
    let readme = std::fs::read_to_string(&path).unwrap();
    let mut errors = Vec::new();
    let text = written(&readme, &mut errors);
    if std::env::var_os("MRDW_BLESS").is_some() {
        std::fs::write(&path, &text).unwrap();
    } else if text != readme {
        let first = readme
            .lines()
            .zip(text.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(readme.lines().count().min(text.lines().count()));
        errors.push(format!(
            "cases/README.md's key tables differ from the structs from line {}: run \
             MRDW_BLESS=1 cargo test --release --test suite key_tables",
            first + 1
        ));
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
}
