//! The Slurm back end: the same plan as batch scripts, one job per stage, a job array for a
//! swept stage (task `i` is frame `i`), each job submitted after the jobs whose outputs it
//! reads (`--dependency`). Every task runs its step through `irsig-run --step`, so it is
//! skipped when up to date by the same content-hash rule as a local run, and its record
//! lands in the same run state.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;
use std::path::PathBuf;

use irsig_formats::ron_tree::{Kind, Node};

use crate::emit::{comment_text, file_name};
use crate::error::{ErrorKind, PipelineError};
use crate::plan::Plan;
use crate::spec::{self, Source, Spanned};
use crate::step::Step;

/// Memory asked for a task whose stage does not say: a floor for the process, its tables
/// and a frame of up to 256 × 256 pixels (irsig-trace, the thesis fly-by frame: 17 MiB peak).
pub const MEMORY_FLOOR_MIB: u64 = 64;

/// Bytes of memory asked per byte of input, on top of the floor. irsig-trace holds about
/// 10.5 bytes per byte of raw scene at its peak (a 1M-triangle, 40 MB raw scene: 410 MiB,
/// BVH build included); 12 leaves a margin.
pub const MEMORY_PER_INPUT_BYTE: u64 = 12;

/// What a stage's tasks ask Slurm for, from its `slurm: (...)` field.
#[derive(Debug, Clone, Default)]
pub(crate) struct Resources {
    /// CPUs per task (`--cpus-per-task`).
    cpus: Option<Spanned<u64>>,
    /// Memory per task, MiB (`--mem`).
    memory_mib: Option<Spanned<u64>>,
    /// Wall-time limit per task, minutes (`--time`).
    time_limit_min: Option<Spanned<u64>>,
}

const CPUS_MAX: u64 = 4096;
/// 1 PiB, in MiB: more than any node declares, small enough to be a typo's bound.
const MEMORY_MAX_MIB: u64 = 1 << 30;
/// Ten years, in minutes.
const TIME_MAX_MIN: u64 = 10 * 365 * 24 * 60;

/// Parses a stage's `slurm: (cpus: N, memory_mib: N, time_limit_min: N)` field.
pub(crate) fn resources(src: Source<'_>, node: &Node) -> Result<Resources, PipelineError> {
    let fields = spec::fields_of(
        src,
        node,
        "Slurm",
        &["cpus", "memory_mib", "time_limit_min"],
    )?;
    let whole = |name: &str, max: u64, what: &str| -> Result<Option<Spanned<u64>>, PipelineError> {
        let Some(n) = fields.get(name) else {
            return Ok(None);
        };
        let value = match &n.kind {
            Kind::Number(text) => text.replace('_', "").parse::<u64>().ok(),
            _ => None,
        }
        .filter(|v| (1..=max).contains(v))
        .ok_or_else(|| {
            src.error(
                ErrorKind::Structure,
                n.start,
                n.end,
                format!("expected `{name}` to be {what}, a whole number from 1 to {max}"),
            )
        })?;
        Ok(Some(Spanned {
            value,
            start: n.start,
            end: n.end,
        }))
    };
    Ok(Resources {
        cpus: whole("cpus", CPUS_MAX, "the CPUs each task uses")?,
        memory_mib: whole(
            "memory_mib",
            MEMORY_MAX_MIB,
            "the memory of each task in MiB",
        )?,
        time_limit_min: whole(
            "time_limit_min",
            TIME_MAX_MIN,
            "each task's time limit in minutes",
        )?,
    })
}

/// The largest node a job may land on, as the cluster declares it (`sinfo`), to refuse at
/// emission a request no node can satisfy, which Slurm would otherwise refuse at submission.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NodeLimits {
    /// The most CPUs of any node.
    pub cpus: u64,
    /// The most memory of any node, MiB (`RealMemory`).
    pub memory_mib: u64,
    /// Where these figures come from, for messages: `sinfo, partition "batch"`.
    pub source: String,
}

