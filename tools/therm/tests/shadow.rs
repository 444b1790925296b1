//! A roof's shadow sweeping over the ground on a June morning: the ground it has covered for
//! an hour is cooler than the open ground by what a hand estimate gives — the shadow's edge
//! found by hand geometry from the sun's direction, the cooling from the closed-form
//! response of a semi-infinite solid to a lost flux (Carslaw & Jaeger), summed over the
//! hour by Duhamel's principle.

use std::path::Path;
use std::process::Command;

use irsig_atmosphere::sun::SunSpec;

const SIGMA: f64 = 5.670_374_419e-8;
/// The roof's height, m, and its southern and northern edges, m.
const ROOF_Z: f64 = 30.0;
const ROOF_Y: (f64, f64) = (-5.0, 5.0);
/// The ground strip's cells along y, m.
const CELL: f64 = 0.25;
const Y0: f64 = -40.0;
const CELLS: usize = 480;
/// The soil: conductivity, density, specific heat (Incropera Table A.3, "soil").
const SOIL: (f64, f64, f64) = (0.52, 2050.0, 1840.0);
const ABSORPTANCE: f64 = 0.9;
const EMISSIVITY: f64 = 0.95;
const DNI: f64 = 800.0;
const AIR_K: f64 = 300.0;
const WIND: f64 = 2.0;
const DAY: &str = "2026-06-21";

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

/// The direction toward the sun at 40° N, 0° E at `hh:mm` UTC, by SPA.
fn to_sun(minutes: f64) -> [f64; 3] {
    let utc = format!(
        "{DAY}T{:02}:{:02}:{:02}Z",
        (minutes / 60.0) as u32,
        (minutes % 60.0) as u32,
        ((minutes * 60.0) % 60.0) as u32
    );
    SunSpec::At {
        utc,
        latitude_deg: 40.0,
        longitude_deg: 0.0,
        altitude_m: 0.0,
        refraction: None,
        delta_t_s: None,
        delta_ut1_s: None,
    }
    .position()
    .unwrap()
    .to_scene_direction()
}

/// Where the shadow's northern (leading) edge lies on the ground at `minutes` UTC: a ray
/// from (·, y, 0) toward the sun meets the roof's plane at y + z_roof · s_y / s_z.
fn leading_edge(minutes: f64) -> f64 {
    let s = to_sun(minutes);
    ROOF_Y.1 - ROOF_Z * s[1] / s[2]
}

