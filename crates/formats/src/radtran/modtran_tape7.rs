//! MODTRAN's `tape7`: a spectral table with named columns, in transmittance, radiance or
//! direct solar irradiance mode (MODTRAN 4 and 5; the samples are pyradi's test data).
//! Spec page: `formats/radtran/modtran-tape7.md`.
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
//! holds between the end of the previous column and the end of this one. The one name of
//! two words on a single header line, direct solar mode's `SOL TR`, is one column. Every
//! row must have exactly as many numbers as the header has columns. `FREQ` is cm⁻¹ and
//! must strictly increase; radiances are W cm⁻² sr⁻¹ per cm⁻¹ and irradiances W cm⁻² per
//! cm⁻¹, not negative; transmittances (`TOT_TRANS`, `COMBIN TRANS`, `TRANS`) lie in 0–1.01.
//!
//! Card 1's IEMSCT (columns 11–15: MODTRAN 4's `2A1,I3,12I5`, and where pyradi's MODTRAN 5
//! `tape7-05` has it) says which columns hold data: an IEMSCT 1 run prints the solar
//! columns of an IEMSCT 2 run, without valid values, so the solar accessors answer only
//! for IEMSCT 2 (scattered sunlight) and 3 (direct solar irradiance).
//!
//! Card 4's range is kept as [`ModtranTape7::declared`] and never used: the rows are the
//! data. A file cut down after MODTRAN wrote it (as pyradi's `tape7-01b`, whose card 4
//! says 655–33665 cm⁻¹ and whose rows stop at 750) reads as its rows.

use super::{Source, TextLine, number, push_row, read_int, text_lines};
use crate::ParseError;
use crate::legacy::Position;

/// Transmittance columns, checked to lie in 0-1.01 (`TRANS` is direct solar mode's).
const TRANSMITTANCES: [&str; 3] = ["TOT_TRANS", "COMBIN TRANS", "TRANS"];
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
/// Irradiance columns (W cm⁻² per cm⁻¹), checked not to be negative: radiance mode's
/// `REF_SOL`, `SOL@OBS` and `TOA_SUN`, direct solar mode's `SOL TR` and `SOLAR`.
const IRRADIANCES: [&str; 5] = ["REF_SOL", "SOL@OBS", "TOA_SUN", "SOL TR", "SOLAR"];
/// Card 1's IEMSCT: columns 11-15 (0-based 10, width 5).
const IEMSCT_COLUMN: usize = 10;

