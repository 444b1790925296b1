//! The rough specular lobe end to end: a rough plate lit by a LOWTRAN7-built sun
//! through `irsig-trace`, every pixel's glint against a hand computation of the
//! Cook–Torrance lobe (Beckmann D; for σ = 0.1 and views within 45° Smith's G and the
//! lobe's albedo are 1 to e⁻³⁰, so the hand value is `r·E_n·D(h)/(4 cos θ_o)`).

use std::path::Path;

use irsig_formats::canonical;
use irsig_model::SpectralAtmosphere;
use irsig_model::truth::Layer;
use irsig_tests::{bin, lowtran};

const ZENITH_DEG: f64 = 30.0;
const SIGMA: f64 = 0.1;
const EPSILON: f64 = 0.5;
const PLATE_M: f64 = 150.0;

/// A plan of one thermal path and the sun's beam at 0, 300 and 1000 m over 4–5 µm.
fn plan_ron() -> String {
    format!(
        "(
  name: \"lobe\",
  model: Standard(6),
  wavenumber_per_cm: (1980.0, 2520.0, 20.0),
  path_end_m: 1.0,
  observers_m: [1000.0],
  levels_m: [1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 5.0, 10.0],
  ground_sky_zenith_deg: [0.0],
  hemispheric: [],
  slant_altitude_m: [1000.0],
  slant_nadir_deg: [0.0],
  sky_altitude_m: [0.0],
  sky_zenith_deg: [0.0],
  sun: Some((zenith_deg: {ZENITH_DEG:.1}, day_of_year: 95, altitude_m: [0.0, 300.0, 1000.0])),
)
"
    )
}

/// The beam's normal irradiance over 4–5 µm at `h_m`, W m⁻², from the file's spectra: the
/// trapezoid in wavelength, τ linear in altitude between the rows.
fn normal_irradiance(a: &SpectralAtmosphere, h_m: f64) -> f64 {
    let solar = a.solar.as_ref().unwrap();
    let n = a.grid.points.len();
    let k = solar
        .altitude_m
        .iter()
        .position(|&x| x >= h_m)
        .unwrap()
        .max(1);
    let (h0, h1) = (solar.altitude_m[k - 1], solar.altitude_m[k]);
    let t = (h_m - h0) / (h1 - h0);
    let mut points: Vec<(f64, f64)> = (0..n)
        .filter_map(|i| {
            let nu = a.grid.points[i];
            let um = 1e4 / nu;
            if !(4.0 - 1e-9..=5.0 + 1e-9).contains(&um) {
                return None;
            }
            let tau = |row: usize| f64::from(solar.transmission[row * n + i]);
            let e_per_um = f64::from(solar.extraterrestrial_w_m2_per_unit[i]) * nu * nu / 1e4;
            Some((um, e_per_um * (tau(k - 1) * (1.0 - t) + tau(k) * t)))
        })
        .collect();
    points.sort_by(|x, y| x.0.total_cmp(&y.0));
    points
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum()
}

fn layer(path: &Path, name: &str) -> Vec<f32> {
    let r = irsig_raster::read_exr(&std::fs::read(path).unwrap()).unwrap();
    r.layer(name).unwrap().data.clone()
}

const VIEW: &str = "LookAt(position_m: (0.0, -500.0, 1016.0254037844386), \
     target_m: (0.0, 0.0, 150.0), up: (0.0, 0.0, 1.0), pixels: (9, 9), fov_deg: (24.0, 24.0))";

