//! Fuzzing by property tests: the scene parser and the height-map readers return a
//! result (usually an error with a message) on any input, and never panic.

use compare::scene::Scene;
use mrd::topography::HeightMap;
use proptest::prelude::*;

/// Values that break naive code.
const NASTY: &[&str] = &[
    "0",
    "-1",
    "1e308",
    "-1e308",
    "1e-308",
    "nan",
    "inf",
    "-inf",
    "18446744073709551615",
    "-0.0",
    "\"\"",
    "[]",
    "{}",
    "true",
    "1e400",
    "4294967296",
    "3",
    "0.5",
];

/// Every number token of a text: (start, end) byte offsets.
fn numbers(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts = (b[i].is_ascii_digit() || b[i] == b'-')
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'));
        if starts {
            let s = i;
            i += 1;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'.' || b[i] == b'-') {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn parser_returns_on_arbitrary_text(text in "(?s).{0,300}") {
        let _ = Scene::parse(&text, "fuzz", None);
    }

    #[test]
    fn parser_returns_on_toml_like_text(
        lines in proptest::collection::vec(
            "(name|kind|hurst|grid|points|springs|max|depth|e_star|mu|rim|size|loads) = [-0-9.e\"a-z\\[\\], ]{0,20}|\\[\\[outputs\\]\\]|\\[material\\]|\\[profile\\]",
            0..20,
        )
    ) {
        let _ = Scene::parse(&lines.join("\n"), "fuzz", None);
    }

    /// Every embedded scene with one value replaced (or one line dropped) parses to a
    /// scene or an error; a scene that parses also plans.
    #[test]
    fn mutated_embedded_scenes_parse_or_fail_cleanly(
        scene in 0usize..compare::scenes::EMBEDDED.len(),
        pick in any::<prop::sample::Index>(),
        nasty in 0usize..NASTY.len(),
        drop_line in any::<bool>(),
    ) {
        let (_, text) = compare::scenes::EMBEDDED[scene];
        let mutated = if drop_line {
            let lines: Vec<&str> = text.lines().collect();
            let k = pick.index(lines.len());
            lines.iter().enumerate().filter(|(i, _)| *i != k).map(|(_, l)| *l).collect::<Vec<_>>().join("\n")
        } else {
            let nums = numbers(text);
            prop_assume!(!nums.is_empty());
            let (a, b) = nums[pick.index(nums.len())];
            format!("{}{}{}", &text[..a], NASTY[nasty], &text[b..])
        };
        if let Ok(s) = Scene::parse(&mutated, "fuzz", None) {
            let _ = compare::run::plan(&s);
        }
    }

    #[test]
    fn height_map_readers_return_on_arbitrary_bytes(
        body in proptest::collection::vec(any::<u8>(), 0..300),
        header in "\\{'descr': '<f8', 'fortran_order': (False|True), 'shape': \\([0-9]{0,12}, ?[0-9]{0,12}\\), \\}",
        version in 0u8..4,
        with_magic in any::<bool>(),
    ) {
        let dir = tempfile::tempdir().unwrap();
        let mut npy = Vec::new();
        if with_magic {
            npy.extend_from_slice(b"\x93NUMPY");
            npy.push(version);
            npy.push(0);
            let h = header.as_bytes();
            npy.extend_from_slice(&(h.len() as u16).to_le_bytes());
            npy.extend_from_slice(h);
        }
        npy.extend_from_slice(&body);
        let p = dir.path().join("m.npy");
        std::fs::write(&p, &npy).unwrap();
        let _ = HeightMap::read(&p);
        let t = dir.path().join("m.txt");
        std::fs::write(&t, &body).unwrap();
        let _ = HeightMap::read(&t);
    }

    #[test]
    fn text_maps_of_numbers_and_junk(rows in proptest::collection::vec("[-0-9.e ,;#nainf]{0,40}", 0..12)) {
        let dir = tempfile::tempdir().unwrap();
        let t = dir.path().join("m.txt");
        std::fs::write(&t, rows.join("\n")).unwrap();
        if let Ok(m) = HeightMap::read(&t) {
            prop_assert_eq!(m.data.len(), m.rows * m.cols);
            prop_assert!(m.data.iter().all(|v| v.is_finite()));
        }
    }
}
