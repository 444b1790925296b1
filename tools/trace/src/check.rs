//! What the flags alone are refused for, before a file is read ([`irsig_cli::CheckArgs`]):
//! the checks the plan makes of them (the sun's position, the tolerance and its
//! percentile), made early so that `irsig-run` refuses a stage with them before anything
//! runs, and a model pinned twice, which nothing later would notice.

use irsig_render::tolerance::Pin;
use irsig_render::{RequestError, Setting};

use crate::Cli;

impl irsig_cli::CheckArgs for Cli {
    fn check_args(&self) -> miette::Result<()> {
        check_flags(self).map_err(crate::as_usage)
    }
}

fn check_flags(cli: &Cli) -> miette::Result<()> {
    // The flags' sun only: a view file's is checked where the file is read.
    if let Some(sun) = crate::sun::request(&cli.sun, cli.sun_shadow_rays, None)? {
        sun.position()?;
    }
    if let Some(tolerance_k) = cli.tolerance.kelvin {
        irsig_model::decision::check_tolerance(tolerance_k, "tolerance")
            .map_err(|e| RequestError::report(Setting::Tolerance, e.kind.to_string()))?;
        irsig_model::decision::check_percentile(cli.tolerance_percentile, "percentile")
            .map_err(|e| RequestError::report(Setting::TolerancePercentile, e.kind.to_string()))?;
    }
    check_pins(&cli.pin)
}

/// Each model pinned at most once: `--pin bounces=1 --pin bounces=2` ran with the last.
///
/// # Errors
/// The second pin of a model, naming the first.
pub(crate) fn check_pins(pins: &[Pin]) -> miette::Result<()> {
    for (i, pin) in pins.iter().enumerate() {
        if let Some(first) = pins[..i].iter().find(|p| p.model() == pin.model()) {
            return Err(RequestError::of_value(
                Setting::Pin,
                pin,
                format!(
                    "`{}` is pinned twice (first --pin {first}): pin each model once",
                    pin.model()
                ),
            ));
        }
    }
    Ok(())
}
