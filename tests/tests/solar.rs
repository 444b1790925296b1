//! The atmosphere in sunlight, first part: the sun's direct beam from real
//! LOWTRAN7 direct solar irradiance runs (IEMSCT = 3). A small plan with a sun is built by
//! `irsig-atmos build`; its direct irradiance on plates at and between the table's
//! altitudes is checked against hand integrals over the TAPE7 of LOWTRAN7 runs made here
//! from decks written by hand; LOWTRAN7's extraterrestrial spectrum against the solar
//! constant; `irsig-atmos plan --sun-zenith-deg/--day-of-year` against the deck format;
//! a sun at or below the horizon, or a day that is none, refused at the flag or at its
//! line and column in the plan. Then `irsig-trace --sun-…` end to end: the sunlight a grey
//! diffuse plate adds to its pixels against τ·(1 − ε)·E·cos θ/π by hand from the built
//! atmosphere's solar spectra, and every sun the atmosphere cannot light refused naming its
//! flag, with no file written. The sun also comes from a view file and from a pipeline's
//! `sun` block, each making the flags' pixels bit for bit; the sun's truth layers are checked
//! against the same hand values, and a sunlit frame in tiles merges into the whole.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH
//! (`sh scripts/atmosphere/install-lowtran.sh` builds it). When it is missing these tests
//! fail, saying so: they never skip.

// Exact zeros (a plate facing away) and numbers copied through a deck: equality is exact.
#![allow(clippy::float_cmp)]

use std::path::{Path, PathBuf};
use std::time::Instant;

use irsig_atmosphere::solar::DirectSun;
use irsig_formats::canonical;
use irsig_model::SpectralAtmosphere;
use irsig_model::truth::Layer;
use irsig_tests::{bin, lowtran};

/// The sun of these tests: 30° from the zenith on 5 April (day 95), when the Earth is at
/// about its mean distance from the Sun.
const ZENITH_DEG: f64 = 30.0;
const DAY: u32 = 95;
/// The spectral range: the whole of LOWTRAN7's solar spectrum (0.2–500 µm) every 20 cm⁻¹.
const V1: f64 = 20.0;
const V2: f64 = 50_000.0;
const DV: f64 = 20.0;

/// A plan of a few thermal paths and the sun's beam at 0, 300 and 1000 m, as RON.
fn plan_ron(zenith: &str, day: &str) -> String {
    plan_ron_over(zenith, day, [V1, V2, DV])
}

/// [`plan_ron`] over wavenumbers `[v1, v2]` every `dv`, cm⁻¹.
fn plan_ron_over(zenith: &str, day: &str, [v1, v2, dv]: [f64; 3]) -> String {
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

/// One row of an IEMSCT = 3 TAPE7: wavenumber (cm⁻¹), τ, the transmitted solar irradiance
/// and the extraterrestrial one (W cm⁻² per cm⁻¹).
#[derive(Debug, Clone, Copy)]
struct SolarRow {
    nu: f64,
    tau: f64,
    transmitted: f64,
    solar: f64,
}

/// LOWTRAN7's direct solar irradiance at `h_km`, the US Standard 1976 model, the sun at
/// `ZENITH_DEG` on `DAY`: a deck written here column by column (LOWTRAN7 user's guide,
/// card 3's alternate form `3F10.3,I5,5X,F10.3,I5,F10.3`: H1 H2 ANGLE IDAY RO ISOURC
/// ANGLEM; ISOURC 0 is the sun), its TAPE7 read here by words.
fn lowtran_solar(h_km: f64) -> Vec<SolarRow> {
    let deck = format!(
        "    6    3    3    0    0    0    0    0    0    0    0    0    0   0.000   0.00\n\
         \x20   0    0    0    0    0    0     0.000     0.000     0.000     0.000     0.000\n\
         {h_km:10.3}{:10.3}{ZENITH_DEG:10.3}{DAY:5}     {:10.3}{:5}{:10.3}\n\
         {V1:10.3}{V2:10.3}{DV:10.3}\n\
         \x20   0\n",
        0.0, 0.0, 0, 0.0
    );
    let t7 = irsig_tests::run_lowtran(&deck).tape7;
    let mut lines = t7
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("FREQ"));
    let header = lines.next().expect("a column header in TAPE7");
    assert!(header.contains("SOL TR"), "{header}");
    let rows: Vec<SolarRow> = lines
        .take_while(|l| l.trim() != "-9999.")
        .map(|l| {
            let w: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            SolarRow {
                nu: w[0],
                tau: w[1],
                transmitted: w[2],
                solar: w[3],
            }
        })
        .collect();
    assert_eq!(rows.len(), 2500, "{deck}");
    rows
}

/// `∫ y_λ dλ` over `[lo_um, hi_um]` of a spectral density given per cm⁻¹ at the rows'
/// wavenumbers (`y(row)`, W m⁻² per cm⁻¹), by the rule formats/canonical/spectral-
/// atmosphere.md states: converted to per µm at the points (`y_λ = y_ν ν² / 10⁴`), the
/// trapezoid in wavelength over the points inside the band, closed at each edge by a value
/// linear in wavenumber between the two points around it.
fn band_integral(rows: &[SolarRow], lo_um: f64, hi_um: f64, y: impl Fn(&SolarRow) -> f64) -> f64 {
    let per_um = |r: &SolarRow| y(r) * r.nu * r.nu / 1e4;
    let at_edge = |um: f64| -> (f64, f64) {
        let nu = 1e4 / um;
        let k = rows.iter().position(|r| r.nu >= nu).unwrap();
        if (rows[k].nu - nu).abs() < 1e-9 {
            return (um, per_um(&rows[k]));
        }
        let (a, b) = (&rows[k - 1], &rows[k]);
        let t = (nu - a.nu) / (b.nu - a.nu);
        (um, per_um(a) + t * (per_um(b) - per_um(a)))
    };
    let mut nodes = vec![at_edge(lo_um)];
    let mut inside: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (1e4 / r.nu, per_um(r)))
        .filter(|&(l, _)| l > lo_um * (1.0 + 1e-12) && l < hi_um * (1.0 - 1e-12))
        .collect();
    inside.sort_by(|a, b| a.0.total_cmp(&b.0));
    nodes.extend(inside);
    nodes.push(at_edge(hi_um));
    nodes
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum()
}

