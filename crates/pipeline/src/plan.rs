//! From the pipeline file to a checked plan: templates expanded per frame, every stage
//! instance's command line built, tools found, parameters validated, outputs unique, inputs
//! present or produced, and the instances ordered so that producers come first.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::{Component, Path, PathBuf};

use crate::error::{ErrorKind, PipelineError};
use crate::spec::{self, Param, PipelineSpec, Source, Spanned, StageSpec};
use crate::step::{FileRef, Step};
use crate::sun::SunFlags;
use crate::times::TimeFlags;

/// Checks a stage's command line (program name first, as `std::env::args` gives it) the way
/// the tool itself would parse it, without running anything. The message is shown to the
/// user at the offending parameter.
pub type Validator = Box<dyn Fn(&[String]) -> Result<(), String> + Send + Sync>;

/// Finds a tool's program by the tool's name.
type Lookup = dyn Fn(&str) -> Option<PathBuf> + Send + Sync;

/// How the runner finds and checks the tools stages name.
pub struct Tools {
    lookup: Box<Lookup>,
    validators: BTreeMap<String, Validator>,
    sun_flags: Option<SunFlags>,
    time_flags: Option<TimeFlags>,
}

impl std::fmt::Debug for Tools {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Tools")
            .field("validators", &self.validators.keys().collect::<Vec<_>>())
            .finish_non_exhaustive()
    }
}

impl Tools {
    /// Tools found by `lookup` (the tool's name, such as `trace`, to the path of its
    /// program, or `None` when there is no such tool), with no parameter validators yet.
    pub fn new(lookup: impl Fn(&str) -> Option<PathBuf> + Send + Sync + 'static) -> Self {
        Self {
            lookup: Box::new(lookup),
            validators: BTreeMap::new(),
            sun_flags: None,
            time_flags: None,
        }
    }

    /// Says how the tools spell a sun, so that a pipeline's `sun` can become a trace
    /// stage's flags and be checked against an atmosphere plan stage's. Without it a
    /// pipeline with a `sun` is refused.
    pub fn with_sun_flags(&mut self, flags: SunFlags) -> &mut Self {
        self.sun_flags = Some(flags);
        self
    }

    /// Says how the tools name a weather record, so that the frames of a `Times` sweep are
    /// checked against the record a stage reads before anything runs. Without it they are
    /// checked only by the tool, when it runs.
    pub fn with_time_flags(&mut self, flags: TimeFlags) -> &mut Self {
        self.time_flags = Some(flags);
        self
    }

    /// Registers the parameter check of `tool`: usually `Cli::try_parse_from` of the tool's
    /// own clap `Cli`, so that every flag has a single definition. Stages of tools without a
    /// validator are checked only when they run.
    pub fn register(&mut self, tool: &str, validator: Validator) -> &mut Self {
        self.validators.insert(tool.to_owned(), validator);
        self
    }

    /// The tools with a registered validator.
    pub fn validated_tools(&self) -> impl Iterator<Item = &str> {
        self.validators.keys().map(String::as_str)
    }

    fn validate(&self, tool: &str, argv: &[String]) -> Option<Result<(), String>> {
        self.validators.get(tool).map(|v| v(argv))
    }
}

/// A parsed pipeline file, not yet checked against the file system or the tools.
#[derive(Debug, Clone)]
pub struct Pipeline {
    file: String,
    text: String,
    base_dir: PathBuf,
    spec: PipelineSpec,
}

impl Pipeline {
    /// Reads and parses the pipeline file at `path`. Paths in it are relative to its
    /// directory.
    ///
    /// # Errors
    /// An unreadable file, or any error of [`Pipeline::parse`].
    pub fn load(path: &Path) -> Result<Self, PipelineError> {
        let bytes = irsig_formats::file::read_file(path).map_err(|e| {
            PipelineError::io(format!("cannot read pipeline file `{}`", path.display()), e)
        })?;
        // Not UTF-8: an error at the first bad byte, as every reader of text gives.
        let text = irsig_formats::canonical::utf8(&path.display().to_string(), &bytes)
            .map_err(|e| PipelineError::located(ErrorKind::Syntax, e))?;
        let base_dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        Self::parse(&path.display().to_string(), text, &base_dir)
    }

