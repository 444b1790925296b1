//! End-to-end tests across the irsig binaries live in `tests/`, one file per area; each
//! file says in its first comment what it covers. This library holds only what those files
//! share.
//!
//! The binaries are those cargo builds beside the test executable ([`bin_path`]).

use std::path::{Path, PathBuf};
use std::process::Command;

pub mod hazy_day;
pub mod recipe;
pub mod slant_plate;
pub mod sunlit_plate;

/// The repository root.
#[must_use]
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map_or_else(|| PathBuf::from("."), std::path::Path::to_path_buf)
}

/// A text with every run of whitespace as one space, trimmed: how a test finds a
/// sentence a document may wrap anywhere.
#[must_use]
pub fn squeeze(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// LOWTRAN7: `$IRSIG_LOWTRAN`, else `lowtran7` on `PATH`.
///
/// # Panics
/// When `$IRSIG_LOWTRAN` is not a file or LOWTRAN7 is not found: the tests that need it
/// fail, saying how to install it; they never skip.
#[must_use]
pub fn lowtran() -> PathBuf {
    if let Some(p) = std::env::var_os("IRSIG_LOWTRAN").filter(|p| !p.is_empty()) {
        let p = PathBuf::from(p);
        assert!(
            p.is_file(),
            "IRSIG_LOWTRAN={} is not a file: run sh scripts/atmosphere/install-lowtran.sh",
            p.display()
        );
        return p;
    }
    std::env::var_os("PATH")
        .and_then(|path| {
            std::env::split_paths(&path)
                .map(|d| d.join("lowtran7"))
                .find(|p| p.is_file())
        })
        .unwrap_or_else(|| {
            panic!(
                "LOWTRAN7 is needed by this test and was not found: run `sh scripts/atmosphere/install-lowtran.sh` and set IRSIG_LOWTRAN to the path it prints"
            )
        })
}

/// What one LOWTRAN7 run printed: its TAPE6 (the listing) and TAPE7 (the spectral table).
#[derive(Debug, Clone)]
pub struct LowtranRun {
    /// TAPE6's text.
    pub tape6: String,
    /// TAPE7's text.
    pub tape7: String,
}

/// Runs [`lowtran`] on the card deck `deck` (TAPE5's text) in a directory of its own, as
/// `irsig-atmos build` runs it (its `out/` holding empty TAPE6-8), and returns what it
/// printed; panics, naming the deck, when LOWTRAN7 fails.
#[must_use]
pub fn run_lowtran(deck: &str) -> LowtranRun {
    let dir = tempfile::tempdir().expect("a scratch directory");
    std::fs::write(dir.path().join("TAPE5"), deck).expect("write TAPE5");
    std::fs::create_dir(dir.path().join("out")).expect("make out/");
    for t in ["TAPE6", "TAPE7", "TAPE8"] {
        std::fs::write(dir.path().join("out").join(t), "").expect("make out/TAPEn");
    }
    let status = std::process::Command::new(lowtran())
        .current_dir(dir.path())
        .stdout(std::process::Stdio::null())
        .status()
        .expect("start LOWTRAN7");
    assert!(status.success(), "LOWTRAN7 failed on\n{deck}");
    let read = |t: &str| std::fs::read_to_string(dir.path().join("out").join(t)).expect(t);
    LowtranRun {
        tape6: read("TAPE6"),
        tape7: read("TAPE7"),
    }
}

/// `irsig-flatten` of the quickstart scene into `dir/scene.raw` (once), then `irsig-atmos
/// plan` of it from the quickstart's view into the plan directory `dir/name`, with the
/// model's flags `model` (`--atmosphere us-std-1976`, or a radiosonde) and `extra`.
#[must_use]
pub fn quickstart_plan(dir: &Path, name: &str, model: &[&str], extra: &[&str]) -> PathBuf {
    let raw = dir.join("scene.raw");
    if !raw.exists() {
        bin("irsig-flatten")
            .args([
                "pipelines/quickstart/scene.ron",
                "--materials",
                "pipelines/quickstart/materials.ron",
                "-o",
            ])
            .arg(&raw)
            .assert()
            .success();
    }
    let plan = dir.join(name);
    bin("irsig-atmos")
        .args(["plan", "--scene"])
        .arg(&raw)
        .args(["--view", "pipelines/quickstart/view.ron"])
        .args(model)
        .args(extra)
        .arg("-o")
        .arg(&plan)
        .assert()
        .success();
    plan
}

/// The path of an irsig binary, built by this test run.
///
/// `cargo test` does not build other packages' binaries, so the first call builds every
/// workspace binary, the test-only ones too (`cargo build --workspace --bins --features
/// irsig-tests/test-tools`; a no-op when they are up to date, as `scripts/test.sh` leaves
/// them), in the profile this test executable was built in: the one whose folder holds it
/// (`target/release` for release, `target/debug` for dev and test). Cargo compiles again a
/// crate last built under another profile's name, so the tools of any other profile would
/// cost a build of every crate.
///
/// # Panics
/// When the build fails or the binary does not exist.
#[must_use]
pub fn bin_path(name: &str) -> PathBuf {
    // The test executable sits in target/<profile>/deps; the binaries one level up.
    let exe = std::env::current_exe().expect("current test executable");
    let dir = exe
        .parent()
        .and_then(std::path::Path::parent)
        .expect("target/<profile> directory");
    static BUILT: std::sync::OnceLock<()> = std::sync::OnceLock::new();
    BUILT.get_or_init(|| {
        let profile = match dir.file_name().and_then(|n| n.to_str()) {
            Some("debug") | None => "dev",
            Some(other) => other,
        };
        let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
        let status = Command::new(cargo)
            .args([
                "build",
                "--quiet",
                "--workspace",
                "--bins",
                "--profile",
                profile,
            ])
            .args(["--features", "irsig-tests/test-tools"])
            .current_dir(repo_root())
            .status()
            .expect("run cargo build");
        assert!(
            status.success(),
            "cargo build --workspace --bins --profile {profile} failed"
        );
    });
    let path = dir.join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    assert!(path.is_file(), "{} was not built", path.display());
    path
}

/// A command for an irsig binary, run from the repository root.
#[must_use]
pub fn bin(name: &str) -> assert_cmd::Command {
    let mut cmd = Command::new(bin_path(name));
    cmd.current_dir(repo_root());
    assert_cmd::Command::from_std(cmd)
}

/// Per region, the named numeric columns of `irsig-stats TRUTH --regions REGIONS --format
/// csv EXTRA...` (kelvin, pixels).
///
/// # Panics
/// When irsig-stats fails.
#[must_use]
pub fn stats_csv(
    truth: &std::path::Path,
    regions: &std::path::Path,
    extra: &[&str],
) -> std::collections::HashMap<String, std::collections::HashMap<String, f64>> {
    let out = bin("irsig-stats")
        .arg(truth)
        .arg("--regions")
        .arg(regions)
        .args(["--format", "csv"])
        .args(extra)
        .output()
        .expect("run irsig-stats");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("UTF-8 CSV");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("a header row").split(',').collect();
    lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            let values = header
                .iter()
                .zip(&cells)
                .skip(1)
                .filter_map(|(h, c)| c.parse().ok().map(|v| ((*h).to_owned(), v)))
                .collect();
            (cells[0].to_owned(), values)
        })
        .collect()
}

/// A pipe whose reader has gone, as a child's stdout or stderr: every write to it fails
/// (`EPIPE`), as `tool 2>&1 | head -c1` leaves the tool's stderr once `head` has exited.
/// Made from the stdin of a `true` that has already ended.
///
/// # Panics
/// When `true` cannot run.
#[must_use]
pub fn closed_pipe() -> std::process::Stdio {
    let mut reader = Command::new("true")
        .stdin(std::process::Stdio::piped())
        .spawn()
        .expect("`true` must run");
    let writer = reader.stdin.take().expect("a piped stdin");
    reader.wait().expect("`true` ends");
    std::process::Stdio::from(writer)
}
