//! Nothing of a pipeline file runs as a command: whatever text its names, paths, flags and
//! parameters hold, the dry run run by `sh`, the Makefile run by `make` and the Slurm
//! scripts run by `sh` run exactly the planned command lines and nothing else.
//!
//! Hostile strings (command substitutions, quotes, `$`, `#`, `%`, newlines, NULs, tabs,
//! arbitrary Unicode) are put into a two-stage pipeline in every place text can go: the
//! stage's name, a parameter's flag and value, a subcommand word, an output path that the
//! second stage reads, a sweep variable, the pipeline file's name and its directory. The
//! stage tool is a stand-in that records its arguments (one file per call, NUL after each
//! word); `sbatch` and `irsig-run` are stand-ins too. A file `CANARY` appearing anywhere, or
//! a recorded call the plan does not hold, is an injection. A refusal is not: a control
//! character is refused where the file is read, at its line and column, and a path make
//! cannot spell is refused for the Makefile.

#![cfg(unix)]

use std::collections::BTreeMap;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use irsig_pipeline::{ErrorKind, Pipeline, Plan, SlurmOptions, Tools};
use proptest::prelude::*;

/// The stand-in stage tool (and `irsig-run`, and `sbatch`): its arguments into a new file of
/// `$PROBE_CALLS`, each followed by a NUL. `sbatch` prints a job id.
const PROBE: &str = r#"#!/bin/sh
call=$(mktemp "$PROBE_CALLS/call.XXXXXX")
printf '%s\n' "$(basename "$0")" > "$call.tool"
for a in "$@"; do printf '%s\0' "$a"; done > "$call"
case "$0" in */sbatch) echo 42 ;; esac
exit 0
"#;

/// A sandbox: a root folder holding the stand-in programs and the pipeline's folder.
struct Sandbox {
    root: tempfile::TempDir,
    bin: PathBuf,
    calls: PathBuf,
}

impl Sandbox {
    fn new() -> Self {
        let root = tempfile::tempdir().unwrap();
        let bin = root.path().join("bin");
        let calls = root.path().join("calls");
        std::fs::create_dir(&bin).unwrap();
        std::fs::create_dir(&calls).unwrap();
        for name in ["irsig-probe", "irsig-run", "sbatch", "scancel"] {
            let p = bin.join(name);
            std::fs::write(&p, PROBE).unwrap();
            std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755)).unwrap();
        }
        Self { root, bin, calls }
    }

    fn tools(&self) -> Tools {
        let bin = self.bin.clone();
        Tools::new(move |t| Some(bin.join(format!("irsig-{t}"))))
    }

    /// Runs `program args` in `dir` with the stand-ins first on `PATH`; its exit status.
    fn run(&self, dir: &Path, program: &str, args: &[&str], env: &[(&str, &str)]) -> bool {
        let path = format!(
            "{}:{}",
            self.bin.display(),
            std::env::var("PATH").unwrap_or_default()
        );
        Command::new(program)
            .args(args)
            .current_dir(dir)
            .env("PATH", path)
            .env("PROBE_CALLS", &self.calls)
            .envs(env.iter().copied())
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .unwrap_or_else(|e| panic!("{program} must run: {e}"))
            .success()
    }

    /// The calls recorded since the last time, each as (program name, arguments), sorted.
    fn take_calls(&self) -> Vec<(String, Vec<String>)> {
        let mut calls = Vec::new();
        for entry in std::fs::read_dir(&self.calls).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "tool") {
                continue;
            }
            let bytes = std::fs::read(&path).unwrap();
            let tool =
                std::fs::read_to_string(format!("{}.tool", path.display())).unwrap_or_default();
            let words = bytes
                .split(|&b| b == 0)
                .map(|w| String::from_utf8(w.to_vec()).unwrap())
                .collect::<Vec<_>>();
            let words = words[..words.len().saturating_sub(1)].to_vec();
            calls.push((tool.trim_end().to_owned(), words));
        }
        for entry in std::fs::read_dir(&self.calls).unwrap() {
            std::fs::remove_file(entry.unwrap().path()).unwrap();
        }
        calls.sort();
        calls
    }

    /// Every file named `CANARY` under the root (the sandbox's own names may hold the word).
    fn canaries(&self) -> Vec<PathBuf> {
        let mut found = Vec::new();
        let mut stack = vec![self.root.path().to_path_buf()];
        while let Some(dir) = stack.pop() {
            for entry in std::fs::read_dir(&dir).unwrap() {
                let entry = entry.unwrap();
                let path = entry.path();
                if entry.file_name() == "CANARY" {
                    found.push(path.clone());
                }
                if entry.file_type().unwrap().is_dir() {
                    stack.push(path);
                }
            }
        }
        found
    }
}

