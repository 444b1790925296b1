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
        zenith_deg: position.geometric_zenith_deg,
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
        let plan = words.starts_with(&["atmos", "plan"]);
        let zenith_given = param(stage, (flags.field)(SunField::ZenithDeg)).is_some();
        if words.first() == Some(&"trace") {
            refuse_own_sun(src, flags, sun_line, stage, None)?;
            stage.params.extend(sun_params(sun, flags));
        } else if plan && sun.day_of_year.is_some() && !zenith_given {
            // A sun given by its time and place: the plan takes the same flags as the
            // trace stages and works out the zenith angle and the day from them, by the
            // same SPA, so the two cannot disagree.
            refuse_own_sun(src, flags, sun_line, stage, Some(flags.day_of_year))?;
            stage.params.extend(sun_params(sun, flags));
        } else if plan {
            check_plan(src, sun, flags, sun_line, stage)?;
        }
    }
    Ok(())
}

/// The sun's fields as a stage's parameters, each flag spelt as `flags` spells it and
/// spanned at the value it came from.
fn sun_params(sun: &PipelineSun, flags: &SunFlags) -> Vec<(Spanned<String>, Param)> {
    sun.fields
        .iter()
        .map(|(field, value)| {
            let key = Spanned {
                value: (flags.field)(*field).to_owned(),
                start: value.start,
                end: value.end,
            };
            (key, Param::One(value.clone()))
        })
        .collect()
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
mod tests;