/// The direct irradiance on a plate facing the sun, W m⁻² over the band: LOWTRAN7's τ
/// times its extraterrestrial irradiance (W cm⁻² → W m⁻²).
fn normal_by_hand(rows: &[SolarRow], lo_um: f64, hi_um: f64) -> f64 {
    band_integral(rows, lo_um, hi_um, |r| r.tau * r.solar * 1e4)
}

fn build(plan_dir: &Path, out: &Path) -> SpectralAtmosphere {
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

fn to_sun(azimuth_deg: f64) -> [f64; 3] {
    let (z, a) = (ZENITH_DEG.to_radians(), azimuth_deg.to_radians());
    [z.sin() * a.sin(), z.sin() * a.cos(), z.cos()]
}

#[test]
fn direct_sunlight_is_lowtran7s_transmitted_irradiance_times_the_cosine() {
    let start = Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let plan_dir = dir.path().join("plan");
    std::fs::create_dir(&plan_dir).unwrap();
    std::fs::write(
        plan_dir.join("plan.ron"),
        plan_ron(&format!("{ZENITH_DEG:.1}"), &DAY.to_string()),
    )
    .unwrap();
    let a = build(&plan_dir, &dir.path().join("sunny.spa"));
    let solar = a.solar.as_ref().expect("a solar table");
    assert_eq!(solar.altitude_m, [0.0, 300.0, 1000.0]);
    assert_eq!(
        (solar.zenith_deg, u32::from(solar.day_of_year)),
        (ZENITH_DEG, DAY)
    );
    assert!(a.source.contains("IEMSCT=3"), "{}", a.source);

    // 3-5 um: the lower edge falls between grid points (3333.3 cm-1), the upper on one.
    let (lo, hi) = (3.0, 5.0);
    let sun = DirectSun::new(&a, lo, hi, |_| 1.0).unwrap();
    let at_300 = lowtran_solar(0.3);
    let normal = normal_by_hand(&at_300, lo, hi);
    let s = to_sun(120.0);
    // A horizontal plate at a node of the table: cos 30°.
    let flat = sun.irradiance_w_m2(300.0, [0.0, 0.0, 1.0], s).unwrap();
    let expected = normal * ZENITH_DEG.to_radians().cos();
    assert!(
        (flat / expected - 1.0).abs() < 1e-6,
        "horizontal plate at 300 m: {flat} W m-2 against {expected} by hand"
    );
    eprintln!(
        "3-5 um direct irradiance on a horizontal plate at 300 m: {flat:.6} W m-2, by hand \
         {expected:.6} W m-2 ({:+.2e} relative)",
        flat / expected - 1.0
    );
    // A plate tilted to face the sun: the whole beam. Facing away, or face down: nothing.
    let facing = sun.irradiance_w_m2(300.0, s, s).unwrap();
    assert!(
        (facing / normal - 1.0).abs() < 1e-6,
        "{facing} against {normal}"
    );
    assert_eq!(
        sun.irradiance_w_m2(300.0, [-s[0], -s[1], -s[2]], s)
            .unwrap(),
        0.0
    );
    assert_eq!(
        sun.irradiance_w_m2(300.0, [0.0, 0.0, -1.0], s).unwrap(),
        0.0
    );
    // LOWTRAN's own transmitted column is τ E_toa on a surface normal to the beam (a
    // horizontal one would be 13 % less): it agrees to its three printed digits.
    let transmitted = band_integral(&at_300, lo, hi, |r| r.transmitted * 1e4);
    eprintln!(
        "LOWTRAN's SOL TR column over 3-5 um: {transmitted:.5} W m-2 ({:+.2e} from tau x SOLAR)",
        transmitted / normal - 1.0
    );
    assert!(
        (transmitted / normal - 1.0).abs() < 5e-3,
        "LOWTRAN's SOL TR column gives {transmitted} W m-2, tau x SOLAR {normal}"
    );
    // The ground row too, and more sun higher up (less air above).
    let ground = normal_by_hand(&lowtran_solar(0.0), lo, hi);
    assert!((sun.normal_w_m2(0.0) / ground - 1.0).abs() < 1e-6);
    assert!(sun.normal_w_m2(0.0) < sun.normal_w_m2(300.0));
    assert!(sun.normal_w_m2(300.0) < sun.normal_w_m2(1000.0));

    // Between the rows: linear in altitude, against LOWTRAN7 run at the midpoint.
    let mid = normal_by_hand(&lowtran_solar(0.15), lo, hi);
    let interpolated = sun.normal_w_m2(150.0);
    let error = interpolated / mid - 1.0;
    eprintln!(
        "3-5 um direct irradiance at 150 m, sun at 30 deg: LOWTRAN7 {mid:.5} W m-2, \
         interpolated between 0 and 300 m {interpolated:.5} W m-2 ({error:+.2e} relative)"
    );
    assert!(error.abs() < 1e-3, "{error}");

    // The extraterrestrial spectrum over 0.2-500 um is the solar constant, 1367 W m-2
    // (World Radiation Center, Fröhlich 1981, as adopted by the WMO), to 1 %: on day 95
    // the Earth is within 0.1 % of its mean distance from the Sun.
    let whole = DirectSun::new(&a, 1e4 / V2, 1e4 / V1, |_| 1.0).unwrap();
    let e0 = whole.extraterrestrial_w_m2();
    assert!((e0 / 1367.0 - 1.0).abs() < 0.01, "{e0} W m-2");
    // And 3-5 um of it against LOWTRAN's column by hand.
    let etoa_3_5 = band_integral(&at_300, lo, hi, |r| r.solar * 1e4);
    assert!((sun.extraterrestrial_w_m2() / etoa_3_5 - 1.0).abs() < 1e-6);

    let secs = start.elapsed().as_secs_f64();
    eprintln!(
        "solar constant of LOWTRAN7's spectrum: {e0:.1} W m-2 on day {DAY}; build and runs \
         {secs:.1} s"
    );
}

/// flatten + plan for the quickstart scene into `dir`, with `extra` flags.
fn quickstart_plan(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    irsig_tests::quickstart_plan(dir, name, &["--atmosphere", "us-std-1976"], extra)
}

fn decks(plan: &Path) -> Vec<String> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(plan.join("runs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| std::fs::read_to_string(f).unwrap())
        .collect()
}

#[test]
fn plan_puts_the_suns_runs_after_the_nights() {
    let dir = tempfile::tempdir().unwrap();
    let night = quickstart_plan(dir.path(), "night", &[]);
    let sun_flags = ["--sun-zenith-deg", "41.25", "--day-of-year", "200"];
    let direct = quickstart_plan(dir.path(), "direct", &sun_flags);
    let day = quickstart_plan(
        dir.path(),
        "day",
        &[&sun_flags[..], &["--sun-scattering"]].concat(),
    );
    let read = |p: &Path| -> irsig_model::AtmospherePlan {
        canonical::from_ron_bytes("plan.ron", &std::fs::read(p.join("plan.ron")).unwrap()).unwrap()
    };
    // By default a day plan adds the direct beam's runs only, one per sky row of the
    // night's, after the night's decks.
    let (n, mut b) = (read(&night), read(&direct));
    let beam = b.sun.take().expect("a sun");
    assert_eq!(b, n, "the sun changes nothing else");
    assert!(beam.relative_azimuth_deg.is_empty(), "{beam:?}");
    assert_eq!(beam.altitude_m, n.sky_altitude_m);
    let (nd, bd) = (decks(&night), decks(&direct));
    assert_eq!(bd.len(), nd.len() + n.sky_altitude_m.len());
    assert_eq!(bd[..nd.len()], nd[..]);
    // Card 1 (13I5): the third field is IEMSCT, 3 for a direct solar irradiance run.
    let iemsct = |deck: &str| deck.lines().next().unwrap()[10..15].trim().to_owned();
    assert!(bd[nd.len()..].iter().all(|d| iemsct(d) == "3"));
    let mut d = read(&day);
    assert!(
        !std::fs::read_to_string(night.join("plan.ron"))
            .unwrap()
            .contains("sun"),
        "a plan without --sun-zenith-deg is for night"
    );
    let sun = d.sun.take().expect("a sun");
    assert_eq!(d, n, "the sun changes nothing else");
    assert_eq!((sun.zenith_deg, sun.day_of_year), (41.25, 200));
    // With --sun-scattering: the night's sky rows and the finer rows of the scattered sky
    // (500, 700, 1500 m).
    let mut rows = n.sky_altitude_m.clone();
    rows.extend(irsig_atmosphere::plan::DAY_SKY_ALTITUDE_M);
    rows.sort_by(f64::total_cmp);
    assert_eq!(sun.altitude_m, rows);
    let (nd, dd) = (decks(&night), decks(&day));
    // The direct beam's runs, then each slant and sky path once per azimuth from the sun
    // (IEMSCT = 2, tests/tests/sunlit.rs).
    let sunlit = (n.slant_altitude_m.len() * n.slant_nadir_deg.len()
        + sun.altitude_m.len() * n.sky_zenith_deg.len())
        * sun.relative_azimuth_deg.len();
    assert_eq!(dd.len(), nd.len() + sun.altitude_m.len() + sunlit);
    assert_eq!(
        dd[..nd.len()],
        nd[..],
        "the night's decks keep their numbers"
    );
    for (deck, h_m) in dd[nd.len()..].iter().zip(&sun.altitude_m) {
        let cards: Vec<&str> = deck.lines().collect();
        // Card 1 (13I5): MODEL 6, ITYPE 3, IEMSCT 3.
        assert_eq!(&cards[0][..15], "    6    3    3", "{deck}");
        // Card 3's alternate form (3F10.3,I5,5X,F10.3,I5,F10.3), read by column.
        let field = |a: usize, b: usize| cards[2].get(a..b).unwrap_or("").trim();
        let h_km: f64 = field(0, 10).parse().unwrap();
        assert!((h_km * 1000.0 - h_m).abs() < 1e-9, "{deck}");
        assert_eq!(field(20, 30).parse::<f64>().unwrap(), 41.25, "{deck}");
        assert_eq!(field(30, 35), "200", "{deck}");
        // ISOURC 0 is the sun (1 the moon); blank reads as 0 too.
        assert!(matches!(field(50, 55), "" | "0"), "{deck}");
    }
}

#[test]
fn a_sun_at_or_below_the_horizon_or_a_day_that_is_none_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    // The flags: refused as bad usage before anything is read, naming the flag.
    for (zenith, day, flag) in [
        (Some("90"), Some("172"), "--sun-zenith-deg"),
        (Some("95"), Some("172"), "--sun-zenith-deg"),
        (Some("NaN"), Some("172"), "--sun-zenith-deg"),
        (Some("-1"), Some("172"), "--sun-zenith-deg"),
        (Some("89.9996"), Some("172"), "--sun-zenith-deg"),
        (Some("30"), Some("0"), "--day-of-year"),
        (Some("30"), Some("367"), "--day-of-year"),
        (Some("30"), None, "--day-of-year"),
    ] {
        let out = dir.path().join("never");
        let mut cmd = bin("irsig-atmos");
        cmd.args(["plan", "--scene", "no-scene.raw", "--view", "no-view.ron"]);
        cmd.args(["--atmosphere", "us-std-1976"]);
        // `=`: clap would take a separate `-1` for a flag of its own.
        if let Some(z) = zenith {
            cmd.arg(format!("--sun-zenith-deg={z}"));
        }
        if let Some(d) = day {
            cmd.arg(format!("--day-of-year={d}"));
        }
        let assert = cmd.arg("-o").arg(&out).assert().code(2);
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
        assert!(stderr.contains(flag), "{zenith:?} {day:?}: {stderr}");
        assert!(!out.exists());
    }
    // The plan file: refused at the value's line and column, before LOWTRAN7 runs.
    for (zenith, day, bad) in [
        ("90.0", "95", "90.0"),
        ("NaN", "95", "NaN"),
        ("30.0", "0", "day_of_year: 0"),
        ("30.0", "367", "day_of_year: 367"),
    ] {
        let text = plan_ron(zenith, day);
        let at = text.find(bad).unwrap();
        let at = at + bad.find(|c: char| c.is_ascii_digit() || c == 'N').unwrap();
        let line = text[..at].matches('\n').count() + 1;
        let column = at - text[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
        let plan_dir = dir.path().join(format!("plan-{zenith}-{day}"));
        std::fs::create_dir(&plan_dir).unwrap();
        std::fs::write(plan_dir.join("plan.ron"), &text).unwrap();
        let out = dir.path().join("never.spa");
        bin("irsig-atmos")
            .env("IRSIG_LOWTRAN", lowtran())
            .arg("build")
            .arg(&plan_dir)
            .args(["--atmosphere", "us-std-1976", "-o"])
            .arg(&out)
            .assert()
            .code(1)
            .stderr(predicates::str::contains(format!(
                "plan.ron:{line}:{column}"
            )))
            .stderr(predicates::str::contains(if day == "95" {
                "horizon"
            } else {
                "day of the year"
            }));
        assert!(!out.exists());
    }
}

/// A grey, fully diffuse plate of emissivity `EPSILON` at 300 K, 200 km across, horizontal
/// at `PLATE_M` above the ground, and a 4 × 4-pixel view straight down on it from 1000 m.
/// Returns the raw scene, the materials and the view.
fn plate(dir: &Path) -> [PathBuf; 3] {
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

/// `irsig-atmos plan` of the plate's scene and `view` (text) with `flags`, into
/// `dir/NAME`.
fn plan_plate(dir: &Path, name: &str, view: &str, flags: &[&str]) -> assert_cmd::assert::Assert {
    let [scene, ..] = plate(dir);
    let view_file = dir.join(format!("{name}-view.ron"));
    std::fs::write(&view_file, view).unwrap();
    bin("irsig-atmos")
        .args(["plan", "--atmosphere", "us-std-1976", "--scene"])
        .arg(scene)
        .arg("--view")
        .arg(view_file)
        .args(flags)
        .arg("-o")
        .arg(dir.join(name))
        .assert()
}

#[test]
fn plan_takes_the_sun_of_a_view_file_as_trace_does() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let plain = std::fs::read_to_string(plate(d)[2].clone()).unwrap();
    // A direction and the day by flag: the same plan, deck for deck, as the flags make.
    plan_plate(
        d,
        "flags",
        &plain,
        &["--sun-zenith-deg", "41.25", "--day-of-year", "200"],
    )
    .success();
    let direction = view_with_sun("Direction(zenith_deg: 41.25, azimuth_deg: 200.0)");
    plan_plate(
        d,
        "view",
        &direction,
        &["--day-of-year", "200", "--sun-scattering"],
    )
    .success();
    plan_plate(d, "view-direct", &direction, &["--day-of-year", "200"]).success();
    assert_eq!(
        std::fs::read(d.join("flags/plan.ron")).unwrap(),
        std::fs::read(d.join("view-direct/plan.ron")).unwrap()
    );
    assert_eq!(decks(&d.join("flags")), decks(&d.join("view-direct")));
    assert!(decks(&d.join("view")).len() > decks(&d.join("flags")).len());
    // A time and a place: the day is the time's (1 August 2026 is day 31 + 28 + 31 + 30 +
    // 31 + 30 + 31 + 1 = 213), the zenith the position SPA gives there, as irsig-trace
    // computes it, rounded to the 0.001 deg of a deck.
    let at = "At(utc: \"2026-08-01T15:00:00Z\", latitude_deg: 43.08, longitude_deg: -77.67)";
    plan_plate(d, "at", &view_with_sun(at), &[]).success();
    let plan: irsig_model::AtmospherePlan =
        canonical::from_ron_bytes("plan.ron", &std::fs::read(d.join("at/plan.ron")).unwrap())
            .unwrap();
    let sun = plan.sun.expect("a plan with the view's sun");
    assert_eq!(sun.day_of_year, 213);
    let spec: irsig_atmosphere::sun::SunSpec = ron::from_str(at).unwrap();
    let zenith = spec.position().unwrap().zenith_deg;
    assert!(
        (sun.zenith_deg - zenith).abs() <= 0.0005,
        "{} {zenith}",
        sun.zenith_deg
    );
    // A view that gives the air for SPA's refraction lifts the direction the light comes
    // from, not the plan's sun: the plan keeps the geometric zenith, whose beam the build
    // bends itself along LOWTRAN7's refracted path (else it would be bent twice). Near
    // sunrise the two differ by a few tenths of a degree.
    let refracted = "At(utc: \"2026-08-01T10:30:00Z\", latitude_deg: 43.08, longitude_deg: \
                     -77.67, refraction: Some((pressure_hpa: 1000.0, temperature_c: 15.0)))";
    plan_plate(d, "refracted", &view_with_sun(refracted), &[]).success();
    let plan: irsig_model::AtmospherePlan = canonical::from_ron_bytes(
        "plan.ron",
        &std::fs::read(d.join("refracted/plan.ron")).unwrap(),
    )
    .unwrap();
    let sun = plan.sun.expect("a plan with the view's sun");
    let spec: irsig_atmosphere::sun::SunSpec = ron::from_str(refracted).unwrap();
    let position = spec.position().unwrap();
    assert!(
        position.geometric_zenith_deg - position.zenith_deg > 0.1,
        "{position:?}"
    );
    assert!(
        (sun.zenith_deg - position.geometric_zenith_deg).abs() <= 0.0005,
        "the plan's sun {} is not the geometric {}",
        sun.zenith_deg,
        position.geometric_zenith_deg
    );
    // Refused, exit 2, nothing written: a sun given twice (naming the flag and the view's
    // line and column), a direction without a day, a day that is not the time's, a day or
    // scattering without any sun.
    for (name, view, flags, says) in [
        (
            "twice",
            &direction,
            &["--sun-zenith-deg", "41.25", "--day-of-year", "200"][..],
            "--sun-zenith-deg 41.25 and the `sun` of the view file at ",
        ),
        (
            "no-day",
            &direction,
            &[][..],
            "is a direction, which has no date",
        ),
        (
            "other-day",
            &view_with_sun(at),
            &["--day-of-year", "212"][..],
            "is seen on day 213 of its year",
        ),
        (
            "night-day",
            &plain,
            &["--day-of-year", "212"][..],
            "--day-of-year 212 without a sun",
        ),
        (
            "night-scatter",
            &plain,
            &["--sun-scattering"][..],
            "--sun-scattering without a sun",
        ),
    ] {
        let assert = plan_plate(d, name, view, flags).code(2);
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
        assert!(stderr.contains(says), "{name}: {stderr}");
        if name == "twice" {
            assert!(stderr.contains(&format!("{name}-view.ron:3:8")), "{stderr}");
        }
        assert!(!d.join(name).exists(), "{name}");
    }
}

/// The plate's emissivity and height above the ground, m: half-way between the solar
/// table's rows at 0 and 300 m, so that the beam is interpolated in altitude.
const EPSILON: f64 = 0.6;
const PLATE_M: f64 = 150.0;

/// `irsig-trace` of the plate through `atmosphere` in 4-5 µm (8-14 µm, the built-ins'
/// spectra, when `atmosphere` names no file) with `extra` flags, writing `dir/PREFIX.*`.
fn trace_plate(
    dir: &Path,
    atmosphere: &Path,
    prefix: &str,
    extra: &[&str],
) -> assert_cmd::assert::Assert {
    trace_plate_lit(dir, atmosphere, prefix, extra, None)
}

/// The plate's view straight down, as [`plate`] writes it, with `sun` (RON) added as its
/// last field on a line of its own (line 3, column 8).
fn view_with_sun(sun: &str) -> String {
    format!(
        "LookAt(position_m: (0.0, 0.0, 1000.0), target_m: (0.0, 0.0, 0.0),\n\
         up: (0.0, 1.0, 0.0), pixels: (4, 4), fov_deg: (1.0, 1.0),\n  sun: {sun},\n)\n"
    )
}

/// [`trace_plate`], with the view's text replaced by `view` when given.
fn trace_plate_lit(
    dir: &Path,
    atmosphere: &Path,
    prefix: &str,
    extra: &[&str],
    view_text: Option<&str>,
) -> assert_cmd::assert::Assert {
    let [scene, materials, mut view] = plate(dir);
    if let Some(text) = view_text {
        view = dir.join(format!("sun-view-{prefix}.ron"));
        std::fs::write(&view, text).unwrap();
    }
    bin("irsig-trace")
        .arg("--scene")
        .arg(scene)
        .arg("--materials")
        .arg(materials)
        .arg("--view")
        .arg(view)
        .arg("--atmosphere")
        .arg(atmosphere)
        .args(["--band", if atmosphere.is_file() { "4-5" } else { "8-14" }])
        .args(extra)
        .arg("-o")
        .arg(dir.join(prefix))
        .assert()
}

fn layer(path: &Path, name: &str) -> Vec<f32> {
    let r = irsig_raster::read_exr(&std::fs::read(path).unwrap()).unwrap();
    r.layer(name)
        .unwrap_or_else(|| panic!("no layer `{name}` in {}", path.display()))
        .data
        .clone()
}

/// `∫ E_toa(λ) τ_sun(λ, h) dλ` over `[lo_um, hi_um]`, W m⁻², from the atmosphere file's
/// solar spectra (a wavenumber grid whose points include both edges): each spectrum per
/// cm⁻¹ converted to per µm at the points, the trapezoid in wavelength, τ linear in
/// altitude between the table's rows.
fn direct_by_hand(a: &SpectralAtmosphere, lo_um: f64, hi_um: f64, h_m: f64) -> f64 {
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
            if um < lo_um - 1e-9 || um > hi_um + 1e-9 {
                return None;
            }
            let tau = |row: usize| f64::from(solar.transmission[row * n + i]);
            let tau_h = tau(k - 1) * (1.0 - t) + tau(k) * t;
            let e_per_um = f64::from(solar.extraterrestrial_w_m2_per_unit[i]) * nu * nu / 1e4;
            Some((um, e_per_um * tau_h))
        })
        .collect();
    points.sort_by(|x, y| x.0.total_cmp(&y.0));
    assert!(
        (points[0].0 - lo_um).abs() < 1e-9 && (points[points.len() - 1].0 - hi_um).abs() < 1e-9
    );
    points
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum()
}