/// How to write the Slurm scripts of a plan.
#[derive(Debug, Clone)]
pub struct SlurmOptions {
    /// The pipeline file, absolute: the jobs run `irsig-run --step NAME` on it.
    pub pipeline: PathBuf,
    /// The directory the scripts are written to, absolute; job logs go to `logs/` in it.
    pub script_dir: PathBuf,
    /// The `irsig-run` program the jobs run, absolute (it finds the stage tools beside
    /// itself, as on the command line).
    pub runner: PathBuf,
    /// `--partition` of every job, when given.
    pub partition: Option<String>,
    /// Further `#SBATCH` options for every job, such as `--account=proj42`.
    pub sbatch: Vec<String>,
    /// Shell lines every job runs before its step, such as `module load irsig`.
    pub setup: Vec<String>,
    /// The cluster's largest node, when known; requests beyond it are errors.
    pub node: Option<NodeLimits>,
    /// Submit every step, not only those out of date.
    pub force: bool,
}

/// The scripts for one submission, to be written into [`SlurmOptions::script_dir`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SlurmScripts {
    /// `(file name, text)`: one `NN-<stage>.sbatch` per job, then `submit.sh`.
    pub files: Vec<(String, String)>,
    /// The jobs, in submission order.
    pub jobs: Vec<SlurmJob>,
}

/// One job of a submission: a stage, or the out-of-date frames of a swept stage.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SlurmJob {
    /// The job script's file name.
    pub script: String,
    /// The stage's name.
    pub stage: String,
    /// `--array` (frame numbers such as `1-4,7`) for a swept stage.
    pub array: Option<String>,
    /// How many steps (tasks) the job runs.
    pub tasks: usize,
    /// CPUs per task.
    pub cpus: u64,
    /// Memory per task, MiB.
    pub memory_mib: u64,
    /// Whether `memory_mib` is the estimate rather than the pipeline's own figure.
    pub memory_estimated: bool,
    /// The `--dependency` on earlier jobs, with their indices in [`SlurmScripts::jobs`]:
    /// `afterok` (all of the earlier job) or `aftercorr` (task `i` after task `i`).
    pub after: Vec<(Dependency, usize)>,
}

/// How a job waits for an earlier one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dependency {
    /// After every task of the earlier job succeeded.
    AfterOk,
    /// Task `i` after task `i` of the earlier job succeeded (two arrays over one sweep, each
    /// frame reading only its own frame's outputs).
    AfterCorr,
}

impl Dependency {
    fn keyword(self) -> &'static str {
        match self {
            Dependency::AfterOk => "afterok",
            Dependency::AfterCorr => "aftercorr",
        }
    }
}

impl Plan {
    /// Slurm batch scripts that do what [`Plan::run`] does, on a cluster: one job per stage
    /// with steps out of date (all stages with [`SlurmOptions::force`]), a job array for a
    /// swept stage whose tasks are its out-of-date frames, each job depending on the jobs
    /// that write its inputs; and `submit.sh`, which submits them in order.
    ///
    /// # Errors
    /// [`ErrorKind::ExceedsNode`] for a stage asking more CPUs or memory than
    /// [`SlurmOptions::node`] declares, located at the request (or at the stage, for an
    /// estimate); [`ErrorKind::Structure`] for a partition or `#SBATCH` option that cannot
    /// be written into a script; a tool program that cannot be read for hashing.
    pub fn slurm(&self, options: &SlurmOptions) -> Result<SlurmScripts, PipelineError> {
        check_options(options)?;
        let pending: BTreeSet<&str> = self
            .dry_run(options.force)?
            .into_iter()
            .filter_map(|(s, runs)| runs.then_some(s.name.as_str()))
            .collect();
        // Stages in the order of their first pending step: producers come first.
        let mut stage_order: Vec<usize> = Vec::new();
        let mut steps_of: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for (i, step) in self.steps.iter().enumerate() {
            if !pending.contains(step.name.as_str()) {
                continue;
            }
            if !steps_of.contains_key(&step.stage) {
                stage_order.push(step.stage);
            }
            steps_of.entry(step.stage).or_default().push(i);
        }
        let job_of_stage: BTreeMap<usize, usize> = stage_order
            .iter()
            .enumerate()
            .map(|(job, &stage)| (stage, job))
            .collect();
        let width = stage_order.len().to_string().len().max(2);
        let mut memo = vec![None; self.steps.len()];
        let mut jobs = Vec::new();
        for (job_index, &stage) in stage_order.iter().enumerate() {
            let steps = &steps_of[&stage];
            let spec = &self.stages[stage];
            let name = self.stage_name(stage);
            let resources = spec.slurm.clone().unwrap_or_default();
            let cpus = resources.cpus.as_ref().map_or(1, |c| c.value);
            let (memory_mib, memory_estimated) = match &resources.memory_mib {
                Some(m) => (m.value, false),
                None => {
                    let bytes = steps
                        .iter()
                        .map(|&i| self.input_bytes(i, &mut memo))
                        .max()
                        .unwrap_or(0);
                    (estimate_memory_mib(bytes), true)
                }
            };
            if let Some(node) = &options.node {
                self.check_node(node, spec, &resources, &name, cpus, memory_mib)?;
            }
            let swept = spec.sweep.is_some();
            let array = swept.then(|| {
                array_spec(
                    &steps
                        .iter()
                        .filter_map(|&i| self.steps[i].frame)
                        .collect::<Vec<_>>(),
                )
            });
            let after = self.dependencies(steps, &steps_of, &job_of_stage, job_index);
            jobs.push(SlurmJob {
                script: format!("{:0width$}-{}.sbatch", job_index + 1, file_word(&name)),
                stage: name,
                array,
                tasks: steps.len(),
                cpus,
                memory_mib,
                memory_estimated,
                after,
            });
        }
        let mut files = Vec::new();
        for (job, &stage) in jobs.iter().zip(&stage_order) {
            let spec = &self.stages[stage];
            let time = spec
                .slurm
                .as_ref()
                .and_then(|r| r.time_limit_min.as_ref())
                .map(|t| t.value);
            files.push((
                job.script.clone(),
                self.job_script(job, (stage, &steps_of[&stage]), time, options)?,
            ));
        }
        files.push(("submit.sh".to_owned(), self.submit_script(&jobs, options)?));
        Ok(SlurmScripts { files, jobs })
    }