/// `s` as a RON string literal: escaped, or raw (with its characters as they are) when
/// `raw` and it can be.
fn ron_string(s: &str, raw: bool) -> String {
    if raw && !s.contains("\"#") {
        return format!("r#\"{s}\"#");
    }
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => out.push_str(&format!("\\u{{{:x}}}", u32::from(c))),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Text for a file or folder name: no `/` and no NUL (no file system takes them), short.
fn file_word(s: &str, fallback: &str) -> String {
    let w: String = s
        .chars()
        .filter(|&c| c != '/' && c != '\0')
        .take(40)
        .collect();
    if w.is_empty() || w == "." || w == ".." {
        fallback.to_owned()
    } else {
        w
    }
}

fn fragment() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("$(touch CANARY)".to_owned()),
        Just("`touch CANARY`".to_owned()),
        Just(";touch CANARY;".to_owned()),
        Just("\ntouch CANARY\n".to_owned()),
        Just("\nCANARY: ; touch CANARY #".to_owned()),
        Just("\r\n\ttouch CANARY".to_owned()),
        Just(">CANARY".to_owned()),
        Just("&&touch CANARY".to_owned()),
        Just("|touch CANARY".to_owned()),
        Just("\0".to_owned()),
        Just("\t".to_owned()),
        Just("\\".to_owned()),
        Just("'".to_owned()),
        Just("\"".to_owned()),
        Just("$$".to_owned()),
        Just("$(".to_owned()),
        Just("${HOME}".to_owned()),
        Just("#".to_owned()),
        Just("%".to_owned()),
        Just(":".to_owned()),
        Just("=".to_owned()),
        Just(" ".to_owned()),
        Just("*".to_owned()),
        Just("?".to_owned()),
        Just("~".to_owned()),
        Just("!".to_owned()),
        Just("^".to_owned()),
        Just("{a,b}".to_owned()),
        Just("-".to_owned()),
        Just("[".to_owned()),
        "[a-z0-9_.]{1,4}",
        "\\PC{1,3}",
        any::<char>().prop_map(String::from),
    ]
}

fn hostile() -> impl Strategy<Value = String> {
    prop::collection::vec(fragment(), 0..5).prop_map(|v| v.concat())
}

/// The hostile texts of one case, one per place.
#[derive(Debug, Clone)]
struct Case {
    name: String,
    key: String,
    value: String,
    word: String,
    output: String,
    variable: String,
    file: String,
    dir: String,
    raw: bool,
}

fn case() -> impl Strategy<Value = Case> {
    (
        (hostile(), hostile(), hostile(), hostile()),
        (hostile(), hostile(), hostile(), hostile()),
        any::<bool>(),
    )
        .prop_map(
            |((name, key, value, word), (output, variable, file, dir), raw)| Case {
                name,
                key,
                value,
                word,
                output,
                variable,
                file,
                dir,
                raw,
            },
        )
}

/// Writes the case's pipeline file; returns its path.
fn write_pipeline(sandbox: &Sandbox, c: &Case) -> PathBuf {
    let dir = sandbox.root.path().join(file_word(&c.dir, "work"));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("p{}.ron", file_word(&c.file, "")));
    let q = |s: &str| ron_string(s, c.raw);
    // The output lies in `out/`: its text may not climb out of the sandbox.
    let output = format!("out/{}", c.output.replace('/', "_").replace("..", "_."));
    // `{` would be a template in a stage without a sweep: it is doubled.
    let literal = |s: &str| s.replace('{', "{{").replace('}', "}}");
    let text = format!(
        "Pipeline(\n    sweeps: {{\"s\": Frames([{{\"v\": {variable}}}])}},\n    stages: [\n        \
         Stage(name: {name}, tool: {tool}, params: {{\"p\": {value}, {key}: \"x\"}}, outputs: {{\"o\": {out}}}),\n        \
         Stage(tool: \"probe\", sweep: \"s\", args: [{out}], params: {{\"q\": \"{{v}}\"}}, outputs: {{\"o\": \"f{{frame}}.txt\"}}),\n    ],\n)\n",
        variable = q(&c.variable),
        name = q(&format!("n{}", c.name)),
        tool = q(&format!("probe {}", literal(&c.word))),
        value = q(&literal(&c.value)),
        key = q(&format!("k{}", literal(&c.key))),
        out = q(&literal(&output)),
    );
    std::fs::write(&file, text).unwrap();
    file
}

