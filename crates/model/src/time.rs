//! Times inside irsig: seconds since 1970-01-01T00:00:00Z (UTC, leap seconds not counted,
//! as POSIX and RFC 3339 count), an `f64`, exact to a microsecond for millennia either side
//! of 1970. The calendar is the `jiff` crate's (proleptic Gregorian); this module turns
//! calendar fields into such seconds and back into the forms messages and file names use.
//! Parsing what users type (offsets, time zones, ranges) is `irsig_formats::time`'s.

/// Seconds since 1970-01-01T00:00:00Z of a UTC date and time. `hour` may be 24 (the end of
/// the day, as hourly weather files write midnight).
///
/// # Errors
/// A month outside 1–12, a day the month does not have, an hour above 24, a minute above
/// 59, seconds outside 0–60 (60 for a leap second's stamp, taken as the next minute's
/// start), or a year outside 1–9999: the message says which.
pub fn utc_seconds(
    year: i64,
    month: u32,
    day: u32,
    hour: u32,
    minute: u32,
    second: f64,
) -> Result<f64, String> {
    if !(1..=9999).contains(&year) {
        return Err(format!("year {year}: expected 1 to 9999"));
    }
    if hour > 24 {
        return Err(format!("hour {hour}: expected 0 to 24"));
    }
    if minute > 59 {
        return Err(format!("minute {minute}: expected 0 to 59"));
    }
    if !(0.0..61.0).contains(&second) {
        return Err(format!("second {second}: expected 0 to 60"));
    }
    let (Ok(y), Ok(m), Ok(d)) = (i16::try_from(year), i8::try_from(month), i8::try_from(day))
    else {
        return Err(format!("{year}-{month:02}-{day:02} is not a date"));
    };
    let date = jiff::civil::Date::new(y, m, d)
        .map_err(|e| format!("{year}-{month:02}-{day:02} is not a date of the calendar ({e})"))?;
    let midnight = date
        .to_zoned_datetime(jiff::tz::TimeZone::UTC)
        .map_err(|e| format!("{year}-{month:02}-{day:02}: {e}"))?
        .timestamp()
        .as_second();
    Ok(midnight as f64 + f64::from(hour * 3600 + minute * 60) + second)
}

fn timestamp(time_s: f64) -> Option<jiff::Timestamp> {
    if !time_s.is_finite() || time_s.abs() > 2.5e11 {
        return None;
    }
    jiff::Timestamp::from_microsecond((time_s * 1e6).round() as i64).ok()
}

fn utc(time_s: f64) -> Option<jiff::ZonedDateTime> {
    let t = jiff::Timestamp::from_second(time_s.floor() as i64).ok()?;
    Some(t.to_zoned_datetime(jiff::tz::TimeZone::UTC))
}

/// `time_s` as RFC 3339 UTC, `YYYY-MM-DDTHH:MM:SS[.fraction]Z`, to the microsecond; a time
/// outside the calendar's years as seconds (`1e300 s`).
#[must_use]
pub fn format_utc(time_s: f64) -> String {
    timestamp(time_s).map_or_else(|| format!("{time_s} s"), |t| t.to_string())
}

/// `time_s` compact, for file names: `20260715T140000Z` (whole seconds, rounded down).
#[must_use]
pub fn compact_utc(time_s: f64) -> Option<String> {
    Some(utc(time_s)?.strftime("%Y%m%dT%H%M%SZ").to_string())
}

/// The day of the year of `time_s` in UTC, 1–366.
#[must_use]
pub fn day_of_year_utc(time_s: f64) -> Option<u16> {
    u16::try_from(utc(time_s)?.day_of_year()).ok()
}

/// The year of `time_s` in UTC.
#[must_use]
pub fn year_utc(time_s: f64) -> Option<i64> {
    Some(i64::from(utc(time_s)?.year()))
}

/// A moment as the clocks of one time zone show it: what a frame of a day is named and
/// labelled by.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ZonedTime {
    /// RFC 3339 with the zone's offset at that moment, whole seconds:
    /// `2001-08-07T14:00:00-06:00` (what `irsig_formats::time::parse_time` reads back).
    pub rfc3339: String,
    /// The local date, `2001-08-07`.
    pub date: String,
    /// The local time of day, `14:00` (hours and minutes).
    pub clock: String,
}

