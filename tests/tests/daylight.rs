//! Daylight, with real LOWTRAN7 runs:
//!
//! - **Day in LWIR**: the sun's share of the radiance of a grey, diffuse plate of
//!   emissivity 0.95 at 300 K, seen straight down from 1 km, at several sun zeniths, in
//!   8–14 µm and (for contrast) 3–5 µm: the sunlight the tracer adds against a hand
//!   integral over the built atmosphere's own spectra, and the share tabled
//!   (docs/accuracy.md, "The sun's share by day").
//! - **MWIR**: a low-ε metal plate (aluminium, Rakić 1995) whose 3–5 µm radiance is mostly
//!   reflected sunlight, against `∫ τ_path (ε B(T) + (1 − ε)(E_sun cos θ/π + L_sky)) +
//!   L_path` integrated by hand over the file's spectra, ε from Fresnel's equations at
//!   normal incidence on the published n, k.
//! - **The daylight pipeline** (`pipelines/daylight.ron`) end to end, through its README's
//!   recipe as written (`irsig_tests::recipe`), and its generator's recipe: its run time; the
//!   car's shadow on the clay track where hand geometry puts it, and the sunlit ground's
//!   3–5 µm excess `τ (1 − ε) E cos θ/π` with E by hand; the pool's glint within the sun's
//!   disk; the sun's share small in 8–14 µm; the library is what its generator makes; and
//!   the README's picture (`docs/daylight.png`) is what the pipeline makes now.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH: these tests fail when it is
//! missing, saying so; they never skip.

// Material ids, table nodes and the sun's zenith are exact values stored as floats.
#![allow(clippy::float_cmp)]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Instant;

use irsig_formats::canonical;
use irsig_model::SpectralAtmosphere;
use irsig_raster::Raster;
use irsig_tests::{bin, lowtran, recipe, repo_root};

/// CODATA 2018: Planck constant (J s), speed of light (m/s), Boltzmann constant (J/K).
const H: f64 = 6.626_070_15e-34;
const C: f64 = 299_792_458.0;
const K_B: f64 = 1.380_649e-23;

/// Blackbody spectral radiance, W m⁻² sr⁻¹ µm⁻¹, at `um` micrometres and `t` kelvin.
fn planck_per_um(um: f64, t: f64) -> f64 {
    let l = um * 1e-6;
    2.0 * H * C * C / l.powi(5) / ((H * C / (l * K_B * t)).exp() - 1.0) * 1e-6
}

/// The plate's height, m: the slant paths' lower end (LOWTRAN's 1 m), where the table's
/// node is the path exactly, and a row of the solar table.
const PLATE_M: f64 = 1.0;
/// The observer's height, m: a row of the slant table, looking straight down (a node).
const OBSERVER_M: f64 = 1000.0;
/// The day of the year of the sun (5 April: the Earth at about its mean distance).
const DAY: u32 = 95;

/// A plan of the few paths a plate seen straight down from 1 km needs, and the sun at
/// `zenith_deg` at 0 m, the plate's 1 m and 1 km, over 710–3335 cm⁻¹ (3–14 µm) every 5.
fn plan_ron(zenith_deg: f64) -> String {
    let hemispheric = hemispheric_rule();
    format!(
        "(
  name: \"plate\",
  model: Standard(6),
  wavenumber_per_cm: (710.0, 3335.0, 5.0),
  path_end_m: {PLATE_M:?},
  observers_m: [{OBSERVER_M:?}],
  levels_m: [{OBSERVER_M:?}],
  correction_altitude_m: {OBSERVER_M:?},
  correction_nadir_deg: [0.0, 5.0, 10.0],
  ground_sky_zenith_deg: [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 85.0, 90.0],
  hemispheric: [{hemispheric}],
  slant_altitude_m: [{OBSERVER_M:?}],
  slant_nadir_deg: [0.0],
  sky_altitude_m: [0.0],
  sky_zenith_deg: [0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 85.0, 90.0],
  sun: Some((zenith_deg: {zenith_deg:?}, day_of_year: {DAY}, altitude_m: [0.0, {PLATE_M:?}, {OBSERVER_M:?}])),
)
"
    )
}