/// What the plan's steps should have run: (program, arguments), sorted.
fn planned(plan: &Plan) -> Vec<(String, Vec<String>)> {
    let mut calls: Vec<_> = plan
        .steps
        .iter()
        .map(|s| (s.argv[0].clone(), s.argv[1..].to_vec()))
        .collect();
    calls.sort();
    calls
}

fn has_control(c: &Case) -> bool {
    [&c.name, &c.key, &c.value, &c.word, &c.output, &c.variable]
        .iter()
        .any(|s| s.contains(char::is_control))
}

fn check(c: &Case) -> Result<(), TestCaseError> {
    let sandbox = Sandbox::new();
    let file = write_pipeline(&sandbox, c);
    let dir = file.parent().unwrap().to_path_buf();
    let text = std::fs::read_to_string(&file).unwrap();
    let pipeline = match Pipeline::parse(&file.display().to_string(), &text, &dir) {
        Ok(p) => p,
        Err(e) => {
            // The reasons a file of this shape is refused, each located: a control
            // character, or a flag name with whitespace in it.
            let key_space = c.key.contains(char::is_whitespace);
            prop_assert!(
                (has_control(c) && e.kind() == ErrorKind::ControlCharacter)
                    || (key_space && e.kind() == ErrorKind::Structure),
                "{}",
                e
            );
            prop_assert!(e.line_column().is_some());
            return Ok(());
        }
    };
    prop_assert!(!has_control(c), "a control character was accepted");
    let plan = match pipeline.plan(&sandbox.tools()) {
        Ok(plan) => plan,
        Err(e) => return Err(TestCaseError::fail(format!("not planned: {e}"))),
    };
    let want = planned(&plan);

    // The dry run, run by sh from the sandbox's root, runs exactly the plan.
    match plan.dry_run_script(true) {
        Ok(script) => {
            prop_assert!(sandbox.run(sandbox.root.path(), "sh", &["-c", &script], &[]));
            prop_assert_eq!(sandbox.take_calls(), want.clone(), "dry run:\n{}", script);
        }
        Err(e) => prop_assert_eq!(e.kind(), ErrorKind::ControlCharacter, "{}", e),
    }
    prop_assert!(sandbox.canaries().is_empty(), "{:?}", sandbox.canaries());

    // The Makefile, run by make in the pipeline's folder, runs exactly the plan.
    match plan.makefile() {
        Ok(makefile) => {
            std::fs::write(dir.join("Makefile.irsig"), &makefile).unwrap();
            prop_assert!(
                sandbox.run(&dir, "make", &["-s", "-f", "Makefile.irsig", "all"], &[]),
                "make failed:\n{}",
                makefile
            );
            prop_assert_eq!(
                sandbox.take_calls(),
                want.clone(),
                "Makefile:\n{}",
                makefile
            );
            std::fs::remove_file(dir.join("Makefile.irsig")).unwrap();
        }
        Err(e) => prop_assert!(
            matches!(
                e.kind(),
                ErrorKind::NotMakeable | ErrorKind::ControlCharacter
            ),
            "{}",
            e
        ),
    }
    prop_assert!(sandbox.canaries().is_empty(), "{:?}", sandbox.canaries());

    // The Slurm scripts: each job script runs `irsig-run --step NAME PIPELINE` and nothing
    // else; submit.sh runs sbatch once per job.
    let script_dir = sandbox.root.path().join("slurm");
    let options = SlurmOptions {
        pipeline: file.clone(),
        script_dir: script_dir.clone(),
        runner: sandbox.bin.join("irsig-run"),
        partition: None,
        sbatch: vec!["--account=proj42".to_owned()],
        setup: vec!["true".to_owned()],
        node: None,
        force: true,
    };
    match plan.slurm(&options) {
        Ok(scripts) => {
            std::fs::create_dir_all(&script_dir).unwrap();
            for (name, text) in &scripts.files {
                std::fs::write(script_dir.join(name), text).unwrap();
            }
            for job in &scripts.jobs {
                let script = script_dir.join(&job.script);
                prop_assert!(sandbox.run(
                    sandbox.root.path(),
                    "sh",
                    &[&script.display().to_string()],
                    &[("SLURM_ARRAY_TASK_ID", "1")],
                ));
                let step = if job.array.is_some() {
                    format!("{}[1]", job.stage)
                } else {
                    job.stage.clone()
                };
                prop_assert_eq!(
                    sandbox.take_calls(),
                    vec![(
                        "irsig-run".to_owned(),
                        vec!["--step".to_owned(), step, file.display().to_string()]
                    )],
                    "{}",
                    std::fs::read_to_string(&script).unwrap()
                );
            }
            let submit = script_dir.join("submit.sh");
            prop_assert!(sandbox.run(
                sandbox.root.path(),
                "sh",
                &[&submit.display().to_string()],
                &[]
            ));
            let calls = sandbox.take_calls();
            prop_assert_eq!(calls.len(), scripts.jobs.len());
            for (tool, args) in &calls {
                prop_assert_eq!(tool, "sbatch");
                let last = args.last().cloned().unwrap_or_default();
                prop_assert!(
                    scripts
                        .jobs
                        .iter()
                        .any(|j| last == script_dir.join(&j.script).display().to_string()),
                    "{:?}",
                    args
                );
                let chdir = format!("--chdir={}", dir.display());
                prop_assert!(args.contains(&chdir), "{:?}", args);
            }
        }
        Err(e) => prop_assert_eq!(e.kind(), ErrorKind::ControlCharacter, "{}", e),
    }
    prop_assert!(sandbox.canaries().is_empty(), "{:?}", sandbox.canaries());
    Ok(())
}

