//! A trace from Python: `irsig-trace`'s argument list read into a plan by the tool itself
//! (`irsig_trace::plan_of`: the same flags, the same request, the same inputs' checks),
//! rendered here with the GIL released, and each frame's files handed back as bytes.
//!
//! While the plan renders on a thread of its own, the calling thread wakes every
//! [`POLL`] to give a Python callable the rows traced so far and to let Python's signal
//! handlers run: an interrupt (Ctrl-C's `KeyboardInterrupt`) or an exception from the
//! callable stops the rendering: the tracer has no stopping point inside a frame (the rows
//! already handed to its threads are traced), so the run ends with the frame it is on, no
//! further frame is traced or encoded, and nothing is written. When the argument
//! list names outputs (`-o PREFIX` or the per-file flags, `--decision-out`), the files are
//! staged as each frame's bytes arrive and renamed into place together at the end, or none
//! (`irsig_cli::StagedFrames`), exactly as the command line does.

use std::panic::{AssertUnwindSafe, catch_unwind, resume_unwind};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Duration;

use irsig_model::decision::Decision;
use irsig_model::frame::{FrameFile, FrameFiles};
use irsig_render::{Plan, Sink};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::errors::to_py;

/// How often the caller hears of the rendering's progress and Python's signals are checked.
const POLL: Duration = Duration::from_millis(50);

/// What unwinds the rendering when the caller stops it, from the progress of each row
/// traced after: a payload of its own, never a panic message (`resume_unwind` runs no panic
/// hook).
struct Stopped;

/// Traces `irsig-trace`'s `args` (the arguments after the program's name); `progress`, if
/// given, is called with (rows traced, rows in all) from the calling thread as rows are
/// traced, and once more at the end.
///
/// Returns one dict per frame: `files` (file kind to bytes: `radiance.exr`, `truth.exr`,
/// and where the frame makes them `map.png`, `dc.png`, `lut.txt`), `decision` (the pilot's,
/// canonical RON, with `--tolerance`), `band` and `atmosphere` (as the command line spells
/// them, its defaults where not given), `angles_x_deg` and `angles_y_deg` (the pixel
/// centres' angles from the optical axis), and the run's `notes` and `warnings`.
///
/// Raises `IrsigError` for what `irsig-trace` refuses (with file, line and column), and
/// whatever Python raised while it ran (`KeyboardInterrupt`, the callable's exception),
/// once the frame being traced is done.
#[pyfunction]
#[pyo3(signature = (args, progress=None))]
pub(crate) fn trace<'py>(
    py: Python<'py>,
    args: Vec<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let argv = std::iter::once("irsig-trace".to_owned()).chain(args);
    let cli: irsig_trace::Cli = irsig_cli::parse_from(argv).map_err(|e| to_py(&e))?;
    let (plan, wanted) = py.detach(|| prepare(&cli)).map_err(|e| to_py(&e))?;
    let notes = plan.notes();
    let band = cli.band.or_default().to_string();
    let atmosphere = cli.atmosphere.given().unwrap_or("none").to_owned();
    let angles = plan
        .views()
        .iter()
        .map(crate::layers::angles_deg)
        .collect::<miette::Result<Vec<_>>>()
        .map_err(|e| to_py(&e))?;
    let rows = plan
        .rows(None)
        .map_err(|e| to_py(&miette::Report::new(e)))?;
    let mut sink = Collect::new(wanted, staged(&cli, &plan).map_err(|e| to_py(&e))?);
    let pool = cli.threads.pool().map_err(|e| to_py(&e))?;
    let stop = AtomicBool::new(false);
    let done = AtomicU64::new(0);
    let outcome = py.detach(|| {
        std::thread::scope(|s| {
            let worker = s.spawn(|| {
                catch_unwind(AssertUnwindSafe(|| {
                    pool.install(|| {
                        let tick = |n: u64| {
                            if stop.load(Ordering::Relaxed) {
                                resume_unwind(Box::new(Stopped));
                            }
                            done.fetch_add(n, Ordering::Relaxed);
                        };
                        plan.render(None, &tick, &mut sink)
                    })
                }))
            });
            let (mut raised, mut told) = (None, None);
            while !worker.is_finished() {
                std::thread::sleep(POLL);
                if raised.is_none() {
                    // The callable hears of new rows only; the signals are checked each time.
                    let now = done.load(Ordering::Relaxed);
                    let callable = progress.as_ref().filter(|_| told != Some(now));
                    told = Some(now);
                    raised = Python::attach(|py| report(py, callable, now, rows)).err();
                    stop.store(raised.is_some(), Ordering::Relaxed);
                }
            }
            (worker.join(), raised)
        })
    });
    match outcome {
        (_, Some(raised)) => Err(raised),
        (Ok(Ok(Ok(()))), None) => {
            report(py, progress.as_ref(), rows, rows)?;
            sink.finish(
                py,
                &Said {
                    band,
                    atmosphere,
                    notes,
                },
                &angles,
            )
        }
        (Ok(Ok(Err(e))), None) => Err(to_py(&miette::Report::new(e))),
        // A panic of the tracer's is a bug: it surfaces as Python's `PanicException`.
        (Ok(Err(payload)) | Err(payload), None) => resume_unwind(payload),
    }
}

