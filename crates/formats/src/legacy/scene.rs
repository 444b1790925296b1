//! The scene file: which objects make up the scene and where they go (thesis §4.1).
//!
//! ```text
//! road.fac            object file name (no whitespace, no `#`, not a number)
//! 0 0 90              ξ ψ ν: rotation about x, y, z in degrees
//! 1.6 -3.0 0.0        t_x t_y t_z: translation, in the object file's length unit
//! 1 1 1               s_x s_y s_z: scale (dimensionless, non-zero)
//! 293.15              optional: the whole object's kinetic temperature in K
//!
//! tree.fac
//! ...
//! ```
//!
//! There is no count: there are as many objects as entries, at least one. The 1990 layout
//! is the name on its own line and three lines of three values; this parser accepts the
//! nine values in any line layout (all on the name line, or on one line after it, ...)
//! because the thesis gives only their order. The optional temperature is either a tenth
//! value on the line holding the ninth, or a line of exactly one number right after it.
//! (The 1990 flattener asked the user for each object's temperature; recording it here
//! is an irsig extension, and files without it are the 1990 form.)
//!
//! The order in which rotation, translation and scale apply is the flattener's
//! (`irsig-flatten`), not this file's; this module only reads the numbers.

use std::fmt::Write as _;

use super::lex::{Lines, position};
use super::{Position, WriteError, WriteErrorKind, check_finite, check_name, real};
use crate::ParseError;

/// One object placed in the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneEntry {
    /// The object file's name as written (a path relative to the scene file, or a bare
    /// name the user resolves).
    pub object: String,
    /// ξ, ψ, ν: rotations about the x, y and z axes, in degrees.
    pub rotation_deg: [f64; 3],
    /// t_x, t_y, t_z: translation, in the object file's length unit (km for 1990 data).
    pub translation: [f64; 3],
    /// s_x, s_y, s_z: scale factors, dimensionless, non-zero (negative mirrors).
    pub scale: [f64; 3],
    /// The object's kinetic temperature in kelvin, if the entry gives one.
    pub temperature_k: Option<f64>,
    /// Where the entry's object name is.
    pub position: Position,
}

/// A parsed scene file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SceneFile {
    /// The entries in file order.
    pub entries: Vec<SceneEntry>,
}

const VALUE_NAMES: [&str; 10] = [
    "rotation about x in degrees",
    "rotation about y in degrees",
    "rotation about z in degrees",
    "translation x",
    "translation y",
    "translation z",
    "scale x",
    "scale y",
    "scale z",
    "temperature in K",
];

/// Reads a scene file.
///
/// # Errors
/// A [`ParseError`] for an empty file, an object name that is a number (usually a sign of
/// a wrong count of values before it), fewer than nine values for an entry, a value that
/// is not a finite number, more than ten values, a zero scale, or a temperature that is
/// not above 0 K.
pub fn parse(file: &str, text: &str) -> Result<SceneFile, ParseError> {
    let mut lines = Lines::new(file, text);
    let mut entries = Vec::new();
    while let Some(name_line) = lines.next_line() {
        let mut tokens = Lines::tokens(name_line);
        let name_tok = tokens.next().unwrap_or(name_line.span);
        let name = *name_tok.fragment();
        if super::lex::looks_numeric(name) {
            let message = if entries.is_empty() {
                format!("expected an object file name, found the number `{name}`")
            } else {
                format!(
                    "expected an object file name, found the number `{name}` \
                     (does the entry before have more than 9 values and a temperature?)"
                )
            };
            return Err(lines.error(name_tok, message));
        }
        let mut values = [0.0; 10];
        let mut n = 0;
        let mut rest = tokens;
        loop {
            for tok in rest.by_ref() {
                if n == 10 {
                    return Err(lines.error(
                        tok,
                        format!(
                            "expected at most 10 values for object `{name}` \
                             (rotation, translation, scale, temperature), found more: `{}`",
                            tok.fragment()
                        ),
                    ));
                }
                let what = VALUE_NAMES[n];
                let v = lines.real(tok, what).map_err(|e| {
                    if n < 9 && !super::lex::looks_numeric(tok.fragment()) {
                        lines.error(
                            tok,
                            format!(
                                "expected value {} of 9 ({what}) for object `{name}`, found `{}`",
                                n + 1,
                                tok.fragment()
                            ),
                        )
                    } else {
                        e
                    }
                })?;
                check_value(n, v).map_err(|m| lines.error(tok, m))?;
                values[n] = v;
                n += 1;
            }
            if n >= 9 {
                break;
            }
            let what = format!(
                "value {} of 9 ({}) for object `{name}`",
                n + 1,
                VALUE_NAMES[n]
            );
            rest = Lines::tokens(lines.expect_line(&what)?);
        }
        // A line of exactly one number right after the ninth value is the temperature.
        if n == 9 {
            let mut peek = lines.clone();
            if let Some(line) = peek.next_line() {
                let mut tokens = Lines::tokens(line);
                if let (Some(tok), None) = (tokens.next(), tokens.next()) {
                    if super::lex::looks_numeric(tok.fragment()) {
                        let t = lines.real(tok, VALUE_NAMES[9])?;
                        check_value(9, t).map_err(|m| lines.error(tok, m))?;
                        values[9] = t;
                        n = 10;
                        lines = peek;
                    }
                }
            }
        }
        let [r0, r1, r2, t0, t1, t2, s0, s1, s2, temp] = values;
        entries.push(SceneEntry {
            object: name.to_owned(),
            rotation_deg: [r0, r1, r2],
            translation: [t0, t1, t2],
            scale: [s0, s1, s2],
            temperature_k: (n == 10).then_some(temp),
            position: position(name_tok),
        });
    }
    if entries.is_empty() {
        return Err(lines.eof_error("expected at least one object entry, found end of file"));
    }
    Ok(SceneFile { entries })
}

