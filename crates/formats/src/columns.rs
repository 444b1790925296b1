//! Spectral column tables (SRF, n/k): whitespace-separated numbers, one row a line, the
//! first column a wavelength in µm, strictly increasing. Blank lines and lines starting
//! with `#` are skipped. This module owns what every such table shares (the columns, the
//! numbers, the wavelength axis, at least two rows) and where each field sits in the text;
//! each format checks its own columns' ranges.

// ParseError is the crate's shared error; its size is decided there, not here.
#![allow(clippy::result_large_err)]

use crate::ParseError;

/// One number of a row and where its text starts in the file.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Field<'t> {
    pub value: f64,
    at: usize,
    text: &'t str,
}

impl Field<'_> {
    /// An error underlining this field.
    pub fn error(&self, file: &str, source: &str, message: String) -> ParseError {
        ParseError::at_span(file, source, self.at, self.text.len(), message)
    }
}

/// The rows of `text`, each exactly `N` finite numbers (`names[i]` says what column `i`
/// holds, for messages; `header` is the row's form, "wavelength_um n k"), the first a
/// positive wavelength in µm that increases from row to row; at least two rows.
pub(crate) fn rows<'t, const N: usize>(
    file: &str,
    text: &'t str,
    header: &str,
    names: [&str; N],
) -> Result<Vec<[Field<'t>; N]>, ParseError> {
    let mut rows: Vec<[Field<'t>; N]> = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let content = line.trim_end_matches(['\n', '\r']);
        if content.trim().is_empty() || content.trim_start().starts_with('#') {
            continue;
        }
        let mut pieces = Vec::new();
        let mut pos = 0;
        for piece in content.split_whitespace() {
            let at = content[pos..].find(piece).map_or(pos, |i| pos + i);
            pos = at + piece.len();
            pieces.push((start + at, piece));
        }
        let count_error = |found: usize| {
            let at = pieces.get(N).map_or(start + content.len(), |p| p.0);
            ParseError::at_offset(
                file,
                text,
                at,
                format!("expected {N} columns `{header}`, found {found}"),
            )
        };
        if pieces.len() != N {
            return Err(count_error(pieces.len()));
        }
        let mut fields = Vec::with_capacity(N);
        for (&(at, s), what) in pieces.iter().zip(names) {
            match s.parse::<f64>() {
                Ok(value) if value.is_finite() => fields.push(Field { value, at, text: s }),
                _ => {
                    return Err(ParseError::at_span(
                        file,
                        text,
                        at,
                        s.len(),
                        format!("expected {what} (a finite number), found `{s}`"),
                    ));
                }
            }
        }
        let row = <[Field<'t>; N]>::try_from(fields).map_err(|f| count_error(f.len()))?;
        let w = row[0].value;
        if w <= 0.0 {
            return Err(row[0].error(
                file,
                text,
                format!("expected a positive wavelength in µm, found {w}"),
            ));
        }
        if let Some(last) = rows.last().map(|r| r[0].value)
            && w <= last
        {
            return Err(row[0].error(
                file,
                text,
                format!("wavelengths must increase: {w} µm follows {last} µm"),
            ));
        }
        rows.push(row);
    }
    if rows.len() < 2 {
        return Err(ParseError::at_offset(
            file,
            text,
            text.len(),
            format!("expected at least 2 rows `{header}`, found {}", rows.len()),
        ));
    }
    Ok(rows)
}
