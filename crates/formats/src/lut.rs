//! The sensor stage's look-up table (`irsig-sensor --lut`, `formats/sensor.md`): `#` lines
//! are comments (the first names the columns), then one row per digital count, four
//! whitespace-separated fields `dc radiance_w_m2_sr temperature_k temperature_c`, the counts
//! 0, 1, 2, … in order, every number finite.
//!
//! ```
//! let lut = irsig_formats::lut::parse(
//!     "dc.lut",
//!     "# dc radiance_w_m2_sr temperature_k temperature_c\n0 4.7e1 288.4512 15.3012\n1 4.8e1 288.6163 15.4663\n",
//! )?;
//! assert_eq!(lut.len(), 2);
//! assert_eq!(lut[1].dc, 1);
//! assert_eq!(lut[1].temperature_k, 288.6163);
//! # Ok::<(), irsig_formats::ParseError>(())
//! ```

// ParseError is the crate's shared error; its size is decided there, not here.
#![allow(clippy::result_large_err)]

use crate::ParseError;

/// One row of the LUT.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LutRow {
    /// The digital count.
    pub dc: u32,
    /// Band radiance at the centre of the count's interval, W m⁻² sr⁻¹.
    pub radiance_w_m2_sr: f64,
    /// Its blackbody temperature, K.
    pub temperature_k: f64,
    /// The same in degrees Celsius.
    pub temperature_c: f64,
}

const COLUMNS: &str = "dc radiance_w_m2_sr temperature_k temperature_c";

/// The largest count a LUT holds: counts are at most 16 bits (`--dc-bits` 1–16).
pub const MAX_COUNT: u32 = (1 << 16) - 1;

/// Parses the text of a LUT file named `file` (for messages).
///
/// # Errors
/// A [`ParseError`] at the offending line and column: a row without exactly four fields, a
/// count that is not the next integer (0 first) or is past 16 bits (65,535), a field that
/// is not a finite number, or a file without rows.
pub fn parse(file: &str, text: &str) -> Result<Vec<LutRow>, ParseError> {
    let mut rows: Vec<LutRow> = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let content = line.trim_end_matches(['\n', '\r']);
        if content.trim().is_empty() || content.trim_start().starts_with('#') {
            continue;
        }
        let mut fields: Vec<(usize, &str)> = Vec::with_capacity(4);
        let mut pos = 0;
        for piece in content.split_whitespace() {
            let at = content[pos..].find(piece).map_or(pos, |i| pos + i);
            pos = at + piece.len();
            fields.push((start + at, piece));
        }
        if fields.len() != 4 {
            let at = fields.get(4).map_or(start + content.len(), |f| f.0);
            return Err(ParseError::at_offset(
                file,
                text,
                at,
                format!("expected 4 columns `{COLUMNS}`, found {}", fields.len()),
            ));
        }
        let expected = u32::try_from(rows.len()).unwrap_or(u32::MAX);
        let (at, dc_text) = fields[0];
        let dc = dc_text.parse::<u32>().map_err(|_| {
            ParseError::at_span(
                file,
                text,
                at,
                dc_text.len(),
                format!("expected the digital count {expected}, found `{dc_text}`"),
            )
        })?;
        if dc > MAX_COUNT {
            return Err(ParseError::at_span(
                file,
                text,
                at,
                dc_text.len(),
                format!(
                    "expected at most {} rows: counts are at most 16 bits (0 to {MAX_COUNT}), found {dc}",
                    MAX_COUNT + 1
                ),
            ));
        }
        if dc != expected {
            return Err(ParseError::at_span(
                file,
                text,
                at,
                dc_text.len(),
                format!(
                    "expected the digital count {expected} (counts run 0, 1, 2, … in order), found {dc}"
                ),
            ));
        }
        let mut numbers = [0.0; 3];
        for (i, (&(at, piece), what)) in fields[1..]
            .iter()
            .zip([
                "a radiance in W m^-2 sr^-1",
                "a temperature in K",
                "a temperature in degC",
            ])
            .enumerate()
        {
            numbers[i] = piece
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    ParseError::at_span(
                        file,
                        text,
                        at,
                        piece.len(),
                        format!("expected {what} (a finite number), found `{piece}`"),
                    )
                })?;
        }
        rows.push(LutRow {
            dc,
            radiance_w_m2_sr: numbers[0],
            temperature_k: numbers[1],
            temperature_c: numbers[2],
        });
    }
    if rows.is_empty() {
        return Err(ParseError::at_offset(
            file,
            text,
            text.len(),
            format!("expected rows `{COLUMNS}`, found none"),
        ));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_rows_and_names_the_bad_field() {
        let ok = "# dc radiance_w_m2_sr temperature_k temperature_c\n\
                  0 4.77201355e1 288.4512 15.3012\r\n1 4.78439209e1 288.6163 15.4663\n";
        let rows = parse("a.lut", ok).unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].dc, 0);
        assert!((rows[0].radiance_w_m2_sr - 47.720_135_5).abs() < 1e-9);
        assert!((rows[1].temperature_c - 15.4663).abs() < 1e-12);

        for (text, line, column, says) in [
            ("0 1 2 3\n2 1 2 3\n", 2, 1, "digital count 1"),
            ("0 1 nan 3\n", 1, 5, "a temperature in K"),
            ("0 1 2\n", 1, 6, "expected 4 columns"),
            ("0 1 2 3 4\n", 1, 9, "found 5"),
            ("x 1 2 3\n", 1, 1, "digital count 0"),
            ("# only a header\n", 2, 1, "found none"),
        ] {
            let e = parse("b.lut", text).unwrap_err();
            let shown = format!("{e:?} {e}");
            assert!(shown.contains(says), "{text:?}: {shown}");
            let (l, c) = crate::line_column(text, e.span().0);
            assert_eq!((l, c), (line, column), "{text:?}: {shown}");
        }
    }

    #[test]
    fn counts_stop_at_16_bits() {
        // A LUT holds one row per count of at most 16 bits: a longer one is no sensor's.
        let mut text = String::new();
        for dc in 0..=65_536 {
            text.push_str(&format!("{dc} 1 2 3\n"));
        }
        let e = parse("c.lut", &text).unwrap_err();
        assert!(e.message.contains("at most 65536 rows"), "{e}");
        assert_eq!(crate::line_column(&text, e.span().0).0, 65_537);
        text.truncate(text.rfind("65536").unwrap());
        assert_eq!(parse("c.lut", &text).unwrap().len(), 65_536);
    }
}
