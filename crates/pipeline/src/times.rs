//! Frames in time: the `Times(start: ..., end: ..., step: ..., zone: ...)` sweep, one frame
//! per step from a local start time to a local end time in a time zone, and the check that
//! every frame's time lies inside the weather record a stage reads.
//!
//! The frames are spaced by the step in absolute time (seconds, UTC), the way the thermal
//! model steps, so that across a change of daylight-saving time they stay evenly spaced and
//! only their local clock labels jump. Each frame's variables name its moment in the forms
//! the tools and file names want: `time` (RFC 3339 with the zone's offset), `utc` (RFC 3339
//! UTC, what a sun by time takes), `time_utc` (compact UTC, what file names take:
//! `20010807T200000Z`, as `irsig-therm -o PREFIX` names its scenes), `date` and `clock`
//! (local, for labels).

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

use irsig_formats::ron_tree::{Kind, Node};

use crate::error::{ErrorKind, PipelineError};
use crate::spec::{Param, Source, StageSpec, fields_of};

/// The most frames one `Times` sweep may hold, as for a fly-by.
const FRAMES_MAX: usize = 100_000;

/// How the tools name the weather record a stage reads and the year a typical-year record
/// is read as, so that the frames' times can be checked against it before anything runs.
/// The program that fills [`crate::Tools`] gives it ([`crate::Tools::with_time_flags`]).
#[derive(Debug, Clone, Copy)]
pub struct TimeFlags {
    /// The input flag (without dashes) that names a weather record: `weather`.
    pub weather: &'static str,
    /// The parameter that reads a typical-year record as a given year: `weather-year`.
    pub weather_year: &'static str,
}

/// A `Times` sweep as read: each frame's moment and where its fields are in the file.
#[derive(Debug, Clone)]
pub(crate) struct TimesSpec {
    /// Each frame's moment, seconds since 1970-01-01T00:00:00Z, increasing.
    pub instants_s: Vec<f64>,
    /// The byte ranges of the `start` and `end` values, for errors about a time.
    pub start: (usize, usize),
    pub end: (usize, usize),
}

