//! LOWTRAN7's `TAPE6`, the printed output: what irsig reads of it is each calculation's
//! spectral table, its integrated values and LOWTRAN's messages (why it rejected a path).
//! Spec page: `formats/radtran/lowtran-tape6.md`.
//!
//! TAPE6 is a line-printer listing: column 1 is a carriage-control character (`1` new
//! page, `0` blank line before), then the echo of each card (`0 CARD 1  *****  …`), the
//! profiles, the path geometry, the spectral table in pages, and the integrated values:
//!
//! ```text
//! 0   FREQ WAVLEN   ATMOS RADIANCE       INTEGRAL TOTAL
//!   (CM-1) (MICRN)  (CM-1)    (MICRN)   (CM-1)    TRANS
//!
//!     710.  14.085  1.07E-05  5.37E-04  2.66E-05   0.1245
//! 0INTEGRATED ABSORPTION FROM  710 TO 1250 CM-1 =     87.10 CM-1
//!  AVERAGE TRANSMITTANCE =0.8387
//! 0INTEGRATED RADIANCE =  7.830E-04 WATTS CM-2 STER-1
//! 0 CARD 5 *****    3
//! ```
//!
//! Each calculation ends with the echo of card 5 (`0 CARD 5 *****`), so that line splits
//! the file into runs, in the deck's order. A run whose path LOWTRAN cannot make says
//! `GEO:  IERROR NE 0` and has no table.
//!
//! Numbers are read by column, with the Fortran formats LOWTRAN7 prints them with (as the
//! card deck's reader reads its cards), never by splitting words: a blank field is an
//! error, not the next field moved left.
//!
//! | line | LOWTRAN7 format | read |
//! | --- | --- | --- |
//! | card 1 echo | `'0 CARD 1  *****',13I5,…` (1111) | IEMSCT, columns 26-30 |
//! | profile row | `I4,F9.2,F9.3,F7.1,…` (905, 906) | I 1-4, Z 5-13, P 14-22, T 23-29 |
//! | IEMSCT 1 row | `1X,F7.0,F8.3,3E10.2,F9.4` (916) | columns 2-8, 9-16, 17-26, 27-36, 37-46, 47-55 |
//! | IEMSCT 0 row | `1X,F7.0,F8.3,11F9.4,F12.3` (906) | columns 2-8, 9-16, 11 × 9 from 17, 116-127 |
//! | IEMSCT 2 row | `1X,F7.0,F8.3,1P9E10.2,0PF9.4` (926) | columns 2-8, 9-16, 9 × 10 from 17, 107-115 |
//! | IEMSCT 2 row, IMULT 1 | `1X,F6.0,F8.3,1P11E10.2,0PF7.4` (928) | columns 2-7, 8-15, 11 × 10 from 16, 126-132 |
//! | IEMSCT 3 row | `1X,F7.0,F8.3,1P6E10.2,0PF9.4` (936) | columns 2-8, 9-16, 6 × 10 from 17, 77-85 |
//! | integrated absorption | `'0INTEGRATED ABSORPTION FROM',I5,' TO',I5,' CM-1 =',F10.2` (740) | columns 48-57 |
//! | average transmittance | `' AVERAGE TRANSMITTANCE =',F6.4` (740) | columns 25-30 |
//! | integrated radiance | `'0INTEGRATED RADIANCE = ',E10.3` (750) | columns 24-33 |
//! | integrated irradiance | `'0INTEGRATED IRRADIANCE = ',E10.3` (755) | columns 26-35 |
//!
//! Which table a run has is told by its column header (formats 900, 910, 920, 921, 930),
//! and must be the one of the run's IEMSCT.

use super::lowtran_tape7::TRANSMITTANCE_MAX;
use super::{Source, TextLine, read_real, text_lines};
use crate::ParseError;
use crate::legacy::Position;

mod reader;

use reader::Reader;

/// A message LOWTRAN printed for a run: an error, a warning or a value it reset.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    /// The text, without the carriage-control character.
    pub text: String,
    /// Where it is.
    pub position: Position,
}

/// A run's spectral table, column by column.
#[derive(Debug, Clone, PartialEq)]
pub struct Tape6Table {
    /// The columns' names; the first two are `FREQ` (cm⁻¹) and `WAVELENGTH` (µm).
    pub names: Vec<&'static str>,
    /// `columns[c][row]`, wavenumbers increasing.
    pub columns: Vec<Vec<f64>>,
}

