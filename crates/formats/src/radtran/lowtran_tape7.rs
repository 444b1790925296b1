//! LOWTRAN7's `TAPE7`: the spectral table of each calculation of a deck, as the Fortran
//! program writes it (`WRITE(IPU, …)` in `LWTRN7` and `TRANS`). Spec page:
//! `formats/radtran/lowtran-tape7.md`.
//!
//! Each calculation writes one block that ends with the line ` -9999.`:
//!
//! ```text
//!     6    2    1    0    6    6    6    6    6    6    1    0    0   0.000   0.00   card 1 (13I5,F8.3,F7.2)
//!     0    1    1    0    0    0     0.000     0.000     0.000     0.000     0.000   card 2
//!    -99.000   -99.000   -99.000       -99                                         card 2A
//!    -99.000   -99.000   -99.000                                                   card 2B
//!    331976 U S STANDARD                                                           ML, model name
//!      1.000     0.001   180.000     0.999     0.000     0.000    0                card 3 (RANGE filled in)
//!   -99  -99  -99  -99                                                             card 3A1
//!    -99.000   -99.000   -99.000 …                                                 card 3A2
//!    710.000  1250.000     5.000                                                   card 4
//!     0                                                                            IRPT
//!   FREQ   TRANS     ATMOS   PATH     SINGLE   GROUND DIRECT   TOTAL RAD          column header
//!    710.  0.1245 1.07E-05                                            2.083E+00   rows
//!  -9999.
//! ```
//!
//! The rows hold, by IEMSCT (card 1's third field):
//!
//! | IEMSCT | columns (format) |
//! | --- | --- |
//! | 0 | FREQ, τ total, H2O, CO2+, O3, trace, N2 cont., H2O cont., mol. scat., aer-hyd, HNO3, aer-hyd abs., −ln τ (`F7.0,11F8.4,1PE10.3`) |
//! | 1 | FREQ, τ, atmospheric radiance, −ln τ (`F7.0,F8.4,1PE9.2,T96,E10.3`) |
//! | 2 | FREQ, τ, thermal, scattered, single-scattered, ground-reflected, its single-scattered part, total radiance, two ground transmittances, −ln τ (`F7.0,F8.4,1P6E9.2,0P2F8.4,T96,1PE10.3`) |
//! | 3 | FREQ, τ, transmitted and extraterrestrial solar irradiance, −ln τ (`F7.0,F8.4,1P2E9.2,T96,E10.3`) |
//!
//! FREQ is cm⁻¹; radiances are W cm⁻² sr⁻¹ per cm⁻¹, irradiances W cm⁻² per cm⁻¹. A
//! calculation LOWTRAN rejects (a path its geometry cannot make) writes only the next
//! `IRPT` and ` -9999.`: such a run is kept, marked as failed, so that the runs still line
//! up with the deck's calculations (TAPE6 says why). Transmittances up to 1.01 are read:
//! LOWTRAN prints 1.0002 on metre-long humid paths (a slightly negative optical depth).

use super::{Edit, Source, TextLine, push_row, read_card, text_lines};
use crate::ParseError;
use crate::legacy::Position;

/// What card 1, card 3 and card 4 of a run's header say.
#[derive(Debug, Clone, PartialEq)]
pub struct RunHeader {
    /// MODEL (1–7, 0).
    pub model: i64,
    /// ITYPE (1–3).
    pub itype: i64,
    /// IEMSCT (0–3): what the table holds.
    pub iemsct: i64,
    /// The model atmosphere's name as LOWTRAN prints it (`1976 U S STANDARD`).
    pub model_name: String,
    /// Card 3 as LOWTRAN completed it: H1, H2 in km, the zenith angle at H1 in degrees and
    /// the path's length in km. `None` for MODEL = 0, whose header has no card 3.
    pub path: Option<[f64; 4]>,
    /// Card 4: V1, V2, DV in cm⁻¹, each `None` where LOWTRAN printed asterisks (the value
    /// overflowed `F10.3`).
    pub spectral: [Option<f64>; 3],
}

