//! Memory per pixel, as the README's budget states it, held at the 8,192 × 8,192 cap: a
//! 284 KB EXR that decodes to 2²⁶ pixels (`tests/data/malformed/exr-sensor/
//! declares-8192-squared.exr`) made `irsig-sensor` hold 2.3 GB and `irsig-report` take 60 s.
//! The tools' peak resident memory is read from `/proc` while they run (Linux).

#![cfg(target_os = "linux")]

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use irsig_tests::{bin_path, repo_root};

const SIDE: u64 = 8192;

/// What a process holds besides its images: the program, its libraries, threads' stacks.
const ALLOWANCE_BYTES: u64 = 100 << 20;

fn big_exr() -> std::path::PathBuf {
    repo_root().join("tests/data/malformed/exr-sensor/declares-8192-squared.exr")
}

/// Runs `tool args` in `dir`; its exit code and its peak resident memory (VmHWM), bytes.
fn run_measured(tool: &str, args: &[&str], dir: &Path) -> (Option<i32>, u64, String) {
    let mut child = Command::new(bin_path(tool))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let status_file = format!("/proc/{}/status", child.id());
    let mut peak_kib = 0;
    let status = loop {
        if let Ok(text) = std::fs::read_to_string(&status_file)
            && let Some(line) = text.lines().find(|l| l.starts_with("VmHWM:"))
        {
            let kib: u64 = line
                .split_whitespace()
                .nth(1)
                .and_then(|v| v.parse().ok())
                .unwrap_or(0);
            peak_kib = peak_kib.max(kib);
        }
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
    (status.code(), peak_kib * 1024, stderr)
}

/// The next length from `n` up with no prime factor above 5, the FFT length the blur pads
/// to (typed again here, not taken from the code under test).
fn five_smooth_from(n: u64) -> u64 {
    (n..)
        .find(|&m| {
            let mut r = m;
            for p in [2, 3, 5] {
                while r % p == 0 {
                    r /= p;
                }
            }
            r == 1
        })
        .unwrap_or(n)
}

#[test]
fn the_sensor_holds_its_stated_bytes_per_pixel_at_the_cap() {
    // README: 8 bytes per pixel for each layer while decoding; then 4 per layer but the
    // radiance, 8 more, and 16 per pixel of the image the blur transforms: a 1 × 1 box
    // reaches 1.5 pixels (2 on each side), so 8,196 columns and rows, rounded up to 8,640.
    let dir = tempfile::tempdir().unwrap();
    let exr = big_exr();
    let (code, peak, stderr) = run_measured(
        "irsig-sensor",
        &[&exr.to_string_lossy(), "--mtf", "box:1x1", "-o", "s.exr"],
        dir.path(),
    );
    assert_eq!(code, Some(0), "{stderr}");
    let padded = five_smooth_from(SIDE + 4);
    assert_eq!(padded, 8640);
    let bound = (8 * SIDE * SIDE).max(8 * SIDE * SIDE + 16 * padded * padded) + ALLOWANCE_BYTES;
    assert!(
        peak <= bound,
        "irsig-sensor held {peak} bytes, more than the stated {bound} ({:.1} bytes per pixel)",
        peak as f64 / (SIDE * SIDE) as f64
    );
    assert!(dir.path().join("s.exr").is_file());
}

#[test]
fn the_report_holds_its_stated_bytes_per_pixel_at_the_cap() {
    // README: 8 bytes per pixel for each layer while decoding, then 4 per layer and 8 more.
    let dir = tempfile::tempdir().unwrap();
    let exr = big_exr();
    let (code, peak, stderr) = run_measured(
        "irsig-report",
        &["--radiance", &exr.to_string_lossy(), "-o", "r.html"],
        dir.path(),
    );
    assert_eq!(code, Some(0), "{stderr}");
    let bound = (8 * SIDE * SIDE).max((4 + 8) * SIDE * SIDE) + ALLOWANCE_BYTES;
    assert!(
        peak <= bound,
        "irsig-report held {peak} bytes, more than the stated {bound} ({:.1} bytes per pixel)",
        peak as f64 / (SIDE * SIDE) as f64
    );
}

#[test]
fn a_blur_past_the_budget_is_refused_before_it_starts() {
    // A Gaussian of σ = 3000 px pads the 8,192² image to 5 times its width each way: 16
    // bytes per pixel of that is about 33 GB, past the 16 GiB budget.
    let dir = tempfile::tempdir().unwrap();
    let exr = big_exr();
    let (code, peak, stderr) = run_measured(
        "irsig-sensor",
        &[
            &exr.to_string_lossy(),
            "--mtf",
            "gauss:sigma=3000",
            "-o",
            "s.exr",
        ],
        dir.path(),
    );
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("budget"), "{stderr}");
    // It stopped after decoding (8 bytes per pixel), before any blur.
    assert!(peak <= 8 * SIDE * SIDE + ALLOWANCE_BYTES, "{peak}");
    assert!(!dir.path().join("s.exr").exists());
}

