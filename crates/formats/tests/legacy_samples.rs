//! The sample files in `formats/legacy/samples/` parse, with values checked by hand
//! against the files (and, for the object file, against the sample printed in thesis §4.1).
#![allow(clippy::float_cmp)] // decimal literals parse to exactly the same f64 as in Rust

use std::path::PathBuf;

use irsig_formats::legacy::{self, Position, object, scene};

fn sample(name: &str) -> (String, String) {
    let path: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "..",
        "formats",
        "legacy",
        "samples",
        name,
    ]
    .iter()
    .collect();
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let text = legacy::decode(name, &bytes).unwrap().to_owned();
    (name.to_owned(), text)
}

#[test]
fn thesis_object_sample() {
    let (name, text) = sample("thesis-4facets.fac");
    let obj = object::parse(&name, &text).unwrap();
    assert_eq!(obj.facets.len(), 4);
    assert_eq!(obj.facets[0].vertices[0], [0.0, 0.0, 0.0]);
    assert_eq!(obj.facets[1].vertices[0], [-4.100_13, -1.886_12, 0.0]);
    assert_eq!(obj.facets[2].vertices[1], [-3.1818, -3.181_83, 0.0]);
    assert_eq!(
        obj.facets[3].position,
        Position {
            line: 18,
            column: 1
        }
    );
}

#[test]
fn scene_sample() {
    let (name, text) = sample("two-patches.scn");
    let s = scene::parse(&name, &text).unwrap();
    assert_eq!(s.entries.len(), 2);
    assert_eq!(s.entries[0].temperature_k, Some(293.15));
    assert_eq!(s.entries[1].object, "thesis-4facets.fac");
    assert_eq!(s.entries[1].rotation_deg, [0.0, 0.0, 90.0]);
    assert_eq!(s.entries[1].translation, [10.0, -3.0, 0.5]);
    assert_eq!(s.entries[1].scale, [0.5, 0.5, 1.0]);
    assert_eq!(s.entries[1].temperature_k, None);
    assert_eq!(s.entries[1].position, Position { line: 7, column: 1 });
}
