//! The pipeline runner `irsig-run`, end to end, with the test-only stage tool
//! `irsig-testcat` (concatenates its inputs to `-o`): dependency order, parallel independent
//! stages, skipping up-to-date stages by content (not mtime), `--force`, `--dry-run`
//! (copy-pasteable commands), `--emit-makefile` with GNU make giving byte-identical outputs,
//! frame sweeps, and errors located at the pipeline file's line and column that leave no
//! outputs behind.

use std::path::{Path, PathBuf};
use std::process::Command;

use irsig_tests::{bin, bin_path};
use predicates::prelude::*;

/// A scratch directory holding a pipeline file and its inputs.
struct Scratch {
    dir: tempfile::TempDir,
}

impl Scratch {
    fn new(pipeline: &str, files: &[(&str, &str)]) -> Self {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("pipeline.ron"), pipeline).unwrap();
        for (name, text) in files {
            let path = dir.path().join(name);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, text).unwrap();
        }
        Self { dir }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn read(&self, name: &str) -> String {
        std::fs::read_to_string(self.path(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
    }

    fn run(&self, args: &[&str]) -> assert_cmd::assert::Assert {
        let mut cmd = bin("irsig-run");
        cmd.current_dir(self.dir.path())
            .args(args)
            .arg("pipeline.ron");
        cmd.assert()
    }

    /// How many times the stages logging to `log.txt` have run, by output name.
    fn runs(&self, output: &str) -> usize {
        std::fs::read_to_string(self.path("log.txt"))
            .unwrap_or_default()
            .lines()
            .filter(|l| *l == output)
            .count()
    }

    /// Every file under the directory, relative, sorted; the runner's state excluded.
    fn files(&self) -> Vec<String> {
        let mut out = Vec::new();
        collect(self.dir.path(), self.dir.path(), &mut out);
        out.sort();
        out
    }
}

fn collect(root: &Path, dir: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            collect(root, &path, out);
        } else {
            out.push(path.strip_prefix(root).unwrap().display().to_string());
        }
    }
}

/// 1-based line and column of the first occurrence of `needle`, counted here
/// independently of the runner.
fn line_col(text: &str, needle: &str) -> String {
    let offset = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle} not in text"));
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    format!("pipeline.ron:{line}:{column}")
}

/// A chain written out of order: `c` needs `b` needs `a`, listed c, a, b.
const CHAIN: &str = r#"Pipeline(
    stages: [
        Stage(
            name: "c",
            tool: "testcat",
            args: ["build/b.txt", "tail.txt"],
            params: {"log": "log.txt"},
            outputs: {"o": "build/c.txt"},
        ),
        Stage(
            name: "a",
            tool: "testcat",
            args: ["head.txt"],
            params: {"prefix": "A:", "log": "log.txt"},
            outputs: {"o": "build/a.txt"},
        ),
        Stage(
            name: "b",
            tool: "testcat",
            args: ["build/a.txt"],
            params: {"prefix": "B:", "upper": true, "log": "log.txt"},
            outputs: {"o": "build/b.txt"},
        ),
    ],
)
"#;

fn chain() -> Scratch {
    Scratch::new(CHAIN, &[("head.txt", "head\n"), ("tail.txt", "tail\n")])
}

#[test]
fn stages_run_in_dependency_order_not_file_order() {
    let s = chain();
    s.run(&["--threads", "1"]).success();
    assert_eq!(s.read("build/a.txt"), "A:head\n");
    // b upper-cases everything it writes, its own prefix included.
    assert_eq!(s.read("build/b.txt"), "B:A:HEAD\n");
    assert_eq!(s.read("build/c.txt"), "B:A:HEAD\ntail\n");
    assert_eq!(
        std::fs::read_to_string(s.path("log.txt")).unwrap(),
        "build/a.txt\nbuild/b.txt\nbuild/c.txt\n"
    );
}

