//! The object (facet) file: the VAX parser's output from an Intergraph finite-element
//! model (thesis §4.1, the "object" file sample; Appendix H `facet_type`).
//!
//! ```text
//! 4                 number of facets
//!
//! 6                 material index [temperature in K: irsig extension]
//! 0.000000 0.000000 0.000000      vertex 1, x y z (km in the 1990 data)
//! -4.096910 -3.133200 0.000000    vertex 2
//! -5.000670 -1.810670 0.000000    vertex 3
//!
//! 6
//! ...
//! ```
//!
//! The facet count comes first; then each facet is a material-index line and three vertex
//! lines. Blank lines between facets are optional. The count must match the facets that
//! follow. A facet's material index line may carry a second value, the facet's kinetic
//! temperature in kelvin: the thesis recommends (§5.2) that each facet's material and
//! temperature be editable, and this lets a legacy file hold that edit. Files without it
//! are the 1990 form.
//!
//! What this parser does **not** check: triangle shape. A degenerate (zero-area) triangle
//! is well-formed syntax; `irsig_model::Object::validate` rejects it after import, naming
//! the facet, whose [`LegacyFacet::position`] points back into this file.

use std::fmt::Write as _;

use super::lex::{Lines, Span, position};
use super::{Position, WriteError, WriteErrorKind, check_finite, real};
use crate::ParseError;

/// One triangle of an object file. Coordinates are in the file's length unit, which the
/// file does not record (kilometres for the 1990 data; the importer asks).
#[derive(Debug, Clone, PartialEq)]
pub struct LegacyFacet {
    /// The material index, 1 to 65535, a row of the material index file. 0 is rejected:
    /// the interaction map uses 0 for "nothing hit". (The 1990 tracer allowed 1 to 15.)
    pub material_index: u16,
    /// The facet's kinetic temperature in kelvin, when the material line carries one
    /// (irsig extension; absent in 1990 files).
    pub temperature_k: Option<f64>,
    /// The three vertices as `[x, y, z]`, in the file's length unit, in file order. The
    /// 1990 code took the normal as `(v2 − v1) × (v3 − v1)`.
    pub vertices: [[f64; 3]; 3],
    /// Where the facet's material index line is.
    pub position: Position,
}

/// A parsed object file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjectFile {
    /// The facets in file order (facet 0 is the first).
    pub facets: Vec<LegacyFacet>,
    /// Where the facet count is.
    pub count_position: Position,
}

/// Reads an object file.
///
/// # Errors
/// A [`ParseError`] for a missing or malformed count, a count of 0, a material index that
/// is not a whole number from 1 to 65535, a temperature that is not above 0 K, a vertex
/// line without exactly three finite numbers, fewer facets than declared (truncated
/// file) or data after the declared facets.
pub fn parse(file: &str, text: &str) -> Result<ObjectFile, ParseError> {
    let mut lines = Lines::new(file, text);
    let count_line = lines.expect_line("the number of facets")?;
    let count = lines.single_unsigned(count_line, "the number of facets")?;
    let count_position = position(count_line.span);
    if count == 0 {
        return Err(lines.error(
            count_line.span,
            "expected at least 1 facet, found a declared count of 0 (an empty object)",
        ));
    }
    // Never trust the declared count for allocation: a facet takes at least 16 bytes
    // ("1\n0 0 0\n0 0 0\n0 0 0\n"), so the text bounds what can really follow.
    let plausible = (text.len() / 16).min(usize::try_from(count).unwrap_or(usize::MAX));
    let mut facets = Vec::with_capacity(plausible);
    for i in 0..count {
        let ordinal = i + 1;
        let index_line = lines.next_line().ok_or_else(|| {
            lines.eof_error(&format!(
                "expected facet {ordinal} of the {count} declared on line {}, found end of file",
                count_position.line
            ))
        })?;
        let (material_index, temperature_k) = material_line(&lines, index_line)?;
        let mut vertices = [[0.0; 3]; 3];
        for (k, vertex) in vertices.iter_mut().enumerate() {
            let what = format!("x y z of vertex {} of facet {ordinal}", k + 1);
            let line = lines.expect_line(&what)?;
            *vertex = lines.reals::<3>(line, &what)?.0;
        }
        facets.push(LegacyFacet {
            material_index,
            temperature_k,
            vertices,
            position: position(index_line.span),
        });
    }
    if let Some(extra) = lines.next_line() {
        return Err(lines.error(
            extra.span,
            format!(
                "expected end of file after the {count} facets declared on line {}, found more: `{}`",
                count_position.line,
                extra.span.fragment()
            ),
        ));
    }
    Ok(ObjectFile {
        facets,
        count_position,
    })
}

