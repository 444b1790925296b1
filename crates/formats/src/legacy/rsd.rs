//! `.rsd`: radiosonde data, DIRTRAN's input for LOWTRAN (thesis §3.2.2, Figure 9).
//!
//! ```text
//! 0.154 1013.0 12.5 3.1     altitude km, pressure mb, temperature degC, dew-point depression degC
//! ```
//!
//! One row per level. Figure 9 names the columns "altitude (km), atmospheric pressure,
//! temp (°C), dewpoint depression (°C)" without a pressure unit; this toolchain reads it
//! in millibars (= hPa), the unit LOWTRAN's radiosonde input (JCHAR 'A') uses and
//! radiosondes report. Altitudes strictly increase; pressure is above 0; temperature is
//! above absolute zero (−273.15 °C); the dew-point depression (temperature minus dew
//! point) is 0 or more. No 1990 `.rsd` survives; none is in the reference tables.

use super::lex::Lines;
use super::table::{
    RawRow, Violation, at_token, increasing, non_negative, positive, read_rows, write_rows,
};
use super::{Position, WriteError};
use crate::ParseError;

/// One radiosonde level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RsdRow {
    /// Altitude above sea level, km.
    pub altitude_km: f64,
    /// Atmospheric pressure, mb (hPa).
    pub pressure_mb: f64,
    /// Air temperature, °C.
    pub temperature_c: f64,
    /// Dew-point depression (temperature minus dew point), °C (a difference, so also K).
    pub dew_point_depression_c: f64,
    /// Where the row is.
    pub position: Position,
}

impl RsdRow {
    /// The row's values in the file's column order: altitude (km), pressure (mb),
    /// temperature (°C), dew-point depression (°C).
    #[must_use]
    pub fn to_values(&self) -> [f64; 4] {
        [
            self.altitude_km,
            self.pressure_mb,
            self.temperature_c,
            self.dew_point_depression_c,
        ]
    }

    /// A row from values in the file's column order ([`RsdRow::to_values`]).
    #[must_use]
    pub fn from_values(values: [f64; 4], position: Position) -> Self {
        let [
            altitude_km,
            pressure_mb,
            temperature_c,
            dew_point_depression_c,
        ] = values;
        Self {
            altitude_km,
            pressure_mb,
            temperature_c,
            dew_point_depression_c,
            position,
        }
    }
}

/// A parsed `.rsd` file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RsdTable {
    /// The levels, altitudes strictly increasing.
    pub rows: Vec<RsdRow>,
}

impl RsdTable {
    /// The rows as arrays in the file's column order ([`RsdRow::to_values`]), the form
    /// `irsig_atmosphere::legacy::DirtranTables::rsd` takes.
    #[must_use]
    pub fn to_rows(&self) -> Vec<[f64; 4]> {
        self.rows.iter().map(RsdRow::to_values).collect()
    }

    /// A table from arrays in the file's column order, without positions (for writing).
    #[must_use]
    pub fn from_rows(rows: &[[f64; 4]]) -> Self {
        Self {
            rows: rows
                .iter()
                .map(|&v| RsdRow::from_values(v, Position::default()))
                .collect(),
        }
    }
}

const COLUMNS: &str =
    "altitude in km, pressure in mb, temperature in degC, dew-point depression in degC";

fn check(rows: &[[f64; 4]]) -> Result<(), Violation> {
    for (i, r) in rows.iter().enumerate() {
        positive(i, 1, r[1], "a pressure in mb")?;
        if r[2] <= -273.15 {
            return Err(Violation::new(
                i,
                2,
                format!("expected a temperature above -273.15 degC, found {}", r[2]),
            ));
        }
        non_negative(i, 3, r[3], "a dew-point depression in degC")?;
        // The dew point itself, temperature minus depression, is a temperature too.
        if r[2] - r[3] <= -273.15 {
            return Err(Violation::new(
                i,
                3,
                format!(
                    "expected a dew-point depression below {} degC, which would put the dew \
                     point at or below absolute zero, found {}",
                    r[2] + 273.15,
                    r[3]
                ),
            ));
        }
    }
    increasing(rows, 0, "the altitude")
}

/// Reads an `.rsd` file.
///
/// # Errors
/// A [`ParseError`] for an empty file, a row without exactly four finite numbers, a
/// pressure not above 0, a temperature at or below absolute zero, a negative dew-point
/// depression or one that puts the dew point at or below absolute zero, or altitudes that
/// do not strictly increase.
pub fn parse(file: &str, text: &str) -> Result<RsdTable, ParseError> {
    let mut lines = Lines::new(file, text);
    let raw: Vec<RawRow<'_, 4>> = read_rows(&mut lines, COLUMNS)?;
    let values: Vec<[f64; 4]> = raw.iter().map(|r| r.values).collect();
    check(&values).map_err(|v| at_token(&lines, &raw, v))?;
    Ok(RsdTable {
        rows: raw
            .iter()
            .map(|r| RsdRow::from_values(r.values, r.position))
            .collect(),
    })
}

/// Writes an `.rsd` file.
///
/// # Errors
/// A [`WriteError`] for an empty table or a value the parser would reject.
pub fn write(table: &RsdTable) -> Result<String, WriteError> {
    write_rows(&table.to_rows(), check)
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn reads_and_checks() {
        let t = parse("s.rsd", "0.154 1013 12.5 3.1\n1.5 850 4 6\n").unwrap();
        assert_eq!(t.rows[0].pressure_mb, 1013.0);
        assert_eq!(t.rows[1].dew_point_depression_c, 6.0);
        for (text, line, col) in [
            ("0 0 10 1\n", 1, 3),
            ("0 1000 -273.15 1\n", 1, 8),
            ("0 1000 10 -1\n", 1, 11),
            ("1 1000 10 1\n1 900 5 1\n", 2, 1),
            // A depression of 300 degC at 10 degC: a dew point of -290 degC, below 0 K.
            ("0 1000 10 300\n", 1, 11),
            ("0 1000 10 283.15\n", 1, 11),
        ] {
            let e = parse("s.rsd", text).unwrap_err();
            assert_eq!((e.line, e.column), (line, col), "{text:?}: {e}");
        }
    }

    #[test]
    fn rows_are_the_columns_in_file_order() {
        let t = parse("s.rsd", "0.154 1013 12.5 3.1\n1.5 850 4 6\n").unwrap();
        assert_eq!(
            t.to_rows(),
            [[0.154, 1013.0, 12.5, 3.1], [1.5, 850.0, 4.0, 6.0]]
        );
        let back = RsdTable::from_rows(&t.to_rows());
        assert_eq!(write(&back).unwrap(), write(&t).unwrap());
        assert_eq!(back.rows[1].temperature_c, 4.0);
    }
}
