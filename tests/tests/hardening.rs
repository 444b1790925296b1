//! The promises every tool keeps on hostile or careless use, end to end: a closed pipe is
//! success, an interrupt leaves no staged file, several outputs appear all together or not
//! at all, and an error far along a long line is reported without a panic.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Stdio};

use irsig_tests::{bin, bin_path};
use predicates::prelude::*;

/// An OBJ of `n` triangles in a strip, several megabytes of scene when written out.
fn big_obj(path: &Path, n: usize) {
    let mut s = String::new();
    for i in 0..n + 2 {
        s.push_str(&format!("v {i} {} 0\n", i % 2));
    }
    for i in 1..=n {
        s.push_str(&format!("f {i} {} {}\n", i + 1, i + 2));
    }
    std::fs::write(path, s).unwrap();
}

#[test]
fn a_reader_that_stops_early_is_success() {
    // `irsig-import big.obj | head -c 100` used to exit 1 "Broken pipe", failing any
    // pipeline run under `set -o pipefail`.
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("big.obj");
    big_obj(&obj, 60_000);
    let mut child = Command::new(bin_path("irsig-import"))
        .current_dir(irsig_tests::repo_root())
        .args([
            "--materials",
            "formats/canonical/samples/materials.ron",
            "--default-material",
            "concrete",
        ])
        .arg(&obj)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 100];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap();
    // The read end is closed here, long before the scene is all written.
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{:?}: {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn an_error_at_column_72032_is_reported_not_a_panic() {
    // A machine-written one-line scene with a typo far along: the diagnostic renderer used
    // to panic past column 65,535 (exit 101).
    let dir = tempfile::tempdir().unwrap();
    let mut line = String::from("(objects: [");
    while line.len() < 72_000 {
        line.push_str("                    ");
    }
    line.push_str("Objekt(file: \"a.obj\")])");
    let scene = dir.path().join("long.ron");
    std::fs::write(&scene, &line).unwrap();
    let out = bin("irsig-flatten")
        .arg(&scene)
        .args(["--materials", "formats/canonical/samples/materials.ron"])
        .arg("-o")
        .arg(dir.path().join("out.raw"))
        .assert()
        .code(1)
        .get_output()
        .clone();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("long.ron:1:"), "{err}");
    assert!(err.len() < 4_000, "the line is cut: {} bytes", err.len());
    assert!(!dir.path().join("out.raw").exists());
}

#[cfg(unix)]
#[test]
fn an_interrupt_leaves_no_staged_file() {
    // SIGTERM while an output is being staged: the hidden `.irsig-*.tmp` files went on
    // lying in the output folder. The tool reads its input from a pipe that stays open, so
    // it is certainly interrupted before it could finish.
    let dir = tempfile::tempdir().unwrap();
    let mut child = Command::new(bin_path("irsig-testcat"))
        .arg("-o")
        .arg(dir.path().join("out.txt"))
        .arg("--copy-stdin")
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until the staged file exists, then interrupt.
    let staged = || {
        std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .count()
    };
    let start = std::time::Instant::now();
    while staged() == 0 {
        assert!(start.elapsed().as_secs() < 60, "nothing was staged");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // Hold the pipe open through the wait: `Child::wait` closes a stdin it still owns, and
    // the end of its input would let the tool finish normally, racing the signal.
    let stdin = child.stdin.take();
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    drop(stdin);
    assert!(!status.success(), "{status:?}");
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[test]
fn the_same_output_twice_is_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let raw = dir.path().join("scene.raw");
    bin("irsig-flatten")
        .args([
            "formats/canonical/samples/scene.ron",
            "--materials",
            "formats/canonical/samples/materials.ron",
            "-o",
        ])
        .arg(&raw)
        .assert()
        .success();
    let view = dir.path().join("view.ron");
    std::fs::write(
        &view,
        "LookAt(position_m: (1.5, -14.0, 3.0), target_m: (1.5, 1.0, 0.5), pixels: (8, 6), \
         fov_deg: (64.0, 48.0))",
    )
    .unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let trace = |radiance: &str, truth: &str| {
        let mut cmd = bin("irsig-trace");
        cmd.arg("--scene")
            .arg(&raw)
            .args(["--materials", "formats/canonical/samples/materials.ron"])
            .arg("--view")
            .arg(&view)
            .args(["--atmosphere", "us-std-1976"])
            .arg("--radiance-exr")
            .arg(out.join(radiance))
            .arg("--truth-exr")
            .arg(out.join(truth));
        cmd
    };
    trace("a.exr", "a.exr")
        .assert()
        .code(2)
        .stderr(predicate::str::contains("more than one output"));
    assert!(std::fs::read_dir(&out).unwrap().next().is_none());
    // A directory among the outputs: the radiance EXR is not left behind.
    std::fs::create_dir(out.join("adir")).unwrap();
    trace("r.exr", "adir")
        .assert()
        .code(1)
        .stderr(predicate::str::contains("is a directory"));
    let left: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, ["adir"]);
}
