//! LOWTRAN7's `TAPE6`, the printed output: what irsig reads of it is each calculation's
//! spectral table, its integrated values and LOWTRAN's messages (why it rejected a path).
//! Spec page: `formats/radtran/lowtran-tape6.md`.
//!
//! TAPE6 is a line-printer listing: column 1 is a carriage-control character (`1` new
//! page, `0` blank line before), then the echo of each card (`0 CARD 1  *****  …`), the
//! profiles, the path geometry, the spectral table in pages, and the integrated values:
//!
//! ```text
//! 0   FREQ WAVLEN   ATMOS RADIANCE       INTEGRAL TOTAL
//!   (CM-1) (MICRN)  (CM-1)    (MICRN)   (CM-1)    TRANS
//!
//!     710.  14.085  1.07E-05  5.37E-04  2.66E-05   0.1245
//! 0INTEGRATED ABSORPTION FROM  710 TO 1250 CM-1 =     87.10 CM-1
//!  AVERAGE TRANSMITTANCE =0.8387
//! 0INTEGRATED RADIANCE =  7.830E-04 WATTS CM-2 STER-1
//! 0 CARD 5 *****    3
//! ```
//!
//! Each calculation ends with the echo of card 5 (`0 CARD 5 *****`), so that line splits
//! the file into runs, in the deck's order. A run whose path LOWTRAN cannot make says
//! `GEO:  IERROR NE 0` and has no table.

use super::{Source, TextLine, number, text_lines};
use crate::ParseError;
use crate::legacy::Position;

/// A message LOWTRAN printed for a run: an error, a warning or a value it reset.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    /// The text, without the carriage-control character.
    pub text: String,
    /// Where it is.
    pub position: Position,
}

/// A run's spectral table, column by column.
#[derive(Debug, Clone, PartialEq)]
pub struct Tape6Table {
    /// The columns' names; the first two are `FREQ` (cm⁻¹) and `WAVELENGTH` (µm).
    pub names: Vec<&'static str>,
    /// `columns[c][row]`, wavenumbers increasing.
    pub columns: Vec<Vec<f64>>,
}

/// One calculation's part of TAPE6.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Tape6Run {
    /// IEMSCT of the run (card 1's echo, or the last one before a repeat).
    pub iemsct: Option<i64>,
    /// The spectral table, if LOWTRAN made one.
    pub table: Option<Tape6Table>,
    /// `INTEGRATED ABSORPTION FROM … = X CM-1`: ∫(1 − τ) dν over the range, cm⁻¹.
    pub integrated_absorption_per_cm: Option<f64>,
    /// `AVERAGE TRANSMITTANCE = X`.
    pub average_transmittance: Option<f64>,
    /// `INTEGRATED RADIANCE = X WATTS CM-2 STER-1`: ∫ L dν, W cm⁻² sr⁻¹.
    pub integrated_radiance_w_cm2_sr: Option<f64>,
    /// Errors, warnings and resets LOWTRAN printed.
    pub messages: Vec<Message>,
    /// The first `ATMOSPHERIC PROFILES` table: altitude (km), pressure (mb) and
    /// temperature (K) of each of LOWTRAN's levels (a run after `IRPT = 3` has none).
    pub profile: Vec<[f64; 3]>,
    /// Whether LOWTRAN gave up on the path (`GEO:  IERROR NE 0`).
    pub rejected: bool,
    /// Where the run starts.
    pub position: Position,
}

/// A LOWTRAN7 `TAPE6`.
#[derive(Debug, Clone, PartialEq)]
pub struct LowtranTape6 {
    /// One run per calculation, in order.
    pub runs: Vec<Tape6Run>,
}

const RADIANCE: [&str; 6] = [
    "FREQ",
    "WAVELENGTH",
    "RADIANCE PER CM-1",
    "RADIANCE PER MICRON",
    "INTEGRAL",
    "TRANS",
];
const TRANSMITTANCE: [&str; 14] = [
    "FREQ",
    "WAVELENGTH",
    "TOTAL TRANS",
    "H2O TRANS",
    "CO2+ TRANS",
    "OZONE TRANS",
    "TRACE TRANS",
    "N2 CONT TRANS",
    "H2O CONT TRANS",
    "MOL SCAT TRANS",
    "AER-HYD TRANS",
    "HNO3 TRANS",
    "AER-HYD ABS",
    "INTEGRATED ABSORPTION",
];

const MESSAGE_WORDS: [&str; 7] = [
    "ERROR",
    "CANNOT",
    "WARNING",
    "RESET",
    "NOT USEABLE",
    "INVALID",
    "IERROR",
];

fn body<'a>(line: &TextLine<'a>) -> &'a str {
    // Column 1 is carriage control.
    line.text.get(1..).unwrap_or("")
}

/// The number after the first `=` of `text`.
fn value_after_equals(text: &str) -> Option<&str> {
    text.split_once('=')?.1.split_whitespace().next()
}

fn table_names(iemsct: i64) -> Option<&'static [&'static str]> {
    match iemsct {
        0 => Some(&TRANSMITTANCE),
        1 => Some(&RADIANCE),
        _ => None,
    }
}

