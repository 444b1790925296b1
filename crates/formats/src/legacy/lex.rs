//! The lexical layer every legacy format shares: significant lines, whitespace-separated
//! tokens, strict numbers, and errors that point at a token.
//!
//! The 1990 files were read with C `fscanf`, so the layout rules are deliberately loose
//! (blank lines anywhere, CRLF or LF line ends, tabs, trailing whitespace, and `#`
//! comments as an irsig extension) while numbers are strict: a number is a decimal
//! literal (`-4.096910`, `1e-3`, `.5`); `NaN`, `inf`, `1,5` or `0x10` are errors, and so
//! is a literal too large for an `f64`.

use nom::bytes::complete::{take_till, take_till1, take_while};
use nom::character::complete::digit1;
use nom::combinator::all_consuming;
use nom::number::complete::recognize_float;
use nom::{IResult, Input, Parser};
use nom_locate::LocatedSpan;

use crate::ParseError;
use crate::legacy::Position;

/// A slice of the input that knows where it sits (byte offset, line).
pub(crate) type Span<'a> = LocatedSpan<&'a str>;

/// Reads a legacy file line by line, skipping blank and comment-only lines.
#[derive(Debug, Clone)]
pub(crate) struct Lines<'a> {
    file: &'a str,
    text: &'a str,
    rest: Span<'a>,
    /// Byte offset just past the last significant line handed out: where "unexpected end
    /// of file" errors point, so they land on the last line that has content.
    last_end: usize,
}

/// One significant line: its content with the comment, the line end and surrounding
/// whitespace removed. Never empty.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Line<'a> {
    pub span: Span<'a>,
}

fn split_line(i: Span<'_>) -> (Span<'_>, Span<'_>) {
    let parsed: IResult<Span<'_>, Span<'_>, ()> = take_till(|c| c == '\n').parse(i);
    match parsed {
        Ok((rest, line)) => {
            let rest = if rest.fragment().starts_with('\n') {
                rest.take_from(1)
            } else {
                rest
            };
            (rest, line)
        }
        // `take_till` on complete input cannot fail; treat it as "the rest is one line".
        Err(_) => (i.take_from(i.fragment().len()), i),
    }
}

fn next_token(i: Span<'_>) -> Option<(Span<'_>, Span<'_>)> {
    let parsed: IResult<Span<'_>, Span<'_>, ()> = (
        take_while(char::is_whitespace),
        take_till1(char::is_whitespace),
    )
        .map(|(_, tok)| tok)
        .parse(i);
    parsed.ok()
}

impl<'a> Lines<'a> {
    pub(crate) fn new(file: &'a str, text: &'a str) -> Self {
        Self {
            file,
            text,
            rest: Span::new(text),
            last_end: 0,
        }
    }

    /// The next significant line, or `None` at the end of the file.
    pub(crate) fn next_line(&mut self) -> Option<Line<'a>> {
        loop {
            if self.rest.fragment().is_empty() {
                return None;
            }
            let (rest, raw) = split_line(self.rest);
            self.rest = rest;
            let content = match raw.fragment().find('#') {
                Some(i) => raw.take(i),
                None => raw,
            };
            let content = content.take(content.fragment().trim_end().len());
            let lead = content.fragment().len() - content.fragment().trim_start().len();
            let content = content.take_from(lead);
            if content.fragment().is_empty() {
                continue;
            }
            self.last_end = content.location_offset() + content.fragment().len();
            return Some(Line { span: content });
        }
    }

    /// The next significant line, or an "expected `what`, found end of file" error.
    pub(crate) fn expect_line(&mut self, what: &str) -> Result<Line<'a>, ParseError> {
        self.next_line()
            .ok_or_else(|| self.eof_error(&format!("expected {what}, found end of file")))
    }

    /// An error at the end of the last significant line (or at the start of an empty file).
    pub(crate) fn eof_error(&self, message: &str) -> ParseError {
        ParseError::at_offset(self.file, self.text, self.last_end, message)
    }

    /// An error covering `span`.
    pub(crate) fn error(&self, span: Span<'_>, message: impl Into<String>) -> ParseError {
        ParseError::at_span(
            self.file,
            self.text,
            span.location_offset(),
            span.fragment().len().max(1),
            message,
        )
    }

    /// The whitespace-separated tokens of a line.
    pub(crate) fn tokens(line: Line<'a>) -> Tokens<'a> {
        Tokens { rest: line.span }
    }

    /// Parses a whole line as exactly `N` real numbers. `what` names them for messages,
    /// e.g. "x y z coordinates".
    pub(crate) fn reals<const N: usize>(
        &self,
        line: Line<'a>,
        what: &str,
    ) -> Result<([f64; N], [Span<'a>; N]), ParseError> {
        let mut values = [0.0; N];
        let mut spans = [line.span; N];
        let mut tokens = Self::tokens(line);
        for k in 0..N {
            let Some(tok) = tokens.next() else {
                let found = if k == 0 {
                    "nothing".to_owned()
                } else {
                    format!("{k}")
                };
                return Err(self.error(
                    line.span,
                    format!("expected {N} numbers ({what}), found {found}"),
                ));
            };
            values[k] = self.real(tok, what)?;
            spans[k] = tok;
        }
        if let Some(extra) = tokens.next() {
            return Err(self.error(
                extra,
                format!(
                    "expected {N} numbers ({what}), found more: `{}`",
                    extra.fragment()
                ),
            ));
        }
        Ok((values, spans))
    }

    /// A token as a finite real number.
    pub(crate) fn real(&self, tok: Span<'_>, what: &str) -> Result<f64, ParseError> {
        let s = *tok.fragment();
        let literal: IResult<&str, &str, ()> = all_consuming(recognize_float).parse(s);
        if literal.is_err() {
            let bare = s.trim_start_matches(['+', '-']).to_ascii_lowercase();
            let message = if matches!(bare.as_str(), "nan" | "inf" | "infinity") {
                format!("expected a finite number ({what}), found `{s}`")
            } else {
                format!("expected a number ({what}), found `{s}`")
            };
            return Err(self.error(tok, message));
        }
        match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(self.error(
                tok,
                format!("expected a finite number ({what}), found `{s}`, which overflows"),
            )),
        }
    }

    /// A token as a non-negative decimal integer (no sign, no fraction).
    pub(crate) fn unsigned(&self, tok: Span<'_>, what: &str) -> Result<u64, ParseError> {
        let s = *tok.fragment();
        let digits: IResult<&str, &str, ()> = all_consuming(digit1).parse(s);
        if digits.is_err() {
            return Err(self.error(
                tok,
                format!("expected a whole number ({what}), found `{s}`"),
            ));
        }
        s.parse::<u64>().map_err(|_| {
            self.error(
                tok,
                format!("expected a whole number ({what}), found `{s}`, which is too large"),
            )
        })
    }

    /// A whole line holding exactly one whole number.
    pub(crate) fn single_unsigned(&self, line: Line<'a>, what: &str) -> Result<u64, ParseError> {
        let mut tokens = Self::tokens(line);
        let tok = tokens.next().unwrap_or(line.span);
        let v = self.unsigned(tok, what)?;
        if let Some(extra) = tokens.next() {
            return Err(self.error(
                extra,
                format!(
                    "expected only {what} on this line, found `{}`",
                    extra.fragment()
                ),
            ));
        }
        Ok(v)
    }
}

