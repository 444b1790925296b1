//! What every irsig tool shares, so that all of them behave alike at the command line.
//!
//! - **Input** is a path, or `-` for stdin ([`read_input`]). The bytes come back with the
//!   name diagnostics should print (`<stdin>` for standard input).
//! - **Output** goes to `-o FILE` or to stdout ([`write_output`]). A file is written to a
//!   temporary file beside its destination and renamed into place only when complete, so a
//!   failure never leaves a partial file.
//! - **Exit codes** ([`run`]): 0 for success, 1 for bad input, 2 for bad usage. clap already
//!   exits with 2 on a malformed command line; a tool signals a semantic usage error (two
//!   options that contradict each other) with [`usage_error`]. A closed pipe on stdout counts
//!   as success, as it does for `head` and ripgrep.
//! - **Progress** ([`progress_bar`]) is drawn on stderr only when stderr is a terminal;
//!   notes and warnings go through [`note!`], which never panics on a closed stderr.
//! - **No output is an input** ([`refuse_output_is_input`]): one check every tool makes
//!   before any work.
//!
//! - **Memory** ([`memory::check_fits`]): an estimate checked against what the process may
//!   still take before a large allocation, refused with both figures and the way out.
//!
//! - **Shared flags** ([`args`]): every flag two tools share, defined once (the band, the
//!   sun, the views and the unit of 1990 files, the atmosphere, threads, the digital-count
//!   calibration, the inputs and outputs several tools name), spelt, typed and checked the
//!   same in every tool.
//!
//! This is the only library crate that knows about processes, exit codes and terminals.
//!
//! ```no_run
//! use std::process::ExitCode;
//! fn main() -> ExitCode {
//!     irsig_cli::run(|| {
//!         let input = irsig_cli::read_input("-")?;
//!         irsig_cli::write_output(None, |w| w.write_all(&input.bytes))?;
//!         Ok(())
//!     })
//! }
//! # use std::io::Write;
//! ```

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![deny(clippy::print_stdout, clippy::print_stderr)]

pub mod args;
mod frames;
pub mod memory;
mod staged;

pub use frames::StagedFrames;
pub use staged::{
    ScratchDir, Staged, check_output, remove_staged_files, remove_staged_files_and_exit,
    write_dir_atomic,
};