/// Exit code 2, the flag named on stderr, and no file written.
fn refused(
    assert: assert_cmd::assert::Assert,
    dir: &Path,
    prefix: &str,
    flag: &str,
    also: &[&str],
) {
    let assert = assert.code(2);
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(stderr.contains(flag), "expected {flag} in: {stderr}");
    for a in also {
        assert!(stderr.contains(a), "expected `{a}` in: {stderr}");
    }
    let left: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(prefix) || n.contains(".irsig-"))
        .collect();
    assert!(left.is_empty(), "{flag}: files left: {left:?}");
    eprintln!("refused: {}", stderr.trim());
}

#[test]
fn irsig_trace_lights_a_plate_by_the_suns_beam_and_refuses_a_sun_the_table_is_not_for() {
    let start = Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let plan_dir = dir.path().join("plan");
    std::fs::create_dir(&plan_dir).unwrap();
    // 4-5 um is 2000-2500 cm-1: both edges on the grid.
    std::fs::write(
        plan_dir.join("plan.ron"),
        plan_ron_over(
            &format!("{ZENITH_DEG:.1}"),
            &DAY.to_string(),
            [1980.0, 2520.0, 20.0],
        ),
    )
    .unwrap();
    let spa = dir.path().join("sunny.spa");
    let a = build(&plan_dir, &spa);
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    trace_plate(&out, &spa, "night", &[]).success();
    day_takes_16_sub_bands_unless_asked(&out, &spa);
    the_beam_and_the_sun_layers_are_the_hand_computed_ones(&out, &a);
    tiles_of_a_day_merge_to_the_whole_frame(&out, &spa);
    the_sun_of_a_view_or_a_pipeline_is_the_flags_sun(&out, &spa);
    suns_the_table_is_not_for_are_refused(&out, &spa);
    let secs = start.elapsed().as_secs_f64();
    eprintln!("build, four traces, a merge and five refusals: {secs:.1} s");
}

