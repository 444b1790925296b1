//! Aliasing and the footprint filter: a fine checkerboard (256 × 256 texels of +0 and
//! +10 K on a 10 m quad, a texel 3.9 cm across) seen from 2 km, where a pixel's footprint
//! covers about 5 texels. The mean of its texels is +5 K, by hand (half are +10 K). With
//! `Footprint` every pixel on the quad renders 305 K: a single-texel checkerboard repeats
//! within every level's texel from level 1 up, so the filter's stated error (the spread of
//! the texel means at the level read) is nothing, and only f32 greys and the radiance's
//! inversion remain (under 10⁻³ K). With `Nearest` each pixel takes the one texel its centre
//! ray meets: 300 or 310 K, the moiré, a spread of kelvins. Near, where a pixel covers a
//! tenth of a texel, `Footprint` is `Bilinear`, bit for bit. Supersampled, each ray filters
//! its own cell of the pixel: stripes 16 texels wide read white wherever a pixel lies
//! within them.

use irsig_model::image_map::{ImageMap, ImageMaps, MapFilter};
use irsig_model::{MaterialId, RawScene, View};
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_texture::{GreyImage, MaterialMaps};
use irsig_tracer::testing::{grey_materials, raw_scene};
use irsig_tracer::{Camera, DVec3, TraceOptions, Tracer, Vacuum};

/// The quad's half-width, m, and its tilt about x, degrees.
const HALF_M: f64 = 5.0;
const TILT_DEG: f64 = 25.0;
/// The checkerboard's texels along a side.
const FINE_TEXELS: usize = 256;
/// The sensor straight above, far: at 2 km a pixel of 64 across 0.32° is 8.7·10⁻⁵ rad,
/// 17.5 cm on the ground, 19 cm on the tilted quad: 4.9 texels (level 2.3).
const FAR_M: f64 = 2000.0;
const FAR_FOV_DEG: f64 = 0.32;
const PIXELS: u32 = 64;
/// The largest difference from the texels' mean allowed with the footprint filter, K: the
/// filter's own error is nothing here; f32 greys and the inverse of the band radiance are
/// good to 10⁻⁵ K.
const FOOTPRINT_TOLERANCE_K: f64 = 1e-3;

fn slope() -> f64 {
    TILT_DEG.to_radians().tan()
}

/// The quad (-5, -5) to (5, 5) in x and y on z = y·tan 25°, texture coordinates
/// u = (x + 5)/10, v = (y + 5)/10, material 1 at 300 K.
fn tilted_quad() -> RawScene {
    let corners = [
        [-HALF_M, -HALF_M],
        [HALF_M, -HALF_M],
        [HALF_M, HALF_M],
        [-HALF_M, HALF_M],
    ];
    let positions: Vec<[f64; 3]> = corners.iter().map(|&[x, y]| [x, y, y * slope()]).collect();
    let mesh = (positions, vec![[0, 1, 2], [0, 2, 3]]);
    let mut scene = raw_scene(&[(&mesh, 1, 300.0)]);
    let uv = |k: usize| {
        let [x, y] = corners[k];
        [(x + HALF_M) / (2.0 * HALF_M), (y + HALF_M) / (2.0 * HALF_M)]
    };
    for f in &mut scene.facets {
        f.uv = Some(f.vertices.map(|v| uv(v as usize)));
    }
    scene
}

/// A checkerboard of single texels, `side` across: white where column + row is odd.
fn checkerboard(side: usize) -> GreyImage {
    let grey = (0..side * side)
        .map(|k| ((k / side + k % side) % 2) as f32)
        .collect();
    GreyImage::new(side, side, grey).unwrap()
}