#[test]
fn up_to_date_stages_are_skipped_and_content_changes_rerun_them() {
    let s = chain();
    s.run(&[]).success();
    s.run(&[])
        .success()
        .stderr(predicate::str::contains("0 stage(s) ran, 3 up to date"));
    assert_eq!(s.runs("build/a.txt"), 1);

    // Rewriting tail.txt with the same bytes (a new mtime) changes nothing.
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(s.path("tail.txt"), "tail\n").unwrap();
    s.run(&[]).success();
    assert_eq!(s.runs("build/c.txt"), 1);

    // New content in tail.txt reruns only c.
    std::fs::write(s.path("tail.txt"), "TAIL\n").unwrap();
    s.run(&[])
        .success()
        .stderr(predicate::str::contains("1 stage(s) ran, 2 up to date"));
    assert_eq!((s.runs("build/a.txt"), s.runs("build/c.txt")), (1, 2));
    assert_eq!(s.read("build/c.txt"), "B:A:HEAD\nTAIL\n");

    // head.txt changes only in case: a reruns, b reruns (its input changed) but writes the
    // same bytes (it upper-cases), so c is up to date.
    std::fs::write(s.path("head.txt"), "HEAD\n").unwrap();
    s.run(&[]).success();
    assert_eq!(
        (
            s.runs("build/a.txt"),
            s.runs("build/b.txt"),
            s.runs("build/c.txt")
        ),
        (2, 2, 2)
    );

    // An output edited by hand is redone.
    std::fs::write(s.path("build/b.txt"), "tampered").unwrap();
    s.run(&[]).success();
    assert_eq!(s.read("build/b.txt"), "B:A:HEAD\n");
    assert_eq!(s.runs("build/b.txt"), 3);

    // A changed parameter reruns the stage.
    std::fs::write(s.path("pipeline.ron"), CHAIN.replace("\"A:\"", "\"a:\"")).unwrap();
    s.run(&[]).success();
    assert_eq!(s.read("build/a.txt"), "a:HEAD\n");
    assert_eq!(s.runs("build/a.txt"), 3);

    s.run(&["--force"])
        .success()
        .stderr(predicate::str::contains("3 stage(s) ran, 0 up to date"));
    assert_eq!(s.runs("build/a.txt"), 4);
}

#[test]
fn independent_stages_run_at_the_same_time() {
    // Each stage waits for the other to have started: run one after the other, the first
    // would give up after 20 s and fail.
    let text = r#"Pipeline(stages: [
        Stage(tool: "testcat", args: ["x.txt"], params: {"touch": "left.flag", "wait-for": "right.flag"}, outputs: {"o": "left.txt"}),
        Stage(tool: "testcat", args: ["x.txt"], params: {"touch": "right.flag", "wait-for": "left.flag"}, outputs: {"o": "right.txt"}),
    ])"#;
    let s = Scratch::new(text, &[("x.txt", "x")]);
    // `--jobs` (and `-j`), the old spelling of `--threads`, is still taken.
    s.run(&["--jobs", "2"]).success();
    assert_eq!(s.read("left.txt"), "x");
    assert_eq!(s.read("right.txt"), "x");
}

/// Stages run side by side: every line a stage's tool writes on stderr begins with the
/// stage's name, whole; one stage at a time, the tool's stderr is the runner's own.
#[test]
fn warnings_of_stages_run_side_by_side_name_their_stage() {
    let text = r#"Pipeline(stages: [
        Stage(name: "left", tool: "testcat", args: ["x.txt"], params: {"warn": "saturated at 255", "touch": "left.flag", "wait-for": "right.flag"}, outputs: {"o": "left.txt"}),
        Stage(name: "right", tool: "testcat", args: ["x.txt"], params: {"warn": "saturated at 0", "touch": "right.flag", "wait-for": "left.flag"}, outputs: {"o": "right.txt"}),
    ])"#;
    let s = Scratch::new(text, &[("x.txt", "x")]);
    let out = s.run(&["--threads", "2"]).success().get_output().clone();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr
            .lines()
            .any(|l| l == "[left] irsig-testcat: warning: saturated at 255"),
        "{stderr}"
    );
    assert!(
        stderr
            .lines()
            .any(|l| l == "[right] irsig-testcat: warning: saturated at 0"),
        "{stderr}"
    );

    let text = r#"Pipeline(stages: [
        Stage(name: "alone", tool: "testcat", args: ["x.txt"], params: {"warn": "saturated"}, outputs: {"o": "alone.txt"}),
    ])"#;
    let s = Scratch::new(text, &[("x.txt", "x")]);
    let out = s.run(&["--threads", "1"]).success().get_output().clone();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr
            .lines()
            .any(|l| l == "irsig-testcat: warning: saturated"),
        "{stderr}"
    );
}

