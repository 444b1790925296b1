//! `irsig-atmos sun`: the sun's position from a UTC time and a place (NREL's SPA, through
//! `irsig_atmosphere::sun`), as angles and as the unit vector toward it in the scene frame.

use irsig_atmosphere::sun::{Refraction, SunSpec};
use irsig_atmosphere::{AtmosphereError, AtmosphereErrorKind};
use irsig_cli::args::TableFormat;
use miette::miette;

use crate::common::{Column, print_table};

/// Arguments of `sun`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The time, UTC: `YYYY-MM-DDTHH:MM:SS[.fraction]Z` (years -2000 to 6000).
    #[arg(long, allow_hyphen_values = true)]
    pub utc: String,
    /// Latitude, degrees, positive north, in [-90, 90].
    #[arg(long, allow_hyphen_values = true)]
    pub latitude_deg: f64,
    /// Longitude, degrees, positive east, in [-180, 180].
    #[arg(long, allow_hyphen_values = true)]
    pub longitude_deg: f64,
    /// The site's altitude, metres above mean sea level.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub altitude_m: f64,
    /// Local air pressure, hPa, for the refracted (apparent) zenith angle; with
    /// `--temperature-c`. Without both the direction is geometric.
    #[arg(long, requires = "temperature_c", allow_hyphen_values = true)]
    pub pressure_hpa: Option<f64>,
    /// Local air temperature, °C, for the refracted zenith angle; with `--pressure-hpa`.
    #[arg(long, requires = "pressure_hpa", allow_hyphen_values = true)]
    pub temperature_c: Option<f64>,
    /// ΔT = TT − UT1, seconds [default: the Espenak & Meeus estimate for the month].
    #[arg(long, allow_hyphen_values = true)]
    pub delta_t_s: Option<f64>,
    /// UT1 − UTC, seconds, in [-0.9, 0.9] [default: 0].
    #[arg(long, allow_hyphen_values = true)]
    pub delta_ut1_s: Option<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub format: TableFormat,
}

pub fn run(args: &Args) -> miette::Result<()> {
    let refraction = match (args.pressure_hpa, args.temperature_c) {
        (Some(pressure_hpa), Some(temperature_c)) => Some(Refraction {
            pressure_hpa,
            temperature_c,
        }),
        // clap requires the two together.
        _ => None,
    };
    let spec = SunSpec::At {
        utc: args.utc.clone(),
        latitude_deg: args.latitude_deg,
        longitude_deg: args.longitude_deg,
        altitude_m: args.altitude_m,
        refraction,
        delta_t_s: args.delta_t_s,
        delta_ut1_s: args.delta_ut1_s,
    };
    let sun = spec.position().map_err(|e| flag_error(&e))?;
    if !sun.is_above_horizon() {
        irsig_cli::note!(
            "irsig-atmos: the sun is below the horizon ({:.3}° elevation)",
            sun.elevation_deg()
        );
    }
    let [east, north, up] = sun.to_scene_direction();
    let mut columns = vec![Column::new("zenith_deg", 6)];
    let mut row = vec![sun.zenith_deg];
    if sun.refracted {
        columns.push(Column::new("geometric_zenith_deg", 6));
        row.push(sun.geometric_zenith_deg);
    }
    columns.extend([
        Column::new("azimuth_deg", 6),
        Column::new("elevation_deg", 6),
        Column::new("x_east", 6),
        Column::new("y_north", 6),
        Column::new("z_up", 6),
    ]);
    row.extend([sun.azimuth_deg, sun.elevation_deg(), east, north, up]);
    print_table(args.format, &columns, &[row])
}

/// The library names a field (`latitude_deg`, `refraction.pressure_hpa`); the command line
/// names its flag (`--latitude-deg`, `--pressure-hpa`).
fn flag_error(e: &AtmosphereError) -> miette::Report {
    match &e.kind {
        AtmosphereErrorKind::Sun { field, message } => {
            let name = field.rsplit('.').next().unwrap_or(field).replace('_', "-");
            miette!("--{name}: {message}")
        }
        _ => miette!("{e}"),
    }
}
