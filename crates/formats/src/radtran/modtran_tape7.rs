//! MODTRAN's `tape7`: a spectral table with named columns, in transmittance or radiance
//! mode (MODTRAN 4 and 5; the samples are pyradi's test data). Spec page:
//! `formats/radtran/modtran-tape7.md`.
//!
//! ```text
//! T F 6    3    2    0 …                                  card 1 (a letter in column 1)
//!  … the other input cards, echoed …
//!     2050.0    2100.0       1.0       1.0NW              card 4: V1 V2 DV FWHM (cm⁻¹)
//!     0   0    0.000  0    0.000  0    1.000              card 5
//!     FREQ  TOT_TRANS  PTH_THRML  THRML_SCT … TOTAL_RAD …  column names (radiance mode)
//!  2050.00 0.74772996 5.6037E-08 0.0000E+00 …              rows
//!  -9999.
//! ```
//!
//! Transmittance mode has two header lines (names, then units: `CM-1 TRANS TRANS …`) whose
//! names may run together (`H2-CH4CH4-CH4`), so columns are found from the last header
//! line: each of its words ends a column, and a column's name is what every header line
//! holds between the end of the previous column and the end of this one. Every row must
//! have exactly as many numbers as the header has columns. `FREQ` is cm⁻¹ and must
//! strictly increase; radiances are W cm⁻² sr⁻¹ per cm⁻¹, not negative; transmittances
//! (`TOT_TRANS`, `COMBIN TRANS`) lie in 0–1.01.
//!
//! Card 4's range is kept as [`ModtranTape7::declared`] and never used: the rows are the
//! data. A file cut down after MODTRAN wrote it (as pyradi's `tape7-01b`, whose card 4
//! says 655–33665 cm⁻¹ and whose rows stop at 750) reads as its rows.

use super::{Source, TextLine, number, push_row, text_lines};
use crate::ParseError;
use crate::legacy::Position;

/// Transmittance columns, checked to lie in 0-1.01.
const TRANSMITTANCES: [&str; 2] = ["TOT_TRANS", "COMBIN TRANS"];
/// Radiance columns, checked not to be negative.
const RADIANCES: [&str; 8] = [
    "PTH_THRML",
    "THRML_SCT",
    "SURF_EMIS",
    "SOL_SCAT",
    "SING_SCAT",
    "GRND_RFLT",
    "DRCT_RFLT",
    "TOTAL_RAD",
];

/// What the columns say the file is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Band-model transmittances per species (`COMBIN TRANS` …).
    Transmittance,
    /// Transmittance and radiance components (`TOT_TRANS`, `PTH_THRML`, `TOTAL_RAD` …).
    Radiance,
    /// Another table MODTRAN writes (irradiance, …): the columns are read all the same.
    Other,
}

/// Card 4's V1, V2 and DV, cm⁻¹, as the header says.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeclaredRange {
    /// V1, cm⁻¹.
    pub v1_per_cm: f64,
    /// V2, cm⁻¹.
    pub v2_per_cm: f64,
    /// DV, cm⁻¹.
    pub dv_per_cm: f64,
    /// Where card 4 is.
    pub position: Position,
}

/// A MODTRAN `tape7`.
#[derive(Debug, Clone, PartialEq)]
pub struct ModtranTape7 {
    /// What the file is.
    pub mode: Mode,
    /// Column names, header lines joined by a space (`FREQ CM-1`, `TOT_TRANS`, `COMBIN TRANS`).
    pub names: Vec<String>,
    /// `columns[c][row]`; column 0 is the wavenumber, cm⁻¹.
    pub columns: Vec<Vec<f64>>,
    /// Where each row is.
    pub positions: Vec<Position>,
    /// Card 4's range, if a card 4 was found before the column header.
    pub declared: Option<DeclaredRange>,
    /// Where the column header's last line is.
    pub header_position: Position,
}

