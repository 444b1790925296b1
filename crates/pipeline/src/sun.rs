//! The pipeline's `sun` (issue 30): one sun for the whole job, written once and given to
//! every `trace` stage as the tool's own sun flags, so that what runs is still exactly a
//! command line a user could type. An `atmos plan` stage in the same file must be planned
//! for that sun: its zenith angle must agree with the sun's within the solar table's
//! tolerance (the check irsig-trace makes later against the built table, made here before
//! anything runs), and with a sun given by time its day of the year with the date. A trace
//! stage that gives sun flags of its own is refused: the sun is given once. The flags are
//! the tools' to spell ([`SunFlags`], which the program filling [`crate::Tools`] gives): this
//! crate knows the sun's fields, not their flags.

use irsig_atmosphere::AtmosphereErrorKind;
use irsig_atmosphere::solar::ZENITH_TOLERANCE_DEG;
use irsig_atmosphere::sun::{SunField, SunSpec};
use irsig_formats::ron_tree::{Kind, Node};

use crate::error::{ErrorKind, PipelineError};
use crate::spec::{Param, Source, Spanned, StageSpec, fields_of, scalar};

/// How the tools spell a sun: the flag (without its dashes) of each field of a sun, as the
/// `trace` tool takes it and as an `atmos plan` stage gives its zenith angle, and the flag
/// of a plan's day of the year. The program that fills [`crate::Tools`] gives it
/// ([`crate::Tools::with_sun_flags`]).
#[derive(Debug, Clone, Copy)]
pub struct SunFlags {
    /// The flag of a field of a sun: `sun-zenith-deg` for [`SunField::ZenithDeg`].
    pub field: fn(SunField) -> &'static str,
    /// The flag of an atmosphere plan's day of the year (LOWTRAN7's IDAY).
    pub day_of_year: &'static str,
}

/// The fields a trace stage may give a sun by: a stage that gives any of them when the
/// pipeline has a `sun` gives a second sun.
const TRACE_SUN_FIELDS: [SunField; 6] = [
    SunField::ZenithDeg,
    SunField::AzimuthDeg,
    SunField::Utc,
    SunField::LatitudeDeg,
    SunField::LongitudeDeg,
    SunField::AltitudeM,
];

/// The pipeline's sun as read: its fields as written, and its position.
#[derive(Debug, Clone)]
pub(crate) struct PipelineSun {
    /// Each field given, in the order of its form, with its value spanned at the value it
    /// came from.
    fields: Vec<(SunField, Spanned<String>)>,
    /// The day of the year of a sun given by time (1–366).
    day_of_year: Option<u32>,
    zenith_deg: f64,
    /// Where the `sun` value starts in the file.
    start: usize,
}

