//! The band travels with the image: irsig-trace records the band (a response file's table
//! itself), the atmosphere and its inputs in its EXRs; irsig-sensor, irsig-stats and
//! irsig-report convert with the recorded band when no `--band` is given (the same
//! apparent temperatures as with the right `--band`), refuse a `--band` that is another
//! band (exit 2, naming both) unless `--override-band`, and the sensor carries the record
//! on, its own input added. The LUTs say their band.

use std::path::{Path, PathBuf};

use irsig_tests::bin;

/// A response peaked at 10 µm, inside the built-in atmospheres' 8-14.08 µm.
const RESPONSE: &str =
    "# wavelength_um response\n8.0 0.0\n9.0 0.5\n10.0 1.0\n11.0 0.6\n13.5 0.1\n14.0 0.0\n";

const VIEW: &str = "LookAt(position_m: (0.0, -22.6851, 5.0), target_m: (1.5, 0.0, 1.0), \
                    pixels: (48, 36), fov_deg: (47.0, 36.0))";

struct Run {
    dir: tempfile::TempDir,
}

impl Run {
    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn s(&self, name: &str) -> String {
        self.path(name).to_string_lossy().into_owned()
    }
}

/// The quickstart scene traced in the response's band.
fn traced() -> Run {
    let run = Run {
        dir: tempfile::tempdir().unwrap(),
    };
    std::fs::write(run.path("cam.srf"), RESPONSE).unwrap();
    std::fs::write(run.path("view.ron"), VIEW).unwrap();
    bin("irsig-flatten")
        .args([
            "pipelines/quickstart/scene.ron",
            "--materials",
            "pipelines/quickstart/materials.ron",
            "-o",
            &run.s("scene.raw"),
        ])
        .assert()
        .success();
    bin("irsig-trace")
        .args(["--scene", &run.s("scene.raw")])
        .args(["--materials", "pipelines/quickstart/materials.ron"])
        .args(["--view", &run.s("view.ron"), "--atmosphere", "us-std-1976"])
        .args(["--band", &run.s("cam.srf"), "-o", &run.s("f")])
        .assert()
        .success();
    run
}

fn layer(path: &Path, name: &str) -> Vec<f32> {
    let r = irsig_raster::read_exr(&std::fs::read(path).unwrap()).unwrap();
    r.layer(name).unwrap().data.clone()
}