impl Tape6Table {
    /// The column named `name` (one of [`Tape6Table::names`]).
    #[must_use]
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.names
            .iter()
            .position(|n| *n == name)
            .map(|i| self.columns[i].as_slice())
    }

    /// Wavenumbers, cm⁻¹, increasing.
    #[must_use]
    pub fn wavenumber_per_cm(&self) -> &[f64] {
        &self.columns[0]
    }

    /// The path's total transmittance, 0-1 (every table's last transmittance column).
    #[must_use]
    pub fn transmission(&self) -> Option<&[f64]> {
        self.column("TRANS").or_else(|| self.column("TOTAL TRANS"))
    }

    /// The thermal radiance of the path, W cm⁻² sr⁻¹ per cm⁻¹ (IEMSCT 1 and 2).
    #[must_use]
    pub fn thermal_radiance(&self) -> Option<&[f64]> {
        self.column("RADIANCE PER CM-1")
            .or_else(|| self.column("ATMOS RADIANCE PER CM-1"))
    }

    /// The sunlight scattered into the path, W cm⁻² sr⁻¹ per cm⁻¹: IEMSCT 2's `PATH
    /// SCATTERED` per cm⁻¹ (single scattering, and multiple scattering with IMULT = 1).
    #[must_use]
    pub fn scattered_radiance(&self) -> Option<&[f64]> {
        self.column("PATH SCATTERED RADIANCE PER CM-1")
    }

    /// The single-scattered part of [`Tape6Table::scattered_radiance`], W cm⁻² sr⁻¹ per
    /// cm⁻¹: printed by an IEMSCT 2 run with IMULT = 1 only (`S SCAT`).
    #[must_use]
    pub fn single_scattered_radiance(&self) -> Option<&[f64]> {
        self.column("SINGLE SCATTERED RADIANCE PER CM-1")
    }

    /// The total radiance of an IEMSCT 2 run, W cm⁻² sr⁻¹ per cm⁻¹: thermal, scattered
    /// and ground-reflected.
    #[must_use]
    pub fn total_radiance(&self) -> Option<&[f64]> {
        self.column("TOTAL RADIANCE PER CM-1")
    }

    /// The solar irradiance transmitted along the path, on a surface normal to the beam,
    /// W cm⁻² per cm⁻¹: IEMSCT 3's `TRANSMITTED` per cm⁻¹.
    #[must_use]
    pub fn transmitted_solar_irradiance(&self) -> Option<&[f64]> {
        self.column("TRANSMITTED SOLAR IRRADIANCE PER CM-1")
    }

    /// The extraterrestrial solar (or lunar) irradiance, on a surface normal to the beam,
    /// W cm⁻² per cm⁻¹: IEMSCT 3's `SOLAR` per cm⁻¹.
    #[must_use]
    pub fn extraterrestrial_irradiance(&self) -> Option<&[f64]> {
        self.column("SOLAR IRRADIANCE PER CM-1")
    }
}

/// One calculation's part of TAPE6.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Tape6Run {
    /// IEMSCT of the run (card 1's echo, or the last one before a repeat).
    pub iemsct: Option<i64>,
    /// The spectral table, if LOWTRAN made one.
    pub table: Option<Tape6Table>,
    /// `INTEGRATED ABSORPTION FROM … = X CM-1`: ∫(1 − τ) dν over the range, cm⁻¹.
    pub integrated_absorption_per_cm: Option<f64>,
    /// `AVERAGE TRANSMITTANCE = X`.
    pub average_transmittance: Option<f64>,
    /// `INTEGRATED RADIANCE = X WATTS CM-2 STER-1`: ∫ L dν, W cm⁻² sr⁻¹ (IEMSCT 2: of
    /// the total, thermal plus scattered plus ground-reflected).
    pub integrated_radiance_w_cm2_sr: Option<f64>,
    /// `INTEGRATED IRRADIANCE = X WATTS CM-2` (IEMSCT 3): ∫ of the transmitted solar
    /// irradiance dν, W cm⁻².
    pub integrated_irradiance_w_cm2: Option<f64>,
    /// Errors, warnings and resets LOWTRAN printed.
    pub messages: Vec<Message>,
    /// The first `ATMOSPHERIC PROFILES` table: altitude (km), pressure (mb) and
    /// temperature (K) of each of LOWTRAN's levels (a run after `IRPT = 3` has none).
    pub profile: Vec<[f64; 3]>,
    /// `BENDING = X DEG` of the run's first `SUMMARY OF THE GEOMETRY CALCULATION`: how far
    /// refraction turns the line of sight between H1 and its far end, degrees. Card 3's
    /// ANGLE is the apparent zenith angle at H1; ANGLE + BENDING is the direction the ray
    /// leaves the atmosphere in (of a direct solar run, the sun's geometric zenith).
    pub bending_deg: Option<f64>,
    /// Whether LOWTRAN gave up on the path (`GEO:  IERROR NE 0`).
    pub rejected: bool,
    /// Where the run starts.
    pub position: Position,
}