/// The hemispheric sky's quadrature (thesis eq. 5, `L = ∫ L(μ) 2μ dμ` over μ = cos θ in
/// 0–1): the 4-point Gauss–Legendre rule mapped to 0–1, as `(zenith_deg, weight)` with the
/// zenith rounded to the 0.001° a deck holds and the weight `2 w μ` at it.
fn hemispheric_rule() -> String {
    const RULE: [(f64, f64); 4] = [
        (-0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
        (-0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
        (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
        (0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
    ];
    let mut nodes: Vec<(f64, f64)> = RULE
        .iter()
        .map(|&(x, w)| {
            let mu: f64 = f64::midpoint(x, 1.0);
            let zenith = (mu.acos().to_degrees() * 1000.0).round() / 1000.0;
            (zenith, w * zenith.to_radians().cos())
        })
        .collect();
    nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
    nodes
        .iter()
        .map(|(z, w)| format!("({z:?}, {w:?})"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `irsig-atmos build` of [`plan_ron`] for the sun at `zenith_deg`, into `dir`.
fn build(dir: &Path, zenith_deg: f64) -> (PathBuf, SpectralAtmosphere) {
    let plan = dir.join(format!("plan-{zenith_deg}.ron"));
    std::fs::write(&plan, plan_ron(zenith_deg)).unwrap();
    let out = dir.join(format!("sun-{zenith_deg}.spa"));
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&plan)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let a = canonical::read_spectral_atmosphere("built", &std::fs::read(&out).unwrap()).unwrap();
    (out, a)
}

/// The plate (2 km across, horizontal at [`PLATE_M`], material 1 at `t_k`) and a 4 × 4
/// view of 1° straight down on it from [`OBSERVER_M`], in `dir`.
fn plate(dir: &Path, t_k: f64) -> [PathBuf; 2] {
    let scene = dir.join("plate.raw.ron");
    std::fs::write(
        &scene,
        format!(
            "(objects: [\"plate\"], \
             positions_m: [(-1e3, -1e3, {PLATE_M:?}), (1e3, -1e3, {PLATE_M:?}), \
                           (1e3, 1e3, {PLATE_M:?}), (-1e3, 1e3, {PLATE_M:?})], \
             facets: [(vertices: (0, 1, 2), material: 1, temperature_k: {t_k:?}, object: 0), \
                      (vertices: (0, 2, 3), material: 1, temperature_k: {t_k:?}, object: 0)])"
        ),
    )
    .unwrap();
    let view = dir.join("down.ron");
    std::fs::write(
        &view,
        format!(
            "LookAt(position_m: (0.0, 0.0, {OBSERVER_M:?}), target_m: (0.0, 0.0, 0.0), \
             up: (0.0, 1.0, 0.0), pixels: (4, 4), fov_deg: (1.0, 1.0))"
        ),
    )
    .unwrap();
    [scene, view]
}

/// The mean radiance, W m⁻² sr⁻¹, of the plate traced in `band` through `atmosphere`,
/// with the sun at `sun` (zenith, azimuth in degrees) or without, and `extra` flags.
fn trace_plate(
    dir: &Path,
    materials: &Path,
    atmosphere: &Path,
    band: &str,
    sun: Option<(f64, f64)>,
    extra: &[&str],
) -> f64 {
    let [scene, view] = plate(dir, 300.0);
    let prefix = dir.join("plate");
    let mut cmd = bin("irsig-trace");
    cmd.arg("--scene")
        .arg(scene)
        .arg("--materials")
        .arg(materials)
        .arg("--view")
        .arg(view)
        .arg("--atmosphere")
        .arg(atmosphere)
        .args(["--band", band])
        .args(extra)
        .arg("-o")
        .arg(&prefix);
    if let Some((z, a)) = sun {
        cmd.args(["--sun-zenith-deg", &z.to_string()])
            .args(["--sun-azimuth-deg", &a.to_string()]);
    }
    cmd.assert().success();
    let r = exr(&dir.join("plate.radiance.exr"));
    let data = &r.layer("radiance").unwrap().data;
    data.iter().map(|&v| f64::from(v)).sum::<f64>() / data.len() as f64
}

fn exr(path: &Path) -> Raster {
    irsig_raster::read_exr(
        &std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())),
    )
    .unwrap()
}

/// The spectra of a built plate atmosphere at the plate's node, per µm at the grid's
/// wavelengths: path τ and path radiance (observer 1 km, nadir 0, down to 1 m), the direct
/// solar irradiance on a surface normal to the beam at 1 m, and the hemispheric sky at the
/// ground. Densities per cm⁻¹ become per µm as `y_λ = y_ν ν² / 10⁴`.
struct Spectra {
    um: Vec<f64>,
    tau: Vec<f64>,
    path_per_um: Vec<f64>,
    sun_normal_per_um: Vec<f64>,
    sky_hemi_per_um: Vec<f64>,
}

impl Spectra {
    fn of(a: &SpectralAtmosphere) -> Self {
        let n = a.grid.points.len();
        let slant = a.slant.as_ref().expect("a slant table");
        assert_eq!(
            (
                slant.altitude_m.as_slice(),
                slant.nadir_deg.as_slice(),
                slant.ground_m
            ),
            (&[OBSERVER_M][..], &[0.0][..], Some(PLATE_M))
        );
        let solar = a.solar.as_ref().expect("a solar table");
        let row = solar.altitude_m.iter().position(|&h| h == PLATE_M).unwrap();
        let hemi = a
            .sky_hemispheric_w_m2_sr_per_unit
            .as_ref()
            .expect("a hemispheric sky");
        let per_um = |nu: f64, y: f32| f64::from(y) * nu * nu / 1e4;
        let mut s = Self {
            um: Vec::with_capacity(n),
            tau: Vec::with_capacity(n),
            path_per_um: Vec::with_capacity(n),
            sun_normal_per_um: Vec::with_capacity(n),
            sky_hemi_per_um: Vec::with_capacity(n),
        };
        for (i, &nu) in a.grid.points.iter().enumerate() {
            s.um.push(1e4 / nu);
            s.tau.push(f64::from(slant.transmission[i]));
            s.path_per_um
                .push(per_um(nu, slant.path_radiance_w_m2_sr_per_unit[i]));
            s.sun_normal_per_um.push(
                per_um(nu, solar.extraterrestrial_w_m2_per_unit[i])
                    * f64::from(solar.transmission[row * n + i]),
            );
            s.sky_hemi_per_um.push(per_um(nu, hemi[i]));
        }
        s
    }

    /// `∫ f(i) dλ` over `[lo_um, hi_um]`, `f` a density per µm at grid point `i`: the
    /// trapezoid in wavelength over the points inside, closed at each edge by a value
    /// linear in wavenumber between the two points around it (the rule of
    /// formats/canonical/spectral-atmosphere.md).
    fn integral(&self, lo_um: f64, hi_um: f64, f: impl Fn(usize) -> f64) -> f64 {
        let mut pts: Vec<(f64, f64)> = (0..self.um.len())
            .filter(|&i| self.um[i] > lo_um * (1.0 + 1e-12) && self.um[i] < hi_um * (1.0 - 1e-12))
            .map(|i| (self.um[i], f(i)))
            .collect();
        let edge = |um: f64| -> (f64, f64) {
            let nu = 1e4 / um;
            // The grid runs in increasing wavenumber.
            let k = self.um.iter().position(|&l| 1e4 / l >= nu - 1e-9).unwrap();
            if (1e4 / self.um[k] - nu).abs() < 1e-9 {
                return (um, f(k));
            }
            let (nu0, nu1) = (1e4 / self.um[k - 1], 1e4 / self.um[k]);
            let t = (nu - nu0) / (nu1 - nu0);
            (um, f(k - 1) + t * (f(k) - f(k - 1)))
        };
        pts.push(edge(lo_um));
        pts.push(edge(hi_um));
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts.windows(2)
            .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
            .sum()
    }
}

/// A library of one diffuse material, id 1: grey `epsilon`, or the spectrum `(µm, ε)`.
fn material(dir: &Path, name: &str, epsilon: f64, spectrum: Option<&[(f64, f64)]>) -> PathBuf {
    let spectral = spectrum.map_or_else(String::new, |s| {
        let (um, e): (Vec<f64>, Vec<f64>) = s.iter().copied().unzip();
        format!(", spectral: Some((wavelength_um: {um:?}, emissivity: {e:?}))")
    });
    let path = dir.join(format!("{name}.ron"));
    std::fs::write(
        &path,
        format!(
            "(materials: [(id: 1, name: \"{name}\", emissivity: [(0.0, {epsilon:?}), \
             (90.0, {epsilon:?})], specular_fraction: 0.0, source: \"a test\"{spectral})])"
        ),
    )
    .unwrap();
    path
}

/// Day in LWIR: the sun's share of a 300 K plate of emissivity 0.95, by zenith and band.
#[test]
fn the_suns_share_of_a_300_k_plate_of_emissivity_0_95_is_small_in_8_14_um() {
    const EPSILON: f64 = 0.95;
    let start = Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let grey = material(dir.path(), "grey", EPSILON, None);
    let mut rows = Vec::new();
    for zenith in [0.0, 30.0, 60.0, 75.0] {
        let (spa, a) = build(dir.path(), zenith);
        let s = Spectra::of(&a);
        let cos = f64::to_radians(zenith).cos();
        for (band, lo, hi) in [("8-14", 8.0, 14.0), ("3-5", 3.0, 5.0)] {
            // The sunlight the plate reflects to the observer, by hand over the spectra.
            let sun = s.integral(lo, hi, |i| {
                s.tau[i] * (1.0 - EPSILON) * s.sun_normal_per_um[i] * cos / std::f64::consts::PI
            });
            let mut errors = [0.0; 2];
            let mut night_full = 0.0;
            for (k, extra) in [&["--sub-bands", "1"][..], &["--sub-bands", "full"][..]]
                .iter()
                .enumerate()
            {
                let night = trace_plate(dir.path(), &grey, &spa, band, None, extra);
                let day = trace_plate(dir.path(), &grey, &spa, band, Some((zenith, 0.0)), extra);
                errors[k] = (day - night) / sun - 1.0;
                night_full = night;
            }
            let share = sun / (night_full + sun);
            eprintln!(
                "zenith {zenith:>4} deg, {band:>4} um: without the sun {night_full:.5} W m-2 \
                 sr-1, the sun adds {sun:.6} by hand, share {:.4} %; traced with one \
                 sub-band {:+.2e}, with one per grid interval {:+.2e}",
                share * 100.0,
                errors[0],
                errors[1]
            );
            // One sub-band per interval of the grid is the spectral integral, up to the
            // averaging within each 5 cm-1 interval.
            assert!(
                errors[1].abs() < 2e-3,
                "zenith {zenith}, {band} um, full: {:+.3e}",
                errors[1]
            );
            // One sub-band sends the sunlight through the path's τ weighted by the sunlight
            // (docs/accuracy.md, "Sub-bands by day"): the spectral integral too, at this
            // path, which is a row of the slant table. (The band's τ alone, weighted for the
            // emission, missed the covariance of τ_path and τ_sun, which share the same CO2
            // and water bands: 7-26 % low.)
            assert!(
                errors[0].abs() < 2e-3,
                "zenith {zenith}, {band} um, one sub-band: {:+.3e}",
                errors[0]
            );
            rows.push((zenith, band, share));
        }
    }
    for (zenith, band, share) in &rows {
        // (1 − ε) E cos θ/π against ε B(300 K): in 8–14 µm the sun's irradiance is a
        // few W m⁻², a 300 K body's exitance there over 100, and 1 − ε = 0.05.
        if *band == "8-14" {
            assert!(*share < 0.005, "zenith {zenith}: {share}");
        }
    }
    // In 3–5 µm the overhead sun's share is at least ten times its 8–14 µm share.
    assert!(rows[1].2 > 10.0 * rows[0].2, "{rows:?}");
    let secs = start.elapsed().as_secs_f64();
    eprintln!("four builds, thirty-two traces: {secs:.1} s");
}

/// Normal-incidence Fresnel emissivity `1 − |(N − 1)/(N + 1)|²` of `N = n + ik`.
fn fresnel_normal(n: f64, k: f64) -> f64 {
    1.0 - ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k)
}

/// MWIR: a low-ε metal plate lit by the sun, against a hand computation.
#[test]
fn an_aluminium_plate_in_3_5_um_is_mostly_reflected_sunlight_as_computed_by_hand() {
    const ZENITH: f64 = 30.0;
    const T_K: f64 = 300.0;
    let dir = tempfile::tempdir().unwrap();
    // ε(λ) of aluminium at the published n, k rows (Rakić 1995), by hand.
    let nk = std::fs::read_to_string(repo_root().join("pipelines/daylight/aluminium-rakic-nk.txt"))
        .unwrap();
    let spectrum: Vec<(f64, f64)> = nk
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            (v[0], fresnel_normal(v[1], v[2]))
        })
        .collect();
    let eps_at = |um: f64| {
        let k = spectrum
            .partition_point(|p| p.0 <= um)
            .clamp(1, spectrum.len() - 1);
        let (a, b) = (spectrum[k - 1], spectrum[k]);
        a.1 + (um - a.0) / (b.0 - a.0) * (b.1 - a.1)
    };
    let normal = eps_at(4.0);
    let metal = material(dir.path(), "aluminium", normal, Some(&spectrum));
    let (spa, a) = build(dir.path(), ZENITH);
    let s = Spectra::of(&a);
    let cos = ZENITH.to_radians().cos();
    let pi = std::f64::consts::PI;
    let (lo, hi) = (3.0, 5.0);
    let emitted = s.integral(lo, hi, |i| {
        s.tau[i] * eps_at(s.um[i]) * planck_per_um(s.um[i], T_K)
    });
    let sunlight = s.integral(lo, hi, |i| {
        s.tau[i] * (1.0 - eps_at(s.um[i])) * s.sun_normal_per_um[i] * cos / pi
    });
    let sky = s.integral(lo, hi, |i| {
        s.tau[i] * (1.0 - eps_at(s.um[i])) * s.sky_hemi_per_um[i]
    });
    let path = s.integral(lo, hi, |i| s.path_per_um[i]);
    let by_hand = emitted + sunlight + sky + path;
    assert!(
        sunlight > 0.5 * by_hand,
        "sunlight {sunlight} of {by_hand}: not dominated by the sun"
    );
    let mut worst = Vec::new();
    for (label, extra, tolerance) in [
        // One sub-band per interval of the grid: the spectral integral, up to the
        // averaging within each 5 cm⁻¹ interval.
        (
            "one sub-band per grid interval",
            &["--sub-bands", "full"][..],
            2e-3,
        ),
        // The default by day, 16 sub-bands.
        ("the default (16 sub-bands)", &[][..], 5e-3),
        // One sub-band: the sunlight through its own τ, but τ_path, ε and the sky each
        // averaged over 3–5 µm, their covariance missed (docs/accuracy.md, "Sub-bands by
        // day").
        ("one sub-band", &["--sub-bands", "1"][..], 0.05),
    ] {
        let traced = trace_plate(dir.path(), &metal, &spa, "3-5", Some((ZENITH, 0.0)), extra);
        let error = traced / by_hand - 1.0;
        eprintln!(
            "aluminium (eps {normal:.4} at 4 um), 300 K, sun at {ZENITH} deg, 3-5 um, {label}: \
             traced {traced:.6} W m-2 sr-1, by hand {by_hand:.6} (emitted {emitted:.6}, \
             sunlight {sunlight:.6}, sky {sky:.6}, path {path:.6}): {error:+.2e}"
        );
        assert!(
            error.abs() < tolerance,
            "{label}: traced {traced}, by hand {by_hand} ({error:+.3e})"
        );
        worst.push(error);
    }
}

/// Sub-bands by day: a grey plate of ε 0.3 at 300 K under the sun at 60°, in 3–5 and 8–14
/// µm, at 1, 2, 4, 8 and 16 sub-bands against the full grid. The sunlight is the spectral
/// integral's at every count (the sub-bands cost it nothing); the whole radiance's error
/// in kelvin shrinks as the count grows (in 8–14 µm from 2 on: at 2 the reflected sky's
/// own product of averages, the same at night, is larger than at 1); and the default by
/// day, 16, is within 0.3 K.
#[test]
fn by_day_more_sub_bands_never_cost_more_and_the_default_is_within_0_3_k() {
    const EPSILON: f64 = 0.3;
    const ZENITH: f64 = 60.0;
    /// What a count may lose against the one before it, K: the f32 images and the
    /// emission's Planck weight at 300 K (docs/accuracy.md, "Sub-bands by day").
    const SLACK_K: f64 = 0.02;
    let dir = tempfile::tempdir().unwrap();
    let grey = material(dir.path(), "grey", EPSILON, None);
    let (spa, _) = build(dir.path(), ZENITH);
    let sun = Some((ZENITH, 0.0));
    for (band, lo, hi) in [("3-5", 3.0, 5.0), ("8-14", 8.0, 14.0)] {
        let model = irsig_radiometry::Band::new(lo, hi).unwrap();
        let kelvin = |radiance: f64| model.temperature(radiance);
        let full = ["--sub-bands", "full"];
        let day_full = trace_plate(dir.path(), &grey, &spa, band, sun, &full);
        let sunlight_full = day_full - trace_plate(dir.path(), &grey, &spa, band, None, &full);
        let mut errors_k = Vec::new();
        for count in ["1", "2", "4", "8", "16"] {
            let asked = ["--sub-bands", count];
            let day = trace_plate(dir.path(), &grey, &spa, band, sun, &asked);
            let night = trace_plate(dir.path(), &grey, &spa, band, None, &asked);
            let sunlight_error = (day - night) / sunlight_full - 1.0;
            let error_k = kelvin(day) - kelvin(day_full);
            eprintln!(
                "{band} um, eps {EPSILON}, sun at {ZENITH} deg, {count:>2} sub-band(s): \
                 {error_k:+.3} K against the full grid, the sunlight {sunlight_error:+.2e}"
            );
            assert!(
                sunlight_error.abs() < 2e-3,
                "{band} um, {count} sub-bands: the sunlight {sunlight_error:+.3e}"
            );
            errors_k.push(error_k.abs());
        }
        let from = if band == "8-14" { 1 } else { 0 };
        for k in from + 1..errors_k.len() {
            assert!(
                errors_k[k] <= errors_k[k - 1] + SLACK_K,
                "{band} um: {errors_k:?} K grows at count {k}"
            );
        }
        let default = trace_plate(dir.path(), &grey, &spa, band, sun, &[]);
        let error_k = kelvin(default) - kelvin(day_full);
        eprintln!("{band} um, the default by day: {error_k:+.3} K");
        assert!(
            error_k.abs() <= 0.3,
            "{band} um, the default: {error_k:+.3} K"
        );
        let sixteen = trace_plate(dir.path(), &grey, &spa, band, sun, &["--sub-bands", "16"]);
        assert!((default - sixteen).abs() <= 1e-12 * sixteen);
    }
}

/// The daylight pipeline's recipe (`pipelines/daylight/README.md`), run once as written
/// (LOWTRAN7's installer, then `irsig-run`) in a scratch copy of the clone, and how long
/// it took, s.
struct Daylight {
    dir: tempfile::TempDir,
    secs: f64,
}

impl Daylight {
    fn out(&self, name: &str) -> PathBuf {
        self.dir.path().join("out/daylight").join(name)
    }

    fn exr(&self, name: &str) -> Raster {
        exr(&self.out(name))
    }
}

fn daylight() -> &'static Daylight {
    static RUN: OnceLock<Daylight> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = recipe::scratch_root();
        let block = recipe::block(
            "pipelines/daylight/README.md",
            "export IRSIG_LOWTRAN=\"$(sh scripts/atmosphere/install-lowtran.sh)\"   # LOWTRAN7's path",
        );
        // Built before the clock starts: the run is timed, not the build.
        let _ = recipe::tools_dir();
        let start = Instant::now();
        recipe::run_ok(&block, dir.path(), &[]);
        let secs = start.elapsed().as_secs_f64();
        eprintln!("the daylight recipe: {secs:.1} s");
        Daylight { dir, secs }
    })
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