#[test]
fn dry_run_prints_what_would_run_and_runs_nothing() {
    let s = chain();
    let out = s.run(&["--dry-run"]).success().get_output().stdout.clone();
    let out = String::from_utf8(out).unwrap();
    assert_eq!(
        out,
        "irsig-testcat head.txt --prefix A: --log log.txt -o build/a.txt\n\
         irsig-testcat build/a.txt --prefix B: --upper --log log.txt -o build/b.txt\n\
         irsig-testcat build/b.txt tail.txt --log log.txt -o build/c.txt\n"
    );
    assert!(!s.path("build").exists() && !s.path("log.txt").exists());

    // Up-to-date steps are listed too, as shell comments, so the output still pastes into a
    // shell and runs only what is out of date.
    s.run(&[]).success();
    s.run(&["-n"]).success().stdout(
        "# up to date: irsig-testcat head.txt --prefix A: --log log.txt -o build/a.txt\n\
         # up to date: irsig-testcat build/a.txt --prefix B: --upper --log log.txt -o build/b.txt\n\
         # up to date: irsig-testcat build/b.txt tail.txt --log log.txt -o build/c.txt\n",
    );
    std::fs::write(s.path("tail.txt"), "other\n").unwrap();
    s.run(&["-n"]).success().stdout(
        "# up to date: irsig-testcat head.txt --prefix A: --log log.txt -o build/a.txt\n\
         # up to date: irsig-testcat build/a.txt --prefix B: --upper --log log.txt -o build/b.txt\n\
         irsig-testcat build/b.txt tail.txt --log log.txt -o build/c.txt\n",
    );
    assert_eq!(s.runs("build/c.txt"), 1, "the dry runs ran nothing");
}

#[test]
fn dry_run_commands_paste_into_a_shell_with_the_same_result() {
    let text = r#"Pipeline(stages: [
        Stage(tool: "testcat", args: ["in put.txt"], params: {"prefix": "it's $HOME: "}, outputs: {"o": "out/o.txt"}),
    ])"#;
    let s = Scratch::new(text, &[("in put.txt", "body"), ("out/.keep", "")]);
    let script = s
        .run(&["-n", "--force"])
        .success()
        .get_output()
        .stdout
        .clone();
    let status = Command::new("sh")
        .arg("-c")
        .arg(String::from_utf8(script).unwrap())
        .current_dir(s.dir.path())
        .env("PATH", path_with_tools())
        .status()
        .unwrap();
    assert!(status.success());
    assert_eq!(s.read("out/o.txt"), "it's $HOME: body");
    let by_shell = s.read("out/o.txt");
    std::fs::remove_file(s.path("out/o.txt")).unwrap();
    s.run(&[]).success();
    assert_eq!(s.read("out/o.txt"), by_shell);
}

fn path_with_tools() -> std::ffi::OsString {
    let dir = bin_path("irsig-testcat").parent().unwrap().to_path_buf();
    let mut paths = vec![dir];
    paths.extend(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    ));
    std::env::join_paths(paths).unwrap()
}

/// Frames from a list of variables and from a fly-by, and a stage gathering all frames.
const SWEEPS: &str = r#"Pipeline(
    sweeps: {
        "words": Frames([{"word": "alpha"}, {"word": "beta"}, {"word": "gamma"}]),
        "flyby": FlyBy(frames: 3, path: [(0, 0, 100), (0, 2000, 100)], look_at: (0, 1000, 0)),
    },
    stages: [
        Stage(name: "word", tool: "testcat", sweep: "words", args: ["base.txt"],
              params: {"prefix": "{frame}/{frames} {word} "}, outputs: {"o": "frames/{frame:03}.txt"}),
        Stage(name: "sheet", tool: "testcat", gather: "words", args: ["frames/{frame:03}.txt"],
              outputs: {"o": "sheet.txt"}),
        Stage(name: "fly", tool: "testcat", sweep: "flyby", args: ["base.txt"],
              params: {"prefix": "eye={eye} at={look_at} y={eye_y_m} "}, outputs: {"o": "fly/{frame}.txt"}),
    ],
)"#;

