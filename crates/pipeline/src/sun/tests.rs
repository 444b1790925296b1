use super::*;
use crate::{Pipeline, Plan, Tools};
use std::path::{Path, PathBuf};

fn plan(text: &str) -> Result<Plan, PipelineError> {
    let mut tools = Tools::new(|t| Some(PathBuf::from(format!("/opt/irsig-{t}"))));
    tools.with_sun_flags(FLAGS);
    Pipeline::parse("p.ron", text, Path::new("/nonexistent"))?.plan(&tools)
}

/// The tools' spelling of a sun, as a program filling `Tools` gives it (irsig-run's
/// is irsig-cli's).
const FLAGS: SunFlags = SunFlags {
    field: |field| match field {
        SunField::ZenithDeg => "sun-zenith-deg",
        SunField::AzimuthDeg => "sun-azimuth-deg",
        SunField::Utc => "sun-utc",
        SunField::LatitudeDeg => "latitude-deg",
        SunField::LongitudeDeg => "longitude-deg",
        SunField::AltitudeM => "altitude-m",
        _ => "not-a-trace-flag",
    },
    day_of_year: "day-of-year",
};

#[test]
fn a_sun_without_the_tools_spelling_is_refused() {
    let text = lit("Direction(zenith_deg: 30.0, azimuth_deg: 120)", "", "");
    let tools = Tools::new(|t| Some(PathBuf::from(format!("/opt/irsig-{t}"))));
    let e = Pipeline::parse("p.ron", &text, Path::new("/nonexistent"))
        .unwrap()
        .plan(&tools)
        .unwrap_err()
        .to_string();
    assert!(e.contains("p.ron:2:8") && e.contains("does not say"), "{e}");
}

/// A pipeline of a plan, a trace and a sensor stage under `sun`, the plan with
/// `plan_params`, the trace with `trace_params`.
fn lit(sun: &str, plan_params: &str, trace_params: &str) -> String {
    format!(
        "(\n  sun: {sun},\n  stages: [\n    (tool: \"atmos plan\", params: {{{plan_params}}}, \
         outputs: {{\"o\": \"plan\"}}),\n    (tool: \"trace\", inputs: {{\"view\": \"plan\"}}, \
         params: {{{trace_params}}}, outputs: {{\"o\": \"frame\"}}),\n    (tool: \"sensor\", \
         args: [\"frame\"], outputs: {{\"o\": \"s.exr\"}}),\n  ],\n)"
    )
}

fn argv(p: &Plan, tool: &str) -> Vec<String> {
    p.steps
        .iter()
        .find(|s| s.tool == tool)
        .unwrap()
        .argv
        .clone()
}

#[test]
fn the_pipelines_sun_becomes_every_trace_stages_flags() {
    let p = plan(&lit(
        "Direction(zenith_deg: 30.0, azimuth_deg: 120)",
        "\"sun-zenith-deg\": 30.0, \"day-of-year\": 95",
        "\"band\": \"4-5\"",
    ))
    .unwrap();
    assert_eq!(
        argv(&p, "trace"),
        [
            "irsig-trace",
            "--view",
            "plan",
            "--band",
            "4-5",
            "--sun-zenith-deg",
            "30.0",
            "--sun-azimuth-deg",
            "120",
            "-o",
            "frame"
        ]
    );
    // Other stages are as written.
    assert_eq!(argv(&p, "sensor"), ["irsig-sensor", "frame", "-o", "s.exr"]);
    // By time and place, `Some(...)` around it; the plan at the sun's zenith and day.
    let spec = SunSpec::At {
        utc: "2024-06-21T12:00:00Z".into(),
        latitude_deg: 51.5,
        longitude_deg: -0.1,
        altitude_m: 20.0,
        refraction: None,
        delta_t_s: None,
        delta_ut1_s: None,
    };
    let z = spec.position().unwrap().zenith_deg;
    let sun = "Some(At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 51.5, \
               longitude_deg: -0.1, altitude_m: 20))";
    let p = plan(&lit(
        sun,
        &format!("\"sun-zenith-deg\": {z:.3}, \"day-of-year\": 173"),
        "",
    ))
    .unwrap();
    assert_eq!(
        argv(&p, "trace"),
        [
            "irsig-trace",
            "--view",
            "plan",
            "--sun-utc",
            "2024-06-21T12:00:00Z",
            "--latitude-deg",
            "51.5",
            "--longitude-deg",
            "-0.1",
            "--altitude-m",
            "20",
            "-o",
            "frame"
        ]
    );
}