fn check_value(n: usize, v: f64) -> Result<(), String> {
    match n {
        6..=8 if v == 0.0 => Err(format!(
            "expected a non-zero {}, found 0 (it would flatten the object)",
            VALUE_NAMES[n]
        )),
        9 if v <= 0.0 => Err(format!("expected a temperature above 0 K, found {v}")),
        _ => Ok(()),
    }
}

/// Writes a scene file in the 1990 layout: the name, then rotation, translation and scale
/// lines, then the temperature line when there is one, and a blank line after each entry.
///
/// # Errors
/// A [`WriteError`] for a scene without entries, a name that would not read back (empty,
/// whitespace, `#`, numeric), a non-finite value, a zero scale, or a temperature that is
/// not above 0 K.
pub fn write(scene: &SceneFile) -> Result<String, WriteError> {
    if scene.entries.is_empty() {
        return Err(WriteError::new("scene", WriteErrorKind::Empty));
    }
    let mut out = String::new();
    for (i, e) in scene.entries.iter().enumerate() {
        let record = || format!("entry {} (`{}`)", i + 1, e.object);
        check_name(record, &e.object)?;
        let mut values: Vec<f64> = [e.rotation_deg, e.translation, e.scale].concat();
        values.extend(e.temperature_k);
        check_finite(record, &values)?;
        for (n, &v) in values.iter().enumerate() {
            check_value(n, v)
                .map_err(|m| WriteError::new(record(), WriteErrorKind::OutOfRange(m)))?;
        }
        let _ = writeln!(out, "{}", e.object);
        for triple in [e.rotation_deg, e.translation, e.scale] {
            let _ = writeln!(
                out,
                "{} {} {}",
                real(triple[0]),
                real(triple[1]),
                real(triple[2])
            );
        }
        if let Some(t) = e.temperature_k {
            let _ = writeln!(out, "{}", real(t));
        }
        out.push('\n');
    }
    Ok(out)
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal, so the
// tests compare floats exactly.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_1990_layout_with_and_without_temperatures() {
        let text = "road.fac\n0 0 90\n1.6 -3.0 0.0\n1 1 1\n\ntree.fac\n0.0 0.0 0.0\n0.2 0.1 0\n2 2 3\n289.15\n\ncar.fac\n1 2 3\n4 5 6\n7 8 9\n";
        let s = parse("s.scn", text).unwrap();
        assert_eq!(s.entries.len(), 3);
        let road = &s.entries[0];
        assert_eq!(road.object, "road.fac");
        assert_eq!(road.rotation_deg, [0.0, 0.0, 90.0]);
        assert_eq!(road.translation, [1.6, -3.0, 0.0]);
        assert_eq!(road.scale, [1.0; 3]);
        assert_eq!(road.temperature_k, None);
        assert_eq!(s.entries[1].temperature_k, Some(289.15));
        assert_eq!(s.entries[1].scale, [2.0, 2.0, 3.0]);
        assert_eq!(s.entries[1].position, Position { line: 6, column: 1 });
        assert_eq!(s.entries[2].scale, [7.0, 8.0, 9.0]);
        assert_eq!(s.entries[2].temperature_k, None);
    }

    #[test]
    fn values_may_sit_on_any_lines() {
        let s = parse(
            "s",
            "a.fac 1 2 3 4 5 6 7 8 9 300\nb.fac\n1 2 3 4 5 6 7 8 9\n250\n",
        )
        .unwrap();
        assert_eq!(s.entries[0].temperature_k, Some(300.0));
        assert_eq!(s.entries[0].scale, [7.0, 8.0, 9.0]);
        assert_eq!(s.entries[1].temperature_k, Some(250.0));
        // A temperature must be alone on its line; two numbers there start nothing valid.
        let e = parse("s", "a.fac\n1 2 3\n4 5 6\n7 8 9\n250 1\n").unwrap_err();
        assert_eq!((e.line, e.column), (5, 1), "{e}");
    }

    #[test]
    fn errors_name_the_value_and_the_object() {
        let e = parse("s", "a.fac\n1 2 3\n4 5 6\nb.fac\n").unwrap_err();
        assert_eq!((e.line, e.column), (4, 1), "{e}");
        assert!(
            e.message
                .contains("value 7 of 9 (scale x) for object `a.fac`"),
            "{e}"
        );
        let e = parse("s", "a.fac\n1 2 3\n4 5 6\n").unwrap_err();
        assert!(e.message.contains("found end of file"), "{e}");
        assert_eq!((e.line, e.column), (3, 6), "{e}");
        let e = parse("s", "a.fac\n1 2 3\n4 inf 6\n7 8 9\n").unwrap_err();
        assert_eq!((e.line, e.column), (3, 3), "{e}");
        let e = parse("s", "a.fac\n1 2 3\n4 5 6\n7 0 9\n").unwrap_err();
        assert!(e.message.contains("non-zero scale y"), "{e}");
        let e = parse("s", "a.fac\n1 2 3\n4 5 6\n7 8 9\n-3\n").unwrap_err();
        assert!(e.message.contains("above 0 K"), "{e}");
        let e = parse("s", "a.fac 1 2 3 4 5 6 7 8 9 300 4\n").unwrap_err();
        assert_eq!((e.line, e.column), (1, 29), "{e}");
        let e = parse("s", "\n\n").unwrap_err();
        assert!(e.message.contains("at least one object"), "{e}");
        let e = parse("s", "42\n").unwrap_err();
        assert!(e.message.contains("object file name"), "{e}");
    }

    #[test]
    fn writer_rejects_what_would_not_read_back() {
        let entry = SceneEntry {
            object: "a.fac".into(),
            rotation_deg: [0.0; 3],
            translation: [0.0; 3],
            scale: [1.0; 3],
            temperature_k: Some(300.0),
            position: Position::default(),
        };
        let scene = SceneFile {
            entries: vec![entry.clone()],
        };
        assert_eq!(
            write(&scene).unwrap(),
            "a.fac\n0.0 0.0 0.0\n0.0 0.0 0.0\n1.0 1.0 1.0\n300.0\n\n"
        );
        for name in ["", "my car", "x#1", "12", "-1e3"] {
            let mut s = scene.clone();
            s.entries[0].object = name.into();
            assert!(
                matches!(write(&s).unwrap_err().kind, WriteErrorKind::BadName(_)),
                "{name:?}"
            );
        }
        let mut s = scene.clone();
        s.entries[0].scale[2] = 0.0;
        assert!(matches!(
            write(&s).unwrap_err().kind,
            WriteErrorKind::OutOfRange(_)
        ));
        let mut s = scene;
        s.entries[0].temperature_k = Some(f64::INFINITY);
        assert_eq!(write(&s).unwrap_err().kind, WriteErrorKind::NotFinite);
    }
}
