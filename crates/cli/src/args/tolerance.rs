//! `--tolerance K` and `--decision-out FILE`, in every tool that chooses its models'
//! settings for a tolerance (`irsig-trace`: apparent temperature, `irsig-therm`: facet
//! temperature) and writes what it chose. A tool says what K bounds in its help
//! (`mut_arg`) and which of its own flags the choice replaces (`conflicts_with_all`).

use std::path::PathBuf;

/// `--tolerance K`: choose the cheapest models that keep the result within K kelvin of a
/// converged one.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct Tolerance {
    /// Choose the cheapest settings of the models that keep the result within K kelvin of
    /// a converged one; the decision is printed on stderr.
    #[arg(
        id = "tolerance",
        long = "tolerance",
        value_name = "K",
        allow_negative_numbers = true
    )]
    pub kelvin: Option<f64>,
}

/// `--decision-out FILE`: where the decision a tolerance made is written.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct DecisionOut {
    /// With --tolerance, write the decision (canonical RON) to FILE.
    #[arg(
        id = "decision_out",
        long = "decision-out",
        value_name = "FILE",
        requires = "tolerance"
    )]
    pub path: Option<PathBuf>,
}
