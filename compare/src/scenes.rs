//! Scenes embedded in the binary, so a user without the repository can run them.
//! Every file in `cases/` must be listed here (a test checks it).

/// (name, TOML text); the first is the default scene.
pub const EMBEDDED: &[(&str, &str)] = &[
    ("fig6", include_str!("../../cases/fig6.toml")),
    ("adhesion-3d", include_str!("../../cases/adhesion-3d.toml")),
    (
        "adhesion-3d-punch",
        include_str!("../../cases/adhesion-3d-punch.toml"),
    ),
    (
        "adhesion-tabor",
        include_str!("../../cases/adhesion-tabor.toml"),
    ),
    (
        "adhesion-tabor-exponential",
        include_str!("../../cases/adhesion-tabor-exponential.toml"),
    ),
    (
        "adhesion-3d-cone",
        include_str!("../../cases/adhesion-3d-cone.toml"),
    ),
    (
        "adhesive-cone",
        include_str!("../../cases/adhesive-cone.toml"),
    ),
    (
        "cattaneo-mindlin",
        include_str!("../../cases/cattaneo-mindlin.toml"),
    ),
    (
        "tangential-3d",
        include_str!("../../cases/tangential-3d.toml"),
    ),
    (
        "tangential-3d-free",
        include_str!("../../cases/tangential-3d-free.toml"),
    ),
    (
        "tangential-3d-cone",
        include_str!("../../cases/tangential-3d-cone.toml"),
    ),
    (
        "rough-adhesion-3d-ci",
        include_str!("../../cases/rough-adhesion-3d-ci.toml"),
    ),
    (
        "rough-adhesion-3d",
        include_str!("../../cases/rough-adhesion-3d.toml"),
    ),
    (
        "rough-adhesion-3d-punch",
        include_str!("../../cases/rough-adhesion-3d-punch.toml"),
    ),
    (
        "rough-partial-slip-3d-ci",
        include_str!("../../cases/rough-partial-slip-3d-ci.toml"),
    ),
    (
        "rough-partial-slip-3d",
        include_str!("../../cases/rough-partial-slip-3d.toml"),
    ),
    (
        "tangential-stiffness-3d-ci",
        include_str!("../../cases/tangential-stiffness-3d-ci.toml"),
    ),
    (
        "tangential-stiffness-3d",
        include_str!("../../cases/tangential-stiffness-3d.toml"),
    ),
    (
        "calibrate-ci",
        include_str!("../../cases/calibrate-ci.toml"),
    ),
    (
        "calibrate-rolloff",
        include_str!("../../cases/calibrate-rolloff.toml"),
    ),
    ("cone", include_str!("../../cases/cone.toml")),
    (
        "contact-area-ci",
        include_str!("../../cases/contact-area-ci.toml"),
    ),
    ("ejike", include_str!("../../cases/ejike.toml")),
    ("fig6-ci", include_str!("../../cases/fig6-ci.toml")),
    ("fig6-full", include_str!("../../cases/fig6-full.toml")),
    (
        "fig6-converged",
        include_str!("../../cases/fig6-converged.toml"),
    ),
    (
        "fig6-converged-ci",
        include_str!("../../cases/fig6-converged-ci.toml"),
    ),
    ("fig7", include_str!("../../cases/fig7.toml")),
    ("fig7-ci", include_str!("../../cases/fig7-ci.toml")),
    ("fig7-3d", include_str!("../../cases/fig7-3d.toml")),
    ("fig7-3d-ci", include_str!("../../cases/fig7-3d-ci.toml")),
    (
        "fig7-viscous",
        include_str!("../../cases/fig7-viscous.toml"),
    ),
    ("fig9", include_str!("../../cases/fig9.toml")),
    (
        "rough-sphere",
        include_str!("../../cases/rough-sphere.toml"),
    ),
    (
        "rough-sphere-ci",
        include_str!("../../cases/rough-sphere-ci.toml"),
    ),
    (
        "rough-slip-3d",
        include_str!("../../cases/rough-slip-3d.toml"),
    ),
    (
        "rough-slip-3d-ci",
        include_str!("../../cases/rough-slip-3d-ci.toml"),
    ),
    (
        "rough-slip-3d-punch",
        include_str!("../../cases/rough-slip-3d-punch.toml"),
    ),
    (
        "tangential-viscoelastic",
        include_str!("../../cases/tangential-viscoelastic.toml"),
    ),
    (
        "tangential-viscoelastic-3d",
        include_str!("../../cases/tangential-viscoelastic-3d.toml"),
    ),
    (
        "viscoelastic-rough",
        include_str!("../../cases/viscoelastic-rough.toml"),
    ),
    (
        "viscoelastic-rough-ci",
        include_str!("../../cases/viscoelastic-rough-ci.toml"),
    ),
    (
        "static-friction-3d",
        include_str!("../../cases/static-friction-3d.toml"),
    ),
    (
        "static-friction-3d-ci",
        include_str!("../../cases/static-friction-3d-ci.toml"),
    ),
    (
        "fig9-readings",
        include_str!("../../cases/fig9-readings.toml"),
    ),
    ("flat-punch", include_str!("../../cases/flat-punch.toml")),
    ("hertz", include_str!("../../cases/hertz.toml")),
    ("jkr", include_str!("../../cases/jkr.toml")),
    (
        "mindlin-damping",
        include_str!("../../cases/mindlin-damping.toml"),
    ),
    ("power-law", include_str!("../../cases/power-law.toml")),
    ("radok", include_str!("../../cases/radok.toml")),
    (
        "rough-stiffness",
        include_str!("../../cases/rough-stiffness.toml"),
    ),
    ("tabulated", include_str!("../../cases/tabulated.toml")),
    ("tour", include_str!("../../cases/tour.toml")),
];

/// The scene `mrdw run` runs when given none.
pub const DEFAULT: &str = "fig6";

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
