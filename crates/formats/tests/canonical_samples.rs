//! Every sample in `formats/canonical/samples` parses, validates and round-trips through
//! the RON writer; the raw scene also through the binary form.

use std::path::PathBuf;

use irsig_formats::canonical::{self, Canonical};
use irsig_model::uncertainty::{Facets, Uncertainties};
use irsig_model::{Atmosphere, MaterialLibrary, Object, RegionSet, Scene, View};

fn sample(name: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../formats/canonical/samples")
        .join(name);
    std::fs::read_to_string(path).unwrap()
}

fn round_trip<T: Canonical + PartialEq + std::fmt::Debug>(name: &str) -> T {
    let value: T = canonical::from_ron(name, &sample(name)).unwrap();
    let again: T = canonical::from_ron(name, &canonical::to_ron(&value).unwrap()).unwrap();
    assert_eq!(again, value, "{name}");
    value
}

#[test]
fn every_sample_reads_and_round_trips() {
    let lib: MaterialLibrary = round_trip("materials.ron");
    assert_eq!(lib.materials.len(), 3);
    let object: Object = round_trip("box.ron");
    assert_eq!(object.facets.len(), 12);
    let scene: Scene = round_trip("scene.ron");
    assert_eq!(scene.objects.len(), 2);
    assert!(scene.objects[1].scale[0] < 0.0);
    let atmosphere: Atmosphere = round_trip("atmosphere.ron");
    assert_eq!(atmosphere.levels.len(), 2);
    let view: View = round_trip("view.ron");
    assert_eq!(view.pixels(), [256, 256]);
    let look: View = round_trip("view-look-at.ron");
    assert!(matches!(look, View::LookAt { .. }));
    let u: Uncertainties = round_trip("uncertainties.ron");
    assert_eq!(u.temperature[1].facets, Facets::Object("panel".into()));
    assert!((u.path_radiance_relative - 0.05).abs() < 1e-12);
}

#[test]
fn the_flattened_sample_is_the_same_in_ron_and_binary() {
    let object: Object = canonical::from_ron("box.ron", &sample("box.ron")).unwrap();
    let scene: Scene = canonical::from_ron("scene.ron", &sample("scene.ron")).unwrap();
    let raw = irsig_scene::flatten(&scene, &[&object, &object]).unwrap();
    let ron = canonical::to_ron(&raw).unwrap();
    let bin = canonical::binary::encode(&raw).unwrap();
    assert_eq!(
        canonical::read_raw_scene("r.ron", ron.as_bytes()).unwrap(),
        raw
    );
    assert_eq!(canonical::read_raw_scene("r.bin", &bin).unwrap(), raw);
    assert!(bin.starts_with(b"IRSIGRAW"));
}

#[test]
fn the_regions_sample_reads_and_round_trips() {
    let set: RegionSet = round_trip("regions.ron");
    assert_eq!(set.references.len(), 2);
    assert_eq!(set.regions.len(), 3);
    assert_eq!(
        RegionSet::reference(&set.regions[1], "measured"),
        Some(297.4)
    );
    assert_eq!(RegionSet::reference(&set.regions[2], "kinetic"), None);
}