#[test]
fn sweeps_run_one_stage_per_frame_and_gather_collects_them() {
    let s = Scratch::new(SWEEPS, &[("base.txt", ".\n")]);
    s.run(&[]).success();
    assert_eq!(s.read("frames/002.txt"), "2/3 beta .\n");
    assert_eq!(
        s.read("sheet.txt"),
        "1/3 alpha .\n2/3 beta .\n3/3 gamma .\n"
    );
    // Three frames spread evenly over 2000 m: y = 0, 1000, 2000.
    assert_eq!(s.read("fly/1.txt"), "eye=0,0,100 at=0,1000,0 y=0 .\n");
    assert_eq!(s.read("fly/2.txt"), "eye=0,1000,100 at=0,1000,0 y=1000 .\n");
    assert_eq!(s.read("fly/3.txt"), "eye=0,2000,100 at=0,1000,0 y=2000 .\n");
}

#[test]
fn the_makefile_gives_byte_identical_outputs() {
    let by_runner = Scratch::new(SWEEPS, &[("base.txt", ".\n")]);
    by_runner.run(&[]).success();
    let by_make = Scratch::new(SWEEPS, &[("base.txt", ".\n")]);
    by_make.run(&["--emit-makefile", "Makefile"]).success();
    let status = Command::new("make")
        .args(["-j4", "--no-print-directory"])
        .current_dir(by_make.dir.path())
        .env("PATH", path_with_tools())
        .status()
        .unwrap();
    assert!(status.success());
    let outputs: Vec<String> = by_runner
        .files()
        .into_iter()
        .filter(|f| !f.starts_with(".irsig-run"))
        .collect();
    assert!(outputs.len() > 6, "{outputs:?}");
    for f in &outputs {
        assert_eq!(
            std::fs::read(by_runner.path(f)).unwrap(),
            std::fs::read(by_make.path(f)).unwrap(),
            "{f} differs"
        );
    }
    // make agrees that everything is up to date afterwards.
    let again = Command::new("make")
        .args(["-q"])
        .current_dir(by_make.dir.path())
        .env("PATH", path_with_tools())
        .status()
        .unwrap();
    assert!(again.success(), "make -q says something is out of date");
}

/// The report with miette's line wrapping undone: every run of whitespace and the `│`
/// that starts a wrapped line become one space.
fn unwrapped(report: &str) -> String {
    report
        .replace('│', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// Runs a broken pipeline and checks the error names `needle`'s line and column, carries
/// `message`, exits 1, and leaves the directory as it was.
fn fails_at(text: &str, needle: &str, message: &str) {
    let s = Scratch::new(text, &[("x.txt", "x")]);
    let before = s.files();
    let stderr = s.run(&[]).code(1).get_output().stderr.clone();
    let stderr = unwrapped(&String::from_utf8_lossy(&stderr));
    let place = line_col(text, needle);
    assert!(
        stderr.contains(&place) && stderr.contains(message),
        "expected {place} and {message:?} in:\n{stderr}"
    );
    s.run(&["--dry-run"]).code(1);
    s.run(&["--emit-makefile", "Makefile"]).code(1);
    assert_eq!(s.files(), before, "a failed run left files behind");
}

#[test]
fn a_syntax_error_names_its_line_and_column() {
    fails_at(
        "Pipeline(stages: [\n    Stage(tool: \"testcat\" args: [\"x.txt\"]),\n])",
        "args",
        "Expected",
    );
}

#[test]
fn an_unknown_field_names_its_line_and_column() {
    fails_at(
        "Pipeline(stages: [\n    Stage(tool: \"testcat\", argz: [\"x.txt\"]),\n])",
        "argz",
        "unknown field `argz`",
    );
}

#[test]
fn a_missing_input_names_its_line_and_column() {
    fails_at(
        r#"Pipeline(stages: [
    Stage(tool: "testcat", args: ["x.txt"], outputs: {"o": "a.txt"}),
    Stage(tool: "testcat", args: ["a.txt", "nope.txt"], outputs: {"o": "b.txt"}),
])"#,
        "\"nope.txt\"",
        "input file `nope.txt` does not exist and no stage writes it",
    );
}

