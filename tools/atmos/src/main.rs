use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_atmos::run(irsig_atmos::Cli::parse()))
}