/// One run's spectral table, column by column.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectralTable {
    /// The columns' names, in order (the first is `FREQ`).
    pub names: Vec<&'static str>,
    /// `columns[c][row]`; `columns[0]` is the wavenumber in cm⁻¹, strictly increasing.
    pub columns: Vec<Vec<f64>>,
    /// Where each row is.
    pub positions: Vec<Position>,
}

impl SpectralTable {
    /// Wavenumbers, cm⁻¹, increasing.
    #[must_use]
    pub fn wavenumber_per_cm(&self) -> &[f64] {
        &self.columns[0]
    }

    /// Total transmittance of the path, 0–1.
    #[must_use]
    pub fn transmission(&self) -> &[f64] {
        &self.columns[1]
    }

    /// The extraterrestrial solar (or lunar) irradiance on a surface normal to the beam,
    /// W cm⁻² per cm⁻¹: IEMSCT 3's `SOLAR IRRADIANCE` column. (Its `TRANSMITTED SOLAR
    /// IRRADIANCE` is this times [`SpectralTable::transmission`], to the printed digits.)
    #[must_use]
    pub fn extraterrestrial_irradiance(&self) -> Option<&[f64]> {
        (self.names.get(3) == Some(&"SOLAR IRRADIANCE")).then(|| self.columns[3].as_slice())
    }

    /// The solar (or lunar) radiance scattered into the path, W cm⁻² sr⁻¹ per cm⁻¹:
    /// IEMSCT 2's `SCATTERED RADIANCE` (single scattering unless IMULT = 1).
    #[must_use]
    pub fn scattered_radiance(&self) -> Option<&[f64]> {
        (self.names.get(3) == Some(&"SCATTERED RADIANCE")).then(|| self.columns[3].as_slice())
    }

    /// The thermal (atmospheric) radiance of the path, W cm⁻² sr⁻¹ per cm⁻¹: IEMSCT 1 and 2.
    #[must_use]
    pub fn thermal_radiance(&self) -> Option<&[f64]> {
        matches!(
            self.names.get(2),
            Some(&"ATMOS RADIANCE" | &"THERMAL RADIANCE")
        )
        .then(|| self.columns[2].as_slice())
    }
}

/// One calculation's block.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// The header cards; `None` for a run LOWTRAN rejected.
    pub header: Option<RunHeader>,
    /// The table; `None` for a run LOWTRAN rejected.
    pub table: Option<SpectralTable>,
    /// Where the block starts.
    pub position: Position,
}

impl Run {
    /// Whether LOWTRAN rejected this calculation (its block has no table).
    #[must_use]
    pub fn failed(&self) -> bool {
        self.table.is_none()
    }
}

/// A LOWTRAN7 `TAPE7`.
#[derive(Debug, Clone, PartialEq)]
pub struct LowtranTape7 {
    /// One run per calculation of the deck, in order.
    pub runs: Vec<Run>,
}

/// The largest transmittance the reader takes: LOWTRAN7 prints values a little above 1
/// (1.0002 for a 1 m tropical path); users of the table clamp them to 1.
pub const TRANSMITTANCE_MAX: f64 = 1.01;

const TRANSMITTANCE: [&str; 13] = [
    "FREQ",
    "TOTAL TRANS",
    "H2O TRANS",
    "CO2+ TRANS",
    "OZONE TRANS",
    "TRACE TRANS",
    "N2 CONT TRANS",
    "H2O CONT TRANS",
    "MOL SCAT TRANS",
    "AER-HYD TRANS",
    "HNO3 TRANS",
    "AER-HYD ABS TRANS",
    "-LN TRANS",
];
const THERMAL: [&str; 4] = ["FREQ", "TRANS", "ATMOS RADIANCE", "-LN TRANS"];
const SCATTERED: [&str; 11] = [
    "FREQ",
    "TRANS",
    "THERMAL RADIANCE",
    "SCATTERED RADIANCE",
    "SINGLE SCATTERED RADIANCE",
    "GROUND REFLECTED RADIANCE",
    "GROUND REFLECTED SINGLE SCATTERED RADIANCE",
    "TOTAL RADIANCE",
    "GROUND TRANS 1",
    "GROUND TRANS 2",
    "-LN TRANS",
];
const SOLAR: [&str; 5] = [
    "FREQ",
    "TRANS",
    "TRANSMITTED SOLAR IRRADIANCE",
    "SOLAR IRRADIANCE",
    "-LN TRANS",
];