/// The quickstart camera (`pipelines/quickstart/view.ron`) as a pinhole, here by hand:
/// pixel (c, r) looks along `f + u·right + v·up`, `u = (2(c + ½)/W − 1)·tan(fov_x/2)`,
/// `v = (1 − 2(r + ½)/H)·tan(fov_y/2)` (formats/canonical/view.md).
struct Camera {
    eye: [f64; 3],
    forward: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    tan_half: [f64; 2],
    pixels: [usize; 2],
}

impl Camera {
    fn quickstart() -> Self {
        let text =
            std::fs::read_to_string(repo_root().join("pipelines/quickstart/view.ron")).unwrap();
        let irsig_model::View::LookAt {
            position_m,
            target_m,
            pixels,
            fov_deg,
            ..
        } = ron::from_str(&text).unwrap()
        else {
            panic!("the quickstart view is a LookAt view");
        };
        let forward = unit(sub(target_m, position_m));
        let right = unit(cross(forward, [0.0, 0.0, 1.0]));
        Self {
            eye: position_m,
            forward,
            right,
            up: cross(right, forward),
            tan_half: [
                (fov_deg[0].to_radians() / 2.0).tan(),
                (fov_deg[1].to_radians() / 2.0).tan(),
            ],
            pixels: [pixels[0] as usize, pixels[1] as usize],
        }
    }

