//! `irsig-run --emit-slurm` through a real Slurm cluster (the several nodes on one machine
//! `scripts/slurm/start-local-cluster.sh` starts, as `.ci/run` does): the thesis fly-by's 24
//! frames, submitted by `docs/slurm.md`'s recipes as written, as a job array spread over the nodes, byte for byte the same files as `irsig-run`
//! writes; one of those frames killed while it runs, and a resubmission that runs that frame
//! alone (every other file keeps its time) and ends with the same bytes; a day of hourly
//! frames (a `Times` sweep) as an array waiting for the one thermal job that solves the
//! whole day, spread over the nodes, with irsig-run's bytes; one 1024²
//! frame in 16 tiles (`pipelines/quickstart-tiles.ron`: a job array of tiles, the merge and
//! the sensor stage after it), byte for byte the frame `irsig-run` traces whole; a per-frame
//! chain waiting task by task (`aftercorr`), a failed task, and a re-submission that runs only
//! what is still out of date; a memory request beyond the node refused at its line and
//! column. Without a running cluster those tests fail and say why: they never skip.
//!
//! Also, without a cluster: `irsig-run --step` (what each task runs) and its shared run
//! state under concurrent runners, and `submit.sh` without `sbatch` on `PATH`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use irsig_tests::{bin, bin_path, recipe, repo_root};
use predicates::prelude::*;

/// How long a submission may take before the test gives up and names what is still queued.
/// The fly-by takes 20-40 s on the 2-core machine.
const TIMEOUT: Duration = Duration::from_secs(300);

/// Why the cluster cannot take jobs, if it cannot.
fn cluster_problem() -> Option<String> {
    let output = |program: &str, args: &[&str]| -> Result<String, String> {
        let out = Command::new(program)
            .args(args)
            .stdin(Stdio::null())
            .output()
            .map_err(|e| {
                format!("cannot run `{program}` ({e}): is Debian's slurm-wlm installed?")
            })?;
        if out.status.success() {
            Ok(String::from_utf8_lossy(&out.stdout).into_owned())
        } else {
            Err(format!(
                "`{program} {}` failed: {}",
                args.join(" "),
                String::from_utf8_lossy(&out.stderr).trim()
            ))
        }
    };
    match output("scontrol", &["ping"]) {
        Err(e) => return Some(e),
        Ok(text) if !text.contains("is UP") => {
            return Some(format!("slurmctld is not answering: {}", text.trim()));
        }
        Ok(_) => {}
    }
    match output("sinfo", &["--noheader", "--format=%T"]) {
        Err(e) => Some(e),
        Ok(states) => {
            let usable = states
                .lines()
                .any(|s| ["idle", "mixed", "allocated", "completing"].contains(&s.trim()));
            (!usable).then(|| format!("no node takes jobs (sinfo states: {})", states.trim()))
        }
    }
}

/// Fails the test, with the reason, unless the cluster takes jobs.
fn require_cluster() {
    if let Some(problem) = cluster_problem() {
        panic!(
            "the Slurm cluster these tests submit to is not running: {problem}\n\
             start it with `scripts/slurm/start-local-cluster.sh` (as root; .ci/run does), \
             after `apt-get install slurm-wlm munge`"
        );
    }
}

/// Copies a pipeline file and its data directory (without any `build/`) into a new scratch
/// directory.
fn copy_pipeline(name: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let src = repo_root().join("pipelines");
    std::fs::copy(
        src.join(format!("{name}.ron")),
        dir.path().join(format!("{name}.ron")),
    )
    .unwrap();
    recipe::copy_tree(&src.join(name), &dir.path().join(name));
    dir
}

/// `irsig-run --emit-slurm slurm PIPELINE` in `dir`, then `sh slurm/submit.sh`: the job ids
/// with their scripts, in submission order.
fn emit_and_submit(dir: &Path, pipeline: &str) -> Vec<(String, String)> {
    bin("irsig-run")
        .current_dir(dir)
        .args(["--emit-slurm", "slurm", pipeline])
        .assert()
        .success();
    submit(dir)
}

/// The first line of `docs/slurm.md`'s recipe that submits the fly-by, and of the one that
/// submits it again after a loss.
const FLYBY_RECIPE: &str = "irsig-run --emit-slurm slurm pipelines/thesis-flyby.ron   # writes slurm/*.sbatch, slurm/submit.sh";
const FLYBY_AGAIN_RECIPE: &str =
    "irsig-run --emit-slurm slurm pipelines/thesis-flyby.ron   # now: only the frames not done";

