//! The sun's position on a command line ([`SunArgs`]), one spelling in every tool that
//! takes a sun: a direction (`--sun-zenith-deg` with `--sun-azimuth-deg`) or a UTC time and
//! a place (`--sun-utc` with `--latitude-deg`, `--longitude-deg` and `--altitude-m`); the
//! air and clock corrections of NREL's SPA for a time ([`SunPrecisionArgs`]); and a plan's
//! day of the year ([`DayOfYear`]). Every value is checked at parse time by the rule
//! `irsig_atmosphere::sun` applies to its field ([`SunField::check`], [`check_utc`]), and
//! [`flag`] spells each field of a sun as these flags do, for the tools that report a
//! library's error about a field and for the pipeline runner, which gives a pipeline's sun
//! to its tools.
//!
//! A tool that needs a sun given one way says so on its own command (`mut_arg`, `mut_group`
//! on the group [`SUN_GROUP`]); the flags and their checks are these.

use irsig_atmosphere::sun::{Refraction, SunField, SunSpec, check_utc};

/// The group of the two ways of giving a sun, `--sun-zenith-deg` and `--sun-utc`: one of
/// them at most, or exactly one where a tool makes the group required.
pub const SUN_GROUP: &str = "sun";

/// Where the sun is: a direction, or a UTC time and a place. Without these flags, no sun.
#[derive(Debug, Clone, Default, clap::Args)]
#[command(
    group(clap::ArgGroup::new(SUN_GROUP).args(["sun_zenith_deg", "sun_utc"])),
    mut_arg("latitude_deg", |a| a.requires("sun_utc").help(
        "Latitude of the place, degrees, positive north, in [-90, 90]; with --sun-utc")),
    mut_arg("longitude_deg", |a| a.requires("sun_utc").help(
        "Longitude of the place, degrees, positive east, in [-180, 180]; with --sun-utc")),
    mut_arg("altitude_m", |a| a.requires("sun_utc").help(
        "Altitude of the place, metres above mean sea level (the sun's parallax); with \
         --sun-utc")),
)]
pub struct SunArgs {
    /// The sun's zenith angle, degrees (0 overhead, below 90: above the horizon), with
    /// --sun-azimuth-deg.
    #[arg(
        long,
        value_name = "DEG",
        requires = "sun_azimuth_deg",
        allow_negative_numbers = true,
        value_parser = zenith_deg
    )]
    pub sun_zenith_deg: Option<f64>,
    /// The sun's azimuth, degrees clockwise from north (the scene's +y; 90 = east, +x), in
    /// [0, 360); with --sun-zenith-deg.
    #[arg(
        long,
        value_name = "DEG",
        requires = "sun_zenith_deg",
        allow_negative_numbers = true,
        value_parser = number_of(SunField::AzimuthDeg)
    )]
    pub sun_azimuth_deg: Option<f64>,
    /// The sun seen at this time, UTC (`YYYY-MM-DDTHH:MM:SS[.fraction]Z`, years -2000 to
    /// 6000), from --latitude-deg, --longitude-deg and --altitude-m (NREL's SPA, ±0.0003°).
    #[arg(long, value_name = "TIME", conflicts_with = "sun_zenith_deg",
          requires_all = ["latitude_deg", "longitude_deg"], allow_hyphen_values = true,
          value_parser = utc)]
    pub sun_utc: Option<String>,
    /// The place a sun by time is seen from.
    #[command(flatten)]
    pub place: PlaceArgs,
}

/// A place on the Earth: latitude, longitude and altitude above sea level. A sun by time is
/// seen from it (with `--sun-utc`, which requires the first two); the thermal model
/// computes its suns there.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct PlaceArgs {
    /// Latitude of the place, degrees, positive north, in [-90, 90].
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        value_parser = number_of(SunField::LatitudeDeg)
    )]
    pub latitude_deg: Option<f64>,
    /// Longitude of the place, degrees, positive east, in [-180, 180].
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        value_parser = number_of(SunField::LongitudeDeg)
    )]
    pub longitude_deg: Option<f64>,
    /// Altitude of the place, metres above mean sea level (the sun's parallax).
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "M",
        allow_hyphen_values = true,
        value_parser = number_of(SunField::AltitudeM)
    )]
    pub altitude_m: f64,
}

