//! A pipeline file's text never runs as a command, end to end through `irsig-run`: a
//! newline in a parameter or a stage name cannot add a rule to the Makefile (`make` runs it)
//! or a line to a Slurm script, and the dry run, run by `sh`, runs only the planned
//! commands. Each case plants `touch CANARY`; the file `CANARY` must never appear, and the
//! file is refused at the line and column of the control character. (The library's
//! property test, `crates/pipeline/tests/injection.rs`, puts arbitrary text everywhere.)

#![cfg(unix)]

use std::path::Path;
use std::process::{Command, Output, Stdio};

use irsig_tests::bin_path;

/// A folder with `a.txt` and the pipeline `p.ron` of `text`.
fn pipeline(text: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("a.txt"), "a").unwrap();
    std::fs::write(dir.path().join("p.ron"), text).unwrap();
    dir
}

fn irsig_run(dir: &Path, args: &[&str]) -> Output {
    Command::new(bin_path("irsig-run"))
        .args(args)
        .arg("p.ron")
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .unwrap()
}

/// Runs `program args` in `dir`, the irsig tools first on `PATH`.
fn run_in(dir: &Path, program: &str, args: &[&str]) {
    let bin = bin_path("irsig-testcat");
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let _ = Command::new(program)
        .args(args)
        .current_dir(dir)
        .env("PATH", path)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap_or_else(|e| panic!("{program} must run: {e}"));
}

/// The pipeline is refused at `line:column` as holding a control character, and nothing
/// it could have become runs a command: whatever `irsig-run` wrote is run, by make or sh.
fn refused_and_inert(text: &str, line_column: &str, args: &[&str], then: &[&str]) {
    let dir = pipeline(text);
    let out = irsig_run(dir.path(), args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        // Today's code must not get here; should it, its output must be harmless.
        std::fs::write(dir.path().join("dry-run.sh"), &out.stdout).unwrap();
        if !then.is_empty() {
            run_in(dir.path(), then[0], &then[1..]);
        }
    }
    assert!(
        !dir.path().join("CANARY").exists(),
        "{args:?} ran the planted command"
    );
    assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(
        stderr.contains(&format!("p.ron:{line_column}")) && stderr.contains("control character"),
        "{args:?}: {stderr}"
    );
}

#[test]
fn a_newline_in_a_parameter_adds_no_rule_to_the_makefile() {
    // `params: {"prefix": "a\nr.html: ; touch X #"}` wrote a rule make ran.
    let text = "(stages: [(tool: \"testcat\", args: [\"a.txt\"],\n  \
                params: {\"prefix\": \"a\\nb.txt: ; touch CANARY #\"}, outputs: {\"o\": \"b.txt\"})])";
    refused_and_inert(
        text,
        "2:24",
        &["--emit-makefile", "Makefile"],
        &["make", "-f", "Makefile", "all"],
    );
}

#[test]
fn a_newline_in_a_stage_name_adds_no_rule_to_the_makefile() {
    // The name went unescaped into the `# NAME (...)` comment.
    let text = "(stages: [(name: \"s\\nb.txt: ; touch CANARY\",\n  tool: \"testcat\", \
                args: [\"a.txt\"], outputs: {\"o\": \"b.txt\"})])";
    refused_and_inert(
        text,
        "1:20",
        &["--emit-makefile", "Makefile"],
        &["make", "-f", "Makefile", "all"],
    );
}

#[test]
fn a_newline_in_a_stage_name_adds_no_line_to_a_slurm_script() {
    // The name became a command line of the `.sbatch` script, after its comment.
    let text = "(stages: [(name: \"s\\ntouch CANARY\",\n  tool: \"testcat\", \
                args: [\"a.txt\"], outputs: {\"o\": \"b.txt\"})])";
    let dir = pipeline(text);
    let out = irsig_run(dir.path(), &["--emit-slurm", "slurm"]);
    if out.status.success() {
        for entry in std::fs::read_dir(dir.path().join("slurm")).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "sbatch") {
                // The job's own command fails at once (no such runner here); a planted
                // line before it would already have run.
                run_in(dir.path(), "sh", &[&path.display().to_string()]);
            }
        }
    }
    assert!(!dir.path().join("CANARY").exists(), "the script ran it");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("p.ron:1:20") && stderr.contains("control character"),
        "{stderr}"
    );
}

#[test]
fn a_pipelines_sun_adds_no_rule_and_no_command() {
    // The sun's time becomes a word of every trace stage's command line: a newline in it
    // is refused where it stands, as in any parameter.
    let stage = "stages: [(tool: \"testcat\", args: [\"a.txt\"], outputs: {\"o\": \"b.txt\"})]";
    let text = format!(
        "(sun: At(utc: \"2024-06-21T12:00:00Z\\nb.txt: ; touch CANARY #\", latitude_deg: 0, \
         longitude_deg: 0),\n {stage})"
    );
    refused_and_inert(
        &text,
        "1:36",
        &["--emit-makefile", "Makefile"],
        &["make", "-f", "Makefile", "all"],
    );
    // Text that is no time, `$(...)` or a flag: refused at the value by the sun's model
    // before anything is planned, printed or run.
    for utc in ["$(touch CANARY)", "--o=CANARY"] {
        let text =
            format!("(sun: At(utc: \"{utc}\", latitude_deg: 0, longitude_deg: 0),\n {stage})");
        let dir = pipeline(&text);
        let out = irsig_run(dir.path(), &["--dry-run"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        if out.status.success() {
            std::fs::write(dir.path().join("dry-run.sh"), &out.stdout).unwrap();
            run_in(dir.path(), "sh", &["dry-run.sh"]);
        }
        assert!(!dir.path().join("CANARY").exists(), "{utc}: ran");
        assert_eq!(out.status.code(), Some(1), "{utc}: {stderr}");
        assert!(
            stderr.contains("p.ron:1:15") && stderr.contains("utc"),
            "{stderr}"
        );
    }
}

#[test]
fn the_dry_run_never_prints_a_raw_word() {
    // A word holding a NUL was printed raw (shlex refuses to quote it); run as a script,
    // the `$(...)` in it ran.
    let text = "(stages: [(tool: \"testcat\", args: [\"a.txt\"],\n  \
                params: {\"prefix\": \"$(touch CANARY)\\u{0}\"}, outputs: {\"o\": \"b.txt\"})])";
    refused_and_inert(text, "2:38", &["--dry-run"], &["sh", "dry-run.sh"]);
}

#[test]
fn a_dry_run_run_by_sh_runs_the_plan() {
    // Quotes, `$`, backquotes and `#` in parameters, quoted for sh: the output it makes is
    // the one `irsig-run` makes.
    let text = r#"(stages: [(tool: "testcat", args: ["a.txt"],
        params: {"prefix": "$(touch CANARY) `touch CANARY` 'q' \"d\" #; \\ "},
        outputs: {"o": "b.txt"})])"#;
    let dir = pipeline(text);
    let out = irsig_run(dir.path(), &["--dry-run"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::write(dir.path().join("dry-run.sh"), &out.stdout).unwrap();
    run_in(dir.path(), "sh", &["dry-run.sh"]);
    assert!(!dir.path().join("CANARY").exists());
    assert_eq!(
        std::fs::read_to_string(dir.path().join("b.txt")).unwrap(),
        "$(touch CANARY) `touch CANARY` 'q' \"d\" #; \\ a"
    );
}
