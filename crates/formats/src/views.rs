//! Views as the tracer reads them: one canonical RON view, a RON list of views (a fly-by),
//! or a 1990 viewing file; and the 1990 execute file that sequences viewing files into
//! frames, each naming the files it writes.
//!
//! The two view forms are told apart by the first significant character of the text: a
//! 1990 viewing file is nothing but numbers (`#` comments aside, an irsig extension of the
//! legacy syntax), so it starts with a digit, a sign or a decimal point; a RON view starts
//! with `Legacy(`, `LookAt(` or `[`. The viewing file's position is in the scene's length
//! unit (km in the thesis's files) and is converted to metres here, at the file boundary.
//!
//! ```
//! use irsig_formats::views::parse_views;
//! use irsig_model::LengthUnit;
//! let views = parse_views("f1.view", "1.6 -3.0 0.7\n256 256\n78.37 0 28.07\n1 1\n", LengthUnit::Km)?;
//! let [x, y, z] = views[0].position_m();
//! assert!((x - 1600.0).abs() < 1e-9 && (y + 3000.0).abs() < 1e-9 && (z - 700.0).abs() < 1e-9);
//! # Ok::<(), irsig_formats::ParseError>(())
//! ```

use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};

use irsig_model::{LengthUnit, View};

use crate::canonical::error_at_path;
use crate::legacy::{Position, decode, execute, view as legacy_view};
use crate::{ParseError, offset_of};

/// Whether `text` is a 1990 viewing file rather than RON: its first character that is not
/// whitespace or inside a comment (`#` legacy, `//` and `/* */` RON) starts a number.
#[must_use]
pub fn is_legacy_viewing_file(text: &str) -> bool {
    let mut rest = text.trim_start_matches('\u{feff}');
    loop {
        rest = rest.trim_start();
        if rest.starts_with('#') || rest.starts_with("//") {
            rest = rest.split_once('\n').map_or("", |(_, r)| r);
        } else if let Some(after) = rest.strip_prefix("/*") {
            rest = after.split_once("*/").map_or("", |(_, r)| r);
        } else {
            break;
        }
    }
    rest.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '.'))
}

/// Whether RON `text` starts with `[` once whitespace and comments are skipped.
fn starts_as_list(text: &str) -> bool {
    let mut rest = text.trim_start_matches('\u{feff}');
    loop {
        rest = rest.trim_start();
        if rest.starts_with("//") {
            rest = rest.split_once('\n').map_or("", |(_, r)| r);
        } else if let Some(after) = rest.strip_prefix("/*") {
            rest = after.split_once("*/").map_or("", |(_, r)| r);
        } else {
            return rest.starts_with('[');
        }
    }
}

/// A single RON view's optional `sun` entry, as the file gives it: the sun lighting the
/// frame ([`parse_views_and_sun`]). Its type is the caller's (the sun's model is
/// `irsig-atmosphere`'s, which this crate does not know).
#[derive(Debug, Clone, PartialEq)]
pub struct ViewSun<S> {
    /// The sun, as read.
    pub sun: S,
    /// `file:line:column` of the sun's value, for messages that must say where it came from.
    pub location: String,
}