    /// The stage's name as steps carry it: its `name`, or `<tool>#<n>`.
    fn stage_name(&self, stage: usize) -> String {
        let spec = &self.stages[stage];
        spec.name.as_ref().map_or_else(
            || {
                let tool = spec
                    .tool
                    .value
                    .split_whitespace()
                    .next()
                    .unwrap_or_default();
                format!("{tool}#{}", stage + 1)
            },
            |n| n.value.clone(),
        )
    }

    /// The bytes a step reads: each input's size on disk, or, for an input not written yet,
    /// what its producer reads (a stand-in for the size of what it will write).
    fn input_bytes(&self, step: usize, memo: &mut Vec<Option<u64>>) -> u64 {
        if let Some(b) = memo[step] {
            return b;
        }
        let mut total = 0u64;
        for input in &self.steps[step].inputs {
            let size = std::fs::metadata(self.base_dir.join(&input.path)).map(|m| m.len());
            total = total.saturating_add(match size {
                Ok(len) => len,
                Err(_) => self.steps[step]
                    .deps
                    .iter()
                    .copied()
                    .find(|&d| self.steps[d].outputs.iter().any(|o| o.key == input.key))
                    .map_or(0, |d| self.input_bytes(d, memo)),
            });
        }
        memo[step] = Some(total);
        total
    }

    fn check_node(
        &self,
        node: &NodeLimits,
        spec: &spec::StageSpec,
        resources: &Resources,
        name: &str,
        cpus: u64,
        memory_mib: u64,
    ) -> Result<(), PipelineError> {
        let src = self.source();
        let help = format!(
            "the largest node has {} CPUs and {} MiB ({})",
            node.cpus, node.memory_mib, node.source
        );
        if cpus > node.cpus {
            let (start, end) = resources
                .cpus
                .as_ref()
                .map_or((spec.start, spec.end), |c| (c.start, c.end));
            return Err(src
                .error(
                    ErrorKind::ExceedsNode,
                    start,
                    end,
                    format!(
                        "stage `{name}` asks for {cpus} CPUs per task, more than any node of the cluster has ({})",
                        node.cpus
                    ),
                )
                .with_help(help));
        }
        if memory_mib > node.memory_mib {
            return Err(match &resources.memory_mib {
                Some(m) => src
                    .error(
                        ErrorKind::ExceedsNode,
                        m.start,
                        m.end,
                        format!(
                            "stage `{name}` asks for {memory_mib} MiB per task, more than any node of the cluster declares ({} MiB)",
                            node.memory_mib
                        ),
                    )
                    .with_help(help),
                None => src
                    .error(
                        ErrorKind::ExceedsNode,
                        spec.start,
                        spec.end,
                        format!(
                            "stage `{name}` needs an estimated {memory_mib} MiB per task (from the size of its inputs), more than any node of the cluster declares ({} MiB)",
                            node.memory_mib
                        ),
                    )
                    .with_help(format!(
                        "{help}; if the estimate is too high, state the need: slurm: (memory_mib: N)"
                    )),
            });
        }
        Ok(())
    }