/// Runs `docs/slurm.md`'s recipe that starts with `first_line` as written in `dir` (a
/// scratch copy of the clone): the job ids `submit.sh` printed with their scripts, in
/// submission order.
fn submit_by_recipe(dir: &Path, first_line: &str) -> Vec<(String, String)> {
    let out = recipe::run_ok(&recipe::block("docs/slurm.md", first_line), dir, &[]);
    // `submit.sh` prints "JOBID SCRIPT" per job; `squeue --me` after it prints a table.
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .filter_map(|l| {
            let (id, script) = l.split_once(' ')?;
            (id.chars().all(|c| c.is_ascii_digit()) && script.ends_with(".sbatch"))
                .then(|| (id.to_owned(), script.to_owned()))
        })
        .collect()
}

fn submit(dir: &Path) -> Vec<(String, String)> {
    let out = Command::new("sh")
        .arg("slurm/submit.sh")
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "submit.sh failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let (id, script) = l.split_once(' ').unwrap_or_else(|| panic!("line {l:?}"));
            assert!(id.chars().all(|c| c.is_ascii_digit()), "job id {id:?}");
            (id.to_owned(), script.to_owned())
        })
        .collect()
}

/// Every task of the jobs: `(job id, array task or "-") -> (state, exit code)`, from
/// `scontrol show job`, which keeps finished jobs for the cluster's MinJobAge (10 min).
/// (`sacct` needs slurmdbd for array tasks; the local cluster has no database.)
fn task_states(jobs: &[(String, String)]) -> BTreeMap<(String, String), (String, String)> {
    let mut states = BTreeMap::new();
    for (id, script) in jobs {
        let out = Command::new("scontrol")
            .args(["--oneliner", "show", "job", id])
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success() && !text.trim().is_empty(),
            "scontrol knows no job {id} ({script}): {}",
            String::from_utf8_lossy(&out.stderr)
        );
        for line in text.lines() {
            let field = |key: &str| {
                line.split_whitespace()
                    .find_map(|w| w.strip_prefix(key))
                    .unwrap_or("-")
                    .to_owned()
            };
            states.insert(
                (id.clone(), field("ArrayTaskId=")),
                (field("JobState="), field("ExitCode=")),
            );
        }
    }
    states
}

/// The nodes the tasks of job `id` ran on (each task's `BatchHost`), from `scontrol show job`.
fn nodes_of(id: &str) -> BTreeSet<String> {
    let out = Command::new("scontrol")
        .args(["--oneliner", "show", "job", id])
        .output()
        .unwrap();
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|line| {
            line.split_whitespace()
                .find_map(|w| w.strip_prefix("BatchHost="))
                .map(str::to_owned)
        })
        .collect()
}

/// Waits until none of the jobs is pending or running. On timeout, cancels them and fails
/// naming each job, task and state.
fn wait_for(jobs: &[(String, String)]) {
    let ids: Vec<&str> = jobs.iter().map(|(id, _)| id.as_str()).collect();
    let start = Instant::now();
    loop {
        let out = Command::new("squeue")
            .args(["--noheader", "--format=%i %T %r", "--jobs", &ids.join(",")])
            .output()
            .unwrap();
        let queued = String::from_utf8_lossy(&out.stdout).trim().to_owned();
        if out.status.success() && queued.is_empty() {
            return;
        }
        if start.elapsed() > TIMEOUT {
            let _ = Command::new("scancel").args(&ids).status();
            panic!(
                "the jobs did not finish within {} s; still queued (job_task state reason):\n{queued}\n\
                 jobs: {jobs:?}",
                TIMEOUT.as_secs()
            );
        }
        std::thread::sleep(Duration::from_millis(250));
    }
}

/// Fails, with each failed task's log, unless every task of the jobs completed.
fn assert_all_completed(dir: &Path, jobs: &[(String, String)]) {
    let states = task_states(jobs);
    let failed: Vec<String> = states
        .iter()
        .filter(|(_, (state, _))| state != "COMPLETED")
        .map(|((id, task), (state, exit))| format!("job {id} task {task}: {state} (exit {exit})"))
        .collect();
    assert!(
        failed.is_empty(),
        "{}\nlogs:\n{}",
        failed.join("\n"),
        logs(dir)
    );
}