/// What the columns say the file is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Band-model transmittances per species (`COMBIN TRANS` …).
    Transmittance,
    /// Transmittance and radiance components (`TOT_TRANS`, `PTH_THRML`, `TOTAL_RAD` …).
    Radiance,
    /// Direct solar irradiance (IEMSCT 3): `TRANS`, `SOL TR`, `SOLAR`, `DEPTH`.
    DirectSolar,
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
    /// Card 1's IEMSCT (0 transmittance, 1 thermal radiance, 2 with scattered sunlight, 3
    /// direct solar irradiance), if the file starts with card 1.
    pub iemsct: Option<i64>,
    /// Where card 1's IEMSCT field is (line 1, column 11), if the file starts with card 1.
    pub iemsct_position: Option<Position>,
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

    /// The path's total transmittance: `TOT_TRANS` (radiance mode), `COMBIN TRANS`
    /// (transmittance mode) or `TRANS` (direct solar mode, the sun's path).
    #[must_use]
    pub fn transmission(&self) -> Option<&[f64]> {
        self.column("TOT_TRANS")
            .or_else(|| self.column("COMBIN TRANS"))
            .or_else(|| self.column("TRANS"))
    }

    /// A column that holds data only in a run of IEMSCT `iemsct`.
    fn of_run(&self, iemsct: i64, name: &str) -> Option<&[f64]> {
        (self.iemsct == Some(iemsct))
            .then(|| self.column(name))
            .flatten()
    }

    /// The sunlight scattered into the path toward the observer, W cm⁻² sr⁻¹ per cm⁻¹:
    /// `SOL_SCAT` of an IEMSCT 2 run. It includes the single-scattered part `SING_SCAT`,
    /// and multiple scattering when MODTRAN ran with it (IMULT ≠ 0).
    #[must_use]
    pub fn solar_scattered_radiance(&self) -> Option<&[f64]> {
        self.of_run(2, "SOL_SCAT")
    }

    /// The single-scattered part of [`ModtranTape7::solar_scattered_radiance`], W cm⁻²
    /// sr⁻¹ per cm⁻¹: `SING_SCAT` of an IEMSCT 2 run.
    #[must_use]
    pub fn single_scattered_radiance(&self) -> Option<&[f64]> {
        self.of_run(2, "SING_SCAT")
    }

    /// Sunlight reflected by the ground at H2 toward the observer, W cm⁻² sr⁻¹ per cm⁻¹:
    /// `GRND_RFLT` of an IEMSCT 2 run, direct plus diffuse (the diffuse part is zero
    /// without multiple scattering).
    #[must_use]
    pub fn ground_reflected_radiance(&self) -> Option<&[f64]> {
        self.of_run(2, "GRND_RFLT")
    }

    /// The part of [`ModtranTape7::ground_reflected_radiance`] from the direct beam, W
    /// cm⁻² sr⁻¹ per cm⁻¹: `DRCT_RFLT` of an IEMSCT 2 run.
    #[must_use]
    pub fn direct_reflected_radiance(&self) -> Option<&[f64]> {
        self.of_run(2, "DRCT_RFLT")
    }

    /// The sum of the radiance components, W cm⁻² sr⁻¹ per cm⁻¹: `TOTAL_RAD`.
    #[must_use]
    pub fn total_radiance(&self) -> Option<&[f64]> {
        self.column("TOTAL_RAD")
    }

    /// The top-of-atmosphere solar irradiance times the transmittance of the L-shaped path
    /// sun → H2 → H1, W cm⁻² per cm⁻¹: `REF_SOL` of an IEMSCT 2 run.
    #[must_use]
    pub fn reflected_path_solar_irradiance(&self) -> Option<&[f64]> {
        self.of_run(2, "REF_SOL")
    }

    /// The solar irradiance at the observer (H1), W cm⁻² per cm⁻¹: `SOL@OBS` of an IEMSCT
    /// 2 run.
    #[must_use]
    pub fn solar_irradiance_at_observer(&self) -> Option<&[f64]> {
        self.of_run(2, "SOL@OBS")
    }

    /// The solar irradiance at the top of the atmosphere on a surface normal to the beam,
    /// W cm⁻² per cm⁻¹: `TOA_SUN` of an IEMSCT 2 run, `SOLAR` of an IEMSCT 3 run.
    #[must_use]
    pub fn extraterrestrial_irradiance(&self) -> Option<&[f64]> {
        self.of_run(2, "TOA_SUN")
            .or_else(|| self.of_run(3, "SOLAR"))
    }

    /// The solar irradiance transmitted to the observer (H1) on a surface normal to the
    /// beam, W cm⁻² per cm⁻¹: `SOL TR` of an IEMSCT 3 run.
    #[must_use]
    pub fn transmitted_solar_irradiance(&self) -> Option<&[f64]> {
        self.of_run(3, "SOL TR")
    }

    /// The path's thermal radiance, W cm⁻² sr⁻¹ per cm⁻¹: `PTH_THRML` (radiance mode
    /// only), which already includes the thermal scattering `THRML_SCT` (its part, as
    /// `SING_SCAT` is `SOL_SCAT`'s: formats/radtran/modtran-tape7.md).
    #[must_use]
    pub fn path_thermal_radiance(&self) -> Option<Vec<f64>> {
        self.column("PTH_THRML").map(<[f64]>::to_vec)
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

/// Card 1's IEMSCT (I5 in columns 11-15 of the first line, which starts with MODTRN, a
/// letter); `None` when the first line is not such a card 1.
fn card1_iemsct(
    src: Source<'_>,
    lines: &[TextLine<'_>],
) -> Result<Option<(i64, Position)>, ParseError> {
    let Some(first) = lines.iter().find(|l| !l.text.trim().is_empty()) else {
        return Ok(None);
    };
    if !first.text.starts_with(|c: char| c.is_ascii_alphabetic()) {
        return Ok(None);
    }
    let field = first.field(IEMSCT_COLUMN, 5);
    match read_int(field).filter(|_| !field.trim().is_empty()) {
        Some(k) if (0..=4).contains(&k) => Ok(Some((
            k,
            Position {
                line: first.number,
                column: IEMSCT_COLUMN + 1,
            },
        ))),
        _ => Err(src.error(
            first.offset_of_column(IEMSCT_COLUMN),
            5,
            format!(
                "expected card 1's IEMSCT (0 to 4, I5 in columns 11-15), found `{}`",
                field.trim()
            ),
        )),
    }
}

/// Reads a MODTRAN `tape7`.
///
/// # Errors
/// A [`ParseError`] at the place: an empty file, no `FREQ` column header, a header of
/// fewer than two columns, a row whose count of numbers is not the header's, a field that
/// is not a finite number, a transmittance outside 0-1.01 or a negative radiance or
/// irradiance, wavenumbers that repeat or do not increase, no row, no ` -9999.` at the end
/// (a truncated file), a card 1 whose IEMSCT is not a number from 0 to 4, or one whose
/// IEMSCT disagrees with the columns (3 is direct solar mode's, and only 3).
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
    let h_end = header_end(&lines, h);
    let header = &lines[h..h_end];
    let last = header[header.len() - 1];
    let names = column_names(src, header)?;
    let (columns, positions) = read_rows(src, &lines[h_end..], &names, last)?;
    let declared = declared_range(&lines[..h]);
    let mode = mode_of(&names);
    let card1 = card1_iemsct(src, &lines)?;
    let iemsct = card1.map(|c| c.0);
    check_iemsct(src, last, iemsct, mode)?;
    Ok(ModtranTape7 {
        mode,
        iemsct,
        iemsct_position: card1.map(|c| c.1),
        names,
        columns,
        positions,
        declared,
        header_position: last.position(),
    })
}

/// Where the column header that starts at line `h` ends: at the first blank line, row of
/// numbers or ` -9999.` after it.
fn header_end(lines: &[TextLine<'_>], h: usize) -> usize {
    let mut h_end = h + 1;
    while h_end < lines.len()
        && !lines[h_end].text.trim().is_empty()
        && !first_is_number(&lines[h_end])
        && !is_end(&lines[h_end])
    {
        h_end += 1;
    }
    h_end
}

/// The columns' names, from the column header's lines: at least two columns.
fn column_names(src: Source<'_>, header: &[TextLine<'_>]) -> Result<Vec<String>, ParseError> {
    let last = header[header.len() - 1];
    let spans = column_spans(&last);
    if spans.len() < 2 {
        return Err(src.error(
            last.offset,
            last.text.len(),
            "expected a column header of at least two columns (FREQ and a transmittance)",
        ));
    }
    Ok(spans
        .iter()
        .map(|&(a, b)| {
            header
                .iter()
                .map(|l| l.field(a, b - a).trim())
                .filter(|s| !s.is_empty())
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect())
}

/// The character span of each column, from the header's last line.
fn column_spans(last: &TextLine<'_>) -> Vec<(usize, usize)> {
    // Each word of the last header line ends a column (names are right-aligned over the
    // numbers); a name is what the header lines hold in that column's span.
    // Direct solar mode's `SOL TR` is one name of two words.
    let mut spans = Vec::new();
    let mut start = 0;
    let tokens = last.tokens();
    for (k, &(at, tok)) in tokens.iter().enumerate() {
        let joined = tok == "SOL"
            && tokens
                .get(k + 1)
                .is_some_and(|&(next, t)| t == "TR" && next == at + tok.len() + 1);
        if joined {
            continue;
        }
        let end_col = last.text[..at - last.offset + tok.len()].chars().count();
        spans.push((start, end_col));
        start = end_col;
    }
    spans
}

/// The rows under the column header (`last` its last line) up to ` -9999.`: the columns
/// and where each row is.
fn read_rows(
    src: Source<'_>,
    rows: &[TextLine<'_>],
    names: &[String],
    last: TextLine<'_>,
) -> Result<(Vec<Vec<f64>>, Vec<Position>), ParseError> {
    let n = names.len();
    let mut columns = vec![Vec::new(); n];
    let mut positions = Vec::new();
    let mut ended = false;
    for line in rows {
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
        push_row(src, line, names, &mut columns, count, |_, name, v| {
            value_fault(name, v)
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
    Ok((columns, positions))
}

/// What is wrong with the value `v` of column `name`, if anything.
fn value_fault(name: &str, v: f64) -> Option<String> {
    // As for LOWTRAN's TAPE7: τ within 0-1.01 (printed slightly above 1 on short
    // humid paths), radiances not negative.
    if TRANSMITTANCES.contains(&name) && !(0.0..=1.01).contains(&v) {
        Some(format!("expected {name} from 0 to 1.01, found {v}"))
    } else if RADIANCES.contains(&name) && v < 0.0 {
        Some(format!(
            "expected {name} of 0 or more (a radiance), found {v}"
        ))
    } else if IRRADIANCES.contains(&name) && v < 0.0 {
        Some(format!(
            "expected {name} of 0 or more (an irradiance), found {v}"
        ))
    } else {
        None
    }
}

/// Card 4's range: the last line before the column header that starts with three numbers,
/// V1 below V2 and DV positive.
fn declared_range(before_header: &[TextLine<'_>]) -> Option<DeclaredRange> {
    before_header.iter().rev().find_map(|l| {
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
    })
}

/// What the columns' names say the file is.
fn mode_of(names: &[String]) -> Mode {
    let has = |name: &str| names.iter().any(|s| s == name);
    if has("SOL TR") && has("SOLAR") {
        Mode::DirectSolar
    } else if names.iter().any(|s| s == "TOT_TRANS" || s == "TOTAL_RAD") {
        Mode::Radiance
    } else if names.iter().any(|s| s == "COMBIN TRANS") {
        Mode::Transmittance
    } else {
        Mode::Other
    }
}

/// Card 1's IEMSCT, if any, must agree with the columns (`last` the header's last line): 3
/// is direct solar mode's, and only 3.
fn check_iemsct(
    src: Source<'_>,
    last: TextLine<'_>,
    iemsct: Option<i64>,
    mode: Mode,
) -> Result<(), ParseError> {
    if let Some(k) = iemsct
        && (k == 3) != (mode == Mode::DirectSolar)
    {
        let expected = if k == 3 {
            "direct solar mode's columns (TRANS, SOL TR, SOLAR) as card 1's IEMSCT = 3 says"
                .to_owned()
        } else {
            format!("the columns of an IEMSCT = {k} run as card 1 says, not direct solar mode's")
        };
        return Err(src.error(last.offset, last.text.len(), format!("expected {expected}")));
    }
    Ok(())
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
        // THRML_SCT is a part of PTH_THRML, not added to it.
        assert_eq!(t.path_thermal_radiance().unwrap(), [5.6037e-8, 9.6305e-8]);
        let d = t.declared.unwrap();
        assert_eq!(
            (d.v1_per_cm, d.v2_per_cm, d.dv_per_cm, d.position.line),
            (2050.0, 2100.0, 1.0, 2)
        );
    }

    #[test]
    fn names_that_run_together_split_by_the_units_line() {
        let text = "M F 1    1    0\n  FREQ H2-CH4CH4-CH4\n  CM-1  TRANS  TRANS\n  655.00 0.5000 1.0000\n -9999.\n";
        let t = parse("t", text).unwrap();
        assert_eq!(t.names, ["FREQ CM-1", "H2-CH4 TRANS", "CH4-CH4 TRANS"]);
    }

    /// Direct solar mode (IEMSCT 3), the header as pyradi's `rymodtran` documents it for
    /// MODTRAN 5 (`FREQ TRANS SOL TR SOLAR DEPTH`); the numbers are LOWTRAN7's for a path
    /// from 300 m up to the sun (formats/radtran/samples/solar.tape7, run 3).
    const SUN: &str = "T F 6    3    3    0\n    2500.0    2600.0      20.0\n    FREQ   TRANS  SOL TR   SOLAR   DEPTH\n 2500.00  0.8304 1.26E-06 1.52E-06  0.186\n 2520.00  0.8575 1.32E-06 1.53E-06  0.154\n -9999.\n";

    #[test]
    fn direct_solar_mode_reads_sol_tr_as_one_column() {
        let t = parse("sun", SUN).unwrap();
        assert_eq!(t.mode, Mode::DirectSolar);
        assert_eq!(t.iemsct, Some(3));
        assert_eq!(t.iemsct_position.unwrap().column, 11);
        assert_eq!(t.names, ["FREQ", "TRANS", "SOL TR", "SOLAR", "DEPTH"]);
        assert_eq!(t.transmission().unwrap(), [0.8304, 0.8575]);
        assert_eq!(
            t.transmitted_solar_irradiance().unwrap(),
            [1.26e-6, 1.32e-6]
        );
        assert_eq!(t.extraterrestrial_irradiance().unwrap(), [1.52e-6, 1.53e-6]);
        assert!(t.solar_scattered_radiance().is_none());
        assert!(t.path_thermal_radiance().is_none());
        // The radiance-mode sample is IEMSCT 2: no direct solar columns.
        let r = parse("tape7", T).unwrap();
        assert_eq!(r.iemsct, Some(2));
        assert!(r.transmitted_solar_irradiance().is_none());
    }

    #[test]
    fn solar_columns_answer_only_for_the_run_that_fills_them() {
        // An IEMSCT 1 run prints SOL_SCAT without valid values.
        let head = "    FREQ  TOT_TRANS  PTH_THRML   SOL_SCAT    TOA_SUN\n 2050.00 0.74772996 5.6037E-08 1.1042E-09 9.6338E-07\n -9999.\n";
        let two = parse("t", &format!("T F 6    3    2    0\n{head}")).unwrap();
        assert_eq!(two.solar_scattered_radiance().unwrap(), [1.1042e-9]);
        assert_eq!(two.extraterrestrial_irradiance().unwrap(), [9.6338e-7]);
        let one = parse("t", &format!("T F 6    3    1    0\n{head}")).unwrap();
        assert!(one.solar_scattered_radiance().is_none());
        assert!(one.extraterrestrial_irradiance().is_none());
    }

    #[test]
    fn bad_direct_solar_tables_are_refused_at_their_place() {
        // Cut in the middle of a row: the row is short, then no end.
        let cut = &SUN[..SUN.find("1.32E-06").unwrap()];
        let e = parse("sun", cut).unwrap_err();
        assert_eq!(e.line, 5, "{e}");
        assert!(e.message.contains("expected 5 columns"), "{e}");
        let nan = SUN.replace("1.26E-06", "     NaN");
        let e = parse("sun", &nan).unwrap_err();
        assert_eq!((e.line, e.column), (4, 23), "{e}");
        assert!(e.message.contains("SOL TR"), "{e}");
        let negative = SUN.replace(" 1.53E-06  0.154", " -1.53E-06 0.154");
        let e = parse("sun", &negative).unwrap_err();
        assert_eq!((e.line, e.column), (5, 27), "{e}");
        assert!(e.message.contains("an irradiance"), "{e}");
        // No SOLAR column: card 1 says IEMSCT 3, the columns are not its.
        let missing = SUN
            .replace("   SOLAR   DEPTH", "   DEPTH")
            .replace(" 1.52E-06", "")
            .replace(" 1.53E-06", "");
        let e = parse("sun", &missing).unwrap_err();
        assert_eq!(e.line, 3, "{e}");
        assert!(e.message.contains("IEMSCT = 3"), "{e}");
        // Card 1's IEMSCT not a number.
        let e = parse("sun", &SUN.replace("    3    0\n", "    x    0\n")).unwrap_err();
        assert_eq!((e.line, e.column), (1, 11), "{e}");
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