/// By day the default is 16 sub-bands, said; asked for by name, said nothing about.
fn day_takes_16_sub_bands_unless_asked(out: &Path, spa: &Path) {
    // By day with no count given the tracer takes 16 sub-bands and says so; one sub-band
    // asked for by name is the band model, said nothing about.
    let sun = ["--sun-zenith-deg", "30", "--sun-azimuth-deg", "120"];
    let chosen = trace_plate(out, spa, "day-16", &sun).success();
    let stderr = String::from_utf8_lossy(&chosen.get_output().stderr).into_owned();
    assert!(
        stderr.contains("by day with no sub-band count given")
            && stderr.contains("16 sub-bands")
            && stderr.contains("--sub-bands 1"),
        "a sunlit trace at the default sub-bands should say what it chose: {stderr}"
    );
    let asked = trace_plate(
        out,
        spa,
        "day-16-asked",
        &[&sun[..], &["--sub-bands", "16"]].concat(),
    )
    .success();
    assert!(!String::from_utf8_lossy(&asked.get_output().stderr).contains("sub-band"));
    assert_eq!(
        layer(&out.join("day-16-asked.radiance.exr"), "radiance"),
        layer(&out.join("day-16.radiance.exr"), "radiance"),
        "--sub-bands 16 is the default's image by day"
    );
    let quiet = trace_plate(out, spa, "day", &[&sun[..], &["--sub-bands", "1"]].concat()).success();
    let stderr = String::from_utf8_lossy(&quiet.get_output().stderr).into_owned();
    assert!(!stderr.contains("sub-band"), "{stderr}");
}

