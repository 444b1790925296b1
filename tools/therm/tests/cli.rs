//! irsig-therm from the command line: a lone plate's steady balance against its root found by
//! hand, what is written and how it is named, the same bytes at any thread count, and bad
//! input refused with nothing written.

use std::path::Path;
use std::process::{Command, Output};

const SIGMA: f64 = 5.670_374_419e-8;

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

fn therm() -> Command {
    Command::new(env!("CARGO_BIN_EXE_irsig-therm"))
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A 2 m square plate of two facets facing up, 1 m above nothing, and a 1 m cube
/// (`block`) beside it.
fn scene(dir: &Path) -> String {
    write(
        dir,
        "scene.ron",
        "(objects: [\"plate\", \"block\"],
          positions_m: [(-1.0, -1.0, 1.0), (1.0, -1.0, 1.0), (1.0, 1.0, 1.0), (-1.0, 1.0, 1.0),
                        (10.0, 0.0, 0.0), (11.0, 0.0, 0.0), (11.0, 1.0, 0.0), (10.0, 1.0, 0.0),
                        (10.0, 0.0, 1.0), (11.0, 0.0, 1.0), (11.0, 1.0, 1.0), (10.0, 1.0, 1.0)],
          facets: [(vertices: (0, 1, 2), material: 1, temperature_k: 300.0, object: 0),
                   (vertices: (0, 2, 3), material: 1, temperature_k: 300.0, object: 0),
                   (vertices: (8, 9, 10), material: 2, temperature_k: 300.0, object: 1),
                   (vertices: (8, 10, 11), material: 2, temperature_k: 300.0, object: 1)])",
    )
}

