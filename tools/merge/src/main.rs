use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_merge::run(irsig_cli::parse()))
}
