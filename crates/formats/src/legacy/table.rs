//! What the DIRTRAN tables (`.ems`, `.atm`, `.dwr`, `.rsd`, `.rtt`) share: one record per
//! line, a fixed number of reals per record, rules on the values checked identically by
//! the parser (pointing at the token) and by the writer (naming the row).

use std::fmt::Write as _;

use super::lex::{Lines, Span, position};
use super::{Position, WriteError, WriteErrorKind, real};
use crate::ParseError;

/// A row as read, with where each value is.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RawRow<'a, const N: usize> {
    pub values: [f64; N],
    pub spans: [Span<'a>; N],
    pub position: Position,
}

/// A broken rule: which row (from 0), which column (from 0), and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Violation {
    pub row: usize,
    pub column: usize,
    pub message: String,
}

impl Violation {
    pub(crate) fn new(row: usize, column: usize, message: impl Into<String>) -> Self {
        Self {
            row,
            column,
            message: message.into(),
        }
    }
}

/// Reads every remaining significant line as a row of `N` reals named by `columns`.
pub(crate) fn read_rows<'a, const N: usize>(
    lines: &mut Lines<'a>,
    columns: &str,
) -> Result<Vec<RawRow<'a, N>>, ParseError> {
    let mut rows = Vec::new();
    while let Some(line) = lines.next_line() {
        let (values, spans) = lines.reals::<N>(line, columns)?;
        rows.push(RawRow {
            values,
            spans,
            position: position(line.span),
        });
    }
    if rows.is_empty() {
        return Err(lines.eof_error(&format!(
            "expected at least one row ({columns}), found end of file"
        )));
    }
    Ok(rows)
}

/// Turns a violation found in parsed rows into an error at the offending token.
pub(crate) fn at_token<const N: usize>(
    lines: &Lines<'_>,
    rows: &[RawRow<'_, N>],
    v: Violation,
) -> ParseError {
    match rows.get(v.row).and_then(|r| r.spans.get(v.column)) {
        Some(span) => lines.error(*span, v.message),
        None => lines.eof_error(&v.message),
    }
}

/// Writes rows of reals, one per line, after checking them with `check`.
pub(crate) fn write_rows<const N: usize>(
    rows: &[[f64; N]],
    check: impl Fn(&[[f64; N]]) -> Result<(), Violation>,
) -> Result<String, WriteError> {
    if rows.is_empty() {
        return Err(WriteError::new("table", WriteErrorKind::Empty));
    }
    for (i, row) in rows.iter().enumerate() {
        super::check_finite(|| format!("row {}", i + 1), row)?;
    }
    check(rows).map_err(|v| {
        WriteError::new(
            format!("row {}", v.row + 1),
            WriteErrorKind::OutOfRange(v.message),
        )
    })?;
    let mut out = String::with_capacity(rows.len() * N * 12);
    for row in rows {
        let mut first = true;
        for &v in row {
            if !first {
                out.push(' ');
            }
            first = false;
            let _ = write!(out, "{}", real(v));
        }
        out.push('\n');
    }
    Ok(out)
}

/// `lo <= v <= hi`, or a message naming the quantity.
pub(crate) fn in_range(
    row: usize,
    column: usize,
    v: f64,
    lo: f64,
    hi: f64,
    what: &str,
) -> Result<(), Violation> {
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(Violation::new(
            row,
            column,
            format!("expected {what} from {lo} to {hi}, found {v}"),
        ))
    }
}

/// `v >= 0`.
pub(crate) fn non_negative(row: usize, column: usize, v: f64, what: &str) -> Result<(), Violation> {
    if v >= 0.0 {
        Ok(())
    } else {
        Err(Violation::new(
            row,
            column,
            format!("expected {what} of 0 or more, found {v}"),
        ))
    }
}

/// `v > 0`.
pub(crate) fn positive(row: usize, column: usize, v: f64, what: &str) -> Result<(), Violation> {
    if v > 0.0 {
        Ok(())
    } else {
        Err(Violation::new(
            row,
            column,
            format!("expected {what} above 0, found {v}"),
        ))
    }
}

/// Column `column` strictly increases from row to row.
pub(crate) fn increasing<const N: usize>(
    rows: &[[f64; N]],
    column: usize,
    what: &str,
) -> Result<(), Violation> {
    for (i, pair) in rows.windows(2).enumerate() {
        let (prev, v) = (pair[0][column], pair[1][column]);
        if v <= prev {
            return Err(Violation::new(
                i + 1,
                column,
                format!("expected {what} to increase from row to row, found {v} after {prev}"),
            ));
        }
    }
    Ok(())
}
