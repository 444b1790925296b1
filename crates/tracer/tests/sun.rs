//! The sun's direct beam against hand computation, in a vacuum (τ = 1, no path
//! radiance, cold sky) so that the sun's part of a pixel is the pixel with the sun minus
//! the pixel without: a Lambertian plate gives `r·E_n·cos θ_i/π`, a plate in a shadow, a
//! plate with the sun behind it and the inside of a closed box give nothing, a mirror
//! gives `r·E_n/Ω_sun` exactly where hand geometry puts the sun's reflection and nothing
//! 1° off, a shadow's edge gives the disk's visible fraction, and no sun changes nothing.

use irsig_model::{MaterialLibrary, RawScene, View};
use irsig_radiometry::TotalRadiance;
use irsig_tracer::testing::{Mesh, box_mesh, grey_materials, ground_quad, raw_scene};
use irsig_tracer::{
    Camera, DVec3, Frame, SUN_ANGULAR_RADIUS_DEG, Sun, SunBeam, TraceOptions, Tracer, Vacuum,
};

/// Direct normal irradiance of the test sun, W m⁻².
const E_N: f64 = 800.0;
/// The sun's zenith angle, degrees; it stands in the +x half of the sky (azimuth east).
const ZENITH_DEG: f64 = 30.0;
const T_K: f64 = 300.0;

fn to_sun() -> [f64; 3] {
    let z = ZENITH_DEG.to_radians();
    [z.sin(), 0.0, z.cos()]
}

fn sun(shadow_rays: u32) -> Sun {
    Sun {
        shadow_rays,
        ..Sun::new(DVec3::from(to_sun()), vec![SunBeam::uniform(E_N).unwrap()])
    }
}

fn tracer(scene: &RawScene, materials: &MaterialLibrary) -> Tracer<TotalRadiance, Vacuum> {
    Tracer::new(scene, materials, TotalRadiance, Vacuum::default()).unwrap()
}

/// A plate from `lo` to `hi` (x, y) at height `z`, facing up.
fn plate(lo: [f64; 2], hi: [f64; 2], z: f64) -> Mesh {
    ground_quad(lo, hi, z)
}

