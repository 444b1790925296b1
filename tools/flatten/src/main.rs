use clap::Parser as _;
use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_flatten::run(irsig_flatten::Cli::parse()))
}