use std::fs::File;
use std::io::{self, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use irsig_formats::file::FileId;
use miette::{Diagnostic, IntoDiagnostic, Report, WrapErr};

/// Writes one line to standard error, as `eprintln!` does, but never panics: a closed or
/// broken stderr (`tool 2>&1 | head -c1`) loses the line, and the tool goes on and exits
/// with its own status. Every tool prints its notes and warnings through it.
///
/// ```
/// irsig_cli::note!("irsig-demo: warning: {} facets have no material", 3);
/// ```
#[macro_export]
macro_rules! note {
    ($($arg:tt)*) => {
        $crate::write_stderr_line(::std::format_args!($($arg)*))
    };
}

/// What [`note!`] calls: the line, then a newline, in one write; errors ignored.
#[doc(hidden)]
pub fn write_stderr_line(args: std::fmt::Arguments<'_>) {
    let mut line = args.to_string();
    line.push('\n');
    let _ = io::stderr().lock().write_all(line.as_bytes());
}

/// Refuses a command line that names one of its inputs as an output: writing the output
/// would replace the file being read (`irsig-sensor a.exr -o a.exr`), and the input would
/// be lost whatever the outcome. Every tool calls it with all the files it reads (those
/// named on its command line and those it finds named inside them) and all the files it
/// writes, before any work; [`Staged`], the one writer, makes the same check again against
/// every file the process has read ([`irsig_formats::file::files_read`]) when an output is
/// staged, so a file found named inside an input (an `mtllib`) is never replaced either.
///
/// Two names are one file when both exist and are the same file (device and inode on
/// Unix, so a symbolic or hard link, `./a` and `d/../a` are all caught; the canonical path
/// elsewhere). `-` as an output (standard output) is never compared; `-` as an input is
/// standard input, compared when it is redirected from a regular file (`tool - -o a.exr <
/// a.exr`). An output that is a device or a socket (`-o /dev/null`) is written in place,
/// never replaced. A name that does not exist yet is no input of the run.
///
/// ```no_run
/// # fn main() -> miette::Result<()> {
/// irsig_cli::refuse_output_is_input(["radiance.exr", "band.srf"], ["sensor.exr", "-"])?;
/// # Ok(()) }
/// ```
///
/// # Errors
/// A usage error (exit code 2) naming the output and the input it is.
pub fn refuse_output_is_input<I, O>(inputs: I, outputs: O) -> miette::Result<()>
where
    I: IntoIterator,
    I::Item: AsRef<Path>,
    O: IntoIterator,
    O::Item: AsRef<Path>,
{
    let inputs: Vec<(PathBuf, FileId)> = inputs
        .into_iter()
        .filter_map(|p| {
            let p = p.as_ref();
            let id = if p.as_os_str() == "-" {
                stdin_file()
            } else {
                FileId::of(p)
            };
            Some((p.to_path_buf(), id?))
        })
        .collect();
    for output in outputs {
        refuse_output_among(output.as_ref(), &inputs)?;
    }
    Ok(())
}

/// Refuses an output that is one of the files another program of the run reads or writes:
/// a pipeline's stage files, which `irsig-run --emit-makefile` and `--emit-slurm` must not
/// write over (a stage's input replaced by the Makefile, or a stage's output that `make`
/// would then write over the Makefile). `files` pairs each such file with what it is, for
/// the message (`an input of stage trace`). Two names are one file when both exist and are
/// the same file, or when they name the same entry of the same real directory (a file not
/// made yet).
///
/// # Errors
/// A usage error (exit code 2) naming the output and what it also is.
pub fn refuse_output_is_named<O>(files: &[(PathBuf, String)], outputs: O) -> miette::Result<()>
where
    O: IntoIterator,
    O::Item: AsRef<Path>,
{
    let keys: Vec<(PathBuf, Option<FileId>, &(PathBuf, String))> = files
        .iter()
        .map(|f| (name_key(&f.0), FileId::of(&f.0), f))
        .collect();
    for output in outputs {
        let output = output.as_ref();
        if output.as_os_str() == "-" || written_in_place(output) {
            continue;
        }
        let (key, id) = (name_key(output), FileId::of(output));
        let clash = keys
            .iter()
            .find(|(k, i, _)| *k == key || matches!((i, &id), (Some(a), Some(b)) if a == b));
        if let Some((_, _, (path, what))) = clash {
            let alias = if path == output {
                String::new()
            } else {
                format!(" (`{}`)", path.display())
            };
            return Err(usage_error(format!(
                "`{}` is this command's output and also {what}{alias}: writing it would \
                 replace that file; name another output",
                output.display(),
            )));
        }
    }
    Ok(())
}

/// `path` as an entry of its real directory (the directory's symbolic links resolved), or,
/// when the directory does not exist, made absolute and cleaned of `.` and `..` by name.
fn name_key(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut clean = PathBuf::new();
    for part in absolute.components() {
        match part {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                clean.pop();
            }
            other => clean.push(other),
        }
    }
    match (clean.parent(), clean.file_name()) {
        (Some(dir), Some(name)) => {
            std::fs::canonicalize(dir).map_or(clean.clone(), |d| d.join(name))
        }
        _ => clean,
    }
}

/// The regular file standard input is redirected from, if it is one.
fn stdin_file() -> Option<FileId> {
    #[cfg(unix)]
    {
        use std::os::fd::AsFd as _;
        let file = File::from(io::stdin().as_fd().try_clone_to_owned().ok()?);
        FileId::of_regular_file(&file)
    }
    #[cfg(not(unix))]
    {
        None
    }
}

