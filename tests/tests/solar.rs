//! The atmosphere in sunlight, first part: the sun's direct beam from real
//! LOWTRAN7 direct solar irradiance runs (IEMSCT = 3). A small plan with a sun is built by
//! `irsig-atmos build`; its direct irradiance on plates at and between the table's
//! altitudes is checked against hand integrals over the TAPE7 of LOWTRAN7 runs made here
//! from decks written by hand; LOWTRAN7's extraterrestrial spectrum against the solar
//! constant; `irsig-atmos plan --sun-zenith-deg/--day-of-year` against the deck format;
//! a sun at or below the horizon, or a day that is none, refused at the flag or at its
//! line and column in the plan; the sun of a view file planned as the flags plan it.
//! `solar_trace.rs` traces the plate by that sun.
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
use irsig_tests::sunlit_plate::{DAY, ZENITH_DEG, build, plan_ron_over, plate, view_with_sun};
use irsig_tests::{bin, lowtran};

/// The spectral range: the whole of LOWTRAN7's solar spectrum (0.2–500 µm) every 20 cm⁻¹.
const V1: f64 = 20.0;
const V2: f64 = 50_000.0;
const DV: f64 = 20.0;

/// A plan of a few thermal paths and the sun's beam at 0, 300 and 1000 m, as RON.
fn plan_ron(zenith: &str, day: &str) -> String {
    plan_ron_over(zenith, day, [V1, V2, DV])
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
