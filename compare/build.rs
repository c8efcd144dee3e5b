//! Embeds every scene of `cases/` (the `*.toml` files) in the library: writes the list
//! `EMBEDDED` of (name, text) that `src/scenes.rs` includes, the default scene first and
//! the others by name. A scene added to or removed from `cases/` is embedded or dropped
//! by the next build, with no list to edit.
use std::fmt::Write as _;
use std::path::Path;

/// The scene `mrdw run` runs when given none (also `scenes::DEFAULT`).
const DEFAULT: &str = "fig6";

fn main() {
    let cases = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases");
    println!("cargo:rerun-if-changed={}", cases.display());
    let mut names: Vec<String> = std::fs::read_dir(&cases)
        .expect("the cases/ folder beside compare/")
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "toml").then(|| p.file_stem()?.to_str().map(String::from))?
        })
        .collect();
    names.sort_by(|a, b| (a != DEFAULT).cmp(&(b != DEFAULT)).then(a.cmp(b)));
    assert_eq!(
        names.first().map(String::as_str),
        Some(DEFAULT),
        "cases/{DEFAULT}.toml"
    );
    let mut out = String::from("pub const EMBEDDED: &[(&str, &str)] = &[\n");
    for n in &names {
        let path = cases.join(format!("{n}.toml"));
        writeln!(
            out,
            "    ({n:?}, include_str!({:?})),",
            path.display().to_string()
        )
        .unwrap();
    }
    out.push_str("];\n");
    let dest = Path::new(&std::env::var("OUT_DIR").unwrap()).join("scenes.rs");
    std::fs::write(dest, out).unwrap();
}
