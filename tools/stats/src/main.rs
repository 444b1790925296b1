use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_stats::run(irsig_stats::Cli::parse()))
}
