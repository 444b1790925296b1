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
//! [x y z                          vertex 4: irsig extension]
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
//! **4-vertex facets** (irsig extension; thesis §5.2 asks whether facets should be "solely
//! 3 vertex or improved to include 4 vertices"): a line of three numbers after a facet's
//! third vertex is its fourth. It cannot be mistaken for the next facet's material line,
//! which holds one or two tokens and starts with a whole number; any other line there is
//! read as a fourth vertex, so a fourth vertex cut short is an error at its own line. The
//! count counts a 4-vertex facet as one facet. The facet must be planar and convex within
//! [`quad_tolerance`] (see [`QuadDefect`]), checked here so that a refusal points at the
//! vertex line. It stays one [`LegacyFacet`] (with [`LegacyFacet::fourth_vertex`]) so that
//! [`write`] gives it back as four vertex lines; it becomes two triangles where the file
//! becomes a mesh (`crate::mesh::from_legacy_object`), split along its shorter diagonal
//! ([`LegacyFacet::triangles`]), so that every later stage sees triangles only and each
//! half keeps the facet's material, temperature and [`LegacyFacet::position`].
//!
//! What this parser does **not** check: triangle shape. A degenerate (zero-area) triangle
//! is well-formed syntax; `irsig_model::Object::validate` rejects it after import, naming
//! the facet, whose [`LegacyFacet::position`] points back into this file.

use std::fmt::Write as _;

use super::lex::{Line, Lines, Span, position};
use super::{Position, WriteError, WriteErrorKind, check_finite, real};
use crate::ParseError;

/// One facet of an object file: a triangle, or a 4-vertex facet (irsig extension).
/// Coordinates are in the file's length unit, which the file does not record (kilometres
/// for the 1990 data; the importer asks).
#[derive(Debug, Clone, PartialEq)]
pub struct LegacyFacet {
    /// The material index, 1 to 65535, a row of the material index file. 0 is rejected:
    /// the interaction map uses 0 for "nothing hit". (The 1990 tracer allowed 1 to 15.)
    pub material_index: u16,
    /// The facet's kinetic temperature in kelvin, when the material line carries one
    /// (irsig extension; absent in 1990 files).
    pub temperature_k: Option<f64>,
    /// The first three vertices as `[x, y, z]`, in the file's length unit, in file order.
    /// The 1990 code took the normal as `(v2 − v1) × (v3 − v1)`.
    pub vertices: [[f64; 3]; 3],
    /// The fourth vertex of a 4-vertex facet (irsig extension, thesis §5.2), `None` for a
    /// triangle. A parsed one is planar and convex ([`LegacyFacet::check_quad`]), wound
    /// like the first three, and stays here until [`LegacyFacet::triangles`] splits it.
    pub fourth_vertex: Option<[f64; 3]>,
    /// Where the facet's material index line is.
    pub position: Position,
}

/// A planar 4-vertex facet may be off by this much, in the file's length unit, plus
/// [`QUAD_RELATIVE_TOLERANCE`] of its longer diagonal; see [`quad_tolerance`].
pub const QUAD_ABSOLUTE_TOLERANCE: f64 = 2e-6;

/// The part of [`quad_tolerance`] that grows with the facet: this fraction of its longer
/// diagonal.
pub const QUAD_RELATIVE_TOLERANCE: f64 = 1e-6;

/// How far, in the file's length unit, the two diagonals of a planar 4-vertex facet may
/// pass apart, and how far out from the diagonal that cuts it off each corner must at
/// least stand: [`QUAD_ABSOLUTE_TOLERANCE`] + [`QUAD_RELATIVE_TOLERANCE`] × the longer
/// diagonal.
///
/// Why: the 1990 code printed coordinates with `%f`, six decimals, so each coordinate of a
/// truly planar facet may be off by 5 × 10⁻⁷ file units and each vertex by √3 × 5 × 10⁻⁷
/// ≈ 8.7 × 10⁻⁷. The diagonals of a convex facet cross inside both, and moving their ends
/// by at most that moves each diagonal, at the crossing, by at most as much: rounding can
/// open a gap of at most 2 × 8.7 × 10⁻⁷ ≈ 1.73 × 10⁻⁶ between them, whatever the facet's
/// size, which the absolute 2 × 10⁻⁶ covers. A tolerance relative to the facet alone would
/// not: a 10 m facet written in km has a 0.014 km diagonal, and 10⁻⁶ of it is 1.4 × 10⁻⁸,
/// below the rounding. The relative part covers coordinates that went through single
/// precision (about 6 × 10⁻⁸ of their size) before they were printed. Both are far below
/// a meant bend: 2 × 10⁻⁶ km is 2 mm.
#[must_use]
pub fn quad_tolerance(longer_diagonal: f64) -> f64 {
    QUAD_ABSOLUTE_TOLERANCE + QUAD_RELATIVE_TOLERANCE * longer_diagonal
}