fn logs(dir: &Path) -> String {
    let mut text = String::new();
    if let Ok(entries) = std::fs::read_dir(dir.join("slurm/logs")) {
        for e in entries.flatten() {
            text.push_str(&format!(
                "--- {}\n{}",
                e.file_name().to_string_lossy(),
                std::fs::read_to_string(e.path()).unwrap_or_default()
            ));
        }
    }
    text
}

/// Every file under `dir`, relative, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| PathBuf::from(e.unwrap().file_name()))
        .collect();
    out.sort();
    out
}

/// The same files, byte for byte.
fn assert_same_files(expected: &Path, got: &Path) {
    let names = files(expected);
    assert_eq!(
        names,
        files(got),
        "{} vs {}",
        expected.display(),
        got.display()
    );
    for name in names {
        let (a, b) = (
            std::fs::read(expected.join(&name)).unwrap(),
            std::fs::read(got.join(&name)).unwrap(),
        );
        assert!(a == b, "{} differs from irsig-run's", name.display());
    }
}

#[test]
fn the_thesis_flyby_as_a_job_array_writes_irsig_runs_bytes() {
    require_cluster();
    let local = copy_pipeline("thesis-flyby");
    bin("irsig-run")
        .current_dir(local.path())
        .args(["--quiet", "thesis-flyby.ron"])
        .assert()
        .success();
    // The page's recipe, as written, in a copy of the clone.
    let cluster = recipe::scratch_root();
    let jobs = submit_by_recipe(cluster.path(), FLYBY_RECIPE);
    let scripts: Vec<&str> = jobs.iter().map(|(_, s)| s.as_str()).collect();
    assert_eq!(
        scripts,
        [
            "01-flatten.sbatch",
            "02-trace.sbatch",
            "03-contact-sheet.sbatch"
        ]
    );
    let trace = std::fs::read_to_string(cluster.path().join("slurm/02-trace.sbatch")).unwrap();
    assert!(trace.contains("\n#SBATCH --array=1-24\n"), "{trace}");
    wait_for(&jobs);
    assert_all_completed(cluster.path(), &jobs);
    let states = task_states(&jobs);
    let trace_tasks = states.keys().filter(|(id, _)| *id == jobs[1].0).count();
    assert_eq!(trace_tasks, 24, "one task per frame: {states:?}");
    // The local cluster is several nodes (one slurmd each): the frames are spread over them,
    // and the bytes below are the same whichever node wrote them.
    let nodes = nodes_of(&jobs[1].0);
    assert!(
        nodes.len() >= 2,
        "the frames ran on one node only: {nodes:?}"
    );
    let build = "thesis-flyby/build";
    let cluster_build = cluster.path().join("pipelines").join(build);
    assert_same_files(&local.path().join(build), &cluster_build);
    // 1 raw scene, 5 files per frame, the contact sheet.
    assert_eq!(files(&cluster_build).len(), 1 + 24 * 5 + 1);

    // The tasks recorded their runs in the shared state: irsig-run finds all 26 steps done.
    bin("irsig-run")
        .current_dir(cluster.path())
        .arg("pipelines/thesis-flyby.ron")
        .assert()
        .success()
        .stderr(predicate::str::contains("0 stage(s) ran, 26 up to date"));

    // A lost frame: the next submission is that frame, and the sheet after it.
    std::fs::remove_file(cluster_build.join("frame-07.truth.exr")).unwrap();
    let jobs = submit_by_recipe(cluster.path(), FLYBY_AGAIN_RECIPE);
    let scripts: Vec<&str> = jobs.iter().map(|(_, s)| s.as_str()).collect();
    assert_eq!(scripts, ["01-trace.sbatch", "02-contact-sheet.sbatch"]);
    let trace = std::fs::read_to_string(cluster.path().join("slurm/01-trace.sbatch")).unwrap();
    assert!(trace.contains("\n#SBATCH --array=7\n"), "{trace}");
    assert!(
        !cluster
            .path()
            .join("slurm/03-contact-sheet.sbatch")
            .exists(),
        "the earlier submission's scripts are replaced"
    );
    wait_for(&jobs);
    assert_all_completed(cluster.path(), &jobs);
    assert_same_files(&local.path().join(build), &cluster_build);
}

