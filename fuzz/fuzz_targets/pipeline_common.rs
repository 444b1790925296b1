//! What the pipeline targets share: a sandbox with stand-in programs, and the checks that
//! nothing a pipeline file holds runs as a command. The stand-in stage tool (and
//! `irsig-run`, `sbatch`, `scancel`) records its arguments, one file per call; a file
//! named `CANARY` anywhere in the sandbox, or a recorded call the plan does not hold, is an
//! injection (the hostile texts plant `touch CANARY` in every form).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};

use irsig_pipeline::{ErrorKind, Pipeline, Plan, SlurmOptions, Tools};

const PROBE: &str = r#"#!/bin/sh
call=$(mktemp "$PROBE_CALLS/call.XXXXXX")
printf '%s\n' "$(basename "$0")" > "$call.tool"
for a in "$@"; do printf '%s\0' "$a"; done > "$call"
case "$0" in */sbatch) echo 42 ;; esac
exit 0
"#;

/// A scratch folder: `bin/` (the stand-ins), `calls/` (what they recorded), `work/` (the
/// pipeline's folder). Removed when dropped.
pub struct Sandbox {
    pub root: PathBuf,
    pub bin: PathBuf,
    pub calls: PathBuf,
    pub work: PathBuf,
}

impl Sandbox {
    pub fn new() -> Self {
        static N: AtomicUsize = AtomicUsize::new(0);
        let root = std::env::temp_dir().join(format!(
            "irsig-fuzz-pipeline-{}-{}",
            std::process::id(),
            N.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&root);
        let (bin, calls, work) = (root.join("bin"), root.join("calls"), root.join("work"));
        for d in [&bin, &calls, &work] {
            std::fs::create_dir_all(d).expect("scratch folders");
        }
        for name in ["irsig-probe", "irsig-run", "sbatch", "scancel"] {
            let p = bin.join(name);
            std::fs::write(&p, PROBE).expect("stand-in");
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o755))
                .expect("stand-in mode");
        }
        Self {
            root,
            bin,
            calls,
            work,
        }
    }

    /// Every tool is the stand-in.
    pub fn tools(&self) -> Tools {
        let probe = self.bin.join("irsig-probe");
        Tools::new(move |_| Some(probe.clone()))
    }

    /// Runs `program args` in `dir`, the stand-ins first on `PATH`; whether it succeeded.
    pub fn run(&self, dir: &Path, program: &str, args: &[&str], env: &[(&str, &str)]) -> bool {
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
            .is_ok_and(|s| s.success())
    }

    /// The calls recorded since the last time: (program, arguments), sorted.
    pub fn take_calls(&self) -> Vec<(String, Vec<String>)> {
        let mut calls = Vec::new();
        let entries: Vec<PathBuf> = std::fs::read_dir(&self.calls)
            .map(|d| d.flatten().map(|e| e.path()).collect())
            .unwrap_or_default();
        for path in &entries {
            if path.extension().is_some_and(|e| e == "tool") {
                continue;
            }
            let bytes = std::fs::read(path).unwrap_or_default();
            let tool = std::fs::read_to_string(format!("{}.tool", path.display()))
                .unwrap_or_default();
            let mut words: Vec<String> = bytes
                .split(|&b| b == 0)
                .map(|w| String::from_utf8_lossy(w).into_owned())
                .collect();
            words.pop();
            calls.push((tool.trim_end().to_owned(), words));
        }
        for path in entries {
            let _ = std::fs::remove_file(path);
        }
        calls.sort();
        calls
    }

    /// Panics when a file named `CANARY` exists anywhere in the sandbox.
    pub fn assert_no_canary(&self, what: &str) {
        let mut stack = vec![self.root.clone()];
        while let Some(dir) = stack.pop() {
            let Ok(entries) = std::fs::read_dir(&dir) else {
                continue;
            };
            for entry in entries.flatten() {
                assert!(
                    entry.file_name() != "CANARY",
                    "{what} ran a planted command: {}",
                    entry.path().display()
                );
                if entry.file_type().is_ok_and(|t| t.is_dir()) {
                    stack.push(entry.path());
                }
            }
        }
    }
}