/// A LOWTRAN7 `TAPE6`.
#[derive(Debug, Clone, PartialEq)]
pub struct LowtranTape6 {
    /// One run per calculation, in order.
    pub runs: Vec<Tape6Run>,
}

const RADIANCE: [&str; 6] = [
    "FREQ",
    "WAVELENGTH",
    "RADIANCE PER CM-1",
    "RADIANCE PER MICRON",
    "INTEGRAL",
    "TRANS",
];
const TRANSMITTANCE: [&str; 14] = [
    "FREQ",
    "WAVELENGTH",
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
    "AER-HYD ABS",
    "INTEGRATED ABSORPTION",
];

/// IEMSCT 2's table (FORMAT 926, header 920): each radiance per cm⁻¹ and per µm.
const SCATTERED: [&str; 12] = [
    "FREQ",
    "WAVELENGTH",
    "ATMOS RADIANCE PER CM-1",
    "ATMOS RADIANCE PER MICRON",
    "PATH SCATTERED RADIANCE PER CM-1",
    "PATH SCATTERED RADIANCE PER MICRON",
    "GROUND REFLECTED RADIANCE PER CM-1",
    "GROUND REFLECTED RADIANCE PER MICRON",
    "TOTAL RADIANCE PER CM-1",
    "TOTAL RADIANCE PER MICRON",
    "INTEGRAL",
    "TRANS",
];
/// IEMSCT 2's table with multiple scattering (FORMAT 928, header 921): the scattered
/// radiance's single-scattered part (`S SCAT`) and the ground-reflected radiance's direct
/// part (`DIRECT`) added, per cm⁻¹.
const SCATTERED_MULTIPLE: [&str; 14] = [
    "FREQ",
    "WAVELENGTH",
    "ATMOS RADIANCE PER CM-1",
    "ATMOS RADIANCE PER MICRON",
    "PATH SCATTERED RADIANCE PER CM-1",
    "PATH SCATTERED RADIANCE PER MICRON",
    "SINGLE SCATTERED RADIANCE PER CM-1",
    "GROUND REFLECTED RADIANCE PER CM-1",
    "GROUND REFLECTED RADIANCE PER MICRON",
    "DIRECT GROUND REFLECTED RADIANCE PER CM-1",
    "TOTAL RADIANCE PER CM-1",
    "TOTAL RADIANCE PER MICRON",
    "INTEGRAL",
    "TRANS",
];
/// IEMSCT 3's table (FORMAT 936, header 930): irradiances per cm⁻¹ and per µm, and the
/// running integrals (W cm⁻²) of the transmitted and the extraterrestrial one.
const SOLAR: [&str; 9] = [
    "FREQ",
    "WAVELENGTH",
    "TRANSMITTED SOLAR IRRADIANCE PER CM-1",
    "TRANSMITTED SOLAR IRRADIANCE PER MICRON",
    "SOLAR IRRADIANCE PER CM-1",
    "SOLAR IRRADIANCE PER MICRON",
    "INTEGRATED TRANSMITTED",
    "INTEGRATED SOLAR",
    "TRANS",
];

/// A numeric field of a printed line: its first column (0-based), its width, the decimals
/// of its edit descriptor (for a field printed without a point) and what it holds.
#[derive(Debug, Clone, Copy)]
struct Field {
    start: usize,
    width: usize,
    decimals: u32,
    edit: &'static str,
}

const fn field(start: usize, width: usize, decimals: u32, edit: &'static str) -> Field {
    Field {
        start,
        width,
        decimals,
        edit,
    }
}

/// FORMAT 916 of LOWTRAN7's `TRANS` (IEMSCT 1): `1X,F7.0,F8.3,1P3E10.2,0PF9.4`.
const RADIANCE_ROW: [Field; 6] = [
    field(1, 7, 0, "F7.0"),
    field(8, 8, 3, "F8.3"),
    field(16, 10, 2, "E10.2"),
    field(26, 10, 2, "E10.2"),
    field(36, 10, 2, "E10.2"),
    field(46, 9, 4, "F9.4"),
];

/// FORMAT 906 of LOWTRAN7's `TRANS` (IEMSCT 0): `1X,F7.0,F8.3,11F9.4,F12.3`.
const TRANSMITTANCE_ROW: [Field; 14] = [
    field(1, 7, 0, "F7.0"),
    field(8, 8, 3, "F8.3"),
    field(16, 9, 4, "F9.4"),
    field(25, 9, 4, "F9.4"),
    field(34, 9, 4, "F9.4"),
    field(43, 9, 4, "F9.4"),
    field(52, 9, 4, "F9.4"),
    field(61, 9, 4, "F9.4"),
    field(70, 9, 4, "F9.4"),
    field(79, 9, 4, "F9.4"),
    field(88, 9, 4, "F9.4"),
    field(97, 9, 4, "F9.4"),
    field(106, 9, 4, "F9.4"),
    field(115, 12, 3, "F12.3"),
];

