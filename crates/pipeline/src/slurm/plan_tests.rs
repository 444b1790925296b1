use super::*;
use crate::{Pipeline, Tools};

/// A scratch directory with a stand-in tool program (hashed, never run) and `in.txt`.
struct Scratch {
    dir: tempfile::TempDir,
}

impl Scratch {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("irsig-tool"), "a program").unwrap();
        std::fs::write(dir.path().join("in.txt"), "input").unwrap();
        Self { dir }
    }

    fn plan(&self, text: &str) -> Result<Plan, PipelineError> {
        let program = self.dir.path().join("irsig-tool");
        let tools = Tools::new(move |_| Some(program.clone()));
        Pipeline::parse("p.ron", text, self.dir.path())?.plan(&tools)
    }

    fn options(&self) -> SlurmOptions {
        SlurmOptions {
            pipeline: self.dir.path().join("p.ron"),
            script_dir: self.dir.path().join("slurm"),
            runner: PathBuf::from("/opt/irsig/bin/irsig-run"),
            partition: None,
            sbatch: Vec::new(),
            setup: Vec::new(),
            node: None,
            force: false,
        }
    }

    fn scripts(&self, text: &str) -> SlurmScripts {
        self.plan(text).unwrap().slurm(&self.options()).unwrap()
    }
}

fn file<'a>(scripts: &'a SlurmScripts, name: &str) -> &'a str {
    &scripts
        .files
        .iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no {name}"))
        .1
}

/// 1-based line and column of the first `needle` in `text`, counted here.
fn line_col(text: &str, needle: &str) -> (usize, usize) {
    let offset = text.find(needle).unwrap();
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    (
        line,
        before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1,
    )
}

const CHAIN: &str = r#"(
    sweeps: {"f": Frames([{"n": "1"}, {"n": "2"}, {"n": "3"}])},
    stages: [
        (name: "a", tool: "t", sweep: "f", args: ["in.txt"], params: {"n": "{n}"},
         outputs: {"o": "build/a-{frame}.txt"}),
        (name: "b", tool: "t", sweep: "f", args: ["build/a-{frame}.txt"],
         outputs: {"o": "build/b-{frame}.txt"}, slurm: (cpus: 2, memory_mib: 300, time_limit_min: 15)),
        (name: "sheet", tool: "t", gather: "f", args: ["build/b-{frame}.txt"],
         outputs: {"o": "build/sheet.txt"}),
    ],
)"#;

#[test]
fn sweeps_become_arrays_and_a_frame_waits_only_for_its_own_frame() {
    let s = Scratch::new();
    let scripts = s.scripts(CHAIN);
    let jobs: Vec<_> = scripts
        .jobs
        .iter()
        .map(|j| {
            (
                j.script.as_str(),
                j.array.as_deref(),
                j.tasks,
                j.after.clone(),
            )
        })
        .collect();
    assert_eq!(
        jobs,
        [
            ("01-a.sbatch", Some("1-3"), 3, vec![]),
            (
                "02-b.sbatch",
                Some("1-3"),
                3,
                vec![(Dependency::AfterCorr, 0)]
            ),
            ("03-sheet.sbatch", None, 1, vec![(Dependency::AfterOk, 1)]),
        ]
    );
    let submit = file(&scripts, "submit.sh");
    assert!(
        submit.contains("--dependency=aftercorr:$job1 \"$dir/02-b.sbatch\""),
        "{submit}"
    );
    assert!(
        submit.contains("--dependency=afterok:$job2 \"$dir/03-sheet.sbatch\""),
        "{submit}"
    );
    assert!(submit.contains("command -v sbatch"), "{submit}");

    let a = file(&scripts, "01-a.sbatch");
    assert!(a.contains("\n#SBATCH --array=1-3\n"), "{a}");
    assert!(a.contains("\n#SBATCH --cpus-per-task=1\n"), "{a}");
    // The first job waits for nothing, so it has no --kill-on-invalid-dep.
    assert!(!a.contains("kill-on-invalid-dep"), "{a}");
    let pipeline = s.dir.path().join("p.ron").display().to_string();
    assert!(
        a.ends_with(&format!(
            "exec /opt/irsig/bin/irsig-run --step a\"[$SLURM_ARRAY_TASK_ID]\" {}\n",
            crate::shell_quote(&pipeline).unwrap()
        )),
        "{a}"
    );
    let b = file(&scripts, "02-b.sbatch");
    for line in [
        "#SBATCH --cpus-per-task=2",
        "#SBATCH --mem=300M",
        "#SBATCH --time=15",
        "#SBATCH --kill-on-invalid-dep=yes",
    ] {
        assert!(b.contains(&format!("\n{line}\n")), "{line} in {b}");
    }
    assert!(!b.contains("estimated"), "{b}");
    let sheet = file(&scripts, "03-sheet.sbatch");
    assert!(
        sheet.contains(&format!(
            "exec /opt/irsig/bin/irsig-run --step sheet {}",
            crate::shell_quote(&pipeline).unwrap()
        )),
        "{sheet}"
    );
}

