//! Tiles of a frame (`Tracer::render_tile`): every pixel of every tile is bit for bit the
//! same pixel of the whole-frame rendering, with supersampling, sky-view rays, a specular
//! bounce and adaptive supersampling (whose edge test reaches one pixel beyond the tile) on;
//! and a tile outside the image is an error.

use irsig_model::View;
use irsig_radiometry::TotalRadiance;
use irsig_tracer::testing::{box_mesh, grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, Frame, Tile, TraceErrorKind, TraceOptions, Tracer, Vacuum};

fn scene() -> (Tracer<TotalRadiance, Vacuum>, Camera) {
    // A cold diffuse ground, a hot diffuse plate and a warm specular box: outlines at every
    // angle, sky-view rays on the diffuse facets, a reflection in the box.
    let ground = ground_quad([-50.0, -50.0], [50.0, 50.0], 0.0);
    let plate = ground_quad([-7.3, -4.1], [6.2, 8.9], 0.5);
    let block = box_mesh([-12.0, -11.0, 0.0], [-4.0, -6.0, 3.0]);
    let scene = raw_scene(&[(&ground, 1, 280.0), (&plate, 2, 340.0), (&block, 3, 310.0)]);
    let materials = grey_materials(&[(1, 0.9, 0.0), (2, 0.95, 0.0), (3, 0.6, 0.8)]);
    let sky = Vacuum {
        sky_radiance_w_m2_sr: 40.0,
    };
    let tracer = Tracer::new(&scene, &materials, TotalRadiance, sky).unwrap();
    let camera = Camera::from_view(&View::Legacy {
        position_m: [5.3, -30.2, 40.0],
        pixels: [37, 29],
        omega_phi_kappa_deg: [35.0, 0.0, 7.0],
        fov_deg: [40.0, 32.0],
        gain_dc_per_k: None,
    })
    .unwrap();
    (tracer, camera)
}

fn options(adaptive: Option<f64>) -> TraceOptions {
    TraceOptions {
        supersampling: 3,
        adaptive_threshold_k: adaptive,
        sky_view_rays: 8,
        specular_bounces: 2,
        seed: 11,
        truth: true,
    }
}

/// Asserts that `tile`'s frame holds, bit for bit, the whole frame's pixels of `tile`.
fn assert_same_pixels(whole: &Frame, part: &Frame, tile: Tile) {
    assert_eq!((part.width, part.height), (tile.width, tile.height));
    for r in 0..tile.height as usize {
        for c in 0..tile.width as usize {
            let i = r * tile.width as usize + c;
            let j = (tile.y as usize + r) * whole.width as usize + tile.x as usize + c;
            assert_eq!(
                part.radiance_w_m2_sr[i].to_bits(),
                whole.radiance_w_m2_sr[j].to_bits(),
                "tile {tile}: pixel ({}, {})",
                tile.x as usize + c,
                tile.y as usize + r
            );
            assert_eq!(
                part.truth[i], whole.truth[j],
                "tile {tile}: truth of pixel {c},{r}"
            );
        }
    }
}

#[test]
fn every_tile_is_bit_for_bit_the_whole_frames_pixels() {
    let (tracer, camera) = scene();
    for adaptive in [None, Some(0.5)] {
        let opts = options(adaptive);
        let whole = tracer.render(&camera, &opts, &|_| {}).unwrap();
        // The scene is not trivial: supersampling changed pixels (outlines), and with the
        // threshold some pixels were refined and some kept their centre ray.
        let centre = tracer
            .render(
                &camera,
                &TraceOptions {
                    supersampling: 1,
                    adaptive_threshold_k: None,
                    ..opts
                },
                &|_| {},
            )
            .unwrap();
        let changed = whole
            .radiance_w_m2_sr
            .iter()
            .zip(&centre.radiance_w_m2_sr)
            .filter(|(a, b)| a.to_bits() != b.to_bits())
            .count();
        assert!(changed > 50, "{changed} pixels changed by supersampling");
        if adaptive.is_some() {
            assert!(changed < 37 * 29, "adaptive refined every pixel");
        }
        let mut tiles: Vec<Tile> = (1..=12)
            .map(|i| Tile::of_grid(i, 4, 3, 37, 29).unwrap())
            .collect();
        // Odd rectangles: a pixel in a corner, a one-pixel row, a column at the right edge.
        tiles.extend([
            Tile {
                x: 36,
                y: 28,
                width: 1,
                height: 1,
            },
            Tile {
                x: 0,
                y: 0,
                width: 1,
                height: 1,
            },
            Tile {
                x: 3,
                y: 17,
                width: 30,
                height: 1,
            },
            Tile {
                x: 35,
                y: 0,
                width: 2,
                height: 29,
            },
            Tile::whole(37, 29),
        ]);
        for tile in tiles {
            let rows = std::sync::atomic::AtomicU64::new(0);
            let part = tracer
                .render_tile(&camera, &opts, tile, &|n| {
                    rows.fetch_add(n, std::sync::atomic::Ordering::Relaxed);
                })
                .unwrap();
            assert_same_pixels(&whole, &part, tile);
            assert_eq!(
                rows.into_inner(),
                u64::from(tile.height),
                "progress in rows"
            );
        }
    }
}

#[test]
fn a_tile_without_truth_has_the_same_radiance() {
    let (tracer, camera) = scene();
    let opts = TraceOptions {
        truth: false,
        ..options(Some(0.5))
    };
    let whole = tracer
        .render(&camera, &options(Some(0.5)), &|_| {})
        .unwrap();
    let tile = Tile::of_grid(5, 3, 3, 37, 29).unwrap();
    let part = tracer.render_tile(&camera, &opts, tile, &|_| {}).unwrap();
    assert!(part.truth.is_empty());
    for r in 0..tile.height as usize {
        let row = (tile.y as usize + r) * 37 + tile.x as usize;
        let a = &part.radiance_w_m2_sr[r * tile.width as usize..][..tile.width as usize];
        assert_eq!(a, &whole.radiance_w_m2_sr[row..row + tile.width as usize]);
    }
}

#[test]
fn a_tile_outside_the_image_is_an_error() {
    let (tracer, camera) = scene();
    for tile in [
        Tile {
            x: 30,
            y: 0,
            width: 8,
            height: 4,
        },
        Tile {
            x: 0,
            y: 29,
            width: 1,
            height: 1,
        },
        Tile {
            x: 2,
            y: 2,
            width: 0,
            height: 3,
        },
        Tile {
            x: u32::MAX,
            y: 0,
            width: 1,
            height: 1,
        },
    ] {
        let e = tracer
            .render_tile(&camera, &options(None), tile, &|_| {})
            .unwrap_err();
        assert!(matches!(e.kind, TraceErrorKind::InvalidTile(_)), "{e}");
    }
}
