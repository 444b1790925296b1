use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_trace::run(irsig_cli::parse()))
}