#[test]
fn two_stages_writing_one_file_is_an_error_at_the_second() {
    fails_at(
        r#"Pipeline(stages: [
    Stage(tool: "testcat", args: ["x.txt"], outputs: {"o": "same.txt"}),
    Stage(tool: "testcat", args: ["x.txt"], outputs: {"o": "./same.txt"}),
])"#,
        "\"./same.txt\"",
        "written by stage `testcat#2` here and by stage `testcat#1` on line 2",
    );
}

#[test]
fn a_cycle_is_an_error_that_tells_the_loop() {
    fails_at(
        r#"Pipeline(stages: [
    Stage(name: "x", tool: "testcat", args: ["x.txt"], outputs: {"o": "p.txt"}),
    Stage(name: "a", tool: "testcat", args: ["c.txt"], outputs: {"o": "a.txt"}),
    Stage(name: "b", tool: "testcat", args: ["a.txt"], outputs: {"o": "b.txt"}),
    Stage(name: "c", tool: "testcat", args: ["b.txt"], outputs: {"o": "c.txt"}),
])"#,
        "\"c.txt\"",
        "the stages form a cycle: `a` reads `c.txt`, written by `c`; `c` reads `b.txt`, written by `b`; `b` reads `a.txt`, written by `a`",
    );
}

#[test]
fn an_unknown_tool_names_its_line_and_column() {
    fails_at(
        "Pipeline(stages: [\n  Stage(tool: \"no-such-tool\", args: [\"x.txt\"]),\n])",
        "\"no-such-tool\"",
        "unknown tool `no-such-tool`",
    );
}

#[test]
fn an_unknown_parameter_is_caught_by_the_tools_own_parser() {
    // `run` is a stage tool whose `Cli` the runner registers: a sub-pipeline.
    fails_at(
        "Pipeline(stages: [\n  Stage(tool: \"run\", args: [\"x.txt\"], params: {\"force\": true, \"no-such-flag\": 3}),\n])",
        "\"no-such-flag\"",
        "unexpected argument '--no-such-flag'",
    );
}

#[test]
fn a_mistyped_parameter_points_at_its_value() {
    fails_at(
        "Pipeline(stages: [\n  Stage(tool: \"run\", args: [\"x.txt\"], params: {\"threads\": \"many\"}),\n])",
        "\"many\"",
        "invalid value 'many' for '--threads <N>'",
    );
}

#[test]
fn an_undefined_frame_variable_names_its_line_and_column() {
    fails_at(
        r#"Pipeline(sweeps: {"s": Frames([{"a": "1"}])}, stages: [
  Stage(tool: "testcat", sweep: "s", args: ["x.txt"], outputs: {"o": "{b}.txt"}),
])"#,
        "\"{b}.txt\"",
        "unknown variable `b`",
    );
}

#[test]
fn a_failing_stage_stops_the_run_and_names_the_stage() {
    // testcat has no validator registered, so its own parser rejects `--bogus` at run time.
    let text = r#"Pipeline(stages: [
    Stage(name: "bad", tool: "testcat", args: ["x.txt"], params: {"bogus": true}, outputs: {"o": "a.txt"}),
    Stage(name: "after", tool: "testcat", args: ["a.txt"], outputs: {"o": "b.txt"}),
])"#;
    let s = Scratch::new(text, &[("x.txt", "x")]);
    s.run(&[])
        .code(1)
        .stderr(
            predicate::str::contains("stage `bad` failed").and(predicate::str::contains(line_col(
                text,
                "Stage(name: \"bad\"",
            ))),
        );
    assert!(!s.path("a.txt").exists() && !s.path("b.txt").exists());
}

