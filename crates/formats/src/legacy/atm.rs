//! `.atm`: the vertical atmosphere table (thesis §3.2.2, Figure 9; Appendix H `atm_type`).
//!
//! ```text
//! 1.000 281.651 1.000 0.819461 7.387818e-04
//! h_sonde_km T_K h_km tau Lu_W_cm2_sr
//! ```
//!
//! One row per altitude, five values: altitude above sea level of the radiosonde level
//! (km), air temperature there (K), altitude above the ground (km; the thesis's
//! "altitude (km) lowtran"), band transmission of the vertical path from the ground to
//! that altitude (0 to 1), and upwelled path radiance seen looking straight down from
//! that altitude (W cm⁻² sr⁻¹, the legacy unit: multiply by 1e4 for W m⁻² sr⁻¹). Both
//! altitude columns strictly increase. The 1990 program held at most 51 rows.

use super::lex::Lines;
use super::table::{
    RawRow, Violation, at_token, in_range, increasing, non_negative, positive, read_rows,
    write_rows,
};
use super::{Position, WriteError};
use crate::ParseError;

/// One altitude of an `.atm` table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtmRow {
    /// Radiosonde altitude above sea level, km.
    pub altitude_asl_km: f64,
    /// Air temperature at that altitude, K (above 0).
    pub temperature_k: f64,
    /// Altitude above the ground, km (0 or more).
    pub altitude_km: f64,
    /// Band transmission of the vertical path from the ground to this altitude, 0 to 1.
    pub transmission: f64,
    /// Upwelled path radiance looking straight down from this altitude, W cm⁻² sr⁻¹.
    pub upwelled_radiance_w_cm2_sr: f64,
    /// Where the row is.
    pub position: Position,
}

impl AtmRow {
    /// The row's values in the file's column order: altitude ASL (km), temperature (K),
    /// altitude above ground (km), transmission, upwelled radiance (W cm⁻² sr⁻¹).
    #[must_use]
    pub fn to_values(&self) -> [f64; 5] {
        [
            self.altitude_asl_km,
            self.temperature_k,
            self.altitude_km,
            self.transmission,
            self.upwelled_radiance_w_cm2_sr,
        ]
    }

    /// A row from values in the file's column order ([`AtmRow::to_values`]).
    #[must_use]
    pub fn from_values(values: [f64; 5], position: Position) -> Self {
        let [
            altitude_asl_km,
            temperature_k,
            altitude_km,
            transmission,
            upwelled_radiance_w_cm2_sr,
        ] = values;
        Self {
            altitude_asl_km,
            temperature_k,
            altitude_km,
            transmission,
            upwelled_radiance_w_cm2_sr,
            position,
        }
    }
}

/// A parsed `.atm` table.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct AtmTable {
    /// The rows, altitudes strictly increasing.
    pub rows: Vec<AtmRow>,
}

impl AtmTable {
    /// The rows as arrays in the file's column order ([`AtmRow::to_values`]), the form
    /// `irsig_atmosphere::legacy::DirtranTables::atm` takes.
    #[must_use]
    pub fn to_rows(&self) -> Vec<[f64; 5]> {
        self.rows.iter().map(AtmRow::to_values).collect()
    }

    /// A table from arrays in the file's column order, without positions (for writing).
    #[must_use]
    pub fn from_rows(rows: &[[f64; 5]]) -> Self {
        Self {
            rows: rows
                .iter()
                .map(|&v| AtmRow::from_values(v, Position::default()))
                .collect(),
        }
    }
}

const COLUMNS: &str = "altitude ASL in km, temperature in K, altitude above ground in km, \
                       transmission, upwelled radiance in W cm^-2 sr^-1";

fn check(rows: &[[f64; 5]]) -> Result<(), Violation> {
    for (i, r) in rows.iter().enumerate() {
        positive(i, 1, r[1], "a temperature in K")?;
        non_negative(i, 2, r[2], "an altitude above ground in km")?;
        in_range(i, 3, r[3], 0.0, 1.0, "a transmission")?;
        non_negative(i, 4, r[4], "an upwelled radiance")?;
    }
    increasing(rows, 0, "the altitude above sea level")?;
    increasing(rows, 2, "the altitude above ground")
}

/// Reads an `.atm` table.
///
/// # Errors
/// A [`ParseError`] for an empty file, a row without exactly five finite numbers, a
/// temperature not above 0 K, a negative altitude above ground, a transmission outside
/// 0–1, a negative radiance, or altitudes that do not strictly increase.
pub fn parse(file: &str, text: &str) -> Result<AtmTable, ParseError> {
    let mut lines = Lines::new(file, text);
    let raw: Vec<RawRow<'_, 5>> = read_rows(&mut lines, COLUMNS)?;
    let values: Vec<[f64; 5]> = raw.iter().map(|r| r.values).collect();
    check(&values).map_err(|v| at_token(&lines, &raw, v))?;
    Ok(AtmTable {
        rows: raw
            .iter()
            .map(|r| AtmRow::from_values(r.values, r.position))
            .collect(),
    })
}

/// Writes an `.atm` table, five values per line.
///
/// # Errors
/// A [`WriteError`] for an empty table or a value the parser would reject.
pub fn write(table: &AtmTable) -> Result<String, WriteError> {
    write_rows(&table.to_rows(), check)
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn reads_rows() {
        let t = parse(
            "a.atm",
            "0.050 287.825 0.050 0.964055 1.519176e-04\n1 281.651 1 0.819461 7.387818e-04\n",
        )
        .unwrap();
        assert_eq!(t.rows.len(), 2);
        assert_eq!(t.rows[1].transmission, 0.819_461);
        assert_eq!(t.rows[1].upwelled_radiance_w_cm2_sr, 7.387_818e-4);
        assert_eq!(t.rows[0].altitude_asl_km, 0.05);
        assert_eq!(t.rows[0].temperature_k, 287.825);
    }

    #[test]
    fn rows_are_the_columns_in_file_order() {
        let t = parse("a.atm", "0.05 287.825 0.05 0.964055 1.5e-4\n").unwrap();
        assert_eq!(t.to_rows(), [[0.05, 287.825, 0.05, 0.964_055, 1.5e-4]]);
        let back = AtmTable::from_rows(&t.to_rows());
        assert_eq!(back.rows[0].upwelled_radiance_w_cm2_sr, 1.5e-4);
        assert_eq!(write(&back).unwrap(), write(&t).unwrap());
    }

    #[test]
    fn rejects_bad_values_at_the_value() {
        for (text, line, col) in [
            ("0 280 0 1.2 0\n", 1, 9),
            ("0 280 0 0.9 -1e-4\n", 1, 13),
            ("0 0 0 0.9 0\n", 1, 3),
            ("0 280 -1 0.9 0\n", 1, 7),
            ("1 280 1 0.9 0\n0.5 280 2 0.9 0\n", 2, 1),
            ("1 280 1 0.9 0\n2 280 1 0.9 0\n", 2, 7),
            ("1 280 1 0.9\n", 1, 1),
        ] {
            let e = parse("a.atm", text).unwrap_err();
            assert_eq!((e.line, e.column), (line, col), "{text:?}: {e}");
        }
    }
}