impl ModtranTape7 {
    /// The column whose name is `name` (as in [`ModtranTape7::names`]).
    #[must_use]
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.names
            .iter()
            .position(|n| n == name)
            .map(|i| self.columns[i].as_slice())
    }

    /// Wavenumbers, cm⁻¹, increasing.
    #[must_use]
    pub fn wavenumber_per_cm(&self) -> &[f64] {
        &self.columns[0]
    }

    /// The path's total transmittance: `TOT_TRANS` (radiance mode) or `COMBIN TRANS`
    /// (transmittance mode).
    #[must_use]
    pub fn transmission(&self) -> Option<&[f64]> {
        self.column("TOT_TRANS")
            .or_else(|| self.column("COMBIN TRANS"))
    }

    /// The path's thermal radiance, W cm⁻² sr⁻¹ per cm⁻¹: `PTH_THRML` plus the thermal
    /// scattering `THRML_SCT` where the file has it (radiance mode only).
    #[must_use]
    pub fn path_thermal_radiance(&self) -> Option<Vec<f64>> {
        let emitted = self.column("PTH_THRML")?;
        Some(match self.column("THRML_SCT") {
            Some(s) => emitted.iter().zip(s).map(|(a, b)| a + b).collect(),
            None => emitted.to_vec(),
        })
    }
}

fn is_end(line: &TextLine<'_>) -> bool {
    line.text.trim() == "-9999."
}

fn first_is_number(line: &TextLine<'_>) -> bool {
    line.text
        .split_whitespace()
        .next()
        .is_some_and(|t| number(t).is_some())
}