/// Copies `formats/samples/pipeline.ron` and its inputs to a scratch directory.
fn sample() -> Scratch {
    let root = irsig_tests::repo_root().join("formats/samples");
    let text = std::fs::read_to_string(root.join("pipeline.ron")).unwrap();
    let inputs: Vec<(String, String)> = ["scene", "objects", "north", "south"]
        .iter()
        .map(|n| {
            let name = format!("pipeline/{n}.txt");
            let body = std::fs::read_to_string(root.join(&name)).unwrap();
            (name, body)
        })
        .collect();
    let refs: Vec<(&str, &str)> = inputs
        .iter()
        .map(|(a, b)| (a.as_str(), b.as_str()))
        .collect();
    Scratch::new(&text, &refs)
}

#[test]
fn the_sample_pipeline_runs_the_same_by_runner_make_shell_and_pipe() {
    let runner = sample();
    runner.run(&[]).success();
    let scene = "scene: a flat field, a road, a panel\nvehicle\n";
    assert_eq!(runner.read("build/scene.txt"), scene);
    let north = "NORTH SCENE: A FLAT FIELD, A ROAD, A PANEL\nVEHICLE\nLOOKING NORTH\n";
    let south = "SOUTH SCENE: A FLAT FIELD, A ROAD, A PANEL\nVEHICLE\nLOOKING SOUTH\n";
    assert_eq!(runner.read("build/view-01.txt"), north);
    assert_eq!(runner.read("build/sheet.txt"), format!("{north}{south}"));
    // 4 frames evenly over y = -1500..1500 m: -1500, -500, 500, 1500.
    assert_eq!(
        runner.read("build/fly-2.txt"),
        format!("frame 2/4 at 0,-500,300 looking at 0,0,0: {scene}")
    );
    assert_eq!(
        runner.read("build/fly-4.txt"),
        format!("frame 4/4 at 0,1500,300 looking at 0,0,0: {scene}")
    );
    let outputs: Vec<String> = runner
        .files()
        .into_iter()
        .filter(|f| f.starts_with("build/"))
        .collect();
    assert_eq!(outputs.len(), 8, "{outputs:?}");

    let by_make = sample();
    by_make.run(&["--emit-makefile", "Makefile"]).success();
    assert!(
        Command::new("make")
            .args(["-j4", "-s"])
            .current_dir(by_make.dir.path())
            .env("PATH", path_with_tools())
            .status()
            .unwrap()
            .success()
    );
    let by_shell = sample();
    let script = by_shell.run(&["-n"]).success().get_output().stdout.clone();
    // The dry run does not create directories: the script's commands need build/.
    std::fs::create_dir(by_shell.path("build")).unwrap();
    assert!(
        Command::new("sh")
            .arg("-c")
            .arg(String::from_utf8(script).unwrap())
            .current_dir(by_shell.dir.path())
            .env("PATH", path_with_tools())
            .status()
            .unwrap()
            .success()
    );
    for f in &outputs {
        let expected = std::fs::read(runner.path(f)).unwrap();
        assert_eq!(
            std::fs::read(by_make.path(f)).unwrap(),
            expected,
            "make: {f}"
        );
        assert_eq!(
            std::fs::read(by_shell.path(f)).unwrap(),
            expected,
            "sh: {f}"
        );
    }

    // The Unix-pipe form of docs/pipelines.md: the scene stage streams into a view stage.
    let piped = sample();
    std::fs::create_dir(piped.path("build")).unwrap();
    let pipe = "irsig-testcat pipeline/scene.txt pipeline/objects.txt --prefix 'scene: ' \
                | irsig-testcat - pipeline/north.txt --prefix 'north ' --upper -o build/view-01.txt";
    assert!(
        Command::new("sh")
            .arg("-c")
            .arg(pipe)
            .current_dir(piped.dir.path())
            .env("PATH", path_with_tools())
            .status()
            .unwrap()
            .success()
    );
    assert_eq!(piped.read("build/view-01.txt"), north);
}