/// The sun adds τ_sun·(1 − ε)·E·cos θ/π to every pixel of the plate, E by hand from the
/// atmosphere file's spectra, and the sun's truth layers hold E·cos θ, the whole disk, the
/// reflected radiance and the sun's share.
fn the_beam_and_the_sun_layers_are_the_hand_computed_ones(out: &Path, a: &SpectralAtmosphere) {
    let night = layer(&out.join("night.radiance.exr"), "radiance");
    let day = layer(&out.join("day.radiance.exr"), "radiance");
    let truth = out.join("day.truth.exr");
    let tau = layer(&truth, "transmission");
    let eps = layer(&truth, "emissivity");
    assert_eq!(tau, layer(&out.join("night.truth.exr"), "transmission"));
    // The beam on the plate, by hand from the file's spectra: half-way between the rows.
    let e = direct_by_hand(a, 4.0, 5.0, PLATE_M);
    let cos = ZENITH_DEG.to_radians().cos();
    let r = (1.0 - EPSILON) * e * cos / std::f64::consts::PI;
    // The sunlight reaches the sensor through the path's transmittance for sunlight, which
    // lies between the band's τ and 1: the beam has already lost the wavelengths the path
    // absorbs (docs/accuracy.md, "Sub-bands by day").
    let tau_sun = (f64::from(day[0]) - f64::from(night[0])) / r;
    for p in 0..day.len() {
        assert_eq!(
            f64::from(eps[p]),
            f64::from(EPSILON as f32),
            "pixel {p} is not the plate"
        );
        let added = f64::from(day[p]) - f64::from(night[p]);
        // f32 images: each radiance holds 6e-8 of itself; the sunlight is a sizeable part
        // of the radiance here, so 1e-5 leaves a margin of 50.
        assert!(
            (added / (tau_sun * r) - 1.0).abs() < 1e-5,
            "pixel {p}: the sun adds {added} W m-2 sr-1, pixel 0 {}",
            tau_sun * r
        );
    }
    assert!(
        f64::from(tau[0]) < tau_sun && tau_sun < 1.0,
        "the sunlight's path transmittance {tau_sun} is not between the band's {} and 1",
        tau[0]
    );
    eprintln!(
        "4-5 um, sun at {ZENITH_DEG} deg, plate eps {EPSILON} at {PLATE_M} m: E {e:.6} W m-2, \
         tau {:.6}, for the sunlight {tau_sun:.6}; the sun adds {:.6} W m-2 sr-1 to {:.6}",
        tau[0],
        f64::from(day[0]) - f64::from(night[0]),
        night[0]
    );
    assert!(day[0] > night[0]);

    // The sun's truth layers (item 5), by hand from the same E: the plate gets E·cos θ, sees
    // the whole disk, reflects (1 − ε)·E·cos θ/π, which is τ·(1 − ε)·E·cos θ/π of the
    // pixel's radiance. A night truth EXR keeps exactly the night's layers.
    let names = |path: &Path| -> Vec<String> {
        irsig_raster::read_exr(&std::fs::read(path).unwrap())
            .unwrap()
            .layers
            .iter()
            .map(|l| l.name.clone())
            .collect()
    };
    let night_layers: Vec<String> = Layer::TRUTH.iter().map(|l| l.name().to_owned()).collect();
    assert_eq!(names(&out.join("night.truth.exr")), night_layers);
    let mut day_layers = night_layers.clone();
    day_layers.extend(Layer::SUN.iter().map(|l| l.name().to_owned()));
    assert_eq!(names(&truth), day_layers);
    let irradiance = layer(&truth, Layer::SolarIrradiance.name());
    let visible = layer(&truth, Layer::SunVisibleFraction.name());
    let reflected = layer(&truth, Layer::ReflectedSolarRadiance.name());
    let share = layer(&truth, Layer::SunShare.name());
    for p in 0..day.len() {
        let close = |got: f32, expected: f64, what: &str| {
            let error = f64::from(got) / expected - 1.0;
            // f32 layers and the same quadrature margin as above.
            assert!(
                error.abs() < 1e-5,
                "pixel {p}: {what} {got}, by hand {expected}"
            );
        };
        close(irradiance[p], e * cos, "solar irradiance");
        assert_eq!(visible[p], 1.0);
        let r = (1.0 - EPSILON) * e * cos / std::f64::consts::PI;
        close(reflected[p], r, "reflected solar radiance");
        close(
            share[p],
            (f64::from(day[p]) - f64::from(night[p])) / f64::from(day[p]),
            "sun share",
        );
    }
    eprintln!(
        "sun layers: E {:.6} W m-2, reflected {:.6} W m-2 sr-1, share {:.6}",
        irradiance[0], reflected[0], share[0]
    );
}

