//! Every legacy writer's output reads back, through its parser, to the same values
//! (bit for bit: the writers print reals in their shortest exact form).

use irsig_formats::legacy::{Position, atm, cor, dwr, ems, object, rsd, rtt, scene};
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
            fourth_vertex: None,
            position: Position::default(),
        },
    )
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// A planar, convex 4-vertex facet: from a corner `p`, along edge directions `u` and `v`
/// (at least 30° apart), the corners (0, 0), (a, 0), (b, c), (0, d) of the `u`, `v`
/// frame, in either winding. The first, second and fourth corners are convex for any
/// positive a, b, c, d; the third is when it lies beyond the diagonal from (a, 0) to
/// (0, d), that is when b / a + c / d > 1 (asked with a margin).
fn quad() -> impl Strategy<Value = object::LegacyFacet> {
    let coord = || -1e3..1e3f64;
    let edge = || -10.0..10.0f64;
    let k = || 0.5..2.0f64;
    (
        (1u16.., temperature()),
        [coord(), coord(), coord()],
        [edge(), edge(), edge()],
        [edge(), edge(), edge()],
        [k(), k(), k(), k()],
        any::<bool>(),
    )
        .prop_filter(
            "edges long and apart, third corner convex",
            |(_, _, u, v, [a, b, c, d], _)| {
                norm(*u) > 0.1
                    && norm(*v) > 0.1
                    && norm(cross(*u, *v)) > 0.5 * norm(*u) * norm(*v)
                    && b / a + c / d > 1.2
            },
        )
        .prop_map(
            |((material_index, temperature_k), p, u, v, [a, b, c, d], reverse)| {
                let at = |s: f64, t: f64| [0, 1, 2].map(|i| p[i] + s * u[i] + t * v[i]);
                let mut corners = [at(0.0, 0.0), at(a, 0.0), at(b, c), at(0.0, d)];
                if reverse {
                    corners.reverse();
                }
                let [v1, v2, v3, v4] = corners;
                object::LegacyFacet {
                    material_index,
                    temperature_k,
                    vertices: [v1, v2, v3],
                    fourth_vertex: Some(v4),
                    position: Position::default(),
                }
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
    fn object_files_with_quads_round_trip(
        facets in proptest::collection::vec(prop_oneof![facet(), quad()], 1..20),
    ) {
        let file = object::ObjectFile { facets, count_position: Position::default() };
        let text = object::write(&file).unwrap();
        let back = object::parse("rt.fac", &text).unwrap();
        prop_assert_eq!(back.facets.len(), file.facets.len());
        for (a, b) in file.facets.iter().zip(&back.facets) {
            prop_assert_eq!(bits(a.vertices.as_flattened()), bits(b.vertices.as_flattened()));
            prop_assert_eq!(
                a.fourth_vertex.map(|v| bits(&v)),
                b.fourth_vertex.map(|v| bits(&v))
            );
        }
    }

    /// Both halves of a 4-vertex facet face the way the facet does (the 1990 normal
    /// (v2 − v1) × (v3 − v1)), and their areas add up to the facet's, half the length of
    /// the cross product of its diagonals.
    #[test]
    fn quads_split_into_two_halves_of_their_normal_and_area(f in quad()) {
        prop_assert!(f.check_quad().is_ok(), "{:?}", f.check_quad());
        let corners: Vec<[f64; 3]> = f.corners().collect();
        let [v1, v2, v3] = f.vertices;
        let v4 = corners[3];
        let facet_normal = cross(sub(v2, v1), sub(v3, v1));
        let area = norm(cross(sub(v3, v1), sub(v4, v2))) / 2.0;
        let mut halves = 0.0;
        prop_assert_eq!(f.triangles().len(), 2);
        for t in f.triangles() {
            let [a, b, c] = t.map(|k| corners[k]);
            let n = cross(sub(b, a), sub(c, a));
            // Same direction: the angle between them is below 1e-6 rad.
            prop_assert!(dot(n, facet_normal) > 0.0);
            prop_assert!(norm(cross(n, facet_normal)) < 1e-6 * norm(n) * norm(facet_normal));
            halves += norm(n) / 2.0;
        }
        prop_assert!((halves - area).abs() < 1e-9 * area, "{} vs {}", halves, area);
        // The cut is along the shorter diagonal.
        let shared: Vec<usize> = f.triangles()[0]
            .iter()
            .copied()
            .filter(|k| f.triangles()[1].contains(k))
            .collect();
        let cut = norm(sub(corners[shared[1]], corners[shared[0]]));
        let other = if shared == [0, 2] { norm(sub(v4, v2)) } else { norm(sub(v3, v1)) };
        prop_assert!(cut <= other);
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

/// Strictly increasing values in `lo..=hi`, at least one.
fn increasing(lo: f64, hi: f64, max: usize) -> impl Strategy<Value = Vec<f64>> {
    proptest::collection::vec(lo..=hi, 1..max).prop_map(|mut v| {
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    })
}

fn with_column<S: Strategy<Value = f64> + Clone>(
    keys: Vec<f64>,
    values: S,
) -> impl Strategy<Value = Vec<(f64, f64)>> {
    let n = keys.len();
    proptest::collection::vec(values, n).prop_map(move |v| keys.iter().copied().zip(v).collect())
}

proptest! {
    #[test]
    fn ems_tables_round_trip(pairs in increasing(0.0, 90.0, 25).prop_flat_map(|k| with_column(k, 0.0..=1.0f64))) {
        let t = ems::EmsTable::from_pairs(&pairs);
        let back = ems::parse("rt.ems", &ems::write(&t).unwrap()).unwrap();
        prop_assert_eq!(back.to_pairs(), pairs);
    }

    #[test]
    fn dwr_tables_round_trip(
        pairs in increasing(0.0, 90.0, 25).prop_flat_map(|k| with_column(k, 0.0..1.0f64)),
        hemi in proptest::option::of(0.0..1.0f64),
    ) {
        let t = dwr::DwrTable {
            rows: pairs.iter().map(|&(zenith_deg, radiance_w_cm2_sr)| dwr::DwrRow {
                zenith_deg, radiance_w_cm2_sr, position: Position::default() }).collect(),
            hemispheric_w_cm2_sr: hemi,
            hemispheric_position: None,
        };
        let back = dwr::parse("rt.dwr", &dwr::write(&t).unwrap()).unwrap();
        prop_assert_eq!(back.to_pairs(), pairs);
        prop_assert_eq!(back.hemispheric_w_cm2_sr, hemi);
    }

    #[test]
    fn rtt_tables_round_trip(temps in increasing(1.0, 5000.0, 50)) {
        // Any non-decreasing radiance will do; T^4 is one.
        let t = rtt::RttTable { rows: temps.iter().map(|&temperature_k| rtt::RttRow {
            temperature_k, radiance_w_cm2_sr: temperature_k.powi(4) * 1e-12, position: Position::default() }).collect() };
        let back = rtt::parse("rt.rtt", &rtt::write(&t).unwrap()).unwrap();
        prop_assert_eq!(back.to_pairs(), t.to_pairs());
    }

    #[test]
    fn atm_tables_round_trip(
        rows in increasing(0.0, 100.0, 30).prop_flat_map(|h| {
            let n = h.len();
            (Just(h), proptest::collection::vec((1.0..400.0f64, 0.0..=1.0f64, 0.0..1.0f64), n), -1.0..1.0f64)
        })
    ) {
        let (heights, cols, ground_asl_km) = rows;
        let t = atm::AtmTable { rows: heights.iter().zip(&cols).map(|(&h, &(temperature_k, transmission, lu))| atm::AtmRow {
            altitude_asl_km: h + ground_asl_km, temperature_k, altitude_km: h, transmission,
            upwelled_radiance_w_cm2_sr: lu, position: Position::default() }).collect() };
        let back = atm::parse("rt.atm", &atm::write(&t).unwrap()).unwrap();
        // Rows compare equal except for positions, which the writer does not carry.
        let strip = |t: &atm::AtmTable| t.rows.iter().map(|r| atm::AtmRow { position: Position::default(), ..*r }).collect::<Vec<_>>();
        prop_assert_eq!(strip(&back), strip(&t));
    }

    #[test]
    fn rsd_tables_round_trip(
        rows in increasing(-0.5, 30.0, 30).prop_flat_map(|h| {
            let n = h.len();
            (Just(h), proptest::collection::vec((0.1..1100.0f64, -100.0..60.0f64, 0.0..40.0f64), n))
        })
    ) {
        let (heights, cols) = rows;
        let t = rsd::RsdTable { rows: heights.iter().zip(&cols).map(|(&altitude_km, &(pressure_mb, temperature_c, dew_point_depression_c))| rsd::RsdRow {
            altitude_km, pressure_mb, temperature_c, dew_point_depression_c, position: Position::default() }).collect() };
        let back = rsd::parse("rt.rsd", &rsd::write(&t).unwrap()).unwrap();
        let strip = |t: &rsd::RsdTable| t.rows.iter().map(|r| rsd::RsdRow { position: Position::default(), ..*r }).collect::<Vec<_>>();
        prop_assert_eq!(strip(&back), strip(&t));
    }

    #[test]
    fn cor_files_round_trip(coefficients in [finite(), finite(), finite()]) {
        let c = cor::CorFile { coefficients, position: Position::default() };
        let back = cor::parse("rt.cor", &cor::write(&c).unwrap()).unwrap();
        prop_assert_eq!(bits(&back.coefficients), bits(&coefficients));
    }
}