    /// The jobs this one waits for. Two arrays over one sweep where every task reads only
    /// its own frame of the earlier array (and every task has one there) wait task by task
    /// (`aftercorr`); everything else waits for the whole earlier job (`afterok`).
    fn dependencies(
        &self,
        steps: &[usize],
        steps_of: &BTreeMap<usize, Vec<usize>>,
        job_of_stage: &BTreeMap<usize, usize>,
        job_index: usize,
    ) -> Vec<(Dependency, usize)> {
        let mut on: BTreeMap<usize, bool> = BTreeMap::new();
        for &i in steps {
            let step = &self.steps[i];
            let mut per_job: BTreeMap<usize, Vec<&Step>> = BTreeMap::new();
            for &d in &step.deps {
                let dep = &self.steps[d];
                if let Some(&job) = job_of_stage.get(&dep.stage) {
                    if job != job_index && steps_of[&dep.stage].contains(&d) {
                        per_job.entry(job).or_default().push(dep);
                    }
                }
            }
            for (job, deps) in per_job {
                let corresponding = deps.len() == 1
                    && step.frame.is_some()
                    && deps[0].frame == step.frame
                    && self.stages[deps[0].stage].sweep.is_some();
                let entry = on.entry(job).or_insert(true);
                *entry &= corresponding;
            }
        }
        // A task with no counterpart in an array it otherwise waits on task by task would
        // have nothing to wait for under `aftercorr`: then the whole job waits.
        on.into_iter()
            .map(|(job, corr)| {
                let stage = job_of_stage
                    .iter()
                    .find_map(|(&s, &j)| (j == job).then_some(s))
                    .unwrap_or_default();
                let every_task_has_one = steps.iter().all(|&i| {
                    self.steps[i]
                        .deps
                        .iter()
                        .any(|&d| self.steps[d].stage == stage && steps_of[&stage].contains(&d))
                });
                if corr && every_task_has_one {
                    (Dependency::AfterCorr, job)
                } else {
                    (Dependency::AfterOk, job)
                }
            })
            .collect()
    }

    fn job_script(
        &self,
        job: &SlurmJob,
        (stage, steps): (usize, &[usize]),
        time_limit_min: Option<u64>,
        options: &SlurmOptions,
    ) -> Result<String, PipelineError> {
        let spec = &self.stages[stage];
        let mut s = String::new();
        let _ = writeln!(s, "#!/bin/sh");
        let _ = writeln!(
            s,
            "# Generated by irsig-run from {}: stage `{}` ({}).",
            file_name(&self.file),
            comment_text(&job.stage),
            comment_text(&self.location_of(spec.start))
        );
        match &job.array {
            Some(array) => {
                let _ = writeln!(
                    s,
                    "# A job array: task i runs frame i of the sweep; these are the frames out of date."
                );
                // What each task shows, when its frames have times: the expansion, readable.
                for &i in steps {
                    let step = &self.steps[i];
                    if let (Some(frame), Some(label)) = (step.frame, &step.label) {
                        let _ = writeln!(s, "#   task {frame}: {}", comment_text(label));
                    }
                }
                let _ = writeln!(s, "#SBATCH --array={array}");
            }
            None => {
                let _ = writeln!(s, "# One task.");
            }
        }
        let _ = writeln!(s, "#SBATCH --job-name=irsig-{}", file_word(&job.stage));
        let _ = writeln!(s, "#SBATCH --ntasks=1");
        let _ = writeln!(s, "#SBATCH --cpus-per-task={}", job.cpus);
        if job.memory_estimated {
            let _ = writeln!(
                s,
                "# Memory estimated: {MEMORY_FLOOR_MIB} MiB + {MEMORY_PER_INPUT_BYTE} x the bytes the task reads (formats/pipeline.md, Slurm)."
            );
        }
        let _ = writeln!(s, "#SBATCH --mem={}M", job.memory_mib);
        if let Some(t) = time_limit_min {
            let _ = writeln!(s, "#SBATCH --time={t}");
        }
        if let Some(p) = &options.partition {
            let _ = writeln!(s, "#SBATCH --partition={p}");
        }
        if !job.after.is_empty() {
            // A job whose dependency failed is cancelled rather than left pending forever.
            let _ = writeln!(s, "#SBATCH --kill-on-invalid-dep=yes");
        }
        for option in &options.sbatch {
            let _ = writeln!(s, "#SBATCH {option}");
        }
        let _ = writeln!(s, "set -eu");
        for line in &options.setup {
            let _ = writeln!(s, "{line}");
        }
        // Tools parallelise with rayon; a task uses the CPUs it was given, no more.
        let _ = writeln!(
            s,
            "export RAYON_NUM_THREADS=\"${{SLURM_CPUS_PER_TASK:-{}}}\"",
            job.cpus
        );
        let runner = crate::shell_quote(&options.runner.display().to_string())?;
        let pipeline = crate::shell_quote(&options.pipeline.display().to_string())?;
        let step = crate::shell_quote(&job.stage)?;
        let step = if job.array.is_some() {
            format!("{step}\"[$SLURM_ARRAY_TASK_ID]\"")
        } else {
            step
        };
        let _ = writeln!(s, "exec {runner} --step {step} {pipeline}");
        Ok(s)
    }

