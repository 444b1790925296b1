use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_run::run(irsig_cli::parse()))
}