/// `F7.0,F8.3` from column 2, then `count` fields `E10.2`, then `F9.4`: FORMATs 926 and
/// 936 of LOWTRAN7's `TRANS`.
const fn e_row<const N: usize>() -> [Field; N] {
    let mut row = [field(1, 7, 0, "F7.0"); N];
    row[1] = field(8, 8, 3, "F8.3");
    let mut k = 2;
    while k + 1 < N {
        row[k] = field(16 + 10 * (k - 2), 10, 2, "E10.2");
        k += 1;
    }
    row[N - 1] = field(16 + 10 * (N - 3), 9, 4, "F9.4");
    row
}

/// FORMAT 926 (IEMSCT 2): `1X,F7.0,F8.3,1P9E10.2,0PF9.4`.
const SCATTERED_ROW: [Field; 12] = e_row::<12>();
/// FORMAT 936 (IEMSCT 3): `1X,F7.0,F8.3,1P6E10.2,0PF9.4`.
const SOLAR_ROW: [Field; 9] = e_row::<9>();
/// FORMAT 928 (IEMSCT 2, IMULT 1): `1X,F6.0,F8.3,1P11E10.2,0PF7.4`, one column narrower
/// at each end.
const SCATTERED_MULTIPLE_ROW: [Field; 14] = {
    let mut row = [field(1, 6, 0, "F6.0"); 14];
    row[1] = field(7, 8, 3, "F8.3");
    let mut k = 2;
    while k < 13 {
        row[k] = field(15 + 10 * (k - 2), 10, 2, "E10.2");
        k += 1;
    }
    row[13] = field(125, 7, 4, "F7.4");
    row
};

/// FORMATs 905 and 906 of LOWTRAN7's `STDMDL`: `I4,0PF9.2,F9.3,F7.1,…`, the level's
/// number, then Z (km), P (mb) and T (K).
const PROFILE_Z_P_T: [Field; 3] = [
    field(4, 9, 2, "F9.2"),
    field(13, 9, 3, "F9.3"),
    field(22, 7, 1, "F7.1"),
];

/// FORMAT 1111 of `DRIVER`, the echo of card 1: `'0 CARD 1  *****',13I5,…`; IEMSCT is the
/// third number.
const CARD1_ECHO: &str = "0 CARD 1  *****";
const IEMSCT_COLUMN: usize = 25;

/// FORMAT 740: `'0INTEGRATED ABSORPTION FROM',I5,' TO',I5,' CM-1 =',F10.2,' CM-1'`.
const ABSORPTION: Field = field(47, 10, 2, "F10.2");
/// FORMAT 740: `' AVERAGE TRANSMITTANCE =',F6.4`.
const AVERAGE: Field = field(24, 6, 4, "F6.4");
/// FORMAT 750: `'0INTEGRATED RADIANCE = ',1PE10.3,' WATTS CM-2 STER-1'`.
const RADIANCE_SUM: Field = field(23, 10, 3, "E10.3");
/// FORMAT 755: `'0INTEGRATED IRRADIANCE = ',1PE10.3,' WATTS CM-2 '`.
const IRRADIANCE_SUM: Field = field(25, 10, 3, "E10.3");

/// FORMAT 4226 of `GEO`'s summary: `10X,'BENDING = ',F10.3,' DEG'`.
const BENDING: Field = field(20, 10, 3, "F10.3");

/// Reads `f` of `line` as a Fortran formatted read does, but a blank field, which LOWTRAN
/// never prints, is an error rather than 0; so is a value that is not a finite number.
fn read_field(
    src: Source<'_>,
    line: &TextLine<'_>,
    f: Field,
    what: &str,
) -> Result<f64, ParseError> {
    let text = line.field(f.start, f.width);
    let trimmed = text.trim();
    let (first, last) = (f.start + 1, f.start + f.width);
    if trimmed.is_empty() {
        return Err(src.error(
            line.offset_of_column(f.start.min(line.text.chars().count())),
            f.width,
            format!(
                "expected {what} ({} in columns {first}-{last}), found a blank field: LOWTRAN7 \
                 prints every field of this line",
                f.edit
            ),
        ));
    }
    let lead = text.chars().take_while(|c| *c == ' ').count();
    // A printed field is right-aligned, a number without blanks: a formatted read would
    // skip inner blanks, and so take the halves of two shifted numbers for one.
    let printed = !text.trim_start().contains(' ') && text.chars().count() == f.width;
    let value = read_real(text, f.decimals).filter(|_| printed);
    value.ok_or_else(|| {
        src.error(
            line.offset_of_column(f.start + lead),
            trimmed.len(),
            format!(
                "expected {what} (a finite number, {} right-aligned in columns {first}-{last}), \
                 found `{trimmed}`",
                f.edit
            ),
        )
    })
}

