//! Sensor response function (SRF) tables: two whitespace-separated columns per line,
//! `wavelength_um response`, wavelengths strictly increasing within 0.2–1000 µm
//! (`irsig_model::limits::RESPONSE_WAVELENGTH_UM`), responses finite, ≥ 0 and at most 10⁶
//! (`MAX_RESPONSE`). Blank lines and lines starting with `#` are ignored. See
//! `formats/srf.md`.
//!
//! ```
//! let table = irsig_formats::srf::parse("camera.srf", "# demo\n8.0 0.1\n10.0 1.0\n12.0 0.2\n")?;
//! assert_eq!(table.wavelength_um, vec![8.0, 10.0, 12.0]);
//! assert_eq!(table.response[1], 1.0);
//! # Ok::<(), irsig_formats::ParseError>(())
//! ```

// ParseError is the crate's shared error; its size is decided there, not here.
#![allow(clippy::result_large_err)]

use crate::{ParseError, columns};
use irsig_model::limits::{MAX_RESPONSE, RESPONSE_WAVELENGTH_UM};

/// A parsed SRF table: matching columns, wavelength in µm and relative response.
#[derive(Debug, Clone, PartialEq)]
pub struct SrfTable {
    /// Wavelengths, µm, strictly increasing, within 0.2–1000 µm.
    pub wavelength_um: Vec<f64>,
    /// Relative response (dimensionless), finite, ≥ 0 and at most 10⁶.
    pub response: Vec<f64>,
}

/// Parses the text of an SRF file named `file` (for messages).
///
/// # Errors
/// A [`ParseError`] at the offending line and column: a field that is not a number, a
/// missing or extra column, a wavelength outside 0.2–1000 µm or that does not increase, a
/// negative, non-finite or larger than 10⁶ response, fewer than two rows, or responses
/// that are all 0.
pub fn parse(file: &str, text: &str) -> Result<SrfTable, ParseError> {
    let rows = columns::rows(
        file,
        text,
        "wavelength_um response",
        ["a wavelength in µm", "a response"],
    )?;
    let mut wavelength_um = Vec::with_capacity(rows.len());
    let mut response = Vec::with_capacity(rows.len());
    let [shortest, longest] = RESPONSE_WAVELENGTH_UM;
    for [w, r] in rows {
        if !(shortest..=longest).contains(&w.value) {
            return Err(w.error(
                file,
                text,
                format!(
                    "expected a wavelength of {shortest}–{longest} µm (ultraviolet to far \
                     infrared), found {}",
                    w.value
                ),
            ));
        }
        if !(0.0..=MAX_RESPONSE).contains(&r.value) {
            return Err(r.error(
                file,
                text,
                format!(
                    "expected a response of 0–{MAX_RESPONSE:e}, found {}",
                    r.value
                ),
            ));
        }
        wavelength_um.push(w.value);
        response.push(r.value);
    }
    if response.iter().all(|&r| r <= 0.0) {
        return Err(ParseError::at_offset(
            file,
            text,
            0,
            "the response is 0 at every wavelength",
        ));
    }
    Ok(SrfTable {
        wavelength_um,
        response,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_line_and_column() {
        let e = parse("a.srf", "8 0.5\n9 x\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 3));
        let e = parse("a.srf", "8 0.5\n7 0.5\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 1));
        let e = parse("a.srf", "8 0.5\n9 -1\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 3));
        let e = parse("a.srf", "8 0.5 3\n").unwrap_err();
        assert_eq!((e.line, e.column), (1, 7));
        assert!(parse("a.srf", "8 0.5\n").is_err());
        assert!(parse("a.srf", "8 0\n9 0\n").is_err());
        assert!(parse("a.srf", "8 NaN\n9 1\n").is_err());
    }

    #[test]
    fn wavelengths_and_responses_have_a_physical_range() {
        // `1e-300 1` / `1e300 1` exhausted memory in the band's quadrature; responses of
        // 1e308 gave a band radiance of 1.797693e308.
        let e = parse("a.srf", "1e-300 1\n1e300 1\n").unwrap_err();
        assert_eq!((e.line, e.column), (1, 1));
        assert!(e.message.contains("0.2–1000 µm"), "{e}");
        let e = parse("a.srf", "8 1\n1e10 1\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 1));
        let e = parse("a.srf", "8 1\n9   1e308\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 5));
        assert!(e.message.contains("0–1e6"), "{e}");
        assert!(parse("a.srf", "0.2 1e6\n1000 0\n").is_ok());
    }

    #[test]
    fn comments_and_blank_lines_are_skipped() {
        let t = parse("a.srf", "# x\n\n8 0.5\r\n  9   1  \n").unwrap();
        assert_eq!(t.wavelength_um.len(), 2);
    }
}