/// Reads the `sun` field: `Direction(zenith_deg: Z, azimuth_deg: A)` or `At(utc: "...",
/// latitude_deg: LAT, longitude_deg: LON[, altitude_m: H])`, optionally in `Some(...)`,
/// every number checked by the sun's own model and the sun above the horizon.
pub(crate) fn read(src: Source<'_>, node: &Node) -> Result<PipelineSun, PipelineError> {
    let inner = match &node.kind {
        Kind::Tuple(Some(name), items) if name == "Some" && items.len() == 1 => &items[0],
        _ => node,
    };
    let expected = "expected `sun: Direction(zenith_deg: DEG, azimuth_deg: DEG)` or `sun: \
                    At(utc: \"YYYY-MM-DDTHH:MM:SSZ\", latitude_deg: DEG, longitude_deg: DEG, \
                    altitude_m: M)`";
    let form = match &inner.kind {
        Kind::Struct(Some(name), _) => name.as_str(),
        other => {
            return Err(src.error(
                ErrorKind::Structure,
                inner.start,
                inner.end,
                format!("{expected}, found {}", other.describe()),
            ));
        }
    };
    let (names, fields_of_form): (&[&str], &[SunField]) = match form {
        "Direction" => (
            &["zenith_deg", "azimuth_deg"],
            &[SunField::ZenithDeg, SunField::AzimuthDeg],
        ),
        "At" => (
            &["utc", "latitude_deg", "longitude_deg", "altitude_m"],
            &[
                SunField::Utc,
                SunField::LatitudeDeg,
                SunField::LongitudeDeg,
                SunField::AltitudeM,
            ],
        ),
        _ => {
            return Err(src.error(
                ErrorKind::Structure,
                inner.start,
                inner.end,
                format!("{expected}, found `{form}(...)`"),
            ));
        }
    };
    let fields = fields_of(src, inner, form, names)?;
    let mut values: Vec<Option<(Spanned<String>, &Node)>> = Vec::new();
    for name in names {
        let value = match fields.get(name) {
            Some(n) => Some((scalar(src, n)?, *n)),
            None if *name == "altitude_m" => None,
            None => {
                return Err(src.error(
                    ErrorKind::Structure,
                    inner.start,
                    inner.end,
                    format!("the sun has no `{name}`: {expected}"),
                ));
            }
        };
        values.push(value);
    }
    // Every number as a number; the time as a string.
    let number = |i: usize| -> Result<f64, PipelineError> {
        let (v, n) = values[i].as_ref().expect("required fields are present");
        match (&n.kind, v.value.parse::<f64>()) {
            (Kind::Number(_), Ok(x)) => Ok(x),
            _ => Err(src.error(
                ErrorKind::Structure,
                n.start,
                n.end,
                format!(
                    "expected a number of degrees or metres, found {}",
                    n.kind.describe()
                ),
            )),
        }
    };
    let spec = if form == "Direction" {
        SunSpec::Direction {
            zenith_deg: number(0)?,
            azimuth_deg: number(1)?,
        }
    } else {
        let (utc, utc_node) = values[0].as_ref().expect("required");
        if !matches!(utc_node.kind, Kind::Str(_)) {
            return Err(src.error(
                ErrorKind::Structure,
                utc_node.start,
                utc_node.end,
                "expected the time as a string, \"YYYY-MM-DDTHH:MM:SSZ\"",
            ));
        }
        SunSpec::At {
            utc: utc.value.clone(),
            latitude_deg: number(1)?,
            longitude_deg: number(2)?,
            altitude_m: if values[3].is_some() { number(3)? } else { 0.0 },
            refraction: None,
            delta_t_s: None,
            delta_ut1_s: None,
        }
    };
    let at_field = |field: &str| -> &Node {
        names
            .iter()
            .position(|n| *n == field)
            .and_then(|i| values[i].as_ref().map(|(_, n)| *n))
            .unwrap_or(inner)
    };
    let position = spec.position().map_err(|e| {
        let (n, message) = match e.kind {
            AtmosphereErrorKind::Sun { field, message } => (
                at_field(field.path()),
                format!("`{}`: {message}", field.path()),
            ),
            _ => (inner, e.to_string()),
        };
        src.error(
            ErrorKind::Structure,
            n.start,
            n.end,
            format!("the sun: {message}"),
        )
    })?;
    if !position.is_above_horizon() {
        let n = at_field(if form == "Direction" {
            "zenith_deg"
        } else {
            "utc"
        });
        return Err(src.error(
            ErrorKind::Structure,
            n.start,
            n.end,
            format!(
                "the sun is {:.4} deg from the zenith, at or below the horizon: a sun below 90 \
                 deg lights the scene; leave `sun` out for a night",
                position.zenith_deg
            ),
        ));
    }
    let day_of_year = spec.day_of_year().map(u32::from);
    let fields = values
        .into_iter()
        .zip(fields_of_form)
        .filter_map(|(v, &field)| v.map(|(value, _)| (field, value)))
        .collect();
    Ok(PipelineSun {
        fields,
        day_of_year,
        zenith_deg: position.zenith_deg,
        start: node.start,
    })
}

impl PipelineSun {
    /// Where the `sun` value starts in the file.
    pub(crate) fn start(&self) -> usize {
        self.start
    }
}

/// The first word and the rest of a stage's tool.
fn tool_words(stage: &StageSpec) -> Vec<&str> {
    stage.tool.value.split_whitespace().collect()
}