/// [`parse_views`], and the `sun` entry of a single RON view, if it has one: `sun:
/// Direction(...)` or `sun: Some(Direction(...))` (`sun: None` is none), read as `S` (its unknown fields refused
/// at their line and column), then checked by `check`, which names the field at fault and
/// why: a field is reported at its value's line and column. A sun in a list of views, or in
/// anything but the view's own fields, is refused where it stands: one sun lights a run.
///
/// # Errors
/// As [`parse_views`]; also a `sun` that is not an `S` or that `check` refuses, or a `sun`
/// in a list of views.
pub fn parse_views_and_sun<S: serde::de::DeserializeOwned>(
    file: &str,
    text: &str,
    unit: LengthUnit,
    check: impl Fn(&S) -> Result<(), (String, String)>,
) -> Result<(Vec<View>, Option<ViewSun<S>>), ParseError> {
    let (rest, entry) = split_sun(file, text)?;
    let views = parse_views_blanked(file, text, &rest, unit)?;
    let Some((start, end)) = entry else {
        return Ok((views, None));
    };
    let value = &text[start..end];
    let sun: S = ron::from_str(value).map_err(|e| {
        let offset = start + offset_of(value, e.span.start.line, e.span.start.col);
        ParseError::at_offset(
            file,
            text,
            offset,
            format!(
                "invalid sun: {}; expected Direction(zenith_deg: DEG, azimuth_deg: DEG) or \
                 At(utc: \"YYYY-MM-DDTHH:MM:SSZ\", latitude_deg: DEG, longitude_deg: DEG, ...)",
                crate::canonical::ron_message(&e.code)
            ),
        )
    })?;
    check(&sun).map_err(|(field, message)| {
        let (from, _) = crate::ron_tree::locate(value, &field);
        ParseError::at_offset(
            file,
            text,
            start + from,
            format!("invalid sun: `{field}`: {message}"),
        )
    })?;
    let (line, column) = crate::error::line_column(text, start);
    Ok((
        views,
        Some(ViewSun {
            sun,
            location: format!("{file}:{line}:{column}"),
        }),
    ))
}

/// `text` with a single RON view's `sun` entry blanked (every byte of `sun: value,` a space,
/// newlines kept, so that every other value keeps its line, column and byte offset), and the
/// byte range of the sun's value with a `Some(...)` around it looked through. A 1990
/// viewing file, or RON with no `sun`, comes back as it is.
fn split_sun(file: &str, text: &str) -> Result<(String, Option<(usize, usize)>), ParseError> {
    use crate::ron_tree::Kind;
    if is_legacy_viewing_file(text) || !text.contains("sun") {
        return Ok((text.to_owned(), None));
    }
    // Text that is not RON is left to the view reader, whose message says what a view is.
    let Ok(root) = crate::ron_tree::parse(file, text, "view") else {
        return Ok((text.to_owned(), None));
    };
    if let Kind::List(items) = &root.kind {
        for item in items {
            if let Kind::Struct(_, fields) = &item.kind
                && let Some((key, _)) = fields.iter().find(|(k, _)| k.name == "sun")
            {
                return Err(ParseError::at_offset(
                    file,
                    text,
                    key.start,
                    "a sun in a list of views: one sun lights a run; give it in a single \
                     view's file, on the command line or in a pipeline's `sun`",
                ));
            }
        }
        return Ok((text.to_owned(), None));
    }
    let Kind::Struct(_, fields) = &root.kind else {
        return Ok((text.to_owned(), None));
    };
    let Some(at) = fields.iter().position(|(k, _)| k.name == "sun") else {
        return Ok((text.to_owned(), None));
    };
    let (key, value) = &fields[at];
    // The entry runs to the next field's key, or past its own comma to the closing bracket.
    let bytes = text.as_bytes();
    let mut end = value.end;
    while end < text.len() && bytes[end].is_ascii_whitespace() {
        end += 1;
    }
    if bytes.get(end) == Some(&b',') {
        end += 1;
    }
    let mut rest = text.as_bytes().to_vec();
    for b in &mut rest[key.start..end] {
        if *b != b'\n' {
            *b = b' ';
        }
    }
    let rest = String::from_utf8(rest).expect("ASCII spaces in place of whole entries");
    // `sun: None` says there is none, as leaving it out does.
    if matches!(&value.kind, Kind::Ident(none) if none == "None") {
        return Ok((rest, None));
    }
    let inner = match &value.kind {
        Kind::Tuple(Some(name), items) if name == "Some" && items.len() == 1 => &items[0],
        _ => value,
    };
    Ok((rest, Some((inner.start, inner.end))))
}

/// The views of one file's text: a RON view, a RON list of views, or a 1990 viewing file
/// whose position is in `unit`. Every view is validated; a broken rule is reported at its
/// value's line and column. A single view's `sun` entry is passed over (it lights the frame,
/// it does not place the camera: [`parse_views_and_sun`] reads it).
///
/// # Errors
/// A syntax error, an empty list, or a view that breaks a model rule.
pub fn parse_views(file: &str, text: &str, unit: LengthUnit) -> Result<Vec<View>, ParseError> {
    let (rest, _) = split_sun(file, text)?;
    parse_views_blanked(file, text, &rest, unit)
}

