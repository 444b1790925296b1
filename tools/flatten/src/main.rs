use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_flatten::run(irsig_cli::parse()))
}