/// The error of `text`, its line and column, and whether its message says `says`.
fn refused(text: &str, line: usize, column: usize, says: &str) {
    let e = plan(text).unwrap_err();
    let shown = e.to_string();
    assert!(shown.contains(says), "expected `{says}`: {shown}");
    let at = format!("p.ron:{line}:{column}");
    assert!(shown.contains(&at), "expected {at}: {shown}");
}

/// Under a sun given by time and place, a plan stage without a zenith of its own takes the
/// trace stages' sun flags; a day of its own is then a second sun.
#[test]
fn a_plan_under_a_sun_by_time_takes_the_trace_stages_flags() {
    let sun = "At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 51.5, longitude_deg: -0.1, \
               altitude_m: 20)";
    let p = plan(&lit(sun, "", "")).unwrap();
    let flags = [
        "--sun-utc",
        "2024-06-21T12:00:00Z",
        "--latitude-deg",
        "51.5",
        "--longitude-deg",
        "-0.1",
        "--altitude-m",
        "20",
    ];
    let plan_argv = argv(&p, "atmos");
    assert!(
        plan_argv.windows(flags.len()).any(|w| w == flags),
        "{plan_argv:?}"
    );
    assert!(
        argv(&p, "trace").windows(flags.len()).any(|w| w == flags),
        "{:?}",
        argv(&p, "trace")
    );
    refused(&lit(sun, "\"day-of-year\": 173", ""), 4, 35, "second sun");
}

#[test]
fn a_sun_the_plan_is_not_for_or_given_twice_is_refused_at_its_place() {
    let good = "\"sun-zenith-deg\": 30.0, \"day-of-year\": 95";
    let sun = "Direction(zenith_deg: 30.0, azimuth_deg: 120)";
    // The plan at 30.5 deg: at its value (line 4; `params: {"sun-zenith-deg": ` ends at
    // column 52, after `    (tool: "atmos plan", `).
    refused(
        &lit(sun, "\"sun-zenith-deg\": 30.5", ""),
        4,
        53,
        "not the pipeline's",
    );
    // A plan for a night.
    refused(&lit(sun, "\"day-of-year\": 95", ""), 4, 12, "for a night");
    // A trace stage's own sun: at its key.
    refused(
        &lit(sun, good, "\"sun-azimuth-deg\": 10"),
        5,
        56,
        "second sun",
    );
    // A day other than the date's.
    let london = "At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 51.5, longitude_deg: 0)";
    let z = SunSpec::At {
        utc: "2024-06-21T12:00:00Z".into(),
        latitude_deg: 51.5,
        longitude_deg: 0.0,
        altitude_m: 0.0,
        refraction: None,
        delta_t_s: None,
        delta_ut1_s: None,
    }
    .position()
    .unwrap()
    .zenith_deg;
    refused(
        &lit(
            london,
            &format!("\"sun-zenith-deg\": {z:.3}, \"day-of-year\": 172"),
            "",
        ),
        4,
        76,
        "day 173",
    );
}