/// [`parse_views`] of `text` whose `sun` entry is blanked in `rest`: errors are placed and
/// shown in `text`.
fn parse_views_blanked(
    file: &str,
    text: &str,
    rest: &str,
    unit: LengthUnit,
) -> Result<Vec<View>, ParseError> {
    if rest == text {
        return parse_views_of(file, text, unit);
    }
    parse_views_of(file, rest, unit).map_err(|e| {
        ParseError::at_offset(file, text, offset_of(rest, e.line, e.column), e.message)
    })
}

fn parse_views_of(file: &str, text: &str, unit: LengthUnit) -> Result<Vec<View>, ParseError> {
    if is_legacy_viewing_file(text) {
        let parsed = legacy_view::parse(file, text)?;
        let v = parsed.to_view(unit);
        // The parser has checked every value the model checks; a failure here is a value
        // that only the model rejects, reported at the file's first value.
        v.validate().map_err(|e| {
            let p = parsed.file_position;
            ParseError::at_line_column(file, text, p.line, p.column, e.to_string())
        })?;
        return Ok(vec![v]);
    }
    let (views, list) = match ron::from_str::<View>(text) {
        Ok(v) => (vec![v], false),
        Err(single) => match ron::from_str::<Vec<View>>(text) {
            Ok(v) => (v, true),
            Err(as_list) => {
                // Report the error of the form the text starts as: a list's own error
                // (an unknown field in its third view) rather than "expected a view" at `[`.
                let e = if starts_as_list(text) {
                    as_list
                } else {
                    single
                };
                let offset = offset_of(text, e.span.start.line, e.span.start.col);
                return Err(ParseError::at_offset(
                    file,
                    text,
                    offset,
                    format!(
                        "expected a view, a list of views (RON) or a 1990 viewing file \
                         (numbers): {}",
                        crate::canonical::ron_message(&e.code)
                    ),
                ));
            }
        },
    };
    if views.is_empty() {
        return Err(ParseError::at_offset(
            file,
            text,
            0,
            "expected at least one view, found an empty list",
        ));
    }
    for (i, v) in views.iter().enumerate() {
        v.validate().map_err(|e| {
            let path = if list {
                format!("[{i}].{}", e.path)
            } else {
                e.path.clone()
            };
            let what = if list {
                format!("invalid view {}", i + 1)
            } else {
                "invalid view".to_owned()
            };
            error_at_path(
                file,
                text,
                &path,
                format!("{what}: `{}`: {}", e.path, e.kind),
            )
        })?;
    }
    Ok(views)
}

/// One frame of a 1990 execute file, its names resolved against the execute file's
/// directory: the view it traces and the files it writes.
#[derive(Debug, Clone, PartialEq)]
pub struct ExecuteFrame {
    /// The view, read from the frame's viewing file.
    pub view: View,
    /// The viewing file it came from.
    pub view_file: PathBuf,
    /// The interaction-map image to write.
    pub map_png: PathBuf,
    /// The digital-count image to write.
    pub dc_png: PathBuf,
    /// The look-up table to write.
    pub lut: PathBuf,
}