impl SunArgs {
    /// Whether the flags give a sun.
    #[must_use]
    pub fn is_given(&self) -> bool {
        self.sun_zenith_deg.is_some() || self.sun_utc.is_some()
    }

    /// The sun the flags give, if any (geometric: no refraction, SPA's default ΔT), with
    /// `precision`'s corrections for a time.
    #[must_use]
    pub fn spec_with(&self, precision: &SunPrecisionArgs) -> Option<SunSpec> {
        match (
            self.sun_zenith_deg,
            self.sun_azimuth_deg,
            &self.sun_utc,
            self.place.latitude_deg,
            self.place.longitude_deg,
        ) {
            (Some(zenith_deg), Some(azimuth_deg), ..) => Some(SunSpec::Direction {
                zenith_deg,
                azimuth_deg,
            }),
            (_, _, Some(utc), Some(latitude_deg), Some(longitude_deg)) => Some(SunSpec::At {
                utc: utc.clone(),
                latitude_deg,
                longitude_deg,
                altitude_m: self.place.altitude_m,
                refraction: precision.refraction(),
                delta_t_s: precision.delta_t_s,
                delta_ut1_s: precision.delta_ut1_s,
            }),
            // clap requires the flags of each form together.
            _ => None,
        }
    }

    /// The sun the flags give, if any: geometric, SPA's default ΔT.
    #[must_use]
    pub fn spec(&self) -> Option<SunSpec> {
        self.spec_with(&SunPrecisionArgs::default())
    }

    /// The flag that says where the sun of these flags is: `--sun-zenith-deg` for a
    /// direction, `--sun-utc` for a time (`None` without a sun).
    #[must_use]
    pub fn given_flag(&self) -> Option<&'static str> {
        if self.sun_utc.is_some() {
            Some(flag(SunField::Utc))
        } else if self.sun_zenith_deg.is_some() {
            Some(flag(SunField::ZenithDeg))
        } else {
            None
        }
    }
}

/// SPA's corrections for a sun given by time: the site's air for the refracted direction,
/// and the clock's ΔT and UT1 − UTC.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct SunPrecisionArgs {
    /// Local air pressure, hPa, for the refracted (apparent) zenith angle; with
    /// --temperature-c. Without both the direction is geometric.
    #[arg(long, value_name = "HPA", requires_all = ["temperature_c", "sun_utc"],
          allow_hyphen_values = true, value_parser = number_of(SunField::PressureHpa))]
    pub pressure_hpa: Option<f64>,
    /// Local air temperature, °C, for the refracted zenith angle; with --pressure-hpa.
    #[arg(long, value_name = "DEG_C", requires = "pressure_hpa", allow_hyphen_values = true,
          value_parser = number_of(SunField::TemperatureC))]
    pub temperature_c: Option<f64>,
    /// ΔT = TT − UT1, seconds [default: the Espenak & Meeus estimate for the month].
    #[arg(long, value_name = "S", requires = "sun_utc", allow_hyphen_values = true,
          value_parser = number_of(SunField::DeltaTS))]
    pub delta_t_s: Option<f64>,
    /// UT1 − UTC, seconds, in [-0.9, 0.9] [default: 0].
    #[arg(long, value_name = "S", requires = "sun_utc", allow_hyphen_values = true,
          value_parser = number_of(SunField::DeltaUt1S))]
    pub delta_ut1_s: Option<f64>,
}

