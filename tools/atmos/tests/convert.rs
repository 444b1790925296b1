//! `irsig-atmos convert` end to end: the LOWTRAN7 reference tables to a canonical
//! atmosphere equal to the built-in, back to DIRTRAN tables with the same numbers, and bad
//! tables or missing units rejected with the file, line and column and nothing written.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use irsig_model::Atmosphere;
use predicates::prelude::*;

fn lowtran(ext: &str) -> String {
    let p: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "../../crates/atmosphere/data/lowtran/us-std-1976",
    ]
    .iter()
    .collect();
    p.join(format!("us-std-1976.{ext}")).display().to_string()
}

fn atmos() -> Command {
    Command::cargo_bin("irsig-atmos").unwrap()
}

fn rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect()
}

#[test]
fn reference_tables_convert_to_the_builtin_and_back() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("us.ron");
    let builtin = irsig_atmosphere::builtin("us-std-1976").unwrap();
    atmos()
        .args([
            "convert",
            "--atm",
            &lowtran("atm"),
            "--cor",
            &lowtran("cor"),
            "--dwr",
            &lowtran("dwr"),
        ])
        .args([
            "--rtt",
            &lowtran("rtt"),
            "--slant",
            &lowtran("slant.ron"),
            "--cor-altitude-m",
            "1000",
        ])
        .args([
            "--altitude-unit",
            "km",
            "--radiance-unit",
            "W/cm2/sr",
            "--name",
            "us-std-1976",
        ])
        .args(["--source", &builtin.source, "-o"])
        .arg(&out)
        .assert()
        .success();
    let converted: Atmosphere =
        irsig_formats::canonical::from_ron("out.ron", &std::fs::read_to_string(&out).unwrap())
            .unwrap();
    assert_eq!(converted, builtin);

    atmos()
        .args([
            "convert",
            "--to-legacy",
            "builtin:us-std-1976",
            "--altitude-unit",
            "km",
        ])
        .args(["--radiance-unit", "W/cm2/sr", "--stem", "back", "--out-dir"])
        .arg(dir.path())
        .assert()
        .success();
    for ext in ["atm", "cor", "dwr", "rtt"] {
        let (a, b) = (
            rows(&dir.path().join(format!("back.{ext}"))),
            rows(Path::new(&lowtran(ext))),
        );
        assert_eq!(a.len(), b.len(), "{ext}");
        for (ra, rb) in a.iter().zip(&b) {
            for (x, y) in ra.iter().zip(rb) {
                assert!((x - y).abs() <= 1e-12 * y.abs(), "{ext}: {x} vs {y}");
            }
        }
    }
}

#[test]
fn metres_and_si_radiance_are_honoured() {
    let dir = tempfile::tempdir().unwrap();
    let atm = dir.path().join("a.atm");
    let dwr = dir.path().join("a.dwr");
    std::fs::write(&atm, "50 287.8 50 0.964 1.519\n100 287.5 100 0.946 2.282\n").unwrap();
    std::fs::write(&dwr, "0 11.66\n90 43.94\n-1 15.13\n").unwrap();
    let out = atmos()
        .args(["convert", "--atm"])
        .arg(&atm)
        .arg("--dwr")
        .arg(&dwr)
        .args([
            "--altitude-unit",
            "m",
            "--radiance-unit",
            "W/m2/sr",
            "--name",
            "si",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let a: Atmosphere =
        irsig_formats::canonical::from_ron("stdout", std::str::from_utf8(&out).unwrap()).unwrap();
    assert!((a.levels[1].altitude_m - 100.0).abs() < 1e-12);
    assert!((a.levels[1].path_radiance_w_m2_sr - 2.282).abs() < 1e-12);
    assert_eq!(a.sky_hemispheric_w_m2_sr, Some(15.13));
}

#[test]
fn bad_tables_name_file_line_and_column_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let atm = dir.path().join("bad.atm");
    std::fs::write(&atm, "0.05 287 0.05 0.96 1e-4\n0.1 287 0.1 1.2 2e-4\n").unwrap();
    let out = dir.path().join("out.ron");
    atmos()
        .args(["convert", "--atm"])
        .arg(&atm)
        .args([
            "--dwr",
            &lowtran("dwr"),
            "--altitude-unit",
            "km",
            "--radiance-unit",
            "W/cm2/sr",
            "--name",
            "x",
            "-o",
        ])
        .arg(&out)
        .assert()
        .code(1)
        .stderr(
            predicates::str::contains("bad.atm:2:").and(predicates::str::contains("transmission")),
        );
    assert!(!out.exists());
    // Sky angles out of order.
    let dwr = dir.path().join("bad.dwr");
    std::fs::write(&dwr, "0 1e-3\n10 1.1e-3\n5 1.2e-3\n").unwrap();
    atmos()
        .args(["convert", "--atm", &lowtran("atm"), "--dwr"])
        .arg(&dwr)
        .args([
            "--altitude-unit",
            "km",
            "--radiance-unit",
            "W/cm2/sr",
            "--name",
            "x",
        ])
        .assert()
        .code(1)
        .stderr(predicates::str::contains("bad.dwr:3:"));
}

#[test]
fn legacy_units_must_be_stated() {
    atmos()
        .args([
            "convert",
            "--atm",
            &lowtran("atm"),
            "--dwr",
            &lowtran("dwr"),
            "--name",
            "x",
        ])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("--radiance-unit"));
}

#[test]
fn help_has_an_example() {
    atmos()
        .args(["convert", "--help"])
        .assert()
        .success()
        .stdout(predicates::str::contains("Examples:"));
}
