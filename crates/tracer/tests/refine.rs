//! Refinement to a standard-error target (`Tracer::with_refinement`): edge pixels converge
//! on their exact area-averaged radiance within the error each reports; a pole a quarter
//! of a pixel wide, between the centre rays, is found from the geometry and measured; so is
//! the horizon inside the image's top row; a sliver along a pixel's border that its rays
//! missed is not taken as converged; a refined frame in tiles is bit for bit the frame
//! whole.

use irsig_model::View;
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_tracer::testing::{EdgeExperiment, grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, Refinement, Tile, TraceOptions, Tracer, Vacuum};

fn t_of(l: f64) -> f64 {
    TotalRadiance.temperature(l)
}

const REFINE: Refinement = Refinement {
    target_k: 0.05,
    edge_k: 0.1,
    max_side: 32,
    thin_side: 8,
};

#[test]
fn edge_pixels_reach_their_exact_value_within_the_error_they_report() {
    let e = EdgeExperiment::new();
    let [w, h] = EdgeExperiment::PIXELS;
    let tracer = e.tracer.with_refinement(Some(REFINE)).unwrap();
    let frame = tracer
        .render(&e.camera, &TraceOptions::default(), &|_| {})
        .unwrap();
    assert_eq!(frame.sampling.len(), (w * h) as usize);
    let (mut crossed, mut within) = (0, 0);
    for row in 0..h {
        for col in 0..w {
            let i = (row * w + col) as usize;
            let exact = EdgeExperiment::exact_radiance_w_m2_sr(col, row);
            let s = frame.sampling[i];
            let error = (t_of(frame.radiance_w_m2_sr[i]) - t_of(exact)).abs();
            let f = irsig_tracer::testing::pixel_fraction_left_of_line(
                EdgeExperiment::X0,
                EdgeExperiment::SLOPE,
                col.into(),
                row.into(),
            );
            if f > 0.0 && f < 1.0 {
                crossed += 1;
                // Every pixel the 30 K edge crosses is refined, to the target or the cap.
                assert!(s.rays > 1, "({col}, {row}) kept its centre ray");
                assert!(f64::from(s.sigma_k) <= REFINE.target_k || s.capped, "{s:?}");
                if error <= 3.0 * f64::from(s.sigma_k) + 1e-9 {
                    within += 1;
                }
                assert!(error < 0.5, "({col}, {row}): {error} K off, {s:?}");
            } else {
                // A uniform pixel is exact with its centre ray.
                assert!(error < 1e-9, "({col}, {row}): {error} K off");
            }
        }
    }
    assert!(crossed > 50, "{crossed}");
    // The reported error is honest: nearly all pixels lie within 3σ of their exact value.
    assert!(
        within * 100 >= crossed * 90,
        "{within} of {crossed} within 3 sigma"
    );
}

/// The nadir view the thin-pole and sliver tests share: 100 m up, 21 × 11 pixels over
/// 21 × 11°.
const NADIR_HEIGHT_M: f64 = 100.0;
const NADIR_PIXELS: [u32; 2] = [21, 11];
const NADIR_FOV_DEG: [f64; 2] = [21.0, 11.0];

fn nadir_camera() -> Camera {
    Camera::from_view(&View::Legacy {
        position_m: [0.0, 0.0, NADIR_HEIGHT_M],
        pixels: NADIR_PIXELS,
        omega_phi_kappa_deg: [0.0; 3],
        fov_deg: NADIR_FOV_DEG,
        gain_dc_per_k: None,
    })
    .unwrap()
}

/// Ground x of the nadir view's pixel column `c`'s left edge, m (the camera's x runs east,
/// column 0 west; fractions of a column are linear on the ground).
fn column_x(c: f64) -> f64 {
    let half = NADIR_HEIGHT_M * (NADIR_FOV_DEG[0] / 2.0).to_radians().tan();
    -half + c * 2.0 * half / f64::from(NADIR_PIXELS[0])
}

/// The index of the nadir view's pixel (`col`, `row`).
fn nadir_at(col: u32, row: u32) -> usize {
    (row * NADIR_PIXELS[0] + col) as usize
}