/// Traced in two tiles and merged, the day's truth is the whole frame's, byte for byte.
fn tiles_of_a_day_merge_to_the_whole_frame(out: &Path, spa: &Path) {
    let truth = out.join("day.truth.exr");
    // Traced in two tiles and merged, the day's truth is the whole frame's, byte for byte.
    for i in 1..=2 {
        trace_plate(
            out,
            spa,
            &format!("tile{i}"),
            &[
                "--sun-zenith-deg",
                "30",
                "--sun-azimuth-deg",
                "120",
                "--tile",
                &format!("{i}/2x1"),
                "--sub-bands",
                "1",
            ],
        )
        .success();
    }
    bin("irsig-merge")
        .arg(out.join("tile1.truth.exr"))
        .arg(out.join("tile2.truth.exr"))
        .arg("--view")
        .arg(out.join("down.ron"))
        .arg("--truth-exr")
        .arg(out.join("merged.truth.exr"))
        .assert()
        .success();
    assert_eq!(
        std::fs::read(out.join("merged.truth.exr")).unwrap(),
        std::fs::read(&truth).unwrap(),
        "merged tiles' truth differs from the whole frame's"
    );
}

/// The same sun from the view file and from a pipeline's `sun` block gives the flags'
/// pixels, bit for bit; given twice, or other than the table's in the view, it is refused.
fn the_sun_of_a_view_or_a_pipeline_is_the_flags_sun(out: &Path, spa: &Path) {
    // The same sun from the view file: the same pixels, bit for bit, in every layer (the
    // files' headers differ only by the view file's checksum in the provenance).
    let lit = "Some(Direction(zenith_deg: 30.0, azimuth_deg: 120.0))";
    trace_plate_lit(out, spa, "viewsun", &[], Some(&view_with_sun(lit))).success();
    let pixels = |path: &Path| -> Vec<(String, Vec<u32>)> {
        irsig_raster::read_exr(&std::fs::read(path).unwrap())
            .unwrap()
            .layers
            .iter()
            .map(|l| (l.name.clone(), l.data.iter().map(|v| v.to_bits()).collect()))
            .collect()
    };
    for file in ["radiance.exr", "truth.exr"] {
        let (a, b) = (
            out.join(format!("day-16.{file}")),
            out.join(format!("viewsun.{file}")),
        );
        assert_eq!(
            pixels(&a),
            pixels(&b),
            "{file}: the view's sun differs from the flags'"
        );
    }
    // The same sun from a pipeline's `sun` block, run by irsig-run: the same pixels again.
    // (In a folder of its own: the runner keeps its state beside the pipeline file.)
    let pipe = out.join("pipe");
    std::fs::create_dir(&pipe).unwrap();
    std::fs::copy(spa, pipe.join("sunny.spa")).unwrap();
    plate(&pipe);
    std::fs::write(
        pipe.join("lit.ron"),
        "(\n  sun: Direction(zenith_deg: 30.0, azimuth_deg: 120.0),\n  stages: [Stage(tool: \
         \"trace\", inputs: {\"scene\": \"plate.raw.ron\", \"materials\": \"grey.ron\", \
         \"view\": \"down.ron\", \"atmosphere\": \"sunny.spa\"}, params: {\"band\": \"4-5\"}, \
         outputs: {\"radiance-exr\": \"piped/frame.radiance.exr\", \"truth-exr\": \
         \"piped/frame.truth.exr\"})],\n)\n",
    )
    .unwrap();
    let run = bin("irsig-run")
        .arg("lit.ron")
        .current_dir(&pipe)
        .assert()
        .success();
    eprintln!(
        "{}",
        String::from_utf8_lossy(&run.get_output().stderr).trim()
    );
    for file in ["radiance.exr", "truth.exr"] {
        let (a, b) = (
            out.join(format!("day-16.{file}")),
            pipe.join(format!("piped/frame.{file}")),
        );
        assert_eq!(
            pixels(&a),
            pixels(&b),
            "{file}: the pipeline's sun differs from the flags'"
        );
    }
    // Given twice, by the view and by the flags: refused, naming both (the sun's value,
    // inside `Some(`, at column 13).
    refused(
        trace_plate_lit(
            out,
            spa,
            "twice",
            &["--sun-zenith-deg", "30", "--sun-azimuth-deg", "120"],
            Some(&view_with_sun(lit)),
        ),
        out,
        "twice",
        "--sun-zenith-deg",
        &["sun-view-twice.ron:3:13", "both give a sun"],
    );
    // A view's sun other than the table's: refused at its place in the file.
    let other = trace_plate_lit(
        out,
        spa,
        "viewother",
        &[],
        Some(&view_with_sun(
            "Direction(zenith_deg: 31.0, azimuth_deg: 0.0)",
        )),
    )
    .failure();
    let stderr = String::from_utf8_lossy(&other.get_output().stderr).into_owned();
    assert!(
        stderr.contains("sun-view-viewother.ron:3:8") && stderr.contains("30 deg"),
        "{stderr}"
    );
    assert!(!out.join("viewother.radiance.exr").exists());
}

