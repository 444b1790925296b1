//! `irsig-atmos`: the atmosphere stage's tools, one module per subcommand.
//!
//! - `convert` ([`convert`]): legacy DIRTRAN tables (`.atm .cor .dwr .rtt .rsd`) to and
//!   from the canonical atmosphere file, units stated, every table validated.
//! - Calculators a user decides a scene's models with (band radiance, apparent
//!   temperature, `.rtt` tables, thesis Appendix A bounces and Appendix B shape factors,
//!   the sun's position by NREL's SPA). Each prints a plain aligned table by default,
//!   or `--format csv` / `--format ron`.
//!
//! Material files (the 1990 index and its `.ems` tables, Fresnel emissivity) are
//! `irsig-material`'s.
//!
//! - `plan` and `build` ([`plan`], [`build`]): the LOWTRAN7 runs a scene needs, and their
//!   outputs assembled into a canonical spectral atmosphere; [`lowtran`] finds and runs
//!   the program. `plan --loads` plans a day's broadband thermal loads at the ground
//!   instead (direct and diffuse sunlight per sun zenith angle, the sky's longwave), and
//!   `build` writes their table.
//!
//! ```text
//! irsig-atmos plan --scene scene.raw --view view.ron --atmosphere tropical -o plan
//! irsig-atmos build plan -o tropical.spa
//! irsig-atmos plan --loads --model midlat-summer --sun-zeniths-deg 20:85:5,89 \
//!     --day-of-year 172 -o june-loads
//! irsig-atmos build june-loads -o june-loads.ron
//! irsig-atmos convert --atm us.atm --dwr us.dwr --altitude-unit km \
//!     --radiance-unit W/cm2/sr --name us -o us.ron
//! irsig-atmos radiance --temperature 300            # 54.933461 W m^-2 sr^-1
//! irsig-atmos temperature --radiance-w-m2-sr 54.93
//! irsig-atmos rtt --from 200 --to 350 --step-k 1 --legacy -o us.rtt
//! irsig-atmos bounces --target-temperature 260:400:10 --max 4
//! irsig-atmos shape-factor --emissivity 0.95 --object-temperature 240 \
//!     --background-temperature 240,280,320,360 --ld 0.0014 --ld-unit W/m2/sr
//! irsig-atmos sun --sun-utc 2026-06-21T12:00:00Z --latitude-deg 43.08 --longitude-deg -77.67
//! ```

// A closed stderr must not panic the tool: notes go through `irsig_cli::note!`.
#![warn(clippy::print_stderr)]

use clap::{Parser, Subcommand};

mod bounces;
pub mod build;
mod build_loads;
mod common;
pub mod convert;
pub mod lowtran;
pub mod plan;
mod plan_loads;
mod plan_sun;
mod radiance;
mod rtt;
mod runs;
mod shape_factor;
mod sun;
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
  irsig-atmos temperature --radiance-w-m2-sr 54.93 --band 8-14
  irsig-atmos rtt --from 200 --to 350 --step-k 1 --legacy -o us-std.rtt
  irsig-atmos bounces --target-emissivity 0.98 --target-temperature 260:400:10 \\
      --background-emissivity 0.95 --background-temperature 300 --max 4
  irsig-atmos shape-factor --emissivity 0.95 --object-temperature 240 \\
      --background-temperature 240,280,320,360 --ld 0.0014 --ld-unit W/m2/sr
  irsig-atmos sun --sun-utc 2026-06-21T12:00:00Z --latitude-deg 43.08 \\
      --longitude-deg -77.67 --altitude-m 170

Material libraries (the 1990 index and .ems tables, Fresnel emissivity): irsig-material."
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// DIRTRAN tables <-> canonical atmosphere; validated, units stated.
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
    /// The sun's zenith, azimuth (degrees) and scene-frame direction at a UTC time and
    /// place (NREL's SPA, ±0.0003°).
    Sun(sun::Args),
    /// The radiative-transfer paths a scene needs (or, with --loads, a day's broadband
    /// loads at the ground): a plan and one LOWTRAN7 card deck per path.
    Plan(Box<plan::PlanArgs>),
    /// A plan's runs (LOWTRAN7, run here, or given tape7s) assembled into one spectral
    /// atmosphere, or a loads plan's into a table of broadband loads.
    Build(build::BuildArgs),
}

/// The flags' own rules, checked before a file is read (and when `irsig-run` asks of a
/// stage): the sun's fields, and a plan's aerosol.
impl irsig_cli::CheckArgs for Cli {
    fn check_args(&self) -> miette::Result<()> {
        match &self.command {
            Command::Sun(a) => sun::check(a),
            Command::Plan(a) => {
                plan::aerosol_of(a.aerosol.as_deref(), a.visibility_km, a.wind_speed_m_s).map(drop)
            }
            _ => Ok(()),
        }
    }
}

/// Runs one subcommand.
///
/// # Errors
/// Bad input (exit 1): a malformed table or SRF file, a bad value (negative temperature,
/// emissivity outside 0–1, malformed list or range, a latitude or time out of range); or
/// bad usage (exit 2).
pub fn run(cli: Cli) -> miette::Result<()> {
    match cli.command {
        Command::Convert(args) => convert::run(&args),
        Command::Radiance(a) => radiance::run(&a),
        Command::Temperature(a) => temperature::run(&a),
        Command::Rtt(a) => rtt::run(&a),
        Command::Bounces(a) => bounces::run(&a),
        Command::ShapeFactor(a) => shape_factor::run(&a),
        Command::Sun(a) => sun::run(&a),
        Command::Plan(a) => plan::run(&a),
        Command::Build(a) => build::run(&a),
    }
}