/// A vertical plate in the plane x = `x`, from `y0` to `y1` and `z0` to `z1`.
fn wall(x: f64, [y0, y1]: [f64; 2], [z0, z1]: [f64; 2]) -> Mesh {
    (
        vec![[x, y0, z0], [x, y1, z0], [x, y1, z1], [x, y0, z1]],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

fn look_at(position_m: [f64; 3], target_m: [f64; 3], pixels: [u32; 2], fov_deg: f64) -> Camera {
    Camera::from_view(&View::LookAt {
        position_m,
        target_m,
        up: [0.0, 1.0, 0.0],
        pixels,
        fov_deg: [fov_deg, fov_deg],
        gain_dc_per_k: None,
    })
    .unwrap()
}

fn looking_down(above: [f64; 3]) -> Camera {
    Camera::from_view(&View::Legacy {
        position_m: above,
        pixels: [5, 5],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [1.0, 1.0],
        gain_dc_per_k: None,
    })
    .unwrap()
}

/// Every pixel of `camera` with the sun minus without, W m⁻² sr⁻¹.
fn sun_part(
    night: &Tracer<TotalRadiance, Vacuum>,
    day: &Tracer<TotalRadiance, Vacuum>,
    camera: &Camera,
    options: &TraceOptions,
) -> Vec<f64> {
    let a = night.render(camera, options, &|_| {}).unwrap();
    let b = day.render(camera, options, &|_| {}).unwrap();
    b.radiance_w_m2_sr
        .iter()
        .zip(&a.radiance_w_m2_sr)
        .map(|(d, n)| d - n)
        .collect()
}

/// `r·E_n·cos θ_i/π` of a Lambertian facet of emissivity `eps`.
fn lambertian(eps: f64, cos_i: f64) -> f64 {
    (1.0 - eps) * E_N * cos_i / std::f64::consts::PI
}

#[test]
fn a_lambertian_plate_reflects_r_e_cos_over_pi() {
    let scene = raw_scene(&[(&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K)]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let camera = looking_down([0.0, 0.0, 100.0]);
    let expected = lambertian(0.9, ZENITH_DEG.to_radians().cos());
    for rays in [1, 64] {
        let day = tracer(&scene, &materials)
            .with_sun(Some(sun(rays)))
            .unwrap();
        let part = sun_part(
            &tracer(&scene, &materials),
            &day,
            &camera,
            &TraceOptions::default(),
        );
        for p in part {
            if rays == 1 {
                assert!((p / expected - 1.0).abs() < 1e-9, "{p} vs {expected}");
            } else {
                // Many rays weight each point of the disk by its own cosine, which lies
                // between cos(θ + α) and cos(θ − α).
                let (z, a) = (ZENITH_DEG.to_radians(), SUN_ANGULAR_RADIUS_DEG.to_radians());
                let (lo, hi) = (
                    lambertian(0.9, (z + a).cos()),
                    lambertian(0.9, (z - a).cos()),
                );
                assert!(lo < p && p < hi, "{rays} rays: {p} outside [{lo}, {hi}]");
            }
        }
    }
}

#[test]
fn a_plate_in_a_shadow_gets_no_sun() {
    // An opaque plate 10 m above, centred on the line from the plate's middle to the sun
    // (x = 10 tan 30° = 5.77 m) and out of the camera's 1° view.
    let x = 10.0 * ZENITH_DEG.to_radians().tan();
    let roof = plate([x - 3.0, -3.0], [x + 3.0, 3.0], 11.0);
    let scene = raw_scene(&[
        (&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K),
        (&roof, 1, T_K),
    ]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let camera = looking_down([0.0, 0.0, 100.0]);
    for rays in [1, 16] {
        let day = tracer(&scene, &materials)
            .with_sun(Some(sun(rays)))
            .unwrap();
        let night = tracer(&scene, &materials);
        let part = sun_part(&night, &day, &camera, &TraceOptions::default());
        assert!(part.iter().all(|&p| p == 0.0), "{rays} rays: {part:?}");
    }
    // Without the roof the same pixels are sunlit: the test can fail.
    let open = raw_scene(&[(&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K)]);
    let day = tracer(&open, &materials).with_sun(Some(sun(1))).unwrap();
    let part = sun_part(
        &tracer(&open, &materials),
        &day,
        &camera,
        &TraceOptions::default(),
    );
    assert!(part.iter().all(|&p| p > 0.0));
}

#[test]
fn a_plate_sees_the_sun_only_from_the_sunward_side() {
    // A vertical plate in the plane x = 0; the sun is in the +x half of the sky, 60° from
    // the plate's +x normal. Seen from −x its seen side faces away: nothing. Seen from +x:
    // cos θ_i = sin 30°.
    let scene = raw_scene(&[(&wall(0.0, [-20.0, 20.0], [1.0, 41.0]), 1, T_K)]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let day = tracer(&scene, &materials).with_sun(Some(sun(1))).unwrap();
    let night = tracer(&scene, &materials);
    let options = TraceOptions::default();
    let behind = look_at([-100.0, 0.0, 20.0], [0.0, 0.0, 20.0], [5, 5], 1.0);
    let part = sun_part(&night, &day, &behind, &options);
    assert!(part.iter().all(|&p| p == 0.0), "{part:?}");
    let front = look_at([100.0, 0.0, 20.0], [0.0, 0.0, 20.0], [5, 5], 1.0);
    let expected = lambertian(0.9, ZENITH_DEG.to_radians().sin());
    for p in sun_part(&night, &day, &front, &options) {
        assert!((p / expected - 1.0).abs() < 1e-9, "{p} vs {expected}");
    }
}

#[test]
fn a_closed_box_in_the_sun_is_dark_inside() {
    let scene = raw_scene(&[(&box_mesh([-5.0, -5.0, 0.5], [5.0, 5.0, 4.5]), 1, T_K)]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let night = tracer(&scene, &materials);
    let options = TraceOptions::default();
    // Looking at the floor, and at the wall on the sun's side (whose inner face looks
    // away from the sun) and the one opposite (whose inner face looks toward it).
    let cameras = [
        look_at([0.0, 0.0, 4.0], [0.0, 0.0, 0.5], [9, 9], 60.0),
        look_at([0.0, 0.0, 2.5], [5.0, 0.0, 2.5], [9, 9], 60.0),
        look_at([0.0, 0.0, 2.5], [-5.0, 0.0, 2.5], [9, 9], 60.0),
    ];
    for rays in [1, 16] {
        let day = tracer(&scene, &materials)
            .with_sun(Some(sun(rays)))
            .unwrap();
        for camera in &cameras {
            let part = sun_part(&night, &day, camera, &options);
            assert!(part.iter().all(|&p| p == 0.0), "{rays} rays: {part:?}");
        }
    }
}

/// The mirror of the glint tests: a horizontal plate, ε = 0.9, wholly specular, and a
/// camera on the reflected sun ray through the plate's centre (the mirror image of the
/// sun's direction, `(−sin θ, 0, cos θ)` from the centre, 100 m out), looking at that
/// centre through an odd number of pixels so that the centre pixel's ray is that ray.
const MIRROR_PIXELS: u32 = 101;
const MIRROR_FOV_DEG: f64 = 4.0;

fn mirror_setup(
    specular_bounces: u32,
) -> (
    Tracer<TotalRadiance, Vacuum>,
    Tracer<TotalRadiance, Vacuum>,
    Camera,
    TraceOptions,
) {
    let scene = raw_scene(&[(&plate([-50.0, -50.0], [50.0, 50.0], 1.0), 1, T_K)]);
    let materials = grey_materials(&[(1, 0.9, 1.0)]);
    let z = ZENITH_DEG.to_radians();
    let camera = look_at(
        [-100.0 * z.sin(), 0.0, 1.0 + 100.0 * z.cos()],
        [0.0, 0.0, 1.0],
        [MIRROR_PIXELS; 2],
        MIRROR_FOV_DEG,
    );
    let options = TraceOptions {
        specular_bounces,
        ..TraceOptions::default()
    };
    let day = tracer(&scene, &materials).with_sun(Some(sun(1))).unwrap();
    (tracer(&scene, &materials), day, camera, options)
}

/// The angle between pixel (`column`, `row`)'s ray and the centre pixel's, degrees: a
/// pinhole camera puts the image plane at unit distance, `tan(fov/2)` at its edge. A flat
/// mirror keeps angles, so this is also the angle of the pixel's reflected ray from the
/// sun's centre.
fn off_axis_deg(column: u32, row: u32) -> f64 {
    let pitch = 2.0 * (MIRROR_FOV_DEG / 2.0).to_radians().tan() / f64::from(MIRROR_PIXELS);
    let c = f64::from(MIRROR_PIXELS / 2);
    let (u, v) = (
        (f64::from(column) - c) * pitch,
        (f64::from(row) - c) * pitch,
    );
    // Angle between (u, v, 1) and (0, 0, 1).
    (u.hypot(v)).atan2(1.0).to_degrees()
}

#[test]
fn a_mirror_glints_within_the_disk_where_hand_geometry_puts_it() {
    let a = SUN_ANGULAR_RADIUS_DEG.to_radians();
    let omega = std::f64::consts::TAU * (1.0 - a.cos());
    let glint = 0.1 * E_N / omega;
    for bounces in [1, 0] {
        let (night, day, camera, options) = mirror_setup(bounces);
        let part = sun_part(&night, &day, &camera, &options);
        let n = MIRROR_PIXELS;
        let centre = (n / 2) as usize;
        let at = |c: u32, r: u32| part[r as usize * n as usize + c as usize];
        assert!(
            (at(centre as u32, centre as u32) / glint - 1.0).abs() < 1e-9,
            "{} vs {glint}",
            at(centre as u32, centre as u32)
        );
        let mut lit = 0;
        for r in 0..n {
            for c in 0..n {
                let off = off_axis_deg(c, r);
                let p = at(c, r);
                // 1e-3° either side of the rim: the rounding of the ray directions.
                if off < SUN_ANGULAR_RADIUS_DEG - 1e-3 {
                    assert!((p / glint - 1.0).abs() < 1e-9, "({c}, {r}) {off}°: {p}");
                    lit += 1;
                } else if off > SUN_ANGULAR_RADIUS_DEG + 1e-3 {
                    assert!(p == 0.0, "({c}, {r}) {off}°: {p}");
                }
            }
        }
        // The disk, 0.267° in radius, at 0.0396° a pixel: about π·6.7² ≈ 142 pixels.
        assert!((120..170).contains(&lit), "{lit} pixels glint");
        // A pixel whose reflection is 1° off the sun: 1° is 25 pixels at this pitch.
        let c1 = (centre + 25) as u32;
        assert!((off_axis_deg(c1, centre as u32) - 1.0).abs() < 0.02);
        assert!(at(c1, centre as u32) == 0.0);
    }
}

#[test]
fn a_shadow_edge_lets_through_the_visible_part_of_the_disk() {
    // A roof 10 m above the plate's middle covering x ≥ x_e, its edge seen from the middle
    // at zenith 30° + α/2: the edge's plane (through the point and the edge, which runs
    // along y) passes α/2 beyond the sun's centre, so it cuts off the segment of the disk
    // beyond a chord at α/2 from the centre. Of a disk of radius R, the segment beyond a
    // chord at distance d holds (R² acos(d/R) − d √(R² − d²))/(πR²): at d = R/2,
    // (π/3 − √3/4)/π = 0.19550; the sun keeps 0.80450 (the small-angle disk; the cosine
    // weighting across it moves this by about 1e-3).
    let a = SUN_ANGULAR_RADIUS_DEG.to_radians();
    let x_e = 10.0 * (ZENITH_DEG.to_radians() + a / 2.0).tan();
    let roof = plate([x_e, -500.0], [x_e + 500.0, 500.0], 11.0);
    let scene = raw_scene(&[
        (&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K),
        (&roof, 1, T_K),
    ]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    // One pixel, straight down at the plate's middle.
    let camera = Camera::from_view(&View::Legacy {
        position_m: [0.0, 0.0, 100.0],
        pixels: [1, 1],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [1e-3, 1e-3],
        gain_dc_per_k: None,
    })
    .unwrap();
    let full = lambertian(0.9, ZENITH_DEG.to_radians().cos());
    let kept = 1.0 - (std::f64::consts::FRAC_PI_3 - 3f64.sqrt() / 4.0) / std::f64::consts::PI;
    assert!((kept - 0.80450).abs() < 1e-5);
    let night = tracer(&scene, &materials);
    let day = tracer(&scene, &materials)
        .with_sun(Some(sun(4096)))
        .unwrap();
    let mut fractions = Vec::new();
    for seed in 0..4 {
        let options = TraceOptions {
            seed,
            ..TraceOptions::default()
        };
        let f = sun_part(&night, &day, &camera, &options)[0] / full;
        assert!(f > 0.0 && f < 1.0, "{f}");
        // 4096 stratified rays: the error is far below 1e-3; 4e-3 leaves room for the
        // cosine weighting.
        assert!((f - kept).abs() < 4e-3, "seed {seed}: {f} vs {kept}");
        fractions.push(f);
    }
    // The seeds draw different points.
    assert!(
        fractions
            .windows(2)
            .any(|w| w[0].to_bits() != w[1].to_bits())
    );
    // One ray, at the centre, which the roof misses: the whole sun.
    let hard = tracer(&scene, &materials).with_sun(Some(sun(1))).unwrap();
    let f = sun_part(&night, &hard, &camera, &TraceOptions::default())[0] / full;
    assert!((f - 1.0).abs() < 1e-9, "{f}");
}

#[test]
fn the_terrain_background_reflects_the_sun_unshadowed() {
    let mut scene = raw_scene(&[(&plate([-1.0, -1.0], [1.0, 1.0], 1.0), 1, T_K)]);
    scene.terrain.emissivity = 0.85;
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let night = tracer(&scene, &materials);
    let eps_t = scene.terrain.emissivity;
    let day = tracer(&scene, &materials).with_sun(Some(sun(1))).unwrap();
    // Straight down 50 m beside the plate: the terrain.
    let part = sun_part(
        &night,
        &day,
        &looking_down([50.0, 0.0, 100.0]),
        &TraceOptions::default(),
    );
    let expected = (1.0 - eps_t) * E_N * ZENITH_DEG.to_radians().cos() / std::f64::consts::PI;
    assert!(expected > 0.0);
    for p in part {
        assert!((p / expected - 1.0).abs() < 1e-9, "{p} vs {expected}");
    }
}

/// Two frames alike bit for bit, their radiance and truth (whose NaNs `==` would refuse).
fn same(a: &Frame, b: &Frame) -> bool {
    let bits = |f: &Frame| {
        f.radiance_w_m2_sr
            .iter()
            .map(|l| l.to_bits())
            .collect::<Vec<_>>()
    };
    bits(a) == bits(b) && format!("{:?}", a.truth) == format!("{:?}", b.truth)
}

#[test]
fn no_sun_renders_bit_for_bit_as_before() {
    // The pit and a mirror, sky-view rays and supersampling on: every random stream in use.
    let scene = raw_scene(&[
        (&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K),
        (&box_mesh([-2.0, -2.0, 1.0], [2.0, 2.0, 5.0]), 2, 320.0),
    ]);
    let materials = grey_materials(&[(1, 0.9, 0.3), (2, 0.8, 0.0)]);
    let air = Vacuum {
        sky_radiance_w_m2_sr: 20.0,
    };
    let camera = look_at([30.0, 20.0, 25.0], [0.0, 0.0, 2.0], [24, 24], 50.0);
    let options = TraceOptions {
        sky_view_rays: 8,
        supersampling: 2,
        ..TraceOptions::default()
    };
    let fresh = Tracer::new(&scene, &materials, TotalRadiance, air).unwrap();
    let before = fresh.render(&camera, &options, &|_| {}).unwrap();
    let none = Tracer::new(&scene, &materials, TotalRadiance, air)
        .unwrap()
        .with_sun(None)
        .unwrap();
    assert!(!none.has_sun());
    assert!(same(
        &none.render(&camera, &options, &|_| {}).unwrap(),
        &before
    ));
    // A sun given and taken away again leaves nothing behind, the terrain included.
    let lit = Tracer::new(&scene, &materials, TotalRadiance, air)
        .unwrap()
        .with_sun(Some(sun(4)))
        .unwrap();
    assert!(lit.has_sun());
    let day = lit.render(&camera, &options, &|_| {}).unwrap();
    assert_ne!(day.radiance_w_m2_sr, before.radiance_w_m2_sr);
    let unlit = lit.with_sun(None).unwrap();
    assert!(same(
        &unlit.render(&camera, &options, &|_| {}).unwrap(),
        &before
    ));
}

#[test]
fn a_sunlit_frame_does_not_depend_on_the_thread_count() {
    let scene = raw_scene(&[
        (&plate([-20.0, -20.0], [20.0, 20.0], 1.0), 1, T_K),
        (&box_mesh([-2.0, -2.0, 1.0], [2.0, 2.0, 5.0]), 2, 320.0),
    ]);
    let materials = grey_materials(&[(1, 0.9, 0.3), (2, 0.8, 0.0)]);
    let camera = look_at([30.0, 20.0, 25.0], [0.0, 0.0, 2.0], [32, 32], 50.0);
    let options = TraceOptions {
        sky_view_rays: 4,
        supersampling: 2,
        ..TraceOptions::default()
    };
    let day = tracer(&scene, &materials).with_sun(Some(sun(9))).unwrap();
    let render = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| day.render(&camera, &options, &|_| {}).unwrap())
    };
    assert!(same(&render(1), &render(3)));
}

#[test]
fn a_sun_with_the_wrong_number_of_beams_or_bad_geometry_is_refused() {
    let scene = raw_scene(&[(&plate([-1.0, -1.0], [1.0, 1.0], 1.0), 1, T_K)]);
    let materials = grey_materials(&[(1, 0.9, 0.0)]);
    let beam = SunBeam::uniform(E_N).unwrap();
    let bad = [
        Sun::new(DVec3::from(to_sun()), vec![]),
        Sun::new(DVec3::from(to_sun()), vec![beam.clone(), beam.clone()]),
        Sun::new(DVec3::new(0.0, 0.0, 0.0), vec![beam.clone()]),
        Sun::new(DVec3::new(f64::NAN, 0.0, 1.0), vec![beam.clone()]),
        Sun {
            shadow_rays: 0,
            ..sun(1)
        },
        Sun {
            angular_radius_deg: -0.1,
            ..sun(1)
        },
    ];
    for s in bad {
        assert!(
            tracer(&scene, &materials)
                .with_sun(Some(s.clone()))
                .is_err(),
            "{s:?}"
        );
    }
}
