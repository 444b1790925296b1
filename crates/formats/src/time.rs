//! Times as users and files write them, parsed into irsig's time: seconds since
//! 1970-01-01T00:00:00Z (`irsig_model::time`, which also formats them).
//!
//! Accepted forms (parsed by the `jiff` crate):
//! - RFC 3339 with `Z` or an offset: `2026-07-15T14:00:00Z`, `2026-07-15T14:00-06:00`
//!   (seconds may be left out);
//! - RFC 9557, a local time with an IANA time zone in brackets:
//!   `2026-07-15T14:00[America/Denver]`, its offset that day taken from the time zone
//!   database bundled with irsig (the same on every machine). A local time that the zone
//!   skips (a spring-forward gap) or repeats is refused rather than guessed.
//!
//! A time without an offset or a zone is refused: "14:00" means nothing until it is said
//! where.

/// The forms [`parse_time`] accepts, for messages.
pub const TIME_FORMS: &str = "an RFC 3339 time with an offset (2026-07-15T14:00:00Z, \
                              2026-07-15T14:00-06:00) or a local time in an IANA zone \
                              (2026-07-15T14:00[America/Denver])";

/// Parses a time (see the module's forms) into seconds since 1970-01-01T00:00:00Z.
///
/// # Errors
/// A time in none of the forms, a time zone the database does not have, a local time the
/// zone skips or repeats, or a time jiff cannot represent (years −9999 to 9999).
pub fn parse_time(text: &str) -> Result<f64, String> {
    use jiff::fmt::temporal::DateTimeParser;
    use jiff::tz::Disambiguation;
    // A local time the zone skips or repeats is refused, not moved.
    const PARSER: DateTimeParser = DateTimeParser::new().disambiguation(Disambiguation::Reject);
    let text = text.trim();
    if text.ends_with(']') {
        let zoned = PARSER.parse_zoned_datetime(text).map_err(|e| {
            format!("`{text}` is not a time in a known zone, or not one its zone has ({e}): expected {TIME_FORMS}")
        })?;
        return Ok(seconds(zoned.timestamp()));
    }
    let timestamp = PARSER.parse_timestamp(text).map_err(|e| {
        format!("`{text}` is not a time with an offset or a zone ({e}): expected {TIME_FORMS}")
    })?;
    Ok(seconds(timestamp))
}

/// The most times [`parse_times`] expands a range into.
pub const MAX_TIMES: usize = 1_000_000;

