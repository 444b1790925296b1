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
