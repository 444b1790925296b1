//! What the daylight path tests share (`tests/scattered_trace.rs`, `tests/slab_trace.rs`,
//! and `tests/sunlit.rs`, which also runs the day in clear air):
//! one hazy 3.4–4.1 µm day (US Standard 1976, a rural 10 km aerosol, the sun at 30° from
//! the zenith on day 172), LOWTRAN7 run for one path under it, the band integrals of its
//! TAPE7, and `irsig-trace --probe` of one pixel looking at a plate through an atmosphere
//! built for it.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::{bin, lowtran};

/// The sun's zenith angle, degrees.
pub const SUN_ZENITH_DEG: f64 = 30.0;
/// The sun's azimuth from north toward east, degrees: the view's azimuths are measured
/// from it.
pub const SUN_AZIMUTH_DEG: f64 = 120.0;
/// Day of the year.
pub const DAY: u32 = 172;
/// The spectral grid, cm⁻¹: from, to, step. The 3.4–4.1 µm window on the grid's points,
/// where the sun's scattered light is a real share of the path radiance (outside it, the
/// 4.3 µm CO₂ and the 2.7 µm H₂O bands' emission dominates).
pub const V1: f64 = 2440.0;
pub const V2: f64 = 2940.0;
pub const DV: f64 = 10.0;
/// The band traced: the grid's span, a hair inside its ends.
pub const BAND: &str = "3.40137-4.09836";
/// LOWTRAN7's card 2 for the plans' aerosol: rural (IHAZE 1), visibility 10 km.
pub const CARD2: &str =
    "    1    0    0    0    0    0    10.000     0.000     0.000     0.000     0.000";

/// One row of an IEMSCT = 2 TAPE7: wavenumber (cm⁻¹), τ, and the thermal, scattered and
/// total radiance (W cm⁻² sr⁻¹ per cm⁻¹).
#[derive(Debug, Clone, Copy)]
pub struct Row {
    pub nu: f64,
    pub trans: f64,
    pub thermal: f64,
    pub scattered: f64,
    pub total: f64,
}

/// LOWTRAN7's card 2 without an aerosol (IHAZE 0): clear air, only Rayleigh scattering.
pub const CLEAR_CARD2: &str =
    "    0    0    0    0    0    0     0.000     0.000     0.000     0.000     0.000";

/// [`lowtran_sunlit_under`] the hazy day's aerosol ([`CARD2`]).
///
/// # Panics
/// As [`lowtran_sunlit_under`].
#[must_use]
pub fn lowtran_sunlit(itype: u32, h1_km: f64, h2_km: f64, angle_deg: f64, az_deg: f64) -> Vec<Row> {
    lowtran_sunlit_under(CARD2, itype, h1_km, h2_km, angle_deg, az_deg)
}

/// LOWTRAN7's radiance with single-scattered sunlight along one path, its aerosol card 2
/// `card2` (a deck written by columns: cards 1 and 2 `6I5,5F10.3`, 3 `6F10.3,I5`, 3A1 `4I5`
/// IPARM 2 IPH 2 IDAY ISOURC 0, 3A2 `8F10.3` PARM1 = azimuth of the line of sight from the
/// sun, PARM2 = the sun's zenith, 4, 5): `itype` 2 from `h1_km` to `h2_km`, 3 from `h1_km`
/// to space, `angle_deg` the zenith angle at `h1_km`.
///
/// # Panics
/// When LOWTRAN7 fails or its TAPE7 has no radiance columns.
#[must_use]
pub fn lowtran_sunlit_under(
    card2: &str,
    itype: u32,
    h1_km: f64,
    h2_km: f64,
    angle_deg: f64,
    az_deg: f64,
) -> Vec<Row> {
    let deck = format!(
        "    6{itype:5}    2    0    0    0    0    0    0    0    0    0    0   0.000   0.00\n\
         {card2}\n\
         {h1_km:10.3}{h2_km:10.3}{angle_deg:10.3}{:10.3}{:10.3}{:10.3}{:5}\n\
         \x20   2    2{DAY:5}    0\n\
         {az_deg:10.3}{SUN_ZENITH_DEG:10.3}{:10.3}{:10.3}{:10.3}{:10.3}{:10.3}{:10.3}\n\
         {V1:10.3}{V2:10.3}{DV:10.3}\n\
         \x20   0\n",
        0.0, 0.0, 0.0, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    );
    let t7 = crate::run_lowtran(&deck).tape7;
    let mut lines = t7
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("FREQ"));
    let header = lines.next().expect("a column header in TAPE7");
    assert!(header.contains("TOTAL RAD"), "{header}\n{deck}");
    lines
        .take_while(|l| l.trim() != "-9999.")
        .map(|l| {
            let w: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            // FREQ TRANS THERMAL PATH-SCATTERED SINGLE GROUND GROUND-SINGLE TOTAL …
            Row {
                nu: w[0],
                trans: w[1],
                thermal: w[2],
                scattered: w[3],
                total: w[7],
            }
        })
        .collect()
}

