//! The sun of `irsig-atmos plan`: its flags (every tool's sun flags, `--sun-zenith-deg`
//! with `--day-of-year` or `--sun-utc` with the place) or the `sun` of a view file
//! (`formats/canonical/view.md`), the one `irsig-trace` lights the same views by. A sun
//! given both ways is refused, naming the flag and the file's line and column, as
//! `irsig-trace` refuses it: neither wins silently.
//!
//! The plan takes the zenith angle `irsig-trace` will check its solar table against:
//! the sun's [`SunPosition::geometric_zenith_deg`], rounded to the 0.001° a deck holds,
//! also when a view gives the air for SPA's refraction (that lifts the direction the
//! light arrives from, which the trace keeps for shadows and glints; the build finds the
//! beam's own refracted path from LOWTRAN7's bending, so a refracted zenith here would be
//! bent twice). Its day of the year (LOWTRAN7's IDAY,
//! the Earth–Sun distance) is the time's for a sun given by time and place; a sun given as
//! a direction has no date, so `--day-of-year` must give it.
//!
//! [`SunPosition::geometric_zenith_deg`]: irsig_atmosphere::sun::SunPosition::geometric_zenith_deg

use irsig_atmosphere::sun::SunSpec;
use irsig_formats::views::ViewSun;

/// The sun a plan is for: its zenith angle, degrees, and its day of the year.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PlanSunChoice {
    pub zenith_deg: f64,
    pub day_of_year: u16,
}

/// A deck holds 0.001 deg: the plan keeps the angle rounded so, and a sun that rounds to
/// the horizon gives no direct light.
pub(crate) fn rounds_above_horizon(z: f64) -> Result<f64, String> {
    if (z * 1000.0).round() / 1000.0 >= 90.0 {
        return Err(format!(
            "{z} deg rounds to 90 at the 0.001 deg a LOWTRAN7 deck holds: the sun on the horizon gives no direct light; expected at most 89.999 degrees"
        ));
    }
    Ok(z)
}

/// The plan's sun from the flags' sun (`flags`: the sun and how the flags gave it, such as
/// `--sun-zenith-deg 30`, checked at parse time), `--day-of-year` (`day`), `--sun-scattering` (`scattering`) and the
/// views' sun (`view`, checked above the horizon by its reader), if any.
///
/// # Errors
/// A usage error when both give a sun; a direction without `--day-of-year`; a
/// `--day-of-year` that is not the time's, or that has no sun; `--sun-scattering` without
/// a sun; a sun that rounds to the horizon.
pub(crate) fn choose(
    flags: Option<(&SunSpec, &str)>,
    day: Option<u16>,
    scattering: bool,
    view: Option<&ViewSun<SunSpec>>,
) -> miette::Result<Option<PlanSunChoice>> {
    let (sun, given_by) = match (flags, view) {
        (Some((_, given)), Some(view)) => {
            return Err(irsig_cli::usage_error(format!(
                "{given} and the `sun` of the view file at {} both give a sun: give it once, \
                 by the flags or in the view file",
                view.location
            )));
        }
        (Some((spec, given)), None) => (spec, given.to_owned()),
        (None, Some(view)) => (
            &view.sun,
            format!("the `sun` of the view file at {}", view.location),
        ),
        (None, None) => {
            return match day {
                Some(d) => Err(irsig_cli::usage_error(format!(
                    "--day-of-year {d} without a sun: give --sun-zenith-deg, --sun-utc with the \
                     place, or a view file with a `sun`"
                ))),
                None if scattering => Err(irsig_cli::usage_error(
                    "--sun-scattering without a sun: give --sun-zenith-deg and --day-of-year, \
                     --sun-utc with the place, or a view file with a `sun`",
                )),
                None => Ok(None),
            };
        }
    };
    let position = sun
        .position()
        .map_err(|e| irsig_cli::usage_error(format!("{given_by}: {e}")))?;
    let zenith_deg = rounds_above_horizon(position.geometric_zenith_deg)
        .map_err(|e| irsig_cli::usage_error(format!("{given_by}: {e}")))?;
    let day_of_year = match (sun.day_of_year(), day) {
        (Some(of_time), Some(given)) if of_time != given => {
            return Err(irsig_cli::usage_error(format!(
                "--day-of-year {given}, but {given_by} is seen on day {of_time} of its year: \
                 leave out --day-of-year"
            )));
        }
        (Some(of_time), _) => of_time,
        (None, Some(given)) => given,
        (None, None) => {
            return Err(irsig_cli::usage_error(format!(
                "{given_by} is a direction, which has no date: give --day-of-year D (1-366) \
                 for the Earth-Sun distance, or give the sun by time and place"
            )));
        }
    };
    Ok(Some(PlanSunChoice {
        zenith_deg,
        day_of_year,
    }))
}