fn columns_for(iemsct: i64) -> &'static [&'static str] {
    match iemsct {
        0 => &TRANSMITTANCE,
        1 => &THERMAL,
        2 => &SCATTERED,
        _ => &SOLAR,
    }
}

/// The column header lines LOWTRAN7 writes to TAPE7 (its FORMATs 931, 932 and 933, in
/// `lowtran7.f`), as words, and the IEMSCT values each is written for.
const COLUMN_HEADERS: [(&str, &[i64]); 3] = [
    (
        "FREQ TOTAL H2O CO2+ OZONE TRACE N2 CON H2O CON MOL SCAT AER-HYD HNO3 AER-HYD",
        &[0],
    ),
    (
        "FREQ TRANS ATMOS PATH SINGLE GROUND DIRECT TOTAL RAD",
        &[1, 2],
    ),
    ("FREQ TRANS SOL TR SOLAR", &[3]),
];

/// The IEMSCT values a column header line is written for: its words must be exactly one
/// of LOWTRAN's headers (`SOL TX` for `SOL TR`, or a column added, is not LOWTRAN's).
fn header_kind(line: &str) -> Option<&'static [i64]> {
    let words: Vec<&str> = line.split_whitespace().collect();
    COLUMN_HEADERS
        .iter()
        .find(|(h, _)| h.split_whitespace().eq(words.iter().copied()))
        .map(|&(_, kinds)| kinds)
}

fn is_end(line: &TextLine<'_>) -> bool {
    line.text.trim() == "-9999."
}

fn read_header(src: Source<'_>, lines: &[TextLine<'_>]) -> Result<RunHeader, ParseError> {
    let card1 = read_card(
        src,
        &lines[0],
        &[
            (Edit::I(5), "MODEL"),
            (Edit::I(5), "ITYPE"),
            (Edit::I(5), "IEMSCT"),
        ],
    )
    .map_err(|mut e| {
        e.message = format!("card 1 of the run's header: {}", e.message);
        e
    })?;
    #[allow(clippy::cast_possible_truncation)]
    let (model, itype, iemsct) = (card1[0] as i64, card1[1] as i64, card1[2] as i64);
    if !(0..=3).contains(&iemsct) {
        return Err(src.error(
            lines[0].offset_of_column(10),
            5,
            format!("expected IEMSCT 0 to 3 in card 1 of the run's header, found {iemsct}"),
        ));
    }
    // Card 1, 2, 2A, 2B, model line, card 3 (or, MODEL 0, the HMDLZ line), 3A1, 3A2, card 4, IRPT.
    let model_line = &lines[4];
    let model_name = model_line.field(5, 72).trim().to_owned();
    let path = if model == 0 {
        None
    } else {
        let v = read_card(
            src,
            &lines[5],
            &[
                (Edit::F(10, 3), "H1"),
                (Edit::F(10, 3), "H2"),
                (Edit::F(10, 3), "ANGLE"),
                (Edit::F(10, 3), "RANGE"),
            ],
        )
        .map_err(|mut e| {
            e.message = format!("card 3 of the run's header: {}", e.message);
            e
        })?;
        Some([v[0], v[1], v[2], v[3]])
    };
    let c4 = &lines[8];
    let spectral = [0, 10, 20].map(|col| {
        let f = c4.field(col, 10);
        if f.contains('*') {
            None
        } else {
            super::read_real(f, 3)
        }
    });
    if spectral
        .iter()
        .enumerate()
        .any(|(i, v)| v.is_none() && !c4.field(i * 10, 10).contains('*'))
    {
        return Err(src.error(
            c4.offset,
            c4.text.len(),
            "expected card 4 of the run's header, V1 V2 DV (3F10.3)",
        ));
    }
    Ok(RunHeader {
        model,
        itype,
        iemsct,
        model_name,
        path,
        spectral,
    })
}

