//! `.rtt`: band radiance of a blackbody by temperature (thesis §3.2.2, Figure 9; Appendix H
//! `planck_type`), the 1990 program's Planck lookup table.
//!
//! ```text
//! 300 4.35e-03      temperature in K, band radiance in W cm^-2 sr^-1
//! ```
//!
//! Temperatures strictly increase and are above 0 K; radiances are 0 or more and never
//! decrease (Planck's law is monotonic, and the inverse lookup needs it). The unit of the
//! radiance column follows thesis Figure 9 (W cm⁻² sr⁻¹); the thesis text says W m⁻² sr⁻¹,
//! so a file from elsewhere may differ by 1e4: the converter must be told. The 1990
//! program held at most 200 rows.

use super::lex::Lines;
use super::table::{
    RawRow, Violation, at_token, increasing, non_negative, positive, read_rows, write_rows,
};
use super::{Position, WriteError};
use crate::ParseError;

/// One row of an `.rtt` table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RttRow {
    /// Blackbody temperature, K.
    pub temperature_k: f64,
    /// Its band radiance, W cm⁻² sr⁻¹ (see the module notes on the unit).
    pub radiance_w_cm2_sr: f64,
    /// Where the row is.
    pub position: Position,
}

/// A parsed `.rtt` table.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RttTable {
    /// The rows, temperatures strictly increasing.
    pub rows: Vec<RttRow>,
}

impl RttTable {
    /// The table as `(temperature_k, radiance_w_cm2_sr)` pairs.
    #[must_use]
    pub fn to_pairs(&self) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .map(|r| (r.temperature_k, r.radiance_w_cm2_sr))
            .collect()
    }
}

const COLUMNS: &str = "temperature in K and radiance in W cm^-2 sr^-1";

fn check(rows: &[[f64; 2]]) -> Result<(), Violation> {
    for (i, r) in rows.iter().enumerate() {
        positive(i, 0, r[0], "a temperature in K")?;
        non_negative(i, 1, r[1], "a radiance")?;
    }
    increasing(rows, 0, "the temperature")?;
    for (i, pair) in rows.windows(2).enumerate() {
        if pair[1][1] < pair[0][1] {
            return Err(Violation::new(
                i + 1,
                1,
                format!(
                    "expected the radiance not to decrease as the temperature rises, found {} after {}",
                    pair[1][1], pair[0][1]
                ),
            ));
        }
    }
    Ok(())
}

/// Reads an `.rtt` table.
///
/// # Errors
/// A [`ParseError`] for an empty file, a row without exactly two finite numbers, a
/// temperature not above 0 K or not above the one before, or a negative or decreasing
/// radiance.
pub fn parse(file: &str, text: &str) -> Result<RttTable, ParseError> {
    let mut lines = Lines::new(file, text);
    let raw: Vec<RawRow<'_, 2>> = read_rows(&mut lines, COLUMNS)?;
    let values: Vec<[f64; 2]> = raw.iter().map(|r| r.values).collect();
    check(&values).map_err(|v| at_token(&lines, &raw, v))?;
    Ok(RttTable {
        rows: raw
            .iter()
            .map(|r| RttRow {
                temperature_k: r.values[0],
                radiance_w_cm2_sr: r.values[1],
                position: r.position,
            })
            .collect(),
    })
}

/// Writes an `.rtt` table.
///
/// # Errors
/// A [`WriteError`] for an empty table or a value the parser would reject.
pub fn write(table: &RttTable) -> Result<String, WriteError> {
    let rows: Vec<[f64; 2]> = table
        .rows
        .iter()
        .map(|r| [r.temperature_k, r.radiance_w_cm2_sr])
        .collect();
    write_rows(&rows, check)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_and_checks() {
        let t = parse("p.rtt", "200 6.01175039861e-04\n201 6.20761893613e-04\n").unwrap();
        assert_eq!(t.to_pairs().len(), 2);
        for (text, line, col) in [
            ("200 1\n200 2\n", 2, 1),
            ("200 2\n201 1\n", 2, 5),
            ("0 0\n", 1, 1),
            ("200 -1\n", 1, 5),
        ] {
            let e = parse("p.rtt", text).unwrap_err();
            assert_eq!((e.line, e.column), (line, col), "{text:?}: {e}");
        }
    }
}