/// Calls `progress(done, rows)` and runs Python's signal handlers.
fn report(py: Python<'_>, progress: Option<&Py<PyAny>>, done: u64, rows: u64) -> PyResult<()> {
    if let Some(callable) = progress {
        callable.call1(py, (done.min(rows), rows))?;
    }
    py.check_signals()
}

/// The plan the arguments make, and which files each frame makes: every kind the frame can
/// make (the map only when the materials' ids fit it), so that Python gets them all.
fn prepare(cli: &irsig_trace::Cli) -> miette::Result<(Plan, Vec<FrameFiles<()>>)> {
    if cli.probe.is_some() || cli.tile.is_some() || cli.execute.is_some() {
        return Err(irsig_cli::usage_error(
            "--probe, --tile and --execute are the command line's: trace the frame and read \
             its layers, or run irsig-trace",
        ));
    }
    cli.output.check_stdout()?;
    let plan = irsig_trace::plan_of(cli)?;
    irsig_trace::fits_in_memory(&plan, None)?;
    let mut wanted = FrameFiles::default();
    for kind in plan.file_kinds(true) {
        wanted.set(kind, ());
    }
    let frames = plan.views().len();
    Ok((plan, vec![wanted; frames]))
}

/// The files the arguments name, checked and ready to stage, as `irsig-trace` names them;
/// `None` when they name none.
fn staged(cli: &irsig_trace::Cli, plan: &Plan) -> miette::Result<Option<Staging>> {
    let out = &cli.output;
    if !(out.prefix.path.is_some() || out.has_files() || cli.decision_out.path.is_some()) {
        return Ok(None);
    }
    let frames = plan.views().len();
    if !plan.map_fits()
        && let Some(path) = &out.map_png
    {
        return Err(miette::miette!(
            "{}: {}",
            path.display(),
            irsig_render::products::map_refusal(plan.max_material_id())
        ));
    }
    let files = out.frames(frames, &plan.file_kinds(true))?;
    let decisions: Vec<Option<PathBuf>> = (0..frames)
        .map(|i| match (&cli.tolerance.kelvin, &cli.decision_out.path) {
            (None, _) => None,
            (Some(_), Some(path)) => Some(path.clone()),
            (Some(_), None) => out.decision_file(i, frames, &files[i]),
        })
        .collect();
    let inputs = [cli.scene.required()?]
        .into_iter()
        .chain(cli.materials.file.as_deref())
        .chain(
            cli.trailing_views
                .files(&cli.views)
                .iter()
                .map(String::as_str),
        )
        .chain(cli.atmosphere.given())
        .chain(cli.decision.file.as_deref())
        .chain(cli.uncertainties.file.as_deref())
        .chain(cli.band.response_file());
    let written = files.iter().flat_map(|f| f.iter().map(|(_, p)| p.clone()));
    irsig_cli::refuse_output_is_input(inputs, written.chain(decisions.iter().flatten().cloned()))?;
    let more: Vec<&std::path::Path> = decisions.iter().flatten().map(PathBuf::as_path).collect();
    let frames = irsig_cli::StagedFrames::new(files, &more)?;
    Ok(Some(Staging { frames, decisions }))
}