/// A sun other than the table's, below the horizon, or with shadow rays beside a
/// tolerance: refused, naming the flag, nothing written.
fn suns_the_table_is_not_for_are_refused(out: &Path, spa: &Path) {
    // A sun other than the table's, by direction or by time and place (London at noon on
    // the solstice, about 28 deg from the zenith), and a sun below the horizon.
    refused(
        trace_plate(
            out,
            spa,
            "other",
            &["--sun-zenith-deg", "31", "--sun-azimuth-deg", "0"],
        ),
        out,
        "other",
        "--sun-zenith-deg",
        &["31.0000", "30 deg"],
    );
    refused(
        trace_plate(
            out,
            spa,
            "london",
            &[
                "--sun-utc",
                "2024-06-21T12:00:00Z",
                "--latitude-deg",
                "51.5",
                "--longitude-deg",
                "0",
            ],
        ),
        out,
        "london",
        "--sun-utc",
        &["30 deg"],
    );
    refused(
        trace_plate(
            out,
            spa,
            "low",
            &["--sun-zenith-deg", "95", "--sun-azimuth-deg", "0"],
        ),
        out,
        "low",
        "--sun-zenith-deg",
        &["horizon"],
    );
    refused(
        trace_plate(
            out,
            spa,
            "midnight",
            &[
                "--sun-utc",
                "2024-06-21T00:00:00Z",
                "--latitude-deg",
                "51.5",
                "--longitude-deg",
                "0",
            ],
        ),
        out,
        "midnight",
        "--sun-utc",
        &["horizon"],
    );
    // With a tolerance the pilot chooses the shadow rays (tests/pilot_sun.rs): giving
    // them as well is refused.
    refused(
        trace_plate(
            out,
            spa,
            "piloted",
            &[
                "--sun-zenith-deg",
                "30",
                "--sun-azimuth-deg",
                "0",
                "--sun-shadow-rays",
                "4",
                "--tolerance",
                "0.5",
            ],
        ),
        out,
        "piloted",
        "--tolerance",
        &["--sun-shadow-rays"],
    );
}

