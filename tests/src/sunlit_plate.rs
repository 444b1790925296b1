//! The sunlit plate of the solar tests (`tests/tests/solar.rs`, `solar_trace.rs`): a grey
//! diffuse plate between the rows of a small LOWTRAN7 plan with a sun, the plan itself,
//! its build, and the plate's view with a sun.

use std::path::{Path, PathBuf};

use irsig_formats::canonical;
use irsig_model::SpectralAtmosphere;

use crate::{bin, lowtran};

/// The sun of these tests: 30° from the zenith on 5 April (day 95), when the Earth is at
/// about its mean distance from the Sun.
pub const ZENITH_DEG: f64 = 30.0;
pub const DAY: u32 = 95;
/// The plate's emissivity and height above the ground, m: half-way between the solar
/// table's rows at 0 and 300 m, so that the beam is interpolated in altitude.
pub const EPSILON: f64 = 0.6;
pub const PLATE_M: f64 = 150.0;

/// A plan of a few thermal paths and the sun's beam at 0, 300 and 1000 m, as RON, over
/// wavenumbers `[v1, v2]` every `dv`, cm⁻¹.
pub fn plan_ron_over(zenith: &str, day: &str, [v1, v2, dv]: [f64; 3]) -> String {
    format!(
        "(
  name: \"sunny\",
  model: Standard(6),
  wavenumber_per_cm: ({v1:.1}, {v2:.1}, {dv:.1}),
  path_end_m: 1.0,
  observers_m: [1000.0],
  levels_m: [1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 5.0, 10.0],
  ground_sky_zenith_deg: [0.0],
  hemispheric: [],
  slant_altitude_m: [1000.0],
  slant_nadir_deg: [0.0],
  sky_altitude_m: [0.0, 1000.0],
  sky_zenith_deg: [0.0],
  sun: Some((
    zenith_deg: {zenith},
    day_of_year: {day},
    altitude_m: [0.0, 300.0, 1000.0],
  )),
)
"
    )
}

/// `irsig-atmos build` of the plan in `plan_dir` (US Standard 1976) into `out`, read back.
pub fn build(plan_dir: &Path, out: &Path) -> SpectralAtmosphere {
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(plan_dir)
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(out)
        .assert()
        .success();
    canonical::read_spectral_atmosphere("built", &std::fs::read(out).unwrap()).unwrap()
}

/// A grey, fully diffuse plate of emissivity `EPSILON` at 300 K, 200 km across, horizontal
/// at `PLATE_M` above the ground, and a 4 × 4-pixel view straight down on it from 1000 m.
/// Returns the raw scene, the materials and the view.
pub fn plate(dir: &Path) -> [PathBuf; 3] {
    let scene = dir.join("plate.raw.ron");
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
    let materials = dir.join("grey.ron");
    std::fs::write(
        &materials,
        format!(
            "(materials: [(id: 1, name: \"grey\", emissivity: [(0.0, {EPSILON:?}), \
             (90.0, {EPSILON:?})], specular_fraction: 0.0, source: \"a test\")])"
        ),
    )
    .unwrap();
    let view = dir.join("down.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (0.0, 0.0, 1000.0), target_m: (0.0, 0.0, 0.0), \
         up: (0.0, 1.0, 0.0), pixels: (4, 4), fov_deg: (1.0, 1.0))",
    )
    .unwrap();
    [scene, materials, view]
}

/// The plate's view straight down, as [`plate`] writes it, with `sun` (RON) added as its
/// last field on a line of its own (line 3, column 8).
pub fn view_with_sun(sun: &str) -> String {
    format!(
        "LookAt(position_m: (0.0, 0.0, 1000.0), target_m: (0.0, 0.0, 0.0),\n\
         up: (0.0, 1.0, 0.0), pixels: (4, 4), fov_deg: (1.0, 1.0),\n  sun: {sun},\n)\n"
    )
}