fn inputs(dir: &Path) -> (String, String, String) {
    // The roof: 400 m east-west, 10 m north-south, facing down, held at the air's
    // temperature. The ground: a strip of cells 1 m wide along y.
    let mut positions = vec![
        (-200.0, ROOF_Y.0, ROOF_Z),
        (200.0, ROOF_Y.0, ROOF_Z),
        (200.0, ROOF_Y.1, ROOF_Z),
        (-200.0, ROOF_Y.1, ROOF_Z),
    ];
    let mut facets = vec![
        "(vertices: (0, 2, 1), material: 1, temperature_k: 300.0, object: 0)".to_owned(),
        "(vertices: (0, 3, 2), material: 1, temperature_k: 300.0, object: 0)".to_owned(),
    ];
    for k in 0..=CELLS {
        let y = Y0 + CELL * k as f64;
        positions.push((-0.5, y, 0.0));
        positions.push((0.5, y, 0.0));
    }
    for k in 0..CELLS {
        let (a, b, c, d) = (4 + 2 * k, 5 + 2 * k, 7 + 2 * k, 6 + 2 * k);
        facets.push(format!(
            "(vertices: ({a}, {b}, {c}), material: 2, temperature_k: 300.0, object: 1)"
        ));
        facets.push(format!(
            "(vertices: ({a}, {c}, {d}), material: 2, temperature_k: 300.0, object: 1)"
        ));
    }
    let positions: Vec<String> = positions
        .iter()
        .map(|(x, y, z)| format!("({x:?}, {y:?}, {z:?})"))
        .collect();
    let scene = write(
        dir,
        "scene.ron",
        &format!(
            "(objects: [\"roof\", \"ground\"], positions_m: [{}], facets: [{}])",
            positions.join(", "),
            facets.join(", ")
        ),
    );
    let (k, rho, c) = SOIL;
    let materials = write(
        dir,
        "mats.ron",
        &format!(
            "(materials: [
               (id: 1, name: \"roof\", emissivity: [(0.0, 1.0)], specular_fraction: 0.0, source: \"t\"),
               (id: 2, name: \"soil\", emissivity: [(0.0, {EMISSIVITY})], specular_fraction: 0.0, \
                source: \"t\", thermal: Some((layers: [(thickness_m: 1.0, conductivity_w_m_k: {k:?}, \
                density_kg_m3: {rho:?}, specific_heat_j_kg_k: {c:?}, source: \"t\")], back: \
                Temperature(temperature_k: 300.0), solar_absorptance: Some({ABSORPTANCE}), \
                thermal_emissivity: Some({EMISSIVITY}), source: \"t\")))])"
        ),
    );
    // No diffuse sunlight and a sky at the air's temperature: what a cell sees of the
    // (held, black) roof or of the sky then makes no difference, and the beam is all that
    // the shadow takes away.
    let sky = SIGMA * AIR_K.powi(4);
    let mut weather = String::from(
        "time,air_temperature[K],dew_point[K],pressure[Pa],wind_speed[m/s],dni[W/m2],dhi[W/m2],longwave_down[W/m2]\n",
    );
    for h in 0..48 {
        weather.push_str(&format!(
            "2026-06-{:02}T{:02}:00:00Z,{AIR_K},280,100000,{WIND},{DNI},0,{sky}\n",
            20 + h / 24,
            h % 24
        ));
    }
    (scene, materials, write(dir, "weather.csv", &weather))
}

/// The surface temperature drop of a semi-infinite solid of effusivity `e` (J m⁻² K⁻¹
/// s⁻½) whose surface loses heat at `h` W m⁻² K⁻¹ (linearised), `t` seconds after its
/// absorbed flux falls by 1 W m⁻² (Carslaw & Jaeger, §2.7):
/// `(1/h) (1 − exp(β²) erfc(β))`, `β = h √t / e`.
fn step_response(h: f64, e: f64, t: f64) -> f64 {
    let beta = h * t.max(0.0).sqrt() / e;
    (1.0 - (beta * beta).exp() * libm::erfc(beta)) / h
}

#[test]
fn the_ground_a_shadow_has_covered_for_an_hour_is_as_much_cooler_as_a_hand_estimate_says() {
    // The leading edge sweeps north all morning (checked each minute from 07:00 to 10:00).
    let mut last = f64::NEG_INFINITY;
    for m in 420..600 {
        let e = leading_edge(f64::from(m));
        assert!(e > last, "{m}: {e}");
        last = e;
    }
    // Compare at 09:30 UTC: cell B is the one whose centre the edge crossed at 08:30; cell
    // A lies 5 m north of where the edge is at 09:30, never yet covered.
    let (t_cover, t_compare) = (510.0, 570.0);
    let cell_of = |y: f64| ((y - Y0) / CELL).floor() as usize;
    let b = cell_of(leading_edge(t_cover) - 0.5 * CELL);
    let a = cell_of(leading_edge(t_compare) + 5.0);
    assert!(a < CELLS && b < a);
    // Still inside the shadow at 09:30: its southern edge is 10 m behind the northern.
    assert!(Y0 + CELL * b as f64 > leading_edge(t_compare) - 10.0);

    let dir = tempfile::tempdir().unwrap();
    let (scene, materials, weather) = inputs(dir.path());
    let out = Command::new(env!("CARGO_BIN_EXE_irsig-therm"))
        .args([&scene, "--materials", &materials, "--weather", &weather])
        .args(["--at", &format!("{DAY}T09:30Z"), "--spin-up-h", "24"])
        .args([
            "--latitude-deg",
            "40",
            "--longitude-deg",
            "0",
            "--hold",
            "roof=300",
        ])
        .args([
            "--step-s",
            "60",
            "--shadow-samples",
            "8",
            "--convection",
            "mcadams",
        ])
        .args(["--ground-albedo", "0", "-o"])
        .arg(dir.path().join("t"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(dir.path().join("t.raw")).unwrap();
    let scene = irsig_formats::canonical::read_raw_scene("t.raw", &bytes).unwrap();
    // Cells' facets follow the roof's two: cell k is facets 2 + 2k and 3 + 2k.
    let cell_k = |k: usize| scene.facets[2 + 2 * k].temperature_k;
    let (t_a, t_b) = (cell_k(a), cell_k(b));
    let measured = t_a - t_b;

    // The hand estimate: the flux B lost, α · DNI · cos z, minute by minute from 08:30,
    // each change of it acting through the step response (Duhamel); the surface's loss
    // coefficient McAdams' h plus the radiation's 4 ε σ T³ at the two cells' mean.
    let (k, rho, c) = SOIL;
    let effusivity = (k * rho * c).sqrt();
    let t_mean = 0.5 * (t_a + t_b);
    let h = 5.7 + 3.8 * WIND + 4.0 * EMISSIVITY * SIGMA * t_mean.powi(3);
    let lost = |m: f64| ABSORPTANCE * DNI * to_sun(m)[2];
    let mut estimate = 0.0;
    let mut previous = 0.0;
    let mut m = t_cover;
    while m < t_compare {
        let q = lost(m + 0.5);
        estimate += (q - previous) * step_response(h, effusivity, (t_compare - m) * 60.0);
        previous = q;
        m += 1.0;
    }
    assert!(measured > 5.0, "{measured}");
    assert!(
        (measured - estimate).abs() < 0.1 * estimate,
        "A {t_a:.3} K, B {t_b:.3} K: {measured:.3} K cooler in the shadow, the hand estimate {estimate:.3} K"
    );
}
