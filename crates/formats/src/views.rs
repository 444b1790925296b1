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

/// The views of one file's text: a RON view, a RON list of views, or a 1990 viewing file
/// whose position is in `unit`. Every view is validated; a broken rule is reported at its
/// value's line and column.
///
/// # Errors
/// A syntax error, an empty list, or a view that breaks a model rule.
pub fn parse_views(file: &str, text: &str, unit: LengthUnit) -> Result<Vec<View>, ParseError> {
    if is_legacy_viewing_file(text) {
        let parsed = legacy_view::parse(file, text)?;
        let v = parsed.to_view(unit);
        // The parser has checked every value the model checks; a failure here is a value
        // that only the model rejects, reported at the file's first value.
        v.validate().map_err(|e| {
            let p = parsed.file_position;
            ParseError::at_offset(file, text, offset_of(text, p.line, p.column), e.to_string())
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
        ParseError::at_offset(file, text, offset_of(text, p.line, p.column), message)
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
                     traces one flattened scene (--scene) with one BVH; split the execute file \
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