/// `∫ y_λ dλ` over the grid of a quantity per cm⁻¹ (`L_λ = L_ν ν²/10⁴`; radiances in W
/// cm⁻² sr⁻¹ become W m⁻² sr⁻¹ with the ×10⁴ that cancels it), by the trapezoid in
/// wavelength; with `per_um` false the plain `∫ y dλ` (for τ).
#[must_use]
pub fn band_integral(rows: &[Row], per_um: bool, y: impl Fn(&Row) -> f64) -> f64 {
    let nodes: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| {
            let scale = if per_um { r.nu * r.nu } else { 1.0 };
            (1e4 / r.nu, y(r) * scale)
        })
        .collect();
    nodes
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[0].0 - w[1].0))
        .sum()
}

/// A line of sight `zenith_deg` from straight up and `azimuth_deg` from the sun's azimuth
/// (scene frame: x east, y north, z up).
#[must_use]
pub fn direction(zenith_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (sz, cz) = zenith_deg.to_radians().sin_cos();
    let (sa, ca) = (SUN_AZIMUTH_DEG + azimuth_deg).to_radians().sin_cos();
    [sz * sa, sz * ca, cz]
}

/// A horizontal square 4 km across at `z_m` (material 1, 300 K), written in `dir`.
///
/// # Panics
/// When the file cannot be written.
#[must_use]
pub fn plate(dir: &Path, z_m: f64) -> PathBuf {
    let scene = dir.join(format!("plate-{z_m}.raw.ron"));
    std::fs::write(
        &scene,
        format!(
            "(objects: [\"plate\"], \
             positions_m: [(-2e3, -2e3, {z_m:?}), (2e3, -2e3, {z_m:?}), \
                           (2e3, 2e3, {z_m:?}), (-2e3, 2e3, {z_m:?})], \
             facets: [(vertices: (0, 1, 2), material: 1, temperature_k: 300.0, object: 0), \
                      (vertices: (0, 2, 3), material: 1, temperature_k: 300.0, object: 0)])"
        ),
    )
    .unwrap();
    scene
}

/// `irsig-atmos build` of `plan` (its text) with real LOWTRAN7, into `dir/NAME.spa`; says
/// how long it took and how large the file is.
///
/// # Panics
/// When the build fails.
#[must_use]
pub fn build(dir: &Path, name: &str, plan: &str) -> PathBuf {
    let p = dir.join(format!("plan-{name}"));
    std::fs::create_dir(&p).unwrap();
    std::fs::write(p.join("plan.ron"), plan).unwrap();
    let spa = dir.join(format!("{name}.spa"));
    let t = std::time::Instant::now();
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&p)
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(&spa)
        .assert()
        .success();
    eprintln!(
        "{name}: built in {:.1} s, {} bytes",
        t.elapsed().as_secs_f64(),
        std::fs::metadata(&spa).unwrap().len()
    );
    spa
}

/// The probe's terms of the one pixel of a view from `(0, 0, observer_m)` along `look`
/// (0.01° across) onto `scene` (a grey material 1, ε = 0.2) in the built atmosphere `spa`,
/// with the sun or without, and `extra` flags: `hemispheric` (L_d), `path` (L_u),
/// `radiance` (L at the sensor), W m⁻² sr⁻¹; `transmission`; `range`, m.
///
/// # Panics
/// When irsig-trace fails.
#[must_use]
pub fn probe(
    dir: &Path,
    spa: &Path,
    scene: &Path,
    (observer_m, look): (f64, [f64; 3]),
    sun: bool,
    extra: &[&str],
) -> HashMap<String, f64> {
    let view = dir.join("view.ron");
    let t = [
        look[0] * 100.0,
        look[1] * 100.0,
        observer_m + look[2] * 100.0,
    ];
    std::fs::write(
        &view,
        format!(
            "LookAt(position_m: (0.0, 0.0, {observer_m:?}), target_m: ({:?}, {:?}, {:?}), \
             up: (0.0, 0.0, 1.0), pixels: (1, 1), fov_deg: (0.01, 0.01))",
            t[0], t[1], t[2]
        ),
    )
    .unwrap();
    let materials = dir.join("materials.ron");
    std::fs::write(
        &materials,
        "(materials: [(id: 1, name: \"grey\", emissivity: [(0.0, 0.2), (90.0, 0.2)], \
         specular_fraction: 0.0, source: \"a test\")])",
    )
    .unwrap();
    let mut cmd = bin("irsig-trace");
    cmd.arg("--scene")
        .arg(scene)
        .arg("--materials")
        .arg(&materials)
        .arg("--view")
        .arg(&view)
        .arg("--atmosphere")
        .arg(spa)
        .args(["--band", BAND, "--probe", "0,0"])
        .args(extra);
    // The band model, whose terms are the tables' band averages that LOWTRAN7's are
    // compared with (by day the tracer's default is 16 sub-bands).
    if !extra.contains(&"--sub-bands") {
        cmd.args(["--sub-bands", "1"]);
    }
    if sun {
        cmd.args(["--sun-zenith-deg", &SUN_ZENITH_DEG.to_string()])
            .args(["--sun-azimuth-deg", &SUN_AZIMUTH_DEG.to_string()]);
    }
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let mut terms = HashMap::new();
    for line in text.lines() {
        for (label, key) in [
            ("L_d hemispheric", "hemispheric"),
            ("L_u (W m-2 sr-1)", "path"),
            ("L at sensor (W m-2 sr-1)", "radiance"),
            ("τ ", "transmission"),
            ("range_m", "range"),
        ] {
            if let Some(rest) = line.strip_prefix(label) {
                terms.insert(key.to_owned(), rest.trim().parse::<f64>().unwrap());
            }
        }
    }
    terms
}
