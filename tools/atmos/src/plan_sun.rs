//! The sun of `irsig-atmos plan`: its flags (`--sun-zenith-deg`, `--day-of-year`) or the
//! `sun` of a view file (`formats/canonical/view.md`), the one `irsig-trace` lights the
//! same views by. A sun given both ways is refused, naming the flag and the file's line
//! and column, as `irsig-trace` refuses it: neither wins silently.
//!
//! The plan takes the zenith angle `irsig-trace` will check its solar table against:
//! the view's sun's [`SunPosition::zenith_deg`] (geometric, unless the view gives the air
//! for refraction), rounded to the 0.001° a deck holds. Its day of the year (LOWTRAN7's
//! IDAY, the Earth–Sun distance) is the time's for a sun given by time and place; a sun
//! given as a direction has no date, so `--day-of-year` must give it.
//!
//! [`SunPosition::zenith_deg`]: irsig_atmosphere::sun::SunPosition::zenith_deg

use irsig_atmosphere::sun::SunSpec;
use irsig_formats::views::ViewSun;

/// The sun a plan is for: its zenith angle, degrees, and its day of the year.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PlanSunChoice {
    pub zenith_deg: f64,
    pub day_of_year: u16,
}

/// `--sun-zenith-deg`: a finite angle from 0 to below 90 degrees.
pub(crate) fn sun_zenith(s: &str) -> Result<f64, String> {
    let z: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("expected the sun's zenith angle in degrees, found `{s}`"))?;
    if !z.is_finite() || z < 0.0 {
        return Err(format!(
            "expected the sun's zenith angle from 0 to below 90 degrees, found {z}"
        ));
    }
    if z >= 90.0 {
        return Err(format!(
            "the sun at {z} deg from the zenith is at or below the horizon and gives no direct light: expected 0 to below 90 degrees (leave out --sun-zenith-deg for night)"
        ));
    }
    rounds_above_horizon(z)
}

/// A deck holds 0.001 deg: the plan keeps the angle rounded so, and a sun that rounds to
/// the horizon gives no direct light.
fn rounds_above_horizon(z: f64) -> Result<f64, String> {
    if (z * 1000.0).round() / 1000.0 >= 90.0 {
        return Err(format!(
            "{z} deg rounds to 90 at the 0.001 deg a LOWTRAN7 deck holds: the sun on the horizon gives no direct light; expected at most 89.999 degrees"
        ));
    }
    Ok(z)
}

