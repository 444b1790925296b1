//! `irsig-atmos shape-factor`: thesis Appendix B, the apparent temperature of a diffuse
//! object `L = ε L(T_obj) + (1 − ε)[F L_d + (1 − F) L(T_b)]` against the shape factor F.

use miette::miette;

use irsig_cli::args::Format;
use irsig_radiometry::shape_factor_temperature;

use crate::common::{BandArgs, Column, diagnostic, fractions, print_table, temperatures};

/// Unit of `--ld`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum RadianceUnit {
    /// W m^-2 sr^-1 (SI).
    #[value(name = "W/m2/sr")]
    WM2Sr,
    /// W cm^-2 sr^-1 (the legacy DIRTRAN unit; 1 W cm^-2 sr^-1 = 1e4 W m^-2 sr^-1).
    #[value(name = "W/cm2/sr")]
    WCm2Sr,
}

/// Arguments of `shape-factor`. Emissivity and temperatures take a value, a list or a
/// range `from:to:step`; every combination is printed, one column per shape factor.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Object emissivity (0–1).
    #[arg(long, allow_hyphen_values = true)]
    pub emissivity: String,
    /// Object temperature, K.
    #[arg(long, allow_hyphen_values = true)]
    pub object_temperature: String,
    /// Background (blackbody) temperature, K.
    #[arg(long, default_value = "300", allow_hyphen_values = true)]
    pub background_temperature: String,
    /// Hemispheric sky radiance L_d, in the unit `--ld-unit` names.
    #[arg(long, allow_hyphen_values = true, requires = "ld_unit")]
    pub ld: f64,
    /// Unit of `--ld`.
    #[arg(long, value_enum)]
    pub ld_unit: RadianceUnit,
    /// Shape factors F (fraction of the hemisphere that is sky), 0–1.
    #[arg(long, default_value = "1,0.75,0.5,0.25,0", allow_hyphen_values = true)]
    pub factors: String,
    #[command(flatten)]
    pub band: BandArgs,
    /// `--format`.
    #[command(flatten)]
    pub format: Format,
}

pub fn run(args: &Args) -> miette::Result<()> {
    let band = args.band.load()?;
    let emissivities = fractions("--emissivity", &args.emissivity)?;
    let objects = temperatures("--object-temperature", &args.object_temperature)?;
    let backgrounds = temperatures("--background-temperature", &args.background_temperature)?;
    let factors = fractions("--factors", &args.factors)?;
    if !(args.ld.is_finite() && args.ld >= 0.0) {
        return Err(miette!(
            "--ld: a sky radiance must be finite and ≥ 0, found {}",
            args.ld
        ));
    }
    let sky_w_m2_sr = match args.ld_unit {
        RadianceUnit::WM2Sr => args.ld,
        RadianceUnit::WCm2Sr => args.ld * 1e4,
    };
    let mut rows = Vec::new();
    for &e in &emissivities {
        for &t_obj in &objects {
            for &t_b in &backgrounds {
                let mut row = vec![e, t_obj, t_b];
                for &f in &factors {
                    row.push(
                        shape_factor_temperature(&band, e, t_obj, t_b, sky_w_m2_sr, f)
                            .map_err(diagnostic)?,
                    );
                }
                rows.push(row);
            }
        }
    }
    let mut columns = vec![
        Column::new("emissivity", 4),
        Column::new("object_temperature_k", 4),
        Column::new("background_temperature_k", 4),
    ];
    columns.extend(factors.iter().map(|f| Column::new(format!("f_{f}_k"), 4)));
    print_table(args.format.value, &columns, &rows)
}