/// Every file under `dir` with its modification time.
fn file_times(dir: &Path) -> BTreeMap<PathBuf, std::time::SystemTime> {
    files(dir)
        .into_iter()
        .map(|name| {
            let time = std::fs::metadata(dir.join(&name))
                .and_then(|m| m.modified())
                .unwrap();
            (name, time)
        })
        .collect()
}

/// Cancels (SIGTERM, then SIGKILL: what a lost node or a pre-emption does to a task) one
/// task of array job `id` while it runs, and returns its task number. A task seen running
/// may end before the cancel reaches it; then the next one running is tried.
fn kill_one_running_task(id: &str) -> String {
    let start = Instant::now();
    let mut tried = BTreeSet::new();
    while start.elapsed() < TIMEOUT {
        let out = Command::new("squeue")
            .args([
                "--noheader",
                "--format=%i",
                "--states=RUNNING",
                "--jobs",
                id,
            ])
            .output()
            .unwrap();
        let running = String::from_utf8_lossy(&out.stdout).into_owned();
        // A task after the first few, so that its frame is in the middle of the array.
        let task = running
            .lines()
            .filter_map(|l| l.trim().strip_prefix(&format!("{id}_")).map(str::to_owned))
            .find(|t| t.parse::<usize>().is_ok_and(|n| n >= 3) && !tried.contains(t));
        if let Some(task) = task {
            tried.insert(task.clone());
            let _ = Command::new("scancel").arg(format!("{id}_{task}")).status();
            // Wait for the task to leave the queue, then see whether the cancel was in time.
            while Command::new("squeue")
                .args(["--noheader", "--jobs", &format!("{id}_{task}")])
                .output()
                .is_ok_and(|o| !String::from_utf8_lossy(&o.stdout).trim().is_empty())
            {
                std::thread::sleep(Duration::from_millis(100));
            }
            let states = task_states(&[(id.to_owned(), String::new())]);
            if states
                .get(&(id.to_owned(), task.clone()))
                .is_some_and(|(state, _)| state == "CANCELLED")
            {
                return task;
            }
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    panic!("no task of job {id} could be cancelled while it ran (tried {tried:?})");
}

#[test]
fn a_task_killed_mid_run_is_all_a_resubmission_runs_and_the_bytes_are_the_same() {
    require_cluster();
    let local = copy_pipeline("thesis-flyby");
    bin("irsig-run")
        .current_dir(local.path())
        .args(["--quiet", "thesis-flyby.ron"])
        .assert()
        .success();
    let cluster = recipe::scratch_root();
    let jobs = submit_by_recipe(cluster.path(), FLYBY_RECIPE);
    assert_eq!(jobs[1].1, "02-trace.sbatch");
    let killed = kill_one_running_task(&jobs[1].0);
    // The sheet waits for every frame, so it can never start now: it is cancelled too once
    // the other frames are done.
    wait_for(&jobs[..2]);
    let _ = Command::new("scancel").arg(&jobs[2].0).status();
    wait_for(&jobs);
    let states = task_states(&jobs);
    for ((id, task), (state, _)) in &states {
        let expected = if (*id == jobs[1].0 && *task == killed) || *id == jobs[2].0 {
            "CANCELLED"
        } else {
            "COMPLETED"
        };
        assert_eq!(state, expected, "job {id} task {task}: {states:?}");
    }
    let build = cluster.path().join("pipelines/thesis-flyby/build");
    let before = file_times(&build);

    // The resubmission, by the page's recipe: the killed frame, and the sheet after it;
    // nothing else.
    let jobs = submit_by_recipe(cluster.path(), FLYBY_AGAIN_RECIPE);
    let scripts: Vec<&str> = jobs.iter().map(|(_, s)| s.as_str()).collect();
    assert_eq!(scripts, ["01-trace.sbatch", "02-contact-sheet.sbatch"]);
    let trace = std::fs::read_to_string(cluster.path().join("slurm/01-trace.sbatch")).unwrap();
    assert!(
        trace.contains(&format!("\n#SBATCH --array={killed}\n")),
        "{trace}"
    );
    wait_for(&jobs);
    assert_all_completed(cluster.path(), &jobs);
    // Every file of another frame is the one the first submission wrote, untouched.
    let frame = format!("frame-{:02}.", killed.parse::<usize>().unwrap());
    let after = file_times(&build);
    for (name, time) in &before {
        let text = name.to_string_lossy();
        if !text.starts_with(&frame) && !text.starts_with("contact-sheet") {
            assert_eq!(after.get(name), Some(time), "{text} was written again");
        }
    }
    assert_same_files(&local.path().join("thesis-flyby/build"), &build);
}

/// A day of the thermal pipeline's scene in hourly frames: one `irsig-therm` over the whole
/// day gathering every frame's scene, then one small 8-14 um trace per frame (a built-in
/// atmosphere, no sun), each output named by the frame's UTC time.
const DAY: &str = r#"Pipeline(
    sweeps: {"day": Times(start: "2001-08-07T00:00", end: "2001-08-07T23:00", step: "PT1H",
                          zone: "America/Denver")},
    stages: [
        Stage(name: "flatten", tool: "flatten", args: ["thermal/scene.ron"],
              reads: ["thermal/ground.ron", "quickstart/box.ron"],
              inputs: {"materials": "thermal/materials.ron"}, outputs: {"o": "build/start.raw"}),
        Stage(name: "therm", tool: "therm", gather: "day", args: ["build/start.raw"],
              inputs: {"materials": "thermal/materials.ron", "weather": "golden-tmy3-aug.epw"},
              params: {"at": "{time}", "spin-up-h": 12, "step-s": 600},
              outputs: {"raw": "build/{time_utc}.raw"}),
        Stage(name: "trace", tool: "trace", sweep: "day",
              inputs: {"scene": "build/{time_utc}.raw", "materials": "thermal/materials.ron",
                       "view": "view.ron"},
              params: {"band": "8-14", "atmosphere": "us-std-1976", "atmosphere-model": "table"},
              outputs: {"radiance-exr": "build/{time_utc}.radiance.exr",
                        "truth-exr": "build/{time_utc}.truth.exr"}),
    ],
)
"#;

/// A scratch directory holding [`DAY`] as `day.ron`, the thermal pipeline's scene and the
/// quickstart's box it places, the August weather record and a 64 x 48 view of the scene.
fn day() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let pipelines = repo_root().join("pipelines");
    for data in ["thermal", "quickstart"] {
        recipe::copy_tree(&pipelines.join(data), &dir.path().join(data));
    }
    std::fs::copy(
        repo_root().join("formats/samples/golden-tmy3-aug.epw"),
        dir.path().join("golden-tmy3-aug.epw"),
    )
    .unwrap();
    std::fs::write(
        dir.path().join("view.ron"),
        "LookAt(position_m: (3.0, 26.0, 7.0), target_m: (2.0, 3.0, 0.5), pixels: (64, 48), \
         fov_deg: (47.0, 36.0))\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("day.ron"), DAY).unwrap();
    dir
}

#[test]
fn a_days_frames_run_as_an_array_after_one_thermal_job_with_irsig_runs_bytes() {
    require_cluster();
    let local = day();
    bin("irsig-run")
        .current_dir(local.path())
        .args(["--quiet", "day.ron"])
        .assert()
        .success();
    let cluster = day();
    let jobs = emit_and_submit(cluster.path(), "day.ron");
    let scripts: Vec<&str> = jobs.iter().map(|(_, s)| s.as_str()).collect();
    assert_eq!(
        scripts,
        ["01-flatten.sbatch", "02-therm.sbatch", "03-trace.sbatch"]
    );
    // The frames are an array that waits for the one thermal job, and say their times.
    let submit_sh = std::fs::read_to_string(cluster.path().join("slurm/submit.sh")).unwrap();
    assert!(
        submit_sh.contains("--dependency=afterok:$job2 "),
        "{submit_sh}"
    );
    let trace = std::fs::read_to_string(cluster.path().join("slurm/03-trace.sbatch")).unwrap();
    for line in [
        "#   task 1: 2001-08-07T00:00:00-06:00",
        "#   task 15: 2001-08-07T14:00:00-06:00",
        "#SBATCH --array=1-24",
    ] {
        assert!(trace.contains(&format!("\n{line}\n")), "{line} in {trace}");
    }
    wait_for(&jobs);
    assert_all_completed(cluster.path(), &jobs);
    let nodes = nodes_of(&jobs[2].0);
    assert!(
        nodes.len() >= 2,
        "the frames ran on one node only: {nodes:?}"
    );
    let build = cluster.path().join("build");
    // The start, and each hour's scene, radiance and truth, named by its UTC time: 14:00
    // in Denver in August is 20:00 UTC.
    assert_eq!(files(&build).len(), 1 + 24 * 3);
    assert!(build.join("20010807T200000Z.truth.exr").is_file());
    assert_same_files(&local.path().join("build"), &build);
}

/// `pipelines/quickstart-tiles.ron` with the frame traced whole: the same flatten, one trace
/// writing what the merge writes, the same sensor stage; into `out/whole/`.
const WHOLE_FRAME: &str = r#"Pipeline(stages: [
    Stage(name: "flatten", tool: "flatten", args: ["quickstart/scene.ron"],
          reads: ["quickstart/ground.ron", "quickstart/box.ron"],
          inputs: {"materials": "quickstart/materials.ron"}, outputs: {"o": "../out/whole/scene.raw"}),
    Stage(name: "trace", tool: "trace",
          inputs: {"scene": "../out/whole/scene.raw", "materials": "quickstart/materials.ron",
                   "view": "quickstart/view-1024.ron"},
          params: {"band": "8-14", "atmosphere": "us-std-1976", "atmosphere-model": "table",
                   "supersample": 2, "adaptive-supersampling": 0.25, "sky-view-rays": 4,
                   "dc-per-kelvin": 4},
          outputs: {"radiance-exr": "../out/whole/radiance.exr", "truth-exr": "../out/whole/truth.exr",
                    "map-png": "../out/whole/map.png", "dc-png": "../out/whole/dc.png",
                    "lut": "../out/whole/lut.txt"}),
    Stage(name: "sensor", tool: "sensor", args: ["../out/whole/radiance.exr"],
          params: {"mtf": "box:5x5", "dc-per-kelvin": 4},
          outputs: {"o": "../out/whole/sensor.exr", "temperature-exr": "../out/whole/temperature.exr",
                    "colour-preview": "../out/whole/colour.png"}),
])
"#;