/// The files staged for the arguments' outputs, and where each frame's decision goes.
struct Staging {
    frames: irsig_cli::StagedFrames,
    decisions: Vec<Option<PathBuf>>,
}

/// What the run says of every frame: the band and atmosphere as the command line spells
/// them (its defaults where not given) and the plan's notes.
struct Said {
    band: String,
    atmosphere: String,
    notes: Vec<String>,
}

/// One frame's bytes as they arrive.
#[derive(Default)]
struct Frame {
    files: Vec<(FrameFile, Vec<u8>)>,
    decision: Option<String>,
}

/// The sink: every frame's files kept for Python, and staged when outputs are named.
struct Collect {
    wanted: Vec<FrameFiles<()>>,
    frames: Vec<Frame>,
    warnings: Vec<String>,
    staging: Option<Staging>,
}

impl Collect {
    fn new(wanted: Vec<FrameFiles<()>>, staging: Option<Staging>) -> Self {
        let frames = wanted.iter().map(|_| Frame::default()).collect();
        Self {
            wanted,
            frames,
            warnings: Vec::new(),
            staging,
        }
    }

    /// The frames as Python dicts, after the staged files (if any) are renamed into place.
    fn finish<'py>(
        self,
        py: Python<'py>,
        said: &Said,
        angles: &[(Vec<f64>, Vec<f64>)],
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        if let Some(staging) = self.staging {
            py.detach(|| staging.frames.commit())
                .map_err(|e| to_py(&e))?;
        }
        self.frames
            .into_iter()
            .zip(angles)
            .map(|(frame, (x_deg, y_deg))| {
                let dict = PyDict::new(py);
                let files = PyDict::new(py);
                for (kind, bytes) in frame.files {
                    files.set_item(kind.suffix(), PyBytes::new(py, &bytes))?;
                }
                dict.set_item("files", files)?;
                dict.set_item("decision", frame.decision)?;
                dict.set_item("angles_x_deg", x_deg)?;
                dict.set_item("angles_y_deg", y_deg)?;
                dict.set_item("band", &said.band)?;
                dict.set_item("atmosphere", &said.atmosphere)?;
                dict.set_item("notes", said.notes.clone())?;
                dict.set_item("warnings", self.warnings.clone())?;
                Ok(dict)
            })
            .collect()
    }
}

impl Sink for Collect {
    fn files(&self, index: usize) -> FrameFiles<()> {
        self.wanted.get(index).cloned().unwrap_or_default()
    }

    fn decision(&mut self, index: usize, d: &Decision, _seconds: f64) -> miette::Result<()> {
        let text = irsig_formats::canonical::to_ron(d).map_err(|e| miette::miette!("{e}"))?;
        if let Some(staging) = &mut self.staging
            && let Some(path) = staging.decisions.get(index).cloned().flatten()
        {
            staging.frames.stage_other(&path, text.as_bytes())?;
        }
        if let Some(frame) = self.frames.get_mut(index) {
            frame.decision = Some(text);
        }
        Ok(())
    }

    fn file(&mut self, index: usize, kind: FrameFile, bytes: Vec<u8>) -> miette::Result<()> {
        if let Some(staging) = &mut self.staging {
            staging.frames.stage(index, kind, &bytes)?;
        }
        if let Some(frame) = self.frames.get_mut(index) {
            frame.files.push((kind, bytes));
        }
        Ok(())
    }

    fn warning(&mut self, text: &str) {
        self.warnings.push(text.to_owned());
    }
}
