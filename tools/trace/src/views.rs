//! Reading views: canonical RON (one view or a list), the 1990 viewing file, and the 1990
//! execute file that sequences viewing files into frames.
//!
//! The two view forms are told apart by the first significant character of the file:
//! a 1990 viewing file is nothing but numbers (`#` comments aside, an irsig extension of the
//! legacy syntax), so it starts with a digit, a sign or a decimal point; a RON view starts
//! with `Legacy(`, `LookAt(` or `[`. The viewing file's position is in the scene's length
//! unit (km in the thesis's files) and is converted to metres here, at the file boundary,
//! because the tracer works in metres (and its BVH cannot resolve 1e-4 km).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use irsig_formats::ParseError;
use irsig_formats::legacy::{decode, execute, view as legacy_view};
use irsig_model::{LengthUnit, View};
use miette::{WrapErr, miette};

use crate::Outputs;

/// Whether `text` is a 1990 viewing file rather than RON: its first character that is not
/// whitespace or inside a comment (`#` legacy, `//` and `/* */` RON) starts a number.
pub(crate) fn is_legacy_viewing_file(text: &str) -> bool {
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

/// The views of one file: a RON view, a RON list of views, or a 1990 viewing file whose
/// position is in `unit`.
pub(crate) fn read_views(path: &str, unit: LengthUnit) -> miette::Result<Vec<View>> {
    let input = irsig_cli::read_input(path)?;
    let text = decode(&input.name, &input.bytes)?;
    if is_legacy_viewing_file(text) {
        let file = legacy_view::parse(&input.name, text)?;
        let v = file.to_view(unit);
        // The parser has checked every value the model checks; a failure here is a value
        // that only the model rejects, reported at the file's first value.
        v.validate().map_err(|e| {
            let p = file.file_position;
            let offset = irsig_formats::offset_of(text, p.line, p.column);
            ParseError::at_offset(&input.name, text, offset, e.to_string())
        })?;
        return Ok(vec![v]);
    }
    let views = match ron::from_str::<View>(text) {
        Ok(v) => vec![v],
        Err(single) => ron::from_str::<Vec<View>>(text).map_err(|_| {
            let offset =
                irsig_formats::offset_of(text, single.span.start.line, single.span.start.col);
            ParseError::at_offset(
                &input.name,
                text,
                offset,
                format!(
                    "expected a view, a list of views (RON) or a 1990 viewing file (numbers): {}",
                    single.code
                ),
            )
        })?,
    };
    if views.is_empty() {
        return Err(miette!("{}: the list of views is empty", input.name));
    }
    for (i, v) in views.iter().enumerate() {
        v.validate()
            .map_err(|e| miette!("{}: view {}: {e}", input.name, i + 1))?;
    }
    Ok(views)
}

/// The frames of a 1990 execute file: each frame's view (read from its viewing file, in
/// `unit`) and the outputs it names (interaction map, DC image, LUT), paths relative to
/// the execute file's directory.
///
/// Every frame must name the same scene file, since the run traces one flattened scene with
/// one BVH; two frames naming one output file would overwrite each other. Both are errors
/// at the offending name.
pub(crate) fn read_execute(
    path: &str,
    unit: LengthUnit,
) -> miette::Result<(Vec<View>, Vec<Outputs>)> {
    let input = irsig_cli::read_input(path)?;
    let text = decode(&input.name, &input.bytes)?;
    let file = execute::parse(&input.name, text)?;
    let base = input.base_dir();
    let at =
        |offset: usize, message: String| ParseError::at_offset(&input.name, text, offset, message);
    // Where each name of a frame starts: the parser keeps the first name's position; the
    // others are found by scanning forward from it.
    let locate = |frame: &execute::ExecuteFrame, name: &str| {
        let start = irsig_formats::offset_of(text, frame.position.line, frame.position.column);
        text.get(start..)
            .and_then(|rest| rest.find(name))
            .map_or(start, |i| start + i)
    };
    let first_scene = file.frames.first().map(|f| f.scene.as_str()).unwrap_or("");
    let mut views = Vec::with_capacity(file.frames.len());
    let mut outputs = Vec::with_capacity(file.frames.len());
    let mut written: HashMap<PathBuf, usize> = HashMap::new();
    for (i, frame) in file.frames.iter().enumerate() {
        if frame.scene != first_scene {
            return Err(at(
                locate(frame, &frame.scene),
                format!(
                    "expected the scene file of frame 1, `{first_scene}`, found `{}`: one run \
                     traces one flattened scene (--scene) with one BVH; split the execute file \
                     by scene",
                    frame.scene
                ),
            )
            .into());
        }
        let view_path = resolve(&base, &frame.view);
        let mut frame_views =
            read_views(&view_path.to_string_lossy(), unit).wrap_err_with(|| {
                format!(
                    "{}:{}:{}: the viewing file of frame {}",
                    input.name,
                    frame.position.line,
                    frame.position.column,
                    i + 1
                )
            })?;
        if frame_views.len() != 1 {
            return Err(at(
                locate(frame, &frame.view),
                format!(
                    "expected a viewing file holding one view, found {} views in `{}`",
                    frame_views.len(),
                    frame.view
                ),
            )
            .into());
        }
        views.append(&mut frame_views);
        let frame_outputs = [&frame.map_image, &frame.image, &frame.lut].map(|n| resolve(&base, n));
        for (k, p) in frame_outputs.iter().enumerate() {
            if let Some(other) = written.insert(p.clone(), i + 1) {
                let name = [&frame.map_image, &frame.image, &frame.lut][k];
                return Err(at(
                    locate(frame, name),
                    format!(
                        "expected a file name no other output uses, found `{name}`, which \
                         frame {other} also writes"
                    ),
                )
                .into());
            }
        }
        let [map_png, dc_png, lut] = frame_outputs;
        outputs.push(Outputs {
            map_png: Some(map_png),
            dc_png: Some(dc_png),
            lut: Some(lut),
            ..Outputs::default()
        });
    }
    Ok((views, outputs))
}

/// A name from an execute file, relative to the execute file's directory.
fn resolve(base: &Path, name: &str) -> PathBuf {
    let p = Path::new(name);
    if p.is_absolute() || base == Path::new(".") {
        p.to_path_buf()
    } else {
        base.join(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
