//! Parsers and writers for the 1990 file formats (thesis §3.2.2 Figure 9, §4.1, Appendix H).
//!
//! Each submodule holds one format: a typed record in the **file's own units** (km,
//! W cm⁻² sr⁻¹, °C where the file has them; every field says its unit), a `parse`
//! function and a `write` function whose output `parse` reads back to the same values.
//! Converting to the canonical SI model is the importer's, flattener's and `irsig-atmos`'s
//! job; only conversions that are trivial and belong beside the syntax live here
//! ([`ems::EmsTable::to_pairs`], [`view::ViewingFile::to_view`]).
//!
//! | module | file | 1990 reader |
//! | --- | --- | --- |
//! | [`object`] | Intergraph-derived facet file | VAX parser output, `facet_type` |
//! | [`scene`] | object name + 9 values (+ temperature) | `read_scene_data` |
//! | [`material_index`] | material number, name, `.ems`, specular flag | `emis_type` |
//! | [`view`] | viewing file | `read_viewing_data`, `view_type` |
//! | [`execute`] | execute file (frames of view, scene, outputs) | `read_exec_file` |
//! | [`ems`] | angle → emissivity | `read_emis` |
//! | [`atm`] | altitude → τ, L_u | `read_atm`, `atm_type` |
//! | [`cor`] | a1 a2 a3 of eq. 10 | `read_cor` |
//! | [`dwr`] | angle → L_d, plus `-1 L_d,hemi` | `read_dwr`, `dwr_type` |
//! | [`rsd`] | radiosonde | (DIRTRAN input) |
//! | [`rtt`] | temperature → band radiance | `read_rtt`, `planck_type` |
//! | [`map`] | interaction map pixels (an image the 1990 tracer wrote) | — |
//!
//! Layout is read liberally, as C `fscanf` did: blank lines anywhere, LF or CRLF line
//! ends, spaces or tabs, trailing whitespace, a leading UTF-8 byte-order mark, and `#`
//! starting a comment to the end of the line (an irsig extension; the writers never emit
//! comments, so their output is what the 1990 programs read). Numbers are strict: decimal
//! literals only, never `NaN`, `inf` or a literal that overflows `f64`. Every error is a
//! [`ParseError`] naming the file, line and column. Declared counts are never trusted for
//! allocation.
//!
//! ```
//! use irsig_formats::legacy::object;
//! let text = "1\n\n6\n0 0 0\n1 0 0\n0 1 0\n";
//! let obj = object::parse("tri.fac", text).unwrap();
//! assert_eq!(obj.facets[0].material_index, 6);
//! assert_eq!(obj.facets[0].vertices[1], [1.0, 0.0, 0.0]);
//! assert_eq!(object::parse("tri.fac", &object::write(&obj).unwrap()).unwrap().facets[0].vertices,
//!            obj.facets[0].vertices);
//! ```

pub mod atm;
pub mod cor;
pub mod dwr;
pub mod ems;
pub mod execute;
pub(crate) mod lex;
pub mod map;
pub mod material_index;
pub mod object;
pub mod rsd;
pub mod rtt;
pub mod scene;
mod table;
pub mod view;

use crate::ParseError;

/// Where a record starts in its file: 1-based line, and column in characters.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Position {
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
}

impl std::fmt::Display for Position {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// A value a writer cannot put into a legacy file, or one its parser would reject.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{record}: {kind}")]
pub struct WriteError {
    /// Which record, e.g. `facet 3` or `row 7`, counted from 1 as a reader of the file would.
    pub record: String,
    /// What is wrong with it.
    pub kind: WriteErrorKind,
}

/// Why a value cannot be written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum WriteErrorKind {
    /// A number is NaN or infinite; the format has no spelling for it.
    #[error("a number is NaN or infinite")]
    NotFinite,
    /// A number lies outside what the format allows (the parser would reject it).
    #[error("{0}")]
    OutOfRange(String),
    /// A name is empty, contains whitespace or `#`, or looks like a number, so it would not
    /// read back as the same name.
    #[error(
        "name `{0}` cannot be written: it must be non-empty, without whitespace or `#`, and not a number"
    )]
    BadName(String),
    /// A table or object that must hold at least one record holds none.
    #[error("nothing to write: the format needs at least one record")]
    Empty,
}

impl WriteError {
    pub(crate) fn new(record: impl Into<String>, kind: WriteErrorKind) -> Self {
        Self {
            record: record.into(),
            kind,
        }
    }
}

/// Checks that `bytes` are UTF-8 text (the 1990 files are ASCII, a subset) and drops a
/// leading byte-order mark. Call this first when reading a file from disk.
///
/// # Errors
/// A [`ParseError`] at the first byte that is not UTF-8, naming the byte.
pub fn decode<'a>(file: &str, bytes: &'a [u8]) -> Result<&'a str, ParseError> {
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(text.strip_prefix('\u{feff}').unwrap_or(text)),
        Err(e) => {
            let at = e.valid_up_to();
            let byte = bytes.get(at).copied().unwrap_or(0);
            let lossy = String::from_utf8_lossy(bytes);
            Err(ParseError::at_offset(
                file,
                &lossy,
                at,
                format!("expected UTF-8 text, found the byte 0x{byte:02x}"),
            )
            .with_help("legacy files are plain ASCII; is this a binary file?"))
        }
    }
}

/// Formats a real so that it reads back bit-identically: Rust's shortest round-trip form,
/// which uses an exponent only for very large or small magnitudes (`1e-7`, `1e16`).
pub(crate) fn real(v: f64) -> String {
    format!("{v:?}")
}

pub(crate) fn check_finite(record: impl Fn() -> String, values: &[f64]) -> Result<(), WriteError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(WriteError::new(record(), WriteErrorKind::NotFinite))
    }
}

pub(crate) fn check_name(record: impl Fn() -> String, name: &str) -> Result<(), WriteError> {
    if name.is_empty()
        || name.contains(char::is_whitespace)
        || name.contains('#')
        || lex::looks_numeric(name)
    {
        Err(WriteError::new(
            record(),
            WriteErrorKind::BadName(name.to_owned()),
        ))
    } else {
        Ok(())
    }
}

// Parsing a decimal literal must give exactly the f64 of the same Rust literal, so the
// tests compare floats exactly.
#[cfg(test)]
#[allow(clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn decode_names_the_first_bad_byte() {
        let e = decode("f.ems", b"0 0.9\n10 \xff0.8\n").unwrap_err();
        assert_eq!((e.line, e.column), (2, 4));
        assert!(e.message.contains("0xff"), "{}", e.message);
        assert_eq!(decode("f", "\u{feff}1 2".as_bytes()).unwrap(), "1 2");
    }

    #[test]
    fn reals_round_trip_bit_for_bit() {
        for v in [
            0.0,
            -0.0,
            0.1,
            -4.09691,
            1e-300,
            6.02e23,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
        ] {
            let s = real(v);
            assert!(lex::looks_numeric(&s), "{s}");
            assert_eq!(s.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{s}");
        }
    }
}
