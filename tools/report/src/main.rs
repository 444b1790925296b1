use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_report::run(irsig_cli::parse()))
}