/// Nothing may follow a row's last field: a longer row is not the table's.
fn end_of_row(
    src: Source<'_>,
    line: &TextLine<'_>,
    after: usize,
    what: &str,
) -> Result<(), ParseError> {
    let rest: String = line.text.chars().skip(after).collect();
    let lead = rest.chars().take_while(|c| c.is_whitespace()).count();
    if rest.trim().is_empty() {
        return Ok(());
    }
    Err(src.error(
        line.offset_of_column(after + lead),
        rest.trim().len(),
        format!(
            "expected the end of {what} after column {after}, found `{}`",
            rest.trim()
        ),
    ))
}

const MESSAGE_WORDS: [&str; 7] = [
    "ERROR",
    "CANNOT",
    "WARNING",
    "RESET",
    "NOT USEABLE",
    "INVALID",
    "IERROR",
];

fn body<'a>(line: &TextLine<'a>) -> &'a str {
    // Column 1 is carriage control.
    line.text.get(1..).unwrap_or("")
}

/// A table's names, its row's fields and the IEMSCT it belongs to.
type Layout = (&'static [&'static str], &'static [Field], i64);

/// The column header lines LOWTRAN7 prints above its spectral tables (FORMATs 900, 910,
/// 920, 921 and 930 of `lowtran7.f`), as words, with the table each starts.
const TABLE_HEADERS: [(&str, Layout); 5] = [
    (
        "FREQ WAVELENGTH TOTAL H2O CO2+ OZONE TRACE N2 CONT H2O CONT MOL SCAT AER-HYD HNO3 \
         AER-HYD INTEGRATED",
        (&TRANSMITTANCE, &TRANSMITTANCE_ROW, 0),
    ),
    (
        "FREQ WAVLEN ATMOS RADIANCE INTEGRAL TOTAL",
        (&RADIANCE, &RADIANCE_ROW, 1),
    ),
    (
        "FREQ WAVLEN ATMOS RADIANCE PATH SCATTERED GROUND REFLECTED TOTAL INTEGRAL TOTAL",
        (&SCATTERED, &SCATTERED_ROW, 2),
    ),
    (
        "FREQ WAVLEN ATMOS RADIANCE PATH SCATTERED RADIANCE GROUND REFLECTED RADIANCE TOTAL \
         RADIANCE INTEGRAL TOTAL",
        (&SCATTERED_MULTIPLE, &SCATTERED_MULTIPLE_ROW, 2),
    ),
    (
        "FREQ WAVLEN TRANSMITTED SOLAR INTEGRATED TOTAL",
        (&SOLAR, &SOLAR_ROW, 3),
    ),
];

/// Whether a line is a spectral table's column header: it starts `FREQ WAVLEN` or `FREQ
/// WAVELENGTH`, as every one LOWTRAN7 prints does.
fn is_table_header(t: &str) -> bool {
    let mut words = t.split_whitespace();
    words.next() == Some("FREQ") && matches!(words.next(), Some("WAVLEN" | "WAVELENGTH"))
}

/// The table a column header line starts, when its words are exactly one of LOWTRAN7's
/// headers (a renamed or added column is not LOWTRAN's, and would be read wrongly).
fn table_layout(t: &str) -> Option<Layout> {
    TABLE_HEADERS
        .iter()
        .find(|(h, _)| h.split_whitespace().eq(t.split_whitespace()))
        .map(|&(_, layout)| layout)
}

/// The largest value a radiance or irradiance column may hold, W cm⁻² (sr⁻¹) per cm⁻¹ or
/// per µm, and the largest integral: 1. The Sun's own irradiance above the atmosphere peaks
/// near 0.2 W cm⁻² µm⁻¹ and totals 0.136 W cm⁻²; a 330 K path's radiance is a
/// thousandth of that. A larger value is an overflow or an edit, not LOWTRAN's.
const FLUX_MAX: f64 = 1.0;

