use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_report::run(irsig_report::Cli::parse()))
}
