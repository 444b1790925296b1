//! The viewing file: where the sensor is and how it looks (thesis §4.1; Appendix H
//! `view_type`).
//!
//! ```text
//! 1.60 -3.00 0.70          V_x V_y V_z: viewer position, km
//! 256 256                  M N: pixels in x (columns) and y (rows)
//! 78.3664 0.00 28.0725     ω φ κ: rotations of the image plane about x, y, z, degrees
//! 1.0 1.0                  fov_x fov_y: full fields of view, degrees
//! 2.0                      DC/K: system gain in digital counts per kelvin (optional)
//! ```
//!
//! (Frame 1 of thesis Table 2.) The values are read in this order whatever the line
//! layout, as `fscanf` would; the gain may be left out (the DC image stage then needs
//! its own). Pixel counts are whole numbers of at least 1 (the 1990 tracer's image array
//! was 512 × 512); fields of view lie strictly between 0 and 180°; a gain, if present, is
//! above 0. The position is in kilometres in 1990 files; [`ViewingFile::to_view`] takes
//! the unit explicitly.

use irsig_model::{LengthUnit, View};

use super::lex::{Lines, Span, position};
use super::{Position, WriteError, WriteErrorKind, check_finite, real};
use crate::ParseError;

/// A parsed viewing file, in its own units.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewingFile {
    /// V_x, V_y, V_z: the viewer's position, in the scene's length unit (km in 1990).
    pub position: [f64; 3],
    /// M, N: image size as `[columns, rows]`.
    pub pixels: [u32; 2],
    /// ω, φ, κ: image-plane rotations about x, y and z, degrees.
    pub omega_phi_kappa_deg: [f64; 3],
    /// fov_x, fov_y: full fields of view, degrees.
    pub fov_deg: [f64; 2],
    /// DC/K: system gain, digital counts per kelvin, if given.
    pub gain_dc_per_k: Option<f64>,
    /// Where the first value is.
    pub file_position: Position,
}

impl ViewingFile {
    /// The canonical legacy view, with the position converted from `unit` to metres
    /// (`LengthUnit::Km` for 1990 files).
    #[must_use]
    pub fn to_view(&self, unit: LengthUnit) -> View {
        View::Legacy {
            position_m: self.position.map(|v| v * unit.metres()),
            pixels: self.pixels,
            omega_phi_kappa_deg: self.omega_phi_kappa_deg,
            fov_deg: self.fov_deg,
            gain_dc_per_k: self.gain_dc_per_k,
        }
    }
}

const NAMES: [&str; 11] = [
    "viewer x (V_x)",
    "viewer y (V_y)",
    "viewer z (V_z)",
    "pixels in x (M)",
    "pixels in y (N)",
    "rotation omega about x in degrees",
    "rotation phi about y in degrees",
    "rotation kappa about z in degrees",
    "field of view x in degrees",
    "field of view y in degrees",
    "gain in DC/K",
];

fn check(k: usize, v: f64) -> Result<(), String> {
    match k {
        8 | 9 if !(v > 0.0 && v < 180.0) => Err(format!(
            "expected a {} strictly between 0 and 180, found {v}",
            NAMES[k]
        )),
        10 if v <= 0.0 => Err(format!("expected a {} above 0, found {v}", NAMES[k])),
        _ => Ok(()),
    }
}

/// Reads a viewing file.
///
/// # Errors
/// A [`ParseError`] for fewer than 10 values, more than 11, a value that is not a finite
/// number, a pixel count that is not a whole number from 1 to 4294967295, a field of view
/// outside (0°, 180°), or a gain that is not above 0.
pub fn parse(file: &str, text: &str) -> Result<ViewingFile, ParseError> {
    let mut lines = Lines::new(file, text);
    let mut values = [0.0; 11];
    let mut pixels = [0u32; 2];
    let mut n = 0;
    let mut first: Option<Span<'_>> = None;
    while let Some(line) = lines.next_line() {
        for tok in Lines::tokens(line) {
            let Some(&what) = NAMES.get(n) else {
                return Err(lines.error(
                    tok,
                    format!(
                        "expected at most 11 values (position, pixels, rotations, fields of view, gain), found more: `{}`",
                        tok.fragment()
                    ),
                ));
            };
            first.get_or_insert(tok);
            if n == 3 || n == 4 {
                let count = lines.unsigned(tok, what)?;
                match u32::try_from(count) {
                    Ok(c) if c >= 1 => pixels[n - 3] = c,
                    _ => {
                        return Err(lines.error(
                            tok,
                            format!("expected {what} from 1 to 4294967295, found {count}"),
                        ));
                    }
                }
            } else {
                let v = lines.real(tok, what)?;
                check(n, v).map_err(|m| lines.error(tok, m))?;
                values[n] = v;
            }
            n += 1;
        }
    }
    if n < 10 {
        let what = NAMES.get(n).copied().unwrap_or("a value");
        return Err(lines.eof_error(&format!(
            "expected value {} of 10 ({what}), found end of file",
            n + 1
        )));
    }
    let [x, y, z, _, _, o, p, k, fx, fy, gain] = values;
    Ok(ViewingFile {
        position: [x, y, z],
        pixels,
        omega_phi_kappa_deg: [o, p, k],
        fov_deg: [fx, fy],
        gain_dc_per_k: (n == 11).then_some(gain),
        file_position: first.map(position).unwrap_or_default(),
    })
}