    /// Parses pipeline text. `file` is the name errors show; relative paths in the pipeline
    /// resolve against `base_dir`, where the stages also run.
    ///
    /// # Errors
    /// Invalid RON ([`ErrorKind::Syntax`]) or a value that does not fit the pipeline shape
    /// ([`ErrorKind::Structure`]), located at its line and column.
    pub fn parse(file: &str, text: &str, base_dir: &Path) -> Result<Self, PipelineError> {
        let src = Source { file, text };
        // `ron` is the judge of syntax (through irsig-formats), so a syntax error reads as it
        // would for any RON file; the tree keeps every value's position for later errors.
        let root = irsig_formats::ron_tree::parse(file, text, "pipeline")
            .map_err(|e| PipelineError::located(ErrorKind::Syntax, e))?;
        let spec = spec::pipeline(src, &root)?;
        Ok(Self {
            file: file.to_owned(),
            text: text.to_owned(),
            base_dir: base_dir.to_path_buf(),
            spec,
        })
    }

    /// The directory the stages run in and relative paths resolve against.
    #[must_use]
    pub fn base_dir(&self) -> &Path {
        &self.base_dir
    }

    fn source(&self) -> Source<'_> {
        Source {
            file: &self.file,
            text: &self.text,
        }
    }

    /// Expands sweeps, builds every command line and checks the whole pipeline before
    /// anything runs.
    ///
    /// # Errors
    /// Located errors for an undefined sweep or template variable, an unknown tool
    /// ([`ErrorKind::UnknownTool`]), parameters the tool rejects
    /// ([`ErrorKind::BadParameter`]), an output written twice
    /// ([`ErrorKind::DuplicateOutput`]), an input neither on disk nor produced
    /// ([`ErrorKind::MissingInput`]) and dependency cycles ([`ErrorKind::Cycle`]).
    pub fn plan(&self, tools: &Tools) -> Result<Plan, PipelineError> {
        self.plan_checking(tools, true)
    }

    /// As [`Pipeline::plan`], for running single steps ([`Plan::run_step_named`]): an input
    /// that is neither on disk nor produced is not an error here, only for the step that
    /// reads it when it runs. A task of a Slurm job array runs one frame; another frame's
    /// missing input is not its concern.
    ///
    /// # Errors
    /// As [`Pipeline::plan`], less [`ErrorKind::MissingInput`].
    pub fn plan_for_single_steps(&self, tools: &Tools) -> Result<Plan, PipelineError> {
        self.plan_checking(tools, false)
    }

    fn plan_checking(&self, tools: &Tools, inputs_must_exist: bool) -> Result<Plan, PipelineError> {
        let src = self.source();
        let mut steps = Vec::new();
        let mut names = BTreeMap::new();
        let stages = self.lit_stages(tools)?;
        let mut weather = crate::times::WeatherSpans::new();
        for (index, stage) in stages.iter().enumerate() {
            let program = self.find_tool(stage, tools)?;
            let base_name = stage.name.as_ref().map_or_else(
                || format!("{}#{}", stage.tool.value, index + 1),
                |n| n.value.clone(),
            );
            if let Some(n) = &stage.name {
                if let Some(first) = names.insert(n.value.clone(), n.start) {
                    return Err(src.error(
                        ErrorKind::Structure,
                        n.start,
                        n.end,
                        format!(
                            "stage name `{}` is already used on line {}",
                            n.value,
                            src.line(first)
                        ),
                    ));
                }
            }
            let gathered = self.gathered(stage)?;
            let timed = self.is_timed(stage);
            for (frame, vars) in self.frames_of(stage)? {
                let name = match frame {
                    Some(f) => format!("{base_name}[{f}]"),
                    None => base_name.clone(),
                };
                let lit = self.lit_frame(stage, vars.as_ref(), tools)?;
                let at_frame = lit.as_ref().unwrap_or(stage);
                let mut step = build_step(
                    src,
                    at_frame,
                    name,
                    &program,
                    vars.as_ref(),
                    gathered.as_deref(),
                )?;
                step.stage = index;
                step.frame = frame;
                step.label = vars
                    .as_ref()
                    .filter(|_| timed)
                    .and_then(|v| v.get("time").cloned());
                check_parameters(src, at_frame, &step, tools)?;
                steps.push(step);
            }
            self.check_weather(stage, tools, &mut weather)?;
        }
        let order = self.link(&mut steps, inputs_must_exist)?;
        Ok(Plan {
            file: self.file.clone(),
            text: self.text.clone(),
            base_dir: self.base_dir.clone(),
            stages,
            steps: reorder(steps, &order),
        })
    }

    /// The stages, with the pipeline's `sun` (if it has one) given to them as `tools`
    /// spell it.
    fn lit_stages(&self, tools: &Tools) -> Result<Vec<StageSpec>, PipelineError> {
        let mut stages = self.spec.stages.clone();
        if let Some(sun) = &self.spec.sun {
            let src = self.source();
            let Some(flags) = &tools.sun_flags else {
                return Err(src.error(
                    ErrorKind::Structure,
                    sun.start(),
                    sun.start(),
                    "this pipeline has a `sun`, and its runner does not say how its tools take \
                     one",
                ));
            };
            crate::sun::apply(src, sun, flags, &mut stages, &self.spec.sweeps)?;
        }
        Ok(stages)
    }

    /// The stage as it runs for one frame, when the pipeline's sun follows the frames'
    /// times and lights this frame of it: `None` when it runs as written.
    fn lit_frame(
        &self,
        stage: &StageSpec,
        vars: Option<&BTreeMap<String, String>>,
        tools: &Tools,
    ) -> Result<Option<StageSpec>, PipelineError> {
        let (Some(sun), Some(vars), Some(flags)) = (&self.spec.sun, vars, &tools.sun_flags) else {
            return Ok(None);
        };
        let params = crate::sun::frame_params(self.source(), sun, flags, stage, vars)?;
        if params.is_empty() {
            return Ok(None);
        }
        let mut lit = stage.clone();
        lit.params.extend(params);
        Ok(Some(lit))
    }

    /// The `Times` sweep a stage runs over (`sweep`) or gathers, if it is one.
    fn times_of(&self, stage: &StageSpec) -> Option<&crate::times::TimesSpec> {
        let name = stage.sweep.as_ref().or(stage.gather.as_ref())?;
        self.spec.sweeps.get(&name.value)?.times.as_ref()
    }

    /// Whether a stage runs once per frame of a `Times` sweep: its steps are labelled by
    /// their frame's time.
    fn is_timed(&self, stage: &StageSpec) -> bool {
        stage.sweep.is_some() && self.times_of(stage).is_some()
    }

    /// The frames' times against the weather record the stage reads, if any.
    fn check_weather(
        &self,
        stage: &StageSpec,
        tools: &Tools,
        spans: &mut crate::times::WeatherSpans,
    ) -> Result<(), PipelineError> {
        let (Some(flags), Some(times)) = (&tools.time_flags, self.times_of(stage)) else {
            return Ok(());
        };
        crate::times::check_weather(
            self.source(),
            &self.base_dir,
            flags,
            stage,
            (times, &times.instants_s),
            spans,
        )
    }

    fn find_tool(&self, stage: &StageSpec, tools: &Tools) -> Result<PathBuf, PipelineError> {
        let tool = stage
            .tool
            .value
            .split_whitespace()
            .next()
            .unwrap_or_default();
        (tools.lookup)(tool).ok_or_else(|| {
            self.source()
                .error(
                    ErrorKind::UnknownTool,
                    stage.tool.start,
                    stage.tool.end,
                    format!("unknown tool `{tool}`: no program `irsig-{tool}` was found"),
                )
                .with_help(
                    "a stage's tool is run as the program irsig-<tool>, looked up beside \
                     irsig-run and then on PATH",
                )
        })
    }

    /// The frames a stage runs for: `(Some(frame number from 1), variables)` per frame of
    /// its sweep, or one `(None, None)` for a stage without a sweep.
    #[allow(clippy::type_complexity)]
    fn frames_of(
        &self,
        stage: &StageSpec,
    ) -> Result<Vec<(Option<usize>, Option<BTreeMap<String, String>>)>, PipelineError> {
        let Some(sweep) = &stage.sweep else {
            return Ok(vec![(None, None)]);
        };
        let frames = self.sweep_frames(sweep)?;
        Ok(frames
            .into_iter()
            .enumerate()
            .map(|(i, vars)| (Some(i + 1), Some(vars)))
            .collect())
    }

    fn gathered(
        &self,
        stage: &StageSpec,
    ) -> Result<Option<Vec<BTreeMap<String, String>>>, PipelineError> {
        stage
            .gather
            .as_ref()
            .map(|g| self.sweep_frames(g))
            .transpose()
    }

    /// Every frame's variables, `frame` (from 1) and `frames` included.
    fn sweep_frames(
        &self,
        name: &Spanned<String>,
    ) -> Result<Vec<BTreeMap<String, String>>, PipelineError> {
        let Some(sweep) = self.spec.sweeps.get(&name.value) else {
            let known: Vec<_> = self.spec.sweeps.keys().map(String::as_str).collect();
            return Err(self.source().error(
                ErrorKind::Structure,
                name.start,
                name.end,
                format!(
                    "no sweep named `{}` (the pipeline defines: {})",
                    name.value,
                    if known.is_empty() {
                        "none".to_owned()
                    } else {
                        known.join(", ")
                    }
                ),
            ));
        };
        let count = sweep.frames.len();
        Ok(sweep
            .frames
            .iter()
            .enumerate()
            .map(|(i, vars)| {
                let mut vars = vars.clone();
                vars.insert("frame".to_owned(), (i + 1).to_string());
                vars.insert("frames".to_owned(), count.to_string());
                vars
            })
            .collect())
    }

    /// Finds each step's producers, refuses duplicate outputs and missing inputs, and
    /// returns a dependency order (or the cycle that prevents one).
    fn link(
        &self,
        steps: &mut [Step],
        inputs_must_exist: bool,
    ) -> Result<Vec<usize>, PipelineError> {
        let src = self.source();
        let mut producer: HashMap<PathBuf, (usize, usize)> = HashMap::new();
        for (i, step) in steps.iter().enumerate() {
            for out in &step.outputs {
                if let Some(&(j, start)) = producer.get(&out.key) {
                    let first = &steps[j];
                    return Err(src.error(
                        ErrorKind::DuplicateOutput,
                        out.start,
                        out.end,
                        format!(
                            "`{}` is written by stage `{}` here and by stage `{}` on line {}",
                            out.path.display(),
                            step.name,
                            first.name,
                            src.line(start)
                        ),
                    ));
                }
                producer.insert(out.key.clone(), (i, out.start));
            }
        }
        for step in steps.iter_mut() {
            let mut deps = BTreeSet::new();
            for input in &step.inputs {
                if let Some(&(j, _)) = producer.get(&input.key) {
                    deps.insert(j);
                } else if inputs_must_exist && !self.base_dir.join(&input.path).is_file() {
                    return Err(src
                        .error(
                            ErrorKind::MissingInput,
                            input.start,
                            input.end,
                            format!(
                                "input file `{}` does not exist and no stage writes it",
                                input.path.display()
                            ),
                        )
                        .with_help(format!(
                            "paths are relative to the pipeline's directory `{}`",
                            self.base_dir.display()
                        )));
                }
            }
            step.deps = deps.into_iter().collect();
        }
        topological_order(src, steps)
    }
}

