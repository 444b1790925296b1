//! The inputs and outputs of the radiative-transfer codes people run: LOWTRAN7's card deck
//! (`tape5`), its printed output (`tape6`) and its spectral table (`tape7`), and MODTRAN's
//! `tape7` in transmittance and radiance modes. Spec pages: `formats/radtran/`.
//!
//! These files are Fortran formatted records: fixed columns, numbers in `I`, `F` and `E`
//! edit descriptors, `-9999.` ending each run's table. The readers keep the file's own
//! units (km, cm⁻¹, W cm⁻² sr⁻¹ per cm⁻¹; every field says its unit) and the position of
//! every record; converting them to the canonical SI model is `irsig-atmosphere`'s job.
//!
//! | module | file | written by |
//! | --- | --- | --- |
//! | [`tape5`] | LOWTRAN7 card deck (input) | the user, `irsig-atmos plan` |
//! | [`lowtran_tape6`] | LOWTRAN7 printed output: spectral table, integrated values, messages | LOWTRAN7 |
//! | [`lowtran_tape7`] | LOWTRAN7 spectral table, one block per run | LOWTRAN7 |
//! | [`modtran_tape7`] | MODTRAN spectral table with named columns | MODTRAN 4/5 |
//!
//! Every error is a [`ParseError`] naming the file, the line and the column and what was
//! expected there.
//!
//! ```
//! use irsig_formats::radtran::tape5;
//! let deck = tape5::parse("TAPE5", "    6    2    1\n    0\n     1.000     0.001   180.000\n   710.000  1250.000     5.000\n    0\n")?;
//! let run = &deck.calculations()[0];
//! assert_eq!(run.card1.model, 6);
//! assert_eq!(run.card3.h1_km(), 1.0);
//! assert_eq!(run.card4.dv_per_cm, 5.0);
//! assert_eq!(tape5::parse("TAPE5", &tape5::write(&deck)?)?, deck);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod lowtran_tape6;
pub mod lowtran_tape7;
pub mod modtran_tape7;
pub mod tape5;

use crate::ParseError;
use crate::legacy::Position;

/// One physical line of a text file: its content without the line end, where it starts and
/// its number.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TextLine<'a> {
    /// The content, without `\n` or `\r\n`.
    pub text: &'a str,
    /// Byte offset of the line's start in the file.
    pub offset: usize,
    /// Line number, from 1.
    pub number: usize,
}

/// The lines of `text`, CRLF or LF.
pub(crate) fn text_lines(text: &str) -> Vec<TextLine<'_>> {
    let mut lines = Vec::new();
    let mut offset = 0;
    for (i, raw) in text.split_inclusive('\n').enumerate() {
        let content = raw.strip_suffix('\n').unwrap_or(raw);
        let content = content.strip_suffix('\r').unwrap_or(content);
        lines.push(TextLine {
            text: content,
            offset,
            number: i + 1,
        });
        offset += raw.len();
    }
    lines
}

impl TextLine<'_> {
    pub(crate) fn position(&self) -> Position {
        Position {
            line: self.number,
            column: 1,
        }
    }

    /// The byte offset in the file of character column `col` (0-based) of this line,
    /// clamped to the line's end.
    pub(crate) fn offset_of_column(&self, col: usize) -> usize {
        self.offset
            + self
                .text
                .char_indices()
                .nth(col)
                .map_or(self.text.len(), |(b, _)| b)
    }

    /// Characters `[start, start + width)` (0-based columns) of the line; past its end
    /// the field is blank, as a Fortran read pads a short record.
    pub(crate) fn field(&self, start: usize, width: usize) -> &str {
        let begin = self.offset_of_column(start) - self.offset;
        let end = self.offset_of_column(start + width) - self.offset;
        &self.text[begin..end]
    }

    /// The whitespace-separated tokens of the line with their byte offsets in the file.
    pub(crate) fn tokens(&self) -> Vec<(usize, &str)> {
        let mut out = Vec::new();
        let mut pos = 0;
        for piece in self.text.split_whitespace() {
            let at = self.text[pos..].find(piece).map_or(pos, |i| pos + i);
            pos = at + piece.len();
            out.push((self.offset + at, piece));
        }
        out
    }
}

/// Where a file's text is, for errors.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Source<'a> {
    pub file: &'a str,
    pub text: &'a str,
}