/// Reads `Times(start: "2001-08-07T00:00", end: "2001-08-07T23:00", step: "PT1H", zone:
/// "America/Denver")`: the frames' variables and the sweep's moments.
pub(crate) fn read(
    src: Source<'_>,
    node: &Node,
) -> Result<(Vec<BTreeMap<String, String>>, TimesSpec), PipelineError> {
    let f = fields_of(src, node, "Times", &["start", "end", "step", "zone"])?;
    let field = |name: &str, what: &str| -> Result<&Node, PipelineError> {
        f.get(name).copied().ok_or_else(|| {
            src.error(
                ErrorKind::Structure,
                node.start,
                node.end,
                format!("Times needs `{name}: {what}`"),
            )
        })
    };
    let zone_node = field("zone", "\"America/Denver\" (an IANA time zone) or \"UTC\"")?;
    let zone = text(
        src,
        zone_node,
        "a time zone such as \"America/Denver\" or \"UTC\"",
    )?;
    irsig_model::time::in_zone(0.0, zone).map_err(|e| {
        src.error(ErrorKind::Structure, zone_node.start, zone_node.end, e)
            .with_help("zones are named as the IANA database names them: Europe/Paris, UTC")
    })?;
    let start_node = field("start", "\"YYYY-MM-DDTHH:MM\", a local time in the zone")?;
    let end_node = field("end", "\"YYYY-MM-DDTHH:MM\", a local time in the zone")?;
    let start_s = local_time(src, start_node, zone)?;
    let end_s = local_time(src, end_node, zone)?;
    let step_node = field("step", "\"PT1H\" (an ISO 8601 duration) or seconds")?;
    let step_s = step(src, step_node)?;
    if end_s < start_s {
        return Err(src.error(
            ErrorKind::Structure,
            end_node.start,
            end_node.end,
            format!(
                "the frames' range ends before it starts: `end` is {}, `start` {}",
                irsig_model::time::format_utc(end_s),
                irsig_model::time::format_utc(start_s)
            ),
        ));
    }
    let count = ((end_s - start_s) / step_s).floor() + 1.0;
    if count > FRAMES_MAX as f64 {
        return Err(src.error(
            ErrorKind::Structure,
            node.start,
            node.end,
            format!("these times are {count} frames: one sweep holds at most {FRAMES_MAX}"),
        ));
    }
    // `count` is at most FRAMES_MAX.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let instants_s: Vec<f64> = (0..count as usize)
        .map(|k| start_s + k as f64 * step_s)
        .collect();
    let frames = instants_s
        .iter()
        .map(|&t| {
            variables(t, zone).map_err(|e| src.error(ErrorKind::Structure, node.start, node.end, e))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((
        frames,
        TimesSpec {
            instants_s,
            start: (start_node.start, start_node.end),
            end: (end_node.start, end_node.end),
        },
    ))
}

/// The variables of the frame at `time_s` in `zone`.
fn variables(time_s: f64, zone: &str) -> Result<BTreeMap<String, String>, String> {
    let local = irsig_model::time::in_zone(time_s, zone)?;
    let compact = irsig_model::time::compact_utc(time_s)
        .ok_or_else(|| format!("{time_s} s has no calendar date"))?;
    Ok(BTreeMap::from([
        ("time".to_owned(), local.rfc3339),
        ("utc".to_owned(), irsig_model::time::format_utc(time_s)),
        ("time_utc".to_owned(), compact),
        ("date".to_owned(), local.date),
        ("clock".to_owned(), local.clock),
    ]))
}

fn text<'n>(src: Source<'_>, node: &'n Node, what: &str) -> Result<&'n str, PipelineError> {
    match &node.kind {
        Kind::Str(s) if !s.contains(char::is_control) => Ok(s),
        Kind::Str(_) => Err(src.error(
            ErrorKind::ControlCharacter,
            node.start,
            node.end,
            "a time or a zone holds no control character",
        )),
        other => Err(src.error(
            ErrorKind::Structure,
            node.start,
            node.end,
            format!("expected {what} in quotes, found {}", other.describe()),
        )),
    }
}

/// A local date and time as the zone's clocks show it, without an offset: the zone gives
/// the offset, and a time the zone skips (a spring-forward gap) or shows twice is refused.
fn local_time(src: Source<'_>, node: &Node, zone: &str) -> Result<f64, PipelineError> {
    let value = text(src, node, "a local time such as \"2001-08-07T00:00\"")?;
    let bad = |message: String| src.error(ErrorKind::Structure, node.start, node.end, message);
    let date_time = value.trim();
    if date_time.contains(['[', ']', 'Z', 'z'])
        || date_time.get(10..).is_some_and(|t| t.contains(['+', '-']))
    {
        return Err(bad(format!(
            "`{value}`: write the local time without an offset or a zone, such as \
             \"2001-08-07T00:00\": the sweep's `zone` gives them"
        )));
    }
    irsig_formats::time::parse_time(&format!("{date_time}[{zone}]")).map_err(bad)
}

/// The step between frames: an ISO 8601 duration (`PT1H`, `PT15M`) or a number of
/// seconds, whole and positive (frames are named to the second).
fn step(src: Source<'_>, node: &Node) -> Result<f64, PipelineError> {
    let bad = |message: String| src.error(ErrorKind::Structure, node.start, node.end, message);
    let step_s = match &node.kind {
        Kind::Number(n) => n
            .replace('_', "")
            .parse::<f64>()
            .map_err(|_| bad(format!("`{n}` is not a number of seconds")))?,
        Kind::Str(s) => irsig_formats::time::parse_duration_s(s).map_err(bad)?,
        other => {
            return Err(bad(format!(
                "expected a step such as \"PT1H\" or 3600 (seconds), found {}",
                other.describe()
            )));
        }
    };
    if !(step_s.is_finite() && step_s >= 1.0 && step_s.fract() == 0.0) {
        return Err(bad(format!(
            "a step of {step_s} s: the step between frames must be a whole number of seconds, \
             at least 1 (frames are named to the second)"
        )));
    }
    Ok(step_s)
}

/// A weather record's first and last time stamps, by (file, year it is read as); `None`
/// when the file cannot be read now (it is made by a stage, or broken: the tool that reads
/// it says so when it runs).
pub(crate) type WeatherSpans = HashMap<(PathBuf, Option<i64>), Option<(f64, f64)>>;

/// Checks that the frames a stage runs for (`instants_s`, from the sweep `times`) lie inside
/// the weather record it reads through the tools' weather flag, if it reads one that exists:
/// a moment outside the record cannot be simulated, and the tool would refuse it only when
/// it runs. The error is at the sweep's `start` (a frame before the record) or `end` (after).
pub(crate) fn check_weather(
    src: Source<'_>,
    base_dir: &Path,
    flags: &TimeFlags,
    stage: &StageSpec,
    (times, instants_s): (&TimesSpec, &[f64]),
    spans: &mut WeatherSpans,
) -> Result<(), PipelineError> {
    let (Some(&first), Some(&last)) = (instants_s.first(), instants_s.last()) else {
        return Ok(());
    };
    let Some((_, path)) = stage
        .inputs
        .iter()
        .find(|(k, _)| k.value.trim_start_matches('-') == flags.weather)
    else {
        return Ok(());
    };
    if path.value.contains('{') {
        // A record per frame is checked by the tool itself.
        return Ok(());
    }
    let year = stage
        .params
        .iter()
        .find(|(k, _)| k.value.trim_start_matches('-') == flags.weather_year)
        .and_then(|(_, v)| match v {
            Param::One(y) => y.value.parse::<i64>().ok(),
            _ => None,
        })
        .or_else(|| irsig_model::time::year_utc(first));
    let file = base_dir.join(&path.value);
    let span = *spans.entry((file.clone(), year)).or_insert_with(|| {
        let bytes = irsig_formats::file::read_file(&file).ok()?;
        let weather = irsig_formats::weather::read(
            &path.value,
            &bytes,
            &irsig_formats::weather::Options { year },
        )
        .ok()?;
        weather.span_s()
    });
    let Some((first_s, last_s)) = span else {
        return Ok(());
    };
    let outside = if first < first_s {
        Some((times.start, first))
    } else if last > last_s {
        Some((times.end, last))
    } else {
        None
    };
    let Some(((start, end), at)) = outside else {
        return Ok(());
    };
    let fmt = irsig_model::time::format_utc;
    Err(src
        .error(
            ErrorKind::Structure,
            start,
            end,
            format!(
                "a frame at {} is outside the weather record `{}`, which runs from {} to {}: \
                 a moment outside the record cannot be simulated",
                fmt(at),
                path.value,
                fmt(first_s),
                fmt(last_s)
            ),
        )
        .with_help(format!(
            "the stage on line {} reads that record; give times inside it (and room before \
             the first frame for the thermal model's spin-up), or a record that covers them",
            src.line(stage.start)
        )))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn times(text: &str) -> Result<Vec<BTreeMap<String, String>>, PipelineError> {
        let root = irsig_formats::ron_tree::parse("p.ron", text, "pipeline").unwrap();
        read(
            Source {
                file: "p.ron",
                text,
            },
            &root,
        )
        .map(|(frames, _)| frames)
    }

    #[test]
    fn a_day_in_a_zone_is_one_frame_per_step() {
        let frames = times(
            r#"Times(start: "2001-08-07T00:00", end: "2001-08-07T23:00", step: "PT1H", zone: "America/Denver")"#,
        )
        .unwrap();
        assert_eq!(frames.len(), 24);
        // Local midnight in mountain daylight time is 06:00 UTC.
        assert_eq!(frames[0]["time"], "2001-08-07T00:00:00-06:00");
        assert_eq!(frames[0]["utc"], "2001-08-07T06:00:00Z");
        assert_eq!(frames[0]["time_utc"], "20010807T060000Z");
        assert_eq!(frames[14]["clock"], "14:00");
        assert_eq!(frames[23]["utc"], "2001-08-08T05:00:00Z");
        assert_eq!(frames[23]["date"], "2001-08-07");
        // Seconds as a number; an end between steps is not reached; UTC by name.
        let frames = times(
            r#"Times(start: "2001-08-07T00:00", end: "2001-08-07T00:50", step: 1200, zone: "UTC")"#,
        )
        .unwrap();
        let clocks: Vec<&str> = frames.iter().map(|f| f["clock"].as_str()).collect();
        assert_eq!(clocks, ["00:00", "00:20", "00:40"]);
        assert_eq!(frames[1]["time"], "2001-08-07T00:20:00+00:00");
    }

    #[test]
    fn across_a_clock_change_the_frames_stay_evenly_spaced() {
        // Denver's clocks went back from 02:00 MDT to 01:00 MST on 28 October 2001: hourly
        // frames from midnight read 00:00, 01:00, 01:00 (again, an hour later), 02:00.
        let frames = times(
            r#"Times(start: "2001-10-28T00:00", end: "2001-10-28T02:00", step: "PT1H", zone: "America/Denver")"#,
        )
        .unwrap();
        let utc: Vec<&str> = frames.iter().map(|f| f["time_utc"].as_str()).collect();
        assert_eq!(
            utc,
            [
                "20011028T060000Z",
                "20011028T070000Z",
                "20011028T080000Z",
                "20011028T090000Z"
            ]
        );
        let time: Vec<&str> = frames.iter().map(|f| f["time"].as_str()).collect();
        assert_eq!(
            time,
            [
                "2001-10-28T00:00:00-06:00",
                "2001-10-28T01:00:00-06:00",
                "2001-10-28T01:00:00-07:00",
                "2001-10-28T02:00:00-07:00"
            ]
        );
    }

    /// The error of `text`'s `Times(...)`, at (column) in its only line, saying `says`.
    fn refused(text: &str, needle: &str, says: &str) {
        let e = times(text).unwrap_err();
        let column = text.find(needle).unwrap() + 1;
        assert_eq!(e.line_column(), Some((1, column)), "{text}: {e}");
        assert!(e.to_string().contains(says), "{text}: {e}");
    }

    #[test]
    fn bad_times_are_refused_at_their_value() {
        let ok = r#"Times(start: "2001-08-07T00:00", end: "2001-08-07T23:00", step: "PT1H", zone: "America/Denver")"#;
        // An end before the start.
        refused(
            &ok.replace("2001-08-07T23:00", "2001-08-06T23:00"),
            "\"2001-08-06T23:00",
            "ends before it starts",
        );
        // A step of 0, as a duration or seconds; a negative step; not a step.
        refused(&ok.replace("\"PT1H\"", "\"PT0S\""), "\"PT0S", "at least 1");
        refused(&ok.replace("\"PT1H\"", "0"), "0, zone", "at least 1");
        refused(
            &ok.replace("\"PT1H\"", "\"-PT1H\""),
            "\"-PT1H",
            "at least 1",
        );
        refused(&ok.replace("\"PT1H\"", "\"soon\""), "\"soon", "not a step");
        refused(&ok.replace("\"PT1H\"", "0.5"), "0.5", "whole number");
        // A zone that does not exist.
        refused(
            &ok.replace("America/Denver", "Mars/Olympus_Mons"),
            "\"Mars",
            "not a time zone",
        );
        // A local time the zone skips: Denver's clocks jumped from 02:00 to 03:00 on
        // 1 April 2001.
        refused(
            &ok.replace("2001-08-07T00:00", "2001-04-01T02:30"),
            "\"2001-04-01T02:30",
            "not a time in a known zone",
        );
        // An offset of its own; a missing field; an unknown one.
        refused(
            &ok.replace("2001-08-07T00:00", "2001-08-07T00:00-06:00"),
            "\"2001-08-07T00:00-06:00",
            "without an offset",
        );
        refused(
            r#"Times(start: "2001-08-07T00:00", end: "2001-08-07T23:00", zone: "UTC")"#,
            "Times",
            "needs `step",
        );
        refused(&ok.replace("zone:", "tz:"), "tz:", "unknown field `tz`");
        // Too many frames.
        refused(
            &ok.replace("\"PT1H\"", "1")
                .replace("2001-08-07T23:00", "2001-08-09T00:00"),
            "Times",
            "at most 100000",
        );
    }
}