#[test]
fn bad_sun_values_are_refused_at_their_line_and_column() {
    // Line 2 is `  sun: ...`; the value starts at column 8.
    for (sun, column, says) in [
        ("Direction(zenith_deg: 95.0, azimuth_deg: 0)", 30, "horizon"),
        (
            "Direction(zenith_deg: 30.0, azimuth_deg: 360)",
            49,
            "azimuth",
        ),
        ("Direction(zenith_deg: 30.0)", 8, "no `azimuth_deg`"),
        (
            "Direction(zenith_deg: 30.0, azimuth_deg: 0, hour: 12)",
            52,
            "hour",
        ),
        (
            "Direction(zenith_deg: \"30\", azimuth_deg: 0)",
            30,
            "expected a number",
        ),
        (
            "At(utc: \"2024-13-01T12:00:00Z\", latitude_deg: 0, longitude_deg: 0)",
            16,
            "utc",
        ),
        (
            "At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 95, longitude_deg: 0)",
            54,
            "latitude",
        ),
        (
            "At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 0, longitude_deg: 0, delta_t_s: 69)",
            75,
            "delta_t_s",
        ),
        // A flag hidden in the time is one word, the time, and no time at that.
        (
            "At(utc: \"--o=/etc/passwd\", latitude_deg: 0, longitude_deg: 0)",
            16,
            "utc",
        ),
        (
            "At(utc: \"2024-06-21T12:00:00Z\\n-o x\", latitude_deg: 0, longitude_deg: 0)",
            37,
            "control",
        ),
        ("Noon", 8, "expected `sun: Direction"),
    ] {
        refused(&lit(sun, "", ""), 2, column, says);
    }
}

/// A day at Golden, Colorado: hourly frames of 7 August 2001, mountain daylight time,
/// each frame's sun; a plan per frame and a trace per frame, with `plan` and `trace`
/// extra parameters.
fn day(plan: &str, trace: &str) -> String {
    format!(
        "(\n  sweeps: {{\"day\": Times(start: \"2001-08-07T00:00\", end: \"2001-08-07T23:00\", \
         step: \"PT1H\", zone: \"America/Denver\")}},\n  sun: At(utc: \"{{utc}}\", \
         latitude_deg: 39.74, longitude_deg: -105.18),\n  stages: [\n    {plan}\n    \
         (name: \"trace\", tool: \"trace\", sweep: \"day\", inputs: {{\"view\": \
         \"p-{{time_utc}}.ron\"}}, {trace}outputs: {{\"o\": \"f-{{time_utc}}\"}}),\n  ],\n)"
    )
}

const PLAN_PER_FRAME: &str = "(name: \"plan\", tool: \"atmos plan\", sweep: \"day\", \
                              outputs: {\"o\": \"p-{time_utc}.ron\"}),";

/// The words after `--sun-utc` in a step, if any.
fn sun_of(p: &Plan, name: &str) -> Option<Vec<String>> {
    let step = p.steps.iter().find(|s| s.name == name).unwrap();
    let at = step.argv.iter().position(|w| w == "--sun-utc")?;
    Some(step.argv[at..].to_vec())
}

#[test]
fn each_frame_is_lit_by_the_sun_of_its_time_and_a_night_frame_by_none() {
    let p = plan(&day(PLAN_PER_FRAME, "")).unwrap();
    // 14:00 MDT is 20:00 UTC: the trace and its frame's plan take that sun.
    let afternoon = [
        "--sun-utc",
        "2001-08-07T20:00:00Z",
        "--latitude-deg",
        "39.74",
        "--longitude-deg",
        "-105.18",
        "-o",
        "f-20010807T200000Z",
    ];
    assert_eq!(sun_of(&p, "trace[15]").unwrap(), afternoon);
    assert_eq!(sun_of(&p, "plan[15]").unwrap()[..6], afternoon[..6]);
    // The frames lit are those whose sun SPA puts above the horizon, no others: a
    // summer day at 40 deg N is about 14 hours long, so 13 or 14 hourly frames.
    let mut lit = Vec::new();
    for hour in 0..24u32 {
        let utc = irsig_model::time::format_utc(
            irsig_model::time::utc_seconds(2001, 8, 7, 6, 0, 0.0).unwrap()
                + f64::from(hour) * 3600.0,
        );
        let above = SunSpec::At {
            utc,
            latitude_deg: 39.74,
            longitude_deg: -105.18,
            altitude_m: 0.0,
            refraction: None,
            delta_t_s: None,
            delta_ut1_s: None,
        }
        .position()
        .unwrap()
        .zenith_deg
            < 90.0;
        let frame = hour + 1;
        assert_eq!(
            sun_of(&p, &format!("trace[{frame}]")).is_some(),
            above,
            "frame {frame}"
        );
        assert_eq!(sun_of(&p, &format!("plan[{frame}]")).is_some(), above);
        if above {
            lit.push(hour);
        }
    }
    assert!((13..=14).contains(&lit.len()), "{lit:?}");
    assert!(!lit.contains(&0) && lit.contains(&12), "{lit:?}");
    // Steps of a time sweep say what time they show.
    let noon = p.steps.iter().find(|s| s.name == "trace[13]").unwrap();
    assert_eq!(noon.described(), "trace[13] (2001-08-07T12:00:00-06:00)");
}