/// The range a column's values must lie in: transmittances 0 to [`TRANSMITTANCE_MAX`] (as
/// in TAPE7), radiances, irradiances and their integrals 0 to [`FLUX_MAX`]; the rest
/// (wavenumber, wavelength, absorption) unchecked here.
fn column_range(name: &str) -> Option<(f64, f64, &'static str)> {
    if name.ends_with("TRANS") {
        Some((0.0, TRANSMITTANCE_MAX, "a transmittance"))
    } else if name.contains("RADIANCE")
        || name == "INTEGRAL"
        || (name.starts_with("INTEGRATED ") && !name.contains("ABSORPTION"))
    {
        Some((0.0, FLUX_MAX, "a radiance or irradiance in W cm-2"))
    } else {
        None
    }
}

/// Where the table being read begins: its column header line.
#[derive(Debug, Clone, Copy)]
struct Opened {
    offset: usize,
    len: usize,
    line: usize,
}

/// A table LOWTRAN7 has ended (with its `INTEGRATED …` line) must have had rows under its
/// column header.
fn check_rows(src: Source<'_>, opened: Option<Opened>, has_rows: bool) -> Result<(), ParseError> {
    match opened {
        Some(o) if !has_rows => Err(src.error(
            o.offset,
            o.len,
            "expected the rows of the table this column header starts, found none before its \
             `INTEGRATED` line",
        )),
        _ => Ok(()),
    }
}

/// A run that ends (at its `CARD 5` echo, or at the file's end) inside a table was cut:
/// LOWTRAN7 ends every table with its `INTEGRATED …` line.
fn check_closed(src: Source<'_>, opened: Option<Opened>, at: usize) -> Result<(), ParseError> {
    match opened {
        Some(o) => Err(src.error(
            at,
            0,
            format!(
                "expected the `INTEGRATED` line that ends the table begun at line {}, found the \
                 run's end: the table was cut",
                o.line
            ),
        )),
        None => Ok(()),
    }
}

/// Reads a LOWTRAN7 `TAPE6`.
///
/// Every mode's table is read: transmittance (IEMSCT 0), thermal radiance (1), with
/// scattered sunlight (2, with or without multiple scattering) and direct solar irradiance
/// (3).
///
/// # Errors
/// A [`ParseError`] at the place: an empty file, a file with no `***** LOWTRAN 7 *****`
/// banner, a table row whose count of numbers is not the table's, a value that is not a
/// finite number (LOWTRAN prints `Infinity` or asterisks when a deck's numbers overflow),
/// wavenumbers that do not increase, an integrated value that is not a number, or a table
/// whose column header is not the one of the run's IEMSCT.
pub fn parse(file: &str, text: &str) -> Result<LowtranTape6, ParseError> {
    let src = Source { file, text };
    let lines = text_lines(text);
    if !lines
        .iter()
        .any(|l| l.text.contains("***** LOWTRAN 7 *****"))
    {
        return Err(src.error(
            0,
            0,
            "expected a LOWTRAN7 TAPE6 (its banner `***** LOWTRAN 7 *****`), found none",
        ));
    }
    let mut reader = Reader::new(src);
    for line in &lines {
        reader.line(line)?;
    }
    reader.finish(text.len())
}

#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    const TEXT: &str = "1                    ***** LOWTRAN 7 *****
0 CARD 1  *****    6    2    1    0    0    0    0    0    0    0    0    0    0   0.000   0.00
1                    RADIANCE(WATTS/CM2-STER-XXX)
0   FREQ WAVLEN   ATMOS RADIANCE       INTEGRAL TOTAL
  (CM-1) (MICRN)  (CM-1)    (MICRN)   (CM-1)    TRANS

    710.  14.085  1.07E-05  5.37E-04  2.66E-05   0.1245
    715.  13.986  9.79E-06  5.00E-04  7.56E-05   0.1915
0INTEGRATED ABSORPTION FROM  710 TO 1250 CM-1 =     87.10 CM-1
 AVERAGE TRANSMITTANCE =0.8387