    fn direction(&self, col: usize, row: usize) -> [f64; 3] {
        let u = (2.0 * (col as f64 + 0.5) / self.pixels[0] as f64 - 1.0) * self.tan_half[0];
        let v = (1.0 - 2.0 * (row as f64 + 0.5) / self.pixels[1] as f64) * self.tan_half[1];
        unit([
            self.forward[0] + u * self.right[0] + v * self.up[0],
            self.forward[1] + u * self.right[1] + v * self.up[1],
            self.forward[2] + u * self.right[2] + v * self.up[2],
        ])
    }
}

/// The sun of the pipeline: 70° from the zenith, due north (+y).
const NOON_ZENITH_DEG: f64 = 70.0;
fn to_sun() -> [f64; 3] {
    let z = NOON_ZENITH_DEG.to_radians();
    [0.0, z.sin(), z.cos()]
}

/// Whether the ray from `p` towards `dir` meets the box `[lo, hi]` (the slab test).
fn hits_box(p: [f64; 3], dir: [f64; 3], lo: [f64; 3], hi: [f64; 3]) -> bool {
    let (mut near, mut far) = (0.0_f64, f64::INFINITY);
    for a in 0..3 {
        if dir[a].abs() < 1e-12 {
            if p[a] < lo[a] || p[a] > hi[a] {
                return false;
            }
            continue;
        }
        let (t0, t1) = ((lo[a] - p[a]) / dir[a], (hi[a] - p[a]) / dir[a]);
        near = near.max(t0.min(t1));
        far = far.min(t0.max(t1));
    }
    near <= far
}

