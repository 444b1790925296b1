//! `.cor`: the angular transmission correction (thesis §3.2.2, Figure 9, eq. 10):
//! `τ(θ) = τ(0) · (a1 + a2·sec θ + a3·sec² θ)`.
//!
//! ```text
//! 1.10293990 -0.11240644 0.00703145
//! ```
//!
//! Exactly three finite numbers, dimensionless, normally on one line (any whitespace
//! layout is read, as `fscanf` would). θ is the nadir angle at the observer. There is no
//! range rule: a least-squares fit need not give `a1 + a2 + a3 = 1`.

use super::lex::{Lines, position};
use super::{Position, WriteError, check_finite, real};
use crate::ParseError;

/// A parsed `.cor` file.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CorFile {
    /// a1, a2, a3 of eq. 10, dimensionless.
    pub coefficients: [f64; 3],
    /// Where a1 is.
    pub position: Position,
}

/// Reads a `.cor` file.
///
/// # Errors
/// A [`ParseError`] for fewer or more than three numbers or a value that is not a finite
/// number.
pub fn parse(file: &str, text: &str) -> Result<CorFile, ParseError> {
    const NAMES: [&str; 3] = ["a1", "a2", "a3"];
    let mut lines = Lines::new(file, text);
    let mut coefficients = [0.0; 3];
    let mut n = 0;
    let mut first = None;
    while let Some(line) = lines.next_line() {
        for tok in Lines::tokens(line) {
            let Some(name) = NAMES.get(n) else {
                return Err(lines.error(
                    tok,
                    format!(
                        "expected exactly 3 coefficients (a1 a2 a3), found more: `{}`",
                        tok.fragment()
                    ),
                ));
            };
            coefficients[n] = lines.real(tok, &format!("coefficient {name} of eq. 10"))?;
            first.get_or_insert(position(tok));
            n += 1;
        }
    }
    if n < 3 {
        return Err(lines.eof_error(&format!(
            "expected 3 coefficients (a1 a2 a3), found {n} before the end of file"
        )));
    }
    Ok(CorFile {
        coefficients,
        position: first.unwrap_or_default(),
    })
}

/// Writes a `.cor` file: `a1 a2 a3` on one line.
///
/// # Errors
/// A [`WriteError`] when a coefficient is not finite.
pub fn write(cor: &CorFile) -> Result<String, WriteError> {
    let [a1, a2, a3] = cor.coefficients;
    check_finite(|| "coefficients".to_owned(), &cor.coefficients)?;
    Ok(format!("{} {} {}\n", real(a1), real(a2), real(a3)))
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn reads_three_numbers() {
        let c = parse("c.cor", "1.10293990 -0.11240644 0.00703145\n").unwrap();
        assert_eq!(c.coefficients, [1.102_939_9, -0.112_406_44, 0.007_031_45]);
        assert_eq!(
            parse("c", "1\n2\n3\n").unwrap().coefficients,
            [1.0, 2.0, 3.0]
        );
        let e = parse("c", "1 2\n").unwrap_err();
        assert!(e.message.contains("found 2"), "{e}");
        assert_eq!((e.line, e.column), (1, 4));
        let e = parse("c", "1 2 3 4\n").unwrap_err();
        assert_eq!((e.line, e.column), (1, 7));
        let e = parse("c", "1 NaN 3\n").unwrap_err();
        assert_eq!((e.line, e.column), (1, 3));
        assert!(
            write(&CorFile {
                coefficients: [1.0, f64::INFINITY, 0.0],
                position: Position::default()
            })
            .is_err()
        );
    }
}
