//! Complex refractive index tables (`n, k` against wavelength): three whitespace-separated
//! columns per line, `wavelength_um n k`, wavelengths strictly increasing, `n > 0`,
//! `k ≥ 0`. Blank lines and lines starting with `#` are ignored. See `formats/nk.md`.
//!
//! ```
//! let table = irsig_formats::nk::parse("water.nk", "# H&Q 1973\n8.0 1.291 0.0343\n14.0 1.210 0.370\n")?;
//! assert_eq!(table.wavelength_um, vec![8.0, 14.0]);
//! assert_eq!(table.k[1], 0.370);
//! # Ok::<(), irsig_formats::ParseError>(())
//! ```

// ParseError is the crate's shared error; its size is decided there, not here.
#![allow(clippy::result_large_err)]

use crate::ParseError;

/// A parsed index table: matching columns.
#[derive(Debug, Clone, PartialEq)]
pub struct NkTable {
    /// Wavelengths, µm, strictly increasing.
    pub wavelength_um: Vec<f64>,
    /// Real part of the refractive index, > 0.
    pub n: Vec<f64>,
    /// Extinction coefficient (imaginary part), ≥ 0.
    pub k: Vec<f64>,
}

/// Parses the text of an index table named `file` (for messages).
///
/// # Errors
/// A [`ParseError`] at the offending line and column: a field that is not a finite number,
/// a row without exactly 3 columns, a wavelength that is not positive or does not
/// increase, `n ≤ 0`, `k < 0`, or fewer than two rows.
pub fn parse(file: &str, text: &str) -> Result<NkTable, ParseError> {
    let mut table = NkTable {
        wavelength_um: Vec::new(),
        n: Vec::new(),
        k: Vec::new(),
    };
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let content = line.trim_end_matches(['\n', '\r']);
        if content.trim().is_empty() || content.trim_start().starts_with('#') {
            continue;
        }
        let mut fields = Vec::new();
        let mut pos = 0;
        for piece in content.split_whitespace() {
            let at = content[pos..].find(piece).map_or(pos, |i| pos + i);
            pos = at + piece.len();
            fields.push((start + at, piece));
        }
        let [w_field, n_field, k_field] = fields[..] else {
            let at = fields.get(3).map_or(start + content.len(), |f| f.0);
            return Err(ParseError::at_offset(
                file,
                text,
                at,
                format!(
                    "expected 3 columns `wavelength_um n k`, found {}",
                    fields.len()
                ),
            ));
        };
        let number = |(at, s): (usize, &str), what: &str| -> Result<f64, ParseError> {
            match s.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(ParseError::at_span(
                    file,
                    text,
                    at,
                    s.len(),
                    format!("expected {what} (a finite number), found `{s}`"),
                )),
            }
        };
        let refuse = |(at, s): (usize, &str), message: String| {
            Err(ParseError::at_span(file, text, at, s.len(), message))
        };
        let w = number(w_field, "a wavelength in µm")?;
        let n = number(n_field, "the real part n")?;
        let k = number(k_field, "the extinction coefficient k")?;
        if w <= 0.0 {
            return refuse(
                w_field,
                format!("expected a positive wavelength in µm, found {w}"),
            );
        }
        let last = table.wavelength_um.last().copied().unwrap_or(0.0);
        if w <= last {
            return refuse(
                w_field,
                format!("wavelengths must increase: {w} µm follows {last} µm"),
            );
        }
        if n <= 0.0 {
            return refuse(n_field, format!("expected n > 0, found {n}"));
        }
        if k < 0.0 {
            return refuse(k_field, format!("expected k ≥ 0, found {k}"));
        }
        table.wavelength_um.push(w);
        table.n.push(n);
        table.k.push(k);
    }
    if table.wavelength_um.len() < 2 {
        return Err(ParseError::at_offset(
            file,
            text,
            text.len(),
            format!(
                "expected at least 2 rows `wavelength_um n k`, found {}",
                table.wavelength_um.len()
            ),
        ));
    }
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_line_and_column() {
        let e = parse("a.nk", "8 1.2 0\n9 x 0\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 3));
        assert!(e.to_string().contains("the real part n"), "{e}");
        let e = parse("a.nk", "8 1.2 0\n7 1.2 0\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 1));
        let e = parse("a.nk", "8 1.2 0\n9 0 0\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 3));
        let e = parse("a.nk", "8 1.2 0\n9 1.2 -0.1\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 7));
        let e = parse("a.nk", "8 1.2 0 4\n").unwrap_err();
        assert_eq!((e.line, e.column), (1, 9));
        let e = parse("a.nk", "8 1.2\n").unwrap_err();
        assert_eq!((e.line, e.column), (1, 6));
        let e = parse("a.nk", "8 NaN 0\n9 1 0\n").unwrap_err();
        assert_eq!((e.line, e.column), (1, 3));
        assert!(parse("a.nk", "8 1.2 0\n").is_err());
        assert!(parse("a.nk", "").is_err());
    }

    #[test]
    fn comments_and_blank_lines_are_skipped() {
        let t = parse("a.nk", "# x\n\n8 1.2 0.1\r\n  9   1.3  0 \n").unwrap();
        assert_eq!(t.wavelength_um, vec![8.0, 9.0]);
        assert_eq!(t.n, vec![1.2, 1.3]);
        assert_eq!(t.k, vec![0.1, 0.0]);
    }
}