/// Whether the ground point `p` is in the shadow of the panel or the car
/// (`pipelines/quickstart/scene.ron`: the panel x −3..3, y 0..0.1, z 0..2.5 m; the car
/// x 6..8, y 4..8.5, z 0..1.4 m), by hand geometry.
fn in_shadow(p: [f64; 3]) -> bool {
    let s = to_sun();
    hits_box(p, s, [-3.0, 0.0, 0.0], [3.0, 0.1, 2.5])
        || hits_box(p, s, [6.0, 4.0, 0.0], [8.0, 8.5, 1.4])
}

/// The direct solar irradiance, W m⁻², on a surface normal to the beam at the ground,
/// over `[lo_um, hi_um]`, by hand from the atmosphere file's solar spectra.
fn direct_at_ground(a: &SpectralAtmosphere, lo_um: f64, hi_um: f64) -> f64 {
    let solar = a.solar.as_ref().expect("a solar table");
    let n = a.grid.points.len();
    let row = solar.altitude_m.iter().position(|&h| h == 0.0).unwrap();
    let s = Spectra {
        um: a.grid.points.iter().map(|nu| 1e4 / nu).collect(),
        tau: vec![0.0; n],
        path_per_um: vec![0.0; n],
        sun_normal_per_um: (0..n)
            .map(|i| {
                let nu = a.grid.points[i];
                f64::from(solar.extraterrestrial_w_m2_per_unit[i]) * nu * nu / 1e4
                    * f64::from(solar.transmission[row * n + i])
            })
            .collect(),
        sky_hemi_per_um: vec![0.0; n],
    };
    s.integral(lo_um, hi_um, |i| s.sun_normal_per_um[i])
}

