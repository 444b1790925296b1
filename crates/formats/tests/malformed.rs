//! Every file in `tests/data/malformed/legacy/` goes through its legacy parser (chosen by
//! extension): no panic, an error, and a line and column that lie inside the file. The
//! few files that are well-formed syntax but bad data (degenerate triangles) must parse
//! and then be rejected by `irsig_model::Object::validate`, the layer that owns that rule.

use std::path::{Path, PathBuf};

use irsig_formats::ParseError;
use irsig_formats::legacy::{self, object};
use irsig_model::{Facet, MaterialId, Object};

/// Parses with the parser for the file's extension.
fn parse(path: &Path) -> Result<(), ParseError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{name}: {e}"));
    let text = legacy::decode(&name, &bytes)?;
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    match ext {
        "fac" => legacy::object::parse(&name, text).map(drop),
        "scn" => legacy::scene::parse(&name, text).map(drop),
        "mat" => legacy::material_index::parse(&name, text).map(drop),
        "view" => legacy::view::parse(&name, text).map(drop),
        "exec" => legacy::execute::parse(&name, text).map(drop),
        "ems" => legacy::ems::parse(&name, text).map(drop),
        "atm" => legacy::atm::parse(&name, text).map(drop),
        "cor" => legacy::cor::parse(&name, text).map(drop),
        "dwr" => legacy::dwr::parse(&name, text).map(drop),
        "rsd" => legacy::rsd::parse(&name, text).map(drop),
        "rtt" => legacy::rtt::parse(&name, text).map(drop),
        other => panic!("{name}: no legacy parser for extension `{other}`"),
    }
}

fn corpus() -> Vec<PathBuf> {
    let dir: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "..",
        "tests",
        "data",
        "malformed",
        "legacy",
    ]
    .iter()
    .collect();
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e != "md"))
        .collect();
    files.sort();
    files
}

/// Syntax that parses; the model rejects it.
const REJECTED_BY_THE_MODEL: [&str; 2] = ["degenerate-collinear.fac", "degenerate-coincident.fac"];

#[test]
fn every_malformed_file_is_an_error_inside_the_file() {
    let files = corpus();
    assert!(files.len() >= 40, "corpus too small: {}", files.len());
    for path in files {
        let file_name = path.file_name().unwrap().to_string_lossy().into_owned();
        if REJECTED_BY_THE_MODEL.contains(&file_name.as_str()) {
            continue;
        }
        let err = parse(&path).expect_err(&file_name);
        let bytes = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&bytes);
        let lines: Vec<&str> = text.split('\n').collect();
        assert!(
            err.line >= 1 && err.line <= lines.len(),
            "{file_name}: {err}"
        );
        let line_chars = lines[err.line - 1].trim_end_matches('\r').chars().count();
        assert!(
            err.column >= 1 && err.column <= line_chars + 1,
            "{file_name}: column {} outside a line of {line_chars} characters: {err}",
            err.column
        );
        assert!(
            err.to_string().starts_with(&path.display().to_string()),
            "{err}"
        );
    }
}

#[test]
fn degenerate_triangles_parse_and_the_model_rejects_them() {
    for name in REJECTED_BY_THE_MODEL {
        let path = corpus().into_iter().find(|p| p.ends_with(name)).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let parsed = object::parse(name, &text).unwrap();
        // The plainest import: three new vertices per facet.
        let mut obj = Object {
            name: name.into(),
            ..Object::default()
        };
        for (i, f) in parsed.facets.iter().enumerate() {
            let base = u32::try_from(3 * i).unwrap();
            obj.positions_m.extend(f.vertices);
            obj.facets.push(Facet {
                vertices: [base, base + 1, base + 2],
                material: MaterialId(f.material_index),
                temperature_k: f.temperature_k,
                uv: None,
            });
        }
        let err = obj.validate().expect_err(name);
        assert!(err.to_string().contains("facets[0]"), "{name}: {err}");
    }
}