#[test]
fn one_frame_in_16_tiles_through_the_cluster_writes_the_whole_frames_bytes() {
    require_cluster();
    let root = tempfile::tempdir().unwrap();
    let pipelines = root.path().join("pipelines");
    std::fs::create_dir(&pipelines).unwrap();
    std::fs::copy(
        repo_root().join("pipelines/quickstart-tiles.ron"),
        pipelines.join("quickstart-tiles.ron"),
    )
    .unwrap();
    recipe::copy_tree(
        &repo_root().join("pipelines/quickstart"),
        &pipelines.join("quickstart"),
    );
    std::fs::write(pipelines.join("whole.ron"), WHOLE_FRAME).unwrap();
    bin("irsig-run")
        .current_dir(&pipelines)
        .args(["--quiet", "whole.ron"])
        .assert()
        .success();

    let jobs = emit_and_submit(&pipelines, "quickstart-tiles.ron");
    let scripts: Vec<&str> = jobs.iter().map(|(_, s)| s.as_str()).collect();
    assert_eq!(
        scripts,
        [
            "01-flatten.sbatch",
            "02-trace.sbatch",
            "03-merge.sbatch",
            "04-sensor.sbatch"
        ]
    );
    let trace = std::fs::read_to_string(pipelines.join("slurm/02-trace.sbatch")).unwrap();
    assert!(trace.contains("\n#SBATCH --array=1-16\n"), "{trace}");
    let submit_sh = std::fs::read_to_string(pipelines.join("slurm/submit.sh")).unwrap();
    // The merge waits for every tile, the sensor stage for the merge.
    assert!(
        submit_sh.contains("--dependency=afterok:$job2 "),
        "{submit_sh}"
    );
    assert!(
        submit_sh.contains("--dependency=afterok:$job3 "),
        "{submit_sh}"
    );
    wait_for(&jobs);
    assert_all_completed(&pipelines, &jobs);
    let states = task_states(&jobs);
    let tile_tasks = states.keys().filter(|(id, _)| *id == jobs[1].0).count();
    assert_eq!(tile_tasks, 16, "one task per tile: {states:?}");

    let (whole, tiled) = (
        root.path().join("out/whole"),
        root.path().join("out/quickstart-tiles"),
    );
    let mut names = files(&tiled);
    names.retain(|n| n != Path::new("tiles"));
    assert_eq!(names, files(&whole));
    for name in &names {
        let (a, b) = (
            std::fs::read(whole.join(name)).unwrap(),
            std::fs::read(tiled.join(name)).unwrap(),
        );
        assert!(a == b, "{} differs from the whole frame's", name.display());
    }
    // The scene, 5 frame files, 3 sensor files; 16 tiles of 2 files.
    assert_eq!(names.len(), 1 + 5 + 3);
    assert_eq!(files(&tiled.join("tiles")).len(), 32);
}

