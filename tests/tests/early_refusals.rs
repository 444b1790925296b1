//! What is refused before any work, by the rule that owns it: a pipeline stage's
//! parameters by the tool's own rules (`irsig_cli::CheckArgs`) in every back end, a model
//! pinned twice, and the flags a tool can refuse without reading a file.

use std::path::Path;

use irsig_tests::bin;

/// A pipeline of one trace stage whose sun is at `zenith`, its files not made yet.
fn sun_pipeline(dir: &Path, zenith: &str) -> std::path::PathBuf {
    let p = dir.join("p.ron");
    std::fs::write(
        &p,
        format!(
            "(stages: [\n  (tool: \"trace\", inputs: {{\"scene\": \"s.raw\", \"materials\": \
             \"m.ron\", \"view\": \"v.ron\"}},\n   params: {{\"sun-zenith-deg\": \"{zenith}\", \
             \"sun-azimuth-deg\": \"10\", \"atmosphere\": \"a.spa\"}},\n   outputs: \
             {{\"radiance-exr\": \"r.exr\"}}),\n])\n"
        ),
    )
    .unwrap();
    p
}

#[test]
fn a_trace_stage_whose_sun_is_below_the_horizon_or_nan_is_refused_by_every_back_end() {
    // `sun-zenith-deg: "NaN"` or `95` in a trace stage passed --dry-run, --emit-makefile and
    // --emit-slurm, and was refused only when the stage ran, after the atmosphere's build.
    let dir = tempfile::tempdir().unwrap();
    for zenith in ["95", "NaN", "90"] {
        let p = sun_pipeline(dir.path(), zenith);
        let makefile = dir.path().join("Makefile");
        let slurm = dir.path().join("slurm");
        let modes: [Vec<std::ffi::OsString>; 3] = [
            vec!["--dry-run".into()],
            vec!["--emit-makefile".into(), makefile.clone().into()],
            vec!["--emit-slurm".into(), slurm.clone().into()],
        ];
        for mode in &modes {
            let out = bin("irsig-run").args(mode).arg(&p).output().unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{zenith} {mode:?}: {stderr}");
            // At the value, line 3: `   params: {"sun-zenith-deg": "95"`.
            assert!(
                stderr.contains("p.ron:3:31") && stderr.contains("--sun-zenith-deg"),
                "{zenith} {mode:?}: {stderr}"
            );
            assert!(out.stdout.is_empty(), "{zenith} {mode:?}: printed commands");
        }
        assert!(!makefile.exists() && !slurm.exists());
    }
    // A sun above the horizon passes the check (the files' contents are the stage's
    // business when it runs).
    for name in ["s.raw", "m.ron", "v.ron", "a.spa"] {
        std::fs::write(dir.path().join(name), "").unwrap();
    }
    let p = sun_pipeline(dir.path(), "30");
    bin("irsig-run").arg("--dry-run").arg(&p).assert().success();
}

#[test]
fn a_model_pinned_twice_is_refused() {
    // `--pin bounces=1 --pin bounces=2` ran and reported the last.
    let out = bin("irsig-trace")
        .args([
            "--scene",
            "no-such.raw",
            "--materials",
            "no-such.ron",
            "--view",
            "no-such-view.ron",
            "--tolerance",
            "1",
            "--pin",
            "bounces=1",
            "--pin",
            "bounces=2",
            "-o",
        ])
        .arg(std::env::temp_dir().join("never-written"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--pin bounces=2") && stderr.contains("pinned twice"),
        "{stderr}"
    );
    // Two models pinned once each are no repetition: the next complaint is the scene.
    let out = bin("irsig-trace")
        .args([
            "--scene",
            "no-such.raw",
            "--materials",
            "no-such.ron",
            "--view",
            "no-such-view.ron",
            "--tolerance",
            "1",
            "--pin",
            "bounces=1",
            "--pin",
            "sky-view=0",
            "-o",
        ])
        .arg(std::env::temp_dir().join("never-written"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("pinned twice"), "{stderr}");
}

#[test]
fn stats_and_report_hold_an_image_to_the_band_and_the_record_it_carries() {
    // `irsig-report t.exr --band 8-12` and `irsig-stats … --band 8-12` on an 8–14 µm image
    // exited 0, and irsig-stats took any record (a reversed, NaN or missing band,
    // non-UTF-8 comments) that report and sensor refuse.
    let dir = tempfile::tempdir().unwrap();
    let folder = irsig_tests::repo_root().join("tests/data/malformed/banded-exr");
    let image = folder.join("records-8-14-band-8-12.exr");
    let regions = folder.join("all.ron");
    let stats = |image: &Path, band: &str| {
        bin("irsig-stats")
            .arg(image)
            .arg("--regions")
            .arg(&regions)
            .args(["--band", band])
            .output()
            .unwrap()
    };
    let report = |image: &Path, band: &str| {
        bin("irsig-report")
            .arg(image)
            .args(["--band", band, "-o"])
            .arg(dir.path().join("r.html"))
            .output()
            .unwrap()
    };
    for out in [stats(&image, "8-12"), report(&image, "8-12")] {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains("8-12 um, flat") && stderr.contains("8-14 um, flat"),
            "{stderr}"
        );
    }
    assert!(stats(&image, "8-14").status.success());
    assert!(report(&image, "8-14").status.success());
    for bad in [
        "band-reversed.exr",
        "band-nan.exr",
        "band-missing.exr",
        "comments-not-utf8.exr",
        "response-hash-short.exr",
    ] {
        let bad = folder.join(bad);
        for out in [stats(&bad, "8-14"), report(&bad, "8-14")] {
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{}: {stderr}", bad.display());
        }
    }
}
