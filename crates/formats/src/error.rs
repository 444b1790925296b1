use std::sync::Arc;

use miette::{Diagnostic, MietteError, MietteSpanContents, SourceCode, SourceSpan, SpanContents};

/// How many characters of a line a snippet shows on each side of the error. A machine-written
/// file can hold its whole content on one line; quoting it in full would flood the terminal,
/// and the diagnostic renderer cannot pad past column 65,535.
const SNIPPET_HALF_WIDTH: usize = 60;

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
    // `result_large_err`) and cloning an error does not copy the snippet.
    // `None` for a binary file, which has no text to show: the message's `file:1:column`
    // (the byte offset) is the whole location.
    #[source_code]
    source_code: Option<Arc<Snippet>>,
    /// The span in the snippet, which is what the renderer underlines.
    #[label("here")]
    label: Option<SourceSpan>,
    #[help]
    help: Option<String>,
}

/// The few lines around an error, each cut to at most [`SNIPPET_HALF_WIDTH`] characters on
/// either side of the error's column, with `…` where text was cut. It reports the lines and
/// columns of the whole file, so the rendered snippet keeps the real line numbers and its
/// caret under the offending character, however long the line.
#[derive(Debug)]
struct Snippet {
    name: String,
    text: String,
    /// The 0-based line of the file where `text` starts.
    first_line: usize,
    /// The 0-based line of `text` that holds the error.
    error_line: usize,
    /// What to add to a byte column of the error line in `text` to get the file's.
    column_shift: isize,
    /// The error's byte offset and length in the whole source, for [`ParseError::span`].
    span: (usize, usize),
}

impl SourceCode for Snippet {
    fn read_span<'a>(
        &'a self,
        span: &SourceSpan,
        context_lines_before: usize,
        context_lines_after: usize,
    ) -> Result<Box<dyn SpanContents<'a> + 'a>, MietteError> {
        let c = self
            .text
            .read_span(span, context_lines_before, context_lines_after)?;
        let column = if c.line() == self.error_line {
            c.column().saturating_add_signed(self.column_shift)
        } else {
            c.column()
        };
        Ok(Box::new(MietteSpanContents::new_named(
            self.name.clone(),
            c.data(),
            *c.span(),
            c.line() + self.first_line,
            column,
            c.line_count(),
        )))
    }
}

impl Snippet {
    /// The snippet of `source` around byte `offset` (a char boundary), with the error's span
    /// of `len` bytes mapped into it (kept to the error's line).
    fn around(name: String, source: &str, offset: usize, len: usize) -> (Self, SourceSpan) {
        let line_start = source[..offset].rfind('\n').map_or(0, |i| i + 1);
        let line_end = source[offset..]
            .find('\n')
            .map_or(source.len(), |i| offset + i);
        let column = source[line_start..offset].chars().count();
        let from = column.saturating_sub(SNIPPET_HALF_WIDTH);
        let to = column + SNIPPET_HALF_WIDTH;
        // A CRLF file's lines keep no `\r`: the renderer would count it as a line break.
        let prev = (line_start > 0).then(|| {
            let start = source[..line_start - 1].rfind('\n').map_or(0, |i| i + 1);
            source[start..line_start - 1].trim_end_matches('\r')
        });
        let next = (line_end < source.len()).then(|| {
            let rest = &source[line_end + 1..];
            rest[..rest.find('\n').unwrap_or(rest.len())].trim_end_matches('\r')
        });
        let line_end = if source[offset..line_end].ends_with('\r') {
            line_end - 1
        } else {
            line_end
        };
        let mut text = String::new();
        let mut error_line = 0;
        if let Some(p) = prev {
            text.push_str(&cut(p, from, to).0);
            text.push('\n');
            error_line = 1;
        }
        let (line, kept_from) = cut(&source[line_start..line_end], from, to);
        let prefix = if kept_from > 0 { "…".len() } else { 0 };
        let in_line = offset - line_start - kept_from + prefix;
        let label_offset = text.len() + in_line;
        let label_len = len.min(line.len().saturating_sub(in_line));
        text.push_str(&line);
        if let Some(n) = next {
            text.push('\n');
            text.push_str(&cut(n, from, to).0);
        }
        let first_line = source[..line_start].bytes().filter(|&b| b == b'\n').count() - error_line;
        #[allow(clippy::cast_possible_wrap)] // both are byte offsets within one line
        let column_shift = kept_from as isize - prefix as isize;
        let snippet = Self {
            name,
            text,
            first_line,
            error_line,
            column_shift,
            span: (offset, len),
        };
        (snippet, SourceSpan::new(label_offset.into(), label_len))
    }
}