fn read_rows(
    src: Source<'_>,
    rows: &[TextLine<'_>],
    names: &'static [&'static str],
    iemsct: i64,
) -> Result<SpectralTable, ParseError> {
    let n = names.len();
    let mut columns = vec![Vec::with_capacity(rows.len()); n];
    let mut positions = Vec::with_capacity(rows.len());
    for row in rows {
        let count = |found| {
            format!(
                "expected {n} columns ({}), as the header and IEMSCT = {iemsct} say, found {found}",
                names.join(", ")
            )
        };
        push_row(src, row, names, &mut columns, count, |c, name, v| {
            // LOWTRAN7 prints transmittances a little above 1 (1.0002) on paths of a few
            // metres, where its continuum gives a slightly negative optical depth.
            if c == 1 && !(0.0..=TRANSMITTANCE_MAX).contains(&v) {
                Some(format!(
                    "expected a transmittance from 0 to 1 (LOWTRAN prints up to {TRANSMITTANCE_MAX}), found {v}"
                ))
            } else if c + 1 < n && name.contains("RADIANCE") && v < 0.0 {
                Some(format!("expected a radiance of 0 or more, found {v}"))
            } else {
                None
            }
        })?;
        positions.push(row.position());
    }
    Ok(SpectralTable {
        names: names.to_vec(),
        columns,
        positions,
    })
}

/// Reads a LOWTRAN7 `TAPE7`.
///
/// # Errors
/// A [`ParseError`] at the place: an empty file, a MODTRAN `tape7` (a letter in column 1:
/// read it with [`super::modtran_tape7`]), a block without its ` -9999.` (a truncated
/// file), a header shorter than LOWTRAN writes, a column header that disagrees with card
/// 1's IEMSCT, a row whose count of columns is not the header's, a field that is not a
/// number, wavenumbers that repeat or do not increase, a transmittance outside 0–1 or a
/// negative radiance.
pub fn parse(file: &str, text: &str) -> Result<LowtranTape7, ParseError> {
    let src = Source { file, text };
    let lines = text_lines(text);
    let first = lines.iter().find(|l| !l.text.trim().is_empty());
    let Some(first) = first else {
        return Err(src.error(0, 0, "expected a LOWTRAN7 TAPE7, found an empty file"));
    };
    if first
        .text
        .trim_start()
        .starts_with(|c: char| c.is_ascii_alphabetic())
    {
        return Err(src.error(
            first.offset,
            1,
            "expected a LOWTRAN7 TAPE7 (card 1: 13 integers), found a letter: this looks like a MODTRAN tape7",
        ));
    }
    let mut runs = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if lines[i].text.trim().is_empty() {
            i += 1;
            continue;
        }
        let start = i;
        let Some(end) = (start..lines.len()).find(|&k| is_end(&lines[k])) else {
            return Err(src.eof_error(format!(
                "expected ` -9999.` ending run {} (from line {}), found the end of the file: the TAPE7 is truncated",
                runs.len() + 1,
                lines[start].number
            )));
        };
        let block = &lines[start..end];
        let position = lines[start].position();
        if block.len() == 1 {
            // A rejected calculation: only the next IRPT.
            runs.push(Run {
                header: None,
                table: None,
                position,
            });
            i = end + 1;
            continue;
        }
        if block.len() < 11 {
            let l = &lines[end];
            return Err(src.error(
                l.offset,
                l.text.len(),
                format!(
                    "expected a run's 10 header lines and a column header before ` -9999.`, found {} lines",
                    block.len()
                ),
            ));
        }
        let header = read_header(src, block)?;
        let col_line = &block[10];
        let Some(kinds) = header_kind(col_line.text) else {
            return Err(src.error(
                col_line.offset,
                col_line.text.len(),
                format!(
                    "expected one of the column headers LOWTRAN7 writes (`{}`, `{}` or `{}`)",
                    COLUMN_HEADERS[0].0, COLUMN_HEADERS[1].0, COLUMN_HEADERS[2].0
                ),
            ));
        };
        if !kinds.contains(&header.iemsct) {
            return Err(src.error(
                col_line.offset,
                col_line.text.len(),
                format!(
                    "this column header is not the one LOWTRAN writes for IEMSCT = {} (card 1 of the run, line {})",
                    header.iemsct, block[0].number
                ),
            ));
        }
        let table = read_rows(src, &block[11..], columns_for(header.iemsct), header.iemsct)?;
        runs.push(Run {
            header: Some(header),
            table: Some(table),
            position,
        });
        i = end + 1;
    }
    Ok(LowtranTape7 { runs })
}

