//! `irsig-run PIPELINE.ron`: runs a declarative pipeline, each stage as its own tool
//! (`irsig-<tool>`, found beside this program or on `PATH`), in dependency order,
//! independent stages in parallel, skipping stages whose outputs are up to date.
//!
//! ```text
//! irsig-run pipelines/quickstart.ron            # run what is out of date
//! irsig-run -n pipelines/quickstart.ron         # print the commands instead
//! irsig-run --emit-makefile Makefile p.ron      # the same steps as a Makefile
//! irsig-run --emit-slurm slurm/ p.ron           # Slurm batch scripts: sh slurm/submit.sh
//! irsig-run --step 'trace[3]' p.ron             # one step (what a Slurm task runs)
//! ```
//!
//! Before anything runs, every stage's parameters are checked by the tool's own clap `Cli`,
//! asked of the tool's program ([`tools`]), so an unknown or mistyped parameter is reported
//! at its line and column in the pipeline file.

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![warn(clippy::print_stderr)]

mod slurm;

use std::path::PathBuf;

use clap::Parser;
use irsig_pipeline::{Event, Pipeline, RunOptions, Tools};

/// Command line of `irsig-run`.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-run",
    version,
    about = "Run a declarative irsig pipeline file (RON)",
    after_help = "\
Each stage runs as its tool, irsig-<tool>, in the pipeline file's directory. A stage is
skipped when its tool, command line and input contents are those of its last successful
run and its outputs are unchanged since (SHA-256; the state is kept in .irsig-run/ beside
the pipeline file).

Examples:
  irsig-run pipelines/quickstart.ron
  irsig-run --dry-run --force pipelines/quickstart.ron
  irsig-run --emit-makefile pipelines/Makefile pipelines/quickstart.ron && make -C pipelines -j
  irsig-run --emit-slurm slurm pipelines/thesis-flyby.ron && sh slurm/submit.sh",
    mut_arg("threads", |a| a
        .short_alias('j')
        .alias("jobs")
        .help("Run at most N tools at once [default: the number of CPUs]; with more than \
               one, each line a tool writes on stderr begins with its stage's name, [STAGE]")),
)]
pub struct Cli {
    /// The pipeline file (RON). Paths in it are relative to its directory.
    pub pipeline: PathBuf,

    /// `--threads N`: tools at once.
    #[command(flatten)]
    pub threads: irsig_cli::args::ThreadsArgs,

    /// Run every stage, even those up to date.
    #[arg(long)]
    pub force: bool,

    /// Print every stage's command (shell-quoted), one per line, those up to date as
    /// `# up to date: COMMAND` comments, and run nothing.
    #[arg(short = 'n', long, conflicts_with = "emit_makefile")]
    pub dry_run: bool,

    /// Write an equivalent Makefile to FILE (`-` for stdout) and run nothing.
    #[arg(long, value_name = "FILE", conflicts_with = "emit_slurm")]
    pub emit_makefile: Option<PathBuf>,

    /// Write Slurm batch scripts for the steps out of date into DIR (a job per stage, a job
    /// array per frame sweep, `--dependency` between them) and `DIR/submit.sh`, which submits
    /// them; run nothing. See formats/pipeline.md.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["dry_run", "step"])]
    pub emit_slurm: Option<PathBuf>,

    /// With --emit-slurm: the partition every job is submitted to.
    #[arg(long, value_name = "NAME", requires = "emit_slurm")]
    pub partition: Option<String>,

    /// With --emit-slurm: a further `#SBATCH` option for every job (repeatable), such as
    /// `--sbatch=--account=proj42`.
    #[arg(
        long,
        value_name = "OPTION",
        requires = "emit_slurm",
        allow_hyphen_values = true
    )]
    pub sbatch: Vec<String>,

    /// With --emit-slurm: a shell line every job runs first (repeatable), such as
    /// `--setup 'module load irsig'`.
    #[arg(long, value_name = "LINE", requires = "emit_slurm")]
    pub setup: Vec<String>,

    /// Run only the step NAME (`trace[3]`: frame 3 of the stage `trace`) unless it is up to
    /// date; its inputs must exist. What each task of the Slurm scripts runs.
    #[arg(long, value_name = "NAME", conflicts_with_all = ["dry_run", "emit_makefile"])]
    pub step: Option<String>,

    /// Do not report stages on stderr.
    #[arg(short, long)]
    pub quiet: bool,
}

