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