0INTEGRATED RADIANCE =  7.830E-04 WATTS CM-2 STER-1
0 CARD 5 *****    3
0 CARD 3  *****     3.000     0.001    91.500     0.000     0.000     0.000    0
0H2 IS LESS THAN THE TANGENT HEIGHT FOR THIS PATH AND CANNOT BE REACHED
0GEO:  IERROR NE 0: END THIS CALCULATION AND SKIP TO THE NEXT CASE
0 CARD 5 *****    0
";

    #[test]
    fn tables_integrals_and_messages_per_run() {
        let t = parse("TAPE6", TEXT).unwrap();
        assert_eq!(t.runs.len(), 2);
        let r = &t.runs[0];
        assert_eq!(r.iemsct, Some(1));
        let tab = r.table.as_ref().unwrap();
        assert_eq!(tab.columns[0], [710.0, 715.0]);
        assert_eq!(tab.columns[2], [1.07e-5, 9.79e-6]);
        assert_eq!(tab.columns[5], [0.1245, 0.1915]);
        assert_eq!(r.integrated_absorption_per_cm, Some(87.10));
        assert_eq!(r.average_transmittance, Some(0.8387));
        assert_eq!(r.integrated_radiance_w_cm2_sr, Some(7.830e-4));
        assert!(!r.rejected);
        let f = &t.runs[1];
        assert!(f.rejected && f.table.is_none());
        assert_eq!(f.messages.len(), 2);
        assert!(
            f.messages[0]
                .text
                .starts_with("H2 IS LESS THAN THE TANGENT HEIGHT")
        );
        assert_eq!(f.messages[0].position.line, 15);
    }

    #[test]
    fn non_finite_values_are_refused() {
        let bad = TEXT.replace("0.1915", "Infinity");
        let e = parse("TAPE6", &bad).unwrap_err();
        assert_eq!((e.line, e.column), (8, 50));
        assert!(parse("TAPE6", "hello\n").is_err());
        let short = TEXT.replace("  2.66E-05   0.1245", "");
        let e = parse("TAPE6", &short).unwrap_err();
        assert!(e.message.contains("found a blank field"), "{e}");
        assert_eq!((e.line, e.column), (7, 37));
    }

    /// The head of a TAPE6 with a profile table, as LOWTRAN7 prints it (FORMAT 910, 905).
    const PROFILE: &str = "1                    ***** LOWTRAN 7 *****
0 CARD 1  *****    6    2    1    0    0    0    0    0    0    0    0    0    0   0.000   0.00
1
  ATMOSPHERIC PROFILES

   I     Z       P       T        N2       CNTMSLF MOL SCAT     N-1     O3 (UV)  O2 (UV)
        (KM)    (MB)    (K)            (MOL/CM2 KM)   (-)       (-)  (ATM CM/KM) (ATM CM/KM)

   1     0.00 1013.000  288.2  7.203E-01 1.566E+20 9.475E-01 2.722E-04 2.519E-03 3.535E+04
   2     1.00  898.800  281.7  5.868E-01 7.926E+19 8.601E-01 2.471E-04 2.519E-03 3.079E+04
   3     2.00  795.000  275.2  4.754E-01 3.781E+19 7.788E-01 2.238E-04 2.519E-03 2.678E+04

0 CARD 5 *****    0
";

    #[test]
    fn the_profile_is_read_by_column() {
        let t = parse("TAPE6", PROFILE).unwrap();
        assert_eq!(
            t.runs[0].profile,
            [
                [0.0, 1013.0, 288.2],
                [1.0, 898.8, 281.7],
                [2.0, 795.0, 275.2]
            ]
        );
        // A blank Z in row 2 used to shift P into Z and T into P: an atmosphere at 281.7 K
        // and 898.8 km.
        let blank_z = PROFILE.replace("   2     1.00  898.800", "   2           898.800");
        let e = parse("TAPE6", &blank_z).unwrap_err();
        assert_eq!((e.line, e.column), (10, 5), "{e}");
        assert!(
            e.message
                .contains("level 2's Z in km (F9.2 in columns 5-13), found a blank field"),
            "{e}"
        );
        // Numbers out of their columns are no row of LOWTRAN's either.
        let shifted = PROFILE.replace(
            "   2     1.00  898.800  281.7",
            "   2  1.00  898.800  281.7   ",
        );
        let e = parse("TAPE6", &shifted).unwrap_err();
        assert_eq!((e.line, e.column), (10, 7), "{e}");
        let missing_t = PROFILE.replace("  281.7  5.868E-01", "         5.868E-01");
        let e = parse("TAPE6", &missing_t).unwrap_err();
        assert!(e.message.contains("T in K (F7.1 in columns 23-29)"), "{e}");
        let blank_iemsct = PROFILE.replace("*****    6    2    1", "*****    6    2     ");
        let e = parse("TAPE6", &blank_iemsct).unwrap_err();
        assert_eq!((e.line, e.column), (2, 26), "{e}");
    }

    /// An IEMSCT 3 run's table and integrals as LOWTRAN7 printed them
    /// (formats/radtran/samples/solar.tape6, run 3: two of its six rows, and the integrals
    /// over all six).
    const SUN: &str = "1                    ***** LOWTRAN 7 *****
0 CARD 1  *****    6    3    3    0    0    0    0    0    0    0    0    0    0   0.000   0.00
1                      IRRADIANCE (WATTS/CM2-XXXX)
0  FREQ   WAVLEN      TRANSMITTED           SOLAR           INTEGRATED         TOTAL
  (CM-1) (MICRN)   (CM-1)    (MICRN)   (CM-1)    (MICRN)   TRANS.    SOLAR     TRANS
   2500.   4.000  1.26E-06  7.88E-04  1.52E-06  9.49E-04  1.26E-05  1.52E-05   0.8304
   2520.   3.968  1.32E-06  8.36E-04  1.53E-06  9.74E-04  3.89E-05  4.59E-05   0.8575