#[test]
fn a_sun_needs_an_atmosphere_with_a_solar_table() {
    let dir = tempfile::tempdir().unwrap();
    let sun = ["--sun-zenith-deg", "30", "--sun-azimuth-deg", "0"];
    // A vacuum, a built-in's band tables, a built-in's spectra (a night atmosphere).
    for (atmosphere, extra, what) in [
        ("none", &[][..], "a vacuum"),
        ("us-std-1976", &[][..], "band atmosphere"),
        ("us-std-1976", &["--sub-bands", "2"][..], "night atmosphere"),
    ] {
        let mut flags = sun.to_vec();
        flags.extend(extra);
        refused(
            trace_plate(dir.path(), Path::new(atmosphere), "lit", &flags)
                .stderr(predicates::str::contains("irsig-atmos plan")),
            dir.path(),
            "lit",
            "--sun-zenith-deg",
            &[what],
        );
    }
    // A view's sun with a value out of range, an unknown field or no form: refused at the
    // value's line and column (line 3: `  sun: ` takes columns 1-7), nothing written.
    for (sun, column, says) in [
        (
            "Direction(zenith_deg: 95.0, azimuth_deg: 0.0)",
            30,
            "horizon",
        ),
        (
            "Direction(zenith_deg: 30.0, azimuth_deg: 400.0)",
            49,
            "azimuth_deg",
        ),
        (
            "At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 95.0, longitude_deg: 0.0)",
            54,
            "latitude_deg",
        ),
        (
            "At(utc: \"2024-13-21T12:00:00Z\", latitude_deg: 51.5, longitude_deg: 0.0)",
            16,
            "utc",
        ),
        (
            "Direction(zenith_deg: 30.0, azimuth_deg: 0.0, hour: 12)",
            54,
            "hour",
        ),
        ("Noon", 8, "expected Direction"),
    ] {
        let bad = trace_plate_lit(
            dir.path(),
            Path::new("none"),
            "bad",
            &[],
            Some(&view_with_sun(sun)),
        )
        .failure();
        let stderr = String::from_utf8_lossy(&bad.get_output().stderr).into_owned();
        let at = format!("sun-view-bad.ron:3:{column}");
        assert!(
            stderr.contains(&at) && stderr.contains(says),
            "{sun}: expected {at}, {says}: {stderr}"
        );
        assert!(!dir.path().join("bad.radiance.exr").exists());
    }
    // A good view sun with no solar table: refused at the sun's place, not at a flag.
    let lit = trace_plate_lit(
        dir.path(),
        Path::new("none"),
        "vacuum",
        &[],
        Some(&view_with_sun(
            "Direction(zenith_deg: 30.0, azimuth_deg: 0.0)",
        )),
    )
    .failure();
    let stderr = String::from_utf8_lossy(&lit.get_output().stderr).into_owned();
    assert!(
        stderr.contains("sun-view-vacuum.ron:3:8") && stderr.contains("a vacuum"),
        "{stderr}"
    );
    // Shadow rays for a view's sun are the flag's; without any sun they are refused.
    trace_plate(
        dir.path(),
        Path::new("none"),
        "rays",
        &["--sun-shadow-rays", "4"],
    )
    .code(2)
    .stderr(predicates::str::contains("without a sun"));

    // Half a sun, or shadow rays without one: clap's usage errors.
    for flags in [
        &["--sun-zenith-deg", "30"][..],
        &["--sun-utc", "2024-06-21T12:00:00Z"][..],
        &["--sun-shadow-rays", "4"][..],
        &["--latitude-deg", "51.5"][..],
        &["--altitude-m", "20"][..],
    ] {
        trace_plate(dir.path(), Path::new("none"), "half", flags).code(2);
    }
}
