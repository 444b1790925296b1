//! `irsig <stage> [args...]` runs `irsig-<stage> [args...]`, as `git` and `cargo` run their
//! subcommands. The stage binary is looked up first beside this executable, then on `PATH`.
//!
//! ```text
//! irsig trace --help          # same as irsig-trace --help
//! irsig --version             # version, and the stages found
//! ```

use std::ffi::OsString;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::{Command, ExitCode};

/// The stages, in pipeline order.
const STAGES: &[&str] = &[
    "import", "flatten", "atmos", "material", "therm", "trace", "merge", "sensor", "stats",
    "report", "run",
];

const USAGE: &str = "\
irsig: radiometric thermal-infrared (3-5 and 8-14 um) synthetic imagery

Usage: irsig <STAGE> [ARGS...]
       irsig --version | --help

Stages (each is also a program of its own, irsig-<STAGE>):
  import    Intergraph facet files, OBJ (+MTL), glTF/GLB -> canonical objects
  flatten   scene + objects -> raw world-space scene
  atmos     LOWTRAN7 plans and builds, the sun's position, DIRTRAN tables <->
            canonical atmosphere, band radiance calculators
  material  material index + .ems <-> material library; Fresnel emissivity
  therm     raw scene + materials + weather -> facet temperatures from a heat balance
  trace     view + raw scene + materials + atmosphere -> radiance image and truth
  merge     the tiles of a frame (trace --tile) -> the frame's images, byte for byte
  sensor    MTF blur, noise, quantisation
  stats     per-region apparent temperature beside reference values (Tables 5-7)
  report    one self-contained HTML page of a run: images, plots, tables, provenance
  run       run a declarative pipeline file (RON)

Example:
  irsig run pipelines/quickstart.ron
  irsig trace --help
";

fn main() -> ExitCode {
    let mut args = std::env::args_os().skip(1);
    let Some(first) = args.next() else {
        eprint!("{USAGE}");
        return ExitCode::from(2);
    };
    match first.to_str() {
        Some("--help" | "-h" | "help") => to_stdout(USAGE),
        Some("--version" | "-V") => {
            let mut text = format!("irsig {}\n", env!("CARGO_PKG_VERSION"));
            for stage in STAGES {
                let _ = match find_stage(stage) {
                    Some(path) => writeln!(text, "  {stage:<8} {}", path.display()),
                    None => writeln!(text, "  {stage:<8} (not found)"),
                };
            }
            to_stdout(&text)
        }
        Some(stage) if !stage.starts_with('-') => run_stage(stage, args.collect()),
        _ => {
            eprintln!(
                "irsig: expected a stage name, found `{}`\n",
                first.to_string_lossy()
            );
            eprint!("{USAGE}");
            ExitCode::from(2)
        }
    }
}

/// Writes `text` to standard output: a reader that closed the pipe has all it wanted
/// (exit 0), any other failure to write is an error.
fn to_stdout(text: &str) -> ExitCode {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("irsig: cannot write to standard output: {e}");
            ExitCode::from(1)
        }
    }
}

fn run_stage(stage: &str, args: Vec<OsString>) -> ExitCode {
    let Some(program) = find_stage(stage) else {
        eprintln!(
            "irsig: no stage `{stage}`: expected one of {} (looked for `irsig-{stage}` beside \
             this program and on PATH)",
            STAGES.join(", ")
        );
        return ExitCode::from(2);
    };
    match Command::new(&program).args(args).status() {
        Ok(status) => match status.code() {
            Some(code) => ExitCode::from(u8::try_from(code).unwrap_or(1)),
            // Killed by a signal: report failure.
            None => ExitCode::from(1),
        },
        Err(e) => {
            eprintln!("irsig: cannot run `{}`: {e}", program.display());
            ExitCode::from(1)
        }
    }
}

/// The path of `irsig-<stage>`: beside this executable first, then on `PATH`.
fn find_stage(stage: &str) -> Option<PathBuf> {
    irsig_cli::find_tool(stage)
}
