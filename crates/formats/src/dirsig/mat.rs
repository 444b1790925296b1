//! DIRSIG classic `.mat`: material entries, nested `NAME { … }` blocks of `KEY = VALUE`
//! lines. What irsig reads of an entry: `ID`, `NAME`, in
//! `SURFACE_PROPERTIES { EMISSIVITY_PROP { … } }` the `FILENAME` of its `.ems` and its
//! `SPECULAR_FRACTION`, and `TEMP_SOLVER_NAME` with the `KEY = VALUE` lines of its
//! `TEMP_SOLVER { … }` block, as written (`dirsig::therm` reads a `Therm` block's numbers);
//! everything else (the radiometry solver, other properties) is skipped.
//!
//! ```text
//! MATERIAL_ENTRY {
//!     ID           = 4
//!     NAME         = grass
//!     SURFACE_PROPERTIES {
//!         EMISSIVITY_PROP_NAME = ClassicEmissivity
//!         EMISSIVITY_PROP {
//!             FILENAME          = emissivity/grass_texture.ems
//!             SPECULAR_FRACTION = 0.1
//!         }
//!     }
//! }
//! ```

use crate::ParseError;
use crate::legacy::Position;
use nom::Input;

use crate::legacy::lex::{Line, Lines, Span, position};

/// A value and where it is.
#[derive(Debug, Clone, PartialEq)]
pub struct Located<T> {
    /// The value.
    pub value: T,
    /// Where it is.
    pub position: Position,
    /// Its byte range in the file.
    pub span: (usize, usize),
}

/// One `MATERIAL_ENTRY`.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// `ID`.
    pub id: Located<u64>,
    /// `NAME` (the rest of its line, trimmed).
    pub name: String,
    /// `EMISSIVITY_PROP`'s `FILENAME`, if any: a path relative to the `.mat`'s folder.
    pub emissivity_file: Option<Located<String>>,
    /// `EMISSIVITY_PROP`'s `SPECULAR_FRACTION`, if any, 0 to 1.
    pub specular_fraction: Option<f64>,
    /// `TEMP_SOLVER_NAME` and the `TEMP_SOLVER` block, if the entry has either.
    pub temp_solver: Option<TempSolver>,
    /// Where the entry starts.
    pub position: Position,
}

/// An entry's temperature solver: its name and its block's lines, as written.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TempSolver {
    /// `TEMP_SOLVER_NAME` (`Therm`, `Null`, `DataDriven`, ...), if given.
    pub name: Option<Located<String>>,
    /// The `TEMP_SOLVER { … }` block's `KEY = VALUE` lines in file order: each key and its
    /// value (the rest of the line, trimmed). Nested blocks inside it are skipped.
    pub values: Vec<(Located<String>, Located<String>)>,
    /// The byte range of the `TEMP_SOLVER {` line, if the block is there.
    pub block: Option<(usize, usize)>,
}

/// An entry being read.
#[derive(Debug, Default)]
struct Partial {
    position: Option<Position>,
    span: Option<(usize, usize)>,
    id: Option<Located<u64>>,
    name: Option<String>,
    emissivity_file: Option<Located<String>>,
    specular_fraction: Option<f64>,
    temp_solver: Option<TempSolver>,
}