/// The suns of a day a plan is for (one build for every sun of the day): the table's zenith
/// angles, degrees, increasing, rounded to the 0.001° a deck holds; its day of the year;
/// and what the plan says of them.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DaySuns {
    pub zenith_deg: Vec<f64>,
    pub day_of_year: u16,
    pub note: String,
}

/// How many times a day's range is sampled at most (at least a minute apart) for its
/// highest sun and whether the sun crosses the horizon in it.
const SAMPLES: u32 = 20_000;

/// The Earth's rotation, degrees per second (360° a sidereal day, 86 164.1 s): no sun's
/// zenith angle moves faster.
const EARTH_TURN_DEG_PER_S: f64 = 360.0 / 86_164.1;

/// The last zenith angle a deck holds below the horizon's 90°, degrees.
const LAST_ZENITH_DEG: f64 = 89.999;

/// Whether a `--sun-utc` is a time range `START/END/STEP` rather than one time.
pub(crate) fn is_range(utc: &str) -> bool {
    utc.contains('/')
}

/// `--sun-utc` of `irsig-atmos plan`: one time, as every tool takes it, or a range
/// `START/END/STEP` (`irsig_formats::time::parse_times`: an end before the start, a step
/// of 0 and a time that is none are refused here, at the flag).
pub(crate) fn utc_or_range(s: &str) -> Result<String, String> {
    if is_range(s) {
        irsig_formats::time::parse_times(s)?;
    } else {
        irsig_atmosphere::sun::check_utc(s)?;
    }
    Ok(s.to_owned())
}

/// The suns of `--sun-zeniths-deg` on `--day-of-year`: those angles, as given.
///
/// # Errors
/// No `--day-of-year`; an angle that rounds to the horizon.
pub(crate) fn suns_of_zeniths(zenith_deg: &[f64], day: Option<u16>) -> miette::Result<DaySuns> {
    let Some(day_of_year) = day else {
        return Err(irsig_cli::usage_error(
            "--sun-zeniths-deg needs --day-of-year D (1-366) for the Earth-Sun distance",
        ));
    };
    for &z in zenith_deg {
        rounds_above_horizon(z)
            .map_err(|e| irsig_cli::usage_error(format!("--sun-zeniths-deg: {e}")))?;
    }
    let mut rows: Vec<f64> = zenith_deg
        .iter()
        .map(|z| (z * 1000.0).round() / 1000.0)
        .collect();
    rows.sort_by(f64::total_cmp);
    rows.dedup();
    Ok(DaySuns {
        note: format!("the suns of --sun-zeniths-deg, {} rows", rows.len()),
        zenith_deg: rows,
        day_of_year,
    })
}

