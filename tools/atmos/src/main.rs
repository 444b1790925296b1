use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_atmos::run(irsig_cli::parse()))
}