#[test]
fn a_pole_thinner_than_a_pixel_between_the_centre_rays_is_found_and_measured() {
    // A nadir camera over cold ground (0 K: black) sees a hot strip (400 K) a quarter of a
    // pixel wide, lying in the left part of pixel column 10: no centre ray touches it.
    let (x0, x1) = (column_x(10.05), column_x(10.30));
    let ground = ground_quad([-100.0, -100.0], [100.0, 100.0], 0.0);
    let strip = ground_quad([x0, -30.0], [x1, 30.0], 0.01);
    let scene = raw_scene(&[(&ground, 1, 0.0), (&strip, 2, 400.0)]);
    let materials = grey_materials(&[(1, 1.0, 0.0), (2, 1.0, 0.0)]);
    let tracer = Tracer::new(&scene, &materials, TotalRadiance, Vacuum::default()).unwrap();
    let camera = nadir_camera();
    let thin = tracer.thin_pixels(&camera);
    let at = nadir_at;
    assert!(thin[at(10, 5)] && !thin[at(3, 5)]);
    // Centre rays alone miss it: the row reads black.
    let plain = tracer
        .render(&camera, &TraceOptions::default(), &|_| {})
        .unwrap();
    assert!(plain.radiance_w_m2_sr[at(10, 5)].abs() < 1e-12);
    // Refined, column 10 holds a quarter of the strip's radiance. (The pixel's quarter on
    // the ground is a quarter of its solid angle to 1e-4 at 0.5° off nadir.)
    let tracer = tracer.with_refinement(Some(REFINE)).unwrap();
    let frame = tracer
        .render(&camera, &TraceOptions::default(), &|_| {})
        .unwrap();
    let expected = 0.25 * TotalRadiance.radiance(400.0);
    for row in 2..9 {
        let l = frame.radiance_w_m2_sr[at(10, row)];
        let s = frame.sampling[at(10, row)];
        let error = (t_of(l) - t_of(expected)).abs();
        assert!(
            error < 0.05 + 3.0 * f64::from(s.sigma_k),
            "row {row}: {l} against {expected}, {error} K, {s:?}"
        );
    }
    // A tile finds the pole's thin pixels among its own, as the frame does: column 10 in
    // a tile that starts beside it, and in one that starts on it.
    for tile in [
        Tile {
            x: 9,
            y: 3,
            width: 3,
            height: 4,
        },
        Tile {
            x: 10,
            y: 0,
            width: 11,
            height: 11,
        },
    ] {
        let part = tracer
            .render_tile(&camera, &TraceOptions::default(), tile, &|_| {})
            .unwrap();
        for r in 0..tile.height {
            for c in 0..tile.width {
                let i = at(tile.x + c, tile.y + r);
                let j = (r * tile.width + c) as usize;
                assert_eq!(
                    part.radiance_w_m2_sr[j].to_bits(),
                    frame.radiance_w_m2_sr[i].to_bits(),
                    "{tile} ({c}, {r})"
                );
                assert_eq!(part.sampling[j], frame.sampling[i], "{tile} ({c}, {r})");
            }
        }
    }
}

#[test]
fn a_refined_frame_in_tiles_is_the_frame_whole() {
    let e = EdgeExperiment::new();
    let tracer = e.tracer.with_refinement(Some(REFINE)).unwrap();
    let options = TraceOptions {
        seed: 3,
        ..TraceOptions::default()
    };
    let whole = tracer.render(&e.camera, &options, &|_| {}).unwrap();
    let [w, h] = EdgeExperiment::PIXELS;
    for tile in [
        Tile {
            x: 0,
            y: 0,
            width: 7,
            height: 40,
        },
        Tile {
            x: 7,
            y: 20,
            width: w - 7,
            height: h - 20,
        },
    ] {
        let part = tracer
            .render_tile(&e.camera, &options, tile, &|_| {})
            .unwrap();
        for r in 0..tile.height {
            for c in 0..tile.width {
                let i = ((tile.y + r) * w + tile.x + c) as usize;
                let j = (r * tile.width + c) as usize;
                assert_eq!(
                    part.radiance_w_m2_sr[j].to_bits(),
                    whole.radiance_w_m2_sr[i].to_bits()
                );
                assert_eq!(part.sampling[j], whole.sampling[i]);
            }
        }
    }
}

