use std::collections::HashMap;

use irsig_model::{Facet, FacetOverride, FacetSelection, MaterialId, Object, Placement, Scene};

use super::*;

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
}

fn placed(rotation_deg: [f64; 3], translation_m: [f64; 3], scale: [f64; 3]) -> Transform {
    Transform::of(&Placement {
        object: "o.ron".into(),
        rotation_deg,
        translation_m,
        scale,
        temperature_k: None,
        overrides: vec![],
    })
}

#[test]
fn quarter_turns_about_each_axis_by_hand() {
    // Right-handed, counter-clockwise looking down the axis towards the origin.
    let rx = placed([90.0, 0.0, 0.0], [0.0; 3], [1.0; 3]);
    assert!(close(rx.apply([0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]));
    assert!(close(rx.apply([0.0, 0.0, 1.0]), [0.0, -1.0, 0.0]));
    let ry = placed([0.0, 90.0, 0.0], [0.0; 3], [1.0; 3]);
    assert!(close(ry.apply([0.0, 0.0, 1.0]), [1.0, 0.0, 0.0]));
    assert!(close(ry.apply([1.0, 0.0, 0.0]), [0.0, 0.0, -1.0]));
    let rz = placed([0.0, 0.0, 90.0], [0.0; 3], [1.0; 3]);
    assert!(close(rz.apply([1.0, 0.0, 0.0]), [0.0, 1.0, 0.0]));
    assert!(close(rz.apply([0.0, 1.0, 0.0]), [-1.0, 0.0, 0.0]));
}

#[test]
fn scale_then_x_then_y_then_z_then_translation_by_hand() {
    // p = (1, 1, 0), S = (2, 1, 1): (2, 1, 0). Rx 90°: (x, y, z) -> (x, -z, y) = (2, 0, 1).
    // Ry 90°: (x, y, z) -> (z, y, -x) = (1, 0, -2). Rz 90°: (x, y, z) -> (-y, x, z)
    // = (0, 1, -2). T = (10, 20, 30): (10, 21, 28).
    let t = placed([90.0, 90.0, 90.0], [10.0, 20.0, 30.0], [2.0, 1.0, 1.0]);
    assert!(
        close(t.apply([1.0, 1.0, 0.0]), [10.0, 21.0, 28.0]),
        "{:?}",
        t.apply([1.0, 1.0, 0.0])
    );
    // The other order (z first) would give a different point: the order matters.
    let zyx = mul(
        &rotation_matrix([90.0, 0.0, 0.0]),
        &mul(
            &rotation_matrix([0.0, 90.0, 0.0]),
            &rotation_matrix([0.0, 0.0, 90.0]),
        ),
    );
    let q = [2.0, 1.0, 0.0];
    let other: Vec<f64> = zyx
        .iter()
        .map(|r| r[0] * q[0] + r[1] * q[1] + r[2] * q[2])
        .collect();
    assert!(!close(
        [other[0] + 10.0, other[1] + 20.0, other[2] + 30.0],
        [10.0, 21.0, 28.0]
    ));
}

fn triangle(temperature_k: Option<f64>) -> Object {
    Object {
        name: "tri".into(),
        source: String::new(),
        positions_m: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        facets: vec![Facet {
            vertices: [0, 1, 2],
            material: MaterialId(1),
            temperature_k,
            uv: None,
        }],
    }
}

fn scene(placement: Placement) -> Scene {
    Scene {
        objects: vec![placement],
        ..Scene::default()
    }
}

fn placement() -> Placement {
    Placement {
        object: "o.ron".into(),
        rotation_deg: [0.0; 3],
        translation_m: [0.0; 3],
        scale: [1.0; 3],
        temperature_k: Some(300.0),
        overrides: vec![],
    }
}

fn normal_z(raw: &RawScene, f: usize) -> f64 {
    let [a, b, c] = raw.facets[f].vertices.map(|v| raw.positions_m[v as usize]);
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

#[test]
fn a_mirror_flips_the_winding_so_the_front_stays_up() {
    let o = triangle(None);
    let plain = flatten(&scene(placement()), &[&o]).unwrap();
    assert!(normal_z(&plain, 0) > 0.0);
    let mut p = placement();
    p.scale = [-1.0, 1.0, 1.0];
    let mirrored = flatten(&scene(p), &[&o]).unwrap();
    // Mirrored in x the triangle still lies in z = 0 facing +z: its front must stay up.
    assert!(normal_z(&mirrored, 0) > 0.0);
    // Two negative factors are a rotation, not a mirror: (x, y) -> (-x, -y), front up.
    let mut p = placement();
    p.scale = [-1.0, -1.0, 1.0];
    assert!(normal_z(&flatten(&scene(p), &[&o]).unwrap(), 0) > 0.0);
}

#[test]
fn texture_coordinates_stay_with_their_corners_through_a_mirror() {
    let mut o = triangle(None);
    // Corner k of the object's triangle (0,0), (1,0), (0,1) has u = x, v = y.
    o.facets[0].uv = Some([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
    let mut p = placement();
    p.scale = [-1.0, 1.0, 1.0];
    for placement in [placement(), p] {
        let sign = placement.scale[0];
        let raw = flatten(&scene(placement), &[&o]).unwrap();
        let f = &raw.facets[0];
        let uv = f.uv.unwrap();
        for (k, &v) in f.vertices.iter().enumerate() {
            // Whatever the order, each corner keeps the coordinates of the object's vertex
            // it came from: (x, y) before placement, recovered from the world position.
            let base = raw.positions_m[0];
            let w = raw.positions_m[v as usize];
            let [x, y] = [(w[0] - base[0]) * sign, w[1] - base[1]];
            assert!((uv[k][0] - x).abs() < 1e-12 && (uv[k][1] - y).abs() < 1e-12);
        }
    }
}

#[test]
fn temperatures_come_from_the_facet_then_the_placement_then_overrides() {
    let mut o = triangle(Some(280.0));
    o.positions_m.push([1.0, 1.0, 0.0]);
    o.facets.push(Facet {
        vertices: [1, 3, 2],
        material: MaterialId(2),
        temperature_k: None,
        uv: None,
    });
    o.facets.push(Facet {
        vertices: [0, 1, 3],
        material: MaterialId(2),
        temperature_k: None,
        uv: None,
    });
    let mut p = placement();
    p.overrides = vec![
        FacetOverride {
            select: FacetSelection::Material(MaterialId(2)),
            material: Some(MaterialId(3)),
            temperature_k: None,
        },
        FacetOverride {
            select: FacetSelection::Range { first: 2, last: 2 },
            material: None,
            temperature_k: Some(350.0),
        },
        // Matches nothing: facet materials are 1 and 3 by now.
        FacetOverride {
            select: FacetSelection::Material(MaterialId(2)),
            material: Some(MaterialId(9)),
            temperature_k: Some(1.0),
        },
    ];
    let raw = flatten(&scene(p), &[&o]).unwrap();
    let got: Vec<(u16, f64)> = raw
        .facets
        .iter()
        .map(|f| (f.material.0, f.temperature_k))
        .collect();
    assert_eq!(got, [(1, 280.0), (3, 300.0), (3, 350.0)]);
}

#[test]
fn a_facet_without_temperature_is_an_error_naming_it() {
    let o = triangle(None);
    let mut p = placement();
    p.temperature_k = None;
    let e = flatten(&scene(p.clone()), &[&o]).unwrap_err();
    assert_eq!(e.kind, FlattenErrorKind::NoTemperature { facet: 0 });
    assert!(
        e.to_string().contains("`tri`") && e.to_string().contains("facet 0"),
        "{e}"
    );
    p.overrides.push(FacetOverride {
        select: FacetSelection::All,
        material: None,
        temperature_k: Some(250.0),
    });
    assert!(flatten(&scene(p), &[&o]).is_ok());
}

#[test]
fn an_override_past_the_facets_is_an_error() {
    let mut p = placement();
    p.overrides.push(FacetOverride {
        select: FacetSelection::Range { first: 0, last: 1 },
        material: Some(MaterialId(2)),
        temperature_k: None,
    });
    let e = flatten(&scene(p), &[&triangle(None)]).unwrap_err();
    assert!(matches!(
        e.kind,
        FlattenErrorKind::RangeOutOfBounds {
            last: 1,
            facets: 1,
            ..
        }
    ));
}

#[test]
fn huge_scales_that_overflow_are_errors() {
    let mut p = placement();
    p.scale = [1e308, 1.0, 1.0];
    p.translation_m = [1e308, 0.0, 0.0];
    let e = flatten(&scene(p), &[&triangle(None)]).unwrap_err();
    assert!(
        matches!(e.kind, FlattenErrorKind::NotFinite { vertex: 1 }),
        "{e}"
    );
}

#[test]
fn tiny_and_huge_but_finite_coordinates_survive() {
    let mut p = placement();
    p.scale = [1e-6; 3];
    p.translation_m = [1e6, -1e6, 1e4];
    let raw = flatten(&scene(p), &[&triangle(None)]).unwrap();
    assert!(close(raw.positions_m[1], [1e6 + 1e-6, -1e6, 1e4]));
}

#[test]
fn objects_and_placements_must_pair_up() {
    let e = flatten(&scene(placement()), &[]).unwrap_err();
    assert!(matches!(
        e.kind,
        FlattenErrorKind::ObjectCount {
            placements: 1,
            objects: 0
        }
    ));
}

/// Every directed edge appears once and its reverse once: closed, consistently wound.
fn assert_closed(o: &Object) {
    let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
    for f in &o.facets {
        let v = f.vertices;
        for k in 0..3 {
            *edges.entry((v[k], v[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &edges {
        assert_eq!(n, 1, "edge {a}->{b} used {n} times");
        assert_eq!(edges.get(&(b, a)), Some(&1), "edge {a}->{b} has no twin");
    }
}

fn volume(o: &Object) -> f64 {
    o.facets
        .iter()
        .map(|f| {
            let [a, b, c] = f.vertices.map(|v| o.positions_m[v as usize]);
            (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0
        })
        .sum()
}

#[test]
fn spheres_are_closed_outward_and_converge_to_the_ball() {
    for (lon, lat) in [(3, 2), (8, 5), (64, 32)] {
        let s = uv_sphere(2.0, lon, lat, MaterialId(1));
        assert_eq!(s.facets.len(), (2 * lon * (lat - 1)) as usize);
        assert_closed(&s);
        s.validate().unwrap();
        assert!(volume(&s) > 0.0);
    }
    // A fine sphere's volume approaches 4/3 π r³ from below.
    let v = volume(&uv_sphere(2.0, 256, 128, MaterialId(1)));
    let ball = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
    assert!(v < ball && v > 0.999 * ball, "{v} vs {ball}");
}

#[test]
fn terrain_is_closed_and_holds_the_volume_under_it() {
    // A plane z = 1 + 0.5x over 4 m × 2 m with base 0: volume = ∫∫ (1 + 0.5x) = 2·(4 + 4) = 16.
    let t = terrain([4.0, 2.0], [8, 3], 0.0, |x, _| 1.0 + 0.5 * x, MaterialId(1));
    assert_eq!(t.facets.len(), 2 * 8 * 3 + 6 * (8 + 3));
    assert_closed(&t);
    t.validate().unwrap();
    assert!((volume(&t) - 16.0).abs() < 1e-9, "{}", volume(&t));
}

#[test]
#[allow(clippy::float_cmp)] // exactness is what is tested
fn quarter_turns_are_exact() {
    let r = rotation_matrix([90.0, -180.0, 270.0]);
    for row in r {
        for v in row {
            assert!(v == 0.0 || v == 1.0 || v == -1.0, "{r:?}");
        }
    }
    // And the general case agrees with the exact one to rounding.
    let a = rotation_matrix([90.0 + 1e-9, 0.0, 0.0]);
    assert!((a[2][1] - 1.0).abs() < 1e-12);
}