fn material_line(
    lines: &Lines<'_>,
    line: super::lex::Line<'_>,
) -> Result<(u16, Option<f64>), ParseError> {
    let mut tokens = Lines::tokens(line);
    let first: Span<'_> = tokens.next().unwrap_or(line.span);
    let what = "a material index, 1 to 65535";
    let index = lines.unsigned(first, what)?;
    let index = match u16::try_from(index) {
        Ok(0) | Err(_) => {
            return Err(lines.error(first, format!("expected {what}, found {index}")));
        }
        Ok(v) => v,
    };
    let temperature = match tokens.next() {
        None => None,
        Some(tok) => {
            let t = lines.real(tok, "the facet temperature in K")?;
            if t <= 0.0 {
                return Err(lines.error(
                    tok,
                    format!("expected a facet temperature above 0 K, found {t}"),
                ));
            }
            Some(t)
        }
    };
    if let Some(extra) = tokens.next() {
        return Err(lines.error(
            extra,
            format!(
                "expected a material index and an optional temperature, found more: `{}`",
                extra.fragment()
            ),
        ));
    }
    Ok((index, temperature))
}

/// Writes an object file in the 1990 layout (count, blank line, then each facet followed
/// by a blank line), with reals in their shortest exact form.
///
/// # Errors
/// A [`WriteError`] for an object without facets, a material index of 0, a non-finite
/// coordinate, or a temperature that is not a finite value above 0 K.
pub fn write(object: &ObjectFile) -> Result<String, WriteError> {
    if object.facets.is_empty() {
        return Err(WriteError::new("object", WriteErrorKind::Empty));
    }
    let mut out = String::with_capacity(object.facets.len() * 80);
    let _ = write!(out, "{}\n\n", object.facets.len());
    for (i, f) in object.facets.iter().enumerate() {
        let record = || format!("facet {}", i + 1);
        if f.material_index == 0 {
            return Err(WriteError::new(
                record(),
                WriteErrorKind::OutOfRange(
                    "material index 0 is reserved for \"nothing hit\"".into(),
                ),
            ));
        }
        check_finite(record, f.vertices.as_flattened())?;
        let _ = write!(out, "{}", f.material_index);
        if let Some(t) = f.temperature_k {
            check_finite(record, &[t])?;
            if t <= 0.0 {
                return Err(WriteError::new(
                    record(),
                    WriteErrorKind::OutOfRange(format!("temperature {t} K is not above 0 K")),
                ));
            }
            let _ = write!(out, " {}", real(t));
        }
        out.push('\n');
        for [x, y, z] in f.vertices {
            let _ = writeln!(out, "{} {} {}", real(x), real(y), real(z));
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

    /// The sample printed in thesis §4.1, as laid out there (blank lines between facets).
    const THESIS_SAMPLE: &str = "4\n\n6\n0.000000 0.000000 0.000000\n-4.096910 -3.133200 0.000000\n\
        -5.000670 -1.810670 0.000000\n\n6\n-4.100130 -1.886120 0.000000\n-5.000670 -1.810670 0.000000\n\
        -4.096910 -3.133200 0.000000\n\n6\n-4.096910 -3.133200 0.000000\n-3.181800 -3.181830 0.000000\n\
        -3.199730 -1.955010 0.000000\n\n6\n-3.199730 -1.955010 0.000000\n-4.100130 -1.886120 0.000000\n\
        -4.096910 -3.133200 0.000000\n";

    #[test]
    fn reads_the_thesis_sample() {
        let obj = parse("thesis.fac", THESIS_SAMPLE).unwrap();
        assert_eq!(obj.facets.len(), 4);
        assert!(
            obj.facets
                .iter()
                .all(|f| f.material_index == 6 && f.temperature_k.is_none())
        );
        assert_eq!(obj.facets[0].vertices[1], [-4.096_91, -3.1332, 0.0]);
        assert_eq!(obj.facets[3].vertices[2], [-4.096_91, -3.1332, 0.0]);
        // Facet 2 starts on line 8 (count, blank, 4 lines, blank).
        assert_eq!(obj.facets[1].position, Position { line: 8, column: 1 });
        assert_eq!(obj.count_position, Position { line: 1, column: 1 });
    }

    #[test]
    fn layout_is_liberal() {
        let text = "# a triangle\r\n  1 \r\n\t7 300.5\r\n0 0 0\r\n1\t0 0   \r\n0 1 0";
        let obj = parse("t", text).unwrap();
        assert_eq!(obj.facets[0].material_index, 7);
        assert_eq!(obj.facets[0].temperature_k, Some(300.5));
        assert_eq!(obj.facets[0].vertices[2], [0.0, 1.0, 0.0]);
        assert_eq!(obj.facets[0].position, Position { line: 3, column: 2 });
    }

    fn err(text: &str) -> ParseError {
        parse("bad.fac", text).unwrap_err()
    }

    #[test]
    fn wrong_counts_are_errors_at_the_right_place() {
        // Declared 2, one facet given: points at the end of the last line.
        let e = err("2\n1\n0 0 0\n1 0 0\n0 1 0\n");
        assert_eq!((e.line, e.column), (5, 6), "{e}");
        assert!(
            e.message.contains("facet 2 of the 2 declared on line 1"),
            "{e}"
        );
        // Declared 1, two given.
        let e = err("1\n1\n0 0 0\n1 0 0\n0 1 0\n1\n0 0 0\n1 0 0\n0 1 0\n");
        assert_eq!((e.line, e.column), (6, 1), "{e}");
        // A huge count does not allocate; it fails at the end of the data.
        let e = err("1000000000000\n1\n0 0 0\n1 0 0\n0 1 0\n");
        assert!(e.message.contains("facet 2 of the 1000000000000"), "{e}");
        let e = err("0\n");
        assert!(e.message.contains("empty object"), "{e}");
        assert_eq!((err("").line, err("").column), (1, 1));
    }

    #[test]
    fn bad_numbers_are_errors_at_the_token() {
        let e = err("1\n1\n0 0 0\n1 NaN 0\n0 1 0\n");
        assert_eq!((e.line, e.column), (4, 3), "{e}");
        assert!(e.message.contains("finite"), "{e}");
        let e = err("1\n1\n0 0 0\n1 0\n0 1 0\n");
        assert_eq!(e.line, 4);
        assert!(e.message.contains("found 2"), "{e}");
        let e = err("1\n1\n0 0 0\n1 0 0 9\n0 1 0\n");
        assert_eq!((e.line, e.column), (4, 7), "{e}");
        for (text, col) in [
            ("1\n0\n", 1),
            ("1\n65536\n", 1),
            ("1\n6.0\n", 1),
            ("1\n6 -3\n", 3),
            ("1\n6 0\n", 3),
        ] {
            let e = err(text);
            assert_eq!((e.line, e.column), (2, col), "{text:?}: {e}");
        }
        let e = err("1.5\n");
        assert!(e.message.contains("number of facets"), "{e}");
    }

    #[test]
    fn degenerate_triangles_are_left_to_the_model() {
        let obj = parse("t", "1\n1\n0 0 0\n0 0 0\n0 0 0\n").unwrap();
        assert_eq!(obj.facets.len(), 1);
    }

    #[test]
    fn writes_the_1990_layout() {
        let obj = parse("t", "1\n6\n0.000000 0.5 -1\n1 0 0\n0 1 0\n").unwrap();
        assert_eq!(
            write(&obj).unwrap(),
            "1\n\n6\n0.0 0.5 -1.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n\n"
        );
        assert_eq!(
            write(&ObjectFile::default()).unwrap_err().kind,
            WriteErrorKind::Empty
        );
        let mut bad = obj.clone();
        bad.facets[0].vertices[0][0] = f64::NAN;
        assert_eq!(write(&bad).unwrap_err().kind, WriteErrorKind::NotFinite);
    }
}