/// The horizon inside the image's top row: every centre ray there sees the terrain
/// background and no row above can show the sky, so no centre's contrast finds the edge.
/// The pixels it crosses are found from their corners, and refined to the share of each
/// pixel above it, set by the geometry: the camera is pitched down so that the Earth's
/// limb crosses row 0 at 0.9 of the top half-field, 40 % of the row's height from its top.
#[test]
fn the_horizon_inside_the_top_row_is_found_and_measured() {
    use irsig_tracer::Atmosphere;
    let (height, pixels, fov_v) = (10.0, [8, 8], 20.0_f64);
    let half = (fov_v / 2.0).to_radians().tan();
    // The limb's depression below the horizontal, from the sensor's altitude (a ray whose
    // nadir angle is under the critical one meets the terrain).
    let sky = Vacuum {
        sky_radiance_w_m2_sr: TotalRadiance.radiance(200.0),
    };
    let dip = (90.0 - sky.critical_nadir_angle_deg(height)).to_radians();
    assert!(dip > 0.0 && dip < 0.01, "{dip}");
    let pitch = (0.9 * half).atan() + dip;
    let ground = ground_quad([-1.0, -1.0], [1.0, 1.0], 0.0);
    let scene = raw_scene(&[(&ground, 1, 300.0)]);
    let materials = grey_materials(&[(1, 1.0, 0.0)]);
    let tracer = Tracer::new(&scene, &materials, TotalRadiance, sky).unwrap();
    let camera = Camera::from_view(&View::LookAt {
        position_m: [0.0, 0.0, height],
        target_m: [0.0, 1000.0, height - 1000.0 * pitch.tan()],
        up: [0.0, 0.0, 1.0],
        pixels,
        fov_deg: [fov_v, fov_v],
        gain_dc_per_k: None,
    })
    .unwrap();
    let thin = tracer.thin_pixels(&camera);
    let at = |col: u32, row: u32| (row * pixels[0] + col) as usize;
    for col in 0..pixels[0] {
        assert!(thin[at(col, 0)], "column {col} of row 0");
        for row in 1..pixels[1] {
            assert!(!thin[at(col, row)], "({col}, {row})");
        }
    }
    let plain = tracer
        .render(&camera, &TraceOptions::default(), &|_| {})
        .unwrap();
    let (l_sky, l_terrain) = (sky.sky_radiance_w_m2_sr, plain.radiance_w_m2_sr[at(3, 1)]);
    // The centre rays alone read row 0 as terrain.
    assert_eq!(
        plain.radiance_w_m2_sr[at(3, 0)].to_bits(),
        l_terrain.to_bits()
    );
    assert!(
        t_of(l_terrain) - t_of(l_sky) > 50.0,
        "an edge worth finding"
    );
    let frame = tracer
        .with_refinement(Some(REFINE))
        .unwrap()
        .render(&camera, &TraceOptions::default(), &|_| {})
        .unwrap();
    let expected = 0.4 * l_sky + 0.6 * l_terrain;
    for col in 0..pixels[0] {
        let l = frame.radiance_w_m2_sr[at(col, 0)];
        let s = frame.sampling[at(col, 0)];
        let error = (t_of(l) - t_of(expected)).abs();
        assert!(
            error < 0.05 + 3.0 * f64::from(s.sigma_k),
            "column {col}: {l} against {expected}, {error} K, {s:?}"
        );
    }
}

/// A sliver of a hot plate, 2e-4 of a pixel wide, along the left border of a pixel that
/// an edge crosses (300 and 310 K ground, its rounds never equal): a level's 512 rays miss
/// the sliver more often than not, and it is worth about 5 K. The level is too few rays
/// for a sliver worth the target to be hardly missed, so the border is walked, meets the
/// plate and sends the pixel on: it ends within its error of the exact value, or capped,
/// never a few kelvin off with a small σ.
#[test]
fn a_sliver_along_the_border_that_the_rays_missed_is_not_taken_as_converged() {
    let sliver = 2e-4;
    let plate = ground_quad(
        [column_x(5.0), -30.0],
        [column_x(10.0 + sliver), 30.0],
        0.01,
    );
    let cool = ground_quad([-100.0, -100.0], [column_x(10.6), 100.0], 0.0);
    let warm = ground_quad([column_x(10.6), -100.0], [100.0, 100.0], 0.0);
    let scene = raw_scene(&[(&plate, 1, 1300.0), (&cool, 2, 300.0), (&warm, 3, 310.0)]);
    let materials = grey_materials(&[(1, 1.0, 0.0), (2, 1.0, 0.0), (3, 1.0, 0.0)]);
    let tracer = Tracer::new(&scene, &materials, TotalRadiance, Vacuum::default()).unwrap();
    let camera = nadir_camera();
    let at = nadir_at;
    assert!(
        !tracer.thin_pixels(&camera)[at(10, 5)],
        "found by its edge, not as thin"
    );
    let frame = tracer
        .with_refinement(Some(REFINE))
        .unwrap()
        .render(&camera, &TraceOptions::default(), &|_| {})
        .unwrap();
    let l = |t: f64| TotalRadiance.radiance(t);
    let expected = sliver * l(1300.0) + (0.6 - sliver) * l(300.0) + 0.4 * l(310.0);
    let without = 0.6 * l(300.0) + 0.4 * l(310.0);
    assert!(
        t_of(expected) - t_of(without) > 4.0,
        "a sliver worth finding"
    );
    for row in 2..9 {
        let s = frame.sampling[at(10, row)];
        let error = (t_of(frame.radiance_w_m2_sr[at(10, row)]) - t_of(expected)).abs();
        assert!(
            s.capped || error < 0.05 + 3.0 * f64::from(s.sigma_k),
            "row {row}: {error} K off, {s:?}"
        );
    }
}