/// A thin steel plate insulated behind (absorptance 0.6, emissivity 0.9), and `block`'s
/// material, given or not a thermal record.
fn materials(dir: &Path, block_thermal: bool) -> String {
    let thermal = if block_thermal {
        ", thermal: Some((layers: [(thickness_m: 0.2, conductivity_w_m_k: 1.4, density_kg_m3: \
         2300.0, specific_heat_j_kg_k: 880.0, source: \"t\")], back: Adiabatic, \
         solar_absorptance: Some(0.7), thermal_emissivity: Some(0.9), source: \"t\"))"
    } else {
        ""
    };
    write(
        dir,
        "mats.ron",
        &format!(
            "(materials: [
               (id: 1, name: \"steel\", emissivity: [(0.0, 0.9)], specular_fraction: 0.0, \
                source: \"t\", thermal: Some((layers: [(thickness_m: 0.002, conductivity_w_m_k: \
                45.0, density_kg_m3: 7800.0, specific_heat_j_kg_k: 480.0, source: \"t\")], back: \
                Adiabatic, solar_absorptance: Some(0.6), thermal_emissivity: Some(0.9), source: \
                \"t\"))),
               (id: 2, name: \"concrete\", emissivity: [(0.0, 0.9)], specular_fraction: 0.0, \
                source: \"t\"{thermal})])"
        ),
    )
}

/// Two days of constant weather at 300 K air, 3 m/s wind, no beam, 200 W/m² of diffuse
/// sky and 380 W/m² of sky longwave, hourly.
fn weather(dir: &Path) -> String {
    let mut text = String::from(
        "time,air_temperature[K],dew_point[K],pressure[Pa],wind_speed[m/s],dni[W/m2],dhi[W/m2],longwave_down[W/m2]\n",
    );
    for h in 0..49 {
        text.push_str(&format!(
            "2026-07-{:02}T{:02}:00:00Z,300,285,100000,3,0,200,380\n",
            14 + h / 24,
            h % 24
        ));
    }
    write(dir, "weather.csv", &text)
}

/// Facet temperatures of a binary raw scene, through the canonical reader.
fn temperatures(path: &Path) -> Vec<f64> {
    let bytes = std::fs::read(path).unwrap();
    let scene = irsig_formats::canonical::read_raw_scene("s", &bytes).unwrap();
    scene.facets.iter().map(|f| f.temperature_k).collect()
}

#[test]
fn a_lone_plate_settles_at_the_root_of_its_balance() {
    let dir = tempfile::tempdir().unwrap();
    let prefix = dir.path().join("t");
    let out = therm()
        .args([
            &scene(dir.path()),
            "--materials",
            &materials(dir.path(), true),
        ])
        .args([
            "--weather",
            &weather(dir.path()),
            "--at",
            "2026-07-15T12:00Z",
        ])
        .args([
            "--latitude-deg",
            "0",
            "--longitude-deg",
            "0",
            "--spin-up-h",
            "24",
        ])
        .args(["--convection", "mcadams", "--hemisphere-rays", "256", "-o"])
        .arg(&prefix)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let t = temperatures(&dir.path().join("t.raw"));
    // The plate sees only sky (nothing is above it): a · 200 + ε · 380 = ε σ T⁴ + h (T −
    // 300), h = 5.7 + 3.8 · 3 (McAdams), solved by bisection. Its 2 mm of steel settles in
    // minutes; a day of spin-up leaves nothing of the start.
    let h = 5.7 + 3.8 * 3.0;
    let balance = |t: f64| 0.6 * 200.0 + 0.9 * 380.0 - 0.9 * SIGMA * t.powi(4) - h * (t - 300.0);
    let (mut lo, mut hi) = (250.0, 350.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if balance(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    for (facet, t) in t.iter().take(2).enumerate() {
        assert!((t - lo).abs() < 0.05, "facet {facet}: {t} against {lo}");
    }
    // The block's top sees nothing above it either, but it is 0.2 m of concrete: it has
    // not reached its balance after a day, and is below the air (its start).
    assert!(t[2] > 290.0 && t[2] < 310.0, "{}", t[2]);
}

#[test]
fn several_moments_are_named_by_time_and_the_history_holds_every_step() {
    let dir = tempfile::tempdir().unwrap();
    let prefix = dir.path().join("d");
    let history = dir.path().join("h.thm");
    let out = therm()
        .args([
            &scene(dir.path()),
            "--materials",
            &materials(dir.path(), true),
        ])
        .args(["--weather", &weather(dir.path())])
        .args(["--at", "2026-07-15T10:00Z/2026-07-15T12:00Z/PT1H"])
        .args([
            "--latitude-deg",
            "0",
            "--longitude-deg",
            "0",
            "--spin-up-h",
            "6",
        ])
        .args(["--step-s", "600", "--history"])
        .arg(&history)
        .arg("-o")
        .arg(&prefix)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    for stamp in ["20260715T100000Z", "20260715T110000Z", "20260715T120000Z"] {
        assert!(
            dir.path().join(format!("d.{stamp}.raw")).exists(),
            "{stamp}"
        );
    }
    let bytes = std::fs::read(&history).unwrap();
    let h = irsig_formats::canonical::binary_history::decode("h", &bytes).unwrap();
    // 10:00 to 12:00 every 600 s: 13 rows of 4 facets.
    assert_eq!(h.time_s.len(), 13);
    assert_eq!(h.facets, 4);
    let t10 = irsig_formats::time::parse_time("2026-07-15T10:00Z").unwrap();
    assert!((h.time_s[0] - t10).abs() < 1e-6);
    // The last row is the 12:00 scene's, to f32.
    let last = temperatures(&dir.path().join("d.20260715T120000Z.raw"));
    for (a, b) in h.at(12).iter().zip(&last) {
        assert!((f64::from(*a) - b).abs() < 1e-4);
    }
    assert_eq!(h.provenance.step_s.to_bits(), 600.0_f64.to_bits());
    assert!(h.provenance.inputs.iter().any(|r| r.role == "weather"));
}

#[test]
fn the_same_bytes_at_any_thread_count() {
    let dir = tempfile::tempdir().unwrap();
    let (s, m, w) = (
        scene(dir.path()),
        materials(dir.path(), true),
        weather(dir.path()),
    );
    let run = |threads: &str, name: &str| {
        let out = therm()
            .args([
                &s,
                "--materials",
                &m,
                "--weather",
                &w,
                "--at",
                "2026-07-15T12:00Z",
            ])
            .args([
                "--latitude-deg",
                "10",
                "--longitude-deg",
                "20",
                "--spin-up-h",
                "6",
            ])
            .args(["--threads", threads, "-o"])
            .arg(dir.path().join(name))
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", stderr(&out));
        std::fs::read(dir.path().join(format!("{name}.raw"))).unwrap()
    };
    assert_eq!(run("1", "one"), run("2", "two"));
}

#[test]
fn a_material_without_thermal_properties_is_refused_by_name_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let prefix = dir.path().join("t");
    let out = therm()
        .args([
            &scene(dir.path()),
            "--materials",
            &materials(dir.path(), false),
        ])
        .args([
            "--weather",
            &weather(dir.path()),
            "--at",
            "2026-07-15T12:00Z",
        ])
        .args(["--latitude-deg", "0", "--longitude-deg", "0", "-o"])
        .arg(&prefix)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let e = stderr(&out);
    assert!(e.contains("`concrete`") && e.contains("block"), "{e}");
    assert!(!dir.path().join("t.raw").exists());
    // Held, the block needs no thermal record.
    let out = therm()
        .args([
            &scene(dir.path()),
            "--materials",
            &materials(dir.path(), false),
        ])
        .args([
            "--weather",
            &weather(dir.path()),
            "--at",
            "2026-07-15T12:00Z",
        ])
        .args([
            "--latitude-deg",
            "0",
            "--longitude-deg",
            "0",
            "--spin-up-h",
            "2",
        ])
        .args(["--hold", "block=330", "-o"])
        .arg(&prefix)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let t = temperatures(&dir.path().join("t.raw"));
    assert_eq!(t[2].to_bits(), 330.0_f64.to_bits());
}

#[test]
fn times_off_the_grid_or_outside_the_weather_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (s, m, w) = (
        scene(dir.path()),
        materials(dir.path(), true),
        weather(dir.path()),
    );
    let prefix = dir.path().join("t");
    let run = |args: &[&str]| {
        therm()
            .args([&s, "--materials", &m, "--weather", &w])
            .args(["--latitude-deg", "0", "--longitude-deg", "0"])
            .args(args)
            .arg("-o")
            .arg(&prefix)
            .output()
            .unwrap()
    };
    // 12:00 and 12:07 are not 300 s apart.
    let out = run(&[
        "--at",
        "2026-07-15T12:00Z",
        "--at",
        "2026-07-15T12:07Z",
        "--spin-up-h",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("nearest are"), "{}", stderr(&out));
    // Three days of spin-up before 12:00 on the 15th reach back before the record.
    let out = run(&["--at", "2026-07-15T12:00Z"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("2026-07-12T12:00:00Z"),
        "{}",
        stderr(&out)
    );
    // A zone that does not exist; a range that ends before it starts.
    for at in [
        "2026-07-15T12:00[Atlantis/Capital]",
        "2026-07-15T12:00Z/2026-07-15T10:00Z/PT1H",
    ] {
        let out = run(&["--at", at]);
        assert_eq!(out.status.code(), Some(2), "{at}: {}", stderr(&out));
    }
    // An object that does not exist.
    let out = run(&[
        "--at",
        "2026-07-15T12:00Z",
        "--hold",
        "bus=300",
        "--spin-up-h",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("`plate` (#0), `block` (#1)"),
        "{}",
        stderr(&out)
    );
    assert!(!dir.path().join("t.raw").exists());
}

#[test]
fn a_tolerance_is_kept_against_the_reference_settings_on_every_facet() {
    // The guarantee checked from outside the pilot: the scene traced with the settings the
    // tolerance chose, against the same scene with every model at its most accurate
    // setting, facet by facet.
    let dir = tempfile::tempdir().unwrap();
    let (s, m, w) = (
        scene(dir.path()),
        materials(dir.path(), true),
        weather(dir.path()),
    );
    let decision = dir.path().join("d.ron");
    let common = |cmd: &mut Command| {
        cmd.args([
            &s,
            "--materials",
            &m,
            "--weather",
            &w,
            "--at",
            "2026-07-15T12:00Z",
        ])
        .args(["--latitude-deg", "30", "--longitude-deg", "0"]);
    };
    let mut cmd = therm();
    common(&mut cmd);
    let out = cmd
        .args(["--tolerance", "0.3", "--decision-out"])
        .arg(&decision)
        .arg("-o")
        .arg(dir.path().join("chosen"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("--tolerance 0.3 K"),
        "{}",
        stderr(&out)
    );
    let text = std::fs::read_to_string(&decision).unwrap();
    let d: irsig_model::thermal_decision::ThermalDecision =
        irsig_formats::canonical::from_ron_as("d.ron", &text, "decision").unwrap();
    assert!(d.measured_p99_k <= 0.3, "{d:?}");
    let spin = d
        .models
        .iter()
        .find(|c| c.model == "spin-up")
        .unwrap()
        .reference
        .trim_end_matches(" h")
        .to_owned();
    let mut cmd = therm();
    common(&mut cmd);
    let out = cmd
        .args([
            "--step-s",
            "60",
            "--scheme",
            "tr-bdf2",
            "--first-cell-mm",
            "0.25",
        ])
        .args([
            "--shadow-samples",
            "8",
            "--hemisphere-rays",
            "1024",
            "--spin-up-h",
            &spin,
        ])
        .arg("-o")
        .arg(dir.path().join("reference"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let chosen = temperatures(&dir.path().join("chosen.raw"));
    let reference = temperatures(&dir.path().join("reference.raw"));
    for (i, (a, b)) in chosen.iter().zip(&reference).enumerate() {
        assert!((a - b).abs() <= 0.3, "facet {i}: {a} against {b}");
    }
}

#[test]
fn sunlight_and_sky_from_a_loads_table_reach_a_lone_plate() {
    // The weather gives no radiation; the sample loads table (LOWTRAN7, mid-latitude
    // summer, day 172) gives the sunlight and the sky. At 45° N, 0° E on 21 June near noon
    // the sun is about 21.6° from the zenith, between the table's rows.
    let dir = tempfile::tempdir().unwrap();
    let mut text =
        String::from("time,air_temperature[K],dew_point[K],pressure[Pa],wind_speed[m/s]\n");
    for h in 0..40 {
        text.push_str(&format!(
            "2026-06-{:02}T{:02}:00:00Z,300,285,100000,3\n",
            20 + h / 24,
            h % 24
        ));
    }
    let weather = write(dir.path(), "w.csv", &text);
    let table_path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../formats/canonical/samples/broadband-loads.ron"
    );
    let at = "2026-06-21T12:02:00Z";
    let out = therm()
        .args([
            &scene(dir.path()),
            "--materials",
            &materials(dir.path(), true),
        ])
        .args([
            "--weather",
            &weather,
            "--loads-table",
            table_path,
            "--at",
            at,
        ])
        .args([
            "--latitude-deg",
            "45",
            "--longitude-deg",
            "0",
            "--spin-up-h",
            "12",
        ])
        .args(["--step-s", "60", "--convection", "mcadams", "--history"])
        .arg(dir.path().join("h.thm"))
        .arg("-o")
        .arg(dir.path().join("t"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    // What the table gives at that sun, by the library the tool uses, and the plate's
    // balance solved by hand with it.
    let text = std::fs::read_to_string(table_path).unwrap();
    let table: irsig_model::loads::BroadbandLoads =
        irsig_formats::canonical::from_ron("t", &text).unwrap();
    let sun = irsig_atmosphere::sun::SunSpec::At {
        utc: at.into(),
        latitude_deg: 45.0,
        longitude_deg: 0.0,
        altitude_m: 0.0,
        refraction: None,
        delta_t_s: None,
        delta_ut1_s: None,
    }
    .position()
    .unwrap();
    let loads = irsig_atmosphere::loads::sun_loads_at(&table, sun.zenith_deg).unwrap();
    let ghi = loads.global_horizontal_w_m2;
    // The table's sky: its effective emissivity at the weather's 300 K air.
    let sky = table.longwave_down_w_m2 * (300.0 / table.air_temperature_k).powi(4);
    let h = 5.7 + 3.8 * 3.0;
    let balance = |t: f64| 0.6 * ghi + 0.9 * sky - 0.9 * SIGMA * t.powi(4) - h * (t - 300.0);
    let (mut lo, mut hi) = (250.0, 400.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if balance(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = temperatures(&dir.path().join("t.raw"));
    // The 2 mm plate lags the sun's slow climb by a few seconds' worth: 0.05 K.
    assert!(
        (t[0] - lo).abs() < 0.05,
        "{} against {lo} (GHI {ghi})",
        t[0]
    );
    let h = irsig_formats::canonical::binary_history::decode(
        "h",
        &std::fs::read(dir.path().join("h.thm")).unwrap(),
    )
    .unwrap();
    assert!(
        h.provenance.radiation.contains("LOWTRAN7"),
        "{}",
        h.provenance.radiation
    );
    assert!(h.provenance.inputs.iter().any(|r| r.role == "loads"));
}

#[test]
fn each_moment_is_written_to_the_raw_file_named_for_it() {
    // A pipeline stage names every file it makes: one --raw per moment, in time order, the
    // same bytes as the -o PREFIX names; as many --raw as moments, or nothing is done.
    let dir = tempfile::tempdir().unwrap();
    let (s, m, w) = (
        scene(dir.path()),
        materials(dir.path(), true),
        weather(dir.path()),
    );
    let base = |out: &mut Command| {
        out.args([&s, "--materials", &m, "--weather", &w])
            .args(["--latitude-deg", "0", "--longitude-deg", "0"])
            .args(["--spin-up-h", "6", "--step-s", "600"]);
    };
    let mut by_prefix = therm();
    base(&mut by_prefix);
    let out = by_prefix
        .args(["--at", "2026-07-15T10:00Z/2026-07-15T11:00Z/PT1H", "-o"])
        .arg(dir.path().join("p"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let mut named = therm();
    base(&mut named);
    // The moments given out of order are still solved in time order; the files follow it.
    let out = named
        .args(["--at", "2026-07-15T11:00Z", "--at", "2026-07-15T10:00Z"])
        .arg("--raw")
        .arg(dir.path().join("ten.raw"))
        .arg("--raw")
        .arg(dir.path().join("eleven.raw"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("ten.raw"), read("p.20260715T100000Z.raw"));
    assert_eq!(read("eleven.raw"), read("p.20260715T110000Z.raw"));
    // Two moments, one file: bad usage, nothing written.
    let mut short = therm();
    base(&mut short);
    let out = short
        .args(["--at", "2026-07-15T10:00Z/2026-07-15T11:00Z/PT1H", "--raw"])
        .arg(dir.path().join("one.raw"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("one --raw per moment"),
        "{}",
        stderr(&out)
    );
    assert!(!dir.path().join("one.raw").exists());
}
