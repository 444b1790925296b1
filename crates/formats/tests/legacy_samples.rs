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
fn quads_object_sample() {
    let (name, text) = sample("quads.fac");
    let obj = object::parse(&name, &text).unwrap();
    // Four facets: three of them 4-vertex facets, each counted once.
    assert_eq!(obj.facets.len(), 4);
    let quads: Vec<bool> = obj
        .facets
        .iter()
        .map(|f| f.fourth_vertex.is_some())
        .collect();
    assert_eq!(quads, [true, true, true, false]);
    // The unit square: equal diagonals, cut along v1–v3.
    assert_eq!(obj.facets[0].fourth_vertex, Some([0.0, 1.0, 0.0]));
    assert_eq!(obj.facets[0].triangles(), [[0, 1, 2], [0, 2, 3]]);
    // The trapezoid (6,0) (4,1) (2,1) (2,0): v1–v3 = (−4, 1) is longer than v2–v4 =
    // (−2, −1), so the cut is v2–v4. It carries 300.5 K, on line 9.
    assert_eq!(obj.facets[1].triangles(), [[0, 1, 3], [1, 2, 3]]);
    assert_eq!(obj.facets[1].temperature_k, Some(300.5));
    assert_eq!(obj.facets[1].position, Position { line: 9, column: 1 });
    // The 10 m square in the plane z = (x − 8 + y) / 3, its z rounded to six decimals:
    // accepted (see `object::quad_tolerance`).
    assert_eq!(obj.facets[2].vertices[2], [8.01, 0.01, 0.006_667]);
    assert_eq!(obj.facets[2].fourth_vertex, Some([8.0, 0.01, 0.003_333]));
    assert_eq!(obj.facets[3].triangles(), [[0, 1, 2]]);
    assert_eq!(
        obj.facets[3].position,
        Position {
            line: 21,
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

// The reference tables' expected values are the "Key numbers" of
// shared/reference/atmospheres/us-std-1976/README.md and the table in
// shared/reference/materials/README.md, not this parser's output.

#[test]
fn reference_ems_water() {
    let (name, text) = sample("water-hale-querry.ems");
    let t = legacy::ems::parse(&name, &text).unwrap();
    let pairs = t.to_pairs();
    assert_eq!(pairs.len(), 19);
    assert_eq!(pairs[0], (0.0, 0.985_191));
    assert_eq!(pairs[12], (60.0, 0.947_086));
    assert_eq!(pairs[18], (90.0, 0.0));
}

#[test]
fn reference_atm_us_std() {
    let (name, text) = sample("us-std-1976.atm");
    let t = legacy::atm::parse(&name, &text).unwrap();
    assert_eq!(t.rows.len(), 14);
    let one_km = t.rows.iter().find(|r| r.altitude_km == 1.0).unwrap();
    assert_eq!(one_km.transmission, 0.819_461);
    assert_eq!(one_km.upwelled_radiance_w_cm2_sr, 7.387_818e-4);
    assert_eq!(t.rows[13].altitude_asl_km, 10.0);
}

#[test]
fn reference_cor_dwr_rtt_us_std() {
    let (name, text) = sample("us-std-1976.cor");
    let c = legacy::cor::parse(&name, &text).unwrap();
    assert_eq!(c.coefficients, [1.102_939_90, -0.112_406_44, 0.007_031_45]);

    let (name, text) = sample("us-std-1976.dwr");
    let d = legacy::dwr::parse(&name, &text).unwrap();
    assert_eq!(d.rows.len(), 19);
    assert_eq!(d.rows[0].radiance_w_cm2_sr, 1.166_214e-3);
    assert_eq!(d.rows[18].zenith_deg, 90.0);
    assert_eq!(d.rows[18].radiance_w_cm2_sr, 4.394_162e-3);
    assert_eq!(d.hemispheric_w_cm2_sr, Some(1.513_059e-3));
    assert_eq!(d.hemispheric_position.unwrap().line, 20);

    let (name, text) = sample("us-std-1976.rtt");
    let r = legacy::rtt::parse(&name, &text).unwrap();
    assert_eq!(r.rows.len(), 151);
    assert_eq!(r.rows[0].temperature_k, 200.0);
    assert_eq!(r.rows[0].radiance_w_cm2_sr, 6.011_750_398_61e-4);
    assert_eq!(r.rows[150].temperature_k, 350.0);
}

#[test]
fn illustrative_rsd() {
    let (name, text) = sample("us-std-1976-illustrative.rsd");
    let r = legacy::rsd::parse(&name, &text).unwrap();
    assert_eq!(r.rows.len(), 10);
    // US Standard Atmosphere 1976 at 1 km: 898.76 hPa, 8.50 degC.
    assert_eq!(r.rows[2].pressure_mb, 898.76);
    assert_eq!(r.rows[2].temperature_c, 8.5);
}

#[test]
fn material_index_view_and_execute_samples() {
    let (name, text) = sample("materials.mat");
    let m = legacy::material_index::parse(&name, &text).unwrap();
    assert_eq!(m.materials.len(), 9);
    let water = m.by_index(6).unwrap();
    assert_eq!(water.name, "water");
    assert_eq!(water.ems_file.as_deref(), Some("water-hale-querry.ems"));
    assert!(water.specular);
    assert!(!m.by_name("grass").unwrap().specular);

    // Thesis Table 2, frame 2.
    let (name, text) = sample("flyby-frame2.view");
    let v = legacy::view::parse(&name, &text).unwrap();
    assert_eq!(v.position, [0.8, -3.0, 0.7]);
    assert_eq!(v.omega_phi_kappa_deg, [77.2948, 0.0, 14.9314]);
    assert_eq!(v.pixels, [256, 256]);
    assert_eq!(v.gain_dc_per_k, Some(2.0));

    let (name, text) = sample("flyby.exec");
    let e = legacy::execute::parse(&name, &text).unwrap();
    assert_eq!(e.frames.len(), 2);
    assert_eq!(e.frames[1].view, "flyby-frame2.view");
    assert_eq!(e.frames[1].lut, "frame2.lut");
    // Every file the execute file reads exists among the samples, and parses.
    for f in &e.frames {
        let (n, t) = sample(&f.view);
        legacy::view::parse(&n, &t).unwrap();
        let (n, t) = sample(&f.scene);
        for entry in scene::parse(&n, &t).unwrap().entries {
            let (n, t) = sample(&entry.object);
            object::parse(&n, &t).unwrap();
        }
    }
}
