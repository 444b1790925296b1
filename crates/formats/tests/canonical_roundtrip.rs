//! Every canonical writer round-trips through its reader, bit for bit: the binary object and
//! raw scene, and the RON object, raw scene and material library, on generated values with
//! any finite coordinates (tiny, huge, subnormal, -0.0) and any Unicode names.
//!
//! Bit equality of geometry is checked by comparing binary encodings, which hold every f64
//! as its eight bytes (`PartialEq` on f64 would let -0.0 equal 0.0).

use irsig_formats::canonical::{self, binary, binary_object};
use irsig_model::{
    Facet, Material, MaterialId, MaterialLibrary, Object, RawFacet, RawScene, Terrain,
};
use proptest::prelude::*;

fn finite() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<f64>().prop_filter("finite", |x| x.is_finite()),
        -1e4..1e4f64,
        Just(0.0),
        Just(-0.0),
        Just(f64::MIN_POSITIVE / 4.0),
        Just(f64::MAX),
    ]
}

fn point() -> impl Strategy<Value = [f64; 3]> {
    [finite(), finite(), finite()]
}

fn object() -> impl Strategy<Value = Object> {
    (
        ".*",
        ".*",
        proptest::collection::vec(point(), 1..30),
        proptest::collection::vec(
            (
                [any::<u32>(), any::<u32>(), any::<u32>()],
                any::<u16>(),
                proptest::option::of(0.0..1e4f64),
            ),
            0..30,
        ),
    )
        .prop_map(|(name, source, positions_m, facets)| Object {
            name,
            source,
            positions_m,
            facets: facets
                .into_iter()
                .map(|(vertices, m, temperature_k)| Facet {
                    vertices,
                    material: MaterialId(m),
                    temperature_k,
                    uv: None,
                })
                .collect(),
        })
}

fn raw_scene() -> impl Strategy<Value = RawScene> {
    (
        (
            0.0..1e4f64,
            0.0..=1.0f64,
            proptest::option::of(1..=u16::MAX),
        ),
        proptest::collection::vec(".*", 0..4),
        proptest::collection::vec(point(), 1..30),
        proptest::collection::vec(
            (
                [any::<u32>(), any::<u32>(), any::<u32>()],
                any::<u16>(),
                any::<u32>(),
                finite(),
            ),
            0..30,
        ),
    )
        .prop_map(|((t, e, m), objects, positions_m, facets)| RawScene {
            terrain: Terrain {
                temperature_k: t,
                emissivity: e,
                material: m.map(MaterialId),
            },
            objects,
            positions_m,
            facets: facets
                .into_iter()
                .map(|(vertices, m, object, temperature_k)| RawFacet {
                    vertices,
                    material: MaterialId(m),
                    object,
                    temperature_k,
                    uv: None,
                })
                .collect(),
            mix_temperatures: Vec::new(),
        })
}

fn library() -> impl Strategy<Value = MaterialLibrary> {
    proptest::collection::vec(
        (
            proptest::collection::vec((0.0..=90.0f64, 0.0..=1.0f64), 1..12),
            0.0..=1.0f64,
            ".*",
        ),
        0..6,
    )
    .prop_map(|materials| MaterialLibrary {
        materials: materials
            .into_iter()
            .enumerate()
            .map(|(i, (mut emissivity, specular_fraction, source))| {
                emissivity.sort_by(|a, b| a.0.total_cmp(&b.0));
                emissivity.dedup_by(|a, b| a.0.total_cmp(&b.0).is_eq());
                let id = u16::try_from(i + 1).unwrap_or(u16::MAX);
                Material {
                    id: MaterialId(id),
                    name: format!("m{i}"),
                    emissivity,
                    specular_fraction,
                    source,
                    band_um: None,
                    spectral: None,
                    rms_slope: None,
                    thermal: None,
                    texture: None,
                    maps: None,
                }
            })
            .collect(),
    })
}

proptest! {
    #[test]
    fn binary_objects_round_trip(o in object()) {
        let bytes = binary_object::encode(&o).unwrap();
        let back = binary_object::decode("rt.bin", &bytes).unwrap();
        prop_assert_eq!(binary_object::encode(&back).unwrap(), bytes);
        prop_assert_eq!(back.facets, o.facets);
        prop_assert_eq!(back.name, o.name);
    }

    #[test]
    fn ron_objects_round_trip(o in object()) {
        let text = canonical::to_ron(&o).unwrap();
        let back: Object = canonical::from_ron_unchecked("rt.ron", &text).unwrap();
        prop_assert_eq!(
            binary_object::encode(&back).unwrap(),
            binary_object::encode(&o).unwrap(),
            "{}", text
        );
    }

    #[test]
    fn binary_raw_scenes_round_trip(s in raw_scene()) {
        let bytes = binary::encode(&s).unwrap();
        let back = binary::decode("rt.raw", &bytes).unwrap();
        prop_assert_eq!(binary::encode(&back).unwrap(), bytes);
    }

    #[test]
    fn ron_raw_scenes_round_trip(s in raw_scene()) {
        let text = canonical::to_ron(&s).unwrap();
        let back: RawScene = canonical::from_ron_unchecked("rt.ron", &text).unwrap();
        prop_assert_eq!(binary::encode(&back).unwrap(), binary::encode(&s).unwrap(), "{}", text);
    }

    #[test]
    fn ron_material_libraries_round_trip(lib in library()) {
        lib.validate().unwrap();
        let text = canonical::to_ron(&lib).unwrap();
        // The checked reader: a library the model accepts stays acceptable after writing.
        let back: MaterialLibrary = canonical::from_ron("rt.ron", &text).unwrap();
        prop_assert_eq!(&back, &lib);
        for (a, b) in back.materials.iter().zip(&lib.materials) {
            for (x, y) in a.emissivity.iter().zip(&b.emissivity) {
                prop_assert_eq!(x.0.to_bits(), y.0.to_bits());
                prop_assert_eq!(x.1.to_bits(), y.1.to_bits());
            }
        }
    }
}
