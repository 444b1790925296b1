//! irsig-trace from the command line: the outputs of a plate seen straight down against a
//! hand computation, sequences, the probe, the >15-material message and bad input.

use std::path::Path;
use std::process::Command;

const SIGMA: f64 = 5.670_374_419e-8;

fn total_radiance(t: f64) -> f64 {
    SIGMA * t.powi(4) / std::f64::consts::PI
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

/// A 20 m plate of two facets: material 1 (ε = 0.9 flat, diffuse, 300 K) and material
/// `second` (blackbody, 320 K).
fn inputs(dir: &Path, second: u16) -> (String, String, String) {
    let scene = write(
        dir,
        "scene.ron",
        &format!(
            "(terrain: (temperature_k: 286.0, emissivity: 1.0), objects: [\"plate\"],
              positions_m: [(-10.0, -10.0, 0.0), (10.0, -10.0, 0.0), (10.0, 10.0, 0.0), (-10.0, 10.0, 0.0)],
              facets: [(vertices: (0, 1, 2), material: 1, temperature_k: 300.0, object: 0),
                       (vertices: (0, 2, 3), material: {second}, temperature_k: 320.0, object: 0)])"
        ),
    );
    let mats = write(
        dir,
        "mats.ron",
        &format!(
            "(materials: [
               (id: 1, name: \"grey\", emissivity: [(0.0, 0.9), (90.0, 0.9)], specular_fraction: 0.0, source: \"test\"),
               (id: {second}, name: \"black\", emissivity: [(0.0, 1.0)], specular_fraction: 0.0, source: \"test\")])"
        ),
    );
    let view = write(
        dir,
        "view.ron",
        "Legacy(position_m: (0.0, 0.0, 100.0), pixels: (8, 6), omega_phi_kappa_deg: (0.0, 0.0, 0.0), fov_deg: (5.0, 4.0), gain_dc_per_k: Some(2.0))",
    );
    (scene, mats, view)
}

fn trace() -> Command {
    Command::new(env!("CARGO_BIN_EXE_irsig-trace"))
}

#[test]
fn a_plate_seen_straight_down_gives_the_hand_computed_images() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    let prefix = dir.path().join("f");
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .args(["--band", "total", "--sky-radiance", "10", "-o"])
        .arg(&prefix)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |s: &str| {
        irsig_raster::read_exr(&std::fs::read(dir.path().join(format!("f.{s}.exr"))).unwrap())
            .unwrap()
    };
    let rad = read("radiance");
    let truth = read("truth");
    assert_eq!((rad.width, rad.height), (8, 6));
    let l = &rad.layer("radiance").unwrap().data;
    let mat = &truth.layer("material_primary").unwrap().data;
    // The diagonal from (−10, −10) to (10, 10) splits the plate: facet 0 (material 1) lies
    // below it (x > y). Top-left pixel looks north-west (x < y): material 2.
    let grey = 0.9 * total_radiance(300.0) + 0.1 * 10.0;
    let black = total_radiance(320.0);
    assert!((f64::from(mat[0]) - 2.0).abs() < 1e-6);
    assert!((f64::from(l[0]) - black).abs() < 1e-4 * black);
    let last = 8 * 6 - 1;
    assert!((f64::from(mat[last]) - 1.0).abs() < 1e-6);
    assert!((f64::from(l[last]) - grey).abs() < 1e-4 * grey);
    let t_app = &truth.layer("apparent_temperature").unwrap().data;
    assert!((f64::from(t_app[0]) - 320.0).abs() < 1e-3);
    // The nibble map: material 1 → 0x10, material 2 → 0x20; PNG written.
    assert!(dir.path().join("f.map.png").exists());
    // DC image and LUT: auto-bias, 256 entries after a header and the band's line.
    let lut = std::fs::read_to_string(dir.path().join("f.lut.txt")).unwrap();
    assert_eq!(lut.lines().count(), 258);
    assert_eq!(
        lut.lines().nth(1),
        Some("# band: the whole spectrum (total)")
    );
    assert!(dir.path().join("f.dc.png").exists());
}

#[test]
fn the_default_8_to_14_um_band_gives_a_blackbody_its_own_temperature() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    let out = trace()
        .args([
            "--scene",
            &scene,
            "--materials",
            &mats,
            "--view",
            &view,
            "--probe",
            "0,0",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let t: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("apparent temperature_k"))
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    // A blackbody in a vacuum: its apparent temperature is its kinetic one in any band.
    assert!((t - 320.0).abs() < 1e-6, "{t}");
    // With a real atmosphere the path terms enter: τ < 1 and L = τ·L_s + L_u.
    let out = trace()
        .args([
            "--scene",
            &scene,
            "--materials",
            &mats,
            "--view",
            &view,
            "--probe",
            "0,0",
        ])
        .args(["--atmosphere", "us-std-1976"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    let get = |k: &str| -> f64 {
        text.lines()
            .find_map(|l| l.strip_prefix(k))
            .unwrap()
            .trim()
            .parse()
            .unwrap()
    };
    let (tau, lu, ls, l) = (
        get("τ"),
        get("L_u (W m-2 sr-1)"),
        get("surface-leaving L(0,θ)"),
        get("L at sensor (W m-2 sr-1)"),
    );
    assert!(tau > 0.5 && tau < 1.0, "{tau}");
    assert!((tau * ls + lu - l).abs() < 1e-9 * l);
}

#[test]
fn more_than_15_materials_skip_the_nibble_map_and_say_why() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 16);
    let out = trace()
        .args([
            "--scene",
            &scene,
            "--materials",
            &mats,
            "--view",
            &view,
            "--no-dc",
            "-o",
        ])
        .arg(dir.path().join("f"))
        .output()
        .unwrap();
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("interaction map not written"));
    assert!(!dir.path().join("f.map.png").exists());
    assert!(dir.path().join("f.truth.exr").exists());
    assert!(!dir.path().join("f.dc.png").exists());
}

