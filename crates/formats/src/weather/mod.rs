//! Weather files, read into [`irsig_model::weather::Weather`]: the EnergyPlus weather
//! format (EPW, [`epw`]), in which most hourly weather comes, and a plain CSV whose header
//! names each column's unit ([`csv`]). Both are converted to SI and UTC here; the record's
//! rules (ranges, order, gaps) are the model's [`Weather::validate`], reported at the line
//! and column of the offending value. See `formats/weather.md`.
//!
//! ```
//! use irsig_formats::weather;
//! let text = "time,air_temperature[degC],dew_point[degC],pressure[hPa],wind_speed[m/s]\n\
//!             2001-08-07T14:00:00-07:00,32.0,8.0,835,5.7\n\
//!             2001-08-07T15:00:00-07:00,32.0,8.0,835,6.2\n";
//! let w = weather::read("day.csv", text.as_bytes(), &weather::Options::default())?;
//! assert_eq!(w.records[0].time_s, 997_218_000.0); // 21:00 UTC
//! assert!((w.records[0].air_temperature_k - 305.15).abs() < 1e-9);
//! # Ok::<(), irsig_formats::ParseError>(())
//! ```

// ParseError is the crate's shared error; its size is decided there, not here.
#![allow(clippy::result_large_err)]

pub mod csv;
pub mod epw;

use irsig_model::ModelError;
use irsig_model::weather::Weather;
use nom::Input;

use crate::ParseError;
use crate::legacy::lex::{Line, Span};

/// How to read a weather file.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Options {
    /// Read every EPW row as this year, whatever its year field says: a typical-year file
    /// (TMY, IWEC) takes each month from a different year, so its own years do not make
    /// one time line. Ignored for the CSV form, whose times are absolute.
    pub year: Option<i64>,
}

/// Reads a weather file in either form: EPW when its first line starts with `LOCATION,`,
/// the CSV form otherwise. Validates the record.
///
/// # Errors
/// Text that is not UTF-8, or whatever [`epw::parse`] or [`csv::parse`] refuses.
pub fn read(file: &str, bytes: &[u8], options: &Options) -> Result<Weather, ParseError> {
    let text = crate::canonical::utf8(file, bytes)?;
    // A byte-order mark is no part of the first line (editors do not show it).
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if text.starts_with("LOCATION,") {
        epw::parse(file, text, options)
    } else {
        csv::parse(file, text)
    }
}

/// The comma-separated fields of a line, each trimmed of surrounding blanks, with its place.
fn fields<'a>(line: Line<'a>) -> Vec<Span<'a>> {
    let text = *line.span.fragment();
    let mut out = Vec::new();
    let mut start = 0;
    for piece in text.split(',') {
        let lead = piece.len() - piece.trim_start().len();
        let span = line.span.take_from(start + lead).take(piece.trim().len());
        out.push(span);
        start += piece.len() + 1;
    }
    out
}

/// The record index and field of a model error's path `records[i].field`.
fn record_field(e: &ModelError) -> Option<(usize, &str)> {
    let rest = e.path.strip_prefix("records[")?;
    let (index, field) = rest.split_once("].")?;
    Some((index.parse().ok()?, field))
}

/// The byte range of a span, to keep after its line is gone.
fn range(span: Span<'_>) -> (usize, usize) {
    (span.location_offset(), span.fragment().len())
}