/// Kahn's algorithm, lowest index first among the ready steps, so the order (and so the
/// dry-run listing and the Makefile) follows the file.
fn topological_order(src: Source<'_>, steps: &[Step]) -> Result<Vec<usize>, PipelineError> {
    let mut waiting: Vec<usize> = steps.iter().map(|s| s.deps.len()).collect();
    let mut dependents = vec![Vec::new(); steps.len()];
    for (i, s) in steps.iter().enumerate() {
        for &d in &s.deps {
            dependents[d].push(i);
        }
    }
    let mut ready: BTreeSet<usize> = (0..steps.len()).filter(|&i| waiting[i] == 0).collect();
    let mut order = Vec::with_capacity(steps.len());
    while let Some(i) = ready.pop_first() {
        order.push(i);
        for &d in &dependents[i] {
            waiting[d] -= 1;
            if waiting[d] == 0 {
                ready.insert(d);
            }
        }
    }
    if order.len() == steps.len() {
        return Ok(order);
    }
    // Walk back along unfinished dependencies until a step repeats: that loop is a cycle.
    let Some(start) = (0..steps.len()).find(|&i| waiting[i] > 0) else {
        return Ok(order);
    };
    let mut path = vec![start];
    let mut current = start;
    while let Some(&next) = steps[current].deps.iter().find(|&&d| waiting[d] > 0) {
        if let Some(pos) = path.iter().position(|&p| p == next) {
            path.drain(..pos);
            break;
        }
        path.push(next);
        current = next;
    }
    // path[k] reads a file written by path[k + 1] (cyclically).
    let mut story = Vec::new();
    let mut first_span = (steps[path[0]].start, steps[path[0]].end);
    for (k, &i) in path.iter().enumerate() {
        let j = path[(k + 1) % path.len()];
        let via = steps[i]
            .inputs
            .iter()
            .find(|inp| steps[j].outputs.iter().any(|o| o.key == inp.key));
        if let Some(inp) = via {
            if k == 0 {
                first_span = (inp.start, inp.end);
            }
            story.push(format!(
                "`{}` reads `{}`, written by `{}`",
                steps[i].name,
                inp.path.display(),
                steps[j].name
            ));
        }
    }
    Err(src.error(
        ErrorKind::Cycle,
        first_span.0,
        first_span.1,
        format!("the stages form a cycle: {}", story.join("; ")),
    ))
}

