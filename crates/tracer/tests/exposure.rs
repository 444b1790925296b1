//! What a facet sees, for the heat balance (`irsig_tracer::exposure`): view factors against
//! their closed forms, and shadows against hand geometry.

use irsig_tracer::DVec3;
use irsig_tracer::exposure::{Exposure, ExposureOptions};
use irsig_tracer::testing::{box_mesh, ground_quad, raw_scene};

const ONE: ExposureOptions = ExposureOptions {
    samples_per_side: 1,
};

/// Three standard errors of a share `f` estimated from `n` rays, plus a little for the
/// sample points' quadrature.
fn tolerance(f: f64, n: u32) -> f64 {
    3.0 * (f * (1.0 - f) / f64::from(n)).sqrt() + 2e-3
}

#[test]
fn an_open_horizontal_facet_sees_only_sky_and_a_vertical_one_half_terrain() {
    let ground = ground_quad([-1.0, -1.0], [1.0, 1.0], 0.0);
    let exposure = Exposure::new(&raw_scene(&[(&ground, 1, 300.0)])).unwrap();
    let v = exposure.view(0, 4096, 7, ONE);
    assert!((v.sky - 1.0).abs() < 1e-12, "{v:?}");
    assert!(v.terrain.to_bits() == 0 && v.facets.is_empty());

    // A wall facing +x: the view factor of a vertical plane to the sky is (1 + cos 90°)/2.
    let wall = (
        vec![
            [0.0, -1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 1.0, 2.0],
            [0.0, -1.0, 2.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let exposure = Exposure::new(&raw_scene(&[(&wall, 1, 300.0)])).unwrap();
    assert!(exposure.frame(0).normal.x > 0.999);
    let n = 8192;
    let v = exposure.view(0, n, 7, ONE);
    assert!((v.sky - 0.5).abs() < tolerance(0.5, n), "{v:?}");
    assert!((v.sky + v.terrain - 1.0).abs() < 1e-12);
}

/// Incropera & DeWitt, Table 13.2: two aligned parallel rectangles `x × y` a distance `l`
/// apart. With X = x/l, Y = y/l.
fn parallel_rectangles(x: f64, y: f64, l: f64) -> f64 {
    let (xb, yb) = (x / l, y / l);
    let (x2, y2) = (1.0 + xb * xb, 1.0 + yb * yb);
    // ln[(1 + X²)(1 + Y²)/(1 + X² + Y²)]^½
    let s = 0.5 * (x2 * y2 / (1.0 + xb * xb + yb * yb)).ln();
    2.0 / (std::f64::consts::PI * xb * yb)
        * (s + xb * y2.sqrt() * (xb / y2.sqrt()).atan() + yb * x2.sqrt() * (yb / x2.sqrt()).atan()
            - xb * xb.atan()
            - yb * yb.atan())
}

#[test]
fn two_parallel_squares_see_each_other_by_their_closed_form() {
    // Hand value first: the table's X = Y = 1 gives 0.1998.
    assert!((parallel_rectangles(1.0, 1.0, 1.0) - 0.1998).abs() < 5e-4);
    let lower = ground_quad([0.0, 0.0], [1.0, 1.0], 0.0);
    // The upper square faces down: wound the other way.
    let upper = (
        vec![
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ],
        vec![[0, 2, 1], [0, 3, 2]],
    );
    let exposure = Exposure::new(&raw_scene(&[(&lower, 1, 300.0), (&upper, 1, 300.0)])).unwrap();
    let n = 16384;
    let options = ExposureOptions {
        samples_per_side: 16,
    };
    // The lower square's two triangles, each of half its area: their mean is the square's.
    let f: f64 = (0..2)
        .map(|i| {
            let v = exposure.view(i, n, 11, options);
            v.facets
                .iter()
                .filter(|(j, _)| *j >= 2)
                .map(|(_, s)| s)
                .sum::<f64>()
        })
        .sum::<f64>()
        / 2.0;
    let expect = parallel_rectangles(1.0, 1.0, 1.0);
    assert!(
        (f - expect).abs() < tolerance(expect, 2 * n),
        "{f} against {expect}"
    );
    // Facets of one plane never see each other.
    let v = exposure.view(0, 1024, 3, options);
    assert!(v.facets.iter().all(|(j, _)| *j >= 2));
}

#[test]
fn the_sun_is_hidden_under_a_box_and_where_hand_geometry_puts_its_shadow() {
    // A 1 m cube standing on nothing, its base 1 m above the ground; the sun 45° from the
    // zenith in the south (azimuth 180°): the direction to it is (0, −sin 45°, cos 45°).
    // The cube's shadow on the ground is its footprint moved north by the 1–2 m height
    // times tan 45°: it covers y from 1 to 3 (x from 0 to 1), from the base corner to the
    // top corner.
    let cube = box_mesh([0.0, 0.0, 1.0], [1.0, 1.0, 2.0]);
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let to_sun = [0.0, -s, s];
    // Small ground triangles: one inside the hand shadow, one outside it to the south, one
    // beyond its tip.
    let tile = |x: f64, y: f64| ground_quad([x, y], [x + 0.1, y + 0.1], 0.0);
    let inside = tile(0.45, 1.95);
    let south = tile(0.45, 0.4);
    let beyond = tile(0.45, 3.1);
    let scene = raw_scene(&[
        (&cube, 1, 300.0),
        (&inside, 2, 300.0),
        (&south, 2, 300.0),
        (&beyond, 2, 300.0),
    ]);
    let exposure = Exposure::new(&scene).unwrap();
    let four = ExposureOptions {
        samples_per_side: 4,
    };
    let fraction = |facet: usize| exposure.sunlit_fraction(facet, DVec3::from(to_sun), four);
    // Facets 12–13 inside, 14–15 south, 16–17 beyond (the cube's 12 first).
    assert_eq!(fraction(12).to_bits(), 0.0_f64.to_bits());
    assert_eq!(fraction(13).to_bits(), 0.0_f64.to_bits());
    assert_eq!(fraction(14).to_bits(), 1.0_f64.to_bits());
    assert_eq!(fraction(17).to_bits(), 1.0_f64.to_bits());
    // The cube's top (facets 2–3) and south face (4–5) are lit, its north face (6–7,
    // facing +y, away from the sun) is not.
    for (facet, lit) in [
        (2, 1.0_f64),
        (3, 1.0),
        (4, 1.0),
        (5, 1.0),
        (6, 0.0),
        (7, 0.0),
    ] {
        assert_eq!(
            fraction(facet).to_bits(),
            lit.to_bits(),
            "cube facet {facet}"
        );
    }
    // The sun below the horizon lights nothing.
    assert_eq!(
        exposure
            .sunlit_fraction(14, DVec3::new(0.0, -1.0, -0.01), four)
            .to_bits(),
        0.0_f64.to_bits()
    );
}

#[test]
fn a_shadow_edge_through_a_facet_hides_the_share_of_its_sample_points_it_covers() {
    // A wall along x = 0 from y = 0 to 10, 1 m high; sun due west at 45° elevation: the
    // shadow falls east, 1 m wide. A 2 m ground square from x = 0 to 2 is half shadowed.
    let wall = (
        vec![
            [0.0, -5.0, 0.0],
            [0.0, 15.0, 0.0],
            [0.0, 15.0, 1.0],
            [0.0, -5.0, 1.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    );
    let ground = ground_quad([0.0, 4.0], [2.0, 6.0], 0.0);
    let exposure = Exposure::new(&raw_scene(&[(&wall, 1, 300.0), (&ground, 2, 300.0)])).unwrap();
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let k = 32;
    let options = ExposureOptions {
        samples_per_side: k,
    };
    let lit: f64 = (2..4)
        .map(|i| exposure.sunlit_fraction(i, DVec3::new(-s, 0.0, s), options))
        .sum::<f64>()
        / 2.0;
    // Sample points are the centroids of k² equal sub-triangles: the lit share is within
    // one strip of sub-triangles (about 2/k of the area) of the exact half.
    assert!((lit - 0.5).abs() < 2.0 / f64::from(k), "{lit}");
}

#[test]
fn views_are_the_same_at_any_thread_count() {
    let cube = box_mesh([0.0, 0.0, 0.5], [1.0, 1.0, 1.5]);
    let ground = ground_quad([-3.0, -3.0], [4.0, 4.0], 0.0);
    let scene = raw_scene(&[(&cube, 1, 300.0), (&ground, 2, 300.0)]);
    let exposure = Exposure::new(&scene).unwrap();
    let options = ExposureOptions {
        samples_per_side: 2,
    };
    let all: Vec<u32> = (0..exposure.facets() as u32).collect();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| exposure.views(&all, 256, 5, options).unwrap());
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
        .install(|| exposure.views(&all, 256, 5, options).unwrap());
    assert_eq!(one, two);
    // Every facet's shares sum to 1.
    for i in 0..exposure.facets() {
        let (_, shares) = one.seen_by(i);
        let total = one.sky[i] + one.terrain[i] + shares.iter().sum::<f32>();
        assert!((total - 1.0).abs() < 1e-4, "facet {i}: {total}");
    }
    // The cube's bottom, 0.5 m above a ground that reaches 3 m beyond it, faces down: it
    // sees no sky, and the ground but for rays beyond about 80° from the vertical
    // (cos² 80° = 3 % of a cosine-weighted hemisphere) that pass the ground's edge.
    for i in 0..2 {
        let (seen, shares) = one.seen_by(i);
        assert_eq!(one.sky[i].to_bits(), 0);
        let ground: f32 = seen
            .iter()
            .zip(shares)
            .filter(|(j, _)| **j >= 12)
            .map(|(_, s)| s)
            .sum();
        assert!(ground > 0.9 && ground < 1.0, "facet {i}: {ground}");
    }
}
