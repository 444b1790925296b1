use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_merge::run(irsig_merge::Cli::parse()))
}