impl Drop for Sandbox {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

/// The calls the plan's steps should make: (program, arguments), sorted.
pub fn planned(plan: &Plan) -> Vec<(String, Vec<String>)> {
    let mut calls: Vec<_> = plan
        .steps
        .iter()
        .map(|s| (s.argv[0].clone(), s.argv[1..].to_vec()))
        .collect();
    calls.sort();
    calls
}

/// Puts a stand-in on `PATH` under every program name the plan runs; `false` when a name
/// cannot be one (it holds a `/`): the plan is then checked without running it.
pub fn stand_ins(sandbox: &Sandbox, plan: &Plan) -> bool {
    for step in &plan.steps {
        let name = &step.argv[0];
        if name.contains('/') || name.is_empty() {
            return false;
        }
        let p = sandbox.bin.join(name);
        if !p.exists() && std::fs::copy(sandbox.bin.join("irsig-probe"), &p).is_err() {
            return false;
        }
    }
    true
}

/// Parses `text` as the pipeline file `work/p.ron`; a refusal must be located inside it.
pub fn parse(sandbox: &Sandbox, text: &str) -> Option<Pipeline> {
    let file = sandbox.work.join("p.ron");
    let _ = std::fs::write(&file, text);
    match Pipeline::parse(&file.display().to_string(), text, &sandbox.work) {
        Ok(p) => Some(p),
        Err(e) => {
            if let Some((line, column)) = e.line_column() {
                assert!(line >= 1 && column >= 1);
                assert!(line <= text.split('\n').count(), "line {line}");
            }
            None
        }
    }
}

/// A planned word never holds a control character: the reader refuses them.
pub fn assert_no_control(plan: &Plan) {
    for step in &plan.steps {
        for word in &step.argv {
            assert!(
                !word.contains(char::is_control),
                "a planned word holds a control character: {word:?}"
            );
        }
        assert!(!step.name.contains(char::is_control), "{:?}", step.name);
    }
}

/// The dry run, run by `sh` from the sandbox's root, runs exactly the plan.
pub fn check_dry_run(sandbox: &Sandbox, plan: &Plan) {
    match plan.dry_run_script(true) {
        Ok(script) => {
            assert!(!script.contains('\0'));
            if !stand_ins(sandbox, plan) {
                return;
            }
            let ran = sandbox.run(&sandbox.root, "sh", &["-c", &script], &[]);
            assert!(ran, "the dry run failed under sh:\n{script}");
            assert_eq!(sandbox.take_calls(), planned(plan), "dry run:\n{script}");
        }
        Err(e) => assert_eq!(e.kind(), ErrorKind::ControlCharacter, "{e}"),
    }
    sandbox.assert_no_canary("the dry run");
}

/// The Makefile, run by make in the pipeline's folder, runs exactly the plan. Its inputs
/// that no step writes are made first (empty), when they lie inside the folder.
pub fn check_makefile(sandbox: &Sandbox, plan: &Plan) {
    let makefile = match plan.makefile() {
        Ok(m) => m,
        Err(e) => {
            assert!(
                matches!(e.kind(), ErrorKind::NotMakeable | ErrorKind::ControlCharacter),
                "{e}"
            );
            return;
        }
    };
    for line in makefile.lines() {
        let text = line.strip_prefix('\t').unwrap_or(line);
        assert!(!text.contains(char::is_control), "{line:?}");
    }
    if !stand_ins(sandbox, plan) {
        return;
    }
    let inside = |p: &Path| {
        p.is_relative()
            && p.components()
                .all(|c| matches!(c, std::path::Component::Normal(_)))
    };
    // make creates the outputs' folders: only inside the sandbox.
    if !plan
        .steps
        .iter()
        .all(|s| s.outputs.iter().all(|o| inside(&o.path)))
    {
        return;
    }
    let produced: Vec<&PathBuf> = plan
        .steps
        .iter()
        .flat_map(|s| s.outputs.iter().map(|o| &o.path))
        .collect();
    for step in &plan.steps {
        for input in &step.inputs {
            if produced.contains(&&input.path) {
                continue;
            }
            if !inside(&input.path) {
                return;
            }
            let p = sandbox.work.join(&input.path);
            if let Some(d) = p.parent() {
                let _ = std::fs::create_dir_all(d);
            }
            let _ = std::fs::write(&p, b"");
        }
    }
    let _ = std::fs::write(sandbox.work.join("Makefile.irsig"), &makefile);
    let ran = sandbox.run(
        &sandbox.work,
        "make",
        &["-s", "-f", "Makefile.irsig", "all"],
        &[],
    );
    assert!(ran, "make failed:\n{makefile}");
    assert_eq!(sandbox.take_calls(), planned(plan), "Makefile:\n{makefile}");
    sandbox.assert_no_canary("the Makefile");
}

/// Each job script runs `irsig-run --step NAME PIPELINE` and nothing else; submit.sh runs
/// sbatch once per job.
pub fn check_slurm(sandbox: &Sandbox, plan: &Plan) {
    let pipeline = sandbox.work.join("p.ron");
    let script_dir = sandbox.root.join("slurm");
    let options = SlurmOptions {
        pipeline: pipeline.clone(),
        script_dir: script_dir.clone(),
        runner: sandbox.bin.join("irsig-run"),
        partition: None,
        sbatch: vec!["--account=proj42".to_owned()],
        setup: vec!["true".to_owned()],
        node: None,
        force: true,
    };
    let scripts = match plan.slurm(&options) {
        Ok(s) => s,
        Err(e) => {
            assert_eq!(e.kind(), ErrorKind::ControlCharacter, "{e}");
            return;
        }
    };
    let _ = std::fs::create_dir_all(&script_dir);
    for (name, text) in &scripts.files {
        assert!(!text.contains('\0'));
        let _ = std::fs::write(script_dir.join(name), text);
    }
    for job in &scripts.jobs {
        let script = script_dir.join(&job.script).display().to_string();
        let ran = sandbox.run(
            &sandbox.root,
            "sh",
            &[&script],
            &[("SLURM_ARRAY_TASK_ID", "1")],
        );
        assert!(ran, "{script} failed");
        let step = if job.array.is_some() {
            format!("{}[1]", job.stage)
        } else {
            job.stage.clone()
        };
        assert_eq!(
            sandbox.take_calls(),
            vec![(
                "irsig-run".to_owned(),
                vec!["--step".to_owned(), step, pipeline.display().to_string()]
            )],
            "{script}"
        );
    }
    let submit = script_dir.join("submit.sh").display().to_string();
    assert!(sandbox.run(&sandbox.root, "sh", &[&submit], &[]), "submit.sh failed");
    let calls = sandbox.take_calls();
    assert_eq!(calls.len(), scripts.jobs.len(), "{calls:?}");
    assert!(calls.iter().all(|(tool, _)| tool == "sbatch"), "{calls:?}");
    sandbox.assert_no_canary("the Slurm scripts");
}

/// A RON string literal of `s`, escaped.
fn ron_string(s: &str) -> String {
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

/// Hostile text in every place of a two-stage pipeline: the first stage's name, a
/// parameter's flag and value, a subcommand word and its output (which the second, swept
/// stage reads), and the sweep's variable. Outputs stay in `out/`.
pub fn pipeline_of(texts: &[String; 6]) -> String {
    let [name, key, value, word, output, variable] = texts;
    let literal = |s: &str| s.replace('{', "{{").replace('}', "}}");
    let output = format!("out/{}", output.replace('/', "_").replace("..", "_."));
    format!(
        "Pipeline(\n  sweeps: {{\"s\": Frames([{{\"v\": {variable}}}])}},\n  stages: [\n    \
         Stage(name: {name}, tool: {tool}, params: {{\"p\": {value}, {key}: \"x\"}}, outputs: {{\"o\": {out}}}),\n    \
         Stage(tool: \"probe\", sweep: \"s\", args: [{out}], params: {{\"q\": \"{{v}}\"}}, outputs: {{\"o\": \"f{{frame}}.txt\"}}),\n  ],\n)\n",
        variable = ron_string(variable),
        name = ron_string(&format!("n{name}")),
        tool = ron_string(&format!("probe w{}", literal(word))),
        value = ron_string(&literal(value)),
        key = ron_string(&format!("k{}", literal(key))),
        out = ron_string(&literal(&output)),
    )
}

/// Parses and plans `pipeline_of(texts)`: `None` when it is refused, which must be for a
/// control character or a flag name with whitespace, located.
pub fn plan_of(sandbox: &Sandbox, texts: &[String; 6]) -> Option<Plan> {
    let text = pipeline_of(texts);
    let control = texts.iter().any(|t| t.contains(char::is_control));
    let key_space = texts[1].contains(char::is_whitespace);
    let file = sandbox.work.join("p.ron");
    let _ = std::fs::write(&file, &text);
    let pipeline = match Pipeline::parse(&file.display().to_string(), &text, &sandbox.work) {
        Ok(p) => p,
        Err(e) => {
            assert!(
                (control && e.kind() == ErrorKind::ControlCharacter)
                    || (key_space && e.kind() == ErrorKind::Structure),
                "refused for another reason: {e}\n{text}"
            );
            assert!(e.line_column().is_some());
            return None;
        }
    };
    assert!(!control, "a control character was accepted:\n{text}");
    let plan = pipeline
        .plan(&sandbox.tools())
        .unwrap_or_else(|e| panic!("not planned: {e}\n{text}"));
    assert_no_control(&plan);
    Some(plan)
}
