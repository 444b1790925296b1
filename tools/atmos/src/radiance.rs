//! `irsig-atmos radiance`: band radiance of blackbodies.

use irsig_cli::args::Format;

use crate::common::{BandArgs, Column, print_table, temperatures};

/// Arguments of `radiance`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Temperature(s), K: a value, a list `a,b,c` or a range `from:to:step`.
    #[arg(long, allow_hyphen_values = true)]
    pub temperature: String,
    #[command(flatten)]
    pub band: BandArgs,
    /// `--format`.
    #[command(flatten)]
    pub format: Format,
}

pub fn run(args: &Args) -> miette::Result<()> {
    let band = args.band.load()?;
    let rows: Vec<Vec<f64>> = temperatures("--temperature", &args.temperature)?
        .into_iter()
        .map(|t| vec![t, band.radiance(t)])
        .collect();
    print_table(
        args.format.value,
        &[
            Column::new("temperature_k", 4),
            Column::new("radiance_w_m2_sr", 6),
        ],
        &rows,
    )
}