/// Characters `from..to` of `line`, with `…` marking a cut at either end, and the byte offset
/// in `line` where the kept text starts.
fn cut(line: &str, from: usize, to: usize) -> (String, usize) {
    let byte = |chars: usize| {
        line.char_indices()
            .nth(chars)
            .map_or(line.len(), |(b, _)| b)
    };
    let (start, end) = (byte(from), byte(to));
    let mut out = String::new();
    if start > 0 {
        out.push('…');
    }
    out.push_str(&line[start..end]);
    if end < line.len() {
        out.push('…');
    }
    (out, start)
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

    /// An error at 1-based `line` and character `column` of `source` (a legacy parser's
    /// `legacy::Position`), with a span of one character; past the text, at its end.
    #[must_use]
    pub fn at_line_column(
        file: impl Into<String>,
        source: &str,
        line: usize,
        column: usize,
        message: impl Into<String>,
    ) -> Self {
        Self::at_offset(file, source, offset_of(source, line, column), message)
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
        let (snippet, label) = Snippet::around(file.clone(), source, offset, len);
        let label = Some(label);
        Self {
            source_code: Some(Arc::new(snippet)),
            file,
            line,
            column,
            message: message.into(),
            label,
            help: None,
        }
    }

    /// An error in a binary file (GLB, binary raw scene) at byte `offset`: reported as line
    /// 1, column `offset + 1`, without a source snippet.
    #[must_use]
    pub fn in_binary(file: impl Into<String>, offset: usize, message: impl Into<String>) -> Self {
        let file = file.into();
        Self {
            source_code: None,
            file,
            line: 1,
            column: offset.saturating_add(1),
            message: message.into(),
            label: None,
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
        self.source_code.as_ref().map_or((0, 0), |s| s.span)
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

    fn render(e: &ParseError) -> String {
        let mut out = String::new();
        miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
            .render_report(&mut out, e)
            .unwrap();
        out
    }

    #[test]
    fn an_error_past_column_65535_renders_a_cut_line_with_its_caret() {
        // A machine-written one-line file with a typo at column 72,032: the renderer used to
        // panic padding the caret ("Formatting argument out of range").
        let mut src = "a".repeat(72_031);
        src.push('X');
        src.push_str(&"b".repeat(10_000_000));
        src.push_str("\nnext line\n");
        let e = ParseError::at_offset("big.ron", &src, 72_031, "expected `a`, found `X`");
        assert_eq!((e.line, e.column), (1, 72_032));
        let out = render(&e);
        assert!(out.len() < 2_000, "the snippet is cut: {} bytes", out.len());
        assert!(out.contains("big.ron:1:72032"), "{out}");
        let line = out.lines().find(|l| l.contains("│ …a")).unwrap();
        let caret = out.lines().find(|l| l.contains('┬')).unwrap();
        let col = |l: &str, c: char| l.chars().position(|x| x == c).unwrap();
        assert_eq!(col(line, 'X'), col(caret, '┬'), "caret under the X:\n{out}");
        assert!(line.contains('…'), "the cut is marked: {out}");
        assert!(out.contains(" 2 │ …"), "the next line, cut alike: {out}");
    }

    #[test]
    fn a_crlf_file_shows_each_line_once_with_its_number() {
        let src = "o cube\r\nv nan 0 0\r\nv nan 0 0\r\nv 1 2 3\r\n";
        let e = ParseError::at_offset("f.obj", src, 10, "expected a finite x");
        assert_eq!((e.line, e.column), (2, 3));
        let out = render(&e);
        assert!(out.contains(" 1 │ o cube\n"), "{out}");
        assert!(out.contains(" 2 │ v nan 0 0\n"), "{out}");
        assert!(out.contains(" 3 │ v nan 0 0\n"), "{out}");
        assert!(!out.contains('\r'), "{out:?}");
    }

    #[test]
    fn a_snippet_keeps_the_real_line_numbers() {
        let src = "one\ntwo\nthree x\nfour\n";
        let e = ParseError::at_offset("f", src, 14, "bad");
        let out = render(&e);
        assert!(out.contains(" 3 │ three x"), "{out}");
        assert!(out.contains(" 2 │ two"), "{out}");
        assert!(out.contains(" 4 │ four"), "{out}");
        assert!(out.contains("[f:3:7]"), "{out}");
    }
}