impl SunPrecisionArgs {
    /// The site's air, when both its pressure and temperature are given.
    #[must_use]
    pub fn refraction(&self) -> Option<Refraction> {
        match (self.pressure_hpa, self.temperature_c) {
            (Some(pressure_hpa), Some(temperature_c)) => Some(Refraction {
                pressure_hpa,
                temperature_c,
            }),
            _ => None,
        }
    }
}

/// `--day-of-year D`: the day of the year a sun given as a direction is seen on, 1-366, for
/// the Earth–Sun distance (LOWTRAN7's IDAY).
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct DayOfYear {
    /// The day of the year, 1-366, for the Earth-Sun distance (LOWTRAN7's IDAY).
    #[arg(id = "day_of_year", long = "day-of-year", value_name = "DAY",
          value_parser = clap::value_parser!(u16).range(1..=366))]
    pub day: Option<u16>,
}

impl DayOfYear {
    /// The flag, without its dashes.
    pub const FLAG: &str = "day-of-year";
}

/// The flag (without its dashes) that gives `field` of a sun in every tool.
#[must_use]
pub fn flag(field: SunField) -> &'static str {
    match field {
        SunField::Utc => "sun-utc",
        SunField::LatitudeDeg => "latitude-deg",
        SunField::LongitudeDeg => "longitude-deg",
        SunField::AltitudeM => "altitude-m",
        SunField::PressureHpa => "pressure-hpa",
        SunField::TemperatureC => "temperature-c",
        SunField::DeltaTS => "delta-t-s",
        SunField::DeltaUt1S => "delta-ut1-s",
        SunField::ZenithDeg => "sun-zenith-deg",
        SunField::AzimuthDeg => "sun-azimuth-deg",
    }
}

/// A number for `field`, checked by the field's own rule.
fn number_of(field: SunField) -> impl Fn(&str) -> Result<f64, String> + Clone {
    move |s: &str| {
        let v: f64 = s
            .trim()
            .parse()
            .map_err(|_| format!("expected a number, found `{s}`"))?;
        field.check(v)?;
        Ok(v)
    }
}

/// `--sun-zenith-deg`: the field's rule, and above the horizon, since a sun at or below it
/// lights nothing (a night is traced without the sun's flags).
fn zenith_deg(s: &str) -> Result<f64, String> {
    let z = number_of(SunField::ZenithDeg)(s)?;
    if z >= 90.0 {
        return Err(format!(
            "the sun at {z} deg from the zenith is at or below the horizon and gives no \
             direct light: expected 0 to below 90 degrees (leave the sun out for a night)"
        ));
    }
    Ok(z)
}

