//! irsig's errors as one Python exception, `irsig.IrsigError`, whose arguments are the
//! message the command line prints and, where the error points into a file, that file, its
//! line and its column (`irsig_formats::ParseError`, wherever it sits in the chain).

use pyo3::PyErr;
use pyo3::exceptions::PyException;

pyo3::create_exception!(
    irsig,
    IrsigError,
    PyException,
    "An input irsig refuses or a run that failed: args are (message, file, line, column, \
     usage), the last four None/False where they do not apply."
);

/// The report as `IrsigError(message, file, line, column, usage)`.
pub(crate) fn to_py(report: &miette::Report) -> PyErr {
    let at = report
        .chain()
        .find_map(|e| e.downcast_ref::<irsig_formats::ParseError>());
    let message: Vec<String> = report.chain().map(ToString::to_string).collect();
    // A chain repeats its source's text when a layer wraps it with context only.
    let mut text = String::new();
    for part in message {
        if !text.contains(&part) {
            if !text.is_empty() {
                text.push_str(": ");
            }
            text.push_str(&part);
        }
    }
    let usage = report.downcast_ref::<irsig_cli::UsageError>().is_some();
    match at {
        Some(e) => IrsigError::new_err((text, e.file.clone(), e.line, e.column, usage)),
        None => IrsigError::new_err((text, None::<String>, None::<usize>, None::<usize>, usage)),
    }
}