#[test]
fn a_frames_sun_is_given_once_and_only_to_stages_that_run_per_frame() {
    let text = day(PLAN_PER_FRAME, "");
    // A trace stage that runs once has no frame's time.
    let once = text.replace(
        "(name: \"trace\", tool: \"trace\", sweep: \"day\",",
        "(name: \"trace\", tool: \"trace\",",
    );
    let e = plan(&once).unwrap_err().to_string();
    assert!(e.contains("runs once, at no frame's time"), "{e}");
    // A trace stage's own sun, a per-frame plan's own day.
    let e = plan(&day(PLAN_PER_FRAME, "params: {\"sun-utc\": \"{utc}\"}, "))
        .unwrap_err()
        .to_string();
    assert!(e.contains("second sun"), "{e}");
    let own_day = PLAN_PER_FRAME.replace("outputs:", "params: {\"day-of-year\": 219}, outputs:");
    let e = plan(&day(&own_day, "")).unwrap_err().to_string();
    assert!(e.contains("second sun") && e.contains("day-of-year"), "{e}");
}

#[test]
fn one_plan_for_the_day_must_hold_every_lit_frames_sun() {
    let once = |params: &str| {
        day(
            &format!(
                "(name: \"plan\", tool: \"atmos plan\", params: {{{params}}}, outputs: \
                 {{\"o\": \"day.ron\"}}),"
            ),
            "",
        )
        .replace("p-{time_utc}.ron", "day.ron")
    };
    // The lit frames run from 07:00 to 19:00 MDT, 13:00 to 01:00 UTC: a plan of the
    // suns from 12:00 to 02:00 UTC holds them all.
    assert!(
        plan(&once(
            "\"sun-utc\": \"2001-08-07T12:00:00Z/2001-08-08T02:00:00Z/PT10M\""
        ))
        .is_ok()
    );
    // One that stops at midnight UTC leaves the evening's frames without a table: the
    // error is at the times' end (line 2).
    let text = once("\"sun-utc\": \"2001-08-07T12:00:00Z/2001-08-08T00:00:00Z/PT10M\"");
    let e = plan(&text).unwrap_err();
    let shown = e.to_string();
    assert!(
        shown.contains("outside the atmosphere's sun table"),
        "{shown}"
    );
    let (line, column) = e.line_column().unwrap();
    assert_eq!(line, 2);
    assert_eq!(
        text.lines().nth(1).unwrap()[column - 1..].get(..18),
        Some("\"2001-08-07T23:00\"")
    );
    // One sun, or a night's plan, cannot light a day.
    for (params, says) in [
        ("\"sun-zenith-deg\": 30", "holds one sun"),
        ("\"sun-utc\": \"2001-08-07T20:00:00Z\"", "holds one sun"),
        ("\"atmosphere\": \"midlat-summer\"", "for a night"),
    ] {
        let e = plan(&once(params)).unwrap_err().to_string();
        assert!(e.contains(says), "{params}: {e}");
    }
}
