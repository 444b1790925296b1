//! The binary object files in `tests/data/object/` and `tests/data/malformed/object/`, which
//! `generate.py` writes from the documented layout with Python's `struct`, independently of
//! the Rust encoder: the good one reads as the values the script wrote, the bad ones fail
//! with an error that says what is wrong and where.

use std::path::PathBuf;

use irsig_formats::canonical::{self, binary_object};
use irsig_model::{Facet, MaterialId};

fn data(path: &str) -> (String, Vec<u8>) {
    let full: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "..",
        "tests",
        "data",
        path,
    ]
    .iter()
    .collect();
    let bytes = std::fs::read(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()));
    (path.to_owned(), bytes)
}

#[test]
fn the_generated_object_reads_as_written() {
    let (name, bytes) = data("object/tri.bin");
    let o = canonical::read_object(&name, &bytes).unwrap();
    assert_eq!(o.name, "tri");
    assert_eq!(o.source, "hand-made (generate.py)");
    assert_eq!(
        o.positions_m,
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 2.0]
        ]
    );
    assert_eq!(
        o.facets,
        [
            Facet {
                vertices: [0, 1, 2],
                material: MaterialId(1),
                temperature_k: Some(300.5),
                uv: None,
            },
            Facet {
                vertices: [0, 3, 1],
                material: MaterialId(2),
                temperature_k: None,
                uv: None,
            },
        ]
    );
    // And the Rust encoder writes exactly the bytes the script did.
    assert_eq!(binary_object::encode(&o).unwrap(), bytes);
}

#[allow(clippy::float_cmp)] // coordinates and greys written exactly, read back exactly
#[test]
fn the_generated_object_with_texture_coordinates_reads_as_written() {
    let (name, bytes) = data("object/tri-uv.bin");
    let o = canonical::read_object(&name, &bytes).unwrap();
    assert_eq!(
        o.facets.iter().map(|f| f.uv).collect::<Vec<_>>(),
        [Some([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]), None]
    );
    // Besides the coordinates, the object of `tri.bin`.
    let (_, plain) = data("object/tri.bin");
    let mut without = o.clone();
    without.facets[0].uv = None;
    assert_eq!(binary_object::encode(&without).unwrap(), plain);
    assert_eq!(binary_object::encode(&o).unwrap(), bytes);
}

/// Reads a malformed file and returns the error's `file:line:column: message`.
fn error_of(file: &str) -> String {
    let (name, bytes) = data(&format!("malformed/object/{file}"));
    let e = canonical::read_object(&name, &bytes).unwrap_err();
    assert_eq!(e.file, name);
    e.to_string()
}

#[test]
fn malformed_objects_fail_with_what_and_where() {
    // 202 bytes less the last 5.
    let e = error_of("truncated.bin");
    assert!(e.contains("take 202 bytes, but the file has 197"), "{e}");
    // A name ending in .bin is read as binary even without the magic, so the error says
    // which magic was expected rather than failing as RON.
    let e = error_of("wrong-magic.bin");
    assert!(
        e.contains("expected a binary object starting with `IRSIGOBJ`"),
        "{e}"
    );
    assert!(e.contains("wrong-magic.bin:1:1:"), "{e}");
    // 10^9 facets declared: 32 + 26 + 96 + 24e9 bytes, refused before any allocation.
    let e = error_of("count-lies.bin");
    assert!(
        e.contains("1000000000 facets, which take 24000000154 bytes"),
        "{e}"
    );
    // Position 1 starts at 32 + 26 + 24 = 82: column 83.
    let e = error_of("nan.bin");
    assert!(e.contains("nan.bin:1:83:"), "{e}");
    assert!(e.contains("`positions_m[1]`"), "{e}");
    // Facet 1 starts at 32 + 26 + 96 + 24 = 178: column 179; index 4 of 4 positions.
    let e = error_of("index-out-of-range.bin");
    assert!(e.contains("index-out-of-range.bin:1:179:"), "{e}");
    assert!(e.contains("`facets[1].vertices[2]`"), "{e}");
    assert!(e.contains('4'), "{e}");
}

#[test]
fn ron_is_still_read_and_told_apart_by_the_magic() {
    let text = "(name: \"t\", positions_m: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], facets: [(vertices: (0, 1, 2), material: 1)])";
    let o = canonical::read_object("t.ron", text.as_bytes()).unwrap();
    assert_eq!(o.facets.len(), 1);
    // The same object through the binary form, under a name that says nothing.
    let bytes = binary_object::encode(&o).unwrap();
    assert_eq!(canonical::read_object("<stdin>", &bytes).unwrap(), o);
    // An empty binary object is refused by the model's rule, at the facets' offset.
    let mut empty = o.clone();
    empty.facets.clear();
    let bytes = binary_object::encode(&empty).unwrap();
    let e = canonical::read_object("<stdin>", &bytes).unwrap_err();
    assert!(e.message.contains("`facets`"), "{e}");
    assert_eq!(e.column, 32 + 1 + 72 + 1);
}