/// `time_s` (rounded down to the second) on the clocks of the IANA time zone `zone`
/// (`America/Denver`, `UTC`), from the time zone database bundled with irsig, so that the
/// same moment reads the same on every machine.
///
/// # Errors
/// A zone the database does not have, or a time outside the calendar's years.
pub fn in_zone(time_s: f64, zone: &str) -> Result<ZonedTime, String> {
    let tz = jiff::tz::TimeZone::get(zone).map_err(|e| {
        format!("`{zone}` is not a time zone of the IANA database irsig carries ({e})")
    })?;
    let at = timestamp(time_s.floor()).ok_or_else(|| format!("{time_s} s has no calendar date"))?;
    let local = at.to_zoned_datetime(tz);
    Ok(ZonedTime {
        rfc3339: local.strftime("%Y-%m-%dT%H:%M:%S%:z").to_string(),
        date: local.strftime("%Y-%m-%d").to_string(),
        clock: local.strftime("%H:%M").to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_calendar_agrees_with_an_independent_one() {
        // Expected seconds from Python's datetime (UTC).
        assert_eq!(utc_seconds(1970, 1, 1, 0, 0, 0.0), Ok(0.0));
        assert_eq!(utc_seconds(2000, 3, 1, 0, 0, 0.0), Ok(951_868_800.0));
        assert_eq!(utc_seconds(2001, 8, 7, 14, 0, 0.0), Ok(997_192_800.0));
        assert_eq!(utc_seconds(2024, 2, 29, 12, 30, 0.0), Ok(1_709_209_800.0));
        assert_eq!(utc_seconds(1969, 12, 31, 23, 59, 0.0), Ok(-60.0));
        // Hour 24 is the next day's midnight, as hourly files write it.
        assert_eq!(
            utc_seconds(2001, 8, 6, 24, 0, 0.0),
            utc_seconds(2001, 8, 7, 0, 0, 0.0)
        );
        assert!(utc_seconds(2001, 2, 29, 0, 0, 0.0).is_err());
        assert!(
            utc_seconds(2000, 2, 29, 0, 0, 0.0).is_ok(),
            "2000 is a leap year"
        );
        assert!(utc_seconds(1900, 2, 29, 0, 0, 0.0).is_err(), "1900 is not");
        assert!(utc_seconds(2001, 13, 1, 0, 0, 0.0).is_err());
        assert!(utc_seconds(2001, 1, 1, 25, 0, 0.0).is_err());
        assert!(utc_seconds(2001, 1, 1, 0, 60, 0.0).is_err());
        assert_eq!(format_utc(997_192_800.0), "2001-08-07T14:00:00Z");
        assert_eq!(format_utc(-60.0), "1969-12-31T23:59:00Z");
        assert_eq!(format_utc(951_868_800.25), "2000-03-01T00:00:00.25Z");
        assert_eq!(format_utc(f64::NAN), "NaN s");
        // Every day of four years, through a leap day, round-trips.
        let start = utc_seconds(1999, 1, 1, 0, 0, 0.0).unwrap();
        for day in 0..4 * 366 {
            let t = start + 86_400.0 * f64::from(day);
            let s = format_utc(t);
            let (y, m, d) = (&s[0..4], &s[5..7], &s[8..10]);
            let back = utc_seconds(
                y.parse().unwrap(),
                m.parse().unwrap(),
                d.parse().unwrap(),
                0,
                0,
                0.0,
            );
            assert_eq!(back, Ok(t), "{s}");
        }
    }

    #[test]
    fn forms_for_people_and_file_names() {
        let t = utc_seconds(2001, 8, 7, 14, 0, 0.0).unwrap();
        assert_eq!(format_utc(t), "2001-08-07T14:00:00Z");
        assert_eq!(format_utc(t + 0.25), "2001-08-07T14:00:00.25Z");
        assert_eq!(format_utc(f64::NAN), "NaN s");
        assert_eq!(compact_utc(t).as_deref(), Some("20010807T140000Z"));
        // 7 August of a common year: 31 + 28 + 31 + 30 + 31 + 30 + 31 + 7 = 219.
        assert_eq!(day_of_year_utc(t), Some(219));
        assert_eq!(year_utc(t), Some(2001));
    }

    #[test]
    fn a_moment_on_a_zones_clocks() {
        // 20:00 UTC on 7 August 2001: Denver keeps mountain daylight time (UTC-6) then,
        // Sydney eastern standard time (UTC+10), so 14:00 on the 7th and 06:00 on the 8th.
        let t = utc_seconds(2001, 8, 7, 20, 0, 0.0).unwrap();
        let denver = in_zone(t, "America/Denver").unwrap();
        assert_eq!(denver.rfc3339, "2001-08-07T14:00:00-06:00");
        assert_eq!(
            (denver.date.as_str(), denver.clock.as_str()),
            ("2001-08-07", "14:00")
        );
        let sydney = in_zone(t, "Australia/Sydney").unwrap();
        assert_eq!(sydney.rfc3339, "2001-08-08T06:00:00+10:00");
        assert_eq!(
            in_zone(t, "UTC").unwrap().rfc3339,
            "2001-08-07T20:00:00+00:00"
        );
        // In January Denver keeps standard time (UTC-7).
        let winter = utc_seconds(2001, 1, 15, 20, 0, 0.0).unwrap();
        assert_eq!(
            in_zone(winter, "America/Denver").unwrap().rfc3339,
            "2001-01-15T13:00:00-07:00"
        );
        assert!(in_zone(t, "Mars/Olympus_Mons").is_err());
        assert!(in_zone(f64::NAN, "UTC").is_err());
    }
}