fn reorder(steps: Vec<Step>, order: &[usize]) -> Vec<Step> {
    let mut new_index = vec![0; steps.len()];
    for (new, &old) in order.iter().enumerate() {
        new_index[old] = new;
    }
    let mut slots: Vec<Option<Step>> = steps.into_iter().map(Some).collect();
    order
        .iter()
        .filter_map(|&old| slots.get_mut(old).and_then(Option::take))
        .map(|mut s| {
            s.deps = s.deps.iter().map(|&d| new_index[d]).collect();
            s.deps.sort_unstable();
            s
        })
        .collect()
}

fn flag(key: &str) -> String {
    if key.starts_with('-') {
        key.to_owned()
    } else if key.chars().count() == 1 {
        format!("-{key}")
    } else {
        format!("--{key}")
    }
}

/// The words one templated text gives a step: one, expanded with the frame's variables;
/// or, in a `gather` stage, one per gathered frame, in frame order, when it holds a
/// template.
fn values(
    src: Source<'_>,
    text: &Spanned<String>,
    vars: Option<&BTreeMap<String, String>>,
    gathered: Option<&[BTreeMap<String, String>]>,
) -> Result<Vec<String>, PipelineError> {
    match gathered {
        Some(frames) if spec::has_template(&text.value) => frames
            .iter()
            .map(|frame| expand(src, text, Some(frame)))
            .collect(),
        _ => Ok(vec![expand(src, text, vars)?]),
    }
}

