//! Running a plan: the up-to-date check by content hash, the run state file, and parallel
//! execution of the steps in dependency order.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::mpsc;

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::error::{ErrorKind, PipelineError};
use crate::plan::Plan;
use crate::step::Step;

/// How to run a plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunOptions {
    /// At most this many tools at once (at least 1).
    pub jobs: usize,
    /// Run every step, up to date or not.
    pub force: bool,
}

/// What the runner is doing, for the caller to report (the library prints nothing).
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum Event<'a> {
    /// The step's outputs match its inputs, parameters and tool: it is skipped.
    UpToDate(&'a Step),
    /// The step's tool is being started.
    Started(&'a Step),
    /// The step's tool finished and wrote its outputs.
    Finished(&'a Step),
}

/// How many steps ran and how many were skipped as up to date.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RunSummary {
    /// Steps whose tool ran.
    pub ran: usize,
    /// Steps skipped because their outputs were up to date.
    pub up_to_date: usize,
}

/// What the runner remembers about a step's last successful run.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
struct Record {
    /// SHA-256 of the tool program, the command line and every input's path and content.
    recipe_sha256: String,
    /// SHA-256 of every output's path and content just after the run.
    outputs_sha256: String,
}

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
struct State {
    steps: BTreeMap<String, Record>,
}

/// The run state as a runner last read or wrote it, and the state file's stamp then. For a
/// pipeline of thousands of steps the file is hundreds of kilobytes: a runner that finds it
/// as it left it does not parse it again before adding a record.
#[derive(Debug, Default)]
struct StateCache {
    state: State,
    seen: Option<Stamp>,
}

/// What tells one version of the state file from another: its size, modification time and,
/// on Unix, inode and change time (every save renames a new file into place, so a file
/// another runner saved is a new inode even within the clock's granularity).
type Stamp = (u64, Option<std::time::SystemTime>, u64, i64);

fn stamp(path: &Path) -> Option<Stamp> {
    let m = std::fs::metadata(path).ok()?;
    #[cfg(unix)]
    let (inode, changed) = {
        use std::os::unix::fs::MetadataExt;
        (m.ino(), m.ctime_nsec() + 1_000_000_000 * m.ctime())
    };
    #[cfg(not(unix))]
    let (inode, changed) = (0, 0);
    Some((m.len(), m.modified().ok(), inode, changed))
}

impl Plan {
    /// Where the run state lives: `.irsig-run/<pipeline file stem>.state.ron` in the
    /// pipeline's directory.
    #[must_use]
    pub fn state_path(&self) -> PathBuf {
        let stem = Path::new(&self.file)
            .file_stem()
            .map_or_else(|| "pipeline".into(), |s| s.to_string_lossy().into_owned());
        self.base_dir
            .join(".irsig-run")
            .join(format!("{stem}.state.ron"))
    }

    /// A missing or unreadable state file means nothing is known to be up to date: the state
    /// is a cache, and the worst a lost one costs is a re-run.
    fn load_state(&self) -> State {
        let path = self.state_path();
        irsig_formats::file::read_file(&path)
            .ok()
            .and_then(|bytes| {
                let file = path.display().to_string();
                let text = String::from_utf8(bytes).ok()?;
                irsig_formats::canonical::from_ron_as(&file, &text, "run state").ok()
            })
            .unwrap_or_default()
    }

    /// Where runners that share a pipeline's state take turns: `.irsig-run/<stem>.state.lock`.
    fn lock_path(&self) -> PathBuf {
        self.state_path().with_extension("lock")
    }

    /// The state file as it is now, with its stamp taken first (so a change while it is read
    /// shows as a changed stamp later, and costs a re-read, never a lost record).
    fn load_cached(&self) -> StateCache {
        let seen = stamp(&self.state_path());
        StateCache {
            state: self.load_state(),
            seen,
        }
    }

    /// Records a step's successful run in the state file. Several runners may finish steps of
    /// one pipeline at once (the tasks of a Slurm job array, each an `irsig-run --step`), so
    /// the file is rewritten under an exclusive lock on `.irsig-run/<stem>.state.lock`, from
    /// its current contents: every runner's record survives, whichever writes last. The file
    /// is parsed again only when another runner has replaced it since `cache` saw it.
    fn record(
        &self,
        cache: &mut StateCache,
        step: &Step,
        record: Record,
    ) -> Result<(), PipelineError> {
        let path = self.lock_path();
        let io = |e| PipelineError::io(format!("cannot lock run state `{}`", path.display()), e);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(io)?;
        }
        let lock = std::fs::OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&path)
            .map_err(io)?;
        fs4::FileExt::lock(&lock).map_err(io)?;
        let state_path = self.state_path();
        if stamp(&state_path) != cache.seen {
            *cache = self.load_cached();
        }
        cache.state.steps.insert(step.name.clone(), record);
        self.save_state(&cache.state)?;
        cache.seen = stamp(&state_path);
        // The lock is released when `lock` is closed, after the new state is in place.
        Ok(())
    }

    fn save_state(&self, state: &State) -> Result<(), PipelineError> {
        let path = self.state_path();
        let io = |e| PipelineError::io(format!("cannot write run state `{}`", path.display()), e);
        let text = irsig_formats::canonical::to_ron_pretty(state)
            .map_err(|e| io(std::io::Error::other(e.to_string())))?;
        let dir = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        std::fs::create_dir_all(&dir).map_err(io)?;
        let tmp = dir.join(format!(
            ".{}.tmp",
            path.file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
        ));
        std::fs::write(&tmp, text).map_err(io)?;
        std::fs::rename(&tmp, &path).map_err(io)
    }

    fn tool_hashes(&self) -> Result<BTreeMap<PathBuf, String>, PipelineError> {
        let programs: BTreeSet<&PathBuf> = self.steps.iter().map(|s| &s.program).collect();
        programs
            .into_iter()
            .map(|p| {
                let bytes = irsig_formats::file::read_file(p).map_err(|e| {
                    PipelineError::io(format!("cannot read tool program `{}`", p.display()), e)
                })?;
                Ok((p.clone(), hex(&Sha256::digest(bytes))))
            })
            .collect()
    }

    /// The recipe hash of a step, or `None` when an input does not exist (yet).
    fn recipe(&self, step: &Step, tool_sha256: &str) -> Option<String> {
        let mut h = Sha256::new();
        h.update(tool_sha256.as_bytes());
        for word in &step.argv {
            h.update((word.len() as u64).to_le_bytes());
            h.update(word.as_bytes());
        }
        for input in &step.inputs {
            let bytes = irsig_formats::file::read_file(&self.base_dir.join(&input.path)).ok()?;
            h.update(Sha256::digest(bytes));
        }
        Some(hex(&h.finalize()))
    }

    /// The hash of the step's outputs as they are now, or `None` when one is missing.
    fn outputs_hash(&self, step: &Step) -> Option<String> {
        let mut h = Sha256::new();
        for out in &step.outputs {
            let bytes = irsig_formats::file::read_file(&self.base_dir.join(&out.path)).ok()?;
            let name = out.path.to_string_lossy();
            h.update((name.len() as u64).to_le_bytes());
            h.update(name.as_bytes());
            h.update(Sha256::digest(bytes));
        }
        Some(hex(&h.finalize()))
    }

    /// A step is up to date when the last run with the same tool, command line and input
    /// contents left outputs that are still there, unchanged. A step without outputs is
    /// never up to date (it exists for what it prints).
    fn is_up_to_date(&self, step: &Step, recipe: Option<&str>, record: Option<&Record>) -> bool {
        let (Some(recipe), Some(record)) = (recipe, record) else {
            return false;
        };
        !step.outputs.is_empty()
            && record.recipe_sha256 == recipe
            && self.outputs_hash(step).as_deref() == Some(record.outputs_sha256.as_str())
    }

    /// Every step in order, each with whether a run would start it, without running
    /// anything: a run starts those not up to date and those downstream of them (all of
    /// them with `force`); `false` marks a step a run would skip as up to date.
    ///
    /// # Errors
    /// A tool program that cannot be read for hashing.
    pub fn dry_run(&self, force: bool) -> Result<Vec<(&Step, bool)>, PipelineError> {
        let tools = self.tool_hashes()?;
        let state = self.load_state();
        let mut would_run = vec![false; self.steps.len()];
        for (i, step) in self.steps.iter().enumerate() {
            would_run[i] = force
                || step.deps.iter().any(|&d| would_run[d])
                || !self.is_up_to_date(
                    step,
                    tools
                        .get(&step.program)
                        .and_then(|t| self.recipe(step, t))
                        .as_deref(),
                    state.steps.get(&step.name),
                );
        }
        Ok(self.steps.iter().zip(would_run).collect())
    }

    /// Runs the plan: each step when its producers are done, up to `jobs` at a time,
    /// skipping those up to date. After the first failure no new step starts; those
    /// running finish, and the failure is returned. The state is saved after every step,
    /// so an interrupted run keeps what it finished.
    ///
    /// # Errors
    /// [`ErrorKind::StageFailed`] for a tool that cannot start, fails, or does not write a
    /// declared output; [`ErrorKind::Io`] for the run state.
    pub fn run(
        &self,
        options: RunOptions,
        on_event: &(dyn Fn(Event<'_>) + Sync),
    ) -> Result<RunSummary, PipelineError> {
        let tools = self.tool_hashes()?;
        let mut cache = self.load_cached();
        let n = self.steps.len();
        let mut waiting: Vec<usize> = self.steps.iter().map(|s| s.deps.len()).collect();
        let mut dependents = vec![Vec::new(); n];
        for (i, s) in self.steps.iter().enumerate() {
            for &d in &s.deps {
                dependents[d].push(i);
            }
        }
        let mut ready: BTreeSet<usize> = (0..n).filter(|&i| waiting[i] == 0).collect();
        let mut summary = RunSummary::default();
        let mut failure = None;
        let (tx, rx) = mpsc::channel();
        std::thread::scope(|scope| {
            let mut running = 0usize;
            loop {
                while failure.is_none() && running < options.jobs.max(1) {
                    let Some(i) = ready.pop_first() else { break };
                    let step = &self.steps[i];
                    let record = cache.state.steps.get(&step.name).cloned();
                    let tool = tools.get(&step.program).cloned().unwrap_or_default();
                    let tx = tx.clone();
                    running += 1;
                    scope.spawn(move || {
                        let how = StepRun {
                            force: options.force,
                            // Stages side by side: each line a stage writes on stderr says
                            // which stage it is.
                            name_lines: options.jobs > 1,
                        };
                        let outcome = self.run_step(step, &tool, record.as_ref(), how, on_event);
                        // The receiver outlives every worker inside this scope.
                        let _ = tx.send((i, outcome));
                    });
                }
                if running == 0 {
                    break;
                }
                let Ok((i, outcome)) = rx.recv() else { break };
                running -= 1;
                match outcome {
                    Ok(None) => summary.up_to_date += 1,
                    Ok(Some(record)) => {
                        summary.ran += 1;
                        if let Err(e) = self.record(&mut cache, &self.steps[i], record) {
                            failure.get_or_insert(e);
                        }
                    }
                    Err(e) => {
                        failure.get_or_insert(e);
                    }
                }
                if failure.is_none() {
                    for &d in &dependents[i] {
                        waiting[d] -= 1;
                        if waiting[d] == 0 {
                            ready.insert(d);
                        }
                    }
                }
            }
        });
        match failure {
            Some(e) => Err(e),
            None => Ok(summary),
        }
    }

    /// Runs the one step named `name` (`trace[3]` for frame 3 of the stage `trace`) unless
    /// it is up to date, and records it in the run state: what a task of a Slurm job array
    /// does. Its inputs must exist; the steps before it are not run.
    ///
    /// # Errors
    /// [`ErrorKind::UnknownStep`] when the plan has no step of that name; otherwise as
    /// [`Plan::run`].
    pub fn run_step_named(
        &self,
        name: &str,
        force: bool,
        on_event: &(dyn Fn(Event<'_>) + Sync),
    ) -> Result<RunSummary, PipelineError> {
        let Some(step) = self.steps.iter().find(|s| s.name == name) else {
            const SHOWN: usize = 12;
            let names: Vec<&str> = self.steps.iter().map(|s| s.name.as_str()).collect();
            let mut listed = names[..names.len().min(SHOWN)].join(", ");
            if names.len() > SHOWN {
                listed.push_str(&format!(", ... ({} more)", names.len() - SHOWN));
            }
            return Err(PipelineError::plain(
                ErrorKind::UnknownStep,
                format!(
                    "`{}` has no step named `{name}`; its steps are: {listed}",
                    self.file
                ),
            ));
        };
        let bytes = irsig_formats::file::read_file(&step.program).map_err(|e| {
            PipelineError::io(
                format!("cannot read tool program `{}`", step.program.display()),
                e,
            )
        })?;
        let tool = hex(&Sha256::digest(bytes));
        let mut cache = self.load_cached();
        let record = cache.state.steps.get(&step.name).cloned();
        let how = StepRun {
            force,
            name_lines: false,
        };
        match self.run_step(step, &tool, record.as_ref(), how, on_event)? {
            None => Ok(RunSummary {
                ran: 0,
                up_to_date: 1,
            }),
            Some(record) => {
                self.record(&mut cache, step, record)?;
                Ok(RunSummary {
                    ran: 1,
                    up_to_date: 0,
                })
            }
        }
    }

    /// Runs one step unless it is up to date. `Ok(None)`: skipped; `Ok(Some(record))`: ran.
    fn run_step(
        &self,
        step: &Step,
        tool_sha256: &str,
        record: Option<&Record>,
        how: StepRun,
        on_event: &(dyn Fn(Event<'_>) + Sync),
    ) -> Result<Option<Record>, PipelineError> {
        let force = how.force;
        let Some(recipe) = self.recipe(step, tool_sha256) else {
            let missing = step
                .inputs
                .iter()
                .find(|i| !self.base_dir.join(&i.path).is_file());
            let message = format!(
                "stage `{}` cannot run: its input `{}` is missing",
                step.described(),
                missing.map_or_else(String::new, |m| m.path.display().to_string())
            );
            return Err(match missing {
                Some(m) => self.file_error(m, ErrorKind::StageFailed, message),
                None => self.step_error(step, ErrorKind::StageFailed, message),
            });
        };
        if !force && self.is_up_to_date(step, Some(&recipe), record) {
            on_event(Event::UpToDate(step));
            return Ok(None);
        }
        for out in &step.outputs {
            if let Some(dir) = self.base_dir.join(&out.path).parent() {
                std::fs::create_dir_all(dir).map_err(|e| {
                    PipelineError::io(format!("cannot create directory `{}`", dir.display()), e)
                })?;
            }
        }
        on_event(Event::Started(step));
        let mut command = Command::new(&step.program);
        command
            .args(step.argv.iter().skip(1))
            .current_dir(&self.base_dir);
        let status = if how.name_lines {
            status_naming_lines(&mut command, &step.name)
        } else {
            command.status()
        }
        .map_err(|e| {
            self.step_error(
                step,
                ErrorKind::StageFailed,
                format!(
                    "stage `{}`: cannot start `{}`: {e}",
                    step.described(),
                    step.program.display()
                ),
            )
        })?;
        if !status.success() {
            let how = status.code().map_or_else(
                || "was killed by a signal".to_owned(),
                |c| format!("exited with code {c}"),
            );
            return Err(self.step_error(
                step,
                ErrorKind::StageFailed,
                format!(
                    "stage `{}` failed: `{}` {how}",
                    step.described(),
                    step.command_line()
                ),
            ));
        }
        let Some(outputs_sha256) = self.outputs_hash(step) else {
            let missing = step
                .outputs
                .iter()
                .find(|o| !self.base_dir.join(&o.path).is_file());
            let message = format!(
                "stage `{}` succeeded but did not write its output `{}`",
                step.described(),
                missing.map_or_else(String::new, |m| m.path.display().to_string())
            );
            return Err(match missing {
                Some(m) => self.file_error(m, ErrorKind::StageFailed, message),
                None => self.step_error(step, ErrorKind::StageFailed, message),
            });
        };
        on_event(Event::Finished(step));
        Ok(Some(Record {
            recipe_sha256: recipe,
            outputs_sha256,
        }))
    }
}

fn hex(bytes: &[u8]) -> String {
    use std::fmt::Write;
    bytes
        .iter()
        .fold(String::with_capacity(bytes.len() * 2), |mut s, b| {
            let _ = write!(s, "{b:02x}");
            s
        })
}

/// How one step is run.
#[derive(Debug, Clone, Copy)]
struct StepRun {
    /// Run it even when it is up to date.
    force: bool,
    /// Begin each line its tool writes on stderr with `[STEP] `: steps run side by side,
    /// and a warning must say which one it is from. The tool's stderr is then a pipe, not
    /// the terminal, so it shows no progress bar (bars of parallel steps would overwrite
    /// each other).
    name_lines: bool,
}

/// Runs `command` with its stderr copied line by line to ours, each line begun with
/// `[name] ` and written whole, so that lines of steps run side by side never interleave
/// within a line. A line that is not UTF-8 is copied as its bytes.
fn status_naming_lines(
    command: &mut Command,
    name: &str,
) -> std::io::Result<std::process::ExitStatus> {
    use std::io::{BufRead as _, Write as _};
    let mut child = command.stderr(std::process::Stdio::piped()).spawn()?;
    if let Some(stderr) = child.stderr.take() {
        let prefix = format!("[{name}] ");
        // A read error ends the copying, never the wait: the child is always reaped.
        for line in std::io::BufReader::new(stderr)
            .split(b'\n')
            .map_while(Result::ok)
        {
            let mut out = std::io::stderr().lock();
            // Our stderr gone (a closed pipe) must not stop the step: its lines are lost.
            let _ = out
                .write_all(prefix.as_bytes())
                .and_then(|()| out.write_all(&line))
                .and_then(|()| out.write_all(b"\n"));
        }
    }
    child.wait()
}