0INTEGRATED ABSORPTION FROM 2500 TO 2600 CM-1 =     18.39 CM-1
 AVERAGE TRANSMITTANCE =0.8161

0INTEGRATED IRRADIANCE =  1.268E-04 WATTS CM-2 
0 CARD 5 *****    0
";

    #[test]
    fn a_direct_solar_table_and_its_integral() {
        let t = parse("TAPE6", SUN).unwrap();
        let r = &t.runs[0];
        assert_eq!(r.iemsct, Some(3));
        let tab = r.table.as_ref().unwrap();
        assert_eq!(tab.wavenumber_per_cm(), [2500.0, 2520.0]);
        assert_eq!(
            tab.transmitted_solar_irradiance().unwrap(),
            [1.26e-6, 1.32e-6]
        );
        assert_eq!(
            tab.extraterrestrial_irradiance().unwrap(),
            [1.52e-6, 1.53e-6]
        );
        assert_eq!(tab.transmission().unwrap(), [0.8304, 0.8575]);
        assert_eq!(r.integrated_irradiance_w_cm2, Some(1.268e-4));
        assert!(tab.scattered_radiance().is_none());
    }

    #[test]
    fn bad_solar_tables_are_refused_at_their_place() {
        // Cut in the middle of a row: its SOLAR per micron is blank.
        let cut = &SUN[..SUN.find("  9.74E-04").unwrap()];
        let e = parse("TAPE6", cut).unwrap_err();
        assert_eq!((e.line, e.column), (7, 47), "{e}");
        assert!(e.message.contains("SOLAR IRRADIANCE PER MICRON"), "{e}");
        let nan = SUN.replace("1.26E-06  7.88E-04", "     NaN  7.88E-04");
        let e = parse("TAPE6", &nan).unwrap_err();
        assert_eq!((e.line, e.column), (6, 24), "{e}");
        // The table of another mode than card 1's.
        let other = SUN.replace("*****    6    3    3", "*****    6    3    1");
        let e = parse("TAPE6", &other).unwrap_err();
        assert_eq!(e.line, 4, "{e}");
        assert!(e.message.contains("IEMSCT = 1 run"), "{e}");
        // Without card 1's echo, a second table of another kind in the run.
        let card1 = SUN.lines().nth(1).unwrap();
        let two = SUN.replace(&format!("{card1}\n"), "").replace(
            "0INTEGRATED ABSORPTION",
            "0   FREQ WAVLEN   ATMOS RADIANCE       INTEGRAL TOTAL\n0INTEGRATED ABSORPTION",
        );
        let e = parse("TAPE6", &two).unwrap_err();
        assert_eq!(e.line, 7, "{e}");
        assert!(e.message.contains("another table"), "{e}");
        let moved = SUN.replace("=  1.268E-04", "= 1.268E-04 ");
        let e = parse("TAPE6", &moved).unwrap_err();
        assert_eq!(e.line, 11, "{e}");
    }

    #[test]
    fn every_table_row_field_and_integral_has_its_columns() {
        // A seventh number after the TRANS column, and integrals out of their columns.
        let long = TEXT.replace("   0.1245\n", "   0.1245 7\n");
        let e = parse("TAPE6", &long).unwrap_err();
        assert_eq!((e.line, e.column), (7, 57), "{e}");
        let moved = TEXT.replace("=     87.10 CM-1", "= 87.10      CM-1");
        let e = parse("TAPE6", &moved).unwrap_err();
        assert_eq!(e.line, 9, "{e}");
        // The sample's transmittance table (IEMSCT 0): 14 columns of FORMAT 906.
        let sample = include_str!("../../../../formats/radtran/samples/us-std-1976.tape6");
        let t = parse("us-std-1976.tape6", sample).unwrap();
        let run = t.runs.iter().find(|r| r.iemsct == Some(0)).unwrap();
        let table = run.table.as_ref().unwrap();
        assert_eq!(table.columns.len(), 14);
        // `    710.  14.085   0.1245   0.8177 ...   0.0000       2.189`, as printed.
        let first: Vec<f64> = table.columns.iter().map(|c| c[0]).collect();
        assert_eq!(
            first,
            [
                710.0, 14.085, 0.1245, 0.8177, 0.1719, 0.9977, 0.9999, 1.0, 0.8882, 1.0, 1.0, 1.0,
                0.0, 2.189
            ]
        );
    }
}