/// The radiance at the sensor of pixel (`col`, `row`) of the pipeline's view by day in
/// `band`, traced with one sub-band per grid interval (`irsig-trace --probe`).
fn probe_full(run: &Daylight, band: &str, col: usize, row: usize) -> f64 {
    let pipelines = run.dir.path().join("pipelines");
    let out = bin("irsig-trace")
        .arg("--scene")
        .arg(run.out("scene.raw"))
        .arg("--materials")
        .arg(pipelines.join("daylight/materials.ron"))
        .arg("--view")
        .arg(pipelines.join("quickstart/view.ron"))
        .arg("--atmosphere")
        .arg(run.out("noon.spa"))
        .args([
            "--band",
            band,
            "--sun-zenith-deg",
            "70",
            "--sun-azimuth-deg",
            "0",
        ])
        .args(["--sub-bands", "full", "--probe", &format!("{col},{row}")])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).into_owned();
    text.lines()
        .find(|l| l.starts_with("L at sensor"))
        .and_then(|l| l.split_whitespace().last())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no radiance at the sensor in: {text}"))
}

#[test]
fn the_daylight_pipeline_lights_the_scene_as_hand_geometry_and_the_atmosphere_say() {
    // Its time is said below, not held: speed is the benchmarks' to measure.
    let run = daylight();
    let a = canonical::read_spectral_atmosphere(
        "noon.spa",
        &std::fs::read(run.out("noon.spa")).unwrap(),
    )
    .unwrap();
    assert_eq!(a.solar.as_ref().unwrap().zenith_deg, NOON_ZENITH_DEG);
    let e_mwir = direct_at_ground(&a, 3.0, 5.0);
    let cos = NOON_ZENITH_DEG.to_radians().cos();
    let camera = Camera::quickstart();
    let [w, h] = camera.pixels;
    let day = run.exr("mwir-day.radiance.exr");
    let nosun = run.exr("mwir-nosun.radiance.exr");
    let truth = run.exr("mwir-day.truth.exr");
    let lwir_day = run.exr("lwir-day.radiance.exr");
    let lwir_nosun = run.exr("lwir-nosun.radiance.exr");
    let layer = |r: &Raster, name: &str| -> Vec<f64> {
        r.layer(name)
            .unwrap_or_else(|| panic!("no layer {name}"))
            .data
            .iter()
            .map(|&v| f64::from(v))
            .collect()
    };
    let (l_day, l_nosun) = (layer(&day, "radiance"), layer(&nosun, "radiance"));
    let (lw_day, lw_nosun) = (layer(&lwir_day, "radiance"), layer(&lwir_nosun, "radiance"));
    let ids = layer(&truth, "material_primary");
    let irradiance = layer(&truth, "solar_irradiance");
    let visible = layer(&truth, "sun_visible_fraction");
    let sun = to_sun();
    let disk_deg = 0.533 / 2.0;
    let (mut shaded, mut sunlit, mut glints, mut dark_water) = (0, 0, 0, 0);
    let mut worst_sunlit = 0.0_f64;
    let mut max_lwir_share = 0.0_f64;
    let mut min_mwir_share = f64::INFINITY;
    for row in 0..h {
        for col in 0..w {
            let p = row * w + col;
            let d = camera.direction(col, row);
            if d[2] >= 0.0 {
                continue;
            }
            let t = -camera.eye[2] / d[2];
            let ground = [camera.eye[0] + t * d[0], camera.eye[1] + t * d[1], 0.0];
            let added = l_day[p] - l_nosun[p];
            match ids[p] {
                // Diffuse ground, clay or grass, where the centre ray meets the ground
                // (not the panel or the car): shadow by hand, with a margin of 0.2 m so
                // that the pixel's centre is clearly on one side of the shadow's edge.
                1.0 | 3.0
                    if !hits_box(camera.eye, d, [-3.0, 0.0, 0.0], [3.0, 0.1, 2.5])
                        && !hits_box(camera.eye, d, [6.0, 4.0, 0.0], [8.0, 8.5, 1.4]) =>
                {
                    let around: Vec<bool> =
                        [(0.0, 0.0), (0.2, 0.0), (-0.2, 0.0), (0.0, 0.2), (0.0, -0.2)]
                            .iter()
                            .map(|(dx, dy)| in_shadow([ground[0] + dx, ground[1] + dy, 0.0]))
                            .collect();
                    if around.iter().all(|&s| s) {
                        // Only the sky lights it, by day as without the sun.
                        assert!(
                            added.abs() <= 1e-6 * l_day[p],
                            "pixel ({col}, {row}) at {ground:?} is in the shade by hand, \
                             yet the sun adds {added}"
                        );
                        shaded += 1;
                    } else if around.iter().all(|&s| !s) {
                        // The whole disk, and the beam's irradiance on the level ground
                        // `E cos θ` with E by hand; the sun adds sunlight and nothing else.
                        let expected = e_mwir * cos;
                        let error = irradiance[p] / expected - 1.0;
                        worst_sunlit = worst_sunlit.max(error.abs());
                        assert!(
                            error.abs() < 1e-4 && visible[p] == 1.0 && added > 0.0,
                            "pixel ({col}, {row}) at {ground:?}, sunlit: the beam's \
                             irradiance {}, by hand {expected} ({error:+.2e}); visible {}; \
                             the sun adds {added}",
                            irradiance[p],
                            visible[p]
                        );
                        sunlit += 1;
                        min_mwir_share = min_mwir_share.min(added / l_day[p]);
                        let lw = (lw_day[p] - lw_nosun[p]) / lw_day[p];
                        max_lwir_share = max_lwir_share.max(lw);
                    }
                }
                // The pool, a mirror: the sun only where the reflected ray falls within
                // the disk.
                2.0 => {
                    let r = [d[0], d[1], -d[2]];
                    let off = dot(r, sun).clamp(-1.0, 1.0).acos().to_degrees();
                    if off < disk_deg - 0.05 {
                        assert!(
                            added > 10.0 * l_nosun[p],
                            "pixel ({col}, {row}): the mirrored sun is {off} deg from \
                             its centre, and adds only {added} to {}",
                            l_nosun[p]
                        );
                        glints += 1;
                    } else if off > disk_deg + 0.1 {
                        assert!(
                            added.abs() <= 1e-6 * l_day[p],
                            "pixel ({col}, {row}): the mirrored sun is {off} deg away, yet \
                             the sun adds {added}"
                        );
                        dark_water += 1;
                    }
                }
                _ => {}
            }
        }
    }
    eprintln!(
        "3-5 um direct irradiance at the ground {e_mwir:.4} W m-2 (normal to the beam); \
         {shaded} shaded and {sunlit} sunlit ground pixels (worst {worst_sunlit:.2e} from \
         E cos by hand), {glints} glint pixels, {dark_water} water pixels without; \
         the sun's share of sunlit ground: at least {:.2} % in 3-5 um, at most {:.3} % in \
         8-14 um; run {:.1} s",
        min_mwir_share * 100.0,
        max_lwir_share * 100.0,
        run.secs
    );
    assert!(
        shaded >= 100 && sunlit >= 1000,
        "{shaded} shaded, {sunlit} sunlit"
    );
    assert!(
        glints >= 1 && dark_water >= 1000,
        "{glints} glints, {dark_water} dark"
    );
    // Sunlit ground: the sun's share is several per cent in 3-5 um and well under one in
    // 8-14 um ((1 - eps) E cos/pi against eps B(298 K) in each band).
    assert!(min_mwir_share > 0.01, "{min_mwir_share}");
    assert!(max_lwir_share < 0.005, "{max_lwir_share}");
    // The pipeline's 16 sub-bands against the spectral integral (`--sub-bands full`, one
    // sub-band per interval of the grid), probed at sunlit pixels of the grass, the clay
    // track and the aluminium car's roof: within 0.05 K in both bands (docs/accuracy.md,
    // "Sub-bands by day", measures 0.015 K at most).
    let ids_lwir = layer(&run.exr("lwir-day.truth.exr"), "material_primary");
    for (band, lo, hi, radiance, ids) in [
        ("3-5", 3.0, 5.0, &l_day, &ids),
        ("8-14", 8.0, 14.0, &lw_day, &ids_lwir),
    ] {
        let model = irsig_radiometry::Band::new(lo, hi).unwrap();
        for ((col, row), material) in [((440, 350), 1.0), ((440, 250), 3.0), ((380, 165), 5.0)] {
            let p = row * w + col;
            assert_eq!(ids[p], material, "pixel ({col}, {row})");
            assert_eq!(visible[p], 1.0, "pixel ({col}, {row}) is not sunlit");
            let full = probe_full(run, band, col, row);
            let error = model.temperature(radiance[p]) - model.temperature(full);
            eprintln!(
                "{band} um, pixel ({col}, {row}), material {material}: 16 sub-bands \
                 {:.6} W m-2 sr-1, full grid {full:.6}: {error:+.4} K",
                radiance[p]
            );
            assert!(
                error.abs() < 0.05,
                "{band} um ({col}, {row}): {error:+.4} K"
            );
        }
    }
}

