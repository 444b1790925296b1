//! `.dwr`: downwelled (sky) radiance seen from the ground (thesis §3.2.2, Figure 9;
//! Appendix H `dwr_type dwr[20]`).
//!
//! ```text
//! 0 1.166214e-03      zenith angle in degrees, sky radiance in W cm^-2 sr^-1
//! 5 1.168348e-03
//! ...
//! 90 4.394162e-03
//! -1 1.513059e-03     optional, last: the hemispheric (cosine-weighted) mean L_d (eq. 5)
//! ```
//!
//! Angular rows: zenith angle 0–90° strictly increasing (5° steps in the thesis, any steps
//! here), radiance 0 or more, in the legacy unit W cm⁻² sr⁻¹. The 1990 program kept the
//! hemispherically integrated L_d used for diffuse facets in the same array, after the 19
//! angular values (`dwr[19].dwrad`); in the file it is a row whose angle is `-1`, which
//! may appear once, as the last row. The 1990 program held 20 rows.

use std::fmt::Write as _;

use super::lex::Lines;
use super::table::{RawRow, Violation, at_token, in_range, increasing, non_negative, read_rows};
use super::{Position, WriteError, WriteErrorKind, check_finite, real};
use crate::ParseError;

/// One angular row of a `.dwr` table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DwrRow {
    /// Zenith angle of the line of sight from the ground, degrees, 0 to 90.
    pub zenith_deg: f64,
    /// Sky radiance along it, W cm⁻² sr⁻¹.
    pub radiance_w_cm2_sr: f64,
    /// Where the row is.
    pub position: Position,
}

/// A parsed `.dwr` table.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DwrTable {
    /// The angular rows, zenith angles strictly increasing.
    pub rows: Vec<DwrRow>,
    /// The `-1` row: hemispheric (cosine-weighted) mean sky radiance, W cm⁻² sr⁻¹, the
    /// radiance a Lambertian facet with sky-view factor 1 reflects per unit reflectance.
    pub hemispheric_w_cm2_sr: Option<f64>,
    /// Where the `-1` row is, if present.
    pub hemispheric_position: Option<Position>,
}

impl DwrTable {
    /// The angular rows as `(zenith_deg, radiance_w_cm2_sr)` pairs.
    #[must_use]
    pub fn to_pairs(&self) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .map(|r| (r.zenith_deg, r.radiance_w_cm2_sr))
            .collect()
    }
}

const COLUMNS: &str = "zenith angle in degrees and radiance in W cm^-2 sr^-1";
const HEMI_MARK: f64 = -1.0;

fn check(rows: &[[f64; 2]]) -> Result<(), Violation> {
    for (i, r) in rows.iter().enumerate() {
        in_range(
            i,
            0,
            r[0],
            0.0,
            90.0,
            "a zenith angle in degrees (or -1 for the hemispheric row, last)",
        )?;
        non_negative(i, 1, r[1], "a radiance")?;
    }
    increasing(rows, 0, "the zenith angle")
}

/// Reads a `.dwr` table.
///
/// # Errors
/// A [`ParseError`] for an empty file, a row without exactly two finite numbers, a zenith
/// angle outside 0–90° or not above the one before, a negative radiance, a `-1` row that
/// is not the last, or no angular row at all.
pub fn parse(file: &str, text: &str) -> Result<DwrTable, ParseError> {
    let mut lines = Lines::new(file, text);
    let mut raw: Vec<RawRow<'_, 2>> = read_rows(&mut lines, COLUMNS)?;
    let mut hemispheric = None;
    #[allow(clippy::float_cmp)] // `-1` is a marker written as a literal, not a computed value
    if raw.last().is_some_and(|r| r.values[0] == HEMI_MARK) {
        hemispheric = raw.pop();
    }
    if let Some(h) = hemispheric {
        if h.values[1] < 0.0 {
            return Err(lines.error(
                h.spans[1],
                format!(
                    "expected a hemispheric radiance of 0 or more, found {}",
                    h.values[1]
                ),
            ));
        }
        if raw.is_empty() {
            return Err(lines.error(
                h.spans[0],
                "expected angular rows before the `-1` hemispheric row, found none",
            ));
        }
    }
    #[allow(clippy::float_cmp)]
    if let Some(early) = raw.iter().find(|r| r.values[0] == HEMI_MARK) {
        return Err(lines.error(
            early.spans[0],
            "expected the `-1` hemispheric row to be the last row, found more rows after it",
        ));
    }
    let values: Vec<[f64; 2]> = raw.iter().map(|r| r.values).collect();
    check(&values).map_err(|v| at_token(&lines, &raw, v))?;
    Ok(DwrTable {
        rows: raw
            .iter()
            .map(|r| DwrRow {
                zenith_deg: r.values[0],
                radiance_w_cm2_sr: r.values[1],
                position: r.position,
            })
            .collect(),
        hemispheric_w_cm2_sr: hemispheric.map(|h| h.values[1]),
        hemispheric_position: hemispheric.map(|h| h.position),
    })
}

/// Writes a `.dwr` table: the angular rows, then `-1 L_d,hemi` when present.
///
/// # Errors
/// A [`WriteError`] for a table without angular rows or a value the parser would reject.
pub fn write(table: &DwrTable) -> Result<String, WriteError> {
    let rows: Vec<[f64; 2]> = table
        .rows
        .iter()
        .map(|r| [r.zenith_deg, r.radiance_w_cm2_sr])
        .collect();
    let mut out = super::table::write_rows(&rows, check)?;
    if let Some(h) = table.hemispheric_w_cm2_sr {
        check_finite(|| "hemispheric row".to_owned(), &[h])?;
        if h < 0.0 {
            return Err(WriteError::new(
                "hemispheric row",
                WriteErrorKind::OutOfRange(format!("radiance {h} is negative")),
            ));
        }
        let _ = writeln!(out, "-1 {}", real(h));
    }
    Ok(out)
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_hemispheric_row() {
        let t = parse("s.dwr", "0 1.1e-3\n90 4.3e-3\n-1 1.5e-3\n").unwrap();
        assert_eq!(t.to_pairs(), vec![(0.0, 1.1e-3), (90.0, 4.3e-3)]);
        assert_eq!(t.hemispheric_w_cm2_sr, Some(1.5e-3));
        assert_eq!(
            t.hemispheric_position,
            Some(Position { line: 3, column: 1 })
        );
        let t = parse("s.dwr", "0 1.1e-3\n90 4.3e-3\n").unwrap();
        assert_eq!(t.hemispheric_w_cm2_sr, None);
    }

    #[test]
    fn rejects_misplaced_marker_and_bad_values() {
        for (text, line, col, needle) in [
            ("0 1\n-1 2\n90 3\n", 2, 1, "last row"),
            ("0 1\n-1 2\n-1 3\n", 2, 1, "last row"),
            ("-1 2\n", 1, 1, "angular rows"),
            ("0 1\n-1 -2\n", 2, 4, "0 or more"),
            ("0 1\n-2 2\n", 2, 1, "-1 for the hemispheric"),
            ("0 1\n95 2\n", 2, 1, "from 0 to 90"),
            ("10 1\n5 2\n", 2, 1, "increase"),
            ("0 -1e-3\n", 1, 3, "0 or more"),
        ] {
            let e = parse("s.dwr", text).unwrap_err();
            assert_eq!((e.line, e.column), (line, col), "{text:?}: {e}");
            assert!(e.message.contains(needle), "{text:?}: {e}");
        }
    }
}