/// The files one templated path names in a step (as [`values`]), each checked to be a
/// file rather than standard input or output.
fn files(
    src: Source<'_>,
    path: &Spanned<String>,
    vars: Option<&BTreeMap<String, String>>,
    gathered: Option<&[BTreeMap<String, String>]>,
) -> Result<Vec<FileRef>, PipelineError> {
    values(src, path, vars, gathered)?
        .into_iter()
        .map(|p| {
            if p == "-" || p.is_empty() {
                return Err(src.error(
                    ErrorKind::Structure,
                    path.start,
                    path.end,
                    "expected a file path: pipeline stages pass files, not standard input or output",
                ));
            }
            let p = PathBuf::from(p);
            Ok(FileRef {
                key: normalise(&p),
                path: p,
                start: path.start,
                end: path.end,
            })
        })
        .collect()
}

/// The words of one parameter: `--key value` (a list repeats the flag, a tuple gives it
/// several values), each templated value once per gathered frame in a `gather` stage.
fn param_words(
    src: Source<'_>,
    key: &str,
    param: &Param,
    vars: Option<&BTreeMap<String, String>>,
    gathered: Option<&[BTreeMap<String, String>]>,
) -> Result<Vec<String>, PipelineError> {
    let mut words = Vec::new();
    match param {
        Param::Switch(false) => {}
        Param::Switch(true) => words.push(flag(key)),
        Param::One(v) => {
            for value in values(src, v, vars, gathered)? {
                words.push(flag(key));
                words.push(value);
            }
        }
        Param::Repeated(vs) => {
            for v in vs {
                for value in values(src, v, vars, gathered)? {
                    words.push(flag(key));
                    words.push(value);
                }
            }
        }
        Param::Several(vs) => match gathered {
            Some(frames) if vs.iter().any(|v| spec::has_template(&v.value)) => {
                for frame in frames {
                    words.push(flag(key));
                    for v in vs {
                        words.push(expand(src, v, Some(frame))?);
                    }
                }
            }
            _ => {
                words.push(flag(key));
                for v in vs {
                    words.push(expand(src, v, vars)?);
                }
            }
        },
    }
    Ok(words)
}

