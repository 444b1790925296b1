//! `irsig-atmos sun`: the sun's position from a UTC time and a place (NREL's SPA, through
//! `irsig_atmosphere::sun`), or as given, as angles and as the unit vector toward it in the
//! scene frame. Its flags are every tool's ([`SunArgs`]; `--utc` is the old spelling of
//! `--sun-utc`).

use irsig_atmosphere::{AtmosphereError, AtmosphereErrorKind};
use irsig_cli::args::sun::SUN_GROUP;
use irsig_cli::args::{Format, SunArgs, SunPrecisionArgs};
use miette::miette;

use crate::common::{Column, print_table};

/// Arguments of `sun`.
#[derive(Debug, clap::Args)]
#[command(
    mut_group(SUN_GROUP, |g| g.required(true)),
    mut_arg("sun_utc", |a| a.alias("utc")),
)]
pub struct Args {
    /// Where the sun is: a UTC time and a place, or a direction (echoed, with its scene
    /// vector).
    #[command(flatten)]
    pub sun: SunArgs,
    /// The site's air for refraction, and the clock's ΔT and UT1 − UTC.
    #[command(flatten)]
    pub precision: SunPrecisionArgs,
    /// `--format`.
    #[command(flatten)]
    pub format: Format,
}

/// The flags' own rules: every field of a sun the flags give in its range, named by its
/// flag (a sun not given is `run`'s to refuse).
pub(crate) fn check(args: &Args) -> miette::Result<()> {
    match args.sun.spec_with(&args.precision) {
        Some(spec) => spec.validate().map_err(|e| flag_error(&e)),
        None => Ok(()),
    }
}

/// Runs `irsig-atmos sun`.
///
/// # Errors
/// No sun given, or a field out of its range, named by its flag.
pub fn run(args: &Args) -> miette::Result<()> {
    let Some(spec) = args.sun.spec_with(&args.precision) else {
        return Err(irsig_cli::usage_error(
            "give the sun: --sun-utc TIME with --latitude-deg and --longitude-deg, or \
             --sun-zenith-deg with --sun-azimuth-deg",
        ));
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
    print_table(args.format.value, &columns, &[row])
}

/// The library names a field of the sun; the command line names its flag.
fn flag_error(e: &AtmosphereError) -> miette::Report {
    match &e.kind {
        AtmosphereErrorKind::Sun { field, message } => {
            miette!("--{}: {message}", irsig_cli::args::sun::flag(*field))
        }
        _ => miette!("{e}"),
    }
}