#[test]
fn the_frames_of_a_day_show_their_times_in_every_script() {
    let s = Scratch::new();
    let text = r#"(
    sweeps: {"day": Times(start: "2001-08-07T23:00", end: "2001-08-08T01:00", step: "PT1H", zone: "America/Denver")},
    stages: [
        (name: "therm", tool: "t", gather: "day", args: ["in.txt"], params: {"at": "{time}"},
         outputs: {"raw": "build/{time_utc}.raw"}),
        (name: "trace", tool: "t", sweep: "day", args: ["build/{time_utc}.raw"],
         outputs: {"o": "build/{time_utc}.exr"}),
    ],
)"#;
    let scripts = s.scripts(text);
    // The frames' one thermal job, then the array that waits for all of it.
    assert_eq!(scripts.jobs[1].after, [(Dependency::AfterOk, 0)]);
    let trace = file(&scripts, "02-trace.sbatch");
    for line in [
        "#   task 1: 2001-08-07T23:00:00-06:00",
        "#   task 2: 2001-08-08T00:00:00-06:00",
        "#   task 3: 2001-08-08T01:00:00-06:00",
        "#SBATCH --array=1-3",
    ] {
        assert!(trace.contains(&format!("\n{line}\n")), "{line} in {trace}");
    }
    let plan = s.plan(text).unwrap();
    let makefile = plan.makefile().unwrap();
    assert!(
        makefile.contains("\n# trace[2] (2001-08-08T00:00:00-06:00) (p.ron:"),
        "{makefile}"
    );
    assert!(
        makefile.contains("build/20010808T060000Z.exr : build/20010808T060000Z.raw\n"),
        "{makefile}"
    );
}

#[test]
fn a_task_reading_another_frame_waits_for_the_whole_array() {
    let s = Scratch::new();
    // Every frame of b reads frame 1 of a.
    let text = CHAIN.replace(
        r#"args: ["build/a-{frame}.txt"]"#,
        r#"args: ["build/a-1.txt"]"#,
    );
    let scripts = s.scripts(&text);
    assert_eq!(scripts.jobs[1].after, [(Dependency::AfterOk, 0)]);
}

#[test]
fn memory_is_estimated_from_what_a_task_reads() {
    let s = Scratch::new();
    // 3 MiB of input: 64 + 36 MiB. b's inputs are not written yet: each counts as what
    // its producer reads (3 MiB), so b asks the same; sheet reads three of them.
    std::fs::write(s.dir.path().join("in.txt"), vec![b'x'; 3 << 20]).unwrap();
    let text = CHAIN.replace(
        ", slurm: (cpus: 2, memory_mib: 300, time_limit_min: 15)",
        "",
    );
    let scripts = s.scripts(&text);
    let mem: Vec<_> = scripts
        .jobs
        .iter()
        .map(|j| (j.memory_mib, j.memory_estimated))
        .collect();
    assert_eq!(mem, [(100, true), (100, true), (64 + 108, true)]);
    assert!(file(&scripts, "01-a.sbatch").contains("\n#SBATCH --mem=100M\n"));
}

#[test]
fn site_options_reach_every_job() {
    let s = Scratch::new();
    let mut options = s.options();
    options.partition = Some("batch".to_owned());
    options.sbatch = vec!["--account=proj42".to_owned()];
    options.setup = vec!["module load irsig".to_owned()];
    let scripts = s.plan(CHAIN).unwrap().slurm(&options).unwrap();
    for job in &scripts.jobs {
        let text = file(&scripts, &job.script);
        let setup = text.find("\nmodule load irsig\n").expect("setup line");
        assert!(setup < text.find("\nexec ").unwrap(), "{text}");
        assert!(text.contains("\n#SBATCH --partition=batch\n"), "{text}");
        assert!(text.contains("\n#SBATCH --account=proj42\n"), "{text}");
    }
    options.partition = Some("batch; rm -rf".to_owned());
    let e = s.plan(CHAIN).unwrap().slurm(&options).unwrap_err();
    assert!(e.to_string().contains("partition"), "{e}");
}

#[test]
fn bad_resource_values_are_located() {
    let s = Scratch::new();
    for (good, bad, needle) in [
        ("cpus: 2", "cpus: 0", "0, memory_mib"),
        ("cpus: 2", "cpus: 2.5", "2.5"),
        ("memory_mib: 300", "memory_mib: \"lots\"", "\"lots\""),
        ("time_limit_min: 15", "time_limit_min: -3", "-3"),
    ] {
        let text = CHAIN.replace(good, bad);
        let e = s.plan(&text).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::Structure, "{bad}: {e}");
        assert_eq!(e.line_column(), Some(line_col(&text, needle)), "{bad}: {e}");
    }
    let text = CHAIN.replace("cpus: 2", "mem: 2");
    let e = s.plan(&text).unwrap_err();
    assert!(
        e.to_string().contains("unknown field `mem` in Slurm"),
        "{e}"
    );
    assert_eq!(e.line_column(), Some(line_col(&text, "mem: 2")));
}

#[test]
fn a_request_no_node_can_meet_is_located() {
    let s = Scratch::new();
    let mut options = s.options();
    options.node = Some(NodeLimits {
        cpus: 2,
        memory_mib: 1000,
        source: "a test".to_owned(),
    });
    assert!(s.plan(CHAIN).unwrap().slurm(&options).is_ok());

    let text = CHAIN.replace("memory_mib: 300", "memory_mib: 1001");
    let e = s.plan(&text).unwrap().slurm(&options).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ExceedsNode);
    assert_eq!(e.line_column(), Some(line_col(&text, "1001")));
    assert!(e.to_string().contains("1001 MiB"), "{e}");

    let text = CHAIN.replace("cpus: 2", "cpus: 3");
    let e = s.plan(&text).unwrap().slurm(&options).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ExceedsNode);
    assert_eq!(e.line_column(), Some(line_col(&text, "3, memory")));

    // An estimate beyond the node points at the stage and says how to state the need.
    std::fs::write(s.dir.path().join("in.txt"), vec![b'x'; 100 << 20]).unwrap();
    let e = s.plan(CHAIN).unwrap().slurm(&options).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::ExceedsNode);
    assert_eq!(e.line_column(), Some(line_col(CHAIN, "(name: \"a\"")));
    assert!(format!("{:?}", miette::Report::new(e)).contains("memory_mib"));
}
