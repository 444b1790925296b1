//! `irsig <stage> [args...]` runs `irsig-<stage> [args...]`, as `git` and `cargo` run their
//! subcommands. The stage binary is looked up first beside this executable, then on `PATH`.
//!
//! ```text
//! irsig trace --help          # same as irsig-trace --help
//! irsig --version             # version, and the stages found
//! ```

use std::ffi::OsString;
use std::path::PathBuf;
use std::process::{Command, ExitCode};

/// The stages, in pipeline order.
const STAGES: &[&str] = &[
    "import", "flatten", "atmos", "material", "trace", "sensor", "stats", "report", "run",
];

const USAGE: &str = "\
irsig: radiometric thermal-infrared (8-14 um) synthetic imagery

Usage: irsig <STAGE> [ARGS...]
       irsig --version | --help

Stages (each is also a program of its own, irsig-<STAGE>):
  import    Intergraph facet files, OBJ (+MTL), glTF/GLB -> canonical objects
  flatten   scene + objects -> raw world-space scene
  atmos     DIRTRAN tables <-> canonical atmosphere; band radiance calculators
  material  material index + .ems <-> material library; Fresnel emissivity
  trace     view + raw scene + materials + atmosphere -> radiance image and truth
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
        Some("--help" | "-h" | "help") => {
            print!("{USAGE}");
            ExitCode::SUCCESS
        }
        Some("--version" | "-V") => {
            println!("irsig {}", env!("CARGO_PKG_VERSION"));
            for stage in STAGES {
                match find_stage(stage) {
                    Some(path) => println!("  {stage:<8} {}", path.display()),
                    None => println!("  {stage:<8} (not found)"),
                }
            }
            ExitCode::SUCCESS
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
