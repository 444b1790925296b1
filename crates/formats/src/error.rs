use std::sync::Arc;

use miette::{Diagnostic, NamedSource, SourceSpan};

/// A malformed input: which file, where in it, and what was expected there.
///
/// `Display` gives the one-line `file:line:column: message` form that editors and `grep`
/// understand; as a [`Diagnostic`] it also shows the source line with the span underlined.
/// Lines and columns count from 1; columns count characters, not bytes.
#[derive(Debug, Clone, thiserror::Error, Diagnostic)]
#[error("{file}:{line}:{column}: {message}")]
pub struct ParseError {
    /// The file name as the user gave it (`<stdin>` for standard input).
    pub file: String,
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
    /// What is wrong, said as "expected X, found Y" where that fits.
    pub message: String,
    // Behind an `Arc` so that `Result<_, ParseError>` stays small (clippy's
    // `result_large_err`) and cloning an error does not copy the file.
    #[source_code]
    source_code: Arc<NamedSource<String>>,
    #[label("here")]
    span: SourceSpan,
    #[help]
    help: Option<String>,
}

impl ParseError {
    /// An error at byte `offset` of the text `source` (clamped to its length), with a span of
    /// one character.
    #[must_use]
    pub fn at_offset(
        file: impl Into<String>,
        source: &str,
        offset: usize,
        message: impl Into<String>,
    ) -> Self {
        Self::at_span(file, source, offset, 1, message)
    }

    /// An error covering `len` bytes from byte `offset` of `source`.
    #[must_use]
    pub fn at_span(
        file: impl Into<String>,
        source: &str,
        offset: usize,
        len: usize,
        message: impl Into<String>,
    ) -> Self {
        let file = file.into();
        let offset = floor_char_boundary(source, offset.min(source.len()));
        let len = len.min(source.len() - offset);
        let (line, column) = line_column(source, offset);
        Self {
            source_code: Arc::new(NamedSource::new(file.clone(), source.to_owned())),
            file,
            line,
            column,
            message: message.into(),
            span: SourceSpan::new(offset.into(), len),
            help: None,
        }
    }

    /// An error in a binary file (GLB, binary raw scene) at byte `offset`: reported as line
    /// 1, column `offset + 1`, without a source snippet.
    #[must_use]
    pub fn in_binary(file: impl Into<String>, offset: usize, message: impl Into<String>) -> Self {
        let file = file.into();
        Self {
            source_code: Arc::new(NamedSource::new(file.clone(), String::new())),
            file,
            line: 1,
            column: offset.saturating_add(1),
            message: message.into(),
            span: SourceSpan::new(0.into(), 0),
            help: None,
        }
    }

    /// Adds advice on how to fix the input.
    #[must_use]
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// The byte offset and length of the span in the source.
    #[must_use]
    pub fn span(&self) -> (usize, usize) {
        (self.span.offset(), self.span.len())
    }
}

/// The 1-based line and character column of byte `offset` in `source`.
#[must_use]
pub fn line_column(source: &str, offset: usize) -> (usize, usize) {
    let offset = floor_char_boundary(source, offset.min(source.len()));
    let before = &source[..offset];
    let line = before.bytes().filter(|&b| b == b'\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

/// The byte offset of 1-based `line` and character `column` in `source`, the inverse of
/// [`line_column`]: how a position reported by another parser (RON's `line:col`) becomes
/// a span. A column past the line's end gives the line's end; a line past the end of the
/// text gives the text's length.
#[must_use]
pub fn offset_of(source: &str, line: usize, column: usize) -> usize {
    let mut offset = 0;
    for (i, l) in source.split_inclusive('\n').enumerate() {
        if i + 1 == line {
            return offset
                + l.char_indices()
                    .nth(column.saturating_sub(1))
                    .map_or(l.len(), |(b, _)| b);
        }
        offset += l.len();
    }
    source.len()
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_count_from_one_in_characters() {
        assert_eq!(line_column("abc", 0), (1, 1));
        assert_eq!(line_column("ab\ncd", 3), (2, 1));
        assert_eq!(line_column("ab\ncd", 4), (2, 2));
        // 'é' is two bytes but one column.
        assert_eq!(line_column("é x", 3), (1, 3));
    }

    #[test]
    fn offset_of_inverts_line_column() {
        let t = "ab\ncé d\n";
        for offset in [0, 1, 3, 4, 6, 7] {
            let (line, column) = line_column(t, offset);
            assert_eq!(offset_of(t, line, column), offset);
        }
        assert_eq!(offset_of(t, 9, 1), t.len());
        assert_eq!(
            offset_of(t, 1, 99),
            3,
            "past the line's end: the end of the line"
        );
    }

    #[test]
    fn offsets_past_the_end_or_inside_a_character_are_clamped() {
        assert_eq!(line_column("ab", 99), (1, 3));
        let e = ParseError::at_offset("f", "é", 1, "m");
        assert_eq!((e.line, e.column), (1, 1));
        let e = ParseError::at_offset("f", "", 5, "m");
        assert_eq!((e.line, e.column), (1, 1));
    }

    #[test]
    fn the_rendered_report_shows_the_line() {
        let src = "1\n2 x\n";
        let e = ParseError::at_offset("s.txt", src, 4, "expected a number, found `x`");
        let mut out = String::new();
        miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
            .render_report(&mut out, &e)
            .unwrap();
        assert!(out.contains("s.txt:2:3"), "{out}");
        assert!(out.contains("2 x"), "{out}");
    }
}