/// A usage error when `output` is one of `inputs` (and not `-`, a device or a socket).
pub(crate) fn refuse_output_among(
    output: &Path,
    inputs: &[(PathBuf, FileId)],
) -> miette::Result<()> {
    if output.as_os_str() == "-" || written_in_place(output) {
        return Ok(());
    }
    let Some(id) = FileId::of(output) else {
        return Ok(());
    };
    if let Some((input, _)) = inputs.iter().find(|(_, i)| *i == id) {
        let alias = if input.as_os_str() == "-" {
            " (standard input is read from it)".to_owned()
        } else if input == output {
            String::new()
        } else {
            format!(" (`{}` is `{}`)", output.display(), input.display())
        };
        return Err(usage_error(format!(
            "`{}` is both an output and an input{alias}: writing it would replace the file \
             being read; name another output",
            output.display()
        )));
    }
    Ok(())
}

/// Whether `path` is a device or a socket: an output there is written in place.
fn written_in_place(path: &Path) -> bool {
    let Ok(meta) = std::fs::metadata(path) else {
        return false;
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        let kind = meta.file_type();
        kind.is_char_device() || kind.is_block_device() || kind.is_socket()
    }
    #[cfg(not(unix))]
    {
        !meta.is_file() && !meta.is_dir()
    }
}

/// Exit code for success.
pub const EXIT_OK: u8 = 0;
/// Exit code for bad input: a malformed, missing or out-of-range input file or value.
pub const EXIT_BAD_INPUT: u8 = 1;
/// Exit code for bad usage: a command line that cannot be carried out as written.
pub const EXIT_USAGE: u8 = 2;

/// The bytes of one input, with the name diagnostics print for it.
#[derive(Debug, Clone)]
pub struct Input {
    /// The path as the user gave it, or `<stdin>`.
    pub name: String,
    /// The path, or `None` for stdin. Relative references inside the input (an OBJ's
    /// `mtllib`, a scene's object files) resolve against its parent directory.
    pub path: Option<PathBuf>,
    /// The whole content.
    pub bytes: Vec<u8>,
}

impl Input {
    /// `sha256:` and the 64 hex digits of the input's bytes: how a record of provenance
    /// names its content.
    #[must_use]
    pub fn sha256(&self) -> String {
        sha256_hex(&self.bytes)
    }

    /// The directory relative references inside this input resolve against: the file's
    /// parent directory, or the working directory for stdin.
    #[must_use]
    pub fn base_dir(&self) -> PathBuf {
        self.path
            .as_deref()
            .and_then(Path::parent)
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
    }
}

/// `sha256:` and the 64 hex digits of `bytes`.
#[must_use]
pub fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest as _;
    let digest = sha2::Sha256::digest(bytes);
    let mut hex = String::with_capacity(7 + 64);
    hex.push_str("sha256:");
    for b in digest {
        hex.push_str(&format!("{b:02x}"));
    }
    hex
}

/// The provenance an image records (`irsig_formats::canonical::provenance_of` of its
/// comments), `name` naming it in messages; `None` for an image that records none.
///
/// # Errors
/// Comments that claim to be a provenance and are not one.
pub fn provenance(
    name: &str,
    raster: &irsig_raster::Raster,
) -> miette::Result<Option<irsig_model::provenance::Provenance>> {
    match raster
        .comments
        .as_deref()
        .and_then(|c| irsig_formats::canonical::provenance_of(name, c))
    {
        Some(Ok(p)) => Ok(Some(p)),
        Some(Err(e)) => Err(miette::Report::new(e)),
        None => Ok(None),
    }
}

/// Reads a whole input: the file at `path`, or stdin when `path` is `-`.
///
/// Reads through [`irsig_formats::file`]: only a regular file or a pipe, at most
/// [`irsig_formats::file::MAX_INPUT_BYTES`].
///
/// # Errors
/// A missing or unreadable file, a device or directory, or an input longer than the limit,
/// reported with its name.
pub fn read_input(path: impl AsRef<Path>) -> miette::Result<Input> {
    let path = path.as_ref();
    if path.as_os_str() == "-" {
        if let Some(id) = stdin_file() {
            irsig_formats::file::record_read(Path::new("-"), id);
        }
        let bytes = irsig_formats::file::read_bounded(io::stdin().lock())
            .into_diagnostic()
            .wrap_err("cannot read standard input")?;
        return Ok(Input {
            name: "<stdin>".to_owned(),
            path: None,
            bytes,
        });
    }
    let bytes = irsig_formats::file::read_file(path)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot read input file `{}`", path.display()))?;
    Ok(Input {
        name: path.display().to_string(),
        path: Some(path.to_path_buf()),
        bytes,
    })
}