#[test]
fn a_material_rms_slope_is_read_and_a_bad_one_is_refused_at_its_place() {
    use irsig_model::MaterialLibrary;
    let lib = |sigma: &str| {
        format!(
            "(\n  materials: [\n    (\n      id: 1, name: \"paint\", emissivity: [(0.0, 0.9)],\n      specular_fraction: 1.0, source: \"x\",\n      rms_slope: {sigma},\n    ),\n  ],\n)\n"
        )
    };
    let ok = irsig_formats::canonical::from_ron::<MaterialLibrary>("lib.ron", &lib("Some(0.15)"))
        .unwrap();
    assert_eq!(ok.materials[0].rms_slope, Some(0.15));
    // Absent is None, and writes nothing back: a library without it keeps its bytes.
    let text = "(materials: [(id: 1, name: \"a\", emissivity: [(0.0, 0.9)], specular_fraction: 1.0, source: \"x\")])";
    let plain = irsig_formats::canonical::from_ron::<MaterialLibrary>("lib.ron", text).unwrap();
    assert_eq!(plain.materials[0].rms_slope, None);
    assert!(
        !irsig_formats::canonical::to_ron_pretty(&plain)
            .unwrap()
            .contains("rms_slope")
    );
    for bad in ["Some(-0.1)", "Some(10.5)", "Some(inf)", "Some(NaN)"] {
        let text = lib(bad);
        let e =
            irsig_formats::canonical::from_ron::<MaterialLibrary>("lib.ron", &text).unwrap_err();
        assert!(e.message.contains("materials[0].rms_slope"), "{bad}: {e}");
        assert_eq!(e.line, 6, "{bad}: {e}");
        let column = text.lines().nth(5).unwrap().find("Some(").unwrap() + 1;
        assert_eq!(e.column, column, "{bad}: {e}");
    }
}

#[test]
fn the_temperature_history_sample_reads_and_writes_back_bit_for_bit() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../formats/canonical/samples/history.thm");
    let bytes = std::fs::read(path).unwrap();
    let h = canonical::binary_history::decode("history.thm", &bytes).unwrap();
    // A plate of two facets, 12:00 to 13:00 MST (UTC-7) on 7 August 2001 every 300 s.
    assert_eq!(h.facets, 2);
    assert_eq!(h.time_s.len(), 13);
    let noon = irsig_model::time::utc_seconds(2001, 8, 7, 19, 0, 0.0).unwrap();
    assert!((h.time_s[0] - noon).abs() < 1e-6);
    assert!(h.temperature_k.iter().all(|&t| (280.0..360.0).contains(&t)));
    assert_eq!(canonical::binary_history::encode(&h).unwrap(), bytes);
}

#[test]
fn the_loads_samples_read_round_trip_and_tell_their_kind_of_plan() {
    use irsig_formats::canonical::AnyPlan;
    use irsig_model::loads::{BroadbandLoads, LoadsPlan};
    let plan: LoadsPlan = round_trip("loads-plan.ron");
    assert_eq!(plan.sun.len(), 2);
    let pi = std::f64::consts::PI;
    for sun in &plan.sun {
        let sum: f64 = sun.diffuse.iter().map(|n| n.2).sum();
        assert!((sum / pi - 1.0).abs() < 1e-3, "{sum}");
    }
    let table: BroadbandLoads = round_trip("broadband-loads.ron");
    assert_eq!(table.sun_zenith_deg.len(), table.direct_normal_w_m2.len());
    assert!(table.longwave_down_w_m2 > table.longwave_outside_range_w_m2);
    // A loads plan is told from an atmosphere plan by its `longwave` field.
    let any = canonical::read_any_plan("loads-plan.ron", sample("loads-plan.ron").as_bytes());
    assert!(matches!(any, Ok(AnyPlan::Loads(p)) if p == plan));
    let atmosphere = "(name: \"a\", model: Standard(1), wavenumber_per_cm: (710.0, 1250.0, 90.0), \
        path_end_m: 1.0, observers_m: [1000.0], levels_m: [1000.0], correction_altitude_m: \
        1000.0, correction_nadir_deg: [0.0], ground_sky_zenith_deg: [0.0], hemispheric: [], \
        slant_altitude_m: [1000.0], slant_nadir_deg: [0.0], sky_altitude_m: [0.0], \
        sky_zenith_deg: [0.0])";
    let any = canonical::read_any_plan("plan.ron", atmosphere.as_bytes());
    assert!(matches!(any, Ok(AnyPlan::Atmosphere(_))), "{any:?}");
    // A loads plan's error is a loads plan's, at its place.
    let bad = sample("loads-plan.ron").replace("day_of_year: 172", "day_of_year: 0");
    let e = canonical::read_any_plan("bad.ron", bad.as_bytes()).unwrap_err();
    assert!(
        e.message.contains("loads plan") && e.message.contains("day_of_year"),
        "{e}"
    );
    assert_eq!(e.line, 9, "{e}");
}