fn tracer(filter: MapFilter, image: GreyImage) -> Tracer<TotalRadiance, Vacuum> {
    let maps = ImageMaps {
        temperature_offset_k: Some(ImageMap {
            image: "checker.png".into(),
            at_black: 0.0,
            per_grey: 10.0,
            filter,
        }),
        emissivity_scale: None,
        material: None,
    };
    let mut lib = grey_materials(&[(1, 1.0, 0.0)]);
    lib.materials[0].maps = Some(maps.clone());
    let loaded = MaterialMaps::new(&maps, |_, _| Ok(image.clone())).unwrap();
    let one = irsig_tracer::SubBand {
        band: TotalRadiance,
        atmosphere: Vacuum::default(),
        emissivity: None,
    };
    Tracer::with_sub_bands_and_maps(
        &tilted_quad(),
        &lib,
        TotalRadiance,
        vec![one],
        vec![(MaterialId(1), loaded)],
    )
    .unwrap()
}

fn camera(height_m: f64, fov_deg: f64, pixels: u32) -> Camera {
    Camera::from_view(&View::Legacy {
        position_m: [0.0, 0.0, height_m],
        pixels: [pixels, pixels],
        omega_phi_kappa_deg: [0.0, 0.0, 0.0],
        fov_deg: [fov_deg, fov_deg],
        gain_dc_per_k: None,
    })
    .unwrap()
}

/// Where the ray from the camera along `d` meets the quad's plane, m: the x and y of the
/// intersection with z = y·tan θ, by hand.
fn ground_xy(cam: &Camera, d: DVec3) -> [f64; 2] {
    let o = cam.position_m;
    let s = (slope() * o[1] - o[2]) / (d[2] - slope() * d[1]);
    [o[0] + s * d[0], o[1] + s * d[1]]
}

/// The apparent temperatures (K; ε = 1 in a vacuum: the kinetic temperature) of the pixels
/// whose centre ray meets the quad at least 2 cm inside its edge (by hand: the ray
/// intersected with the plane z = y·tan θ).
fn on_quad(t: &Tracer<TotalRadiance, Vacuum>, cam: &Camera) -> Vec<f64> {
    let frame = t.render(cam, &TraceOptions::default(), &|_| {}).unwrap();
    let mut out = Vec::new();
    for row in 0..cam.pixels[1] {
        for column in 0..cam.pixels[0] {
            let [x, y] = ground_xy(cam, cam.pixel_direction(column, row));
            if x.abs().max(y.abs()) < HALF_M - 0.02 {
                let l = frame.radiance_w_m2_sr[(row * cam.pixels[0] + column) as usize];
                out.push(TotalRadiance.temperature(l));
            }
        }
    }
    out
}

#[test]
fn a_fine_checkerboard_from_afar_renders_its_texels_mean_with_the_footprint_filter() {
    let cam = camera(FAR_M, FAR_FOV_DEG, PIXELS);
    let mean_k = 300.0 + 0.5 * 10.0;
    let filtered = on_quad(
        &tracer(MapFilter::Footprint, checkerboard(FINE_TEXELS)),
        &cam,
    );
    // The quad (±0.14° of the 0.16° half-field) covers most of the image.
    assert!(filtered.len() > 2500, "{} pixels", filtered.len());
    let worst = filtered
        .iter()
        .map(|t| (t - mean_k).abs())
        .fold(0.0, f64::max);
    assert!(
        worst < FOOTPRINT_TOLERANCE_K,
        "worst {worst} K from {mean_k} K"
    );
    // Nearest: every pixel one texel, 300 or 310 K; the spread is the checkerboard's.
    let nearest = on_quad(&tracer(MapFilter::Nearest, checkerboard(FINE_TEXELS)), &cam);
    assert_eq!(nearest.len(), filtered.len());
    let n = nearest.len() as f64;
    let mean = nearest.iter().sum::<f64>() / n;
    let sd = (nearest.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / n).sqrt();
    let hot = nearest.iter().filter(|&&t| t > 309.9).count();
    let cold = nearest.iter().filter(|&&t| t < 300.1).count();
    assert_eq!(hot + cold, nearest.len());
    assert!(hot > 100 && cold > 100, "{hot} hot, {cold} cold");
    // Two values of some share p: σ = 10·√(p(1 − p)) K, above 3 K for p within 0.1–0.9.
    assert!(sd > 3.0, "nearest's spread {sd} K");
}

