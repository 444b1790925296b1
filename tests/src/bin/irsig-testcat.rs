//! `irsig-testcat`: a test-only stage tool for the pipeline runner's end-to-end tests
//! (`tests/tests/pipeline_runner.rs`). It concatenates its input files to `-o FILE`
//! (stdout by default), written atomically as every irsig tool writes, and exits 1 when an
//! input is missing and 2 on a malformed command line, as every irsig tool does.
//!
//! Test hooks, none of which touch the output: `--log FILE` appends the output's name to
//! FILE each run (to count runs); `--touch FILE` creates FILE on start and `--wait-for FILE`
//! waits up to 20 s for FILE to appear (two stages that wait for each other prove they run
//! at the same time); `--copy-stdin` copies standard input into the output as it comes, so
//! the output is being written for as long as stdin stays open (an interrupt test);
//! `--stage-many N` writes the output N times more, to `OUT.1` … `OUT.N`, all staged
//! together and committed at once (an interrupt at any moment of staging or renaming);
//! `--warn TEXT` writes `irsig-testcat: warning: TEXT` on stderr, as a tool's warning.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::{Duration, Instant};

use clap::Parser;
use miette::{IntoDiagnostic, WrapErr};

#[derive(Debug, Parser)]
#[command(name = "irsig-testcat")]
struct Cli {
    /// Files to concatenate, in order.
    inputs: Vec<String>,
    /// Output file (stdout when absent or `-`).
    #[arg(short)]
    o: Option<PathBuf>,
    /// Text written before the inputs.
    #[arg(long)]
    prefix: Option<String>,
    /// Writes the inputs in upper case.
    #[arg(long)]
    upper: bool,
    /// Appends a line to this file every time the tool runs.
    #[arg(long)]
    log: Option<PathBuf>,
    /// Creates this file when the tool starts.
    #[arg(long)]
    touch: Option<PathBuf>,
    /// Waits (at most 20 s) for this file to exist before writing.
    #[arg(long)]
    wait_for: Option<PathBuf>,
    /// Copies standard input into the output after the inputs, while the output is staged.
    #[arg(long)]
    copy_stdin: bool,
    /// Writes this warning on stderr.
    #[arg(long, value_name = "TEXT")]
    warn: Option<String>,
    /// Also writes the output to OUT.1 … OUT.N, all in one all-or-nothing commit.
    #[arg(long, value_name = "N", requires = "o")]
    stage_many: Option<usize>,
}

impl irsig_cli::CheckArgs for Cli {}

fn main() -> ExitCode {
    irsig_cli::run(|| run(irsig_cli::parse()))
}

fn run(cli: Cli) -> miette::Result<()> {
    if let Some(t) = &cli.touch {
        std::fs::write(t, b"").into_diagnostic()?;
    }
    if let Some(w) = &cli.warn {
        eprintln!("irsig-testcat: warning: {w}");
    }
    let mut bytes = cli.prefix.clone().unwrap_or_default().into_bytes();
    for input in &cli.inputs {
        bytes.extend(irsig_cli::read_input(input)?.bytes);
    }
    if cli.upper {
        bytes.make_ascii_uppercase();
    }
    if let Some(w) = &cli.wait_for {
        let start = Instant::now();
        while !w.exists() {
            if start.elapsed() > Duration::from_secs(20) {
                miette::bail!("gave up waiting for `{}`", w.display());
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    }
    if let Some(log) = &cli.log {
        let mut f = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(log)
            .into_diagnostic()
            .wrap_err("cannot open the log")?;
        let name = cli
            .o
            .as_ref()
            .map_or_else(|| "-".to_owned(), |p| p.display().to_string());
        writeln!(f, "{name}").into_diagnostic()?;
    }
    if let (Some(n), Some(o)) = (cli.stage_many, &cli.o) {
        let mut staged = irsig_cli::Staged::new();
        staged.stage(o, &bytes)?;
        for i in 1..=n {
            let mut name = o.clone().into_os_string();
            name.push(format!(".{i}"));
            staged.stage(std::path::Path::new(&name), &bytes)?;
        }
        return staged.commit();
    }
    irsig_cli::write_output(cli.o.as_deref(), |w| {
        w.write_all(&bytes)?;
        if cli.copy_stdin {
            w.flush()?;
            std::io::copy(&mut std::io::stdin().lock(), w)?;
        }
        Ok(())
    })
}