/// A case whose texts hold no control character (which the reader refuses) and whose flag
/// holds no whitespace (which a flag name cannot): every one reaches the back ends.
fn case_that_plans() -> impl Strategy<Value = Case> {
    case().prop_map(|mut c| {
        for s in [
            &mut c.name,
            &mut c.key,
            &mut c.value,
            &mut c.word,
            &mut c.output,
            &mut c.variable,
        ] {
            s.retain(|ch| !ch.is_control());
        }
        c.key.retain(|ch| !ch.is_whitespace());
        c.word = format!("w{}", c.word);
        c
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 64,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn no_text_of_a_pipeline_runs_as_a_command(c in case_that_plans()) {
        check(&c)?;
    }

    #[test]
    fn a_control_character_is_refused_where_it_is_written(c in case()) {
        check(&c)?;
    }
}

/// The vectors found by hand, each alone.
#[test]
fn the_reported_vectors_run_nothing() {
    let plain = Case {
        name: String::new(),
        key: String::new(),
        value: String::new(),
        word: String::new(),
        output: "o".to_owned(),
        variable: String::new(),
        file: String::new(),
        dir: String::new(),
        raw: false,
    };
    let mut cases: Vec<Case> = Vec::new();
    for raw in [false, true] {
        cases.push(Case {
            value: "a\nr.html: ; touch CANARY #".to_owned(),
            raw,
            ..plain.clone()
        });
        cases.push(Case {
            name: "\ntouch CANARY\n".to_owned(),
            raw,
            ..plain.clone()
        });
        cases.push(Case {
            value: "$(touch CANARY)\0".to_owned(),
            raw,
            ..plain.clone()
        });
    }
    cases.push(Case {
        dir: "d\n$(touch CANARY)".to_owned(),
        file: "\ntouch CANARY\\".to_owned(),
        ..plain.clone()
    });
    cases.push(Case {
        value: "$(touch CANARY)`touch CANARY`$$'\"\\".to_owned(),
        ..plain
    });
    let mut counts = BTreeMap::new();
    for c in &cases {
        check(c).unwrap_or_else(|e| panic!("{c:?}: {e}"));
        *counts.entry(has_control(c)).or_insert(0) += 1;
    }
    assert_eq!(
        counts.len(),
        2,
        "both refused and planned cases are covered"
    );
}
