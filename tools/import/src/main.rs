use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_import::run(irsig_cli::parse()))
}