/// The plan's sun from the flags (`zenith`, `day`, `scattering`) and the views' sun
/// (`view`, already checked above the horizon by its reader), if any.
///
/// # Errors
/// A usage error when both give a sun; a view's direction without `--day-of-year`; a
/// `--day-of-year` that is not the view's time's, or that has no sun; `--sun-scattering`
/// without a sun; a view's sun that rounds to the horizon.
pub(crate) fn choose(
    zenith: Option<f64>,
    day: Option<u16>,
    scattering: bool,
    view: Option<&ViewSun<SunSpec>>,
) -> miette::Result<Option<PlanSunChoice>> {
    let Some(view) = view else {
        return match (zenith, day) {
            // clap requires --day-of-year with --sun-zenith-deg.
            (Some(zenith_deg), Some(day_of_year)) => Ok(Some(PlanSunChoice {
                zenith_deg,
                day_of_year,
            })),
            (None, Some(d)) => Err(irsig_cli::usage_error(format!(
                "--day-of-year {d} without a sun: give --sun-zenith-deg, or a view file with a \
                 `sun`"
            ))),
            _ if scattering => Err(irsig_cli::usage_error(
                "--sun-scattering without a sun: give --sun-zenith-deg and --day-of-year, or a \
                 view file with a `sun`",
            )),
            _ => Ok(None),
        };
    };
    let location = &view.location;
    if let Some(z) = zenith {
        return Err(irsig_cli::usage_error(format!(
            "--sun-zenith-deg {z} and the `sun` of the view file at {location} both give a \
             sun: give it once, by the flags or in the view file"
        )));
    }
    let position = view.sun.position().map_err(|e| {
        irsig_cli::usage_error(format!("the `sun` of the view file at {location}: {e}"))
    })?;
    let zenith_deg = rounds_above_horizon(position.zenith_deg).map_err(|e| {
        irsig_cli::usage_error(format!("the `sun` of the view file at {location}: {e}"))
    })?;
    let day_of_year = match (view.sun.day_of_year(), day) {
        (Some(of_time), Some(given)) if of_time != given => {
            return Err(irsig_cli::usage_error(format!(
                "--day-of-year {given}, but the `sun` of the view file at {location} is seen \
                 on day {of_time} of its year: leave out --day-of-year"
            )));
        }
        (Some(of_time), _) => of_time,
        (None, Some(given)) => given,
        (None, None) => {
            return Err(irsig_cli::usage_error(format!(
                "the `sun` of the view file at {location} is a direction, which has no date: \
                 give --day-of-year D (1-366) for the Earth-Sun distance, or give the sun by \
                 time and place (`At(utc: ...)`)"
            )));
        }
    };
    Ok(Some(PlanSunChoice {
        zenith_deg,
        day_of_year,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view(sun: SunSpec) -> ViewSun<SunSpec> {
        ViewSun {
            sun,
            location: "view.ron:4:8".to_owned(),
        }
    }

    fn direction(zenith_deg: f64) -> ViewSun<SunSpec> {
        view(SunSpec::Direction {
            zenith_deg,
            azimuth_deg: 180.0,
        })
    }

    fn at(utc: &str) -> ViewSun<SunSpec> {
        view(SunSpec::At {
            utc: utc.to_owned(),
            latitude_deg: 0.0,
            longitude_deg: 0.0,
            altitude_m: 0.0,
            refraction: None,
            delta_t_s: None,
            delta_ut1_s: None,
        })
    }

    fn refused(r: miette::Result<Option<PlanSunChoice>>, says: &str) {
        let message = r.expect_err("expected a refusal").to_string();
        assert!(message.contains(says), "{message}");
    }

    #[test]
    fn flags_alone_as_before() {
        assert_eq!(choose(None, None, false, None).unwrap(), None);
        let sun = choose(Some(30.0), Some(172), true, None).unwrap().unwrap();
        assert_eq!((sun.zenith_deg, sun.day_of_year), (30.0, 172));
        refused(
            choose(None, Some(172), false, None),
            "--day-of-year 172 without a sun",
        );
        refused(
            choose(None, None, true, None),
            "--sun-scattering without a sun",
        );
    }

    #[test]
    fn a_views_direction_needs_a_day() {
        let v = direction(40.0);
        let sun = choose(None, Some(100), true, Some(&v)).unwrap().unwrap();
        assert_eq!((sun.zenith_deg, sun.day_of_year), (40.0, 100));
        refused(
            choose(None, None, false, Some(&v)),
            "view.ron:4:8 is a direction",
        );
        refused(
            choose(Some(40.0), Some(100), false, Some(&v)),
            "--sun-zenith-deg 40 and the `sun` of the view file at view.ron:4:8",
        );
        refused(
            choose(None, Some(1), false, Some(&direction(89.9996))),
            "rounds to 90",
        );
    }

    #[test]
    fn a_views_time_gives_its_day() {
        // Noon UTC at the equator and the prime meridian on the 2026 March equinox
        // (20 March, 14:46 UTC), day 79: the declination is within 0.1 deg of 0, and the
        // equation of time (about -7.4 min, 1.85 deg of hour angle) puts the sun about
        // 1.9 deg from the zenith.
        let v = at("2026-03-20T12:00:00Z");
        let sun = choose(None, None, false, Some(&v)).unwrap().unwrap();
        assert_eq!(sun.day_of_year, 31 + 28 + 20);
        assert!((1.6..2.2).contains(&sun.zenith_deg), "{}", sun.zenith_deg);
        assert!(choose(None, Some(79), false, Some(&v)).is_ok());
        refused(
            choose(None, Some(80), false, Some(&v)),
            "is seen on day 79 of its year",
        );
    }
}
