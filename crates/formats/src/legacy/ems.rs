//! `.ems`: angular emissivity of one material (thesis §3.2.2, Figure 9; Appendix H
//! `emis_type`).
//!
//! ```text
//! 0 0.985191        angle from the surface normal in degrees, emissivity (0 to 1)
//! 5 0.985191
//! ...
//! 90 0.000000
//! ```
//!
//! One row per angle, angles from 0 to 90° strictly increasing ("typically 10°" steps in
//! the thesis, any steps here), emissivity 0 to 1. Linearly interpolated between rows and
//! assumed rotationally symmetric. The 1990 program held at most 10 angles per material
//! (`double angle[10]`); this parser has no limit.

use super::lex::Lines;
use super::table::{RawRow, Violation, at_token, in_range, increasing, read_rows, write_rows};
use super::{Position, WriteError};
use crate::ParseError;

/// One row of an `.ems` table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EmsRow {
    /// Angle between the view ray and the surface normal, degrees, 0 to 90.
    pub angle_deg: f64,
    /// Band emissivity at that angle, 0 to 1.
    pub emissivity: f64,
    /// Where the row is.
    pub position: Position,
}

/// A parsed `.ems` table.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EmsTable {
    /// The rows, angles strictly increasing.
    pub rows: Vec<EmsRow>,
}

impl EmsTable {
    /// The table as `(angle_deg, emissivity)` pairs, the form
    /// `irsig_model::Material::emissivity` takes.
    #[must_use]
    pub fn to_pairs(&self) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .map(|r| (r.angle_deg, r.emissivity))
            .collect()
    }

    /// A table from `(angle_deg, emissivity)` pairs, without positions (for writing).
    #[must_use]
    pub fn from_pairs(pairs: &[(f64, f64)]) -> Self {
        Self {
            rows: pairs
                .iter()
                .map(|&(angle_deg, emissivity)| EmsRow {
                    angle_deg,
                    emissivity,
                    position: Position::default(),
                })
                .collect(),
        }
    }
}

const COLUMNS: &str = "angle in degrees and emissivity";

fn check(rows: &[[f64; 2]]) -> Result<(), Violation> {
    for (i, &[angle, eps]) in rows.iter().enumerate() {
        in_range(i, 0, angle, 0.0, 90.0, "an angle in degrees")?;
        in_range(i, 1, eps, 0.0, 1.0, "an emissivity")?;
    }
    increasing(rows, 0, "the angle")
}

/// Reads an `.ems` table.
///
/// # Errors
/// A [`ParseError`] for an empty file, a row without exactly two finite numbers, an angle
/// outside 0–90° or not above the one before, or an emissivity outside 0–1.
pub fn parse(file: &str, text: &str) -> Result<EmsTable, ParseError> {
    let mut lines = Lines::new(file, text);
    let raw: Vec<RawRow<'_, 2>> = read_rows(&mut lines, COLUMNS)?;
    let values: Vec<[f64; 2]> = raw.iter().map(|r| r.values).collect();
    check(&values).map_err(|v| at_token(&lines, &raw, v))?;
    Ok(EmsTable {
        rows: raw
            .iter()
            .map(|r| EmsRow {
                angle_deg: r.values[0],
                emissivity: r.values[1],
                position: r.position,
            })
            .collect(),
    })
}

/// Writes an `.ems` table, one `angle emissivity` row per line.
///
/// # Errors
/// A [`WriteError`] for an empty table or a value the parser would reject.
pub fn write(table: &EmsTable) -> Result<String, WriteError> {
    let rows: Vec<[f64; 2]> = table
        .rows
        .iter()
        .map(|r| [r.angle_deg, r.emissivity])
        .collect();
    write_rows(&rows, check)
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn reads_rows_and_converts_to_pairs() {
        let t = parse("w.ems", "0 0.98\n45\t0.97\r\n90 0\n").unwrap();
        assert_eq!(t.to_pairs(), vec![(0.0, 0.98), (45.0, 0.97), (90.0, 0.0)]);
        assert_eq!(t.rows[1].position, Position { line: 2, column: 1 });
        assert_eq!(
            parse("w", &write(&t).unwrap()).unwrap().to_pairs(),
            t.to_pairs()
        );
    }

    #[test]
    fn rejects_out_of_range_and_disorder_at_the_value() {
        for (text, line, col, needle) in [
            ("0 0.9\n10 1.2\n", 2, 4, "emissivity from 0 to 1"),
            ("0 0.9\n10 -0.1\n", 2, 4, "emissivity from 0 to 1"),
            ("0 0.9\n95 0.5\n", 2, 1, "angle in degrees from 0 to 90"),
            ("-5 0.9\n", 1, 1, "angle in degrees"),
            ("0 0.9\n10 0.8\n10 0.7\n", 3, 1, "increase"),
            ("0 0.9\n20 0.8\n10 0.7\n", 3, 1, "increase"),
            ("0 nan\n", 1, 3, "finite"),
            ("0\n", 1, 1, "found 1"),
            ("", 1, 1, "at least one row"),
        ] {
            let e = parse("m.ems", text).unwrap_err();
            assert_eq!((e.line, e.column), (line, col), "{text:?}: {e}");
            assert!(e.message.contains(needle), "{text:?}: {e}");
        }
    }

    #[test]
    fn writer_rejects_what_the_parser_would() {
        assert!(write(&EmsTable::from_pairs(&[(0.0, 1.5)])).is_err());
        assert!(write(&EmsTable::from_pairs(&[(10.0, 0.5), (5.0, 0.5)])).is_err());
        assert!(write(&EmsTable::default()).is_err());
        assert!(write(&EmsTable::from_pairs(&[(0.0, f64::NAN)])).is_err());
    }
}
