//! irsig-python: the extension module `irsig._irsig` of the Python package `irsig`
//! (`python/irsig/`), built by maturin.
//!
//! It holds conversion only. A trace is the tracer's command line given as an argument list
//! (`irsig_trace::Cli`, so every option the command has is the same option here, defined
//! once), read into an `irsig_render::Plan` by the tool's own `plan_of` and rendered here:
//! with the GIL released, progress reported to a Python callable, an interrupt (Ctrl-C)
//! honoured within the frame being traced, and the frame's files handed back as bytes (and staged and
//! renamed into place exactly as `irsig-trace` does when outputs are named). The other
//! stages (flatten, import, atmos, material, therm, sensor, stats, merge, report) run their
//! tool's own body in this process. A layered EXR is read back into planes by
//! `irsig_raster`, and the pixel angles come from the tracer's camera. Every error becomes
//! an `irsig.IrsigError` carrying the file, line and column the command line prints.
//!
//! ```text
//! import irsig
//! frame = irsig.trace(scene="scene.raw", materials="m.ron", view="view.ron", band="8-14")
//! frame.dataset().radiance.plot()
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

use pyo3::prelude::*;

mod errors;
mod layers;
mod stages;
mod trace;

/// The module `irsig._irsig`.
#[pymodule]
#[pyo3(name = "_irsig")]
fn irsig_native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("IrsigError", m.py().get_type::<errors::IrsigError>())?;
    m.add_function(wrap_pyfunction!(trace::trace, m)?)?;
    m.add_function(wrap_pyfunction!(stages::run_stage, m)?)?;
    m.add_function(wrap_pyfunction!(layers::read_exr, m)?)?;
    m.add("STAGES", stages::STAGES.to_vec())?;
    Ok(())
}
