//! The execute file: which files one run of the tracer reads and writes, frame by frame
//! (thesis §4.1; Appendix H `read_exec_file`, globals `viewfile scenefile mapimage
//! outimage lutfile`).
//!
//! ```text
//! flyby-frame1.view      viewing file
//! two-patches.scn        scene file
//! frame1.map             interaction map image (output)
//! frame1.img             radiance / DC image (output)
//! frame1.lut             look-up table DC -> radiance -> K -> degC (output)
//!
//! flyby-frame2.view      the next frame of a fly-by ...
//! ...
//! ```
//!
//! The thesis says the execute file "tell\[s\] the ray-tracer which viewing file to use,
//! which scene file to use, and the names of the two output images", and that it exists
//! "so fly-by scenarios may be created with relative ease"; the 1990 code reads five names
//! (the three outputs include the LUT file). irsig reads a file as a sequence of frames of
//! exactly these five names, in this order, separated by any whitespace (one per line is
//! the written layout, with a blank line between frames). Names are paths relative to the
//! execute file, without whitespace or `#`. The 1990 names held 19 characters.

use std::fmt::Write as _;

use super::lex::{Lines, Span, position};
use super::{Position, WriteError, WriteErrorKind};
use crate::ParseError;

/// One frame of an execute file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExecuteFrame {
    /// The viewing file to use.
    pub view: String,
    /// The scene file to use.
    pub scene: String,
    /// The interaction-map image to write.
    pub map_image: String,
    /// The radiance (DC) image to write.
    pub image: String,
    /// The look-up-table file to write.
    pub lut: String,
    /// Where each name is, in the order above (view, scene, map image, image, LUT).
    pub positions: [Position; 5],
}

impl ExecuteFrame {
    /// Where the frame starts: its viewing file's name.
    #[must_use]
    pub fn position(&self) -> Position {
        self.positions[0]
    }
}

/// A parsed execute file.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ExecuteFile {
    /// The frames in order.
    pub frames: Vec<ExecuteFrame>,
}

const ROLES: [&str; 5] = [
    "the viewing file",
    "the scene file",
    "the interaction map image",
    "the output image",
    "the LUT file",
];

/// Reads an execute file.
///
/// # Errors
/// A [`ParseError`] for an empty file or a last frame with fewer than five names.
pub fn parse(file: &str, text: &str) -> Result<ExecuteFile, ParseError> {
    let mut lines = Lines::new(file, text);
    let mut frames = Vec::new();
    let mut pending: Vec<Span<'_>> = Vec::with_capacity(5);
    while let Some(line) = lines.next_line() {
        for tok in Lines::tokens(line) {
            pending.push(tok);
            if let [v, s, m, i, l] = pending.as_slice() {
                let name = |t: &Span<'_>| (*t.fragment()).to_owned();
                frames.push(ExecuteFrame {
                    view: name(v),
                    scene: name(s),
                    map_image: name(m),
                    image: name(i),
                    lut: name(l),
                    positions: [v, s, m, i, l].map(|t| position(*t)),
                });
                pending.clear();
            }
        }
    }
    if let Some(role) = ROLES.get(pending.len()).filter(|_| !pending.is_empty()) {
        return Err(lines.eof_error(&format!(
            "expected {role} of frame {}, found end of file (a frame names 5 files: \
             view, scene, map image, output image, LUT)",
            frames.len() + 1
        )));
    }
    if frames.is_empty() {
        return Err(lines.eof_error(
            "expected at least one frame (view, scene, map image, output image, LUT), found end of file",
        ));
    }
    Ok(ExecuteFile { frames })
}

/// Writes an execute file, one name per line and a blank line after each frame.
///
/// # Errors
/// A [`WriteError`] for no frames or a name that is empty or holds whitespace or `#`.
pub fn write(file: &ExecuteFile) -> Result<String, WriteError> {
    if file.frames.is_empty() {
        return Err(WriteError::new("execute file", WriteErrorKind::Empty));
    }
    let mut out = String::new();
    for (i, f) in file.frames.iter().enumerate() {
        for name in [&f.view, &f.scene, &f.map_image, &f.image, &f.lut] {
            if name.is_empty() || name.contains(char::is_whitespace) || name.contains('#') {
                return Err(WriteError::new(
                    format!("frame {}", i + 1),
                    WriteErrorKind::BadName(name.clone()),
                ));
            }
            let _ = writeln!(out, "{name}");
        }
        out.push('\n');
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_frames_in_any_layout() {
        let text = "a.view\nb.scn\nm1 i1 l1\n\na2.view b.scn m2 i2 l2\n";
        let e = parse("x.exec", text).unwrap();
        assert_eq!(e.frames.len(), 2);
        assert_eq!(e.frames[0].map_image, "m1");
        assert_eq!(e.frames[0].lut, "l1");
        assert_eq!(e.frames[1].view, "a2.view");
        assert_eq!(e.frames[1].position(), Position { line: 5, column: 1 });
        assert_eq!(
            e.frames[1].positions[4],
            Position {
                line: 5,
                column: 21
            }
        );
        let again = parse("x", &write(&e).unwrap()).unwrap();
        assert_eq!(
            again.frames.iter().map(|f| &f.image).collect::<Vec<_>>(),
            ["i1", "i2"]
        );
    }

    #[test]
    fn an_incomplete_frame_says_what_is_missing() {
        let e = parse("x", "a.view\nb.scn\nm1 i1 l1\na2.view b.scn\n").unwrap_err();
        assert!(
            e.message.contains("the interaction map image of frame 2"),
            "{e}"
        );
        assert_eq!((e.line, e.column), (4, 14));
        let e = parse("x", "# nothing\n").unwrap_err();
        assert!(e.message.contains("at least one frame"), "{e}");
        let bad = ExecuteFile {
            frames: vec![ExecuteFrame {
                view: "a b".into(),
                scene: "s".into(),
                map_image: "m".into(),
                image: "i".into(),
                lut: "l".into(),
                positions: [Position::default(); 5],
            }],
        };
        assert!(matches!(
            write(&bad).unwrap_err().kind,
            WriteErrorKind::BadName(_)
        ));
    }
}
