use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_therm::run(irsig_cli::parse()))
}