/// Frames 1-3 of `a` (each reading its own input), `b` per frame of `a`, and a sheet of all
/// `b`s; every run of testcat logs its output's name to `log.txt`.
const CHAIN: &str = r#"Pipeline(
    sweeps: {"f": Frames([{"n": "1"}, {"n": "2"}, {"n": "3"}])},
    stages: [
        Stage(name: "a", tool: "testcat", sweep: "f", args: ["in-{n}.txt"],
              params: {"prefix": "a{frame}:", "log": "log.txt"}, outputs: {"o": "build/a-{frame}.txt"}),
        Stage(name: "b", tool: "testcat", sweep: "f", args: ["build/a-{frame}.txt"],
              params: {"upper": true, "log": "log.txt"}, outputs: {"o": "build/b-{frame}.txt"},
              slurm: (memory_mib: 50)),
        Stage(name: "sheet", tool: "testcat", gather: "f", args: ["build/b-{frame}.txt"],
              params: {"log": "log.txt"}, outputs: {"o": "build/sheet.txt"}),
    ],
)
"#;

fn chain() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("chain.ron"), CHAIN).unwrap();
    for n in 1..=3 {
        std::fs::write(dir.path().join(format!("in-{n}.txt")), format!("in {n}\n")).unwrap();
    }
    dir
}