/// Reads a DIRSIG `.mat`.
///
/// # Errors
/// A [`ParseError`] at the place: a line that is neither `KEY = VALUE`, `NAME {` nor `}`,
/// an unbalanced brace, an entry without `ID` or `NAME`, an empty `NAME`, an `ID` that is
/// not a whole number, a `SPECULAR_FRACTION` that is not a number 0 to 1, a key irsig
/// reads given twice in one entry (the second, which would otherwise win silently), or a
/// file with no `MATERIAL_ENTRY` (an empty library).
pub fn parse(file: &str, text: &str) -> Result<Vec<Entry>, ParseError> {
    let mut lines = Lines::new(file, text);
    let mut entries = Vec::new();
    let mut stack: Vec<String> = Vec::new();
    let mut current: Option<Partial> = None;
    // The keys irsig reads that the open entry has given, with their lines.
    let mut seen: Vec<(String, usize)> = Vec::new();
    while let Some(line) = lines.next_line() {
        let body = *line.span.fragment();
        if body == "}" {
            let Some(block) = stack.pop() else {
                return Err(lines.error(
                    line.span,
                    "expected a block to close, found `}` at the top level",
                ));
            };
            if stack.is_empty() && block == "MATERIAL_ENTRY" {
                if let Some(partial) = current.take() {
                    entries.push(partial.finish(file, text, line)?);
                }
            }
            continue;
        }
        if let Some(block) = body.strip_suffix('{') {
            let block = block.trim();
            if block.is_empty() || block.contains(char::is_whitespace) {
                return Err(lines.error(line.span, format!("expected `NAME {{`, found `{body}`")));
            }
            if stack.is_empty() {
                if block != "MATERIAL_ENTRY" {
                    return Err(lines.error(
                        line.span,
                        format!("expected MATERIAL_ENTRY {{, found `{body}`"),
                    ));
                }
                current = Some(Partial {
                    position: Some(position(line.span)),
                    span: Some((line.span.location_offset(), line.span.fragment().len())),
                    ..Partial::default()
                });
                seen.clear();
            } else if stack.len() == 1
                && block == "TEMP_SOLVER"
                && let Some(entry) = current.as_mut()
            {
                let solver = entry.temp_solver.get_or_insert_with(TempSolver::default);
                if solver.block.is_some() {
                    return Err(lines.error(
                        line.span,
                        "TEMP_SOLVER is given twice in this MATERIAL_ENTRY: which one is meant?",
                    ));
                }
                solver.block = Some((line.span.location_offset(), line.span.fragment().len()));
            }
            stack.push(block.to_owned());
            continue;
        }
        let Some((key, value)) = body.split_once('=') else {
            return Err(lines.error(
                line.span,
                format!("expected `KEY = VALUE`, `NAME {{` or `}}`, found `{body}`"),
            ));
        };
        if stack.is_empty() {
            return Err(lines.error(
                line.span,
                "expected MATERIAL_ENTRY {, found a value outside any entry",
            ));
        }
        let (key, raw) = (key.trim(), value.trim());
        let start = line.span.location_offset() + body.len() - value.trim_start().len();
        let vspan = line.span.take_from(start - line.span.location_offset());
        let vspan = vspan.take(raw.len());
        let path: Vec<&str> = stack.iter().map(String::as_str).collect();
        let Some(entry) = current.as_mut() else {
            continue;
        };
        let read = matches!(
            (path.as_slice(), key),
            (["MATERIAL_ENTRY"], "ID" | "NAME" | "TEMP_SOLVER_NAME")
                | (["MATERIAL_ENTRY", "TEMP_SOLVER"], _)
                | (
                    ["MATERIAL_ENTRY", "SURFACE_PROPERTIES", "EMISSIVITY_PROP"],
                    "FILENAME" | "SPECULAR_FRACTION"
                )
        );
        if read {
            let full = format!("{}.{key}", path.join("."));
            if let Some(first) = seen.iter().find(|(k, _)| *k == full) {
                return Err(lines.error(
                    line.span,
                    format!(
                        "{key} is given twice in this MATERIAL_ENTRY (first on line {}): \
                         which one is meant?",
                        first.1
                    ),
                ));
            }
            seen.push((full, position(line.span).line));
        }
        entry.set(&lines, &path, key, raw, line, vspan)?;
    }
    if let Some(open) = stack.last() {
        return Err(lines.eof_error(&format!("expected `}}` closing {open}, found end of file")));
    }
    if entries.is_empty() {
        return Err(lines.eof_error(
            "expected at least one MATERIAL_ENTRY { ... }, found none: the library would be empty",
        ));
    }
    Ok(entries)
}

impl Partial {
    /// The entry, once its block closes at `line`: refused without an `ID` or a `NAME`.
    fn finish(self, file: &str, text: &str, line: Line<'_>) -> Result<Entry, ParseError> {
        let (start, len) = self
            .span
            .unwrap_or_else(|| (line.span.location_offset(), line.span.fragment().len()));
        let missing = |what: &str| {
            ParseError::at_span(
                file,
                text,
                start,
                len,
                format!("this MATERIAL_ENTRY has no {what}"),
            )
        };
        Ok(Entry {
            id: self.id.ok_or_else(|| missing("ID"))?,
            name: self.name.ok_or_else(|| missing("NAME"))?,
            emissivity_file: self.emissivity_file,
            specular_fraction: self.specular_fraction,
            temp_solver: self.temp_solver,
            position: self.position.unwrap_or_else(|| position(line.span)),
        })
    }

