//! Scenes embedded in the binary, so a user without the repository can run them: every
//! file of `cases/`, listed by the build script (`compare/build.rs`).

// (name, TOML text) of every file of `cases/`, the default scene first (build.rs).
include!(concat!(env!("OUT_DIR"), "/scenes.rs"));

/// The scene `mrdw run` runs when given none.
pub const DEFAULT: &str = EMBEDDED[0].0;

pub fn get(name: &str) -> Option<&'static str> {
    EMBEDDED.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// One-line title of an embedded scene (its `title`, else its name).
pub fn title(text: &str) -> String {
    text.lines()
        .find_map(|l| l.strip_prefix("title = "))
        .map(|t| t.trim().trim_matches('"').to_string())
        .unwrap_or_default()
}