/// What is wrong with the shape of a 4-vertex facet.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum QuadDefect {
    /// The diagonals v1–v3 and v2–v4 are parallel, so the facet has no area: its vertices
    /// lie in a line, one repeats, or it is a symmetric bow-tie.
    NoArea,
    /// A coordinate difference is so large that the facet's normal overflows an `f64`.
    Overflow,
    /// The diagonals pass `gap` apart (file units), more than `tolerance`: the facet is
    /// bent, its fourth vertex off the plane of the other three.
    Bent {
        /// The distance between the lines of the two diagonals.
        gap: f64,
        /// [`quad_tolerance`] of the facet.
        tolerance: f64,
    },
    /// The corner at the error's vertex stands `height` (file units) out from the
    /// diagonal that cuts it off, on the side the facet's normal turns to; negative when
    /// it lies inside (a dart, or a bow-tie). It must stand out by more than `tolerance`,
    /// so a corner in a line with its neighbours is refused too.
    NotConvex {
        /// The corner's signed distance from the diagonal joining its neighbours.
        height: f64,
        /// [`quad_tolerance`] of the facet.
        tolerance: f64,
    },
}

/// A 4-vertex facet that is not planar and convex: which vertex (1 to 4, file order) the
/// defect is pointed at (the fourth for a facet bent or without area, the corner for one
/// that is not convex), and the defect with what was measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadError {
    /// The vertex, 1 to 4, in file order.
    pub vertex: usize,
    /// What is wrong.
    pub defect: QuadDefect,
}

impl std::fmt::Display for QuadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.defect {
            QuadDefect::NoArea => write!(
                f,
                "expected a 4-vertex facet with an area, found its diagonals v1–v3 and v2–v4 \
                 parallel (vertices in a line, a repeated vertex, or a bow-tie)"
            ),
            QuadDefect::Overflow => write!(
                f,
                "expected a 4-vertex facet whose normal an f64 can hold, found coordinates so \
                 far apart that it overflows"
            ),
            QuadDefect::Bent { gap, tolerance } => write!(
                f,
                "expected a planar 4-vertex facet, its diagonals v1–v3 and v2–v4 meeting within \
                 {tolerance:.3e}, found them {gap:.3e} apart: vertex 4 is off the plane of the \
                 other three"
            ),
            QuadDefect::NotConvex { height, tolerance } => {
                write!(
                    f,
                    "expected a convex 4-vertex facet, each corner more than {tolerance:.3e} out \
                     from the diagonal that cuts it off, found the corner at vertex {} ",
                    self.vertex
                )?;
                if height < 0.0 {
                    write!(f, "{:.3e} inside it (a dart or a bow-tie)", -height)
                } else {
                    write!(f, "{height:.3e} out (in a line with its neighbours)")
                }
            }
        }
    }
}

impl std::error::Error for QuadError {}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// A facet's triangles as corners (0-based, file order) of its vertices.
const TRIANGLE: &[[usize; 3]] = &[[0, 1, 2]];
/// A 4-vertex facet split along v1–v3: (v1, v2, v3) and (v1, v3, v4).
const ALONG_V1_V3: &[[usize; 3]] = &[[0, 1, 2], [0, 2, 3]];
/// A 4-vertex facet split along v2–v4: (v1, v2, v4) and (v2, v3, v4).
const ALONG_V2_V4: &[[usize; 3]] = &[[0, 1, 3], [1, 2, 3]];