#[test]
fn the_textured_materials_sample_reads_and_a_bad_sigma_is_refused_at_its_place() {
    use irsig_model::texture::{CorrelationLength, FieldFilter, FieldSpectrum};
    let lib: MaterialLibrary = round_trip("materials-textured.ron");
    let grass = lib.materials[0].texture.as_ref().unwrap();
    assert_eq!(grass.seed, 7);
    assert!(grass.emissivity_scale.is_none());
    // No filter named: the point.
    assert_eq!(grass.filter, FieldFilter::Point);
    let asphalt = lib.materials[1].texture.as_ref().unwrap();
    assert_eq!(asphalt.filter, FieldFilter::Footprint);
    assert_eq!(
        asphalt.emissivity_scale.as_ref().unwrap().spectrum,
        FieldSpectrum::Exponential {
            correlation_length_m: CorrelationLength::PerAxis(4.0, 0.3, 0.3)
        }
    );
    // A library without texture writes none back.
    let plain: MaterialLibrary = round_trip("materials.ron");
    assert!(
        !canonical::to_ron_pretty(&plain)
            .unwrap()
            .contains("texture")
    );
    let text = sample("materials-textured.ron");
    for bad in ["-1.5", "NaN"] {
        let broken = text.replacen("sigma: 1.5", &format!("sigma: {bad}"), 1);
        let e = canonical::from_ron::<MaterialLibrary>("lib.ron", &broken).unwrap_err();
        assert!(
            e.message
                .contains("materials[0].texture.temperature_offset_k.sigma"),
            "{bad}: {e}"
        );
        let line = text.lines().position(|l| l.contains("sigma: 1.5")).unwrap() + 1;
        assert_eq!(e.line, line, "{bad}: {e}");
    }
}

#[allow(clippy::float_cmp)] // coordinates and greys written exactly, read back exactly
#[test]
fn the_mapped_materials_sample_reads_and_a_nan_mapping_is_refused_at_its_place() {
    use irsig_model::image_map::MapFilter;
    let lib: MaterialLibrary = round_trip("materials-mapped.ron");
    let maps = lib.materials[0].maps.as_ref().unwrap();
    let t = maps.temperature_offset_k.as_ref().unwrap();
    assert_eq!(
        (t.image.as_str(), t.at_black, t.per_grey),
        ("checker-8x8.png", 0.0, 10.0)
    );
    assert_eq!(t.filter, MapFilter::Nearest);
    let e = maps.emissivity_scale.as_ref().unwrap();
    assert_eq!((e.at(0.0), e.filter), (0.95, MapFilter::Bilinear));
    // A library without maps writes none back.
    let plain: MaterialLibrary = round_trip("materials.ron");
    assert!(!canonical::to_ron_pretty(&plain).unwrap().contains("maps"));
    let text = sample("materials-mapped.ron");
    let broken = text.replacen("per_grey: 10.0", "per_grey: NaN", 1);
    let e = canonical::from_ron::<MaterialLibrary>("lib.ron", &broken).unwrap_err();
    assert!(
        e.message
            .contains("materials[0].maps.temperature_offset_k.per_grey"),
        "{e}"
    );
    let line = text
        .lines()
        .position(|l| l.contains("per_grey: 10.0"))
        .unwrap()
        + 1;
    assert_eq!(e.line, line, "{e}");
}