/// [`read_input`] of `path` when it is `-` or names something that exists; `None` when no
/// file of that name exists (a caller that also takes names of other things, such as a
/// built-in atmosphere's, says what it expected).
///
/// # Errors
/// As [`read_input`].
pub fn read_input_if_any(path: impl AsRef<Path>) -> miette::Result<Option<Input>> {
    let path = path.as_ref();
    if path.as_os_str() != "-" && !path.exists() {
        return Ok(None);
    }
    read_input(path).map(Some)
}

/// Decodes an EXR input (`name` for messages), or an error at its byte offset: the
/// reader every tool that takes an image shares.
///
/// # Errors
/// Bytes that are not a readable EXR, at the offset where they stop being one.
pub fn read_exr(name: &str, bytes: &[u8]) -> miette::Result<irsig_raster::Raster> {
    irsig_raster::read_exr(bytes).map_err(|e| exr_error(name, bytes, &e))
}

/// An EXR input's header only (its size and layers), as [`read_exr`].
///
/// # Errors
/// As [`read_exr`], for the header.
pub fn read_exr_info(name: &str, bytes: &[u8]) -> miette::Result<irsig_raster::RasterInfo> {
    irsig_raster::read_exr_info(bytes).map_err(|e| exr_error(name, bytes, &e))
}

fn exr_error(name: &str, bytes: &[u8], e: &irsig_raster::RasterError) -> Report {
    Report::new(irsig_formats::ParseError::in_binary(
        name,
        irsig_raster::exr_error_offset(bytes, e),
        format!("not a readable EXR: {e}"),
    ))
}

