use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_stats::run(irsig_cli::parse()))
}
