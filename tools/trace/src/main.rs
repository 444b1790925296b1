use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_trace::run(irsig_trace::Cli::parse()))
}
