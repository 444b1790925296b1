//! The `irsig` umbrella command: dispatch to `irsig-<stage>`, `--version`, and usage errors.

use irsig_tests::bin;
use predicates::prelude::*;

#[test]
fn version_lists_every_stage() {
    let mut cmd = bin("irsig");
    cmd.arg("--version").assert().success().stdout(
        predicate::str::contains("irsig ")
            .and(predicate::str::contains("import"))
            .and(predicate::str::contains("trace"))
            .and(predicate::str::contains("run")),
    );
}

#[test]
fn unknown_stage_is_a_usage_error() {
    bin("irsig")
        .arg("no-such-stage")
        .assert()
        .code(2)
        .stderr(predicate::str::contains("no stage `no-such-stage`"));
}

#[test]
fn no_arguments_is_a_usage_error() {
    bin("irsig").assert().code(2);
}

#[test]
fn version_lists_the_merge_stage() {
    bin("irsig")
        .arg("--version")
        .assert()
        .success()
        .stdout(predicate::str::contains("merge"));
}

#[test]
fn a_reader_that_closes_the_pipe_is_success() {
    // `irsig --help | head -c1`: the read end is closed before the usage is written, which
    // used to panic in `print!` (exit 101).
    for arg in ["--help", "--version"] {
        let mut child = std::process::Command::new(irsig_tests::bin_path("irsig"))
            .arg(arg)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        assert!(
            out.status.success(),
            "{arg}: {:?} {}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