/// Writes one output: to `path` atomically (temporary file + rename), or to stdout when
/// `path` is `None` or `-`.
///
/// The writer is buffered. If `write` fails, the temporary file is removed and the
/// destination is left as it was.
///
/// # Errors
/// Any I/O error from `write`, from creating the temporary file or from the rename.
pub fn write_output(
    path: Option<&Path>,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> miette::Result<()> {
    match path {
        None => write_stdout(write),
        Some(p) if p.as_os_str() == "-" => write_stdout(write),
        Some(p) => write_file_atomic(p, write),
    }
}

pub(crate) fn write_stdout(
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> miette::Result<()> {
    let stdout = io::stdout();
    let mut w = io::BufWriter::new(stdout.lock());
    match write(&mut w).and_then(|()| w.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Err(Report::new(ClosedStdout)),
        r => r
            .into_diagnostic()
            .wrap_err("cannot write to standard output"),
    }
}

/// The reader of standard output closed it (`tool | head`): it has all it wanted, and
/// [`run`] exits with success.
#[derive(Debug, thiserror::Error, Diagnostic)]
#[error("standard output was closed by its reader")]
pub struct ClosedStdout;

/// Writes `path` atomically: a temporary file in the same directory, renamed on success.
///
/// # Errors
/// Any I/O error, or `path` is a directory; the destination is then untouched.
pub fn write_file_atomic(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> miette::Result<()> {
    let mut staged = Staged::new();
    staged.stage_with(path, write)?;
    staged.commit()
}

/// Writes several outputs so that either all of them appear or none does (see [`Staged`]).
/// One output may be `-`, standard output: it is written last, after every file is in place.
///
/// # Errors
/// Any I/O error, a destination that is a directory, the same output named twice, or more
/// than one output named `-`; every destination is then as it was.
pub fn write_files_atomic(files: &[(PathBuf, Vec<u8>)]) -> miette::Result<()> {
    let mut staged = Staged::new();
    for (path, bytes) in files {
        staged.stage(path, bytes)?;
    }
    staged.commit()
}

/// Opens a file for reading with an error that names it.
///
/// # Errors
/// A missing or unreadable file.
pub fn open(path: &Path) -> miette::Result<File> {
    File::open(path)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot open `{}`", path.display()))
}

/// The hidden first argument with which `irsig-run` asks a tool only to check its command
/// line ([`parse`]): exit 0 when clap accepts the rest, else clap's message and exit 2.
pub const CHECK_ARGS: &str = "--irsig-check-args";

/// What a tool refuses of its command line from the flags alone, before it reads a file: a
/// value out of its range (a sun below the horizon, a NaN), a flag given twice that may be
/// given once, flags that contradict each other. [`parse`] runs it after clap, and so does
/// the check `irsig-run` asks of a stage ([`CHECK_ARGS`]), so a pipeline's stage is refused
/// by the tool's own rules before anything runs, not when the stage starts.
pub trait CheckArgs {
    /// The flags' own rules.
    ///
    /// # Errors
    /// A usage error naming the flag (`--sun-zenith-deg 95: …`).
    fn check_args(&self) -> miette::Result<()> {
        Ok(())
    }
}

/// The tool's command line, parsed by its clap `Cli` (exit 2 and clap's message when it is
/// malformed), then checked by its own rules ([`CheckArgs`]; exit 2 and the message). With
/// [`CHECK_ARGS`] first, only that: the process ends after the check, so that the pipeline
/// runner checks a stage's parameters with the tool's own definition without depending on
/// the tool's crate.
#[must_use]
pub fn parse<C: clap::Parser + CheckArgs>() -> C {
    let mut args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    if args.get(1).is_some_and(|a| a == CHECK_ARGS) {
        args.remove(1);
        match C::try_parse_from(args) {
            Ok(cli) => match cli.check_args() {
                Ok(()) => std::process::exit(i32::from(EXIT_OK)),
                Err(report) => {
                    // One paragraph, as clap's own complaints start: the runner quotes it.
                    note!("error: {report}");
                    std::process::exit(i32::from(EXIT_USAGE))
                }
            },
            Err(e) => e.exit(),
        }
    }
    let cli = C::parse();
    if let Err(report) = cli.check_args() {
        // As `run` reports it (a bad value is bad input, a contradiction bad usage); nothing
        // is staged yet.
        note!("{report:?}");
        let code = if report.downcast_ref::<UsageError>().is_some() {
            EXIT_USAGE
        } else {
            EXIT_BAD_INPUT
        };
        std::process::exit(i32::from(code));
    }
    cli
}

/// The tool's command line from `argv` (the program's name first), parsed by its clap `Cli`
/// and checked by its own rules ([`CheckArgs`]) as [`parse`] does, for a caller in this
/// process (the Python package): a malformed line is a usage error carrying clap's message,
/// never an exit.
///
/// # Errors
/// Clap's complaint (with `--help` and `--version`, their text) or the tool's own check.
pub fn parse_from<C: clap::Parser + CheckArgs>(
    argv: impl IntoIterator<Item = String>,
) -> miette::Result<C> {
    let cli = C::try_parse_from(argv).map_err(|e| usage_error(e.render().to_string()))?;
    cli.check_args()?;
    Ok(cli)
}

/// Checks `argv` (the program's name first) with the tool at `program`, as [`parse`] does:
/// `Ok` when the tool accepts it, else clap's message. A program that does not know
/// [`CHECK_ARGS`] cannot be asked, and is checked only when it runs (`Ok`).
///
/// # Errors
/// The tool's complaint, or a program that cannot be started.
pub fn check_args(program: &Path, argv: &[String]) -> Result<(), String> {
    let out = std::process::Command::new(program)
        .arg(CHECK_ARGS)
        .args(argv.iter().skip(1))
        .stdin(std::process::Stdio::null())
        .output()
        .map_err(|e| format!("cannot start `{}`: {e}", program.display()))?;
    if out.status.success() {
        return Ok(());
    }
    let message = String::from_utf8_lossy(&out.stderr).into_owned();
    if message.contains(&format!("'{CHECK_ARGS}'")) {
        return Ok(());
    }
    Err(message)
}

/// A command line that is well formed but cannot be carried out as written (exit code 2).
#[derive(Debug, thiserror::Error, Diagnostic)]
#[error("{0}")]
#[diagnostic(code(irsig::usage))]
pub struct UsageError(pub String);

/// Builds a usage error: [`run`] exits with code 2 for it.
#[must_use]
pub fn usage_error(message: impl Into<String>) -> Report {
    Report::new(UsageError(message.into()))
}

/// Runs a tool's body and turns its outcome into the process exit code.
///
/// Errors are printed to stderr with miette (source snippets with file, line and column
/// where the error carries them). A broken pipe on stdout is success.
// The one place a tool's error reaches the terminal.
#[allow(clippy::print_stderr)]
pub fn run(body: impl FnOnce() -> miette::Result<()>) -> ExitCode {
    // An interrupted run leaves no staged `.irsig-*.tmp` file behind. Setting the handler
    // fails only when one is already set (a tool that runs another tool's body in-process).
    let _ = ctrlc::set_handler(|| remove_staged_files_and_exit(130));
    // In a log or a pipe a message stays on one line, whatever the length of its path, so
    // that `grep` finds it; on a terminal miette wraps it to the window.
    let wrap = io::stderr().is_terminal();
    let _ = miette::set_hook(Box::new(move |_| {
        Box::new(miette::MietteHandlerOpts::new().wrap_lines(wrap).build())
    }));
    match body() {
        Ok(()) => ExitCode::from(EXIT_OK),
        Err(report) => {
            if is_broken_pipe(&report) {
                return ExitCode::from(EXIT_OK);
            }
            let code = if report.downcast_ref::<UsageError>().is_some() {
                EXIT_USAGE
            } else {
                EXIT_BAD_INPUT
            };
            // A closed or broken stderr loses the message, not the exit status.
            note!("{report:?}");
            ExitCode::from(code)
        }
    }
}

fn is_broken_pipe(report: &Report) -> bool {
    report.chain().any(|e| {
        e.is::<ClosedStdout>()
            || e.downcast_ref::<io::Error>()
                .is_some_and(|io| io.kind() == io::ErrorKind::BrokenPipe)
    })
}

/// True when standard output is a pipe or a socket (`tool | next-tool`), not a terminal and
/// not a file a shell redirection opened. Tools use it to pick a compact binary form for
/// data that flows into another tool and a readable one for what a person will open.
#[must_use]
pub fn stdout_is_pipe() -> bool {
    #[cfg(unix)]
    {
        use std::os::fd::AsFd as _;
        use std::os::unix::fs::FileTypeExt as _;
        // fstat on a duplicate of fd 1; the duplicate is closed when `file` drops.
        io::stdout()
            .as_fd()
            .try_clone_to_owned()
            .map(File::from)
            .and_then(|file| file.metadata())
            .is_ok_and(|m| m.file_type().is_fifo() || m.file_type().is_socket())
    }
    #[cfg(not(unix))]
    {
        false
    }
}

/// A progress bar on stderr, drawn only when stderr is a terminal, so that logs and pipes
/// stay clean.
#[must_use]
pub fn progress_bar(len: u64, message: &str) -> indicatif::ProgressBar {
    if !io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{msg:>12} [{bar:40}] {pos}/{len} ({eta} left)")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_message(message.to_owned());
    bar
}

/// The path of the stage program `irsig-<tool>`: beside the running executable first (a cargo
/// build or an install directory), then on `PATH`. The umbrella `irsig` and the pipeline
/// runner share this lookup, so both run the same program a user would.
#[must_use]
pub fn find_tool(tool: &str) -> Option<PathBuf> {
    let name = format!("irsig-{tool}{}", std::env::consts::EXE_SUFFIX);
    let beside = std::env::current_exe()
        .ok()
        .and_then(|exe| exe.parent().map(|d| d.join(&name)));
    if let Some(p) = beside.filter(|p| is_file(p)) {
        return Some(p);
    }
    std::env::var_os("PATH").and_then(|path| {
        std::env::split_paths(&path)
            .map(|dir| dir.join(&name))
            .find(|p| is_file(p))
    })
}

fn is_file(p: &Path) -> bool {
    p.metadata().is_ok_and(|m| m.is_file())
}

#[cfg(test)]
mod tests;