/// Writes a viewing file in the five-line layout of thesis §4.1 (four lines when there is
/// no gain).
///
/// # Errors
/// A [`WriteError`] for a non-finite value, a pixel count of 0, a field of view outside
/// (0°, 180°) or a gain that is not above 0.
pub fn write(view: &ViewingFile) -> Result<String, WriteError> {
    let mut values: Vec<f64> = view.position.to_vec();
    values.extend(view.omega_phi_kappa_deg);
    values.extend(view.fov_deg);
    values.extend(view.gain_dc_per_k);
    check_finite(|| "view".to_owned(), &values)?;
    if view.pixels.contains(&0) {
        return Err(WriteError::new(
            "view",
            WriteErrorKind::OutOfRange("a pixel count is 0".into()),
        ));
    }
    for (k, v) in [(8, view.fov_deg[0]), (9, view.fov_deg[1])]
        .into_iter()
        .chain(view.gain_dc_per_k.map(|g| (10, g)))
    {
        check(k, v).map_err(|m| WriteError::new("view", WriteErrorKind::OutOfRange(m)))?;
    }
    let r = |v: [f64; 3]| format!("{} {} {}", real(v[0]), real(v[1]), real(v[2]));
    let mut out = format!(
        "{}\n{} {}\n{}\n{} {}\n",
        r(view.position),
        view.pixels[0],
        view.pixels[1],
        r(view.omega_phi_kappa_deg),
        real(view.fov_deg[0]),
        real(view.fov_deg[1])
    );
    if let Some(g) = view.gain_dc_per_k {
        out.push_str(&real(g));
        out.push('\n');
    }
    Ok(out)
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    const FRAME_1: &str = "1.60 -3.00 0.70\n256 256\n78.3664 0.00 28.0725\n1.0 1.0\n2.0\n";

    #[test]
    fn reads_thesis_table_2_frame_1() {
        let v = parse("f1.view", FRAME_1).unwrap();
        assert_eq!(v.position, [1.6, -3.0, 0.7]);
        assert_eq!(v.pixels, [256, 256]);
        assert_eq!(v.omega_phi_kappa_deg, [78.3664, 0.0, 28.0725]);
        assert_eq!(v.fov_deg, [1.0, 1.0]);
        assert_eq!(v.gain_dc_per_k, Some(2.0));
        // 1.6 km east, 3 km south, 700 m up (thesis §4.4).
        let View::Legacy { position_m, .. } = v.to_view(LengthUnit::Km) else {
            panic!("legacy view expected")
        };
        assert_eq!(position_m, [1600.0, -3000.0, 700.0]);
        let again = parse("f", &write(&v).unwrap()).unwrap();
        assert_eq!(
            again,
            ViewingFile {
                file_position: again.file_position,
                ..v
            }
        );
    }

    #[test]
    fn gain_is_optional_and_layout_free() {
        let v = parse("v", "0 0 1 64 48 0 0 0 20 15").unwrap();
        assert_eq!(v.pixels, [64, 48]);
        assert_eq!(v.gain_dc_per_k, None);
    }

    #[test]
    fn rejects_bad_values_at_the_value() {
        for (text, line, col, needle) in [
            ("1 2 3\n0 256\n", 2, 1, "from 1 to"),
            ("1 2 3\n256.5 256\n", 2, 1, "whole number"),
            (
                "1 2 3\n2 2\n0 0 0\n0 1\n",
                4,
                1,
                "strictly between 0 and 180",
            ),
            (
                "1 2 3\n2 2\n0 0 0\n180 1\n",
                4,
                1,
                "strictly between 0 and 180",
            ),
            ("1 2 3\n2 2\n0 0 0\n1 1\n-2\n", 5, 1, "above 0"),
            ("1 2 3\n2 2\n0 0 0\n1 1\n2 7\n", 5, 3, "at most 11"),
            ("1 2 3\n2 2\n0 0 0\n1\n", 4, 2, "value 10 of 10"),
            ("1 inf 3\n", 1, 3, "finite"),
        ] {
            let e = parse("v", text).unwrap_err();
            assert_eq!((e.line, e.column), (line, col), "{text:?}: {e}");
            assert!(e.message.contains(needle), "{text:?}: {e}");
        }
    }
}
