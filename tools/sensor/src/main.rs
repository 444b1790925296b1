use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_sensor::run(irsig_cli::parse()))
}