/// Whitespace-separated tokens of one line.
#[derive(Debug, Clone)]
pub(crate) struct Tokens<'a> {
    rest: Span<'a>,
}

impl<'a> Iterator for Tokens<'a> {
    type Item = Span<'a>;
    fn next(&mut self) -> Option<Span<'a>> {
        let (rest, tok) = next_token(self.rest)?;
        self.rest = rest;
        Some(tok)
    }
}

/// Where a span starts, 1-based, columns in characters.
pub(crate) fn position(span: Span<'_>) -> Position {
    Position {
        line: span.location_line() as usize,
        column: span.get_utf8_column(),
    }
}

/// True when `s` would be read back as a number, so a name must not look like one.
pub(crate) fn looks_numeric(s: &str) -> bool {
    let literal: IResult<&str, &str, ()> = all_consuming(recognize_float).parse(s);
    literal.is_ok()
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal, so the
// tests compare floats exactly.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn lines_skip_blanks_comments_and_crlf() {
        let text = "\r\n  # header\r\n1 2\t3  \r\n\n# x\n4 # four\n";
        let mut lines = Lines::new("t", text);
        let a = lines.next_line().unwrap();
        assert_eq!(*a.span.fragment(), "1 2\t3");
        assert_eq!(position(a.span), Position { line: 3, column: 1 });
        let b = lines.next_line().unwrap();
        assert_eq!(*b.span.fragment(), "4");
        assert_eq!(position(b.span).line, 6);
        assert!(lines.next_line().is_none());
    }

    #[test]
    fn numbers_are_strict() {
        let lines = Lines::new("t", "x");
        let tok = |s: &'static str| Span::new(s);
        assert_eq!(lines.real(tok("-4.096910"), "x").unwrap(), -4.096_91);
        assert_eq!(lines.real(tok(".5"), "x").unwrap(), 0.5);
        assert_eq!(lines.real(tok("1e-3"), "x").unwrap(), 0.001);
        assert_eq!(lines.real(tok("+2."), "x").unwrap(), 2.0);
        for bad in [
            "NaN", "-inf", "Infinity", "1,5", "0x10", "1e", "--1", "1e999", "", "1.2.3",
        ] {
            assert!(lines.real(tok(bad), "x").is_err(), "{bad} accepted");
        }
        let e = lines.real(tok("nan"), "x").unwrap_err();
        assert!(e.message.contains("finite"), "{}", e.message);
        assert_eq!(lines.unsigned(tok("0042"), "n").unwrap(), 42);
        for bad in ["-1", "+1", "1.0", "1e3", "99999999999999999999999"] {
            assert!(lines.unsigned(tok(bad), "n").is_err(), "{bad} accepted");
        }
    }

    #[test]
    fn end_of_file_errors_point_at_the_last_content() {
        let mut lines = Lines::new("t", "12\n\n\n");
        lines.next_line().unwrap();
        let e = lines.expect_line("a facet").unwrap_err();
        assert_eq!((e.line, e.column), (1, 3));
        let lines = Lines::new("t", "");
        let e = lines.eof_error("expected something");
        assert_eq!((e.line, e.column), (1, 1));
    }
}