impl Source<'_> {
    pub(crate) fn error(
        &self,
        offset: usize,
        len: usize,
        message: impl Into<String>,
    ) -> ParseError {
        ParseError::at_span(self.file, self.text, offset, len.max(1), message)
    }

    /// An error at the end of the file's last non-blank line.
    pub(crate) fn eof_error(&self, message: impl Into<String>) -> ParseError {
        let end = self.text.trim_end().len();
        ParseError::at_offset(self.file, self.text, end, message)
    }
}

/// A Fortran edit descriptor of a numeric field.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Edit {
    /// `Iw`.
    I(usize),
    /// `Fw.d` (also read for `Ew.d`: the two read the same way).
    F(usize, u32),
}

impl Edit {
    pub(crate) fn width(self) -> usize {
        match self {
            Edit::I(w) | Edit::F(w, _) => w,
        }
    }

    fn name(self) -> String {
        match self {
            Edit::I(w) => format!("I{w}"),
            Edit::F(w, d) => format!("F{w}.{d}"),
        }
    }
}

/// Reads a Fortran integer field as LOWTRAN does (`BLANK='NULL'`: blanks are ignored, an
/// all-blank field is 0).
pub(crate) fn read_int(field: &str) -> Option<i64> {
    let s: String = field.chars().filter(|c| *c != ' ').collect();
    if s.is_empty() {
        return Some(0);
    }
    let digits = s.strip_prefix(['+', '-']).unwrap_or(&s);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    s.parse().ok()
}

/// Reads a Fortran real field `Fw.d` / `Ew.d` as a formatted read does: blanks ignored (an
/// all-blank field is 0); without a decimal point the last `d` digits are the fraction; an
/// exponent may be written `E±n`, `D±n` or just `±n` after the digits.
pub(crate) fn read_real(field: &str, decimals: u32) -> Option<f64> {
    let s: String = field.chars().filter(|c| *c != ' ').collect();
    if s.is_empty() {
        return Some(0.0);
    }
    let b = s.as_bytes();
    let mut i = 0;
    let negative = match b[0] {
        b'-' => {
            i = 1;
            true
        }
        b'+' => {
            i = 1;
            false
        }
        _ => false,
    };
    let mantissa_start = i;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
    }
    let int_digits = &s[mantissa_start..i];
    let mut frac_digits = "";
    let has_point = i < b.len() && b[i] == b'.';
    if has_point {
        i += 1;
        let f = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        frac_digits = &s[f..i];
    }
    if int_digits.is_empty() && frac_digits.is_empty() {
        return None;
    }
    let mut exponent: i64 = 0;
    if i < b.len() {
        let mut j = i;
        if matches!(b[j], b'E' | b'e' | b'D' | b'd') {
            j += 1;
        } else if !matches!(b[j], b'+' | b'-') {
            return None;
        }
        let e = &s[j..];
        let digits = e.strip_prefix(['+', '-']).unwrap_or(e);
        if digits.is_empty() || digits.len() > 4 || !digits.bytes().all(|c| c.is_ascii_digit()) {
            return None;
        }
        exponent = e.parse().ok()?;
    }
    let mut text = String::with_capacity(int_digits.len() + frac_digits.len() + 8);
    if negative {
        text.push('-');
    }
    if has_point {
        text.push_str(if int_digits.is_empty() {
            "0"
        } else {
            int_digits
        });
        text.push('.');
        text.push_str(frac_digits);
    } else {
        // No decimal point: the last `decimals` digits are the fraction.
        exponent -= i64::from(decimals);
        text.push_str(int_digits);
    }
    text.push('e');
    text.push_str(&exponent.to_string());
    let v: f64 = text.parse().ok()?;
    v.is_finite().then_some(v)
}

/// Reads the numeric fields of a fixed-format card: `edits` in order from column 1.
/// Integers come back as `f64` exactly (they are small).
pub(crate) fn read_card(
    src: Source<'_>,
    line: &TextLine<'_>,
    edits: &[(Edit, &str)],
) -> Result<Vec<f64>, ParseError> {
    let mut col = 0;
    let mut out = Vec::with_capacity(edits.len());
    for &(edit, what) in edits {
        let w = edit.width();
        let field = line.field(col, w);
        let value = match edit {
            Edit::I(_) => read_int(field).map(|v| v as f64),
            Edit::F(_, d) => read_real(field, d),
        };
        let Some(value) = value else {
            let at = line.offset_of_column(col);
            return Err(src.error(
                at,
                field.len(),
                format!(
                    "expected {what} ({} in columns {}-{}), found `{}`",
                    edit.name(),
                    col + 1,
                    col + w,
                    field.trim()
                ),
            ));
        };
        out.push(value);
        col += w;
    }
    Ok(out)
}