/// `--sun-utc`: a time the sun's model takes.
fn utc(s: &str) -> Result<String, String> {
    check_utc(s)?;
    Ok(s.to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::{Args, Command};

    #[derive(Debug, clap::Parser)]
    struct Cli {
        #[command(flatten)]
        sun: SunArgs,
        #[command(flatten)]
        precision: SunPrecisionArgs,
        #[command(flatten)]
        day: DayOfYear,
    }

    fn parse(args: &[&str]) -> Result<Cli, clap::Error> {
        use clap::Parser;
        Cli::try_parse_from(std::iter::once("t").chain(args.iter().copied()))
    }

    #[test]
    fn every_field_is_spelt_by_a_flag_defined_here() {
        let command = DayOfYear::augment_args(SunPrecisionArgs::augment_args(
            SunArgs::augment_args(Command::new("t")),
        ));
        let longs: Vec<&str> = command
            .get_arguments()
            .filter_map(|a| a.get_long())
            .collect();
        for field in SunField::ALL {
            assert!(longs.contains(&flag(field)), "{field:?}: {longs:?}");
        }
        assert!(longs.contains(&DayOfYear::FLAG));
    }

    #[test]
    fn a_sun_is_a_direction_or_a_time_and_a_place() {
        let cli = parse(&["--sun-zenith-deg", "30", "--sun-azimuth-deg", "180"]).unwrap();
        assert_eq!(
            cli.sun.spec(),
            Some(SunSpec::Direction {
                zenith_deg: 30.0,
                azimuth_deg: 180.0
            })
        );
        assert_eq!(cli.sun.given_flag(), Some("sun-zenith-deg"));
        let cli = parse(&[
            "--sun-utc",
            "2026-06-21T12:00:00Z",
            "--latitude-deg",
            "-43.08",
            "--longitude-deg",
            "-77.67",
            "--pressure-hpa",
            "1010",
            "--temperature-c",
            "20",
        ])
        .unwrap();
        let Some(SunSpec::At {
            latitude_deg,
            refraction,
            altitude_m,
            ..
        }) = cli.sun.spec_with(&cli.precision)
        else {
            panic!("not a time: {:?}", cli.sun);
        };
        assert!((latitude_deg + 43.08).abs() < 1e-12 && altitude_m.abs() < 1e-12);
        assert!(refraction.is_some());
        assert!(cli.sun.spec().is_some_and(|s| matches!(
            s,
            SunSpec::At {
                refraction: None,
                ..
            }
        )));
        let none = parse(&[]).unwrap();
        assert!(!none.sun.is_given() && none.sun.spec().is_none());
        // The two ways at once, or a way half given, are refused.
        assert!(parse(&["--sun-zenith-deg", "30"]).is_err());
        assert!(parse(&["--sun-utc", "2026-06-21T12:00:00Z", "--latitude-deg", "1"]).is_err());
        assert!(parse(&["--latitude-deg", "1"]).is_err());
    }

    #[test]
    fn every_value_is_checked_at_parse_time_by_its_fields_rule() {
        let refused = |args: &[&str], says: &str| {
            let e = parse(args).unwrap_err().to_string();
            assert!(e.contains(says), "{args:?}: {e}");
        };
        let direction =
            |z: &'static str, a: &'static str| ["--sun-zenith-deg", z, "--sun-azimuth-deg", a];
        // 0 (overhead) and just above the horizon are taken; the horizon is not.
        assert!(parse(&direction("0", "0")).is_ok());
        assert!(parse(&direction("89.999", "359.999")).is_ok());
        refused(&direction("90", "0"), "at or below the horizon");
        refused(&direction("-1", "0"), "[0, 180]");
        refused(&direction("NaN", "0"), "[0, 180]");
        refused(&direction("30", "360"), "[0, 360)");
        refused(&direction("30", "-0.5"), "[0, 360)");
        let at = |utc: &'static str, lat: &'static str, lon: &'static str| {
            [
                "--sun-utc",
                utc,
                "--latitude-deg",
                lat,
                "--longitude-deg",
                lon,
            ]
        };
        assert!(parse(&at("2026-06-21T12:00:00Z", "-90", "180")).is_ok());
        refused(&at("2026-06-21T12:00:00Z", "90.5", "0"), "[-90, 90]");
        refused(&at("2026-06-21T12:00:00Z", "0", "-180.5"), "[-180, 180]");
        refused(&at("2026-02-30T12:00:00Z", "0", "0"), "2026-02-30");
        refused(&at("2026-06-21T12:00:00", "0", "0"), "must end in `Z`");
        refused(&at("7000-06-21T12:00:00Z", "0", "0"), "outside SPA's years");
        let mut high = at("2026-06-21T12:00:00Z", "0", "0").to_vec();
        high.extend(["--altitude-m", "100001"]);
        refused(&high, "m above sea level");
        let mut air = at("2026-06-21T12:00:00Z", "0", "0").to_vec();
        air.extend(["--pressure-hpa", "0", "--temperature-c", "20"]);
        refused(&air, "(0, 1100] hPa");
        let mut clock = at("2026-06-21T12:00:00Z", "0", "0").to_vec();
        clock.extend(["--delta-ut1-s", "1"]);
        refused(&clock, "[-0.9, 0.9]");
        refused(&["--day-of-year", "367"], "367");
        assert!(parse(&["--day-of-year", "366"]).is_ok());
    }
}