/// The flags' own rules are clap's and the run's: nothing more is checked before a file
/// is read.
impl irsig_cli::CheckArgs for Cli {}

/// The stage tools whose parameters the runner checks before anything runs.
pub const STAGE_TOOLS: [&str; 11] = [
    "import", "flatten", "atmos", "material", "therm", "trace", "merge", "sensor", "stats",
    "report", "run",
];

/// The tools the runner knows, each found program registered with a validator that asks
/// the program itself to check a stage's parameters (`irsig_cli::check_args`: its own clap
/// definition, nothing run), so that an unknown or mistyped parameter is reported at its
/// line and column before any stage runs, and the runner depends on no tool's crate. A tool
/// without a validator still runs; its parameters are then checked only when it starts.
#[must_use]
pub fn tools() -> Tools {
    let mut tools = Tools::new(irsig_cli::find_tool);
    tools.with_sun_flags(irsig_pipeline::SunFlags {
        field: irsig_cli::args::sun::flag,
        day_of_year: irsig_cli::args::DayOfYear::FLAG,
    });
    // irsig-therm's weather record and the year it reads a typical year as: a day's frames
    // are checked against the record before anything runs.
    tools.with_time_flags(irsig_pipeline::TimeFlags {
        weather: "weather",
        weather_year: "weather-year",
    });
    for tool in STAGE_TOOLS {
        if let Some(program) = irsig_cli::find_tool(tool) {
            tools.register(
                tool,
                Box::new(move |argv| irsig_cli::check_args(&program, argv)),
            );
        }
    }
    tools
}

/// Every file a step of `plan` reads or writes, each with what it is, for the emitters: a
/// file they write must be none of them.
pub(crate) fn stage_files(plan: &irsig_pipeline::Plan) -> Vec<(PathBuf, String)> {
    plan.steps
        .iter()
        .flat_map(|step| {
            let input = step.inputs.iter().map(|f| (f, "an input"));
            let output = step.outputs.iter().map(|f| (f, "an output"));
            input.chain(output).map(|(f, role)| {
                (
                    plan.base_dir().join(&f.path),
                    format!("{role} of the pipeline's step `{}`", step.name),
                )
            })
        })
        .collect()
}

/// Runs `irsig-run`.
///
/// # Errors
/// A malformed or inconsistent pipeline file (with its line and column), a failed stage,
/// or an unwritable Makefile.
pub fn run(cli: Cli) -> miette::Result<()> {
    if let Some(dir) = &cli.emit_slurm {
        return slurm::emit(&cli, dir);
    }
    let pipeline = Pipeline::load(&cli.pipeline)?;
    let plan = if cli.step.is_some() {
        pipeline.plan_for_single_steps(&tools())?
    } else {
        pipeline.plan(&tools())?
    };
    if let Some(path) = &cli.emit_makefile {
        irsig_cli::refuse_output_is_input([&cli.pipeline], [path])?;
        irsig_cli::refuse_output_is_named(&stage_files(&plan), [path])?;
        let text = plan.makefile()?;
        return irsig_cli::write_output(Some(path), |w| w.write_all(text.as_bytes()));
    }
    if cli.dry_run {
        let text = plan.dry_run_script(cli.force)?;
        return irsig_cli::write_output(None, |w| w.write_all(text.as_bytes()));
    }
    let jobs = cli.threads.count();
    let quiet = cli.quiet;
    let report = move |event: Event<'_>| {
        if quiet {
            return;
        }
        match event {
            Event::UpToDate(step) => irsig_cli::note!("  up to date  {}", step.described()),
            Event::Started(step) => {
                irsig_cli::note!(
                    "     running  {}: {}",
                    step.described(),
                    step.command_line()
                );
            }
            _ => {}
        }
    };
    let summary = match &cli.step {
        Some(name) => plan.run_step_named(name, cli.force, &report)?,
        None => plan.run(
            RunOptions {
                jobs,
                force: cli.force,
            },
            &report,
        )?,
    };
    if !quiet {
        irsig_cli::note!(
            "irsig-run: {} stage(s) ran, {} up to date",
            summary.ran,
            summary.up_to_date
        );
    }
    Ok(())
}