/// How often each output was written, from testcat's log.
fn runs(dir: &Path) -> BTreeMap<String, usize> {
    let mut counts = BTreeMap::new();
    for line in std::fs::read_to_string(dir.join("log.txt"))
        .unwrap_or_default()
        .lines()
    {
        *counts.entry(line.to_owned()).or_default() += 1;
    }
    counts
}

#[test]
fn a_failed_frame_is_all_a_resubmission_runs_again() {
    require_cluster();
    let dir = chain();
    bin("irsig-run")
        .current_dir(dir.path())
        .args(["--emit-slurm", "slurm", "chain.ron"])
        .assert()
        .success();
    let submit_sh = std::fs::read_to_string(dir.path().join("slurm/submit.sh")).unwrap();
    assert!(
        submit_sh.contains("--dependency=aftercorr:$job1 "),
        "{submit_sh}"
    );
    assert!(
        submit_sh.contains("--dependency=afterok:$job2 "),
        "{submit_sh}"
    );
    // Frame 2's input vanishes between emission and the task: a[2] fails, so b[2] (which
    // waits for it alone) and the sheet (which waits for every b) never run; b[1] and b[3]
    // do not wait for a[2].
    std::fs::remove_file(dir.path().join("in-2.txt")).unwrap();
    let jobs = submit(dir.path());
    wait_for(&jobs);
    let states = task_states(&jobs);
    let state = |job: usize, task: &str| states[&(jobs[job].0.clone(), task.to_owned())].0.clone();
    let got = [
        state(0, "1"),
        state(0, "2"),
        state(0, "3"),
        state(1, "1"),
        state(1, "2"),
        state(1, "3"),
        state(2, "-"),
    ];
    assert_eq!(
        got.iter().map(String::as_str).collect::<Vec<_>>(),
        [
            "COMPLETED",
            "FAILED",
            "COMPLETED",
            "COMPLETED",
            "CANCELLED",
            "COMPLETED",
            "CANCELLED"
        ],
        "{states:?}\n{}",
        logs(dir.path())
    );
    let failed_log =
        std::fs::read_to_string(dir.path().join(format!("slurm/logs/a-{}_2.out", jobs[0].0)))
            .unwrap();
    assert!(
        failed_log.contains("stage `a[2]` cannot run"),
        "{failed_log}"
    );

    // The input is back: the next submission is frame 2 of a and b, and the sheet.
    std::fs::write(dir.path().join("in-2.txt"), "in 2\n").unwrap();
    let jobs = emit_and_submit(dir.path(), "chain.ron");
    let scripts: Vec<&str> = jobs.iter().map(|(_, s)| s.as_str()).collect();
    assert_eq!(scripts, ["01-a.sbatch", "02-b.sbatch", "03-sheet.sbatch"]);
    for script in ["01-a.sbatch", "02-b.sbatch"] {
        let text = std::fs::read_to_string(dir.path().join("slurm").join(script)).unwrap();
        assert!(text.contains("\n#SBATCH --array=2\n"), "{text}");
    }
    wait_for(&jobs);
    assert_all_completed(dir.path(), &jobs);
    let once = |name: &str| (format!("build/{name}.txt"), 1);
    assert_eq!(
        runs(dir.path()),
        BTreeMap::from([
            once("a-1"),
            once("a-2"),
            once("a-3"),
            once("b-1"),
            once("b-2"),
            once("b-3"),
            once("sheet"),
        ])
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("build/sheet.txt")).unwrap(),
        "A1:IN 1\nA2:IN 2\nA3:IN 3\n"
    );
}

