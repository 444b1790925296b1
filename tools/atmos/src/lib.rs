//! `irsig-atmos`: the atmosphere stage's tools, one module per subcommand.
//!
//! - `convert` ([`convert`]): legacy DIRTRAN tables (`.atm .cor .dwr .rtt .rsd`) to and
//!   from the canonical atmosphere file, units stated, every table validated; and the
//!   legacy material index file with its `.ems` tables to and from the canonical material
//!   library ([`materials`]).
//! - Calculators a user decides a scene's models with (band radiance, apparent
//!   temperature, `.rtt` tables, thesis Appendix A bounces and Appendix B shape factors).
//!   Each prints a plain aligned table by default, or `--format csv` / `--format ron`.
//! - `fresnel`: an angular emissivity table of a smooth opaque surface from its complex
//!   refractive index (constant, or a `wavelength_um n k` table averaged over the band),
//!   as a canonical material library entry or a legacy `.ems`.
//!
//! ```text
//! irsig-atmos convert --atm us.atm --dwr us.dwr --altitude-unit km \
//!     --radiance-unit W/cm2/sr --name us -o us.ron
//! irsig-atmos convert --material-index materials.mat --default-emissivity 0.9 -o lib.ron
//! irsig-atmos radiance --temperature 300            # 54.933461 W m^-2 sr^-1
//! irsig-atmos temperature --radiance 54.93
//! irsig-atmos rtt --from 200 --to 350 --step 1 --legacy -o us.rtt
//! irsig-atmos bounces --target-temperature 260:400:10 --max 4
//! irsig-atmos shape-factor --emissivity 0.95 --object-temperature 240 \
//!     --background-temperature 240,280,320,360 --ld 0.0014 --ld-unit W/m2/sr
//! irsig-atmos fresnel --n 1.2 --k 0.05 -o glassy.ron
//! irsig-atmos fresnel --nk-table water.nk --band 8-14 --temperature 300 -o water.ems
//! ```

use clap::{Parser, Subcommand};

mod bounces;
mod common;
pub mod convert;
mod fresnel;
pub mod materials;
mod radiance;
mod rtt;
mod shape_factor;
mod temperature;

/// Atmosphere tables, and band radiance calculators (8–14 µm unless `--band` says
/// otherwise).
#[derive(Debug, Parser)]
#[command(
    name = "irsig-atmos",
    version,
    after_help = "Examples:
  irsig-atmos convert --to-legacy builtin:us-std-1976 --altitude-unit km \\
      --radiance-unit W/cm2/sr --out-dir /tmp
  irsig-atmos radiance --temperature 300
  irsig-atmos temperature --radiance 54.93 --band 8-14
  irsig-atmos rtt --from 200 --to 350 --step 1 --legacy -o us-std.rtt
  irsig-atmos bounces --target-emissivity 0.98 --target-temperature 260:400:10 \\
      --background-emissivity 0.95 --background-temperature 300 --max 4
  irsig-atmos shape-factor --emissivity 0.95 --object-temperature 240 \\
      --background-temperature 240,280,320,360 --ld 0.0014 --ld-unit W/m2/sr
  irsig-atmos fresnel --n 1.2 --k 0.05 --angles 0:90:5
  irsig-atmos fresnel --nk-table formats/samples/water-hale-querry-nk.txt --band 8-14 \\
      --temperature 300 --angles 0:90:5 --legacy -o water.ems"
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// DIRTRAN tables <-> canonical atmosphere, material index + .ems <-> material
    /// library; validated, units stated.
    Convert(Box<convert::ConvertArgs>),
    /// Band radiance (W m^-2 sr^-1) of a blackbody at each temperature.
    Radiance(radiance::Args),
    /// Apparent (brightness) temperature (K) of each band radiance.
    Temperature(temperature::Args),
    /// Write a radiance-temperature table (`.rtt`).
    Rtt(rtt::Args),
    /// Apparent temperature of a specular target after 0..N bounces (thesis Appendix A).
    Bounces(bounces::Args),
    /// Apparent temperature of a diffuse object against shape factor (thesis Appendix B).
    ShapeFactor(shape_factor::Args),
    /// Angular emissivity of a smooth opaque surface from its complex refractive index
    /// (Fresnel), as a material library entry (RON) or a legacy `.ems`.
    #[command(after_help = "Examples:
  irsig-atmos fresnel --n 1.2 --k 0.05 --angles 0:90:5
  irsig-atmos fresnel --n 25 --k 90 --name aluminium --id 7 -o aluminium.ron
  irsig-atmos fresnel --nk-table formats/samples/water-hale-querry-nk.txt --band 8-14 \\
      --temperature 300 --angles 0:90:5 --legacy -o water.ems

A constant index gives the monochromatic table. A table of n, k against wavelength is
averaged over the band (weighted by its response, for a response file) with Planck weighting at --temperature:
eps(theta) = int eps(lambda, theta) S B(lambda, T) dlambda / int S B(lambda, T) dlambda.
Output is a canonical material library (RON) unless --legacy or -o NAME.ems.")]
    Fresnel(fresnel::Args),
}

/// Runs one subcommand.
///
/// # Errors
/// Bad input (exit 1): a malformed table or SRF file, a bad value (negative temperature,
/// emissivity outside 0–1, malformed list or range); or bad usage (exit 2).
pub fn run(cli: Cli) -> miette::Result<()> {
    match cli.command {
        Command::Convert(args) => convert::run(&args),
        Command::Radiance(a) => radiance::run(&a),
        Command::Temperature(a) => temperature::run(&a),
        Command::Rtt(a) => rtt::run(&a),
        Command::Bounces(a) => bounces::run(&a),
        Command::ShapeFactor(a) => shape_factor::run(&a),
        Command::Fresnel(a) => fresnel::run(&a),
    }
}
