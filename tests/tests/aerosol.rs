//! LOWTRAN7's aerosol models in `irsig-atmos plan`: `--aerosol MODEL
//! --visibility-km V` reach every deck's card 2, checked against physics with real
//! LOWTRAN7 runs: each model's card 2 as the plan wrote it, on a horizontal path at
//! 0.55 µm, gives the extinction of Koschmieder's law (LOWTRAN's VIS is the meteorological
//! range, aerosol and air together: 3.912/VIS per km); a built atmosphere's 8–14 µm
//! transmittance with aerosol lies below the clear one on every path. A plan without the
//! flags (or with `--aerosol none`) is byte for byte the plan of before; bad flags are
//! refused naming the flag, a bad aerosol in a plan file at its line and column, with
//! nothing written.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH; these tests never skip.

// A visibility written to a card and read back: equality is exact.
#![allow(clippy::float_cmp)]

use std::path::{Path, PathBuf};

use irsig_formats::canonical;
use irsig_formats::radtran::tape5;
use irsig_tests::{bin, lowtran};

/// flatten + plan for the quickstart scene into `dir`, US Standard 1976, with `extra` flags.
fn quickstart_plan(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    irsig_tests::quickstart_plan(dir, name, &["--atmosphere", "us-std-1976"], extra)
}