fn sensor(run: &Run, out: &str, extra: &[&str]) -> std::process::Output {
    bin("irsig-sensor")
        .arg(run.s("f.radiance.exr"))
        .args(["--mtf", "box:3x3", "-o", &run.s(&format!("{out}.exr"))])
        .args(["--temperature-exr", &run.s(&format!("{out}.t.exr"))])
        .args([
            "--dc-per-kelvin",
            "4",
            "--lut",
            &run.s(&format!("{out}.lut")),
        ])
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn the_recorded_band_is_the_default_and_another_band_is_refused() {
    let run = traced();
    // The trace's own images say their band, with the response table itself.
    let truth = irsig_raster::read_exr(&std::fs::read(run.path("f.truth.exr")).unwrap()).unwrap();
    let p = irsig_cli::provenance("f.truth.exr", &truth)
        .unwrap()
        .expect("a provenance");
    match &p.band {
        irsig_model::provenance::BandRecord::Response {
            wavelength_um,
            sha256,
            ..
        } => {
            assert_eq!(wavelength_um, &[8.0, 9.0, 10.0, 11.0, 13.5, 14.0]);
            assert_eq!(sha256, &irsig_cli::sha256_hex(RESPONSE.as_bytes()));
        }
        other => panic!("recorded {other:?}"),
    }
    assert_eq!(p.atmosphere, "us-std-1976");
    let roles: Vec<&str> = p.inputs.iter().map(|i| i.role.as_str()).collect();
    assert!(
        ["scene", "materials", "view"]
            .iter()
            .all(|r| roles.contains(r)),
        "{roles:?}"
    );

    // The sensor without --band and with the right one: the same temperatures, bit for bit.
    let out = sensor(&run, "a", &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = sensor(&run, "b", &["--band", &run.s("cam.srf")]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (a, b) = (
        layer(&run.path("a.t.exr"), "apparent_temperature"),
        layer(&run.path("b.t.exr"), "apparent_temperature"),
    );
    assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
    assert_eq!(
        std::fs::read(run.path("a.lut")).unwrap(),
        std::fs::read(run.path("b.lut")).unwrap()
    );
    let lut = std::fs::read_to_string(run.path("a.lut")).unwrap();
    assert!(
        lut.lines()
            .nth(1)
            .is_some_and(|l| l.starts_with("# band: 8-14 um with a response")),
        "{lut}"
    );
    // What the old default did: the flat 8-14 band, kelvins away from the response's.
    let out = sensor(&run, "c", &["--band", "8-14", "--override-band"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("overrides the band"));
    let c = layer(&run.path("c.t.exr"), "apparent_temperature");
    let worst = a
        .iter()
        .zip(&c)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0_f32, f32::max);
    assert!(worst > 1.0, "the flat band differs by only {worst} K");
    // Without --override-band, another band is bad usage naming both.
    let out = sensor(&run, "d", &["--band", "8-14"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("8-14 um, flat") && err.contains("with a response"),
        "{err}"
    );
    assert!(!run.path("d.exr").exists());

    // The sensor's image carries the record on, its own input added.
    let sensed = irsig_raster::read_exr(&std::fs::read(run.path("a.exr")).unwrap()).unwrap();
    let q = irsig_cli::provenance("a.exr", &sensed).unwrap().unwrap();
    assert!(q.band.same_band(&p.band));
    assert_eq!(q.inputs.last().map(|i| i.stage.as_str()), Some("sensor"));

    // The statistics and the report read the sensed image's band.
    std::fs::write(
        run.path("regions.ron"),
        "(regions: [(name: \"all\", pixels: Some((columns: (2, 45), rows: (2, 33))))])",
    )
    .unwrap();
    let stats = |extra: &[&str]| {
        bin("irsig-stats")
            .arg(run.s("f.truth.exr"))
            .args(["--regions", &run.s("regions.ron"), "--format", "csv"])
            .args(["--radiance", &run.s("a.exr")])
            .args(extra)
            .output()
            .unwrap()
    };
    let (plain, right) = (stats(&[]), stats(&["--band", &run.s("cam.srf")]));
    assert!(
        plain.status.success(),
        "{}",
        String::from_utf8_lossy(&plain.stderr)
    );
    assert_eq!(plain.stdout, right.stdout);
    let wrong = stats(&["--band", "8-14"]);
    assert_eq!(wrong.status.code(), Some(2));
    let report = |extra: &[&str]| {
        bin("irsig-report")
            .arg(run.s("f.truth.exr"))
            .args(["--radiance", &run.s("a.exr"), "-o", &run.s("r.html")])
            .args(extra)
            .output()
            .unwrap()
    };
    let ok = report(&[]);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let bad = report(&["--band", "7.5-14"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("7.5-14 um, flat"));
}

#[test]
fn an_image_without_a_record_is_converted_in_8_to_14_um_and_says_so() {
    // An EXR of another program: a radiance layer and nothing about its band.
    let dir = tempfile::tempdir().unwrap();
    let mut r = irsig_raster::Raster::new(4, 3);
    r.push_layer("radiance", "W m^-2 sr^-1", vec![40.0; 12])
        .unwrap();
    let input = dir.path().join("other.exr");
    std::fs::write(&input, irsig_raster::exr_bytes(&r).unwrap()).unwrap();
    let out = bin("irsig-sensor")
        .arg(&input)
        .args(["--mtf", "box:1x1", "-o"])
        .arg(dir.path().join("s.exr"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("records no band") && err.contains("8-14 um"),
        "{err}"
    );
}