/// The frames of an execute file's `text` (named `file`, in directory `base`): each
/// frame's viewing file is read from disk and parsed with its position in `unit`.
///
/// Names are resolved as the mesh readers resolve their references: relative to the
/// execute file's directory, never absolute and never climbing out of it with `..`, so an
/// execute file cannot write outside its own folder. Every frame must name the same scene
/// file (one run traces one flattened scene with one BVH); no two outputs may share a name;
/// no output may be an input of the run (a viewing file, the scene file, the execute file
/// itself), a folder, or in a folder that does not exist. Each is an error at the offending
/// name.
///
/// # Errors
/// As above, a viewing file that cannot be read or parsed (its own error, with the frame
/// that named it as help), or a syntax error of the execute file.
pub fn read_execute(
    file: &str,
    text: &str,
    base: &Path,
    unit: LengthUnit,
) -> Result<Vec<ExecuteFrame>, ParseError> {
    let parsed = execute::parse(file, text)?;
    let at = |p: Position, message: String| {
        ParseError::at_line_column(file, text, p.line, p.column, message)
    };
    let first_scene = parsed.frames.first().map_or("", |f| f.scene.as_str());
    let mut frames = Vec::with_capacity(parsed.frames.len());
    // Every input of the run, and every output written so far, by resolved path.
    let mut inputs: HashMap<PathBuf, usize> = HashMap::new();
    inputs.insert(
        base.join(Path::new(file).file_name().unwrap_or_default()),
        0,
    );
    let mut outputs: HashMap<PathBuf, usize> = HashMap::new();
    let mut scenes: std::collections::HashSet<PathBuf> = std::collections::HashSet::new();
    for (i, frame) in parsed.frames.iter().enumerate() {
        let number = i + 1;
        if frame.scene != first_scene {
            return Err(at(
                frame.positions[1],
                format!(
                    "expected the scene file of frame 1, `{first_scene}`, found `{}`: one run \
                     traces one flattened scene with one BVH; split the execute file \
                     by scene",
                    frame.scene
                ),
            ));
        }
        let names = [&frame.view, &frame.map_image, &frame.image, &frame.lut];
        let places = [0, 2, 3, 4].map(|k| frame.positions[k]);
        let mut resolved = Vec::with_capacity(4);
        for (name, &place) in names.iter().zip(&places) {
            resolved.push(resolve(base, name).map_err(|m| at(place, m))?);
        }
        let view_file = resolved[0].clone();
        inputs.entry(view_file.clone()).or_insert(number);
        // The scene file is an input of the run too, though the tracer reads its flattened
        // form: writing over it would destroy the run's source.
        if let Ok(scene) = resolve(base, &frame.scene) {
            scenes.insert(scene);
        }
        for (k, path) in resolved.iter().enumerate().skip(1) {
            let input = inputs
                .get(path)
                .copied()
                .or_else(|| scenes.contains(path).then_some(usize::MAX));
            if let Some(other) = input {
                let what = match other {
                    0 => "the execute file itself".to_owned(),
                    usize::MAX => "the run's scene file".to_owned(),
                    _ => format!("the viewing file of frame {other}"),
                };
                return Err(at(
                    places[k],
                    format!(
                        "expected an output name, found `{}`, which is {what}: an output \
                         must not overwrite an input of the same run",
                        names[k]
                    ),
                ));
            }
            if let Some(other) = outputs.insert(path.clone(), number) {
                return Err(at(
                    places[k],
                    format!(
                        "expected a file name no other output uses, found `{}`, which frame \
                         {other} also writes",
                        names[k]
                    ),
                ));
            }
            // Checked before any frame is traced, so that no work is lost at the end.
            if path.is_dir() {
                return Err(at(
                    places[k],
                    format!(
                        "expected an output file name, found `{}`, which is a folder",
                        names[k]
                    ),
                ));
            }
            let folder = path.parent().filter(|d| !d.as_os_str().is_empty());
            if folder.is_some_and(|d| !d.is_dir()) {
                return Err(at(
                    places[k],
                    format!(
                        "expected an output in an existing folder, found `{}`, whose folder does \
                         not exist",
                        names[k]
                    ),
                ));
            }
        }
        let view_name = view_file.to_string_lossy().into_owned();
        let named_here = || {
            format!(
                "the viewing file of frame {number}, named at {file}:{}",
                frame.positions[0]
            )
        };
        let bytes = crate::file::read_file(&view_file).map_err(|e| {
            at(
                frame.positions[0],
                format!("cannot read the viewing file `{}`: {e}", frame.view),
            )
        })?;
        let view_text = decode(&view_name, &bytes).map_err(|e| e.with_help(named_here()))?;
        let mut views =
            parse_views(&view_name, view_text, unit).map_err(|e| e.with_help(named_here()))?;
        if views.len() != 1 {
            return Err(at(
                frame.positions[0],
                format!(
                    "expected a viewing file holding one view, found {} views in `{}`",
                    views.len(),
                    frame.view
                ),
            ));
        }
        // Outputs named before this frame's viewing file was known as an input.
        if let Some(&other) = outputs.get(&view_file) {
            return Err(at(
                frame.positions[0],
                format!(
                    "expected a viewing file no frame writes, found `{}`, which frame {other} \
                     writes: an output must not overwrite an input of the same run",
                    frame.view
                ),
            ));
        }
        let [_, map_png, dc_png, lut] = <[PathBuf; 4]>::try_from(resolved)
            .map_err(|_| at(frame.positions[0], "internal: four names".to_owned()))?;
        frames.push(ExecuteFrame {
            view: views.remove(0),
            view_file,
            map_png,
            dc_png,
            lut,
        });
    }
    Ok(frames)
}

