//! `irsig-material list`: the columns against values worked out here (a constant curve
//! averages to itself; a step's band average is the Planck shares of its two sides, by a
//! Simpson sum of this file's own; a band table is refused outside its band), the plots
//! (one SVG per material, named by id and name), and bad input refused with nothing
//! written.

use assert_cmd::Command;
use irsig_material::list::{plot_file_name, render, summarise};
use irsig_model::MaterialLibrary;
use predicates::prelude::*;

fn material() -> Command {
    Command::cargo_bin("irsig-material").unwrap()
}

/// A library of four kinds: a grey curve with a thermal record, a step curve, a table for
/// 8-14 um only, and a grey table for every band.
const LIBRARY: &str = r#"(
  materials: [
    (id: 1, name: "grey curve", emissivity: [(0.0, 0.9), (90.0, 0.9)], specular_fraction: 0.0,
     source: "test: constant 0.9",
     spectral: Some((wavelength_um: [0.3, 15.0], emissivity: [0.9, 0.9])),
     thermal: Some((layers: [(thickness_m: 0.1, conductivity_w_m_k: 1.4, density_kg_m3: 2300.0,
       specific_heat_j_kg_k: 880.0, source: "test")], back: Adiabatic, source: "test"))),
    (id: 2, name: "step / 10 um", emissivity: [(0.0, 0.7), (90.0, 0.7)], specular_fraction: 0.0,
     source: "test: 0.5 below 10 um, 0.9 above",
     spectral: Some((wavelength_um: [2.0, 10.0, 10.000001, 15.0], emissivity: [0.5, 0.5, 0.9, 0.9]))),
    (id: 3, name: "band table", emissivity: [(0.0, 0.95), (90.0, 0.0)], specular_fraction: 0.0,
     source: "test: 8-14 um", band_um: Some((8.0, 14.0))),
    (id: 4, name: "grey table", emissivity: [(0.0, 0.8), (90.0, 0.8)], specular_fraction: 1.0,
     source: "test: grey"),
  ],
)"#;

fn library() -> MaterialLibrary {
    irsig_formats::canonical::from_ron("lib.ron", LIBRARY).unwrap()
}

/// Planck's spectral radiance, W m⁻² sr⁻¹ µm⁻¹ (CODATA 2018 radiation constants).
fn planck(lam_um: f64, t_k: f64) -> f64 {
    let c1 = 1.191_042_972e8;
    let c2 = 1.438_776_877e4;
    c1 / lam_um.powi(5) / ((c2 / (lam_um * t_k)).exp() - 1.0)
}

/// ∫ B dλ over [a, b] by composite Simpson, 2000 intervals.
fn planck_integral(a: f64, b: f64, t_k: f64) -> f64 {
    let n = 2000;
    let h = (b - a) / f64::from(n);
    let mut s = planck(a, t_k) + planck(b, t_k);
    for i in 1..n {
        let w = if i % 2 == 1 { 4.0 } else { 2.0 };
        s += w * planck(a + h * f64::from(i), t_k);
    }
    s * h / 3.0
}

#[test]
fn the_columns_are_the_band_averages_and_the_refusals_the_tracer_makes() {
    let lib = library();
    let s: Vec<_> = lib.materials.iter().map(summarise).collect();
    // A constant curve averages to itself in every band and over the sun's.
    assert_eq!(s[0].coverage, "0.3-15 um");
    for e in s[0].band_emissivity {
        assert!((e.unwrap() - 0.9).abs() < 1e-12, "{e:?}");
    }
    let (solar, how) = s[0].solar.unwrap();
    assert!((solar - 0.9).abs() < 1e-12 && how == "curve");
    assert_eq!(s[0].thermal, "1 layer, 0.1 m, adiabatic");
    // The step: 0.5 over all of 3-5 um; over 8-14 um the Planck shares at 300 K of 8-10 um
    // (0.5) and 10-14 um (0.9).
    assert!((s[1].band_emissivity[0].unwrap() - 0.5).abs() < 1e-12);
    let (lo, hi) = (
        planck_integral(8.0, 10.0, 300.0),
        planck_integral(10.0, 14.0, 300.0),
    );
    let expected = (0.5 * lo + 0.9 * hi) / (lo + hi);
    assert!((s[1].band_emissivity[1].unwrap() - expected).abs() < 1e-6);
    // Its curve starts at 2 um: no solar absorptance, and no thermal record.
    assert_eq!((s[1].solar, s[1].thermal.as_str()), (None, "-"));
    // A table for 8-14 um is refused in 3-5 um; a grey table holds in both.
    assert_eq!(s[2].coverage, "band 8-14 um");
    assert_eq!(s[2].band_emissivity, [None, Some(0.95)]);
    assert_eq!(s[3].coverage, "grey");
    assert_eq!(s[3].band_emissivity, [Some(0.8), Some(0.8)]);
    let text = render(&s);
    assert!(text.contains("0.900 (curve)"), "{text}");
    assert!(text.contains("source: test: 8-14 um"), "{text}");
    assert_eq!(text.lines().count(), 1 + 2 * 4, "{text}");
}

#[test]
fn plots_are_one_svg_per_material_named_by_id_and_name() {
    let dir = tempfile::tempdir().unwrap();
    let lib_path = dir.path().join("lib.ron");
    std::fs::write(&lib_path, LIBRARY).unwrap();
    let plots = dir.path().join("plots");
    std::fs::create_dir(&plots).unwrap();
    material()
        .args(["list", lib_path.to_str().unwrap(), "--plot"])
        .arg(&plots)
        .assert()
        .success()
        .stdout(predicate::str::contains("step / 10 um"));
    let lib = library();
    assert_eq!(plot_file_name(&lib.materials[1]), "2-step-10-um.svg");
    let mut names: Vec<String> = std::fs::read_dir(&plots)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "1-grey-curve.svg",
            "2-step-10-um.svg",
            "3-band-table.svg",
            "4-grey-table.svg"
        ]
    );
    for (name, m) in names.iter().zip(&lib.materials) {
        let svg = std::fs::read_to_string(plots.join(name)).unwrap();
        assert!(svg.starts_with("<svg"), "{name}");
        assert!(svg.contains(&m.name), "{name}");
    }
    // A spectrum is plotted against wavelength, a table against angle.
    let step = std::fs::read_to_string(plots.join("2-step-10-um.svg")).unwrap();
    assert!(step.contains("wavelength (um)"));
    let table = std::fs::read_to_string(plots.join("3-band-table.svg")).unwrap();
    assert!(table.contains("angle from the normal (deg)"));
}

#[test]
fn bad_input_is_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.ron");
    std::fs::write(
        &bad,
        LIBRARY.replace("emissivity: [0.9, 0.9]", "emissivity: [0.9, 1.9]"),
    )
    .unwrap();
    let plots = dir.path().join("plots");
    std::fs::create_dir(&plots).unwrap();
    // An emissivity above 1: exit 1, at its file and line, and no plot.
    material()
        .args(["list", bad.to_str().unwrap(), "--plot"])
        .arg(&plots)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("bad.ron").and(predicate::str::contains("1.9")));
    assert_eq!(std::fs::read_dir(&plots).unwrap().count(), 0);
    // A missing file: exit 1.
    material()
        .args(["list", dir.path().join("none.ron").to_str().unwrap()])
        .assert()
        .code(1);
    // --plot into a directory that does not exist: usage, exit 2.
    let good = dir.path().join("lib.ron");
    std::fs::write(&good, LIBRARY).unwrap();
    material()
        .args(["list", good.to_str().unwrap(), "--plot"])
        .arg(dir.path().join("no-such-dir"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("not a directory"));
}
