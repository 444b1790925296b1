//! The material index file: material names to the numbers facets carry, and, for the
//! tracer, each material's `.ems` file and whether it is specular (thesis §4.1; Appendix
//! H `emis_type { name[16], angle[10], emissivity[10], specular }`).
//!
//! The thesis describes the file's role but never prints it; this is irsig's reading:
//!
//! ```text
//! 3                         optional: the number of materials that follow
//! 1 asphalt asphalt.ems 1   index, name, .ems file, specular flag (1 specular, 0 diffuse)
//! 2 grass   grass.ems   0
//! 6 water   water-hale-querry.ems 1
//! ```
//!
//! One material per line: its index (1–65535; 0 means "nothing hit" in the interaction
//! map), its name (no whitespace, no `#`, not a number), then optionally the `.ems` file
//! (a path relative to the index file) and optionally the specular flag (`0` or `1`;
//! default `0`, diffuse). The short form `index name` is what the 1990 VAX parser needed
//! to turn Intergraph material names into indices; the long form is what the tracer
//! needed to fill `emis_type`. Indices and names are unique. The 1990 tracer held at most
//! 15 materials (4 bits each in the interaction map) and names of 15 characters; this
//! parser has neither limit.

use std::collections::HashMap;
use std::fmt::Write as _;

use super::lex::{Lines, position};
use super::{Position, WriteError, WriteErrorKind, check_name};
use crate::ParseError;

/// One material of the index file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MaterialEntry {
    /// The material's number, 1 to 65535, as object files carry it.
    pub index: u16,
    /// Its name, as the Intergraph files tagged facets (`asphalt`).
    pub name: String,
    /// Its `.ems` file as written (relative to the index file), if given.
    pub ems_file: Option<String>,
    /// True when the material is a specular reflector, false when diffuse (Lambertian).
    pub specular: bool,
    /// Where the entry is.
    pub position: Position,
}

/// A parsed material index file.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct MaterialIndexFile {
    /// The materials in file order.
    pub materials: Vec<MaterialEntry>,
}

impl MaterialIndexFile {
    /// The material called `name`.
    #[must_use]
    pub fn by_name(&self, name: &str) -> Option<&MaterialEntry> {
        self.materials.iter().find(|m| m.name == name)
    }

    /// The material numbered `index`.
    #[must_use]
    pub fn by_index(&self, index: u16) -> Option<&MaterialEntry> {
        self.materials.iter().find(|m| m.index == index)
    }
}

/// Reads a material index file.
///
/// # Errors
/// A [`ParseError`] for an empty file, an index that is not a whole number from 1 to
/// 65535, a name that is a number, a specular flag other than `0` or `1`, more than four
/// fields, a repeated index or name, or a declared count that differs from the entries.
pub fn parse(file: &str, text: &str) -> Result<MaterialIndexFile, ParseError> {
    let mut lines = Lines::new(file, text);
    let mut materials: Vec<MaterialEntry> = Vec::new();
    let mut declared: Option<(u64, Position)> = None;
    let mut by_index: HashMap<u16, usize> = HashMap::new();
    let mut by_name: HashMap<String, usize> = HashMap::new();
    while let Some(line) = lines.next_line() {
        let mut tokens = Lines::tokens(line);
        let index_tok = tokens.next().unwrap_or(line.span);
        let name_tok = tokens.next();
        let Some(name_tok) = name_tok else {
            if materials.is_empty() && declared.is_none() {
                let n = lines.unsigned(index_tok, "the number of materials")?;
                declared = Some((n, position(index_tok)));
                continue;
            }
            return Err(lines.error(
                line.span,
                format!(
                    "expected a material index and name, found only `{}`",
                    index_tok.fragment()
                ),
            ));
        };
        let what = "a material index, 1 to 65535";
        let index = lines.unsigned(index_tok, what)?;
        let index = match u16::try_from(index) {
            Ok(0) | Err(_) => {
                return Err(lines.error(index_tok, format!("expected {what}, found {index}")));
            }
            Ok(v) => v,
        };
        let name = *name_tok.fragment();
        if super::lex::looks_numeric(name) {
            return Err(lines.error(
                name_tok,
                format!("expected a material name, found the number `{name}`"),
            ));
        }
        let ems_file = tokens.next().map(|t| (*t.fragment()).to_owned());
        let specular = match tokens.next() {
            None => false,
            Some(t) => {
                match *t.fragment() {
                    "0" => false,
                    "1" => true,
                    other => {
                        return Err(lines.error(
                        t,
                        format!("expected a specular flag, 0 (diffuse) or 1 (specular), found `{other}`"),
                    ));
                    }
                }
            }
        };
        if let Some(extra) = tokens.next() {
            return Err(lines.error(
                extra,
                format!(
                    "expected at most 4 fields (index, name, .ems file, specular flag), found more: `{}`",
                    extra.fragment()
                ),
            ));
        }
        if let Some(&first) = by_index.get(&index) {
            let line_no = materials.get(first).map_or(0, |m| m.position.line);
            return Err(lines.error(
                index_tok,
                format!("expected a unique material index, found {index} again (first on line {line_no})"),
            ));
        }
        if let Some(&first) = by_name.get(name) {
            let line_no = materials.get(first).map_or(0, |m| m.position.line);
            return Err(lines.error(
                name_tok,
                format!("expected a unique material name, found `{name}` again (first on line {line_no})"),
            ));
        }
        by_index.insert(index, materials.len());
        by_name.insert(name.to_owned(), materials.len());
        materials.push(MaterialEntry {
            index,
            name: name.to_owned(),
            ems_file,
            specular,
            position: position(index_tok),
        });
    }
    if materials.is_empty() {
        return Err(
            lines.eof_error("expected at least one material (index name ...), found end of file")
        );
    }
    if let Some((n, at)) = declared {
        if n != materials.len() as u64 {
            return Err(lines.eof_error(&format!(
                "expected {n} materials as declared on line {}, found {}",
                at.line,
                materials.len()
            )));
        }
    }
    Ok(MaterialIndexFile { materials })
}