#[test]
fn memory_beyond_the_largest_node_is_refused_at_its_line_and_column() {
    require_cluster();
    let dir = chain();
    let text = CHAIN.replace("memory_mib: 50", "memory_mib: 1048576");
    std::fs::write(dir.path().join("chain.ron"), &text).unwrap();
    let line = text[..text.find("1048576").unwrap()].matches('\n').count() + 1;
    bin("irsig-run")
        .current_dir(dir.path())
        .args(["--emit-slurm", "slurm", "chain.ron"])
        .assert()
        .code(1)
        .stderr(
            predicate::str::contains(format!("chain.ron:{line}:"))
                .and(predicate::str::contains("asks for 1048576 MiB per task"))
                .and(predicate::str::contains("sinfo")),
        );
    assert!(
        !dir.path().join("slurm/submit.sh").exists(),
        "no scripts written"
    );
}

#[test]
fn submit_without_sbatch_on_path_says_so() {
    let dir = chain();
    let empty = tempfile::tempdir().unwrap();
    bin("irsig-run")
        .current_dir(dir.path())
        .env("PATH", empty.path())
        .args(["--emit-slurm", "slurm", "chain.ron"])
        .assert()
        .success()
        .stderr(predicate::str::contains("sinfo is not on PATH"));
    let out = Command::new("/bin/sh")
        .arg("slurm/submit.sh")
        .current_dir(dir.path())
        .env("PATH", empty.path())
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("sbatch is not on PATH"), "{stderr}");
    assert!(out.stdout.is_empty());
}

#[test]
fn one_step_runs_alone_and_concurrent_runners_keep_every_record() {
    let dir = chain();
    let run = |args: &[&str]| {
        let mut cmd = bin("irsig-run");
        cmd.current_dir(dir.path()).args(args).arg("chain.ron");
        cmd.assert()
    };
    // b[1] needs a[1]'s output, which does not exist yet.
    run(&["--step", "b[1]"])
        .code(1)
        .stderr(predicate::str::contains("build/a-1.txt"));
    run(&["--step", "a[9]"]).code(1).stderr(
        predicate::str::contains("no step named `a[9]`")
            .and(predicate::str::contains("a[1], a[2], a[3]")),
    );
    // The three frames of a, as three runners at once (as three Slurm tasks would).
    let program = bin_path("irsig-run");
    let children: Vec<_> = (1..=3)
        .map(|n| {
            Command::new(&program)
                .current_dir(dir.path())
                .args(["--quiet", "--step", &format!("a[{n}]"), "chain.ron"])
                .spawn()
                .unwrap()
        })
        .collect();
    for mut c in children {
        assert!(c.wait().unwrap().success());
    }
    run(&["--step", "a[2]"])
        .success()
        .stderr(predicate::str::contains("0 stage(s) ran, 1 up to date"));
    // Every runner's record survived: the whole run finds a up to date.
    run(&[])
        .success()
        .stderr(predicate::str::contains("4 stage(s) ran, 3 up to date"));
    assert_eq!(runs(dir.path()).values().sum::<usize>(), 7);
    // Another frame's missing input is that frame's problem, not this step's.
    std::fs::remove_file(dir.path().join("in-2.txt")).unwrap();
    run(&["--step", "a[1]", "--force"])
        .success()
        .stderr(predicate::str::contains("1 stage(s) ran"));
    run(&["--step", "a[2]", "--force"])
        .code(1)
        .stderr(predicate::str::contains("its input `in-2.txt` is missing"));
}