/// The suns of the moments `utc` (`START/END/STEP`) seen from `place`: each moment's
/// geometric zenith angle (NREL's SPA, as `irsig-trace --sun-utc` sees it) while the sun
/// is above the horizon, the range's highest sun (sampled every minute, or less often than
/// [`SAMPLES`] over a long range) and, when the sun rises or sets in the range, 89.999°,
/// with the rows of [`irsig_atmosphere::plan::day_sun_rows`] between them: any lit time
/// of the range, a frame's or not, is then between the table's rows. The moments with the
/// sun at or below the horizon are dropped, and said. The day of the year is the first lit moment's
/// (a trace on another date scales the beam to its own Earth–Sun distance).
///
/// # Errors
/// A range `parse_times` refuses; a place without latitude or longitude; a `--day-of-year`
/// that is not the first lit moment's; no moment with the sun above the horizon.
pub(crate) fn suns_of_times(
    utc: &str,
    place: &irsig_cli::args::PlaceArgs,
    day: Option<u16>,
) -> miette::Result<DaySuns> {
    let times = irsig_formats::time::parse_times(utc)
        .map_err(|e| irsig_cli::usage_error(format!("--sun-utc {utc}: {e}")))?;
    let (Some(latitude_deg), Some(longitude_deg)) = (place.latitude_deg, place.longitude_deg)
    else {
        return Err(irsig_cli::usage_error(
            "--sun-utc needs --latitude-deg and --longitude-deg",
        ));
    };
    let sun_at = |t: f64| -> miette::Result<(f64, SunSpec)> {
        let spec = SunSpec::At {
            utc: irsig_model::time::format_utc(t),
            latitude_deg,
            longitude_deg,
            altitude_m: place.altitude_m,
            refraction: None,
            delta_t_s: None,
            delta_ut1_s: None,
        };
        let position = spec
            .position()
            .map_err(|e| irsig_cli::usage_error(format!("--sun-utc {utc}: {e}")))?;
        Ok((position.zenith_deg, spec))
    };
    let mut lit = Vec::new();
    let mut dark = 0_usize;
    let mut first_day = None;
    for &t in &times {
        let (zenith_deg, spec) = sun_at(t)?;
        if rounds_above_horizon(zenith_deg).is_err() {
            dark += 1;
            continue;
        }
        lit.push(zenith_deg);
        first_day = first_day.or_else(|| spec.day_of_year());
    }
    // A frame between two moments may see a sun beyond both: higher at a noon between
    // them, lower after a sunrise or before a sunset between them. The table reaches the
    // range's highest sun and, when the sun crosses the horizon in it, the last angle a
    // deck holds, so that every lit time of the range is between its rows.
    let frames = lit.len();
    let (start, end) = (times[0], times[times.len() - 1]);
    let step_s = ((end - start) / f64::from(SAMPLES)).max(60.0);
    let mut t = start;
    let (mut highest, mut crosses) = (f64::INFINITY, false);
    while t <= end {
        let (zenith_deg, _) = sun_at(t)?;
        if rounds_above_horizon(zenith_deg).is_ok() {
            highest = highest.min(zenith_deg);
        } else {
            crosses = true;
        }
        t += step_s;
    }
    if !lit.is_empty() {
        if highest.is_finite() {
            // The true highest lies within half a step of a sample, and no sun's zenith
            // angle moves faster than the Earth turns: the row goes that much higher.
            lit.push((highest - EARTH_TURN_DEG_PER_S * step_s / 2.0).max(0.0));
        }
        if crosses {
            lit.push(LAST_ZENITH_DEG);
        }
    }
    let Some(day_of_year) = first_day else {
        return Err(irsig_cli::usage_error(format!(
            "--sun-utc {utc}: the sun is at or below the horizon at all {} moments: plan a \
             night (leave the sun out)",
            times.len()
        )));
    };
    if let Some(given) = day.filter(|&d| d != day_of_year) {
        return Err(irsig_cli::usage_error(format!(
            "--day-of-year {given}, but the first lit moment of --sun-utc {utc} is on day \
             {day_of_year}: leave out --day-of-year"
        )));
    }
    let rows = irsig_atmosphere::plan::day_sun_rows(&lit);
    let dropped = if dark == 0 {
        String::new()
    } else {
        format!(
            "; {dark} of the {} moments have the sun at or below the horizon and are dropped \
             (no direct light)",
            times.len()
        )
    };
    Ok(DaySuns {
        note: format!(
            "the suns of {frames} lit moments of --sun-utc {utc}, {} rows with the day's \
             highest sun{} and the grid between them{dropped}",
            rows.len(),
            if crosses { ", the horizon's" } else { "" }
        ),
        zenith_deg: rows,
        day_of_year,
    })
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

    /// The sun of the flags `--sun-zenith-deg Z --sun-azimuth-deg 180`.
    fn zenith(zenith_deg: f64) -> SunSpec {
        SunSpec::Direction {
            zenith_deg,
            azimuth_deg: 180.0,
        }
    }

    #[test]
    fn flags_alone_as_before() {
        assert_eq!(choose(None, None, false, None).unwrap(), None);
        let flags = zenith(30.0);
        let sun = choose(Some((&flags, "--sun-zenith-deg 30")), Some(172), true, None)
            .unwrap()
            .unwrap();
        assert_eq!((sun.zenith_deg, sun.day_of_year), (30.0, 172));
        refused(
            choose(
                Some((&zenith(89.9996), "--sun-zenith-deg 89.9996")),
                Some(1),
                false,
                None,
            ),
            "--sun-zenith-deg 89.9996: 89.9996 deg rounds to 90",
        );
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
            choose(
                Some((&zenith(40.0), "--sun-zenith-deg 40")),
                Some(100),
                false,
                Some(&v),
            ),
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

    #[test]
    fn a_time_on_the_flags_gives_its_zenith_and_day_as_a_views_does() {
        let flags = at("2026-03-20T12:00:00Z").sun;
        let from_flags = choose(
            Some((&flags, "--sun-utc 2026-03-20T12:00:00Z")),
            None,
            false,
            None,
        )
        .unwrap()
        .unwrap();
        let view = at("2026-03-20T12:00:00Z");
        let from_view = choose(None, None, false, Some(&view)).unwrap().unwrap();
        assert_eq!(from_flags, from_view);
        refused(
            choose(
                Some((&flags, "--sun-utc 2026-03-20T12:00:00Z")),
                Some(80),
                false,
                None,
            ),
            "--day-of-year 80, but --sun-utc 2026-03-20T12:00:00Z is seen on day 79",
        );
    }

    #[test]
    fn a_days_zenith_list_needs_its_day_and_a_range_is_checked_at_the_flag() {
        let suns = suns_of_zeniths(&[60.0, 30.0004, 45.0, 30.0], Some(172)).unwrap();
        assert_eq!(
            (suns.zenith_deg, suns.day_of_year),
            (vec![30.0, 45.0, 60.0], 172)
        );
        let e = suns_of_zeniths(&[30.0], None).unwrap_err().to_string();
        assert!(e.contains("--day-of-year"), "{e}");
        let e = suns_of_zeniths(&[30.0, 89.9996], Some(1))
            .unwrap_err()
            .to_string();
        assert!(e.contains("rounds to 90"), "{e}");
        // One time, or a range; a range that ends before it starts, or steps by 0, is none.
        assert!(utc_or_range("2026-06-21T12:00:00Z").is_ok());
        assert!(utc_or_range("2026-06-21T00:00:00Z/2026-06-22T00:00:00Z/PT1H").is_ok());
        assert!(is_range("2026-06-21T00:00:00Z/2026-06-22T00:00:00Z/PT1H"));
        assert!(!is_range("2026-06-21T12:00:00Z"));
        for bad in [
            "2026-06-22T00:00:00Z/2026-06-21T00:00:00Z/PT1H",
            "2026-06-21T00:00:00Z/2026-06-22T00:00:00Z/PT0S",
            "2026-06-21T00:00:00Z/2026-06-22T00:00:00Z",
            "2026-13-21T12:00:00Z",
        ] {
            assert!(utc_or_range(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_days_times_give_every_lit_moment_the_noon_and_the_horizon() {
        let place = irsig_cli::args::PlaceArgs {
            latitude_deg: Some(0.0),
            longitude_deg: Some(0.0),
            altitude_m: 0.0,
        };
        // The 2026 March equinox (14:46 UTC) at the equator on the prime meridian: the sun
        // rises about 06:07 and sets about 18:14 UTC (the equation of time, -7.4 min), so
        // 06:00 is dark and 07:00-18:00 lit; at the noon, 12:07, it stands |δ| = 0.39
        // deg/day x 2.65 h = 0.04 deg from the zenith, between two hours (12:00 is 1.9 deg
        // off): the first row is at or above it.
        let suns = suns_of_times(
            "2026-03-20T00:00:00Z/2026-03-21T00:00:00Z/PT1H",
            &place,
            None,
        )
        .unwrap();
        assert_eq!(suns.day_of_year, 79);
        assert!(suns.zenith_deg[0] <= 0.04, "{:?}", suns.zenith_deg);
        assert_eq!(suns.zenith_deg.last(), Some(&89.999));
        assert!(suns.note.contains("12 lit moments"), "{}", suns.note);
        assert!(suns.note.contains("13 of the 25 moments"), "{}", suns.note);
        let e = suns_of_times(
            "2026-03-20T00:00:00Z/2026-03-20T04:00:00Z/PT1H",
            &place,
            None,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("at all 5 moments"), "{e}");
        let e = suns_of_times(
            "2026-03-20T08:00:00Z/2026-03-20T10:00:00Z/PT1H",
            &place,
            Some(80),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("is on day 79"), "{e}");
    }
}