/// Every file of a plan directory, by relative path.
fn files(plan: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = vec![(
        "plan.ron".to_owned(),
        std::fs::read(plan.join("plan.ron")).unwrap(),
    )];
    let mut runs: Vec<PathBuf> = std::fs::read_dir(plan.join("runs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    runs.sort();
    for r in runs {
        out.push((
            r.file_name().unwrap().to_string_lossy().into_owned(),
            std::fs::read(&r).unwrap(),
        ));
    }
    out
}

/// Runs LOWTRAN7 on `deck` and returns TAPE7.
fn run_lowtran(deck: &str) -> String {
    irsig_tests::run_lowtran(deck).tape7
}

/// The plan's deck `deck` with card 3 replaced by a horizontal path of `range_km` at the
/// ground and card 4 by 0.55 µm (18180 cm⁻¹, the nearest 20 cm⁻¹ step), transmittance
/// only (IEMSCT 0, ITYPE 1): cards 1's model and 2 stay as the plan wrote them.
fn horizontal_at_550nm(deck: &str, range_km: f64) -> String {
    let mut d = tape5::parse("deck", deck).unwrap();
    let tape5::Step::Full(c) = &mut d.steps[0] else {
        panic!("a full first calculation")
    };
    c.card1.itype = 1;
    c.card1.iemsct = 0;
    c.geometry.card3 = tape5::Card3::Path {
        h1_km: 0.0,
        h2_km: 0.0,
        angle_deg: 0.0,
        range_km,
        beta_deg: 0.0,
        ro_km: 0.0,
        len: 0,
    };
    c.card4.v1_per_cm = 18_180.0;
    c.card4.v2_per_cm = 18_180.0;
    c.card4.dv_per_cm = 20.0;
    tape5::write(&d).unwrap()
}

/// The total transmittance of the first row of an IEMSCT 0 TAPE7.
fn first_total_transmittance(tape7: &str) -> f64 {
    let row = tape7
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("FREQ"))
        .nth(1)
        .expect("a row after the column header");
    row.split_whitespace().nth(1).unwrap().parse().unwrap()
}

#[test]
fn each_aerosol_gives_koschmieders_extinction_at_550_nm_with_lowtran7() {
    let dir = tempfile::tempdir().unwrap();
    let range_km = 5.0;
    let radiosonde = [
        "--radiosonde",
        "formats/legacy/samples/us-std-1976-illustrative.rsd",
    ];
    for (model, vis_km, extra) in [
        ("rural", 10.0, None),
        // LOWTRAN7's user model (MODEL 7) takes card 2's aerosol through its levels.
        ("rural-radiosonde", 10.0, None),
        ("rural", 23.0, None),
        ("urban", 5.0, None),
        ("maritime", 15.0, None),
        ("tropospheric", 50.0, None),
        ("desert", 8.0, Some("7")),
    ] {
        let (aerosol, model_flags): (&str, &[&str]) = match model.strip_suffix("-radiosonde") {
            Some(a) => (a, &radiosonde),
            None => (model, &["--atmosphere", "us-std-1976"]),
        };
        let mut flags = vec![
            "--aerosol".to_owned(),
            aerosol.to_owned(),
            "--visibility-km".to_owned(),
            vis_km.to_string(),
        ];
        if let Some(w) = extra {
            flags.extend(["--wind-speed-m-s".to_owned(), w.to_owned()]);
        }
        let flags: Vec<&str> = flags.iter().map(String::as_str).collect();
        let plan = irsig_tests::quickstart_plan(
            dir.path(),
            &format!("{model}-{vis_km}"),
            model_flags,
            &flags,
        );
        let all = files(&plan);
        // Every deck carries the aerosol (card 2, `6I5,5F10.3`: IHAZE in columns 1-5,
        // VIS in 31-40, WSS in 41-50).
        let ihaze = match aerosol {
            "rural" => 1,
            "urban" => 5,
            "maritime" => 4,
            "tropospheric" => 6,
            _ => 10,
        };
        for (name, bytes) in &all[1..] {
            let text = std::str::from_utf8(bytes).unwrap();
            let card2 = text.lines().nth(1).unwrap();
            assert_eq!(card2[..5].trim(), ihaze.to_string(), "{name}: {card2}");
            assert_eq!(
                card2[30..40].trim().parse::<f64>().unwrap(),
                vis_km,
                "{name}"
            );
        }
        let plan_text = String::from_utf8(all[0].1.clone()).unwrap();
        assert!(plan_text.contains("aerosol"), "{plan_text}");
        // The cards reach LOWTRAN7: a horizontal path at 0.55 µm is attenuated by
        // exp(-3.912 R / VIS). LOWTRAN's own terms at this wavenumber keep it within
        // 1 % in the extinction coefficient: its Rayleigh term here against the 0.01159
        // per km its visibility assumes (about 1 %% of the air's share), the Chappuis
        // ozone band (2e-4 per km) and τ's 4 printed digits.
        let deck = std::str::from_utf8(&all[1].1).unwrap();
        // Card 1's MODEL: 7, the user model, for the radiosonde.
        let want_model = if model_flags == radiosonde { "7" } else { "6" };
        assert_eq!(deck[..5].trim(), want_model, "{deck}");
        let tau = first_total_transmittance(&run_lowtran(&horizontal_at_550nm(deck, range_km)));
        let k_lowtran = -tau.ln() / range_km;
        let k_koschmieder = 3.912 / vis_km;
        eprintln!(
            "{model} {vis_km} km: LOWTRAN7 {k_lowtran:.5} per km at 0.55 um, Koschmieder {k_koschmieder:.5}: {:+.2} %",
            100.0 * (k_lowtran / k_koschmieder - 1.0)
        );
        assert!(
            (k_lowtran / k_koschmieder - 1.0).abs() < 0.01,
            "{model} at {vis_km} km: LOWTRAN7's extinction at 0.55 um is {k_lowtran} per km, Koschmieder's {k_koschmieder}"
        );
    }
}

#[test]
fn an_aerosol_lowers_the_8_to_14_um_transmittance_of_every_path() {
    let dir = tempfile::tempdir().unwrap();
    // A small plan: a few slant paths, the ground's sky, every 10 cm-1.
    let plan_text = |aerosol: &str| {
        format!(
            "(
  name: \"haze\",
  model: Standard(6),
  wavenumber_per_cm: (710.0, 1250.0, 10.0),
  path_end_m: 1.0,
  observers_m: [1000.0],
  levels_m: [1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 20.0, 40.0],
  ground_sky_zenith_deg: [0.0],
  hemispheric: [],
  slant_altitude_m: [300.0, 1000.0],
  slant_nadir_deg: [0.0, 60.0],
  sky_altitude_m: [0.0],
  sky_zenith_deg: [0.0, 60.0],
{aerosol})
"
        )
    };
    let build = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::create_dir(&p).unwrap();
        std::fs::write(p.join("plan.ron"), text).unwrap();
        let out = dir.path().join(format!("{name}.spa"));
        bin("irsig-atmos")
            .env("IRSIG_LOWTRAN", lowtran())
            .arg("build")
            .arg(&p)
            .args(["--atmosphere", "us-std-1976", "-o"])
            .arg(&out)
            .assert()
            .success();
        canonical::read_spectral_atmosphere("built", &std::fs::read(&out).unwrap()).unwrap()
    };
    let clear = build("clear", &plan_text(""));
    let hazy = build(
        "hazy",
        &plan_text("  aerosol: Some((model: Rural, visibility_m: 5000.0)),\n"),
    );
    assert!(clear.source.contains("IHAZE=0"), "{}", clear.source);
    assert!(
        hazy.source
            .contains("IHAZE=1 (rural aerosol, meteorological range 5 km)"),
        "{}",
        hazy.source
    );
    let (c, h) = (clear.slant.unwrap(), hazy.slant.unwrap());
    let mut lowest_ratio = 1.0_f64;
    for (k, (tc, th)) in c.transmission.iter().zip(&h.transmission).enumerate() {
        // Where the clear path is opaque both print 0.
        if *tc > 1e-3 {
            assert!(th < tc, "value {k}: hazy {th} against clear {tc}");
            lowest_ratio = lowest_ratio.min(f64::from(th / tc));
        }
    }
    // A 5 km rural haze takes more than a few per cent off a 1 km path at 60 deg in the
    // window: a bound any aerosol reaching LOWTRAN passes and none fails.
    assert!(lowest_ratio < 0.9, "{lowest_ratio}");
}