/// The value of a stage's parameter `flag` (`"sun-zenith-deg"`), with its span.
fn param<'a>(
    stage: &'a StageSpec,
    flag: &str,
) -> Option<(&'a Spanned<String>, Option<&'a Spanned<String>>)> {
    stage
        .params
        .iter()
        .find(|(k, _)| k.value.trim_start_matches('-') == flag)
        .map(|(k, v)| {
            let value = match v {
                Param::One(v) => Some(v),
                _ => None,
            };
            (k, value)
        })
}

/// Gives the sun's flags, as `flags` spells them, to every `trace` stage, and checks every
/// `atmos plan` stage against it.
pub(crate) fn apply(
    src: Source<'_>,
    sun: &PipelineSun,
    flags: &SunFlags,
    stages: &mut [StageSpec],
) -> Result<(), PipelineError> {
    let sun_line = src.line(sun.start);
    for stage in stages.iter_mut() {
        let words = tool_words(stage);
        if words.first() == Some(&"trace") {
            if let Some((key, _)) = TRACE_SUN_FIELDS
                .iter()
                .find_map(|&f| param(stage, (flags.field)(f)))
            {
                return Err(src.error(
                    ErrorKind::Structure,
                    key.start,
                    key.end,
                    format!(
                        "the pipeline's `sun` (line {sun_line}) lights every trace stage: this \
                         stage's own `{}` would give a second sun; give the sun once",
                        key.value
                    ),
                ));
            }
            let given = sun.fields.iter().map(|(field, value)| {
                let key = Spanned {
                    value: (flags.field)(*field).to_owned(),
                    start: value.start,
                    end: value.end,
                };
                (key, Param::One(value.clone()))
            });
            stage.params.extend(given);
        } else if words.starts_with(&["atmos", "plan"]) {
            check_plan(src, sun, flags, sun_line, stage)?;
        }
    }
    Ok(())
}

/// An `atmos plan` stage planned for the pipeline's sun: its zenith within the solar
/// table's tolerance, its day the date's when the sun is given by time.
fn check_plan(
    src: Source<'_>,
    sun: &PipelineSun,
    flags: &SunFlags,
    sun_line: usize,
    stage: &StageSpec,
) -> Result<(), PipelineError> {
    let zenith_flag = (flags.field)(SunField::ZenithDeg);
    let day_flag = flags.day_of_year;
    let Some((key, value)) = param(stage, zenith_flag) else {
        return Err(src.error(
            ErrorKind::Structure,
            stage.tool.start,
            stage.tool.end,
            format!(
                "this atmosphere plan is for a night (no `{zenith_flag}`), but the pipeline's \
                 `sun` (line {sun_line}) lights the trace stages at {:.4} deg from the zenith: \
                 give the plan `params: {{\"{zenith_flag}\": {:.3}, \"{day_flag}\": D}}`",
                sun.zenith_deg, sun.zenith_deg
            ),
        ));
    };
    let (start, end) = value.map_or((key.start, key.end), |v| (v.start, v.end));
    let planned: Option<f64> = value.and_then(|v| v.value.parse().ok());
    match planned {
        Some(z) if (z - sun.zenith_deg).abs() <= ZENITH_TOLERANCE_DEG => {}
        _ => {
            return Err(src.error(
                ErrorKind::Structure,
                start,
                end,
                format!(
                    "this atmosphere plan's sun is not the pipeline's: the `sun` (line \
                     {sun_line}) is {:.4} deg from the zenith, and the two must agree within \
                     {ZENITH_TOLERANCE_DEG} deg for its solar table to light the trace stages",
                    sun.zenith_deg
                ),
            ));
        }
    }
    if let (Some(day), Some((key, value))) = (sun.day_of_year, param(stage, day_flag)) {
        let (start, end) = value.map_or((key.start, key.end), |v| (v.start, v.end));
        if value.and_then(|v| v.value.parse::<u32>().ok()) != Some(day) {
            return Err(src.error(
                ErrorKind::Structure,
                start,
                end,
                format!(
                    "this atmosphere plan's day is not the pipeline's: the `sun` (line \
                     {sun_line}) is seen on day {day} of its year"
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
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
}
