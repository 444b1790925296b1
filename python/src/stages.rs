//! The stages other than the trace, each its tool's own body run in this process: the
//! argument list parsed and checked by the tool's `Cli` (`irsig_cli::parse_from`) and
//! handed to the tool's `run`, with the GIL released. Their logic lives in the tool crates
//! (the flattening's object loading and error places, the sensor's chain and outputs, the
//! thermal run's wiring), so this is the one way to run the same model without a second
//! copy of it. Files are written as the tool writes them: staged and renamed into place
//! together, or none.

use pyo3::prelude::*;

use crate::errors::to_py;

/// The stages `run_stage` runs, by the name `irsig-<stage>` is run as.
pub(crate) const STAGES: [&str; 9] = [
    "flatten", "import", "atmos", "material", "therm", "sensor", "stats", "merge", "report",
];

/// Runs `irsig-<stage>` with `args` (the arguments after the program's name) in this
/// process, the GIL released.
///
/// Raises `IrsigError` for what the command line would refuse, with its file, line and
/// column, and `ValueError` for a stage that is not one of `STAGES`.
#[pyfunction]
pub(crate) fn run_stage(py: Python<'_>, stage: &str, args: Vec<String>) -> PyResult<()> {
    if !STAGES.contains(&stage) {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "no stage `{stage}`: one of {}",
            STAGES.join(", ")
        )));
    }
    let argv: Vec<String> = std::iter::once(format!("irsig-{stage}"))
        .chain(args)
        .collect();
    py.detach(|| run(stage, argv)).map_err(|e| to_py(&e))
}

fn run(stage: &str, argv: Vec<String>) -> miette::Result<()> {
    use irsig_cli::parse_from;
    match stage {
        "flatten" => irsig_flatten::run(parse_from(argv)?),
        "import" => irsig_import::run(parse_from(argv)?),
        "atmos" => irsig_atmos::run(parse_from(argv)?),
        "material" => irsig_material::run(parse_from(argv)?),
        "therm" => irsig_therm::run(parse_from(argv)?),
        "sensor" => irsig_sensor::run(parse_from(argv)?),
        "stats" => irsig_stats::run(parse_from(argv)?),
        "merge" => irsig_merge::run(parse_from(argv)?),
        "report" => irsig_report::run(parse_from(argv)?),
        other => Err(miette::miette!("no stage `{other}`")),
    }
}
