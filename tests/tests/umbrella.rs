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