fn build_step(
    src: Source<'_>,
    stage: &StageSpec,
    name: String,
    program: &Path,
    vars: Option<&BTreeMap<String, String>>,
    gathered: Option<&[BTreeMap<String, String>]>,
) -> Result<Step, PipelineError> {
    let mut words = stage.tool.value.split_whitespace();
    let tool = words.next().unwrap_or_default().to_owned();
    let mut argv = vec![format!("irsig-{tool}")];
    argv.extend(words.map(str::to_owned));
    let mut inputs = Vec::new();
    let mut outputs = Vec::new();
    let mut flags = Vec::new();
    for arg in &stage.args {
        inputs.extend(files(src, arg, vars, gathered)?);
    }
    for input in &inputs {
        argv.push(positional(&input.path));
    }
    for (key, path) in &stage.inputs {
        for f in files(src, path, vars, gathered)? {
            flags.push((argv.len(), (key.start, key.end), (path.start, path.end)));
            argv.push(flag(&key.value));
            argv.push(f.path.display().to_string());
            inputs.push(f);
        }
    }
    for read in &stage.reads {
        inputs.extend(files(src, read, vars, gathered)?);
    }
    for (key, param) in &stage.params {
        let (vstart, vend) = match param {
            Param::Switch(_) => (key.start, key.end),
            Param::One(v) => (v.start, v.end),
            Param::Repeated(vs) | Param::Several(vs) => (
                vs.first().map_or(key.start, |v| v.start),
                vs.last().map_or(key.end, |v| v.end),
            ),
        };
        let words = param_words(src, &key.value, param, vars, gathered)?;
        let at = argv.len();
        if !words.is_empty() {
            flags.push((at, (key.start, key.end), (vstart, vend)));
        }
        argv.extend(words);
    }
    for (key, path) in &stage.outputs {
        for f in files(src, path, vars, gathered)? {
            flags.push((argv.len(), (key.start, key.end), (path.start, path.end)));
            argv.push(flag(&key.value));
            argv.push(f.path.display().to_string());
            outputs.push(f);
        }
    }
    Ok(Step {
        name,
        tool,
        program: program.to_path_buf(),
        argv,
        inputs,
        outputs,
        deps: Vec::new(),
        frame: None,
        label: None,
        stage: 0,
        start: stage.start,
        end: stage.end,
        flags,
        tool_span: (stage.tool.start, stage.tool.end),
    })
}