#[test]
fn a_list_of_views_gives_numbered_frames_and_the_probe_prints_every_term() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, _) = inputs(dir.path(), 2);
    let views = write(
        dir.path(),
        "views.ron",
        "[Legacy(position_m: (0.0, 0.0, 100.0), pixels: (4, 4), omega_phi_kappa_deg: (0.0, 0.0, 0.0), fov_deg: (5.0, 5.0)),
          LookAt(position_m: (0.0, -50.0, 50.0), target_m: (0.0, 0.0, 0.0), pixels: (6, 2), fov_deg: (10.0, 5.0))]",
    );
    let out = trace()
        .args([
            "--scene",
            &scene,
            "--materials",
            &mats,
            "--view",
            &views,
            "-o",
        ])
        .arg(dir.path().join("seq"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for n in ["0001", "0002"] {
        assert!(dir.path().join(format!("seq.{n}.radiance.exr")).exists());
    }
    let out = trace()
        .args([
            "--scene",
            &scene,
            "--materials",
            &mats,
            "--view",
            &views,
            "--probe",
            "3,3",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for term in [
        "event",
        "emissivity",
        "L_T",
        "τ",
        "L_u",
        "apparent temperature_k",
    ] {
        assert!(text.contains(term), "{term} missing from\n{text}");
    }
    let out = trace()
        .args([
            "--scene",
            &scene,
            "--materials",
            &mats,
            "--view",
            &views,
            "--probe",
            "4,0",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn bad_input_exits_1_with_file_line_and_column_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, _, view) = inputs(dir.path(), 2);
    let bad = write(dir.path(), "bad.ron", "(materials: [(id: 1 name: \"x\")])");
    let out = trace()
        .args([
            "--scene",
            &scene,
            "--materials",
            &bad,
            "--view",
            &view,
            "-o",
        ])
        .arg(dir.path().join("f"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.ron:1:"), "{err}");
    assert!(!dir.path().join("f.radiance.exr").exists());
    // A facet naming a material the library lacks.
    let (_, mats, _) = inputs(dir.path(), 2);
    let scene2 = write(
        dir.path(),
        "scene2.ron",
        &std::fs::read_to_string(&scene)
            .unwrap()
            .replace("material: 2", "material: 9"),
    );
    let out = trace()
        .args([
            "--scene",
            &scene2,
            "--materials",
            &mats,
            "--view",
            &view,
            "-o",
        ])
        .arg(dir.path().join("f"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("material 9"));
    // Usage: neither -o nor --probe.
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[cfg(unix)]
#[test]
fn an_output_in_a_missing_directory_is_refused_before_tracing_and_dev_null_is_kept() {
    use std::os::unix::fs::FileTypeExt;
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    let ok = dir.path().join("ok.exr");
    let missing = dir.path().join("no-such-dir");
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .arg("--radiance-exr")
        .arg(&ok)
        .arg("--truth-exr")
        .arg(missing.join("t.exr"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    // The check's own words, which name the directory; a late failure named the staged
    // temporary (`.irsig-….tmp`) it could not create there.
    assert!(
        err.contains("is not an existing directory") && err.contains("no-such-dir"),
        "{err}"
    );
    assert!(!err.contains(".irsig-"), "{err}");
    assert!(!ok.exists());
    // A device is an output like any other, written in place (run as root, a rename
    // would have replaced /dev/null with a file).
    let lut = dir.path().join("lut.txt");
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .args(["--radiance-exr", "/dev/null", "--lut"])
        .arg(&lut)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(lut.exists());
    let kind = std::fs::symlink_metadata("/dev/null").unwrap().file_type();
    assert!(kind.is_char_device(), "{kind:?}");
}

#[test]
fn a_tolerance_runs_the_pilot_prints_and_writes_its_decision() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    let prefix = dir.path().join("f");
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .args(["--atmosphere", "us-std-1976", "--tolerance", "0.3", "-o"])
        .arg(&prefix)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    // The table names every model, and why the scene needs no bounces.
    for model in [
        "atmosphere",
        "bounces",
        "sky-view",
        "supersampling",
        "path-terms",
        "sub-bands",
    ] {
        assert!(stderr.contains(model), "{stderr}");
    }
    assert!(stderr.contains("no specular material"), "{stderr}");
    let text = std::fs::read_to_string(dir.path().join("f.decision.ron")).unwrap();
    let decision: irsig_model::decision::Decision =
        irsig_formats::canonical::from_ron("f.decision.ron", &text).unwrap();
    assert!((decision.tolerance_k - 0.3).abs() < 1e-12);
    assert!(decision.predicted.percentile_k <= 0.3, "{decision:?}");
    assert!(dir.path().join("f.radiance.exr").is_file());
    // A decision applied again gives the same image, without a pilot.
    let again = dir.path().join("g");
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .args(["--atmosphere", "us-std-1976", "--decision"])
        .arg(dir.path().join("f.decision.ron"))
        .arg("-o")
        .arg(&again)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read(dir.path().join("f.radiance.exr")).unwrap(),
        std::fs::read(dir.path().join("g.radiance.exr")).unwrap()
    );
}

/// A decision's sub-band count that the atmosphere's grid cannot make (16 sub-bands over
/// 8-8.2 um, where the built-ins' 5 cm-1 grid has 7 intervals: 1250 to 1220 cm-1) is the
/// decision file's error, at its choice: no `--sub-bands` flag was typed.
#[test]
fn a_decisions_sub_bands_the_grid_cannot_make_are_refused_at_the_decision() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    let common = |cmd: &mut Command| {
        cmd.args(["--scene", &scene, "--materials", &mats, "--view", &view])
            .args(["--atmosphere", "us-std-1976", "--band", "8-8.2"]);
    };
    let decision = dir.path().join("d.ron");
    let mut cmd = trace();
    common(&mut cmd);
    let out = cmd
        .args(["--tolerance", "1", "--pin", "sub-bands=4", "--decision-out"])
        .arg(&decision)
        .arg("--radiance-exr")
        .arg(dir.path().join("a.exr"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&decision).unwrap();
    let four = "model: r#sub-bands,\n      setting: \"4\",";
    assert!(text.contains(four), "{text}");
    std::fs::write(
        &decision,
        text.replace(four, &four.replace("\"4\"", "\"16\"")),
    )
    .unwrap();
    let line = text
        .lines()
        .position(|l| l.contains("model: r#sub-bands"))
        .unwrap()
        + 2;
    let mut cmd = trace();
    common(&mut cmd);
    let out = cmd
        .arg("--decision")
        .arg(&decision)
        .arg("--radiance-exr")
        .arg(dir.path().join("b.exr"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).replace('\n', " ");
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains(&format!("d.ron:{line}:")), "{err}");
    assert!(err.contains("this decision's `16`"), "{err}");
    assert!(err.contains("7 intervals"), "{err}");
    assert!(!err.contains("--sub-bands"), "{err}");
    assert!(!dir.path().join("b.exr").exists());
}

#[test]
fn bad_tolerances_and_pins_are_refused_before_tracing() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    for (args, says) in [
        (vec!["--tolerance", "0"], "a tolerance of 0 K"),
        (vec!["--tolerance", "-0.1"], "a tolerance of -0.1 K"),
        (
            vec!["--tolerance", "0.1", "--tolerance-percentile", "0"],
            "percentile",
        ),
        (
            vec!["--tolerance", "0.1", "--tolerance-percentile", "100.5"],
            "percentile",
        ),
        (
            vec!["--tolerance", "0.1", "--pin", "bounce=2"],
            "unknown model `bounce`",
        ),
        (
            vec!["--tolerance", "0.1", "--pin", "supersampling=0"],
            "supersampling=0",
        ),
        (vec!["--tolerance", "0.1", "--bounces", "2"], "--bounces"),
        // The sun's models exist only by day; with a tolerance the pilot chooses the
        // shadow rays.
        (
            vec!["--tolerance", "0.3", "--pin", "sun=off"],
            "this frame has no sun",
        ),
        (
            vec!["--tolerance", "0.3", "--pin", "shadow-rays=many"],
            "shadow-rays=many",
        ),
        (
            vec![
                "--tolerance",
                "0.3",
                "--sun-zenith-deg",
                "30",
                "--sun-shadow-rays",
                "4",
            ],
            "--sun-shadow-rays",
        ),
    ] {
        let out = trace()
            .args([
                "--scene",
                &scene,
                "--materials",
                &mats,
                "--view",
                &view,
                "-o",
            ])
            .arg(dir.path().join("x"))
            .args(&args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        assert!(!dir.path().join("x.radiance.exr").exists());
    }
}

#[test]
fn declared_uncertainties_give_the_error_budget_layers() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    let uncertainties = write(
        dir.path(),
        "u.ron",
        "(temperature: [(facets: All, sigma_k: 0.1), (facets: Material(2), sigma_k: 0.5)],
          emissivity: [(material: 1, sigma: 0.01)], transmission_relative: 0.0,
          path_radiance_relative: 0.0)",
    );
    let prefix = dir.path().join("f");
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .args([
            "--band",
            "total",
            "--sky-radiance",
            "10",
            "--uncertainties",
            &uncertainties,
        ])
        .arg("--truth-exr")
        .arg(&prefix)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let truth = irsig_raster::read_exr(&std::fs::read(&prefix).unwrap()).unwrap();
    let layer = |n: &str| truth.layer(n).unwrap().data.clone();
    let (mat, sig_t, sig_e, total) = (
        layer("material_primary"),
        layer("sigma_kinetic_temperature"),
        layer("sigma_emissivity"),
        layer("sigma_total"),
    );
    // Material 2 is a blackbody (ε = 1, no atmosphere): its apparent temperature is its
    // kinetic one, so σ_T passes through whole; material 1 is grey, ε = 0.9 under a 10 W m^-2
    // sr^-1 sky: σ_T is scaled by ε·dL/dT(300 K)/dL/dT(T_app), by hand 0.1 × 0.92.
    let l = |t: f64| total_radiance(t);
    let d = |t: f64| 4.0 * SIGMA * t.powi(3) / std::f64::consts::PI;
    let grey = 0.9 * l(300.0) + 0.1 * 10.0;
    let t_app = (grey * std::f64::consts::PI / SIGMA).powf(0.25);
    for i in 0..mat.len() {
        let (t, e, all) = (
            f64::from(sig_t[i]),
            f64::from(sig_e[i]),
            f64::from(total[i]),
        );
        if mat[i].to_bits() == 2.0_f32.to_bits() {
            assert!((t - 0.5).abs() < 1e-5, "pixel {i}: {t}");
            assert!(e.abs() < 1e-9, "pixel {i}: {e}");
        } else if mat[i].to_bits() == 1.0_f32.to_bits() {
            assert!(
                (t - 0.1 * 0.9 * d(300.0) / d(t_app)).abs() < 1e-5,
                "pixel {i}: {t}"
            );
            // ∂L/∂ε = L_T − L_sky, by hand.
            assert!(
                (e - 0.01 * (l(300.0) - 10.0) / d(t_app)).abs() < 1e-5,
                "pixel {i}: {e}"
            );
        }
        assert!((all - (t * t + e * e).sqrt()).abs() < 1e-5);
    }
    // An emissivity ± that would leave [0, 1] is refused at its line.
    let bad = write(
        dir.path(),
        "bad.ron",
        "(emissivity: [\n  (material: 2, sigma: 0.01),\n])",
    );
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .args(["--band", "total", "--uncertainties", &bad, "-o"])
        .arg(dir.path().join("x"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("bad.ron:2:"), "{stderr}");
    assert!(!dir.path().join("x.radiance.exr").exists());
}

#[test]
fn defaults_that_change_the_physics_are_said_and_given_values_are_not() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    let run = |extra: &[&str]| {
        let out = trace()
            .args(["--scene", &scene, "--materials", &mats, "--view", &view])
            .args(["--probe", "0,0"])
            .args(extra)
            .output()
            .unwrap();
        assert!(out.status.success());
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let silent = run(&[]);
    assert!(
        silent.contains("note: no band given: tracing 8-14 um, flat")
            && silent.contains("note: no atmosphere given: a vacuum")
            && silent.contains("under a sky of 0 W m^-2 sr^-1"),
        "{silent}"
    );
    let said = run(&["--band", "8-14", "--atmosphere", "none"]);
    assert!(!said.contains("note:"), "{said}");
}

#[test]
fn a_response_outside_a_builtins_spectra_names_the_band_file_both_ranges_and_the_fix() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, view) = inputs(dir.path(), 2);
    // A 7-14 um response: the built-ins' spectra start at 7.41 um.
    let srf = write(
        dir.path(),
        "bolometer.srf",
        "7.0 0.0\n8.0 0.5\n10.0 1.0\n14.0 0.2\n",
    );
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .args(["--atmosphere", "us-std-1976", "--band", &srf, "-o"])
        .arg(dir.path().join("f"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr).replace('\n', " ");
    for needed in [
        "bolometer.srf: the band, 7-14 um with a response",
        // 1e4/1350 = 7.407407 and 1e4/710 = 14.084507 um, rounded inward.
        "7.408-14.084 um",
        "irsig-atmos plan",
    ] {
        assert!(err.contains(needed), "`{needed}` missing from: {err}");
    }
    assert!(!err.contains("--sub-bands"), "{err}");
    assert!(!dir.path().join("f.radiance.exr").exists());
}

#[test]
fn views_repeat_and_the_old_list_after_one_view_flag_traces_the_same_frames() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, first) = inputs(dir.path(), 2);
    let second = write(
        dir.path(),
        "second.ron",
        "LookAt(position_m: (0.0, -50.0, 50.0), target_m: (0.0, 0.0, 0.0), pixels: (6, 2), fov_deg: (10.0, 5.0))",
    );
    let run = |views: &[&str], prefix: &str| {
        let out = trace()
            .args(["--scene", &scene, "--materials", &mats])
            .args(views)
            .args(["--no-dc", "-o"])
            .arg(dir.path().join(prefix))
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{views:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    run(&["--view", &first, "--view", &second], "repeated");
    run(&["--view", &first, &second], "listed");
    for n in ["0001", "0002"] {
        let read = |p: &str| std::fs::read(dir.path().join(format!("{p}.{n}.radiance.exr")));
        assert_eq!(
            read("repeated").unwrap(),
            read("listed").unwrap(),
            "frame {n}"
        );
    }
    // The second frame is the 6 x 2 view: the order given is kept.
    let second_frame = std::fs::read(dir.path().join("listed.0002.radiance.exr")).unwrap();
    let raster = irsig_raster::read_exr(&second_frame).unwrap();
    assert_eq!((raster.width, raster.height), (6, 2));
    // A file anywhere else is not a view.
    let out = trace()
        .args([
            "--scene",
            &scene,
            &second,
            "--materials",
            &mats,
            "--view",
            &first,
        ])
        .args(["-o"])
        .arg(dir.path().join("stray"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn every_setting_the_library_names_is_one_of_the_tools_flags() {
    use clap::CommandFactory;
    use irsig_atmosphere::sun::SunField;
    use irsig_render::Setting;
    let command = irsig_trace::Cli::command();
    let longs: Vec<&str> = command
        .get_arguments()
        .filter_map(|a| a.get_long())
        .collect();
    let settings = [
        Setting::Band,
        Setting::Atmosphere,
        Setting::SkyRadiance,
        Setting::SubBands,
        Setting::Tolerance,
        Setting::TolerancePercentile,
        Setting::Pin,
        Setting::Tile,
        Setting::Probe,
        Setting::SunShadowRays,
    ]
    .into_iter()
    // The sun's fields a trace can be given (refraction and SPA's clock are irsig-atmos
    // sun's alone).
    .chain(
        [
            SunField::ZenithDeg,
            SunField::AzimuthDeg,
            SunField::Utc,
            SunField::LatitudeDeg,
            SunField::LongitudeDeg,
            SunField::AltitudeM,
        ]
        .map(Setting::Sun),
    );
    for setting in settings {
        let flag = irsig_trace::flag(setting);
        let name = flag.trim_start_matches("--");
        assert!(
            longs.contains(&name),
            "{setting:?} -> {flag}: not a flag of irsig-trace"
        );
    }
}

/// A built-in's data stop at 10 km: a camera above is refused before anything is traced,
/// naming both heights and the way to build an atmosphere for it; from 10 km the frame is
/// traced.
#[test]
fn a_camera_above_a_builtins_ten_kilometres_is_refused_with_the_way_out() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, _) = inputs(dir.path(), 2);
    let at = |z: f64| {
        write(
            dir.path(),
            &format!("view-{z}.ron"),
            &format!(
                "LookAt(position_m: (0.0, 0.0, {z:?}), target_m: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), pixels: (4, 3), fov_deg: (0.1, 0.075))"
            ),
        )
    };
    for z in [10_600.0, 30_000.0] {
        let prefix = dir.path().join(format!("high-{z}"));
        let out = trace()
            .args(["--scene", &scene, "--materials", &mats, "--view", &at(z)])
            .args(["--atmosphere", "us-std-1976", "-o"])
            .arg(&prefix)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{z} m: {stderr}");
        assert!(stderr.contains(&format!("{z:.1} m")), "{stderr}");
        assert!(stderr.contains("10000 m"), "{stderr}");
        assert!(stderr.contains("irsig-atmos plan"), "{stderr}");
        let written: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().starts_with("high-"))
            .collect();
        assert!(written.is_empty(), "{z} m wrote {written:?}");
    }
    let prefix = dir.path().join("top");
    let out = trace()
        .args([
            "--scene",
            &scene,
            "--materials",
            &mats,
            "--view",
            &at(10_000.0),
        ])
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(&prefix)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn view_paths_past_the_tables_widest_row_are_counted_and_said() {
    let dir = tempfile::tempdir().unwrap();
    let (scene, mats, _) = inputs(dir.path(), 2);
    // From 300 m a column of 40 pixels looks north from 87.5° to 89.5° from nadir: the
    // built-ins' widest slant row is 88°, the horizon asin(R / (R + h)) = 89.444°
    // (R = 6371.23 km, LOWTRAN7's), beyond which a ray is the sky's.
    let (h, centre_deg, fov_deg, rows) = (300.0_f64, 88.5_f64, 2.0_f64, 40_u32);
    let d = [
        0.0,
        centre_deg.to_radians().sin(),
        -centre_deg.to_radians().cos(),
    ];
    let view = write(
        dir.path(),
        "grazing.ron",
        &format!(
            "LookAt(position_m: (0.0, 0.0, {h:?}), target_m: ({:?}, {:?}, {:?}), up: (0.0, 0.0, 1.0), pixels: (1, {rows}), fov_deg: (0.05, {fov_deg:?}))",
            1e4 * d[0],
            1e4 * d[1],
            h + 1e4 * d[2]
        ),
    );
    // Each row's centre ray by hand: tilted up from the centre by atan((1 − 2(r + ½)/rows)
    // · tan(fov/2)), i.e. that much farther from nadir.
    let horizon_deg = (6_371_230.0_f64 / (6_371_230.0 + h)).asin().to_degrees();
    let nadirs: Vec<f64> = (0..rows)
        .map(|r| {
            let v = (1.0 - 2.0 * (f64::from(r) + 0.5) / f64::from(rows))
                * (fov_deg / 2.0).to_radians().tan();
            centre_deg + v.atan().to_degrees()
        })
        .collect();
    assert!(
        nadirs
            .iter()
            .all(|a| (a - 88.0).abs() > 0.01 && (a - horizon_deg).abs() > 0.01)
    );
    let ground = nadirs.iter().filter(|&&a| a < horizon_deg).count();
    let beyond = nadirs
        .iter()
        .filter(|&&a| a > 88.0 && a < horizon_deg)
        .count();
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &view])
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(dir.path().join("grazing"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let said = format!("view 1: {beyond} of the {ground} view paths to the ground and facets");
    assert!(stderr.contains(&said), "expected `{said}` in: {stderr}");
    assert!(stderr.contains("88.00 deg from nadir"), "{stderr}");
    assert!(
        stderr.contains("The last degrees to the horizon"),
        "{stderr}"
    );
    // Straight down nothing is past the row, and nothing is said.
    let down = write(
        dir.path(),
        "down.ron",
        "LookAt(position_m: (0.0, 0.0, 300.0), target_m: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), pixels: (4, 3), fov_deg: (10.0, 7.5))",
    );
    let out = trace()
        .args(["--scene", &scene, "--materials", &mats, "--view", &down])
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(dir.path().join("down"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("widest row"), "{stderr}");
}