/// Reads one row of a printed spectral table (LOWTRAN's TAPE7, MODTRAN's tape7) onto
/// `columns`: exactly `names.len()` fields (`count(found)` says what was expected when the
/// row has another number), each a finite number that `check(column, name, value)` finds
/// no fault with (its message otherwise), the first a wavenumber of 0 cm⁻¹ or more above
/// the previous row's. Nothing is pushed from a row with a fault.
pub(crate) fn push_row<N: AsRef<str>>(
    src: Source<'_>,
    row: &TextLine<'_>,
    names: &[N],
    columns: &mut [Vec<f64>],
    count: impl FnOnce(usize) -> String,
    check: impl Fn(usize, &str, f64) -> Option<String>,
) -> Result<(), ParseError> {
    let n = names.len();
    let tokens = row.tokens();
    if tokens.len() != n {
        let at = tokens.get(n).map_or(row.offset + row.text.len(), |t| t.0);
        return Err(src.error(at, 1, count(tokens.len())));
    }
    let mut values = Vec::with_capacity(n);
    for (c, &(at, tok)) in tokens.iter().enumerate() {
        let name = names[c].as_ref();
        let Some(v) = number(tok) else {
            return Err(src.error(
                at,
                tok.len(),
                format!("expected {name} (a finite number), found `{tok}`"),
            ));
        };
        let previous = columns[0].last().copied().filter(|_| c == 0);
        let fault = match previous {
            Some(last) if v <= last => Some(if v.total_cmp(&last).is_eq() {
                format!("wavenumber {v} cm-1 is repeated: wavenumbers must strictly increase")
            } else {
                format!("wavenumbers must strictly increase: {v} cm-1 follows {last} cm-1")
            }),
            _ if c == 0 && v < 0.0 => Some(format!(
                "expected a wavenumber of 0 cm-1 or more, found {v}"
            )),
            _ => check(c, name, v),
        };
        if let Some(message) = fault {
            return Err(src.error(at, tok.len(), message));
        }
        values.push(v);
    }
    for (column, v) in columns.iter_mut().zip(values) {
        column.push(v);
    }
    Ok(())
}

/// Parses a free-format number (a token of a printed table): a decimal literal, `710.`
/// included; never `NaN` or `inf`.
pub(crate) fn number(token: &str) -> Option<f64> {
    let t = token.strip_prefix('+').unwrap_or(token);
    let ok = t
        .bytes()
        .all(|b| b.is_ascii_digit() || matches!(b, b'.' | b'-' | b'+' | b'e' | b'E'));
    if !ok || t.is_empty() {
        return None;
    }
    let v: f64 = t.parse().ok()?;
    v.is_finite().then_some(v)
}

#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn fortran_reals_read_as_a_formatted_read_does() {
        assert_eq!(read_real("   710.000", 3), Some(710.0));
        assert_eq!(read_real("          ", 3), Some(0.0));
        assert_eq!(read_real("       0.0", 3), Some(0.0));
        // No decimal point: the last d digits are the fraction.
        assert_eq!(read_real("      1234", 3), Some(1.234));
        assert_eq!(read_real(" 1.07E-05", 2), Some(1.07e-5));
        assert_eq!(read_real("1.0+05", 1), Some(1.0e5));
        assert_eq!(read_real("-.5", 3), Some(-0.5));
        assert_eq!(read_real("1 0.5", 3), Some(10.5));
        assert_eq!(read_real("abc", 3), None);
        assert_eq!(read_real("1.2.3", 3), None);
        assert_eq!(read_real("NaN", 3), None);
        assert_eq!(read_real(".", 3), None);
        assert_eq!(read_real("1E99999", 3), None);
    }

    #[test]
    fn fortran_integers_ignore_blanks() {
        assert_eq!(read_int("    6"), Some(6));
        assert_eq!(read_int("     "), Some(0));
        assert_eq!(read_int("  -99"), Some(-99));
        assert_eq!(read_int("  1.0"), None);
        assert_eq!(read_int("    -"), None);
    }

    #[test]
    fn fields_past_the_end_of_a_short_line_are_blank() {
        let lines = text_lines("    5    3\r\n");
        assert_eq!(lines[0].text, "    5    3");
        assert_eq!(lines[0].field(5, 5), "    3");
        assert_eq!(lines[0].field(10, 5), "");
    }
}