    fn submit_script(
        &self,
        jobs: &[SlurmJob],
        options: &SlurmOptions,
    ) -> Result<String, PipelineError> {
        let dir = crate::shell_quote(&options.script_dir.display().to_string())?;
        let chdir = crate::shell_quote(&self.base_dir.display().to_string())?;
        let mut s = String::new();
        let _ = writeln!(s, "#!/bin/sh");
        let _ = writeln!(
            s,
            "# Generated by irsig-run from {}: submits its out-of-date steps to Slurm, each job",
            file_name(&self.file)
        );
        let _ = writeln!(
            s,
            "# after the jobs that write its inputs. Prints one line per job: its id and script."
        );
        let _ = writeln!(
            s,
            "# Every task checks its step again (irsig-run --step), so running this twice redoes"
        );
        let _ = writeln!(
            s,
            "# nothing that is up to date; after a failure, run irsig-run --emit-slurm again to"
        );
        let _ = writeln!(s, "# submit only the steps still out of date.");
        let _ = writeln!(s, "set -eu");
        let _ = writeln!(s, "if ! command -v sbatch >/dev/null 2>&1; then");
        let _ = writeln!(
            s,
            "    echo \"submit.sh: sbatch is not on PATH: submit from a machine with the Slurm client commands (a login node; 'module load slurm' on some sites)\" >&2"
        );
        let _ = writeln!(s, "    exit 1");
        let _ = writeln!(s, "fi");
        if jobs.is_empty() {
            let _ = writeln!(
                s,
                "echo \"submit.sh: nothing to submit: every step was up to date\" >&2"
            );
            return Ok(s);
        }
        let _ = writeln!(s, "dir={dir}");
        let _ = writeln!(s, "mkdir -p \"$dir/logs\"");
        let _ = writeln!(s, "submitted=");
        let _ = writeln!(
            s,
            "# On a refusal, the jobs already submitted are cancelled: all or nothing."
        );
        let _ = writeln!(s, "fail() {{");
        let _ = writeln!(s, "    echo \"submit.sh: sbatch refused $1\" >&2");
        let _ = writeln!(
            s,
            "    if [ -n \"$submitted\" ]; then scancel $submitted || true; fi"
        );
        let _ = writeln!(s, "    exit 1");
        let _ = writeln!(s, "}}");
        for (i, job) in jobs.iter().enumerate() {
            let log = if job.array.is_some() {
                format!("{}-%A_%a.out", file_word(&job.stage))
            } else {
                format!("{}-%j.out", file_word(&job.stage))
            };
            let mut cmd = format!("sbatch --parsable --chdir={chdir} --output=\"$dir/logs/{log}\"");
            if !job.after.is_empty() {
                let mut by_kind: BTreeMap<&str, Vec<String>> = BTreeMap::new();
                for (kind, j) in &job.after {
                    by_kind
                        .entry(kind.keyword())
                        .or_default()
                        .push(format!("$job{}", j + 1));
                }
                let dependency: Vec<String> = by_kind
                    .into_iter()
                    .map(|(k, ids)| format!("{k}:{}", ids.join(":")))
                    .collect();
                let _ = write!(cmd, " --dependency={}", dependency.join(","));
            }
            let _ = write!(cmd, " \"$dir/{}\"", job.script);
            let n = i + 1;
            let _ = writeln!(s, "job{n}=$({cmd}) || fail {}", job.script);
            // `--parsable` prints `id` or `id;cluster`.
            let _ = writeln!(s, "job{n}=${{job{n}%%;*}}");
            let _ = writeln!(s, "submitted=\"$submitted $job{n}\"");
            let _ = writeln!(s, "echo \"$job{n} {}\"", job.script);
        }
        Ok(s)
    }

