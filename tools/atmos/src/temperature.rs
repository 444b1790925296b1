//! `irsig-atmos temperature`: apparent (brightness) temperature of band radiances.

use irsig_cli::args::{Format, values};
use miette::miette;

use crate::common::{BandArgs, Column, print_table};

/// Arguments of `temperature`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Band radiance(s), W m^-2 sr^-1: a value, a list or a range `from:to:step`.
    /// Must be ≥ 0 (0 gives 0 K).
    #[arg(
        long,
        value_name = "W_M2_SR",
        alias = "radiance",
        allow_hyphen_values = true
    )]
    pub radiance_w_m2_sr: String,
    #[command(flatten)]
    pub band: BandArgs,
    /// `--format`.
    #[command(flatten)]
    pub format: Format,
}

pub fn run(args: &Args) -> miette::Result<()> {
    let band = args.band.load()?;
    let radiances = values("--radiance-w-m2-sr", &args.radiance_w_m2_sr)?;
    if let Some(bad) = radiances.iter().find(|&&l| l < 0.0) {
        return Err(miette!(
            "--radiance-w-m2-sr: a band radiance must be ≥ 0 W m^-2 sr^-1, found {bad}"
        ));
    }
    let rows: Vec<Vec<f64>> = radiances
        .into_iter()
        .map(|l| vec![l, band.temperature(l)])
        .collect();
    print_table(
        args.format.value,
        &[
            Column::new("radiance_w_m2_sr", 6),
            Column::new("temperature_k", 4),
        ],
        &rows,
    )
}
