use std::process::ExitCode;

fn main() -> ExitCode {
    irsig_cli::run(|| irsig_material::run(irsig_cli::parse()))
}