/// Reads a LOWTRAN7 `TAPE6`.
///
/// Only IEMSCT 0 and 1 tables are read (transmittance and thermal radiance); the runs of
/// other modes keep their integrated values and messages.
///
/// # Errors
/// A [`ParseError`] at the place: an empty file, a file with no `***** LOWTRAN 7 *****`
/// banner, a table row whose count of numbers is not the table's, a value that is not a
/// finite number (LOWTRAN prints `Infinity` or asterisks when a deck's numbers overflow),
/// wavenumbers that do not increase, or an integrated value that is not a number.
pub fn parse(file: &str, text: &str) -> Result<LowtranTape6, ParseError> {
    let src = Source { file, text };
    let lines = text_lines(text);
    if !lines
        .iter()
        .any(|l| l.text.contains("***** LOWTRAN 7 *****"))
    {
        return Err(src.error(
            0,
            0,
            "expected a LOWTRAN7 TAPE6 (its banner `***** LOWTRAN 7 *****`), found none",
        ));
    }
    let mut runs = Vec::new();
    let mut run = Tape6Run::default();
    let mut iemsct: Option<i64> = None;
    let mut in_table = false;
    let mut started = false;
    // 0: outside, 1: after the `ATMOSPHERIC PROFILES` banner, 2: in its Z P T table.
    let mut profile_state = 0;
    for line in &lines {
        let b = body(line);
        let t = b.trim();
        if !started {
            run.position = line.position();
            started = true;
        }
        if let Some(rest) = t.strip_prefix("CARD 1  *****") {
            let f: Vec<&str> = rest.split_whitespace().collect();
            iemsct = f.get(2).and_then(|s| s.parse().ok());
        }
        if t.starts_with("ATMOSPHERIC PROFILES") && run.profile.is_empty() {
            profile_state = 1;
            continue;
        }
        if profile_state == 1 && t.starts_with('I') && t.contains(" Z ") {
            profile_state = 2;
            continue;
        }
        if profile_state == 2 {
            let row_line = TextLine {
                text: b,
                offset: line.offset + (line.text.len() - b.len()),
                number: line.number,
            };
            let tokens = row_line.tokens();
            // A row starts with its level number I; anything else (the units line, a blank
            // line, the next table) is not a row.
            let is_row = tokens
                .first()
                .is_some_and(|&(_, i)| i.bytes().all(|c| c.is_ascii_digit()));
            if is_row {
                let value = |k: usize| tokens.get(k).and_then(|&(_, v)| number(v));
                if let (Some(z), Some(p), Some(tk)) = (value(1), value(2), value(3)) {
                    run.profile.push([z, p, tk]);
                    continue;
                }
                let (at, found) = (1..4)
                    .find_map(|k| match tokens.get(k) {
                        Some(&(at, v)) if number(v).is_none() => Some((at, v)),
                        None => Some((line.offset + line.text.len(), "the end of the line")),
                        _ => None,
                    })
                    .unwrap_or((line.offset, ""));
                return Err(src.error(
                    at,
                    found.len(),
                    format!(
                        "expected a profile row (I, then Z in km, P in mb and T in K as finite \
                         numbers), found `{found}`"
                    ),
                ));
            }
            if !run.profile.is_empty() {
                profile_state = 0;
            }
        }
        if t.starts_with("CARD 5 *****") {
            run.iemsct = iemsct;
            runs.push(std::mem::take(&mut run));
            in_table = false;
            profile_state = 0;
            started = false;
            continue;
        }
        if MESSAGE_WORDS.iter().any(|w| t.contains(w)) {
            run.messages.push(Message {
                text: t.to_owned(),
                position: line.position(),
            });
            if t.contains("IERROR NE 0") {
                run.rejected = true;
            }
        }
        let integrated = |what: &str| -> Result<Option<f64>, ParseError> {
            let v = value_after_equals(t).unwrap_or("");
            match number(v) {
                Some(x) => Ok(Some(x)),
                None => {
                    let at =
                        line.offset + b.len() - b.trim_start().len() + 1 + t.find('=').unwrap_or(0);
                    Err(src.error(
                        at,
                        1,
                        format!("expected {what} (a number) after `=`, found `{v}`"),
                    ))
                }
            }
        };
        if t.starts_with("INTEGRATED ABSORPTION") {
            in_table = false;
            run.integrated_absorption_per_cm = integrated("the integrated absorption in cm-1")?;
            continue;
        }
        if t.starts_with("AVERAGE TRANSMITTANCE") {
            run.average_transmittance = integrated("the average transmittance")?;
            continue;
        }
        if t.starts_with("INTEGRATED RADIANCE") {
            in_table = false;
            run.integrated_radiance_w_cm2_sr =
                integrated("the integrated radiance in W cm-2 sr-1")?;
            continue;
        }
        if t.starts_with("FREQ WAVLEN") || t.starts_with("FREQ WAVELENGTH") {
            in_table = true;
            continue;
        }
        if !in_table {
            continue;
        }
        let Some(names) = iemsct.and_then(table_names) else {
            continue;
        };
        // Tokens after the carriage-control column.
        let body_line = TextLine {
            text: b,
            offset: line.offset + (line.text.len() - b.len()),
            number: line.number,
        };
        let tokens = body_line.tokens();
        let Some(&(_, first)) = tokens.first() else {
            continue;
        };
        // Page headers and unit lines (`1/CM  MICRONS …`) inside the table: not a row.
        // A row starts with its wavenumber, which LOWTRAN prints `F7.0` (`710.`).
        if number(first).is_none() || !first.ends_with('.') {
            continue;
        }
        if tokens.len() != names.len() {
            let at = tokens
                .get(names.len())
                .map_or(line.offset + line.text.len(), |t| t.0);
            return Err(src.error(
                at,
                1,
                format!(
                    "expected {} numbers in a row of the IEMSCT = {} table ({}), found {}",
                    names.len(),
                    iemsct.unwrap_or(0),
                    names.join(", "),
                    tokens.len()
                ),
            ));
        }
        let table = run.table.get_or_insert_with(|| Tape6Table {
            names: names.to_vec(),
            columns: vec![Vec::new(); names.len()],
        });
        for (c, &(at, tok)) in tokens.iter().enumerate() {
            let Some(v) = number(tok) else {
                return Err(src.error(
                    at,
                    tok.len(),
                    format!("expected {} (a finite number), found `{tok}`", names[c]),
                ));
            };
            if c == 0
                && let Some(&last) = table.columns[0].last()
                && v <= last
            {
                return Err(src.error(
                    at,
                    tok.len(),
                    format!("wavenumbers must strictly increase: {v} cm-1 follows {last} cm-1"),
                ));
            }
            table.columns[c].push(v);
        }
    }
    if started && (run.table.is_some() || !run.messages.is_empty()) {
        // A file cut before its last `CARD 5` echo: keep what it says.
        run.iemsct = iemsct;
        runs.push(run);
    }
    Ok(LowtranTape6 { runs })
}

