use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_sensor::run(irsig_sensor::Cli::parse()))
}