#[test]
fn a_rough_plate_glints_as_the_cook_torrance_lobe_by_hand() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let plan = d.join("plan");
    std::fs::create_dir(&plan).unwrap();
    std::fs::write(plan.join("plan.ron"), plan_ron()).unwrap();
    let spa = d.join("sunny.spa");
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&plan)
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(&spa)
        .assert()
        .success();
    let a = canonical::read_spectral_atmosphere("built", &std::fs::read(&spa).unwrap()).unwrap();
    let scene = d.join("plate.raw.ron");
    std::fs::write(
        &scene,
        format!(
            "(objects: [\"plate\"], \
             positions_m: [(-1e5, -1e5, {PLATE_M:?}), (1e5, -1e5, {PLATE_M:?}), \
                           (1e5, 1e5, {PLATE_M:?}), (-1e5, 1e5, {PLATE_M:?})], \
             facets: [(vertices: (0, 1, 2), material: 1, temperature_k: 300.0, object: 0), \
                      (vertices: (0, 2, 3), material: 1, temperature_k: 300.0, object: 0)])"
        ),
    )
    .unwrap();
    let view = d.join("view.ron");
    std::fs::write(&view, VIEW).unwrap();
    let trace = |materials: &str, prefix: &str, sun: bool| {
        let lib = d.join(format!("{prefix}.materials.ron"));
        std::fs::write(&lib, materials).unwrap();
        let mut cmd = bin("irsig-trace");
        cmd.arg("--scene")
            .arg(&scene)
            .arg("--materials")
            .arg(&lib)
            .arg("--view")
            .arg(&view)
            .arg("--atmosphere")
            .arg(&spa)
            .args(["--band", "4-5", "--sub-bands", "1"]);
        if sun {
            cmd.args(["--sun-zenith-deg", "30", "--sun-azimuth-deg", "0"]);
        }
        cmd.arg("-o").arg(d.join(prefix)).assert().success();
    };
    let rough = format!(
        "(materials: [(id: 1, name: \"rough\", emissivity: [(0.0, {EPSILON:?}), (90.0, {EPSILON:?})], \
         specular_fraction: 1.0, source: \"a test\", rms_slope: Some({SIGMA:?}))])"
    );
    let mirror = format!(
        "(materials: [(id: 1, name: \"mirror\", emissivity: [(0.0, {EPSILON:?}), (90.0, {EPSILON:?})], \
         specular_fraction: 1.0, source: \"a test\")])"
    );
    trace(&rough, "night", false);
    trace(&rough, "day", true);
    // The same plate without a roughness (a mirror) at night: the lobe changes nothing then
    // (the images' provenance names different material files, so the pixels are compared).
    trace(&mirror, "mirror-night", false);
    let bits = |p: &str| -> Vec<u32> {
        layer(&d.join(p), "radiance")
            .iter()
            .map(|v| v.to_bits())
            .collect()
    };
    assert_eq!(
        bits("night.radiance.exr"),
        bits("mirror-night.radiance.exr")
    );

    let e = normal_irradiance(&a, PLATE_M);
    let night = layer(&d.join("night.radiance.exr"), "radiance");
    let day = layer(&d.join("day.radiance.exr"), "radiance");
    let truth = d.join("day.truth.exr");
    let tau = layer(&truth, "transmission");
    let reflected = layer(&truth, Layer::ReflectedSolarRadiance.name());
    let view_model: irsig_model::View = canonical::from_ron("view.ron", VIEW).unwrap();
    let camera = irsig_tracer::Camera::from_view(&view_model).unwrap();
    let z = ZENITH_DEG.to_radians();
    let to_sun = [0.0, z.sin(), z.cos()];
    let (mut worst, mut peak) = (0.0_f64, (0.0_f64, 0usize));
    for row in 0..9u32 {
        for col in 0..9u32 {
            let p = (row * 9 + col) as usize;
            let dvec = camera.pixel_direction(col, row);
            let len = (dvec[0].powi(2) + dvec[1].powi(2) + dvec[2].powi(2)).sqrt();
            let o = [-dvec[0] / len, -dvec[1] / len, -dvec[2] / len];
            let h = [to_sun[0] + o[0], to_sun[1] + o[1], to_sun[2] + o[2]];
            let hl = (h[0].powi(2) + h[1].powi(2) + h[2].powi(2)).sqrt();
            let cos_h = h[2] / hl;
            let tan2 = (1.0 - cos_h * cos_h) / (cos_h * cos_h);
            let d_beckmann = (-tan2 / (SIGMA * SIGMA)).exp()
                / (std::f64::consts::PI * SIGMA * SIGMA * cos_h.powi(4));
            let glint = (1.0 - EPSILON) * e * d_beckmann / (4.0 * o[2]);
            let added = f64::from(day[p]) - f64::from(night[p]);
            let layer_error = f64::from(reflected[p]) / glint - 1.0;
            worst = worst.max(layer_error.abs());
            // What reaches the sensor of it went through the path's transmittance for
            // sunlight, between the band's τ and 1 (docs/accuracy.md, "Sub-bands by day").
            let tau_sun = added / f64::from(reflected[p]);
            // The disk's average of the lobe against the point sun here: at most
            // (a²/8)·|∇²D|/D, a = the disk's radius in slope (0.0023), 1e-3 over these
            // views; f32 images 1e-6.
            assert!(
                layer_error.abs() < 2e-3 && f64::from(tau[p]) < tau_sun && tau_sun < 1.0,
                "pixel ({col}, {row}): reflected solar {} against {glint} by hand \
                 ({layer_error:+.2e}); the sun adds {added}, through {tau_sun} against the \
                 band's τ {}",
                reflected[p],
                tau[p]
            );
            if added > peak.0 {
                peak = (added, p);
            }
        }
    }
    // The centre pixel looks along the mirror direction: the peak.
    assert_eq!(peak.1, 40, "the glint peaks at pixel {}", peak.1);
    eprintln!(
        "4-5 um rough plate σ {SIGMA}: E_n {e:.4} W m-2, centre glint {:.5} W m-2 sr-1; \
         worst relative error against the hand lobe {worst:.2e}",
        peak.0
    );
}
