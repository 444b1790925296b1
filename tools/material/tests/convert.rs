//! `irsig-material convert` and `convert --to-legacy` end to end on the
//! legacy samples (`formats/legacy/samples/materials.mat` and the Hale & Querry water
//! `.ems` it names): the library holds what the files say (read here with a plain
//! whitespace split, not the parsers under test), converts back to the same files, and bad
//! input fails with the file, line and what is wrong, writing nothing.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use irsig_model::{MaterialId, MaterialLibrary};
use predicates::prelude::*;

fn samples() -> PathBuf {
    [env!("CARGO_MANIFEST_DIR"), "../../formats/legacy/samples"]
        .iter()
        .collect()
}

fn material() -> Command {
    Command::cargo_bin("irsig-material").unwrap()
}

/// `(angle, emissivity)` rows of an `.ems` file, by a plain split.
fn ems_rows(path: &Path) -> Vec<(f64, f64)> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            (v[0], v[1])
        })
        .collect()
}

fn library(bytes: &[u8]) -> MaterialLibrary {
    irsig_formats::canonical::from_ron_bytes("out.ron", bytes).unwrap()
}

#[test]
fn the_sample_index_converts_with_an_explicit_default() {
    let mat = samples().join("materials.mat");
    let out = material()
        .arg("convert")
        .arg(&mat)
        .args(["--default-emissivity", "0.9"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lib = library(&out.stdout);
    // materials.mat: nine entries, indices 1-9 in file order.
    let names: Vec<&str> = lib.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "asphalt", "grass", "conifer", "steel", "glass", "water", "rubber", "concrete", "wood"
        ]
    );
    for (i, m) in lib.materials.iter().enumerate() {
        assert_eq!(m.id, MaterialId(u16::try_from(i + 1).unwrap()));
    }
    // Water (index 6): the .ems rows exactly, and the specular flag 1.
    let water = lib.by_name("water").unwrap();
    assert_eq!(water.id, MaterialId(6));
    assert_eq!(
        water.emissivity,
        ems_rows(&samples().join("water-hale-querry.ems"))
    );
    assert_eq!(water.emissivity.len(), 19);
    assert!((water.specular_fraction - 1.0).abs() < f64::EPSILON);
    assert!(
        water.source.contains("water-hale-querry.ems"),
        "{}",
        water.source
    );
    // An .ems table is one band's, which the file does not say: without --band it is the
    // thesis's 8-14 um, recorded, and stderr says so.
    assert_eq!(water.band_um, Some((8.0, 14.0)));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("8-14 um") && stderr.contains("--band"),
        "{stderr}"
    );
    // The others: the constant the user named, diffuse, and a source that says so; a
    // constant holds in every band.
    let asphalt = lib.by_name("asphalt").unwrap();
    assert_eq!(asphalt.band_um, None);
    assert_eq!(asphalt.emissivity, [(0.0, 0.9)]);
    assert!(asphalt.specular_fraction.abs() < f64::EPSILON);
    assert!(
        asphalt.source.contains("--default-emissivity") && asphalt.source.contains("line 5"),
        "{}",
        asphalt.source
    );
}

#[test]
fn a_library_goes_back_to_the_same_legacy_files() {
    let dir = tempfile::tempdir().unwrap();
    // Only water has an .ems, so convert an index with water alone, then go back.
    std::fs::write(
        dir.path().join("one.mat"),
        "6 water water-hale-querry.ems 1\n",
    )
    .unwrap();
    std::fs::copy(
        samples().join("water-hale-querry.ems"),
        dir.path().join("water-hale-querry.ems"),
    )
    .unwrap();
    let lib_path = dir.path().join("lib.ron");
    material()
        .arg("convert")
        .arg(dir.path().join("one.mat"))
        .arg("-o")
        .arg(&lib_path)
        .assert()
        .success();
    let back = dir.path().join("back");
    std::fs::create_dir(&back).unwrap();
    material()
        .args(["convert", "--to-legacy"])
        .arg(&lib_path)
        .arg("--out-dir")
        .arg(&back)
        .args(["--stem", "legacy"])
        .assert()
        .success();
    // The index names water.ems (the library's name for it) with the specular flag.
    let index = std::fs::read_to_string(back.join("legacy.mat")).unwrap();
    let fields: Vec<&str> = index.split_whitespace().collect();
    assert_eq!(fields, ["6", "water", "water.ems", "1"]);
    // The table holds the original numbers.
    assert_eq!(
        ems_rows(&back.join("water.ems")),
        ems_rows(&samples().join("water-hale-querry.ems"))
    );
    // And converting back again gives the same library, up to its provenance.
    let again = material()
        .arg("convert")
        .arg(back.join("legacy.mat"))
        .output()
        .unwrap();
    let mut a = library(&again.stdout);
    let mut b = library(&std::fs::read(&lib_path).unwrap());
    for m in a.materials.iter_mut().chain(b.materials.iter_mut()) {
        m.source.clear();
    }
    assert_eq!(a, b);
}