#[test]
fn the_material_map_sample_reads_and_an_unknown_name_is_refused_at_its_place() {
    use irsig_model::material_map::MapForm;
    let lib: MaterialLibrary = round_trip("materials-material-map.ron");
    let map = lib.materials[2]
        .maps
        .as_ref()
        .unwrap()
        .material
        .as_ref()
        .unwrap();
    assert_eq!(map.image, "checker-8x8.png");
    assert!(matches!(&map.form, MapForm::Index { table: t } if t.len() == 2 && t[1].grey == 255));
    assert_eq!(map.materials(), ["asphalt", "grass"]);
    let text = sample("materials-material-map.ron");
    for (from, to, path) in [
        (
            r#"(grey: 255, material: "grass")"#,
            r#"(grey: 255, material: "gras")"#,
            "materials[2].maps.material.form.table[1].material",
        ),
        (
            r#"(grey: 255, material: "grass")"#,
            r#"(grey: 0, material: "grass")"#,
            "materials[2].maps.material.form.table[1].grey",
        ),
    ] {
        let broken = text.replacen(from, to, 1);
        let e = canonical::from_ron::<MaterialLibrary>("lib.ron", &broken).unwrap_err();
        assert!(e.message.contains(path), "{e}");
        let line = text.lines().position(|l| l.contains(from)).unwrap() + 1;
        assert_eq!(e.line, line, "{e}");
    }
}

#[allow(clippy::float_cmp)] // coordinates and greys written exactly, read back exactly
#[test]
fn the_object_sample_with_texture_coordinates_reads_and_round_trips_through_binary() {
    let object: Object = round_trip("quad-uv.ron");
    assert_eq!(
        object.facets[1].uv,
        Some([[0.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    );
    let bytes = canonical::binary_object::encode(&object).unwrap();
    // Header 32, name 5, source 16, 4 positions, 2 facets and their coordinates.
    assert_eq!(bytes.len(), 32 + 5 + 16 + 4 * 24 + 2 * 24 + 2 * 48);
    assert_eq!(
        canonical::read_object("quad-uv.bin", &bytes).unwrap(),
        object
    );
}

#[test]
fn per_material_temperatures_round_trip_in_both_forms_and_a_bad_one_is_refused_at_its_place() {
    let text = r#"(
  objects: ["lot"],
  positions_m: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)],
  facets: [(vertices: (0, 1, 2), material: 3, temperature_k: 320.0, object: 0)],
  mix_temperatures: [(facet: 0, temperatures_k: [331.25, 303.5])],
)"#;
    let raw: irsig_model::RawScene = canonical::from_ron("mix.ron", text).unwrap();
    assert_eq!(raw.mix_temperatures_of(0), Some(&[331.25, 303.5][..]));
    let again: irsig_model::RawScene =
        canonical::from_ron("mix.ron", &canonical::to_ron(&raw).unwrap()).unwrap();
    assert_eq!(again, raw);
    let bin = canonical::binary::encode(&raw).unwrap();
    assert_eq!(canonical::read_raw_scene("mix.bin", &bin).unwrap(), raw);
    // Without entries the field is not written: the RON of every earlier scene.
    let mut plain = raw.clone();
    plain.mix_temperatures.clear();
    assert!(
        !canonical::to_ron(&plain)
            .unwrap()
            .contains("mix_temperatures")
    );
    // A negative temperature, at its line and column.
    let bad = text.replace("303.5", "-3.5");
    let e = canonical::from_ron::<irsig_model::RawScene>("mix.ron", &bad).unwrap_err();
    assert_eq!(e.line, 5, "{e}");
    let column = bad.lines().nth(4).unwrap().find("-3.5").unwrap() + 1;
    assert_eq!(e.column, column, "{e}");
    assert!(
        e.message.contains("mix_temperatures[0].temperatures_k[1]"),
        "{e}"
    );
    // In the binary form, at its entry's byte offset.
    let mut bad_raw = raw.clone();
    bad_raw.mix_temperatures[0].facet = 7;
    let bin = canonical::binary::encode(&bad_raw).unwrap();
    let e = canonical::read_raw_scene("mix.bin", &bin).unwrap_err();
    assert_eq!(e.column, bin.len() - 40 + 1, "{e}");
    assert!(e.message.contains("mix_temperatures[0].facet"), "{e}");
}