/// A positional path that starts with `-` would read as a flag: `./-x` is the same file.
fn positional(path: &Path) -> String {
    let s = path.display().to_string();
    if s.starts_with('-') {
        format!("./{s}")
    } else {
        s
    }
}

/// Lexical normalisation (no file system access): `./a/../b` and `b` are the same key.
fn normalise(path: &Path) -> PathBuf {
    let mut out: Vec<Component<'_>> = Vec::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => match out.last() {
                Some(Component::Normal(_)) => {
                    out.pop();
                }
                Some(Component::RootDir | Component::Prefix(_)) => {}
                _ => out.push(c),
            },
            other => out.push(other),
        }
    }
    out.iter().collect()
}

/// Substitutes `{name}` and `{name:0N}` (zero-padded to N digits) from the frame's
/// variables; `{{` and `}}` are literal braces.
pub(crate) fn expand(
    src: Source<'_>,
    text: &Spanned<String>,
    vars: Option<&BTreeMap<String, String>>,
) -> Result<String, PipelineError> {
    let err = |message: String| src.error(ErrorKind::Structure, text.start, text.end, message);
    let s = &text.value;
    let mut out = String::with_capacity(s.len());
    let mut rest = s.as_str();
    while let Some(i) = rest.find(['{', '}']) {
        out.push_str(&rest[..i]);
        let tail = &rest[i..];
        if tail.starts_with("{{") || tail.starts_with("}}") {
            out.push_str(&tail[..1]);
            rest = &tail[2..];
            continue;
        }
        if tail.starts_with('}') {
            return Err(err(format!(
                "unmatched `}}` in {s:?}; write `}}}}` for a literal brace"
            )));
        }
        let Some(close) = tail.find('}') else {
            return Err(err(format!(
                "unmatched `{{` in {s:?}; write `{{{{` for a literal brace"
            )));
        };
        let inner = &tail[1..close];
        let (name, width) = match inner.split_once(':') {
            None => (inner, None),
            Some((n, w)) => {
                let width = w
                    .strip_prefix('0')
                    .and_then(|d| d.parse::<usize>().ok())
                    .filter(|&d| d <= 32)
                    .ok_or_else(|| {
                        err(format!(
                            "bad format `{{{inner}}}`: expected `{{{n}}}` or a zero-padded width such as `{{{n}:03}}`"
                        ))
                    })?;
                (n, Some(width))
            }
        };
        if !spec::is_variable(name) {
            return Err(err(format!(
                "bad template `{{{inner}}}`: expected `{{variable}}`"
            )));
        }
        let Some(vars) = vars else {
            return Err(err(format!(
                "`{{{name}}}` is a frame variable, but this stage has no `sweep` (or `gather`)"
            )));
        };
        let Some(value) = vars.get(name) else {
            let known: Vec<_> = vars.keys().map(String::as_str).collect();
            return Err(err(format!(
                "unknown variable `{name}`: this sweep defines {}",
                known.join(", ")
            )));
        };
        match width {
            Some(w) => out.push_str(&format!("{value:0>w$}")),
            None => out.push_str(value),
        }
        rest = &tail[close + 1..];
    }
    out.push_str(rest);
    Ok(out)
}