/// A list of times: one time, or a range `START/END/STEP` (ISO 8601's interval form) with
/// `STEP` a duration as ISO 8601 writes it (`PT1H`, `PT15M`) or plain seconds (`3600`),
/// expanded to `START, START + STEP, …` up to and including `END` when it falls on the
/// step. Seconds since 1970-01-01T00:00:00Z, increasing.
///
/// # Errors
/// A time [`parse_time`] refuses, a step that is not a positive duration, an end before
/// the start, or more than [`MAX_TIMES`] times.
pub fn parse_times(text: &str) -> Result<Vec<f64>, String> {
    // A zone's name holds `/` too (`America/Denver`): split outside brackets only.
    let mut parts: Vec<&str> = Vec::new();
    let (mut depth, mut from) = (0_i32, 0);
    for (i, c) in text.char_indices() {
        match c {
            '[' => depth += 1,
            ']' => depth -= 1,
            '/' if depth == 0 => {
                parts.push(&text[from..i]);
                from = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&text[from..]);
    let [start, end, step] = parts.as_slice() else {
        if parts.len() == 1 {
            return Ok(vec![parse_time(text)?]);
        }
        return Err(format!(
            "`{text}`: expected one time, or START/END/STEP such as \
             2026-07-15T00:00Z/2026-07-16T00:00Z/PT1H"
        ));
    };
    let (start_s, end_s) = (parse_time(start)?, parse_time(end)?);
    let step_s = parse_duration_s(step)?;
    if !(step_s.is_finite() && step_s > 0.0) {
        return Err(format!(
            "`{text}`: the step must be a positive duration, found {step_s} s"
        ));
    }
    if end_s < start_s {
        return Err(format!("`{text}`: the range ends before it starts"));
    }
    let count = ((end_s - start_s) / step_s + 1e-9).floor() + 1.0;
    if count > MAX_TIMES as f64 {
        return Err(format!(
            "`{text}` expands to {count} times: at most {MAX_TIMES} are accepted"
        ));
    }
    Ok((0..count as usize)
        .map(|k| start_s + k as f64 * step_s)
        .collect())
}

/// A duration as ISO 8601 writes it (`PT1H`, `PT15M`, `-PT1H`) or plain seconds (`3600`),
/// in seconds; its sign is the caller's to check.
///
/// # Errors
/// Text that is neither.
pub fn parse_duration_s(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(s) => Ok(s),
        Err(_) => Ok(text
            .trim()
            .parse::<jiff::SignedDuration>()
            .map_err(|e| {
                format!("`{text}` is not a step: expected a duration such as PT1H or seconds ({e})")
            })?
            .as_secs_f64()),
    }
}

fn seconds(t: jiff::Timestamp) -> f64 {
    t.as_second() as f64 + f64::from(t.subsec_nanosecond()) * 1e-9
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_gives_the_same_instant() {
        // By hand: 1970–2025 are 56 years with 14 leap days, so 2026-01-01 is day
        // 56 · 365 + 14 = 20 454 after the epoch; 15 July is 195 days later (31 + 28 + 31
        // + 30 + 31 + 30 + 14); 20:00 adds 72 000 s.
        let expect = (20_454.0 + 195.0) * 86_400.0 + 20.0 * 3600.0;
        assert_eq!(
            parse_time("2026-07-15T20:00:00Z").unwrap().to_bits(),
            f64::to_bits(expect)
        );
        assert_eq!(
            parse_time("2026-07-15T14:00-06:00").unwrap().to_bits(),
            f64::to_bits(expect)
        );
        // Denver keeps mountain daylight time (UTC−6) in July.
        assert_eq!(
            parse_time("2026-07-15T14:00[America/Denver]")
                .unwrap()
                .to_bits(),
            f64::to_bits(expect)
        );
    }

    #[test]
    fn a_time_without_a_place_or_in_no_zone_is_refused() {
        let e = parse_time("2026-07-15T14:00").unwrap_err();
        assert!(e.contains("expected an RFC 3339 time"), "{e}");
        let e = parse_time("2026-07-15T14:00[Mars/Olympus_Mons]").unwrap_err();
        assert!(e.contains("known zone"), "{e}");
        // Paris skips 02:00–03:00 on 29 March 2026.
        let e = parse_time("2026-03-29T02:30[Europe/Paris]").unwrap_err();
        assert!(e.contains("known zone"), "{e}");
        // An offset that disagrees with the zone is refused; the right one is taken.
        assert!(parse_time("2026-03-29T02:30+01:00[Europe/Paris]").is_err());
        assert_eq!(
            parse_time("2026-03-29T03:30+02:00[Europe/Paris]")
                .unwrap()
                .to_bits(),
            parse_time("2026-03-29T01:30Z").unwrap().to_bits()
        );
        assert!(parse_time("").is_err());
    }

    #[test]
    fn a_range_expands_to_its_steps() {
        let t = parse_times("2026-07-15T00:00Z/2026-07-15T03:00Z/PT1H").unwrap();
        let t0 = parse_time("2026-07-15T00:00Z").unwrap();
        assert_eq!(t, vec![t0, t0 + 3600.0, t0 + 7200.0, t0 + 10_800.0]);
        // Plain seconds; an end between steps is not reached.
        let t = parse_times("2026-07-15T00:00Z/2026-07-15T00:50Z/1200").unwrap();
        assert_eq!(t.len(), 3);
        assert_eq!(parse_times("2026-07-15T00:00Z").unwrap(), vec![t0]);
        // A zone's name holds a slash.
        assert_eq!(
            parse_times("2026-07-14T18:00[America/Denver]/2026-07-14T20:00[America/Denver]/PT1H")
                .unwrap(),
            vec![t0, t0 + 3600.0, t0 + 7200.0]
        );
        assert_eq!(
            parse_times("2026-07-14T18:00[America/Denver]").unwrap(),
            vec![t0]
        );
        for bad in [
            "2026-07-15T03:00Z/2026-07-15T00:00Z/PT1H",
            "2026-07-15T00:00Z/2026-07-15T03:00Z/PT0S",
            "2026-07-15T00:00Z/2026-07-15T03:00Z/0",
            "2026-07-15T00:00Z/2026-07-15T03:00Z/-PT1H",
            "2026-07-15T00:00Z/2026-07-15T03:00Z/soon",
            "2026-07-15T00:00Z/2026-07-15T03:00Z",
            "2026-07-15T00:00Z/2126-07-15T03:00Z/1",
        ] {
            assert!(parse_times(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn fractions_of_a_second_survive() {
        let t = parse_time("2026-07-15T20:00:00.25Z").unwrap();
        assert!((t.fract() - 0.25).abs() < 1e-9);
    }
}