impl LegacyFacet {
    /// The facet's vertices in file order: three, or four for a 4-vertex facet.
    pub fn corners(&self) -> impl Iterator<Item = [f64; 3]> + '_ {
        self.vertices.iter().copied().chain(self.fourth_vertex)
    }

    /// The facet's triangles, as 0-based indices into [`LegacyFacet::corners`]: `[0, 1,
    /// 2]` for a triangle; for a 4-vertex facet two triangles split along its shorter
    /// diagonal, `[0, 1, 2], [0, 2, 3]` along v1–v3 (also on a tie, a rectangle) or `[0, 1,
    /// 3], [1, 2, 3]` along v2–v4. Both keep the facet's winding, so both have the normal
    /// `(v2 − v1) × (v3 − v1)` of the 1990 rule. For a planar convex facet both cuts
    /// cover it exactly; the two splits share the facet's four edges and differ only in
    /// the new one, so the shorter diagonal is the split whose longest edge is shortest
    /// (no sliver along the long diagonal). The choice depends only on the vertices, so a
    /// file always splits the same way.
    #[must_use]
    pub fn triangles(&self) -> &'static [[usize; 3]] {
        let Some(v4) = self.fourth_vertex else {
            return TRIANGLE;
        };
        let [v1, v2, v3] = self.vertices;
        let d13 = sub(v3, v1);
        let d24 = sub(v4, v2);
        if dot(d13, d13) <= dot(d24, d24) {
            ALONG_V1_V3
        } else {
            ALONG_V2_V4
        }
    }

    /// Checks a 4-vertex facet: it has an area, it is planar (its two diagonals pass within
    /// [`quad_tolerance`] of each other) and convex (every corner stands out more than the
    /// tolerance from the diagonal that cuts it off, on the side of the normal `(v3 − v1)
    /// × (v4 − v2)`, which for a convex facet points the way of the 1990 normal `(v2 − v1)
    /// × (v3 − v1)`). A bow-tie is not convex. A triangle passes: its shape is the model's
    /// to check.
    ///
    /// The planarity measure is the gap between the diagonals rather than the fourth
    /// vertex's distance from the plane of the other three: that plane is ill-defined when
    /// v2 lies near the diagonal v1–v3, and rounding the file's coordinates can tilt it
    /// far, while it moves the diagonals of a convex facet by no more than the vertices
    /// move (see [`quad_tolerance`]).
    ///
    /// # Errors
    /// A [`QuadError`] naming the vertex to point at and what was measured.
    pub fn check_quad(&self) -> Result<(), QuadError> {
        let Some(v4) = self.fourth_vertex else {
            return Ok(());
        };
        let [v1, v2, v3] = self.vertices;
        let v = [v1, v2, v3, v4];
        let d13 = sub(v3, v1);
        let d24 = sub(v4, v2);
        let normal = cross(d13, d24);
        let area2 = norm(normal);
        let longer = norm(d13).max(norm(d24));
        let fail = |vertex, defect| Err(QuadError { vertex, defect });
        let edges_finite = (0..4).all(|k| norm(sub(v[(k + 1) % 4], v[k])).is_finite());
        if !(edges_finite && area2.is_finite() && longer.is_finite()) {
            return fail(4, QuadDefect::Overflow);
        }
        if area2 <= 0.0 {
            return fail(4, QuadDefect::NoArea);
        }
        let unit = normal.map(|c| c / area2);
        let tolerance = quad_tolerance(longer);
        // The distance between the lines v1 + s (v3 − v1) and v2 + t (v4 − v2).
        let gap = dot(sub(v2, v1), unit).abs();
        if gap.is_nan() {
            return fail(4, QuadDefect::Overflow);
        }
        if gap > tolerance {
            return fail(4, QuadDefect::Bent { gap, tolerance });
        }
        for k in 0..4 {
            let (before, at, after) = (v[(k + 3) % 4], v[k], v[(k + 1) % 4]);
            let turn = cross(sub(at, before), sub(after, at));
            // Twice the area of (before, at, after) over its base: the corner's height.
            let height = dot(turn, unit) / norm(sub(after, before));
            if height.is_nan() {
                return fail(k + 1, QuadDefect::Overflow);
            }
            if height <= tolerance {
                return fail(k + 1, QuadDefect::NotConvex { height, tolerance });
            }
        }
        Ok(())
    }
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
/// line without exactly three finite numbers, a 4-vertex facet that is not planar and
/// convex ([`LegacyFacet::check_quad`], at the vertex line it names), fewer facets than
/// declared (truncated file) or data after the declared facets.
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
    // The line read after a facet's third vertex when it was not a fourth vertex: the
    // next facet's material line (or data past the last facet).
    let mut pending: Option<Line<'_>> = None;
    for i in 0..count {
        let ordinal = i + 1;
        let index_line = match pending.take().or_else(|| lines.next_line()) {
            Some(line) => line,
            None => {
                return Err(lines.eof_error(&format!(
                    "expected facet {ordinal} of the {count} declared on line {}, found end of file",
                    count_position.line
                )));
            }
        };
        let (material_index, temperature_k) = material_line(&lines, index_line)?;
        let mut vertices = [[0.0; 3]; 3];
        let mut spans = [index_line.span; 4];
        for (k, vertex) in vertices.iter_mut().enumerate() {
            let what = format!("x y z of vertex {} of facet {ordinal}", k + 1);
            let line = lines.expect_line(&what)?;
            *vertex = lines.reals::<3>(line, &what)?.0;
            spans[k] = line.span;
        }
        let mut fourth_vertex = None;
        match lines.next_line() {
            Some(line) if !starts_a_facet(line) => {
                let what = format!("x y z of vertex 4 of facet {ordinal}");
                fourth_vertex = Some(lines.reals::<3>(line, &what)?.0);
                spans[3] = line.span;
            }
            next => pending = next,
        }
        let facet = LegacyFacet {
            material_index,
            temperature_k,
            vertices,
            fourth_vertex,
            position: position(index_line.span),
        };
        if let Err(e) = facet.check_quad() {
            let at = spans[e.vertex.saturating_sub(1).min(3)];
            return Err(lines.error(
                at,
                format!("facet {ordinal} (from line {}): {e}", facet.position.line),
            ));
        }
        facets.push(facet);
    }
    if let Some(extra) = pending.or_else(|| lines.next_line()) {
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

/// Whether a line read after a facet's third vertex begins the next facet (or is data past
/// the last one) rather than being a fourth vertex: a material line holds one or two
/// tokens, the first a whole number. Anything else there is read as a fourth vertex, so
/// that one cut short is an error at its own line.
fn starts_a_facet(line: Line<'_>) -> bool {
    let mut tokens = Lines::tokens(line);
    let whole = tokens
        .next()
        .is_some_and(|t| t.fragment().bytes().all(|b| b.is_ascii_digit()));
    whole && tokens.nth(1).is_none()
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
/// by a blank line), with reals in their shortest exact form. A 4-vertex facet is written
/// as four vertex lines (the irsig extension), so that it reads back as the same facet.
///
/// # Errors
/// A [`WriteError`] for an object without facets, a material index of 0, a non-finite
/// coordinate, a temperature that is not a finite value above 0 K, or a 4-vertex facet
/// that [`parse`] would refuse ([`LegacyFacet::check_quad`]).
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
        check_finite(record, f.fourth_vertex.as_slice().as_flattened())?;
        if let Err(e) = f.check_quad() {
            return Err(WriteError::new(
                record(),
                WriteErrorKind::OutOfRange(e.to_string()),
            ));
        }
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
        for [x, y, z] in f.corners() {
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

    /// The triangles a facet splits into, as vertex triples.
    fn halves(f: &LegacyFacet) -> Vec<[[f64; 3]; 3]> {
        let corners: Vec<[f64; 3]> = f.corners().collect();
        f.triangles()
            .iter()
            .map(|t| t.map(|k| corners[k]))
            .collect()
    }

    /// `(b − a) × (c − a)`, the 1990 rule: twice the area, along the normal.
    fn normal([a, b, c]: [[f64; 3]; 3]) -> [f64; 3] {
        cross(sub(b, a), sub(c, a))
    }

    fn normals(h: &[[[f64; 3]; 3]]) -> Vec<[f64; 3]> {
        h.iter().copied().map(normal).collect()
    }

    fn one(text: &str) -> LegacyFacet {
        let mut obj = parse("quad.fac", text).unwrap();
        assert_eq!(obj.facets.len(), 1);
        obj.facets.remove(0)
    }

    #[test]
    fn a_unit_square_splits_along_v1_v3_in_both_windings() {
        // Counter-clockwise seen from +z: the 1990 normal (v2 − v1) × (v3 − v1) is +z.
        let ccw = one("1\n1\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n");
        assert_eq!(
            ccw.vertices,
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]
        );
        assert_eq!(ccw.fourth_vertex, Some([0.0, 1.0, 0.0]));
        // Equal diagonals (√2 each): the tie goes to v1–v3.
        assert_eq!(ccw.triangles(), [[0, 1, 2], [0, 2, 3]]);
        assert_eq!(
            halves(&ccw),
            [
                [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
                [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            ]
        );
        // Each half: normal +z, area 1/2 (|normal| = 1); together the square's area 1.
        for t in halves(&ccw) {
            assert_eq!(normal(t), [0.0, 0.0, 1.0]);
        }
        // Clockwise: the same square, normal −z, and so are both halves.
        let cw = one("1\n1\n0 0 0\n0 1 0\n1 1 0\n1 0 0\n");
        assert_eq!(cw.triangles(), [[0, 1, 2], [0, 2, 3]]);
        for t in halves(&cw) {
            assert_eq!(normal(t), [0.0, 0.0, -1.0]);
        }
    }

    #[test]
    fn a_trapezoid_splits_along_its_shorter_diagonal() {
        // The right trapezoid (0,0) (4,0) (2,1) (0,1): parallel sides 4 and 2, height 1,
        // area (4 + 2) / 2 × 1 = 3. Diagonals v1–v3 = (2, 1), |·|² = 5, and v2–v4 =
        // (−4, 1), |·|² = 17: cut along v1–v3 into (v1 v2 v3), area 4 × 1 / 2 = 2, and
        // (v1 v3 v4), area 2 × 1 / 2 = 1.
        let a = one("1\n1\n0 0 0\n4 0 0\n2 1 0\n0 1 0\n");
        assert_eq!(a.triangles(), [[0, 1, 2], [0, 2, 3]]);
        let h = halves(&a);
        assert_eq!(h[0], [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0], [2.0, 1.0, 0.0]]);
        assert_eq!(h[1], [[0.0, 0.0, 0.0], [2.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
        assert_eq!(normals(&h), [[0.0, 0.0, 4.0], [0.0, 0.0, 2.0]]);
        // The same trapezoid from (4,0): now v1–v3 = (−4, 1) is the longer diagonal and
        // the cut is v2–v4 = (−2, −1): (v1 v2 v4) = (4,0) (2,1) (0,0), area 2, and
        // (v2 v3 v4) = (2,1) (0,1) (0,0), area 1; normals +z like the quad's.
        let b = one("1\n1\n4 0 0\n2 1 0\n0 1 0\n0 0 0\n");
        assert_eq!(b.triangles(), [[0, 1, 3], [1, 2, 3]]);
        let h = halves(&b);
        assert_eq!(h[0], [[4.0, 0.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 0.0]]);
        assert_eq!(h[1], [[2.0, 1.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 0.0]]);
        assert_eq!(normals(&h), [[0.0, 0.0, 4.0], [0.0, 0.0, 2.0]]);
        // Wound the other way (from (0,0) going to (0,1) first): v1–v3 = (2, 1) is
        // shorter again; both halves have normal −z, areas 1 and 2.
        let c = one("1\n1\n0 0 0\n0 1 0\n2 1 0\n4 0 0\n");
        assert_eq!(c.triangles(), [[0, 1, 2], [0, 2, 3]]);
        assert_eq!(normals(&halves(&c)), [[0.0, 0.0, -2.0], [0.0, 0.0, -4.0]]);
    }

    #[test]
    fn a_tilted_quad_keeps_its_normal_in_both_halves() {
        // A rectangle in the plane z = x, tilted 45° about y, sides (2, 0, 2) and
        // (0, 1, 0): area 2√2 × 1. The 1990 normal (v2 − v1) × (v3 − v1) = (2, 0, 2) ×
        // (2, 1, 2) = (−2, 0, 2), of length 2√2, twice the area of a half. Diagonals
        // equal: cut along v1–v3; the other half, (2, 1, 2) × (0, 1, 0), is (−2, 0, 2) too.
        let f = one("1\n1\n0 0 0\n2 0 2\n2 1 2\n0 1 0\n");
        let h = halves(&f);
        assert_eq!(normals(&h), [[-2.0, 0.0, 2.0], [-2.0, 0.0, 2.0]]);
        let area: f64 = h.iter().map(|&t| norm(normal(t)) / 2.0).sum();
        assert!((area - 2.0 * 2f64.sqrt()).abs() < 1e-15, "{area}");
    }

    fn refusal(text: &str) -> ParseError {
        parse("quad.fac", text).unwrap_err()
    }

    #[test]
    fn a_bent_quad_is_refused_at_its_fourth_vertex() {
        // The unit square with v4 lifted 0.01: the diagonals (1, 1, 0) from the origin
        // and (−1, 1, 0.01) from (1, 0, 0) pass 0.01 / |(0.01, −0.01, 2)| = 0.01 /
        // 2.00005 ≈ 5.000e-3 apart; tolerance 2e-6 + 1e-6 × √2.0001 ≈ 3.414e-6.
        let e = refusal("1\n1\n0 0 0\n1 0 0\n1 1 0\n0 1 0.01\n");
        assert_eq!((e.line, e.column), (6, 1), "{e}");
        for part in [
            "facet 1 (from line 2)",
            "planar",
            "within 3.414e-6",
            "5.000e-3 apart",
        ] {
            assert!(e.message.contains(part), "{part}: {e}");
        }
        let mut f = one("1\n1\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n");
        f.fourth_vertex = Some([0.0, 1.0, 0.01]);
        let Err(QuadError {
            vertex: 4,
            defect: QuadDefect::Bent { gap, tolerance },
        }) = f.check_quad()
        else {
            panic!("{:?}", f.check_quad());
        };
        assert!((gap - 0.01 / 4.0002f64.sqrt()).abs() < 1e-16, "{gap}");
        assert!((tolerance - (2e-6 + 1e-6 * 2.0001f64.sqrt())).abs() < 1e-20);
    }

    /// A 10 m × 10 m square in km (six decimals, as the 1990 code printed), in the plane
    /// z = (x + y) / 3: v2 and v4 have z = 0.00333333…, printed 0.003333, and v3
    /// 0.00666666…, printed 0.006667.
    const ROUNDED: &str = "1\n1\n0.000000 0.000000 0.000000\n0.010000 0.000000 0.003333\n\
        0.010000 0.010000 0.006667\n0.000000 0.010000 0.003333\n";

    #[test]
    fn a_quad_rounded_to_six_decimals_is_accepted() {
        let f = one(ROUNDED);
        // By hand: the diagonals cross above (0.005, 0.005), v1–v3 at z = 0.0033335 and
        // v2–v4 at 0.003333, 5e-7 apart vertically; along the normal (d13 × d24 =
        // (−6.667e-5, −6.667e-5, 2e-4), z share 2e-4 / 2.2111e-4 = 0.9045) that is a gap
        // of 4.52e-7. Under the 2e-6 absolute tolerance, but 29 times the 1e-6 of the
        // diagonal (0.0156 km) a relative tolerance alone would allow.
        let [v1, v2, v3] = f.vertices;
        let v4 = f.fourth_vertex.unwrap();
        let n = cross(sub(v3, v1), sub(v4, v2));
        let gap = dot(sub(v2, v1), n).abs() / norm(n);
        assert!((gap - 4.5226e-7).abs() < 1e-11, "{gap}");
        let longer = norm(sub(v3, v1)).max(norm(sub(v4, v2)));
        assert!(gap > QUAD_RELATIVE_TOLERANCE * longer * 28.0);
        assert!(gap < quad_tolerance(longer));
        // The same square with v4 1e-5 km (1 cm) higher is bent: a gap of 4.07e-6.
        let e =
            refusal(&ROUNDED.replace("0.000000 0.010000 0.003333", "0.000000 0.010000 0.003343"));
        assert_eq!((e.line, e.column), (6, 1), "{e}");
        assert!(e.message.contains("4.070e-6 apart"), "{e}");
    }

    #[test]
    fn a_dart_is_refused_at_its_reflex_corner() {
        // (0,0) (3,1) (0,2) (1,1): the corner at (1,1) points inward. The facet's normal
        // d13 × d24 = (0, 2, 0) × (−2, 0, 0) = +z·4; the corner's turn (1,1)→(0,0) after
        // (0,2)→(1,1) is (1, −1) × (−1, −1) = −2, over the base |v1 − v3| = 2: 1 inside.
        let e = refusal("1\n1\n0 0 0\n3 1 0\n0 2 0\n1 1 0\n");
        assert_eq!((e.line, e.column), (6, 1), "{e}");
        assert!(
            e.message.contains("convex") && e.message.contains("vertex 4 1.000e0 inside"),
            "{e}"
        );
        // The same dart from (0,2): the reflex corner is vertex 2, on line 4.
        let e = refusal("1\n1\n0 2 0\n1 1 0\n0 0 0\n3 1 0\n");
        assert_eq!((e.line, e.column), (4, 1), "{e}");
        assert!(e.message.contains("vertex 2 1.000e0 inside"), "{e}");
    }

    #[test]
    fn bow_ties_and_flat_corners_are_refused() {
        // A symmetric bow-tie (0,0) (1,1) (1,0) (0,1): its diagonals (1,0) and (−1,0) are
        // parallel, so it has no area.
        let e = refusal("1\n1\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n");
        assert_eq!((e.line, e.column), (6, 1), "{e}");
        assert!(e.message.contains("parallel"), "{e}");
        // An uneven one, (0,0) (2,1) (2,0) (0,2): edges v1–v2 and v3–v4 cross at
        // (4/3, 2/3). Normal (2,0,0) × (−2,1,0) = +z·2; at vertex 2 the turn is (2,1) ×
        // (0,−1) = −2 over the base |v3 − v1| = 2: 1 inside.
        let e = refusal("1\n1\n0 0 0\n2 1 0\n2 0 0\n0 2 0\n");
        assert_eq!((e.line, e.column), (4, 1), "{e}");
        assert!(e.message.contains("vertex 2 1.000e0 inside"), "{e}");
        // (0,0) (1,0) (2,0) (1,1): vertex 2 lies on v1–v3, a triangle written as four.
        let e = refusal("1\n1\n0 0 0\n1 0 0\n2 0 0\n1 1 0\n");
        assert_eq!((e.line, e.column), (4, 1), "{e}");
        assert!(e.message.contains("vertex 2 0.000e0 out (in a line"), "{e}");
        // A repeated vertex.
        let e = refusal("1\n1\n0 0 0\n1 0 0\n1 1 0\n1 0 0\n");
        assert!(e.message.contains("parallel"), "{e}");
        // Coordinates whose differences overflow.
        let e = refusal("1\n1\n-1e308 0 0\n1e308 0 0\n1 1 0\n0 1 0\n");
        assert!(e.message.contains("overflows"), "{e}");
    }

    #[test]
    fn a_fourth_vertex_line_cut_short_is_an_error_at_its_line() {
        // Two numbers with decimals cannot start a facet: a fourth vertex missing its z.
        let e = refusal("2\n1\n0 0 0\n1 0 0\n1 1 0\n1.000000 0.000000\n1\n0 0 0\n1 0 0\n0 1 0\n");
        assert_eq!((e.line, e.column), (6, 1), "{e}");
        assert!(
            e.message.contains("vertex 4 of facet 1") && e.message.contains("found 2"),
            "{e}"
        );
        let e = refusal("1\n1\n0 0 0\n1 0 0\n1 1 0\n0.5\n");
        assert!(e.message.contains("found 1"), "{e}");
        let e = refusal("1\n1\n0 0 0\n1 0 0\n1 1 0\n0 x 0\n");
        assert_eq!((e.line, e.column), (6, 3), "{e}");
        let e = refusal("1\n1\n0 0 0\n1 0 0\n1 1 0\n0 1 0 7\n");
        assert_eq!((e.line, e.column), (6, 7), "{e}");
        // Two whole numbers are a material line and a temperature: with one facet
        // declared they are data past its end.
        let e = refusal("1\n1\n0 0 0\n1 0 0\n1 1 0\n1 1\n");
        assert_eq!((e.line, e.column), (6, 1), "{e}");
        assert!(e.message.contains("expected end of file"), "{e}");
    }

    #[test]
    fn triangles_and_quads_mix_and_a_quad_counts_as_one_facet() {
        let text = "3\n\n6\n0 0 0\n1 0 0\n0 1 0\n\n7 300.5\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n\
            \n6\n0 0 2\n1 0 2\n0 1 2\n";
        let obj = parse("mixed.fac", text).unwrap();
        assert_eq!(obj.facets.len(), 3);
        assert_eq!(obj.facets[0].fourth_vertex, None);
        assert_eq!(obj.facets[1].fourth_vertex, Some([0.0, 1.0, 1.0]));
        assert_eq!(obj.facets[1].temperature_k, Some(300.5));
        assert_eq!(obj.facets[2].fourth_vertex, None);
        assert_eq!(obj.facets[1].position, Position { line: 8, column: 1 });
        assert_eq!(
            obj.facets[2].position,
            Position {
                line: 14,
                column: 1
            }
        );
        // Counted as two facets each, the same file is short of one.
        let e = refusal(&text.replacen('3', "4", 1));
        assert!(e.message.contains("facet 4 of the 4"), "{e}");
        // A quad alone is one facet.
        let e = refusal("2\n1\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n");
        assert!(e.message.contains("facet 2 of the 2"), "{e}");
    }

    #[test]
    fn quads_write_back_as_four_vertex_lines() {
        let text = "2\n6 300.5\n0 0 0\n4 0 0\n2 1 0\n0 1 0\n6\n0 0 1\n1 0 1\n0 1 1\n";
        let obj = parse("t", text).unwrap();
        let written = write(&obj).unwrap();
        assert_eq!(
            written,
            "2\n\n6 300.5\n0.0 0.0 0.0\n4.0 0.0 0.0\n2.0 1.0 0.0\n0.0 1.0 0.0\n\n\
             6\n0.0 0.0 1.0\n1.0 0.0 1.0\n0.0 1.0 1.0\n\n"
        );
        let back = parse("t", &written).unwrap();
        for (a, b) in obj.facets.iter().zip(&back.facets) {
            assert_eq!((a.vertices, a.fourth_vertex), (b.vertices, b.fourth_vertex));
            assert_eq!(
                (a.material_index, a.temperature_k),
                (b.material_index, b.temperature_k)
            );
        }
        // A facet the parser would refuse is not written either.
        let mut bent = obj;
        bent.facets[0].fourth_vertex = Some([0.0, 1.0, 0.5]);
        let e = write(&bent).unwrap_err();
        assert_eq!(e.record, "facet 1");
        assert!(
            matches!(&e.kind, WriteErrorKind::OutOfRange(m) if m.contains("planar")),
            "{e}"
        );
        bent.facets[0].fourth_vertex = Some([0.0, f64::NAN, 0.0]);
        assert_eq!(write(&bent).unwrap_err().kind, WriteErrorKind::NotFinite);
    }

    #[test]
    fn a_quad_becomes_two_triangles_in_the_mesh_at_its_line() {
        let text = "3\n6\n0 0 0\n1 0 0\n0 1 0\n7 300.5\n0 0 1\n4 0 1\n2 1 1\n0 1 1\n6\n0 0 2\n1 0 2\n0 1 2\n";
        let mesh = crate::mesh::read_legacy_object("m.fac", text.as_bytes()).unwrap();
        // 3 + 4 + 3 vertices; 1 + 2 + 1 triangles.
        assert_eq!(mesh.positions.len(), 10);
        let tris: Vec<[u32; 3]> = mesh.triangles.iter().map(|t| t.vertices).collect();
        assert_eq!(tris, [[0, 1, 2], [3, 4, 5], [3, 5, 6], [7, 8, 9]]);
        assert_eq!(mesh.positions[6], [0.0, 1.0, 1.0]);
        for t in &mesh.triangles[1..3] {
            assert_eq!(t.temperature_k, Some(300.5));
            assert_eq!(mesh.material_name(1), mesh.material_name(2));
        }
        assert_eq!(mesh.material_name(1), Some("material index 7"));
        assert_eq!(mesh.triangles[3].temperature_k, None);
        let at = |i| mesh.triangle_location(i).to_string();
        assert_eq!(
            [at(0), at(1), at(2), at(3)],
            ["m.fac:2:1", "m.fac:6:1", "m.fac:6:1", "m.fac:11:1"]
        );
        assert_eq!(mesh.locate("facets[2].vertices"), "m.fac:6:1");
        // An ObjectFile built in code with a bent quad is refused at the facet's line.
        let mut obj = parse("m.fac", text).unwrap();
        obj.facets[1].fourth_vertex = Some([0.0, 1.0, 3.0]);
        let e = crate::mesh::from_legacy_object("m.fac", &obj).unwrap_err();
        assert_eq!((e.line, e.column), (6, 1), "{e}");
        assert!(e.message.contains("facet 2 (vertex 4)"), "{e}");
    }
}