#[test]
fn the_daylight_library_is_what_its_generator_makes_and_covers_both_bands() {
    let dir = recipe::scratch_root();
    let block = recipe::block(
        "pipelines/daylight/README.md",
        "sh pipelines/daylight/generate.sh > pipelines/daylight/materials.ron",
    );
    recipe::run_ok(&block, dir.path(), &[]);
    let made =
        std::fs::read_to_string(dir.path().join("pipelines/daylight/materials.ron")).unwrap();
    let committed =
        std::fs::read_to_string(repo_root().join("pipelines/daylight/materials.ron")).unwrap();
    assert!(
        made == committed,
        "pipelines/daylight/materials.ron is not what generate.sh makes"
    );
    let lib: irsig_model::MaterialLibrary =
        canonical::from_ron("materials.ron", &committed).unwrap();
    let ids: Vec<u16> = lib.materials.iter().map(|m| m.id.0).collect();
    assert_eq!(ids, [1, 2, 3, 4, 5]);
    for m in &lib.materials {
        let s = m
            .spectral
            .as_ref()
            .unwrap_or_else(|| panic!("{} has no spectrum", m.name));
        let (first, last) = (
            s.wavelength_um[0],
            s.wavelength_um[s.wavelength_um.len() - 1],
        );
        assert!(
            first <= 3.0 && last >= 14.0,
            "{}: {first}-{last} um",
            m.name
        );
        assert!(!m.source.is_empty());
    }
}