    /// Keeps `key = raw` (on `line`, the value at `vspan`) where the block `path` makes it
    /// one irsig reads; skips it otherwise.
    fn set(
        &mut self,
        lines: &Lines<'_>,
        path: &[&str],
        key: &str,
        raw: &str,
        line: Line<'_>,
        vspan: Span<'_>,
    ) -> Result<(), ParseError> {
        let located = |value: String| Located {
            value,
            position: position(vspan),
            span: (vspan.location_offset(), raw.len()),
        };
        match (path, key) {
            (["MATERIAL_ENTRY"], "ID") => {
                let id = lines.unsigned(vspan, "a material ID")?;
                self.id = Some(Located {
                    value: id,
                    position: position(vspan),
                    span: (vspan.location_offset(), raw.len()),
                });
            }
            (["MATERIAL_ENTRY"], "NAME") => {
                if raw.is_empty() {
                    return Err(lines.error(
                        line.span,
                        "expected a material name after `NAME =`, found nothing",
                    ));
                }
                self.name = Some(raw.to_owned());
            }
            (["MATERIAL_ENTRY"], "TEMP_SOLVER_NAME") => {
                self.temp_solver
                    .get_or_insert_with(TempSolver::default)
                    .name = Some(located(raw.to_owned()));
            }
            (["MATERIAL_ENTRY", "TEMP_SOLVER"], _) => {
                let kspan = line.span.take(key.len());
                let key_at = Located {
                    value: key.to_owned(),
                    position: position(kspan),
                    span: (kspan.location_offset(), key.len()),
                };
                self.temp_solver
                    .get_or_insert_with(TempSolver::default)
                    .values
                    .push((key_at, located(raw.to_owned())));
            }
            (["MATERIAL_ENTRY", "SURFACE_PROPERTIES", "EMISSIVITY_PROP"], "FILENAME") => {
                self.emissivity_file = Some(located(raw.to_owned()));
            }
            (["MATERIAL_ENTRY", "SURFACE_PROPERTIES", "EMISSIVITY_PROP"], "SPECULAR_FRACTION") => {
                let f = lines.real(vspan, "a specular fraction")?;
                if !(0.0..=1.0).contains(&f) {
                    return Err(lines.error(
                        vspan,
                        format!("expected a specular fraction 0 to 1, found {f}"),
                    ));
                }
                self.specular_fraction = Some(f);
            }
            _ => {}
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_read_with_their_emissivity_file() {
        let text = "MATERIAL_ENTRY {\n    ID = 4\n    NAME = grass lawn\n    RAD_SOLVER {\n    }\n    SURFACE_PROPERTIES {\n        EMISSIVITY_PROP {\n            FILENAME = emissivity/grass.ems\n            SPECULAR_FRACTION = 0.1\n        }\n    }\n}\nMATERIAL_ENTRY {\n  ID = 100\n  NAME = bare\n}\n";
        let e = parse("a.mat", text).unwrap();
        assert_eq!(e.len(), 2);
        assert_eq!(e[0].id.value, 4);
        assert_eq!(e[0].name, "grass lawn");
        let f = e[0].emissivity_file.as_ref().unwrap();
        assert_eq!(f.value, "emissivity/grass.ems");
        assert_eq!((f.position.line, f.position.column), (8, 24));
        assert_eq!(&text[f.span.0..f.span.0 + f.span.1], "emissivity/grass.ems");
        assert_eq!(e[0].specular_fraction, Some(0.1));
        assert!(e[1].emissivity_file.is_none());
    }

    #[test]
    fn malformed_entries_fail_at_their_place() {
        let e = parse("b.mat", "MATERIAL_ENTRY {\n  ID = four\n}\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 8), "{e}");
        let e = parse("b.mat", "MATERIAL_ENTRY {\n  ID = 4\n").unwrap_err();
        assert!(e.message.contains("closing MATERIAL_ENTRY"), "{e}");
        let e = parse("b.mat", "MATERIAL_ENTRY {\n  NAME = x\n}\n").unwrap_err();
        assert!(e.message.contains("no ID"), "{e}");
        let e = parse("b.mat", "}\n").unwrap_err();
        assert_eq!(e.line, 1);
    }

    #[test]
    fn what_would_be_accepted_silently_is_refused() {
        // A second FILENAME won over the first; an empty NAME, or a file of no entry (an
        // empty library), went through with exit 0.
        let twice = "MATERIAL_ENTRY {\n  ID = 4\n  NAME = grass\n  SURFACE_PROPERTIES {\n    EMISSIVITY_PROP {\n      FILENAME = a.ems\n      FILENAME = b.ems\n    }\n  }\n}\n";
        let e = parse("c.mat", twice).unwrap_err();
        assert_eq!((e.line, e.column), (7, 7), "{e}");
        assert!(
            e.message.contains("FILENAME is given twice") && e.message.contains("line 6"),
            "{e}"
        );
        let e = parse(
            "c.mat",
            "MATERIAL_ENTRY {\n  ID = 4\n  ID = 5\n  NAME = x\n}\n",
        )
        .unwrap_err();
        assert_eq!(e.line, 3, "{e}");
        let e = parse("c.mat", "MATERIAL_ENTRY {\n  ID = 4\n  NAME =\n}\n").unwrap_err();
        assert_eq!(e.line, 3, "{e}");
        assert!(e.message.contains("material name"), "{e}");
        for empty in ["", "# nothing\n", "\n\n"] {
            let e = parse("c.mat", empty).unwrap_err();
            assert!(e.message.contains("at least one MATERIAL_ENTRY"), "{e}");
        }
        // One key of the same name in two entries is no repeat.
        let two = "MATERIAL_ENTRY {\n  ID = 1\n  NAME = a\n}\nMATERIAL_ENTRY {\n  ID = 2\n  NAME = b\n}\n";
        assert_eq!(parse("c.mat", two).unwrap().len(), 2);
    }
}
