//! The pipeline's `sun`: one sun for the whole job, written once and given to every `trace`
//! stage as the tool's own sun flags, so that what runs is still exactly a command line a
//! user could type. Over a `Times` sweep the sun is templated by the frame's time (`At(utc:
//! "{utc}", ...)`): each per-frame `trace` and `atmos plan` takes the sun of its own time, a
//! frame whose sun is below the horizon none, and one plan for the whole day must hold every
//! lit frame's sun. An `atmos plan` stage in the same file must be planned
//! for that sun: its zenith angle must agree with the sun's within the solar table's
//! tolerance (the check irsig-trace makes later against the built table, made here before
//! anything runs), and with a sun given by time its day of the year with the date. A trace
//! stage that gives sun flags of its own is refused: the sun is given once. The flags are
//! the tools' to spell ([`SunFlags`], which the program filling [`crate::Tools`] gives): this
//! crate knows the sun's fields, not their flags.

use irsig_atmosphere::AtmosphereErrorKind;
use irsig_atmosphere::solar::ZENITH_TOLERANCE_DEG;
use irsig_atmosphere::sun::{SunField, SunPosition, SunSpec};
use irsig_formats::ron_tree::{Kind, Node};

use std::collections::BTreeMap;

use crate::error::{ErrorKind, PipelineError};
use crate::spec::{Param, Source, Spanned, StageSpec, SweepSpec, fields_of, scalar};

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
    /// For a sun whose time is a frame's (`At(utc: "{utc}", ...)`): the place it is seen
    /// from (latitude, longitude, altitude), its position worked out frame by frame.
    per_frame: Option<[f64; 3]>,
}

/// A stand-in time that checks a per-frame sun's other fields when the file is read.
const ANY_TIME: &str = "2000-01-01T12:00:00Z";

/// What a `sun` value may be, for errors.
const EXPECTED: &str = "expected `sun: Direction(zenith_deg: DEG, azimuth_deg: DEG)` or `sun: \
                        At(utc: \"YYYY-MM-DDTHH:MM:SSZ\", latitude_deg: DEG, longitude_deg: \
                        DEG, altitude_m: M)`";

/// The sun's form (`Direction` or `At`), its field names and the sun model's fields.
fn form_of<'n>(
    src: Source<'_>,
    inner: &'n Node,
) -> Result<(&'n str, &'static [&'static str], &'static [SunField]), PipelineError> {
    let form = match &inner.kind {
        Kind::Struct(Some(name), _) => name.as_str(),
        other => {
            return Err(src.error(
                ErrorKind::Structure,
                inner.start,
                inner.end,
                format!("{EXPECTED}, found {}", other.describe()),
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
                format!("{EXPECTED}, found `{form}(...)`"),
            ));
        }
    };
    Ok((form, names, fields_of_form))
}

/// Reads the `sun` field: `Direction(zenith_deg: Z, azimuth_deg: A)` or `At(utc: "...",
/// latitude_deg: LAT, longitude_deg: LON[, altitude_m: H])`, optionally in `Some(...)`,
/// every number checked by the sun's own model and the sun above the horizon.
pub(crate) fn read(src: Source<'_>, node: &Node) -> Result<PipelineSun, PipelineError> {
    let inner = match &node.kind {
        Kind::Tuple(Some(name), items) if name == "Some" && items.len() == 1 => &items[0],
        _ => node,
    };
    let (form, names, fields_of_form) = form_of(src, inner)?;
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
                    format!("the sun has no `{name}`: {EXPECTED}"),
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
    let mut per_frame = None;
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
                "expected the time as a string, \"YYYY-MM-DDTHH:MM:SSZ\", or a frame's, \"{utc}\"",
            ));
        }
        let place = [
            number(1)?,
            number(2)?,
            if values[3].is_some() { number(3)? } else { 0.0 },
        ];
        // A frame's time: the place is checked now, each frame's sun when it is planned.
        let templated = crate::spec::has_template(&utc.value);
        if templated {
            per_frame = Some(place);
        }
        SunSpec::At {
            utc: if templated {
                ANY_TIME.to_owned()
            } else {
                utc.value.clone()
            },
            latitude_deg: place[0],
            longitude_deg: place[1],
            altitude_m: place[2],
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
    if per_frame.is_none() && !position.is_above_horizon() {
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
        day_of_year: day_of_year.filter(|_| per_frame.is_none()),
        zenith_deg: position.zenith_deg,
        start: node.start,
        per_frame,
    })
}

impl PipelineSun {
    /// Where the `sun` value starts in the file.
    pub(crate) fn start(&self) -> usize {
        self.start
    }

    /// The `utc` field as written, with its place.
    fn utc(&self) -> Option<&Spanned<String>> {
        self.fields
            .iter()
            .find_map(|(f, v)| (*f == SunField::Utc).then_some(v))
    }
}