fn check_parameters(
    src: Source<'_>,
    stage: &StageSpec,
    step: &Step,
    tools: &Tools,
) -> Result<(), PipelineError> {
    let Some(Err(message)) = tools.validate(&step.tool, &step.argv) else {
        return Ok(());
    };
    // clap's report: "error: <what>\n\n  tip: ...\n\nUsage: ...". Keep the first paragraph
    // and point at the flag or value it names.
    let message = message.trim_start_matches("error: ");
    let first = message
        .split("\n\n")
        .next()
        .unwrap_or(message)
        .trim()
        .to_owned();
    let invalid_value = first.starts_with("invalid value");
    let mut span = step.tool_span;
    let quoted =
        |word: &str| first.contains(&format!("'{word}'")) || first.contains(&format!("'{word} "));
    // A tool's own rules name the flag first: `--sun-zenith-deg: the sun is 95 deg …`.
    let leading = first
        .split([':', ' '])
        .next()
        .filter(|w| w.starts_with("--"));
    let flag_at = |word: &str| {
        step.flags
            .iter()
            .find(|(at, _, _)| step.argv.get(*at).is_some_and(|w| w == word))
    };
    if let Some(&(_, key, value)) = step
        .flags
        .iter()
        .find(|(at, _, _)| step.argv.get(*at).is_some_and(|w| quoted(w)))
    {
        span = if invalid_value { value } else { key };
    } else if let Some(&(_, _, value)) = leading.and_then(flag_at) {
        span = value;
    } else if let Some(input) = step
        .inputs
        .iter()
        .find(|i| quoted(&i.path.display().to_string()))
    {
        span = (input.start, input.end);
    }
    Err(src
        .error(
            ErrorKind::BadParameter,
            span.0,
            span.1,
            format!(
                "`irsig-{}` rejects this stage's parameters: {first}",
                step.tool
            ),
        )
        .with_help(format!(
            "the stage `{}` runs: {}\n`irsig-{} --help` lists its flags",
            stage
                .name
                .as_ref()
                .map_or(step.name.as_str(), |n| n.value.as_str()),
            step.command_line(),
            step.tool
        )))
}

/// A checked pipeline: every step with its command line, in an order where producers come
/// before the steps that read their outputs.
#[derive(Debug, Clone)]
pub struct Plan {
    pub(crate) file: String,
    pub(crate) text: String,
    pub(crate) base_dir: PathBuf,
    /// The stages as the file gives them, for the back ends that group steps by stage.
    pub(crate) stages: Vec<StageSpec>,
    /// The steps, dependencies first.
    pub steps: Vec<Step>,
}

impl Plan {
    /// The directory the steps run in.
    #[must_use]
    pub fn base_dir(&self) -> &Path {
        &self.base_dir
    }

    pub(crate) fn source(&self) -> Source<'_> {
        Source {
            file: &self.file,
            text: &self.text,
        }
    }

    pub(crate) fn step_error(
        &self,
        step: &Step,
        kind: ErrorKind,
        message: String,
    ) -> PipelineError {
        self.source().error(kind, step.start, step.end, message)
    }

    pub(crate) fn file_error(
        &self,
        file: &FileRef,
        kind: ErrorKind,
        message: String,
    ) -> PipelineError {
        self.source().error(kind, file.start, file.end, message)
    }

    /// `file:line:column` of the stage a step comes from.
    #[must_use]
    pub fn location(&self, step: &Step) -> String {
        let (line, column) = irsig_formats::line_column(&self.text, step.start);
        format!("{}:{line}:{column}", self.file)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalising_paths() {
        assert_eq!(normalise(Path::new("./a/../b/c")), PathBuf::from("b/c"));
        assert_eq!(normalise(Path::new("../x")), PathBuf::from("../x"));
        assert_eq!(normalise(Path::new("/a/./b")), PathBuf::from("/a/b"));
    }

    #[test]
    fn flags_follow_the_command_line_convention() {
        assert_eq!(flag("o"), "-o");
        assert_eq!(flag("band"), "--band");
        assert_eq!(flag("--band"), "--band");
    }
}

#[cfg(test)]
mod plan_tests;
