//! Every legacy writer's output reads back, through its parser, to the same values
//! (bit for bit: the writers print reals in their shortest exact form).

use irsig_formats::legacy::{Position, object, scene};
use proptest::prelude::*;

/// Any finite f64, including subnormals, zeros of both signs and the extremes.
fn finite() -> impl Strategy<Value = f64> {
    use proptest::num::f64::{NEGATIVE, NORMAL, POSITIVE, SUBNORMAL, ZERO};
    POSITIVE | NEGATIVE | NORMAL | SUBNORMAL | ZERO
}

fn triple() -> impl Strategy<Value = [f64; 3]> {
    [finite(), finite(), finite()]
}

fn nonzero() -> impl Strategy<Value = f64> {
    finite().prop_filter("non-zero", |v| *v != 0.0)
}

fn temperature() -> impl Strategy<Value = Option<f64>> {
    proptest::option::of(proptest::num::f64::POSITIVE | proptest::num::f64::NORMAL)
        .prop_map(|t| t.map(f64::abs).filter(|t| *t > 0.0))
}

fn name() -> impl Strategy<Value = String> {
    "[A-Za-z_][A-Za-z0-9_./:-]{0,30}"
}

fn facet() -> impl Strategy<Value = object::LegacyFacet> {
    (1u16.., temperature(), [triple(), triple(), triple()]).prop_map(
        |(material_index, temperature_k, vertices)| object::LegacyFacet {
            material_index,
            temperature_k,
            vertices,
            position: Position::default(),
        },
    )
}

fn entry() -> impl Strategy<Value = scene::SceneEntry> {
    (
        name(),
        [finite(), finite(), finite()],
        [finite(), finite(), finite()],
        [nonzero(), nonzero(), nonzero()],
        temperature(),
    )
        .prop_map(
            |(object, rotation_deg, translation, scale, temperature_k)| scene::SceneEntry {
                object,
                rotation_deg,
                translation,
                scale,
                temperature_k,
                position: Position::default(),
            },
        )
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

proptest! {
    #[test]
    fn object_files_round_trip(facets in proptest::collection::vec(facet(), 1..20)) {
        let file = object::ObjectFile { facets, count_position: Position::default() };
        let text = object::write(&file).unwrap();
        let back = object::parse("rt.fac", &text).unwrap();
        prop_assert_eq!(back.facets.len(), file.facets.len());
        for (a, b) in file.facets.iter().zip(&back.facets) {
            prop_assert_eq!(a.material_index, b.material_index);
            prop_assert_eq!(a.temperature_k.map(f64::to_bits), b.temperature_k.map(f64::to_bits));
            prop_assert_eq!(bits(a.vertices.as_flattened()), bits(b.vertices.as_flattened()));
        }
    }

    #[test]
    fn scene_files_round_trip(entries in proptest::collection::vec(entry(), 1..10)) {
        let file = scene::SceneFile { entries };
        let text = scene::write(&file).unwrap();
        let back = scene::parse("rt.scn", &text).unwrap();
        prop_assert_eq!(back.entries.len(), file.entries.len());
        for (a, b) in file.entries.iter().zip(&back.entries) {
            prop_assert_eq!(&a.object, &b.object);
            prop_assert_eq!(bits(&a.rotation_deg), bits(&b.rotation_deg));
            prop_assert_eq!(bits(&a.translation), bits(&b.translation));
            prop_assert_eq!(bits(&a.scale), bits(&b.scale));
            prop_assert_eq!(a.temperature_k.map(f64::to_bits), b.temperature_k.map(f64::to_bits));
        }
    }
}