/// Writes a material index file without a count line: `index name`, then the `.ems` file
/// and specular flag when there is an `.ems` file (the flag is written whenever the file
/// is, since it follows it).
///
/// # Errors
/// A [`WriteError`] for no materials, an index of 0, a name or file name that would not
/// read back, a specular material without an `.ems` file (the flag has nowhere to go), or
/// a repeated index or name.
pub fn write(file: &MaterialIndexFile) -> Result<String, WriteError> {
    if file.materials.is_empty() {
        return Err(WriteError::new("material index", WriteErrorKind::Empty));
    }
    let mut out = String::new();
    for (i, m) in file.materials.iter().enumerate() {
        let record = || format!("material {} (`{}`)", i + 1, m.name);
        if m.index == 0 {
            return Err(WriteError::new(
                record(),
                WriteErrorKind::OutOfRange(
                    "material index 0 is reserved for \"nothing hit\"".into(),
                ),
            ));
        }
        check_name(record, &m.name)?;
        let earlier = file.materials.get(..i).unwrap_or_default();
        if earlier
            .iter()
            .any(|e| e.index == m.index || e.name == m.name)
        {
            return Err(WriteError::new(
                record(),
                WriteErrorKind::OutOfRange("index or name repeats an earlier material".into()),
            ));
        }
        let _ = write!(out, "{} {}", m.index, m.name);
        match &m.ems_file {
            Some(ems) => {
                if ems.is_empty() || ems.contains(char::is_whitespace) || ems.contains('#') {
                    return Err(WriteError::new(
                        record(),
                        WriteErrorKind::BadName(ems.clone()),
                    ));
                }
                let _ = write!(out, " {ems} {}", u8::from(m.specular));
            }
            None if m.specular => {
                return Err(WriteError::new(
                    record(),
                    WriteErrorKind::OutOfRange(
                        "a specular flag needs an .ems file before it".into(),
                    ),
                ));
            }
            None => {}
        }
        out.push('\n');
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_short_and_long_forms_with_an_optional_count() {
        let m = parse(
            "m.mat",
            "3\n1 asphalt asphalt.ems 1\n2 grass\n6 water water.ems\n",
        )
        .unwrap();
        assert_eq!(m.materials.len(), 3);
        assert!(m.by_name("asphalt").unwrap().specular);
        assert_eq!(m.by_index(2).unwrap().ems_file, None);
        assert_eq!(
            m.by_index(6).unwrap().ems_file.as_deref(),
            Some("water.ems")
        );
        assert!(!m.by_index(6).unwrap().specular);
        assert_eq!(m.materials[1].position, Position { line: 3, column: 1 });
        let again = parse("m", &write(&m).unwrap()).unwrap();
        assert_eq!(again.materials.len(), 3);
        assert_eq!(
            again.by_name("water"),
            Some(&MaterialEntry {
                position: again.materials[2].position,
                ..m.materials[2].clone()
            })
        );
    }

    #[test]
    fn rejects_bad_entries_at_the_field() {
        for (text, line, col, needle) in [
            ("0 air\n", 1, 1, "1 to 65535"),
            ("70000 air\n", 1, 1, "1 to 65535"),
            ("1 7\n", 1, 3, "material name"),
            ("1 a a.ems 2\n", 1, 11, "specular flag"),
            ("1 a a.ems 1 x\n", 1, 13, "at most 4"),
            ("1 a\n2 b\n1 c\n", 3, 1, "unique material index"),
            ("1 a\n2 a\n", 2, 3, "unique material name"),
            ("3\n1 a\n2 b\n", 3, 4, "expected 3 materials"),
            ("2\n", 1, 2, "at least one material"),
            ("1 a\n5\n", 2, 1, "found only"),
        ] {
            let e = parse("m.mat", text).unwrap_err();
            assert_eq!((e.line, e.column), (line, col), "{text:?}: {e}");
            assert!(e.message.contains(needle), "{text:?}: {e}");
        }
    }
}