/// Whether a sun `zenith_deg` from the zenith lights a frame: above the horizon at the
/// 0.001 deg a LOWTRAN7 deck holds, the rule `irsig-atmos plan` plans a sun by, so that a
/// frame lit here has a plan, and one not lit is a night's.
fn lights(zenith_deg: f64) -> bool {
    (zenith_deg * 1000.0).round() / 1000.0 < 90.0
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

/// Refuses a stage's own sun flags (any of `TRACE_SUN_FIELDS`, and for a plan of a
/// per-frame sun its day of the year): the pipeline's sun is given once.
fn refuse_own_sun(
    src: Source<'_>,
    flags: &SunFlags,
    sun_line: usize,
    stage: &StageSpec,
    also: Option<&str>,
) -> Result<(), PipelineError> {
    let own = TRACE_SUN_FIELDS
        .iter()
        .map(|&f| (flags.field)(f))
        .chain(also)
        .find_map(|flag| param(stage, flag));
    match own {
        Some((key, _)) => Err(src.error(
            ErrorKind::Structure,
            key.start,
            key.end,
            format!(
                "the pipeline's `sun` (line {sun_line}) lights this stage: its own `{}` would \
                 give a second sun; give the sun once",
                key.value
            ),
        )),
        None => Ok(()),
    }
}

/// Gives the sun's flags, as `flags` spells them, to every `trace` stage, and checks every
/// `atmos plan` stage against it. A sun whose time is each frame's is given frame by frame
/// ([`frame_params`]); here its stages are checked.
pub(crate) fn apply(
    src: Source<'_>,
    sun: &PipelineSun,
    flags: &SunFlags,
    stages: &mut [StageSpec],
    sweeps: &BTreeMap<String, SweepSpec>,
) -> Result<(), PipelineError> {
    if sun.per_frame.is_some() {
        return check_per_frame(src, sun, flags, stages, sweeps);
    }
    let sun_line = src.line(sun.start);
    for stage in stages.iter_mut() {
        let words = tool_words(stage);
        if words.first() == Some(&"trace") {
            refuse_own_sun(src, flags, sun_line, stage, None)?;
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

/// A frame's sun: the time its variables give the sun's `utc`, and where the sun is then.
fn frame_sun(
    src: Source<'_>,
    sun: &PipelineSun,
    vars: &BTreeMap<String, String>,
) -> Result<Option<(String, SunPosition)>, PipelineError> {
    let (Some(place), Some(utc)) = (sun.per_frame, sun.utc()) else {
        return Ok(None);
    };
    let time = crate::plan::expand(src, utc, Some(vars))?;
    let spec = SunSpec::At {
        utc: time.clone(),
        latitude_deg: place[0],
        longitude_deg: place[1],
        altitude_m: place[2],
        refraction: None,
        delta_t_s: None,
        delta_ut1_s: None,
    };
    let position = spec.position().map_err(|e| {
        src.error(
            ErrorKind::Structure,
            utc.start,
            utc.end,
            format!(
                "the sun of frame {} at `{time}`: {e}",
                vars.get("frame").map_or("?", String::as_str)
            ),
        )
    })?;
    Ok(Some((time, position)))
}

/// The sun's flags a stage takes for one frame when the pipeline's sun is each frame's
/// (`At(utc: "{utc}", ...)`): a `trace` stage's and a swept `atmos plan` stage's, the
/// frame's time in place of the template; none for a frame whose sun is at or below the
/// horizon (a night frame, traced and planned without a sun), nor for other stages.
pub(crate) fn frame_params(
    src: Source<'_>,
    sun: &PipelineSun,
    flags: &SunFlags,
    stage: &StageSpec,
    vars: &BTreeMap<String, String>,
) -> Result<Vec<(Spanned<String>, Param)>, PipelineError> {
    let words = tool_words(stage);
    let takes_sun = words.first() == Some(&"trace")
        || (words.starts_with(&["atmos", "plan"]) && stage.sweep.is_some());
    if !takes_sun {
        return Ok(Vec::new());
    }
    let Some((time, position)) = frame_sun(src, sun, vars)? else {
        return Ok(Vec::new());
    };
    if !lights(position.zenith_deg) {
        return Ok(Vec::new());
    }
    Ok(sun
        .fields
        .iter()
        .map(|(field, value)| {
            let key = Spanned {
                value: (flags.field)(*field).to_owned(),
                start: value.start,
                end: value.end,
            };
            let value = if *field == SunField::Utc {
                Spanned {
                    value: time.clone(),
                    start: value.start,
                    end: value.end,
                }
            } else {
                value.clone()
            };
            (key, Param::One(value))
        })
        .collect())
}

/// A lit frame of a trace stage under a per-frame sun: its time, and where to point when
/// it falls before or after what a plan covers (the `Times` sweep's `start` and `end`, or
/// the sun's `utc`).
struct LitFrame {
    time_s: f64,
    shown: String,
    before: (usize, usize),
    after: (usize, usize),
}

/// The stages of a pipeline whose sun is each frame's: every trace stage runs once per
/// frame (`sweep`) and gives no sun of its own; an `atmos plan` stage swept over frames
/// gets each frame's sun too (a small build per frame) and gives none of its own; one that
/// runs once must plan the suns of every lit frame ([`check_day_plan`]).
fn check_per_frame(
    src: Source<'_>,
    sun: &PipelineSun,
    flags: &SunFlags,
    stages: &[StageSpec],
    sweeps: &BTreeMap<String, SweepSpec>,
) -> Result<(), PipelineError> {
    let sun_line = src.line(sun.start);
    let utc_span = sun
        .utc()
        .map_or((sun.start, sun.start), |u| (u.start, u.end));
    let mut lit = Vec::new();
    let mut once = Vec::new();
    for stage in stages {
        let words = tool_words(stage);
        if words.first() == Some(&"trace") {
            refuse_own_sun(src, flags, sun_line, stage, None)?;
            let Some(name) = &stage.sweep else {
                return Err(src.error(
                    ErrorKind::Structure,
                    stage.tool.start,
                    stage.tool.end,
                    format!(
                        "the pipeline's `sun` (line {sun_line}) is each frame's, and this trace \
                         stage runs once, at no frame's time: give it `sweep` over the frames"
                    ),
                ));
            };
            // An unknown sweep is reported where the stage is planned.
            let Some(sweep) = sweeps.get(&name.value) else {
                continue;
            };
            let (before, after) = sweep
                .times
                .as_ref()
                .map_or((utc_span, utc_span), |t| (t.start, t.end));
            let count = sweep.frames.len().to_string();
            for (i, vars) in sweep.frames.iter().enumerate() {
                let mut vars = vars.clone();
                vars.insert("frame".to_owned(), (i + 1).to_string());
                vars.insert("frames".to_owned(), count.clone());
                let Some((time, position)) = frame_sun(src, sun, &vars)? else {
                    continue;
                };
                if lights(position.zenith_deg) {
                    // The sun's model parsed the time: it is one.
                    let time_s = irsig_formats::time::parse_time(&time).unwrap_or(f64::NAN);
                    lit.push(LitFrame {
                        time_s,
                        shown: time,
                        before,
                        after,
                    });
                }
            }
        } else if words.starts_with(&["atmos", "plan"]) {
            if stage.sweep.is_some() {
                refuse_own_sun(src, flags, sun_line, stage, Some(flags.day_of_year))?;
            } else {
                once.push(stage);
            }
        }
    }
    for stage in once {
        check_day_plan(src, flags, sun_line, stage, &lit)?;
    }
    Ok(())
}

/// An `atmos plan` stage that runs once under a per-frame sun: its atmosphere lights every
/// lit frame, so it must plan the suns of a time range (`sun-utc: "START/END/STEP"`) that
/// holds every lit frame's time; a plan of one sun, or a night's while a frame is lit, is
/// refused, and so is a lit frame outside the range (at the `Times` sweep's `start` or
/// `end`).
fn check_day_plan(
    src: Source<'_>,
    flags: &SunFlags,
    sun_line: usize,
    stage: &StageSpec,
    lit: &[LitFrame],
) -> Result<(), PipelineError> {
    let utc_flag = (flags.field)(SunField::Utc);
    let one_sun = |start: usize, end: usize| {
        src.error(
            ErrorKind::Structure,
            start,
            end,
            format!(
                "this atmosphere plan holds one sun, and the pipeline's `sun` (line {sun_line}) \
                 moves with the frames' times: sweep the plan over the frames (a plan per \
                 frame), or plan every frame's sun, `\"{utc_flag}\": \"START/END/STEP\"`"
            ),
        )
    };
    let Some((key, value)) = param(stage, utc_flag) else {
        if let Some((key, _)) = param(stage, (flags.field)(SunField::ZenithDeg)) {
            return Err(one_sun(key.start, key.end));
        }
        if let Some(frame) = lit.first() {
            return Err(src.error(
                ErrorKind::Structure,
                stage.tool.start,
                stage.tool.end,
                format!(
                    "this atmosphere plan is for a night (no sun), but the pipeline's `sun` (line \
                     {sun_line}) lights the frame at {}",
                    frame.shown
                ),
            ));
        }
        return Ok(());
    };
    let (start, end) = value.map_or((key.start, key.end), |v| (v.start, v.end));
    let range = value
        .and_then(|v| irsig_formats::time::parse_times(&v.value).ok())
        .filter(|t| t.len() > 1);
    let Some(times) = range else {
        return Err(one_sun(start, end));
    };
    let (first, last) = (times[0], times[times.len() - 1]);
    let fmt = irsig_model::time::format_utc;
    for frame in lit {
        let blame = if frame.time_s < first {
            frame.before
        } else if frame.time_s > last {
            frame.after
        } else {
            continue;
        };
        return Err(src
            .error(
                ErrorKind::Structure,
                blame.0,
                blame.1,
                format!(
                    "the frame at {} is outside the atmosphere's sun table, which the plan on \
                     line {} makes for {} to {}: no solar table would light it",
                    frame.shown,
                    src.line(start),
                    fmt(first),
                    fmt(last)
                ),
            )
            .with_help("give frames inside the plan's times, or plan the suns of every frame"));
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
        let own_day =
            PLAN_PER_FRAME.replace("outputs:", "params: {\"day-of-year\": 219}, outputs:");
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
}