#[test]
fn the_readme_daylight_picture_is_what_the_pipeline_makes() {
    let run = daylight();
    let made = image::open(run.out("sheet.png")).unwrap().into_luma8();
    let committed = image::open(repo_root().join("docs/daylight.png"))
        .unwrap()
        .into_luma8();
    let stale = "docs/daylight.png is stale: run `sh scripts/docs/daylight-picture.sh` and \
                 check the README's caption";
    assert_eq!(made.dimensions(), committed.dimensions(), "{stale}");
    let worst = made
        .as_raw()
        .iter()
        .zip(committed.as_raw())
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap_or(0);
    assert!(worst <= 2, "{stale} (a pixel differs by {worst} levels)");
    let readme = std::fs::read_to_string(repo_root().join("README.md")).unwrap();
    for want in [
        "docs/daylight.png",
        "scripts/docs/daylight-picture.sh",
        "pipelines/daylight.ron",
    ] {
        assert!(readme.contains(want), "the README does not name {want}");
    }
}

/// `irsig-atmos plan --wavenumber-per-cm`: a range that is none is refused at the flag
/// (exit 2, nothing written); a good one goes into the plan, which `-o FILE.ron` writes
/// alone (the pipeline above builds from such a file).
#[test]
fn a_spectral_range_that_is_none_is_refused_at_its_flag() {
    let dir = tempfile::tempdir().unwrap();
    let [scene, view] = plate(dir.path(), 300.0);
    let plan = dir.path().join("p.ron");
    let run = |range: &str| {
        bin("irsig-atmos")
            .arg("plan")
            .arg("--scene")
            .arg(&scene)
            .arg("--view")
            .arg(&view)
            .args([
                "--atmosphere",
                "us-std-1976",
                "--wavenumber-per-cm",
                range,
                "-o",
            ])
            .arg(&plan)
            .assert()
    };
    for (range, says) in [
        ("1250,710,5", "0 < V1 < V2"),
        ("710,60000,5", "50000"),
        ("710,1250", "three numbers"),
        ("710,1250,x", "three numbers"),
        ("710,1250,0.5", "step"),
        ("710,1250,inf", "finite"),
    ] {
        let out = run(range).code(2);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        for want in ["--wavenumber-per-cm", says] {
            assert!(
                stderr.contains(want),
                "{range}: expected `{want}` in: {stderr}"
            );
        }
        assert!(!plan.exists(), "{range}: a plan was written");
    }
    run("710,3335,5").success();
    let p: irsig_model::AtmospherePlan =
        canonical::from_ron("p.ron", &std::fs::read_to_string(&plan).unwrap()).unwrap();
    assert_eq!(p.wavenumber_per_cm, [710.0, 3335.0, 5.0]);
    assert!(!dir.path().join("runs").exists());
}
