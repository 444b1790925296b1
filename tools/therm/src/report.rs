//! The decision of `--tolerance` as a table on stderr.

use irsig_model::thermal_decision::ThermalDecision;

/// Prints the decision: each model's setting, error and relative cost, the check of the
/// whole set, and the spreads the tolerance does not choose.
pub fn print(d: &ThermalDecision) {
    irsig_cli::note!(
        "irsig-therm: --tolerance {} K, piloted on {} of {} facets:",
        d.tolerance_k,
        d.pilot_facets,
        d.facets
    );
    irsig_cli::note!(
        "  {:<16} {:<24} {:<24} {:>9} {:>9}",
        "model",
        "setting",
        "reference",
        "error K",
        "cost"
    );
    for m in &d.models {
        irsig_cli::note!(
            "  {:<16} {:<24} {:<24} {:>9.3} {:>9.3}",
            m.model,
            m.setting,
            m.reference,
            m.error_k,
            m.relative_cost
        );
    }
    irsig_cli::note!(
        "  predicted {:.3} K; measured {:.3} K at the 99th percentile ({:.3} K at worst); \
         relative cost {:.3}",
        d.predicted_k,
        d.measured_p99_k,
        d.measured_max_k,
        d.relative_cost
    );
    for s in &d.spreads {
        irsig_cli::note!(
            "  not chosen: {}: {:.3} K at the 99th percentile ({:.3} K at worst)",
            s.what,
            s.p99_k,
            s.max_k
        );
    }
}