#[test]
fn the_band_of_the_ems_tables_is_recorded_and_a_wrong_one_refused() {
    let mat = samples().join("materials.mat");
    let out = material()
        .arg("convert")
        .arg(&mat)
        .args(["--default-emissivity", "0.9", "--band", "3-5"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        library(&out.stdout).by_name("water").unwrap().band_um,
        Some((3.0, 5.0))
    );
    // Given, the band needs no note.
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for (band, expected) in [
        ("5-3", "0 < MIN < MAX"),
        ("0-5", "0 < MIN < MAX"),
        ("total", "range of wavelengths"),
        ("response.srf", "range of wavelengths"),
    ] {
        material()
            .arg("convert")
            .arg(&mat)
            .args(["--default-emissivity", "0.9", "--band", band])
            .assert()
            .failure()
            .stdout(predicate::str::is_empty())
            .stderr(predicate::str::contains(expected));
    }
}

#[test]
fn an_entry_without_ems_and_no_default_is_an_error_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lib.ron");
    material()
        .arg("convert")
        .arg(samples().join("materials.mat"))
        .arg("-o")
        .arg(&out)
        .assert()
        .code(1)
        .stderr(
            predicate::str::contains("materials.mat:5:1")
                .and(predicate::str::contains("`asphalt`"))
                .and(predicate::str::contains("--default-emissivity")),
        );
    assert!(!out.exists());
}

#[test]
fn bad_ems_files_and_values_fail_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let corpus: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "../../tests/data/malformed/legacy",
    ]
    .iter()
    .collect();
    let out = dir.path().join("lib.ron");
    for (ems, expect) in [
        ("emissivity-above-one.ems", "emissivity-above-one.ems:"),
        ("angle-above-90.ems", "angle-above-90.ems:"),
        ("angles-not-increasing.ems", "angles-not-increasing.ems:"),
    ] {
        std::fs::write(dir.path().join("i.mat"), format!("1 paint {ems} 0\n")).unwrap();
        material()
            .arg("convert")
            .arg(dir.path().join("i.mat"))
            .arg("--ems-dir")
            .arg(&corpus)
            .arg("-o")
            .arg(&out)
            .assert()
            .code(1)
            .stderr(predicate::str::contains(expect));
        assert!(!out.exists());
    }
    // An .ems file that does not exist: the index line that names it.
    std::fs::write(dir.path().join("i.mat"), "1 paint\n2 steel nowhere.ems 1\n").unwrap();
    material()
        .arg("convert")
        .arg(dir.path().join("i.mat"))
        .args(["--default-emissivity", "0.5", "-o"])
        .arg(&out)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("i.mat:2:1").and(predicate::str::contains("nowhere.ems")));
    assert!(!out.exists());
    // A default emissivity outside 0-1 is bad usage.
    material()
        .arg("convert")
        .arg(dir.path().join("i.mat"))
        .args(["--default-emissivity", "1.5"])
        .assert()
        .code(2);
    // An index to read and a library to write back do not mix; nor does --ems-dir with
    // --to-legacy, and one of the two is needed.
    for args in [
        &["convert", "x.mat", "--to-legacy", "lib.ron"][..],
        &["convert", "--to-legacy", "lib.ron", "--ems-dir", "d"],
        &["convert"],
    ] {
        material().args(args).assert().code(2);
    }
}

#[test]
fn a_partly_specular_material_has_no_legacy_form() {
    let dir = tempfile::tempdir().unwrap();
    let lib = dir.path().join("lib.ron");
    std::fs::write(
        &lib,
        "(materials: [(id: 1, name: \"paint\", emissivity: [(0.0, 0.9)], specular_fraction: 0.0, source: \"t\"), (id: 2, name: \"gloss\", emissivity: [(0.0, 0.9)], specular_fraction: 0.5, source: \"t\")])",
    )
    .unwrap();
    material()
        .args(["convert", "--to-legacy"])
        .arg(&lib)
        .arg("--out-dir")
        .arg(dir.path())
        .assert()
        .code(1)
        .stderr(predicate::str::contains("`gloss`").and(predicate::str::contains("0.5")));
    // Nothing written, not even the first material's .ems.
    assert!(!dir.path().join("paint.ems").exists());
    assert!(!dir.path().join("materials.mat").exists());
}
