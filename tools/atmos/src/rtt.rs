//! `irsig-atmos rtt`: a radiance-temperature table.
//!
//! Legacy layout (`--legacy`, thesis Figure 9 and the DIRTRAN `.rtt`): one row
//! `T_K L` per temperature, radiance in W cm^-2 sr^-1, 12 significant digits, no header.
//! Otherwise the same rows in W m^-2 sr^-1 after `#` header lines naming band and units.

use irsig_cli::args::outputs::{Legacy, Output};
use miette::miette;
use std::io::Write;

use crate::common::BandArgs;

/// Arguments of `rtt`.
#[derive(Debug, clap::Args)]
#[command(
    mut_arg("legacy", |a| a.help("The 1990 layout: W cm^-2 sr^-1, no header")),
    mut_arg("output", |a| a.help("Output file (stdout when absent or `-`)")),
)]
pub struct Args {
    /// First temperature, K.
    #[arg(long, allow_hyphen_values = true)]
    pub from: f64,
    /// Last temperature, K (included).
    #[arg(long, allow_hyphen_values = true)]
    pub to: f64,
    /// Temperature step, K.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub step_k: f64,
    /// `--legacy`: the 1990 layout.
    #[command(flatten)]
    pub legacy: Legacy,
    #[command(flatten)]
    pub band: BandArgs,
    /// `-o PATH`: the table.
    #[command(flatten)]
    pub output: Output,
}

/// `v` in the `%.11e` layout of C and Python (two-digit exponent at least).
fn c_exponential(v: f64) -> String {
    let s = format!("{v:.11e}");
    match s.split_once('e') {
        Some((mantissa, exp)) => {
            let (sign, digits) = exp.strip_prefix('-').map_or(("+", exp), |d| ("-", d));
            format!("{mantissa}e{sign}{digits:0>2}")
        }
        None => s,
    }
}

pub fn run(args: &Args) -> miette::Result<()> {
    irsig_cli::refuse_output_is_input(args.band.response_file(), args.output.path.iter())?;
    let band = args.band.load()?;
    let range = format!("{}:{}:{}", args.from, args.to, args.step_k);
    let temps = crate::common::temperatures("--from/--to/--step", &range)?;
    if temps.is_empty() {
        return Err(miette!("--from/--to/--step: the range is empty"));
    }
    let (lo, hi) = (band.lambda_min_um(), band.lambda_max_um());
    let srf = band.has_response();
    irsig_cli::write_output(args.output.path.as_deref(), |w: &mut dyn Write| {
        if !args.legacy.on {
            writeln!(
                w,
                "# irsig rtt: blackbody band radiance, {lo}-{hi} um{}, CODATA 2018",
                if srf {
                    ", weighted by a sensor response"
                } else {
                    ""
                }
            )?;
            writeln!(
                w,
                "# columns: temperature_k radiance_w_m2_sr (W m^-2 sr^-1)"
            )?;
        }
        for &t in &temps {
            let l = band.radiance(t);
            let l = if args.legacy.on { l * 1e-4 } else { l };
            writeln!(w, "{t} {}", c_exponential(l))?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn exponent_has_two_digits_and_a_sign() {
        assert_eq!(super::c_exponential(6.01175039861e-4), "6.01175039861e-04");
        assert_eq!(super::c_exponential(54.9), "5.49000000000e+01");
        assert_eq!(super::c_exponential(1.5e-148), "1.50000000000e-148");
    }
}