/// Reads a MODTRAN `tape7`.
///
/// # Errors
/// A [`ParseError`] at the place: an empty file, no `FREQ` column header, a header of
/// fewer than two columns, a row whose count of numbers is not the header's, a field that
/// is not a finite number, wavenumbers that repeat or do not increase, no row, or no
/// ` -9999.` at the end (a truncated file).
pub fn parse(file: &str, text: &str) -> Result<ModtranTape7, ParseError> {
    let src = Source { file, text };
    let lines = text_lines(text);
    if lines.iter().all(|l| l.text.trim().is_empty()) {
        return Err(src.error(0, 0, "expected a MODTRAN tape7, found an empty file"));
    }
    let Some(h) = lines
        .iter()
        .position(|l| l.text.split_whitespace().next() == Some("FREQ"))
    else {
        return Err(src.eof_error(
            "expected a column header line starting with `FREQ`, found none: is this a MODTRAN tape7?",
        ));
    };
    let mut h_end = h + 1;
    while h_end < lines.len()
        && !lines[h_end].text.trim().is_empty()
        && !first_is_number(&lines[h_end])
        && !is_end(&lines[h_end])
    {
        h_end += 1;
    }
    let header = &lines[h..h_end];
    let last = header[header.len() - 1];
    // Each word of the last header line ends a column (names are right-aligned over the
    // numbers); a name is what the header lines hold in that column's span.
    let mut spans = Vec::new();
    let mut start = 0;
    for (at, tok) in last.tokens() {
        let end_col = last.text[..at - last.offset + tok.len()].chars().count();
        spans.push((start, end_col));
        start = end_col;
    }
    if spans.len() < 2 {
        return Err(src.error(
            last.offset,
            last.text.len(),
            "expected a column header of at least two columns (FREQ and a transmittance)",
        ));
    }
    let names: Vec<String> = spans
        .iter()
        .map(|&(a, b)| {
            header
                .iter()
                .map(|l| l.field(a, b - a).trim())
                .filter(|s| !s.is_empty())
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    let n = names.len();
    let mut columns = vec![Vec::new(); n];
    let mut positions = Vec::new();
    let mut ended = false;
    for line in &lines[h_end..] {
        if is_end(line) {
            ended = true;
            break;
        }
        if line.text.trim().is_empty() {
            continue;
        }
        let count = |found| {
            format!(
                "expected {n} columns as the header (line {}) has, found {found}",
                last.number
            )
        };
        push_row(src, line, &names, &mut columns, count, |_, name, v| {
            // As for LOWTRAN's TAPE7: τ within 0-1.01 (printed slightly above 1 on short
            // humid paths), radiances not negative.
            if TRANSMITTANCES.contains(&name) && !(0.0..=1.01).contains(&v) {
                Some(format!("expected {name} from 0 to 1.01, found {v}"))
            } else if RADIANCES.contains(&name) && v < 0.0 {
                Some(format!(
                    "expected {name} of 0 or more (a radiance), found {v}"
                ))
            } else {
                None
            }
        })?;
        positions.push(line.position());
    }
    if !ended {
        return Err(src.eof_error(
            "expected ` -9999.` after the last row, found the end of the file: the tape7 is truncated",
        ));
    }
    if positions.is_empty() {
        return Err(src.error(
            last.offset,
            last.text.len(),
            "expected rows of numbers after the column header, found none",
        ));
    }
    let declared = lines[..h].iter().rev().find_map(|l| {
        let t: Vec<f64> = l
            .text
            .split_whitespace()
            .take(3)
            .map_while(number)
            .collect();
        (t.len() == 3 && t[0] < t[1] && t[2] > 0.0).then(|| DeclaredRange {
            v1_per_cm: t[0],
            v2_per_cm: t[1],
            dv_per_cm: t[2],
            position: l.position(),
        })
    });
    let mode = if names.iter().any(|s| s == "TOT_TRANS" || s == "TOTAL_RAD") {
        Mode::Radiance
    } else if names.iter().any(|s| s == "COMBIN TRANS") {
        Mode::Transmittance
    } else {
        Mode::Other
    };
    Ok(ModtranTape7 {
        mode,
        names,
        columns,
        positions,
        declared,
        header_position: last.position(),
    })
}

#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    const T: &str = "T F 6    3    2\n    2050.0    2100.0       1.0       1.0NW\n    0   0    0.000\n    FREQ  TOT_TRANS  PTH_THRML  THRML_SCT\n 2050.00 0.74772996 5.6037E-08 1.0000E-09\n 2051.00 0.59794545 9.6305E-08 0.0000E+00\n -9999.\n";

    #[test]
    fn named_columns_and_the_declared_range() {
        let t = parse("tape7", T).unwrap();
        assert_eq!(t.mode, Mode::Radiance);
        assert_eq!(t.names, ["FREQ", "TOT_TRANS", "PTH_THRML", "THRML_SCT"]);
        assert_eq!(t.wavenumber_per_cm(), [2050.0, 2051.0]);
        assert_eq!(t.transmission().unwrap(), [0.74772996, 0.59794545]);
        assert_eq!(
            t.path_thermal_radiance().unwrap(),
            [5.6037e-8 + 1e-9, 9.6305e-8]
        );
        let d = t.declared.unwrap();
        assert_eq!(
            (d.v1_per_cm, d.v2_per_cm, d.dv_per_cm, d.position.line),
            (2050.0, 2100.0, 1.0, 2)
        );
    }

    #[test]
    fn names_that_run_together_split_by_the_units_line() {
        let text =
            "M F 1\n  FREQ H2-CH4CH4-CH4\n  CM-1  TRANS  TRANS\n  655.00 0.5000 1.0000\n -9999.\n";
        let t = parse("t", text).unwrap();
        assert_eq!(t.names, ["FREQ CM-1", "H2-CH4 TRANS", "CH4-CH4 TRANS"]);
    }

    #[test]
    fn bad_tables_are_refused_at_their_place() {
        let e = parse("t", &T.replace(" -9999.\n", "")).unwrap_err();
        assert!(e.message.contains("truncated"), "{}", e.message);
        let e = parse("t", &T.replace(" 1.0000E-09", "")).unwrap_err();
        assert_eq!((e.line, e.column), (5, 31));
        let e = parse("t", &T.replace(" 2051.00", " 2050.00")).unwrap_err();
        assert_eq!((e.line, e.column), (6, 2));
        assert!(e.message.contains("repeated"));
        assert!(parse("t", "").is_err());
        assert!(parse("t", "T F\n").unwrap_err().message.contains("FREQ"));
    }
}