#[test]
fn a_plan_without_aerosol_flags_is_the_plan_of_before() {
    let dir = tempfile::tempdir().unwrap();
    let plain = quickstart_plan(dir.path(), "plain", &[]);
    let none = quickstart_plan(dir.path(), "none", &["--aerosol", "none"]);
    let (a, b) = (files(&plain), files(&none));
    assert_eq!(a, b);
    let text = String::from_utf8(a[0].1.clone()).unwrap();
    assert!(!text.contains("aerosol"), "{text}");
    // IHAZE 0 and VIS blank-zero in every deck, as before aerosols existed.
    for (name, bytes) in &a[1..] {
        let card2 = std::str::from_utf8(bytes)
            .unwrap()
            .lines()
            .nth(1)
            .unwrap()
            .to_owned();
        assert_eq!(card2[..5].trim(), "0", "{name}: {card2}");
    }
}

#[test]
fn bad_aerosol_flags_and_plan_fields_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (flags, named) in [
        (&["--aerosol", "fog"][..], "--aerosol"),
        (&["--aerosol", "rural"][..], "--visibility-km"),
        (&["--visibility-km", "10"][..], "--visibility-km"),
        (
            &["--aerosol", "none", "--visibility-km", "10"][..],
            "--visibility-km",
        ),
        (
            &["--aerosol", "rural", "--visibility-km", "0"][..],
            "--visibility-km",
        ),
        (
            &["--aerosol", "rural", "--visibility-km", "-3"][..],
            "--visibility-km",
        ),
        (
            &["--aerosol", "rural", "--visibility-km", "NaN"][..],
            "--visibility-km",
        ),
        (
            &["--aerosol", "rural", "--visibility-km", "400"][..],
            "--visibility-km",
        ),
        (
            &["--aerosol", "desert", "--visibility-km", "10"][..],
            "--wind-speed-m-s",
        ),
        (
            &[
                "--aerosol",
                "urban",
                "--visibility-km",
                "10",
                "--wind-speed-m-s",
                "5",
            ][..],
            "--wind-speed-m-s",
        ),
        (
            &[
                "--aerosol",
                "desert",
                "--visibility-km",
                "10",
                "--wind-speed-m-s",
                "40",
            ][..],
            "--wind-speed-m-s",
        ),
    ] {
        let out = dir.path().join("never");
        let mut cmd = bin("irsig-atmos");
        cmd.args(["plan", "--scene", "no-scene.raw", "--view", "no-view.ron"]);
        cmd.args(["--atmosphere", "us-std-1976"]);
        // `=`: clap would take a separate `-3` for a flag of its own.
        for pair in flags.chunks(2) {
            cmd.arg(format!("{}={}", pair[0], pair[1]));
        }
        let assert = cmd.arg("-o").arg(&out).assert().code(2);
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
        assert!(stderr.contains(named), "{flags:?}: {stderr}");
        assert!(!out.exists());
    }
    // In a plan file: refused at the value's line and column before LOWTRAN7 runs.
    for (aerosol, bad, says) in [
        (
            "(model: Rural, visibility_m: 0.0)",
            "0.0",
            "meteorological range",
        ),
        (
            "(model: Rural, visibility_m: NaN)",
            "NaN",
            "meteorological range",
        ),
        (
            "(model: Urban, visibility_m: 9000.0, wind_speed_m_s: Some(3.0))",
            "Some(3.0)",
            "desert",
        ),
        ("(model: Fog, visibility_m: 9000.0)", "Fog", "Fog"),
    ] {
        let text = format!(
            "(
  name: \"bad\",
  model: Standard(6),
  wavenumber_per_cm: (710.0, 1250.0, 90.0),
  path_end_m: 1.0,
  observers_m: [1000.0],
  levels_m: [1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0],
  ground_sky_zenith_deg: [0.0],
  hemispheric: [],
  slant_altitude_m: [1000.0],
  slant_nadir_deg: [0.0],
  sky_altitude_m: [0.0],
  sky_zenith_deg: [0.0],
  aerosol: Some({aerosol}),
)
"
        );
        let at = text.find("aerosol: Some(").unwrap();
        let at = at + text[at..].find(bad).unwrap();
        let line = text[..at].matches('\n').count() + 1;
        let column = at - text[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
        let plan_dir = dir.path().join(format!("plan-{line}-{column}-{bad}"));
        std::fs::create_dir(&plan_dir).unwrap();
        std::fs::write(plan_dir.join("plan.ron"), &text).unwrap();
        let out = dir.path().join("never.spa");
        let assert = bin("irsig-atmos")
            .env("IRSIG_LOWTRAN", lowtran())
            .arg("build")
            .arg(&plan_dir)
            .arg("-o")
            .arg(&out)
            .assert()
            .code(1);
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
        assert!(stderr.contains(says), "{aerosol}: {stderr}");
        assert!(
            stderr.contains(&format!("plan.ron:{line}:")),
            "{aerosol}: line {line}: {stderr}"
        );
        assert!(!out.exists());
    }
}