    fn location_of(&self, offset: usize) -> String {
        let (line, column) = irsig_formats::line_column(&self.text, offset);
        format!("{}:{line}:{column}", file_name(&self.file))
    }
}

/// `--mem` for a task that reads `input_bytes`: [`MEMORY_FLOOR_MIB`] plus
/// [`MEMORY_PER_INPUT_BYTE`] per byte, rounded up to whole MiB.
#[must_use]
pub fn estimate_memory_mib(input_bytes: u64) -> u64 {
    MEMORY_FLOOR_MIB
        + input_bytes
            .saturating_mul(MEMORY_PER_INPUT_BYTE)
            .div_ceil(1 << 20)
}

/// Frame numbers as a Slurm `--array` list: runs of consecutive frames as ranges,
/// `[1, 2, 3, 5, 7, 8]` → `1-3,5,7-8`.
fn array_spec(frames: &[usize]) -> String {
    let mut sorted = frames.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    let mut parts = Vec::new();
    let mut i = 0;
    while i < sorted.len() {
        let mut j = i;
        while j + 1 < sorted.len() && sorted[j + 1] == sorted[j] + 1 {
            j += 1;
        }
        parts.push(if i == j {
            sorted[i].to_string()
        } else {
            format!("{}-{}", sorted[i], sorted[j])
        });
        i = j + 1;
    }
    parts.join(",")
}

/// A stage name as a word for file and job names: letters, digits, `.`, `_` and `-` kept,
/// anything else `_`.
fn file_word(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

fn check_options(options: &SlurmOptions) -> Result<(), PipelineError> {
    let bad = |message: String| PipelineError::plain(ErrorKind::Structure, message);
    if let Some(p) = &options.partition {
        if p.is_empty()
            || !p
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | ','))
        {
            return Err(bad(format!(
                "partition {p:?}: expected a Slurm partition name (letters, digits, `_`, `-`, `.`; several separated by `,`)"
            )));
        }
    }
    for option in &options.sbatch {
        if !option.starts_with('-') || option.contains(char::is_control) {
            return Err(bad(format!(
                "sbatch option {option:?}: expected one option on one line, without control \
                 characters, such as --account=proj42"
            )));
        }
    }
    for line in &options.setup {
        if line.contains(char::is_control) {
            return Err(bad(format!(
                "setup line {line:?}: expected one shell line, without control characters \
                 (give several lines as several --setup)"
            )));
        }
    }
    for path in [&options.pipeline, &options.script_dir, &options.runner] {
        if !path.is_absolute() {
            return Err(bad(format!(
                "`{}` must be an absolute path: jobs run in another directory",
                path.display()
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn array_lists_are_runs_of_frames() {
        assert_eq!(array_spec(&[1, 2, 3, 5, 7, 8]), "1-3,5,7-8");
        assert_eq!(array_spec(&[24]), "24");
        assert_eq!(array_spec(&[3, 1, 2, 2]), "1-3");
        assert_eq!(array_spec(&[]), "");
    }

    #[test]
    fn memory_estimate_is_the_floor_plus_twelve_bytes_per_input_byte() {
        assert_eq!(estimate_memory_mib(0), 64);
        // 1 MiB read: 12 MiB more.
        assert_eq!(estimate_memory_mib(1 << 20), 76);
        // One byte still rounds up to a whole MiB.
        assert_eq!(estimate_memory_mib(1), 65);
        // The 1M-triangle raw scene, 40 000 103 bytes: 480 001 236 bytes = 457.8 MiB.
        assert_eq!(estimate_memory_mib(40_000_103), 64 + 458);
    }

    #[test]
    fn names_become_safe_words() {
        assert_eq!(file_word("contact-sheet"), "contact-sheet");
        assert_eq!(file_word("trace#2 x/y"), "trace_2_x_y");
    }
}

#[cfg(test)]
mod plan_tests;
