//! `irsig-atmos`: the atmosphere stage's tools. One subcommand per module.
//!
//! - `convert` ([`convert`]): legacy DIRTRAN tables (`.atm .cor .dwr .rtt .rsd`) to and
//!   from the canonical atmosphere file, units stated, every table validated.
//!
//! ```text
//! irsig-atmos convert --atm us.atm --dwr us.dwr --altitude-unit km \
//!     --radiance-unit W/cm2/sr --name us -o us.ron
//! ```

pub mod convert;

use clap::{Parser, Subcommand};

/// Atmosphere tables and radiometry calculators.
#[derive(Debug, Parser)]
#[command(
    name = "irsig-atmos",
    version,
    about,
    after_help = "\
Example:
  irsig-atmos convert --to-legacy builtin:us-std-1976 --altitude-unit km \\
      --radiance-unit W/cm2/sr --out-dir /tmp"
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// DIRTRAN tables <-> canonical atmosphere, validated, units stated.
    Convert(convert::ConvertArgs),
}

/// Runs the tool.
///
/// # Errors
/// Whatever the subcommand reports: bad input (exit 1) or bad usage (exit 2).
pub fn run(cli: Cli) -> miette::Result<()> {
    match cli.command {
        Command::Convert(args) => convert::run(&args),
    }
}
