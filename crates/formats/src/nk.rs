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

use crate::{ParseError, columns};

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
    let rows = columns::rows(
        file,
        text,
        "wavelength_um n k",
        [
            "a wavelength in µm",
            "the real part n",
            "the extinction coefficient k",
        ],
    )?;
    let mut table = NkTable {
        wavelength_um: Vec::with_capacity(rows.len()),
        n: Vec::with_capacity(rows.len()),
        k: Vec::with_capacity(rows.len()),
    };
    for [w, n, k] in rows {
        if n.value <= 0.0 {
            return Err(n.error(file, text, format!("expected n > 0, found {}", n.value)));
        }
        if k.value < 0.0 {
            return Err(k.error(file, text, format!("expected k ≥ 0, found {}", k.value)));
        }
        table.wavelength_um.push(w.value);
        table.n.push(n.value);
        table.k.push(k.value);
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