#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    const TEXT: &str = "1                    ***** LOWTRAN 7 *****
0 CARD 1  *****    6    2    1    0    0    0    0    0    0    0    0    0    0   0.000   0.00
1                    RADIANCE(WATTS/CM2-STER-XXX)
0   FREQ WAVLEN   ATMOS RADIANCE       INTEGRAL TOTAL
  (CM-1) (MICRN)  (CM-1)    (MICRN)   (CM-1)    TRANS

    710.  14.085  1.07E-05  5.37E-04  2.66E-05   0.1245
    715.  13.986  9.79E-06  5.00E-04  7.56E-05   0.1915
0INTEGRATED ABSORPTION FROM  710 TO 1250 CM-1 =     87.10 CM-1
 AVERAGE TRANSMITTANCE =0.8387

0INTEGRATED RADIANCE =  7.830E-04 WATTS CM-2 STER-1
0 CARD 5 *****    3
0 CARD 3  *****     3.000     0.001    91.500     0.000     0.000     0.000    0
0H2 IS LESS THAN THE TANGENT HEIGHT FOR THIS PATH AND CANNOT BE REACHED
0GEO:  IERROR NE 0: END THIS CALCULATION AND SKIP TO THE NEXT CASE
0 CARD 5 *****    0
";

    #[test]
    fn tables_integrals_and_messages_per_run() {
        let t = parse("TAPE6", TEXT).unwrap();
        assert_eq!(t.runs.len(), 2);
        let r = &t.runs[0];
        assert_eq!(r.iemsct, Some(1));
        let tab = r.table.as_ref().unwrap();
        assert_eq!(tab.columns[0], [710.0, 715.0]);
        assert_eq!(tab.columns[2], [1.07e-5, 9.79e-6]);
        assert_eq!(tab.columns[5], [0.1245, 0.1915]);
        assert_eq!(r.integrated_absorption_per_cm, Some(87.10));
        assert_eq!(r.average_transmittance, Some(0.8387));
        assert_eq!(r.integrated_radiance_w_cm2_sr, Some(7.830e-4));
        assert!(!r.rejected);
        let f = &t.runs[1];
        assert!(f.rejected && f.table.is_none());
        assert_eq!(f.messages.len(), 2);
        assert!(
            f.messages[0]
                .text
                .starts_with("H2 IS LESS THAN THE TANGENT HEIGHT")
        );
        assert_eq!(f.messages[0].position.line, 15);
    }

    #[test]
    fn non_finite_values_are_refused() {
        let bad = TEXT.replace("0.1915", "Infinity");
        let e = parse("TAPE6", &bad).unwrap_err();
        assert_eq!((e.line, e.column), (8, 50));
        assert!(parse("TAPE6", "hello\n").is_err());
        let short = TEXT.replace("  2.66E-05   0.1245", "");
        assert!(
            parse("TAPE6", &short)
                .unwrap_err()
                .message
                .contains("expected 6 numbers")
        );
    }
}