#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    const HEAD: &str =
        "    6    2    1    0    6    6    6    6    6    6    1    0    0   0.000   0.00
    0    1    1    0    0    0     0.000     0.000     0.000     0.000     0.000
   -99.000   -99.000   -99.000       -99
   -99.000   -99.000   -99.000
   331976 U S STANDARD   
     1.000     0.001   180.000     0.999     0.000     0.000    0
  -99  -99  -99  -99
   -99.000   -99.000   -99.000   -99.000   -99.000   -99.000   -99.000   -99.000
   710.000  1250.000     5.000
    3
  FREQ   TRANS     ATMOS   PATH     SINGLE   GROUND DIRECT   TOTAL RAD
";
    const ROWS: &str = "   710.  0.1245 1.07E-05                                                                        2.083E+00
   715.  0.1915 9.79E-06                                                                        1.653E+00
 -9999.
";

    #[test]
    fn a_radiance_run_and_a_rejected_one() {
        let text = format!("{HEAD}{ROWS}    0\n -9999.\n");
        let t = parse("TAPE7", &text).unwrap();
        assert_eq!(t.runs.len(), 2);
        let r = &t.runs[0];
        let h = r.header.as_ref().unwrap();
        assert_eq!((h.model, h.itype, h.iemsct), (6, 2, 1));
        assert_eq!(h.model_name, "1976 U S STANDARD");
        assert_eq!(h.path, Some([1.0, 0.001, 180.0, 0.999]));
        assert_eq!(h.spectral, [Some(710.0), Some(1250.0), Some(5.0)]);
        let tab = r.table.as_ref().unwrap();
        assert_eq!(tab.wavenumber_per_cm(), [710.0, 715.0]);
        assert_eq!(tab.transmission(), [0.1245, 0.1915]);
        assert_eq!(tab.thermal_radiance().unwrap(), [1.07e-5, 9.79e-6]);
        assert_eq!(tab.positions[1].line, 13);
        assert!(t.runs[1].failed());
        assert_eq!(t.runs[1].position.line, 15);
    }

    #[test]
    fn a_direct_solar_run_gives_its_transmittance_and_the_extraterrestrial_irradiance() {
        // LOWTRAN7's TAPE7 of a deck with IEMSCT = 3: US Standard 1976, from 1 m up toward
        // a sun 30 deg from the zenith on day 172 (its first and a middle row).
        let text = "    6    3    3    0    6    6    6    6    6    6    1    0    0   0.000   0.00
    0    1    1    0    0    0     0.000     0.000     0.000     0.000     0.000
   -99.000   -99.000   -99.000       -99
   -99.000   -99.000   -99.000
   331976 U S STANDARD   
     0.001   100.000    30.000   115.182     0.510     0.000    0
  -99  -99  172    0
   -99.000   -99.000   -99.000   -99.000   -99.000   -99.000     0.000   -99.000
  2000.000  3340.000    20.000
    0
  FREQ   TRANS     SOL TR  SOLAR    
  2000.  0.2657 2.44E-07 9.18E-07                                                               1.325E+00
  2300.  0.0000 4.96E-17 1.25E-06                                                               2.395E+01
 -9999.
";
        let t = parse("TAPE7", text).unwrap();
        let r = &t.runs[0];
        assert_eq!(r.header.as_ref().unwrap().iemsct, 3);
        let tab = r.table.as_ref().unwrap();
        assert_eq!(tab.names[2], "TRANSMITTED SOLAR IRRADIANCE");
        assert_eq!(tab.transmission(), [0.2657, 0.0]);
        assert_eq!(
            tab.extraterrestrial_irradiance().unwrap(),
            [9.18e-7, 1.25e-6]
        );
        assert_eq!(tab.columns[2], [2.44e-7, 4.96e-17]);
        assert!(tab.thermal_radiance().is_none());
        let thermal = parse("TAPE7", &format!("{HEAD}{ROWS}")).unwrap();
        assert!(
            thermal.runs[0]
                .table
                .as_ref()
                .unwrap()
                .extraterrestrial_irradiance()
                .is_none()
        );
    }

    #[test]
    fn crlf_line_ends_read_the_same() {
        let text = format!("{HEAD}{ROWS}").replace('\n', "\r\n");
        assert_eq!(
            parse("TAPE7", &text).unwrap(),
            parse("TAPE7", &format!("{HEAD}{ROWS}")).unwrap()
        );
    }

    #[test]
    fn bad_tables_are_refused_at_their_place() {
        let truncated = format!(
            "{HEAD}   710.  0.1245 1.07E-05                                                                        2.083E+00\n"
        );
        let e = parse("t7", &truncated).unwrap_err();
        assert!(e.message.contains("truncated"), "{}", e.message);
        assert_eq!(e.line, 12);
        let short = format!("{HEAD}   710.  0.1245 1.07E-05\n -9999.\n");
        let e = parse("t7", &short).unwrap_err();
        assert!(e.message.contains("expected 4 columns"), "{}", e.message);
        assert_eq!((e.line, e.column), (12, 25));
        let repeated = format!(
            "{HEAD}   710.  0.1245 1.07E-05 2.083E+00\n   710.  0.1245 1.07E-05 2.083E+00\n -9999.\n"
        );
        let e = parse("t7", &repeated).unwrap_err();
        assert_eq!((e.line, e.column), (13, 4));
        assert!(e.message.contains("repeated"), "{}", e.message);
        let falling = format!(
            "{HEAD}   715.  0.1245 1.07E-05 2.083E+00\n   710.  0.1245 1.07E-05 2.083E+00\n -9999.\n"
        );
        assert!(
            parse("t7", &falling)
                .unwrap_err()
                .message
                .contains("increase")
        );
        let garbled = format!("{HEAD}   715.  0.1245 ******** 2.083E+00\n -9999.\n");
        let e = parse("t7", &garbled).unwrap_err();
        assert_eq!((e.line, e.column), (12, 17));
        let wrong_mode = HEAD.replace("    6    2    1    0", "    6    2    0    0") + ROWS;
        assert!(
            parse("t7", &wrong_mode)
                .unwrap_err()
                .message
                .contains("IEMSCT = 0")
        );
        // A header that is not LOWTRAN's, word for word: a renamed column, a misspelt
        // one, one added. (LOWTRAN's FORMAT 932 line, in HEAD, reads.)
        for renamed in [
            "  FREQ   TRANS     ATMOS   PAHT     SINGLE   GROUND DIRECT   TOTAL RAD",
            "  FREQ   TRANS     ATMOS   PATH     SINGLE   GROUND DIRECT   TOTAL RAD  EXTRA",
            "  FREQ   TRANS     ATMOS   PATH",
        ] {
            let text = HEAD.replace(
                "  FREQ   TRANS     ATMOS   PATH     SINGLE   GROUND DIRECT   TOTAL RAD",
                renamed,
            ) + ROWS;
            let e = parse("t7", &text).unwrap_err();
            assert_eq!((e.line, e.column), (11, 1), "{renamed}: {}", e.message);
            assert!(
                e.message.contains("column headers LOWTRAN7 writes"),
                "{}",
                e.message
            );
        }
        assert!(parse("t7", "").is_err());
        assert!(
            parse("t7", "T F 6\n")
                .unwrap_err()
                .message
                .contains("MODTRAN")
        );
    }
}