/// A name from an execute file, relative to its directory `base`: refused when absolute or
/// when it climbs out with `..`.
fn resolve(base: &Path, name: &str) -> Result<PathBuf, String> {
    let p = Path::new(name);
    if p.has_root() || p.components().any(|c| matches!(c, Component::Prefix(_))) {
        return Err(format!(
            "`{name}` is an absolute path; expected a name relative to the execute file's \
             folder"
        ));
    }
    if p.components().any(|c| c == Component::ParentDir) {
        return Err(format!(
            "`{name}` climbs out of the execute file's folder with `..`; expected a name \
             inside it"
        ));
    }
    Ok(if base == Path::new(".") || base.as_os_str().is_empty() {
        p.to_path_buf()
    } else {
        base.join(p)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stand-in for the sun's model (`irsig_atmosphere::sun::SunSpec` is not this crate's):
    /// the same two forms, its unknown fields refused.
    #[derive(Debug, Clone, PartialEq, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    enum TestSun {
        Direction { zenith_deg: f64, azimuth_deg: f64 },
        At { utc: String, latitude_deg: f64 },
    }

    fn check(s: &TestSun) -> Result<(), (String, String)> {
        match s {
            TestSun::Direction { zenith_deg, .. } if !(0.0..=180.0).contains(zenith_deg) => Err((
                "zenith_deg".into(),
                format!("{zenith_deg} is out of range: expected 0 to 180"),
            )),
            TestSun::At { latitude_deg, .. } if !(-90.0..=90.0).contains(latitude_deg) => Err((
                "latitude_deg".into(),
                format!("{latitude_deg} is out of range: expected -90 to 90"),
            )),
            _ => Ok(()),
        }
    }

    const VIEW: &str = "LookAt(\n  position_m: (0, -10, 5),\n  target_m: (0, 0, 0),\n  \
                        pixels: (4, 3),\n  fov_deg: (10, 8),\n";

    fn with_sun(sun: &str) -> String {
        format!("{VIEW}  sun: {sun},\n)\n")
    }

    fn read(text: &str) -> Result<(Vec<View>, Option<ViewSun<TestSun>>), ParseError> {
        parse_views_and_sun("v.ron", text, LengthUnit::M, check)
    }

    #[test]
    fn a_views_sun_is_read_in_either_form_and_the_view_is_the_same_without_it() {
        let plain = parse_views("v.ron", &format!("{VIEW})"), LengthUnit::M).unwrap();
        let direction = TestSun::Direction {
            zenith_deg: 30.0,
            azimuth_deg: 120.0,
        };
        // The sun's value starts at line 6, column 8 (after `  sun: `), 13 inside `Some(`.
        for (sun, column) in [
            ("Direction(zenith_deg: 30, azimuth_deg: 120)", 8),
            ("Some(Direction(zenith_deg: 30.0, azimuth_deg: 120.0))", 13),
        ] {
            let text = with_sun(sun);
            let (views, got) = read(&text).unwrap();
            assert_eq!(views, plain);
            let got = got.unwrap();
            assert_eq!(got.sun, direction);
            assert_eq!(got.location, format!("v.ron:6:{column}"));
            // The other readers pass the sun over.
            assert_eq!(parse_views("v.ron", &text, LengthUnit::M).unwrap(), plain);
        }
        let (_, at) = read(&with_sun(
            "At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 51.5)",
        ))
        .unwrap();
        assert_eq!(
            at.unwrap().sun,
            TestSun::At {
                utc: "2024-06-21T12:00:00Z".into(),
                latitude_deg: 51.5
            }
        );
        // No sun, or `sun: None`: none, and the views as ever.
        let (views, none) = read(&format!("{VIEW})")).unwrap();
        assert_eq!((views, none), (plain.clone(), None));
        let (views, none) = read(&with_sun("None")).unwrap();
        assert_eq!((views, none), (plain.clone(), None));
        assert_eq!(
            parse_views("v.ron", &with_sun("None"), LengthUnit::M).unwrap(),
            plain
        );
    }

    #[test]
    fn a_bad_sun_is_refused_at_its_line_and_column() {
        let cases = [
            // Out of range: at the field's value.
            (
                with_sun("Direction(zenith_deg: 200, azimuth_deg: 0)"),
                (6, 30),
                "`zenith_deg`: 200 is out of range",
            ),
            (
                with_sun("At(utc: \"2024-06-21T12:00:00Z\", latitude_deg: 95)"),
                (6, 54),
                "`latitude_deg`: 95 is out of range",
            ),
            // An unknown field, and a form that is none.
            (
                with_sun("Direction(zenith_deg: 20, azimuth_deg: 0, elevation_deg: 70)"),
                (6, 50),
                "elevation_deg",
            ),
            (with_sun("Overhead"), (6, 8), "invalid sun"),
        ];
        for (text, (line, column), says) in cases {
            let e = read(&text).unwrap_err();
            assert_eq!((e.line, e.column), (line, column), "{e}");
            assert!(e.message.contains(says), "{e}");
        }
        // A view error after a sun keeps its own place.
        let text = format!(
            "{VIEW}  sun: Direction(zenith_deg: 20, azimuth_deg: 0),\n  upp: (0, 0, 1),\n)"
        );
        let e = read(&text).unwrap_err();
        assert_eq!((e.line, e.column), (7, 3), "{e}");
        // A sun in a list of views: refused at its key.
        let list = format!("[{VIEW}  sun: Direction(zenith_deg: 20, azimuth_deg: 0),\n)]");
        let e = read(&list).unwrap_err();
        assert_eq!((e.line, e.column), (6, 3), "{e}");
        assert!(e.message.contains("list of views"), "{e}");
        assert!(parse_views("v.ron", &list, LengthUnit::M).is_err());
    }

    #[test]
    fn misspelt_fields_are_errors_at_their_place() {
        // `gain_dc_per_kk` and `upp` used to be skipped, and the later error blamed `up`.
        let cases = [
            (
                "LookAt(position_m: (0, -10, 5), target_m: (0, 0, 0), pixels: (4, 3), \
                 fov_deg: (10, 8), gain_dc_per_kk: 2)",
                "gain_dc_per_kk",
            ),
            (
                "LookAt(position_m: (0, -10, 5), target_m: (0, 0, 0), upp: (0, 0, 1), \
                 pixels: (4, 3), fov_deg: (10, 8))",
                "upp",
            ),
            (
                "Legacy(position_m: (0, 0, 5), pixels: (4, 3), omega_phi_kappa_deg: (0, 0, 0), \
                 fov_deg: (10, 8), colour: 1)",
                "colour",
            ),
        ];
        for (text, field) in cases {
            let e = parse_views("v.ron", text, LengthUnit::M).unwrap_err();
            assert!(e.message.contains(field), "{field}: {e}");
            let at = text.find(field).unwrap();
            assert_eq!(e.column, at + 1, "{e}");
            // The same view third in a list is reported at its place too.
            let list = format!("[\n  {LOOK},\n  {LOOK},\n  {text},\n]\n");
            let e = parse_views("v.ron", &list, LengthUnit::M).unwrap_err();
            assert!(e.message.contains(field), "{field}: {e}");
            assert_eq!((e.line, e.column), (4, at + 3), "{e}");
        }
    }

    #[test]
    fn legacy_and_ron_views_are_told_apart() {
        for legacy in [
            "1.60 -3.00 0.70\n256 256\n",
            "# frame 1\n-1 0 0.7",
            "\u{feff}  .5 0 1",
            "+1 2 3",
        ] {
            assert!(is_legacy_viewing_file(legacy), "{legacy:?}");
        }
        for ron in [
            "Legacy(position_m: (0, 0, 1))",
            "// a view\nLookAt(",
            "/* 1 2 3 */ [Legacy(",
            "",
        ] {
            assert!(!is_legacy_viewing_file(ron), "{ron:?}");
        }
    }

    const LOOK: &str =
        "LookAt(position_m: (0, -10, 5), target_m: (0, 0, 0), pixels: (4, 3), fov_deg: (10, 8))";

    #[test]
    fn a_list_of_views_is_validated_view_by_view_at_the_value() {
        let text = format!(
            "[\n  {LOOK},\n  LookAt(position_m: (0, -10, 5), target_m: (0, 0, 0), pixels: (4, 3), fov_deg: (0, 8)),\n]\n"
        );
        let e = parse_views("f.ron", &text, LengthUnit::M).unwrap_err();
        assert!(e.message.contains("invalid view 2"), "{e}");
        assert_eq!(e.line, 3, "{e}");
        assert_eq!(
            parse_views("f.ron", &format!("[{LOOK}, {LOOK}]"), LengthUnit::M)
                .unwrap()
                .len(),
            2
        );
        let e = parse_views("f.ron", "[]", LengthUnit::M).unwrap_err();
        assert!(e.message.contains("empty list"), "{e}");
    }

    #[test]
    fn execute_names_are_relative_and_outputs_never_inputs() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("f1.view"), "0 0 1\n4 3\n0 0 0\n10 8\n").unwrap();
        let ok = "f1.view s.scn f1.map f1.img f1.lut\n";
        let frames = read_execute("x.exec", ok, dir.path(), LengthUnit::M).unwrap();
        assert_eq!(frames[0].lut, dir.path().join("f1.lut"));
        let z = frames[0].view.position_m()[2];
        assert!((z - 1.0).abs() < f64::EPSILON, "{z}");
        for (text, column, says) in [
            (
                "f1.view s.scn f1.map f1.img f1.view\n",
                29,
                "viewing file of frame 1",
            ),
            (
                "f1.view s.scn f1.map f1.img x.exec\n",
                29,
                "the execute file itself",
            ),
            (
                "f1.view s.scn /tmp/a.map f1.img f1.lut\n",
                15,
                "absolute path",
            ),
            ("f1.view s.scn ../a.map f1.img f1.lut\n", 15, "climbs out"),
            (
                "f1.view s.scn a.map a.map f1.lut\n",
                21,
                "frame 1 also writes",
            ),
        ] {
            let e = read_execute("x.exec", text, dir.path(), LengthUnit::M).unwrap_err();
            assert!(e.message.contains(says), "{text}: {e}");
            assert_eq!((e.line, e.column), (1, column), "{text}: {e}");
        }
        // A later frame writing an earlier frame's viewing file.
        let text = "f1.view s.scn a.map a.img a.lut\nf1.view s.scn f1.view b.img b.lut\n";
        let e = read_execute("x.exec", text, dir.path(), LengthUnit::M).unwrap_err();
        assert!(e.message.contains("viewing file of frame 1"), "{e}");
        assert_eq!((e.line, e.column), (2, 15), "{e}");
    }

    #[test]
    fn a_missing_viewing_file_is_an_error_at_its_name() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_execute(
            "x.exec",
            "\n  nope.view s m i l\n",
            dir.path(),
            LengthUnit::M,
        )
        .unwrap_err();
        assert!(
            e.message
                .contains("cannot read the viewing file `nope.view`"),
            "{e}"
        );
        assert_eq!((e.line, e.column), (2, 3));
    }
}