#[test]
fn where_a_pixel_covers_less_than_a_texel_the_footprint_filter_is_bilinear() {
    // From 60 m, 96 pixels across 12°: a pixel is 2.2 mrad, 13 cm, a tenth of the 8 × 8
    // checkerboard's 1.25 m texels.
    let cam = camera(60.0, 12.0, 96);
    let radiance = |filter| {
        tracer(filter, checkerboard(8))
            .render(&cam, &TraceOptions::default(), &|_| {})
            .unwrap()
            .radiance_w_m2_sr
    };
    let footprint = radiance(MapFilter::Footprint);
    assert_eq!(footprint, radiance(MapFilter::Bilinear));
    assert_ne!(footprint, radiance(MapFilter::Nearest));
}

/// The stripes' width, texels: 62.5 cm on the quad, 3.6 pixels from 2 km.
const STRIPE_TEXELS: usize = 16;

/// Stripes along v, `STRIPE_TEXELS` wide, across an image `FINE_TEXELS` square: white in
/// the columns `i` with `⌊i / 16⌋` even (the first from the quad's left edge, x = −5 m).
fn stripes() -> GreyImage {
    let side = FINE_TEXELS;
    let grey = (0..side * side)
        .map(|k| f32::from(u8::from(k % side / STRIPE_TEXELS % 2 == 0)))
        .collect();
    GreyImage::new(side, side, grey).unwrap()
}

#[test]
fn each_supersampled_ray_filters_its_own_cell_of_the_pixel() {
    // From 2 km a pixel covers 4.5 texels in x (4.9 along the tilt). With 8 × 8 rays a
    // pixel each ray's cell is 0.6 texel across, and the footprint filter reads the image
    // itself bilinearly, within one texel of the ray. So a pixel whose ground lies more
    // than a texel inside a white stripe is white through and through: 310 K. Were every
    // ray to filter the whole pixel (level 2.3: boxes of 4 and 8 texels read bilinearly,
    // reaching 6 texels out), those within 6 texels of a stripe's edge would mix in the
    // black beyond it.
    let cam = camera(FAR_M, FAR_FOV_DEG, PIXELS);
    let options = TraceOptions {
        supersampling: 8,
        ..TraceOptions::default()
    };
    let frame = tracer(MapFilter::Footprint, stripes())
        .render(&cam, &options, &|_| {})
        .unwrap();
    let texel_m = 2.0 * HALF_M / FINE_TEXELS as f64;
    let stripe = |x_m: f64| ((x_m + HALF_M) / (STRIPE_TEXELS as f64 * texel_m)).floor() as i64;
    let mut inside = Vec::new();
    for row in 0..PIXELS {
        for column in 0..PIXELS {
            let (c, r) = (f64::from(column), f64::from(row));
            let corners = [(c, r), (c + 1.0, r), (c, r + 1.0), (c + 1.0, r + 1.0)];
            let ground = corners.map(|(x, y)| ground_xy(&cam, cam.direction_at(x, y)));
            // The pixel's ground, a texel wider on every side.
            let [x, y] = [0, 1].map(|axis| {
                let values = ground.map(|p| p[axis]);
                [
                    values.iter().copied().fold(f64::INFINITY, f64::min) - texel_m,
                    values.iter().copied().fold(f64::NEG_INFINITY, f64::max) + texel_m,
                ]
            });
            let on_quad = x.iter().chain(&y).all(|c| c.abs() < HALF_M);
            let white = stripe(x[0]) == stripe(x[1]) && stripe(x[0]).rem_euclid(2) == 0;
            if on_quad && white {
                let l = frame.radiance_w_m2_sr[(row * PIXELS + column) as usize];
                inside.push(TotalRadiance.temperature(l));
            }
        }
    }
    // About two columns of every white stripe the quad shows.
    assert!(inside.len() > 300, "{} pixels", inside.len());
    let worst = inside.iter().map(|t| (t - 310.0).abs()).fold(0.0, f64::max);
    assert!(worst < FOOTPRINT_TOLERANCE_K, "worst {worst} K from 310 K");
}