/// What a tile may hold per pixel of itself and its one-pixel margin: the README's 150
/// bytes per pixel of a frame with every truth layer, and the camera's two 8-byte
/// direction coordinates per column and per row.
const TRACER_BYTES_PER_PIXEL: u64 = 150;

#[test]
fn a_tile_of_a_very_wide_or_tall_view_holds_memory_for_its_own_pixels() {
    // A 4,096-pixel tile of a 2²⁶ × 1 view (and of a 1 × 2²⁶ one) held 519 MB: 8 bytes per
    // column (or row) of the whole frame, 2²⁶ · 8 = 512 MiB, for the camera's directions.
    // The tile and its margin are at most (4,096 + 2) × 3 pixels; with the truth layers
    // and both direction tables that is under 2 MB, so the process holds its allowance
    // and little more, far below the frame's 512 MiB.
    let dir = tempfile::tempdir().unwrap();
    let root = repo_root();
    let scene = root.join("tests/data/malformed/base/scene.raw.ron");
    let materials = root.join("formats/canonical/samples/materials.ron");
    let long = SIDE * SIDE;
    for (pixels, tile) in [
        (format!("({long}, 1)"), "33550000,0,4096,1"),
        (format!("(1, {long})"), "0,33550000,1,4096"),
    ] {
        let view = dir.path().join("view.ron");
        std::fs::write(
            &view,
            format!(
                "LookAt(position_m: (0.0, 0.0, 50.0), target_m: (0.0, 0.0, 0.0), \
                 up: (0.0, 1.0, 0.0), pixels: {pixels}, fov_deg: (10.0, 10.0))"
            ),
        )
        .unwrap();
        let (code, peak, stderr) = run_measured(
            "irsig-trace",
            &[
                "--scene",
                &scene.to_string_lossy(),
                "--materials",
                &materials.to_string_lossy(),
                "--view",
                "view.ron",
                "--atmosphere",
                "none",
                "--tile",
                tile,
                "-o",
                "t",
            ],
            dir.path(),
        );
        assert_eq!(code, Some(0), "{pixels}: {stderr}");
        let margin = (4096 + 2) * 3;
        let bound = TRACER_BYTES_PER_PIXEL * margin + 2 * 8 * (4096 + 2 + 3) + ALLOWANCE_BYTES;
        assert!(
            peak <= bound,
            "one 4,096-pixel tile of a {pixels} view held {peak} bytes, more than the stated \
             {bound}"
        );
        assert!(dir.path().join("t.radiance.exr").is_file());
        assert!(dir.path().join("t.truth.exr").is_file());
        for f in ["t.radiance.exr", "t.truth.exr"] {
            std::fs::remove_file(dir.path().join(f)).unwrap();
        }
    }
}

#[test]
fn a_frame_too_large_for_the_machine_is_refused_before_the_pilot() {
    // Under a 4 GB address space an 8,192² frame (about 10 GB at the stated 150 bytes a
    // pixel) aborted at once with -o, and with --tolerance after a 33 s pilot, leaving its
    // staged files in the output folder. It is refused before either, saying what it
    // needs, what is left and the way out; a tile of the same frame fits.
    let dir = tempfile::tempdir().unwrap();
    let root = repo_root();
    let scene = root.join("tests/data/malformed/base/scene.raw.ron");
    let materials = root.join("formats/canonical/samples/materials.ron");
    std::fs::write(
        dir.path().join("view.ron"),
        format!(
            "LookAt(position_m: (0.0, 0.0, 50.0), target_m: (0.0, 0.0, 0.0), \
             up: (0.0, 1.0, 0.0), pixels: ({SIDE}, {SIDE}), fov_deg: (10.0, 10.0))"
        ),
    )
    .unwrap();
    let trace = |extra: &str| {
        let script = format!(
            "ulimit -v 4000000 && exec '{}' --scene '{}' --materials '{}' --view view.ron \
             --atmosphere none --band 8-12 {extra} 2>&1",
            bin_path("irsig-trace").display(),
            scene.display(),
            materials.display()
        );
        let out = Command::new("sh")
            .arg("-c")
            .arg(script)
            .current_dir(dir.path())
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
        )
    };
    for extra in ["-o t", "--tolerance 1 -o t"] {
        let (code, text) = trace(extra);
        assert_eq!(code, Some(1), "{extra}: {text}");
        assert!(
            text.contains(
                "tracing a frame, 8192 x 8192 pixels at 150 bytes a pixel, needs about 10.1 GB"
            ) && text.contains("the address space `ulimit -v` leaves is")
                && text.contains("--tile"),
            "{extra}: {text}"
        );
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .filter(|n| n != "view.ron")
            .collect();
        assert!(left.is_empty(), "{extra} left {left:?}");
    }
    // One tile of a 16 × 16 grid, 514² pixels with its margin (about 40 MB), is traced.
    let (code, text) = trace("--tile 1/16x16 -o t");
    assert_eq!(code, Some(0), "{text}");
    assert!(dir.path().join("t.radiance.exr").is_file(), "{text}");
}
